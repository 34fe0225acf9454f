"""A randomized three-way check on model files the project's authors never used (issue
94's probe): the semi-discrete NLS, the exact lattice theory (ring and infinite chain),
the four-wave theory and a simulation of the ring, at seeded random points of six new
models, plus each model's linear dispersion against a hand-derived closed form and a
finite-difference linearisation of the compiled force, and energy conservation (dE/dt =
-2R where the model is damped).

The six models (written below as TOML, loaded from files as a user's would be):

- ``hertzish``: one field, bond r^2/2 + a r^3 + b r^4 (any sign of a, b > 0);
- ``toda``: the Toda chain, bond (e^{-b r} + b r - 1)/b^2 (integrable);
- ``kg46``: Klein-Gordon, soft quartic and hard sextic on-site;
- ``rotor-cross``: sliding u and rotation th, a cubic cross term in the bond;
- ``diatomic3``: masses 1 and m = 2-4, cubic-quartic springs; carrier on either branch;
- ``lossy-kg``: cubic-quartic Klein-Gordon with site and bond Rayleigh damping.

Agreement (the project's stated bars, docs/models.md and tests/test_models_exact.py):
the run's verdict equals the exact ring theory's and its rate is within 10% of it (a
rate too slow for the run's T, ``slow_for_T``, cannot be decided by it); the four-wave
theory names the exact theory's kind of pair, at a rate within 10%; the NLS's verdict
equals the infinite chain's exact one where the latter's fastest mode is the sidebands,
its rate within 20% (it is O(a^2): beyond a = 0.1 the bar is 20% (a / 0.1)^2). A lossy
point compares observability (amplification >= 20x) instead.

    OMP_NUM_THREADS=1 NUMBA_NUM_THREADS=1 python -m bench.probe_models94 [--points 20]
        [--seed 94] [--json OUT.json] [--only INDEX,...]
"""

from __future__ import annotations

import argparse
import json
import math
import pathlib
import sys
import tempfile
import time

import numpy as np

MODELS = {
    "hertzish": '''name = "hertzish"
fields = ["u"]
[parameters]
a = -0.4
b = 0.3
[energy]
kinetic = "u_t**2/2"
bond = "(u_next - u)**2/2 + a*(u_next - u)**3 + b*(u_next - u)**4"
''',
    "toda": '''name = "toda"
fields = ["u"]
[parameters]
b = 1.0
[energy]
kinetic = "u_t**2/2"
bond = "(exp(-b*(u_next - u)) + b*(u_next - u) - 1)/b**2"
''',
    "kg46": '''name = "kg46"
fields = ["u"]
[parameters]
C = 0.5
w0 = 1.0
beta = -0.6
gamma = 2.0
[energy]
kinetic = "u_t**2/2"
bond = "C*(u_next - u)**2/2"
site = "w0**2*u**2/2 + beta*u**4/4 + gamma*u**6/6"
''',
    "rotor-cross": '''name = "rotor-cross"
fields = ["u", "th"]
branch = "th"
[parameters]
I = 0.5
kt = 0.8
w0 = 0.6
c = 0.7
[energy]
kinetic = "u_t**2/2 + I*th_t**2/2"
bond = "(u_next - u)**2/2 + kt*(1 - cos(th_next - th)) + c*(u_next - u)*(2 - cos(th_next) - cos(th))"
site = "w0**2*(1 - cos(th))"
''',
    "diatomic3": '''name = "diatomic3"
fields = ["u", "v"]
branch = "u"
[parameters]
m = 3.0
a = 0.5
b = -0.3
[energy]
kinetic = "u_t**2/2 + m*v_t**2/2"
site = "(v - u)**2/2 + a*(v - u)**3/3 + b*(v - u)**4/4"
bond = "(u_next - v)**2/2 + a*(u_next - v)**3/3 + b*(u_next - v)**4/4"
''',
    "lossy-kg": '''name = "lossy-kg"
fields = ["u"]
[parameters]
C = 1.0
alpha = 0.3
beta = 1.0
gamma = 0.004
eta = 0.002
[energy]
kinetic = "u_t**2/2"
bond = "C*(u_next - u)**2/2"
site = "u**2/2 + alpha*u**3/3 + beta*u**4/4"
[dissipation]
site = "gamma*u_t**2/2"
bond = "eta*(u_next_t - u_t)**2/2"
''',
}

