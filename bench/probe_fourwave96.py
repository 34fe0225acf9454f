"""probe 96 of the four-wave theory and of how it names the fastest pair, where the
NLS is blind: backward pairs near k = pi/2, decays into another branch, crossings of two
fields' branches (exact and avoided, couplings 1e-3 and 1e-2), a diatomic chain near its
gap, Klein-Gordon chains with and without a cubic on-site term.

Per point (k, a, branch) on the infinite chain:
(1) ``four_wave``'s fastest rate and own offset against the exact theory's (``exact_gain``,
    the referee): their ratio;
(2) the fastest pair's kind (four-wave's ``mode_kind``) against the exact mode's
    (``classify_mode``) and, for the two-field models written here, against the field
    content of the exact mode's two waves computed from a dynamical matrix written by hand
    below (not the code's): a pair whose waves both carry > 90% of their weight in the
    carrier's field is the carrier's own (sidebands or backward by |q| <= pi/2), in another
    field parametric; hybrid waves (< 90% in any field) are not refereed by hand;
(3) verdicts that differ (four-wave stable, exact MI, or the reverse);
(4) one run per model at its fastest point (ring of 128) against the exact ring rate;
and (1)-(3) again on the ring of 128 sites.

    OMP_NUM_THREADS=1 NUMBA_NUM_THREADS=1 python -m bench.probe_fourwave96 [--no-runs]
        [--only cross-1e-3,kg-cubic] [--json OUT.json]
"""

from __future__ import annotations

import argparse
import json
import math
import sys
import time

import numpy as np

PI = math.pi

CROSS = '''name = "{name}"
description = "acoustic u and a flat oscillator v, linear coupling eps: an (avoided) crossing"
fields = ["u", "v"]
branch = "u"
[parameters]
wv = 1.0
c = 0.5
b = 0.5
eps = {eps}
[energy]
kinetic = "u_t**2/2 + v_t**2/2"
bond = "(u_next - u)**2/2 + b*(u_next - u)**4/4 + c*(u_next - u)*v**2 + eps*(u_next - u)*v"
site = "wv**2*v**2/2 + v**4/4"
'''

OPT = '''name = "opt"
description = "mass-in-mass: outer u, inner v of mass m on a spring kr (an optical branch)"
fields = ["u", "v"]
branch = "u"
[parameters]
m = 0.5
kr = 1.5
beta = 1.0
g = 0.3
[energy]
kinetic = "u_t**2/2 + m*v_t**2/2"
bond = "(u_next - u)**2/2 + beta*(u_next - u)**4/4"
site = "kr*(v - u)**2/2 + g*(v - u)**3/3 + kr*(v - u)**4/4"
'''

MODELS = {
    "cross-0": CROSS.format(name="cross-0", eps=0.0),
    "cross-1e-3": CROSS.format(name="cross-1e-3", eps=1e-3),
    "cross-1e-2": CROSS.format(name="cross-1e-2", eps=1e-2),
    "opt": OPT,
}


def hand_matrix(name: str, p: dict, kap: float) -> tuple:
    """The mass-weighted dynamical matrix written by hand from each two-field model's
    quadratic energy, and the masses."""
    s2 = 4 * math.sin(kap / 2) ** 2
    if name.startswith("cross"):
        e = p["eps"]
        # eps (u_{n+1} - u_n) v_n: D_uv = eps (e^{-i kap} - 1)
        K = np.array([[s2, e * (np.exp(-1j * kap) - 1)],
                      [e * (np.exp(1j * kap) - 1), p["wv"] ** 2]])
        return K, np.ones(2)
    if name == "opt":
        K = np.array([[s2 + p["kr"], -p["kr"]], [-p["kr"], p["kr"]]], complex)
        m = np.array([1.0, p["m"]])
        s = 1 / np.sqrt(m)
        return s[:, None] * K * s[None, :], m
    raise KeyError(name)


def hand_field(name, p, kap, freq):
    """(field index, its weight) of the linear wave at kap nearest ``freq``, by hand."""
    D, _ = hand_matrix(name, p, kap)
    w2, V = np.linalg.eigh(D)
    b = int(np.argmin(np.abs(np.sqrt(np.maximum(w2, 0)) - freq)))
    wt = np.abs(V[:, b]) ** 2
    return int(np.argmax(wt)), float(np.max(wt))


#: (model, params, k, a, branch): near pi/2, near crossings (cross: pi/3 = 1.047; opt's
#: branches do not cross), near a gap (diatomic: k -> pi), and generic
POINTS = []
for kk in (PI / 2 - 0.06, PI / 2 - 0.02, PI / 2, PI / 2 + 0.03, 1.0, 2.6):
    POINTS.append(("fput", {"alpha": 0.45, "beta": 1.3}, kk, 0.1, None))
for kk in (PI / 2 - 0.05, PI / 2, 0.7, 2.2):
    POINTS.append(("klein-gordon", {"C": 0.6, "omega0": 1.0, "alpha": 0.0, "beta": 1.0},
                   kk, 0.1, None))
