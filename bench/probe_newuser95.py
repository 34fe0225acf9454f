"""A new user's five lattices, end to end (probe 95): model files of kinds the
project had not tried, each checked against what can be derived without the code under
test, at chosen points near band edges, crossings, zero dispersion and k = pi, pi/2.

The five models (TOML, written to files and loaded as a user's would be):

- ``fk-cubic``: Frenkel-Kontorova (on-site w0^2 (1 - cos u)) with a cubic-quartic bond:
  on-site and inter-site nonlinearity together;
- ``cross``: an acoustic field u and a flat oscillator v coupled only nonlinearly, so
  their branches cross exactly at 2 sin(k/2) = wv (k = pi/3 for wv = 1);
- ``soft-pi``: a softening FPUT bond r^2/2 + a3 r^3/3 - b4 r^4/4 (a barrier at r ~ 1),
  MI at k = pi that drives the wave past the barrier;
- ``lossy-res``: mass-in-mass (a local resonator v of mass m on each outer mass u), hardening
  resonator spring, Rayleigh damping on v only;
- ``flat-kg``: Klein-Gordon with a tiny coupling (a nearly flat branch, g1 = C cos k ->
  0 at ~pi/2), unusual names (``q_1``, ``C_tiny_2``, an integer parameter) and a TOML
  description with quotes, unicode, a literal backslash and a tab.

Independent checks per point: the branches against a closed form derived by hand and a
finite-difference linearisation of the compiled force (bench/probe_models94); g1 against
second differences of the hand-derived omega(k); g2 against a closed form where one was
derived by hand (fk-cubic: Lindstedt with its second harmonic; cross's u carrier and
soft-pi: FPUT's -12 beta s^3 + 8 alpha^2 s (1 + s^2); flat-kg: -3 lambda / (2 omega));
the carrier damping against the root of the damped symbol written by hand (lossy-res);
a run's energy against the energy written by hand at its last state, and conservation
(or dE/dt = -2R); then probe_models94's agreement rules (run vs exact within 10%, the
four-wave's kind and rate, the NLS against the infinite chain).

    OMP_NUM_THREADS=1 NUMBA_NUM_THREADS=1 python -m bench.probe_newuser95 [--only 0,3]
        [--json OUT.json]
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
    "fk-cubic": '''name = "fk-cubic"
description = "Frenkel-Kontorova chain with a cubic-quartic bond"
fields = ["u"]
[parameters]
w0 = 0.8
alpha = 0.6
beta = 0.4
[energy]
kinetic = "u_t**2/2"
bond = "(u_next - u)**2/2 + alpha*(u_next - u)**3/3 + beta*(u_next - u)**4/4"
site = "w0**2*(1 - cos(u))"
''',
    "cross": '''name = "cross"
description = "acoustic u and a flat oscillator v, coupled only nonlinearly: branches cross"
fields = ["u", "v"]
branch = "u"
[parameters]
wv = 1.0
c = 0.5
b = 0.5
[energy]
kinetic = "u_t**2/2 + v_t**2/2"
bond = "(u_next - u)**2/2 + b*(u_next - u)**4/4 + c*(u_next - u)*v**2"
site = "wv**2*v**2/2 + v**4/4"
''',
    "soft-pi": '''name = "soft-pi"
description = "softening FPUT chain: negative quartic bond stiffness"
fields = ["u"]
[parameters]
a3 = 0.3
b4 = 1.0
[energy]
kinetic = "u_t**2/2"
bond = "(u_next - u)**2/2 + a3*(u_next - u)**3/3 - b4*(u_next - u)**4/4"
''',
    "lossy-res": '''name = "lossy-res"
description = "mass-in-mass chain, hardening resonator spring, damping on the resonator only"
fields = ["u", "v"]
[parameters]
m = 0.5
kr = 0.6
beta = 1.0
gr = 0.01
[energy]
kinetic = "u_t**2/2 + m*v_t**2/2"
bond = "(u_next - u)**2/2 + beta*(u_next - u)**4/4"
site = "kr*(v - u)**2/2 + kr*(v - u)**4/4"
[dissipation]
site = "gr*v_t**2/2"
''',
    "flat-kg": """# a nearly flat branch: on-site nonlinearity, a tiny coupling