#: per model, each parameter's random range (uniform) and the branches a carrier may take
RANGES = {
    "hertzish": (dict(a=(-0.6, 0.6), b=(0.05, 0.8)), (0,)),
    "toda": (dict(b=(0.3, 2.0)), (0,)),
    "kg46": (dict(C=(0.2, 1.5), beta=(-1.0, 1.0), gamma=(0.5, 3.0)), (0,)),
    "rotor-cross": (dict(kt=(0.3, 1.2), w0=(0.3, 1.0), c=(-1.0, 1.0)), ("th",)),
    "diatomic3": (dict(m=(2.0, 4.0), a=(-0.6, 0.6), b=(-0.4, 0.6)), (0, 1)),
    "lossy-kg": (dict(alpha=(-0.5, 0.5), gamma=(0.0, 0.01), eta=(0.0, 0.005)), (0,)),
}


def dispersion_by_hand(name: str, p: dict, k: float) -> np.ndarray:
    """Each model's linear branches in closed form (derived by hand from its energy's
    quadratic part), sorted."""
    s2 = math.sin(k / 2) ** 2
    if name in ("hertzish", "toda"):  # V''(0) = 1
        return np.array([2 * math.sqrt(s2)])
    if name == "kg46":
        return np.array([math.sqrt(p["w0"] ** 2 + 4 * p["C"] * s2)])
    if name == "lossy-kg":
        return np.array([math.sqrt(1 + 4 * p["C"] * s2)])
    if name == "rotor-cross":  # the cross term is cubic: u and th decouple linearly
        return np.sort([2 * math.sqrt(s2), math.sqrt((p["w0"] ** 2 + 4 * p["kt"] * s2)
                                                     / p["I"])])
    if name == "diatomic3":  # masses 1, m; unit springs
        s = 1 + 1 / p["m"]
        r = math.sqrt(s * s - 4 * s2 / p["m"])
        return np.sqrt([s - r, s + r])
    raise KeyError(name)


def dispersion_by_differences(model, k: float, N: int = 64, h: float = 1e-6) -> np.ndarray:
    """The branches from the compiled force alone: its Jacobian at rest by central
    differences (M^-1 times the Hessian of the ring's energy), projected on the plane
    waves of ring wavenumber k; eigenvalues -> omega^2. Independent of the derivation's
    linearisation (only the force kernel is shared)."""
    from numerics.models import lattice_force

    d = model.n_fields
    n = np.arange(N)
    phase = np.exp(1j * k * n)
    D = np.zeros((d, d), complex)
    for j in range(d):
        cols = []
        for sgn in (1, -1):
            u = np.zeros((d, N))
            u[j] = sgn * h * np.cos(k * n)
            f_c = lattice_force(model, u)
            u[j] = sgn * h * np.sin(k * n)
            f_s = lattice_force(model, u)
            cols.append((f_c, f_s))
        # response to the complex wave h e^{ikn}: (f(cos) + i f(sin)), central difference
        resp = ((cols[0][0] - cols[1][0]) + 1j * (cols[0][1] - cols[1][1])) / (2 * h)
        D[:, j] = -(resp @ phase.conj()) / N
    w2 = np.sort(np.linalg.eigvals(D).real)
    return np.sqrt(np.maximum(w2, 0))