for kk in (PI / 2 - 0.04, PI / 2, 1.2, 2.5):  # the cubic on-site term
    POINTS.append(("klein-gordon", {"C": 1.0, "omega0": 1.0, "alpha": 0.45, "beta": 1.0},
                   kk, 0.1, None))
for kk, br in ((PI - 0.05, "u"), (PI - 0.2, "u"), (PI / 2, "u"), (1.0, "u"),
               (PI - 0.05, 1), (PI - 0.3, 1), (0.5, 1)):
    POINTS.append(("diatomic-fput", {"m": 1.5, "alpha": 0.2, "beta": 1.0}, kk, 0.1, br))
for name in ("cross-0", "cross-1e-3", "cross-1e-2"):
    for kk, br in ((0.98, "u"), (1.12, "u"), (PI / 2, "u"), (0.9, "u"), (2.0, "v"),
                   (PI / 2, "v")):
        POINTS.append((name, {}, kk, 0.1, br))
for kk, br in ((0.6, "u"), (PI / 2, "u"), (2.4, "u"), (1.0, 1), (2.5, 1)):
    POINTS.append(("opt", {}, kk, 0.1, br))


def load(name, params):
    from energy import load_model, parse_model

    if name in MODELS:
        model = load_model(parse_model(MODELS[name], f"{name}.toml"))
    else:
        model = load_model(name)
    return model.with_params(**params) if params else model


def probe_point(name, params, k, a, branch):
    from numerics.models import classify_mode, exact_gain, four_wave

    model = load(name, params)
    t0 = time.perf_counter()
    fw = four_wave(model, k, a, branch)
    t1 = time.perf_counter()
    ex = exact_gain(model, k, a, branch)
    t2 = time.perf_counter()
    cm = classify_mode(ex)
    # the ring of 128 (k snapped to 2 pi m / 128 by both)
    fwr, exr = four_wave(model, k, a, branch, N=128), exact_gain(model, k, a, branch, N=128)
    cmr = classify_mode(exr)
    row = {"ring_fw_gain": fwr.gain, "ring_ex_gain": exr.peak_gain,
           "ring_fw_kind": fwr.mode_kind, "ring_ex_kind": cmr["mode_kind"],
           "ring_fw_verdict": fwr.verdict, "ring_ex_verdict": exr.verdict,
           "model": name, "params": params, "k": k, "a": a, "branch": branch,
           "fw_gain": fw.gain, "fw_offset": fw.offset, "fw_kind": fw.mode_kind,
           "fw_verdict": fw.verdict, "ex_gain": ex.peak_gain, "ex_kind": cm["mode_kind"],
           "ex_offset": cm["fastest_offset"], "ex_verdict": ex.verdict,
           "t_fw": t1 - t0, "t_ex": t2 - t1, "hand_kind": ""}
    if name in MODELS and cm["mode_waves"] and cm["mode_kind"] != "resonance":
        p = model.params
        car_field, car_w = hand_field(name, p, k, fw.omega)
        fields = [hand_field(name, p, w["wavenumber"], w["frequency"])
                  for w in cm["mode_waves"]]
        if car_w > 0.9 and all(wt > 0.9 for _, wt in fields):
            own = all(f == car_field for f, _ in fields)
            qq = abs(math.remainder(cm["mode_waves"][0]["wavenumber"] - k, 2 * PI))
            row["hand_kind"] = (("sidebands" if qq <= PI / 2 else "backward") if own
                                else "parametric")
        else:
            row["hand_kind"] = "hybrid"
    return row