name = "flat-kg"
description = '''Klein-Gordon with "almost no" coupling \u2014 \u03c9 \u2248 \u03a9\u2080; 'quotes', \\n stays, tab\there'''
fields = ["q_1"]
[parameters]
C_tiny_2 = 1e-3
Omega_0 = 1.0
lambda_4 = 1    # an integer, not a float
[energy]
kinetic = \"\"\"q_1_t**2/2\"\"\"
bond = 'C_tiny_2*(q_1_next - q_1)**2/2'
site = "Omega_0**2*q_1**2/2 + lambda_4*q_1**4/4"
""",
}

PI = math.pi
#: (model, params, k, a, N, branch): near band edges, the crossing, zero dispersion, pi, pi/2
POINTS = [
    ("fk-cubic", {}, PI / 2, 0.15, 128, None),
    ("fk-cubic", {}, PI, 0.15, 128, None),
    ("fk-cubic", {}, 1.0, 0.1, 128, None),
    ("cross", {}, 1.0, 0.1, 128, "u"),           # just past the crossing at pi/3
    ("cross", {}, 2.5, 0.1, 64, "u"),
    ("cross", {}, 2.0, 0.1, 64, "v"),            # the flat branch: g1 = 0
    ("soft-pi", {}, 1.0, 0.1, 128, None),
    ("soft-pi", {}, PI, 0.3, 64, None),          # MI drives the wave past its barrier
    ("soft-pi", {}, PI / 2, 0.1, 128, None),
    ("lossy-res", {"gr": 0.001}, 1.0, 0.2, 64, None),
    ("lossy-res", {"gr": 0.0}, 1.0, 0.2, 64, None),
    ("flat-kg", {}, 2.5, 0.1, 64, None),         # the NLS's band passes pi/2
    ("flat-kg", {}, 1.0, 0.1, 64, None),
]


def omega_by_hand(name: str, p: dict, k: float) -> np.ndarray:
    """Each model's linear branches, derived by hand from its energy's quadratic part."""
    s2 = math.sin(k / 2) ** 2
    if name == "fk-cubic":
        return np.array([math.sqrt(p["w0"] ** 2 + 4 * s2)])
    if name == "cross":  # the coupling c (u_next - u) v^2 is cubic: no linear term
        return np.sort([2 * math.sqrt(s2), p["wv"]])
    if name == "soft-pi":
        return np.array([2 * math.sqrt(s2)])
    if name == "flat-kg":
        return np.array([math.sqrt(p["Omega_0"] ** 2 + 4 * p["C_tiny_2"] * s2)])
    if name == "lossy-res":  # M = diag(1, m), K = [[4 s^2 + kr, -kr], [-kr, kr]]
        A, kr, m = 4 * s2 + p["kr"], p["kr"], p["m"]
        tr, det = A + kr / m, (A * kr - kr * kr) / m
        r = math.sqrt(tr * tr / 4 - det)
        return np.sqrt([tr / 2 - r, tr / 2 + r])
    raise KeyError(name)


def g2_by_hand(name: str, p: dict, k: float, branch) -> float | None:
    """g2 in closed form where derived by hand (None where not)."""
    s = math.sin(k / 2)
    if name == "fk-cubic":
        # Lindstedt: omega^2 = W^2 - w0^2 a^2/8 + 12 beta a^2 s^4 - 8 alpha s^2 B sin k,
        # B (per a^2) = 4 alpha s^2 sin k / (W(2k)^2 - 4 W^2); g2 = -4 d omega / a^2
        W2 = p["w0"] ** 2 + 4 * s * s
        B = 4 * p["alpha"] * s * s * math.sin(k) / (p["w0"] ** 2 + 4 * math.sin(k) ** 2
                                                    - 4 * W2)
        dw2 = -p["w0"] ** 2 / 8 + 12 * p["beta"] * s**4 - 8 * p["alpha"] * s * s * B * math.sin(k)
        return -4 * dw2 / (2 * math.sqrt(W2))
    if name == "cross" and branch == "u":  # v is not driven at second order (v^2 coupling)
        return -12 * p["b"] * abs(s) ** 3
    if name == "soft-pi":  # FPUT with alpha = a3, beta = -b4, mean flow included
        return 12 * p["b4"] * s**3 + 8 * p["a3"] ** 2 * s * (1 + s * s)
    if name == "flat-kg":
        return -1.5 * p["lambda_4"] / omega_by_hand(name, p, k)[0]
    return None


def damping_by_hand(p: dict, k: float) -> float:
    """lossy-res's carrier (lower branch) amplitude decay rate: -Im of the root of
    det(K - i omega C - omega^2 M) = m w^4 + i gr w^3 - (A m + kr) w^2 - i A gr w
    + (A kr - kr^2), A = 4 sin^2(k/2) + kr, nearest the lossless lower branch."""
    A, kr, m, gr = 4 * math.sin(k / 2) ** 2 + p["kr"], p["kr"], p["m"], p["gr"]
    roots = np.roots([m, 1j * gr, -(A * m + kr), -1j * A * gr, A * kr - kr * kr])
    w0 = omega_by_hand("lossy-res", p, k)[0]
    return float(-roots[np.argmin(np.abs(roots - w0))].imag)


def energy_by_hand(name: str, p: dict, u, v) -> float:
    """The ring's total energy from its state (u, v: positions and velocities, (d, N))."""
    x, xt = np.asarray(u, float), np.asarray(v, float)
    r = np.roll(x, -1, axis=1) - x  # x_{n+1} - x_n
    if name == "fk-cubic":
        return float(np.sum(xt[0] ** 2 / 2 + r[0] ** 2 / 2 + p["alpha"] * r[0] ** 3 / 3
                            + p["beta"] * r[0] ** 4 / 4 + p["w0"] ** 2 * (1 - np.cos(x[0]))))
    if name == "cross":
        return float(np.sum(xt[0] ** 2 / 2 + xt[1] ** 2 / 2 + r[0] ** 2 / 2
                            + p["b"] * r[0] ** 4 / 4 + p["c"] * r[0] * x[1] ** 2
                            + p["wv"] ** 2 * x[1] ** 2 / 2 + x[1] ** 4 / 4))
    if name == "soft-pi":
        return float(np.sum(xt[0] ** 2 / 2 + r[0] ** 2 / 2 + p["a3"] * r[0] ** 3 / 3
                            - p["b4"] * r[0] ** 4 / 4))
    if name == "lossy-res":
        d = x[1] - x[0]
        return float(np.sum(xt[0] ** 2 / 2 + p["m"] * xt[1] ** 2 / 2 + r[0] ** 2 / 2
                            + p["beta"] * r[0] ** 4 / 4 + p["kr"] * d**2 / 2
                            + p["kr"] * d**4 / 4))
    if name == "flat-kg":
        return float(np.sum(xt[0] ** 2 / 2 + p["C_tiny_2"] * r[0] ** 2 / 2
                            + p["Omega_0"] ** 2 * x[0] ** 2 / 2 + p["lambda_4"] * x[0] ** 4 / 4))
    raise KeyError(name)