def _points(count: int, seed: int):
    rng = np.random.default_rng(seed)
    names = list(MODELS)
    out = []
    for i in range(count):
        name = names[i % len(names)]
        ranges, branches = RANGES[name]
        params = {p: float(np.round(rng.uniform(*r), 3)) for p, r in ranges.items()}
        where = rng.uniform()
        # a third of the points near pi/2 (the umklapp's edge), a sixth near pi
        if where < 1 / 3:
            k = math.pi / 2 + rng.uniform(-0.08, 0.08)
        elif where < 1 / 2:
            k = math.pi - rng.uniform(0, 0.08)
        else:
            k = rng.uniform(0.15, math.pi)
        a = float(np.round(math.exp(rng.uniform(math.log(0.02), math.log(0.2))), 4))
        N = int(rng.choice([64, 128, 256]))
        branch = branches[int(rng.integers(len(branches)))]
        out.append(dict(index=i, model=name, params=params, k=float(np.round(k, 4)), a=a,
                        N=N, branch=branch))
    return out


def _fastest_kind(spec) -> str:
    from numerics.models import classify_mode

    if spec.peak_gain <= 0:
        return "none"
    try:
        return classify_mode(spec)["mode_kind"]
    except Exception as exc:  # a probe reports, it does not stop
        return f"? {type(exc).__name__}"


def probe(pt: dict, folder: pathlib.Path) -> dict:
    """One point: every theory, a run, and the agreements."""
    from energy import load_model
    from numerics.maps import ModelPointSpec, measure_point
    from numerics.models import branches, exact_gain, nls

    path = folder / f"{pt['model']}.toml"
    model = load_model(str(path)).with_params(**pt["params"])
    row = dict(pt)
    t0 = time.time()
    # linear dispersion: by hand, by differences of the force, and the derivation's
    kk = pt["k"]
    hand = dispersion_by_hand(pt["model"], model.params, kk)
    fd = dispersion_by_differences(model, 2 * math.pi * round(kk * 64 / (2 * math.pi)) / 64)
    derived = np.sort(branches(model, kk))
    derived_fd = np.sort(branches(model, 2 * math.pi * round(kk * 64 / (2 * math.pi)) / 64))
    row["dispersion_err"] = float(np.max(np.abs(derived - hand)))
    row["dispersion_fd_err"] = float(np.max(np.abs(derived_fd - fd)))
    try:
        point = measure_point(ModelPointSpec(model, kk, pt["a"], branch=pt["branch"],
                                             N=pt["N"], simulate=True, seeds=1))
    except Exception as exc:
        row["error"] = f"{type(exc).__name__}: {exc}"
        row["seconds"] = time.time() - t0
        return row
    d = point.as_dict()
    row["k_ring"] = d["k"]
    nl, ex, fw, sim = d["semi-discrete NLS"], d["exact lattice"], d["four-wave"], d["simulated"]
    # a lossy point's verdicts are the damped chain's; the comparisons of the theories
    # with each other are of the lossless ones (``lossless_verdict`` where they differ)
    row.update(damped_verdicts={n: d[n]["verdict"] for n in ("semi-discrete NLS",
                                                              "exact lattice", "four-wave")}
               if "amplification" in ex else None)
    for t in (nl, ex, fw):
        t["verdict"] = t.get("lossless_verdict", t["verdict"])
    row.update(nls_verdict=nl["verdict"], nls_rate=nl["peak_gain"],
               nls_reason=nl.get("reason", ""),
               exact_verdict=ex["verdict"], exact_rate=ex.get("peak_gain"),
               exact_kind=ex.get("mode_kind"), exact_mode=ex.get("mode"),
               fw_verdict=fw["verdict"], fw_rate=fw.get("peak_gain"),
               fw_kind=fw.get("mode_kind"), fw_reason=fw.get("reason", ""),
               fw_kind_rates=fw.get("kind_rates", {}),
               exact_lossless_verdict=ex["verdict"],
               exact_damped_verdict=(row.get("damped_verdicts") or {}).get(
                   "exact lattice", ex["verdict"]),
               sim_verdict=sim["simulation_verdict"], sim_rate=sim["peak_gain"],
               sim_visible=sim.get("slowest_visible_rate"), t_end=sim["t_end"],
               energy_drift=sim.get("energy_drift"), energy_balance=sim.get("energy_balance"),
               notes=d.get("notes", []))
    for key in ("amplification", "observable"):
        if key in ex:
            row[f"exact_{key}"] = ex[key]
            row[f"nls_{key}"] = nl.get(key)
            row[f"fw_{key}"] = fw.get(key)
            row[f"sim_{key}"] = sim.get(key)
    # the infinite chain: the NLS's own comparison
    try:
        chain = exact_gain(model, row["k_ring"], pt["a"], pt["branch"])
        row.update(chain_rate=chain.peak_gain, chain_kind=_fastest_kind(chain),
                   chain_modulational=chain.modulational_gain)
    except Exception as exc:
        row["chain_error"] = f"{type(exc).__name__}: {exc}"
    try:
        n = nls(model, row["k_ring"], pt["branch"])
        row["g2_parts"] = {k: float(v) for k, v in n.parts.items()}
    except Exception:
        pass
    row["seconds"] = time.time() - t0
    row["checks"] = judge(row)
    return row