def run_check(name, params, k, a, branch, N=128):
    from numerics.models import exact_gain, simulate_model

    model = load(name, params)
    ring = exact_gain(model, k, a, branch, N=N)
    if not ring.peak_gain > 0:
        return {"model": name, "k": k, "ring_gain": 0.0, "run": "skipped (ring stable)"}
    run = simulate_model(model, k, a, branch=branch, N=N, wave=ring.wave, seed=1,
                         expected_gain=ring.peak_gain, until_saturated=True)
    g = run.growth()
    return {"model": name, "k": float(ring.wave.k), "ring_gain": ring.peak_gain,
            "run_rate": g.rate, "run": g.label, "ratio": g.rate / ring.peak_gain}


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--only", default="", help="comma-separated model names")
    ap.add_argument("--no-runs", action="store_true", help="skip the runs (4)")
    ap.add_argument("--json", default="", help="write the rows here")
    args = ap.parse_args(argv)
    only = set(filter(None, args.only.split(",")))
    rows = []
    print(f"{'model':14s} {'k':>6s} {'br':>3s} {'four-wave':>10s} {'exact':>10s} {'ratio':>6s} "
          f"{'q fw':>6s} {'q ex':>6s} {'kind fw':>10s} {'kind ex':>10s} {'by hand':>10s}")
    for pt in POINTS:
        if only and pt[0] not in only:
            continue
        r = probe_point(*pt)
        rows.append(r)
        ratio = r["fw_gain"] / r["ex_gain"] if r["ex_gain"] > 0 else math.nan
        r["ratio"] = ratio
        print(f"{r['model']:14s} {r['k']:6.3f} {str(r['branch']):>3s} {r['fw_gain']:10.3e} "
              f"{r['ex_gain']:10.3e} {ratio:6.3f} {r['fw_offset']:6.3f} "
              f"{(r['ex_offset'] or math.nan):6.3f} {r['fw_kind']:>10s} {r['ex_kind']:>10s} "
              f"{r['hand_kind']:>10s}", flush=True)
    ratios = np.array([r["ratio"] for r in rows if np.isfinite(r["ratio"])])
    print(f"\n{len(rows)} points, {len({r['model'] + str(r['params']) for r in rows})} "
          "model settings")
    if ratios.size:
        print(f"four-wave / exact: min {ratios.min():.3f}, median {np.median(ratios):.3f}, "
              f"max {ratios.max():.3f} ({ratios.size} MI points)")
    flips = [r for r in rows if r["fw_verdict"] != r["ex_verdict"]]
    said = [r for r in flips if r["fw_verdict"] != "undefined"]
    print(f"verdicts that differ: {len(flips)} ({len(flips) - len(said)} where four-wave "
          f"says 'undefined', {len(said)} contradictions: stable against MI or the reverse)")
    for r in flips:
        print(f"  {r['model']} k {r['k']:.3f} {r['branch']}: four-wave {r['fw_verdict']} "
              f"({r['fw_gain']:.3g}), exact {r['ex_verdict']} ({r['ex_gain']:.3g})")
    names = [r for r in rows if r["ex_kind"] not in ("none", "resonance")
             and r["fw_verdict"] == "MI" and r["fw_kind"] != r["ex_kind"]]
    print(f"kinds that differ (four-wave vs exact): {len(names)}")
    for r in names:
        print(f"  {r['model']} k {r['k']:.3f}: {r['fw_kind']} vs {r['ex_kind']}")
    rr = np.array([r["ring_fw_gain"] / r["ring_ex_gain"] for r in rows
                   if r["ring_ex_gain"] > 0 and np.isfinite(r["ring_fw_gain"])])
    if rr.size:
        print(f"ring of 128, four-wave / exact: min {rr.min():.3f}, median {np.median(rr):.3f}, "
              f"max {rr.max():.3f} ({rr.size} MI points)")
    rflips = [r for r in rows if r["ring_fw_verdict"] != r["ring_ex_verdict"]
              and r["ring_fw_verdict"] != "undefined"]
    rnames = [r for r in rows if r["ring_ex_kind"] not in ("none", "resonance")
              and r["ring_fw_verdict"] == "MI" and r["ring_fw_kind"] != r["ring_ex_kind"]]
    print(f"ring: {len(rflips)} contradictions, {len(rnames)} kinds that differ")
    for r in rflips + rnames:
        print(f"  {r['model']} k {r['k']:.3f} {r['branch']}: four-wave {r['ring_fw_verdict']} "
              f"{r['ring_fw_kind']} ({r['ring_fw_gain']:.3g}), exact {r['ring_ex_verdict']} "
              f"{r['ring_ex_kind']} ({r['ring_ex_gain']:.3g})")
    hand = [r for r in rows if r["hand_kind"] not in ("", "hybrid")]
    bad = [r for r in hand if r["ex_kind"] != r["hand_kind"] or
           (r["fw_verdict"] == "MI" and r["fw_kind"] != r["hand_kind"])]
    print(f"kinds against the hand field content: {len(hand) - len(bad)} of {len(hand)} agree")
    for r in bad:
        print(f"  {r['model']} k {r['k']:.3f}: hand {r['hand_kind']}, four-wave "
              f"{r['fw_kind']}, exact {r['ex_kind']}")
    runs = []
    if not args.no_runs:
        print("\nruns (ring of 128, the model's fastest exact point):")
        for model in dict.fromkeys((r["model"], json.dumps(r["params"])) for r in rows):
            best = max((r for r in rows if (r["model"], json.dumps(r["params"])) == model),
                       key=lambda r: r["ex_gain"])
            if not best["ex_gain"] > 0:
                continue
            rc = run_check(best["model"], best["params"], best["k"], best["a"], best["branch"])
            runs.append(rc)
            print(f"  {rc['model']:14s} k {rc['k']:.4f}: exact ring {rc['ring_gain']:.4g}, "
                  f"run: {rc['run']}" + (f" (ratio {rc['ratio']:.3f})" if "ratio" in rc
                                         else ""), flush=True)
    if args.json:
        with open(args.json, "w") as fh:
            json.dump({"points": rows, "runs": runs}, fh, indent=1, default=str)
    return 0


if __name__ == "__main__":
    sys.exit(main())