def write_models(folder: pathlib.Path) -> dict:
    """The model files in ``folder`` (the unusual one under a non-ASCII file name)."""
    paths = {}
    for name, text in MODELS.items():
        fname = "flat_\u00dcn\u00efcode.toml" if name == "flat-kg" else f"{name}.toml"
        paths[name] = folder / fname
        paths[name].write_text(text, encoding="utf-8")
    return paths


def probe(index: int, pt, paths) -> dict:
    """One point: the independent checks, every theory, a run, and the agreements."""
    from bench.probe_models94 import dispersion_by_differences, judge
    from energy import load_model
    from numerics.maps import ModelPointSpec, measure_point
    from numerics.models import branches, exact_gain, model_coefficients, simulate_model

    name, params, k, a, N, branch = pt
    model = load_model(str(paths[name])).with_params(**params)
    p = dict(model.params)
    row = dict(index=index, model=name, params=params, k=k, a=a, N=N,
               branch=0 if branch is None else branch)
    t0 = time.time()
    k64 = 2 * math.pi * round(k * 64 / (2 * math.pi)) / 64
    row["dispersion_err"] = float(np.max(np.abs(np.sort(branches(model, k))
                                                - omega_by_hand(name, p, k))))
    row["dispersion_fd_err"] = float(np.max(np.abs(np.sort(branches(model, k64))
                                                   - dispersion_by_differences(model, k64))))
    co = model_coefficients(model, k, a, branch)
    h, b = 1e-4, co["branch"]
    w = [omega_by_hand(name, p, k + s * h)[b] for s in (-1, 0, 1)]
    row["g1_err"] = abs(co["g1"] - (w[0] - 2 * w[1] + w[2]) / h**2)  # O(h^2) ~ 1e-8
    want = g2_by_hand(name, p, k, branch)
    row["g2_err"] = None if want is None or co["g2"] is None else abs(co["g2"] - want)
    row["coefficients_verdict"] = co["verdict"]
    if model.lossy:
        row["damping_err"] = abs(co["carrier_damping"] - damping_by_hand(p, k))
    try:
        point = measure_point(ModelPointSpec(model, k, a, branch=branch, N=N, simulate=True,
                                             seeds=1))
    except Exception as exc:  # a probe reports, it does not stop
        row["error"] = f"{type(exc).__name__}: {exc}"
        row["seconds"] = time.time() - t0
        return row
    d = point.as_dict()
    nl, ex, fw, sim = d["semi-discrete NLS"], d["exact lattice"], d["four-wave"], d["simulated"]
    row["k_ring"] = d["k"]
    for t in (nl, ex, fw):
        t["verdict"] = t.get("lossless_verdict", t["verdict"])
    row.update(nls_verdict=nl["verdict"], nls_rate=nl["peak_gain"],
               nls_reason=nl.get("reason", ""), exact_verdict=ex["verdict"],
               exact_rate=ex.get("peak_gain"), exact_kind=ex.get("mode_kind"),
               fw_verdict=fw["verdict"], fw_rate=fw.get("peak_gain"),
               fw_kind=fw.get("mode_kind"), fw_reason=fw.get("reason", ""),
               fw_kind_rates=fw.get("kind_rates", {}), exact_lossless_verdict=ex["verdict"],
               exact_damped_verdict=ex["verdict"], sim_verdict=sim["simulation_verdict"],
               sim_rate=sim["peak_gain"], sim_visible=sim.get("slowest_visible_rate"),
               energy_drift=sim.get("energy_drift"), energy_balance=sim.get("energy_balance"),
               notes=d.get("notes", []))
    if "amplification" in ex:
        row.update(exact_amplification=ex["amplification"],
                   exact_observable=ex["observable"], sim_amplification=sim["amplification"],
                   sim_observable=sim.get("observable"))
        row["exact_damped_verdict"] = d["exact lattice"].get("verdict")
    try:
        chain = exact_gain(model, row["k_ring"], a, branch)
        from bench.probe_models94 import _fastest_kind

        row.update(chain_rate=chain.peak_gain, chain_kind=_fastest_kind(chain),
                   chain_modulational=chain.modulational_gain)
    except Exception as exc:
        row["chain_error"] = f"{type(exc).__name__}: {exc}"
    # the energy written by hand at the end of a short run of this ring, and its drift
    run = simulate_model(model, k, a, branch=branch, N=N, t_end=200.0, seed=1)
    e_hand = energy_by_hand(name, p, *run.state)
    row["energy_hand_err"] = abs(e_hand - float(run.energy[-1])) / abs(e_hand)
    if model.lossy:  # 2R by hand (R = gr v_t^2 / 2 per site) at the last record's state
        two_r = p["gr"] * float(np.sum(np.asarray(run.state[1])[1] ** 2))
        row["dissipation_hand_err"] = abs(two_r - float(run.dissipation[-1])) / max(
            abs(two_r), 1e-300) if two_r else abs(float(run.dissipation[-1]))
    row["seconds"] = time.time() - t0
    row["checks"] = judge(row)
    row["checks"]["g1"] = bool(row["g1_err"] < 1e-6)
    if row["g2_err"] is not None:
        row["checks"]["g2"] = bool(row["g2_err"] < 1e-9 * max(1.0, abs(want)))
    if "damping_err" in row:
        row["checks"]["damping"] = bool(row["damping_err"] < 1e-10)
    row["checks"]["energy_by_hand"] = bool(row["energy_hand_err"] < 1e-12)
    if "dissipation_hand_err" in row:
        row["checks"]["dissipation_by_hand"] = bool(row["dissipation_hand_err"] < 1e-12)
    # the same (k, a) through coefficients (at the ring's k) and through point
    co_ring = model_coefficients(model, row["k_ring"], a, branch)
    # (both lossless words: the point's rows were read as the lossless chain's above)
    row["checks"]["coefficients_vs_point"] = bool(
        co_ring.get("lossless_verdict", co_ring["verdict"]) == d["semi-discrete NLS"]["verdict"])
    # k -> -k: the energy is real, so omega_b(-k) = omega_b(k)
    row["checks"]["k_symmetry"] = bool(np.allclose(branches(model, -k), branches(model, k),
                                                   rtol=1e-13, atol=1e-15))
    return row