def _close(x, y, rel):
    return x is not None and y is not None and abs(x - y) <= rel * max(abs(y), 1e-300)


def judge(r: dict) -> dict:
    """Each comparison: True (agrees), False (disagrees), or a string (why it cannot be
    decided, an expected limitation)."""
    c = {}
    lossy = "exact_observable" in r
    ex_mi = r["exact_lossless_verdict"] == "MI"
    # run vs exact ring theory
    if lossy:
        # the damped verdict: MI only where the gain beats the damping at t = 0
        c["lossy_verdict"] = ((r["exact_damped_verdict"] == "MI") ==
                              (ex_mi and r["exact_amplification"] > 1)
                              or r["exact_amplification"] is None)
        c["run_vs_exact"] = (f"lossy: exact amplification {r['exact_amplification']:.3g}, "
                             f"run {r['sim_amplification']:.3g}; observable "
                             f"{r['exact_observable']}/{r['sim_observable']}")
    elif ex_mi and r["sim_verdict"] == "MI":
        c["run_vs_exact"] = _close(r["sim_rate"], r["exact_rate"], 0.10)
    elif ex_mi and r["exact_rate"] < (r["sim_visible"] or 0):
        c["run_vs_exact"] = "slow for T" if r["sim_verdict"] != "MI" else False
    else:
        c["run_vs_exact"] = (ex_mi == (r["sim_verdict"] == "MI")
                             and r["sim_verdict"] != "undetermined")
    # four-wave vs exact (ring)
    if r["fw_verdict"] == "undefined":
        c["fourwave_vs_exact"] = f"four-wave undefined: {r['fw_reason'][:60]}"
    elif ex_mi != (r["fw_verdict"] == "MI"):
        c["fourwave_vs_exact"] = False
    elif ex_mi:
        # at 4k = 2 pi (k = pi/2 on the ring) a sideband pair and its mirrored backward
        # pair are degenerate in a chain without cubic terms: the kinds tie, so the
        # four-wave's rate of the exact theory's kind is what must agree
        own = (r["fw_kind_rates"] or {}).get(r["exact_kind"])
        c["fourwave_vs_exact"] = ((r["fw_kind"] == r["exact_kind"]
                                   or _close(own, r["fw_rate"], 1e-6))
                                  and _close(r["fw_rate"], r["exact_rate"], 0.10))
    else:
        c["fourwave_vs_exact"] = True
    # NLS vs infinite-chain exact theory
    bar = 0.20 * max(1.0, (r["a"] / 0.1) ** 2)
    if r["nls_verdict"] == "undefined":
        c["nls_vs_exact"] = f"NLS undefined: {r['nls_reason'][:60]}"
    elif "chain_rate" not in r:
        c["nls_vs_exact"] = f"chain: {r.get('chain_error', '')[:60]}"
    elif r["chain_kind"] not in ("sidebands", "none"):
        c["nls_vs_exact"] = (f"exact fastest is {r['chain_kind']}; sidebands' own "
                             f"{r['chain_modulational']:.3g} vs NLS {r['nls_rate']:.3g}")
    elif (r["nls_verdict"] == "MI") != (r["chain_rate"] > 0):
        c["nls_vs_exact"] = False
    elif r["nls_verdict"] == "MI":
        c["nls_vs_exact"] = _close(r["nls_rate"], r["chain_rate"], bar)
    else:
        c["nls_vs_exact"] = True
    # where the exact lattice grows and the NLS cannot say it (another kind of pair, or
    # the NLS stable), the point's notes must say so
    if ex_mi and not lossy and (r["exact_kind"] != "sidebands"
                                or r["nls_verdict"] != "MI"):
        c["note_said"] = any("NLS" in n for n in r["notes"])
    # a disagreement the point's notes explain is a stated limitation, not a bug
    notes = " ".join(r["notes"])
    said = {"run_vs_exact": "harmonics of the carrier",
            "fourwave_vs_exact": "four-wave",
            "nls_vs_exact": "NLS"}
    for key, word in said.items():
        if c.get(key) is False and word in notes:
            c[key] = f"limitation, said in the notes ({word})"
    if (c.get("fourwave_vs_exact") is False and r.get("chain_rate")
            and r["exact_rate"] < 0.6 * r["chain_rate"]
            and _close(r["fw_rate"], r["exact_rate"], 0.25)):
        c["fourwave_vs_exact"] = ("the ring samples only its band's edge (ring "
                                  f"{r['exact_rate']:.3g}, chain {r['chain_rate']:.3g})")
    c["dispersion"] = r["dispersion_err"] < 1e-10 and r["dispersion_fd_err"] < 1e-5
    if lossy:
        c["energy"] = (r["energy_balance"] or 1) < 1e-3
    else:
        c["energy"] = (r["energy_drift"] or 1) < 1e-8
    return c