def _g(x):
    return "-" if x is None else f"{x:.4g}"


def table(rows) -> str:
    """model, point, exact, run, four-wave, NLS, verdicts, agreement."""
    out = ["| # | model | k (ring) | a | N | br | exact (kind) | run | four-wave (kind) | NLS "
           "| verdicts NLS/4w/exact/run | agreement |", "|" + "---|" * 12]
    for r in rows:
        if "error" in r:
            out.append(f"| {r['index']} | {r['model']} | {r['k']:.4f} | {r['a']:g} | {r['N']} "
                       f"| {r['branch']} | {r['error'][:70]} | | | | | FAIL |")
            continue
        bad = ", ".join(f"{k}: {'FAIL' if v is False else v}" for k, v in r["checks"].items()
                        if v is not True) or "all ok"
        out.append(
            f"| {r['index']} | {r['model']} | {r['k_ring']:.4f} | {r['a']:g} | {r['N']} "
            f"| {r['branch']} | {_g(r['exact_rate'])} ({r['exact_kind']}) | {_g(r['sim_rate'])} "
            f"| {_g(r['fw_rate'])} ({r['fw_kind']}) | {_g(r['nls_rate'])} "
            f"| {r['nls_verdict']}/{r['fw_verdict']}/{r['exact_verdict']}/{r['sim_verdict']} "
            f"| {bad} |")
    return "\n".join(out)


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--only", default="", help="point indices, comma-separated")
    ap.add_argument("--json", default="")
    args = ap.parse_args(argv)
    keep = {int(i) for i in args.only.split(",")} if args.only else None
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        paths = write_models(pathlib.Path(tmp))
        for i, pt in enumerate(POINTS):
            if keep is None or i in keep:
                rows.append(probe(i, pt, paths))
                print(json.dumps(rows[-1], default=str), flush=True)
    if args.json:
        pathlib.Path(args.json).write_text(json.dumps(rows, indent=1, default=str))
    print(table(rows), file=sys.stderr)
    bad = [r["index"] for r in rows if "error" in r
           or any(v is False for v in r["checks"].values())]
    print(f"{len(rows)} points, disagreements at {bad}", file=sys.stderr)
    return 0


if __name__ == "__main__":
    sys.exit(main())