def _g(x):
    return "-" if x is None else f"{x:.3g}"


def table(rows) -> str:
    """The points as a markdown table: model, parameters, k (on the ring), a, N, branch,
    the rates (NLS on the chain, exact on the ring, the run's), the four-wave pair, and
    each check (ok, a stated limitation, or FAIL)."""
    out = ["| # | model | params | k | a | N | br | NLS | exact (kind) | run | four-wave (kind) "
           "| checks |", "|" + "---|" * 12]
    for r in rows:
        if "error" in r:
            out.append(f"| {r['index']} | {r['model']} | | | | | | | {r['error'][:60]} | | | |")
            continue
        checks = ", ".join(f"{k}: {'ok' if v is True else 'FAIL' if v is False else v}"
                           for k, v in r["checks"].items() if v is not True) or "all ok"
        params = " ".join(f"{k}={v:g}" for k, v in r["params"].items())
        fw = (f"{_g(r['fw_rate'])} ({r['fw_kind']})" if r["fw_verdict"] != "undefined"
              else "undefined")
        out.append(f"| {r['index']} | {r['model']} | {params} | {r['k_ring']:.4f} | {r['a']:g} "
                   f"| {r['N']} | {r['branch']} | {_g(r['nls_rate'])} | {_g(r['exact_rate'])} "
                   f"({r['exact_kind']}) | {_g(r['sim_rate'])} | {fw} | {checks} |")
    return "\n".join(out)


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--points", type=int, default=20)
    ap.add_argument("--seed", type=int, default=94)
    ap.add_argument("--only", default="")
    ap.add_argument("--json", default="")
    args = ap.parse_args(argv)
    pts = _points(args.points, args.seed)
    if args.only:
        keep = {int(i) for i in args.only.split(",")}
        pts = [p for p in pts if p["index"] in keep]
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        folder = pathlib.Path(tmp)
        for name, text in MODELS.items():
            (folder / f"{name}.toml").write_text(text)
        for pt in pts:
            row = probe(pt, folder)
            rows.append(row)
            print(json.dumps(row, default=str), flush=True)
    if args.json:
        pathlib.Path(args.json).write_text(json.dumps(rows, indent=1, default=str))
    bad = [r["index"] for r in rows if "error" in r
           or any(v is False for v in r.get("checks", {}).values())]
    print(table(rows), file=sys.stderr)
    print(f"{len(rows)} points, disagreements at {bad}", file=sys.stderr)
    return 0


if __name__ == "__main__":
    sys.exit(main())
