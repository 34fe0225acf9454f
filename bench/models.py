"""Any model's compiled force against the fused flexMM kernel, and a model run's cost.

- ns per site of one force evaluation on a ring of N = 500: the fused kernel of eq. `norm`
  (``numerics.lattice`` accel, the paper chain's fast path) and the force compiled from the
  flexmm energy file (``numerics.models``: per cell, the generated gradient of
  W(u_n, u_{n+1}), subtracted from both sites). Same state, same run, best of REPEATS.
  The issue's bar: the generic force within 3x the fused kernel per site.
- The same for the other built-in models (one and two fields).
- A three-way point (exact theory, a simulation, the NLS) per model: wall times.
- The four-wave row against the NLS row per point (``four_wave_cost``): the NLS row
  (``model_coefficients``), the four-wave theory on the ring of 256 sites (``point``'s
  row) and on the infinite chain (``coefficients``' row), best of REPEATS each. The
  issue's bar: the four-wave row within 20x the NLS row.
- A damped point against its lossless twin (``losses_cost``, issue 42): the theories'
  rows (NLS, four-wave, exact on a ring of 256) with and without the amplification along
  the decaying carrier, and a run of the same length (site damping: the exact flow per
  site; bond damping: per ring mode). The issue's bar: within 2x the lossless twin.
Writes the "models" section of results.json (results_quick.json with --quick).

    python -m bench.models [--quick] [--update | --out DIR]
"""

from __future__ import annotations

import math
import time

import numpy as np

from bench.simulator import arguments, machine, write_section
from energy import load_model
from numerics.lattice._kernels import accel
from numerics.models import (
                     compiled_force,
                     exact_gain,
                     four_wave,
                     model_coefficients,
                     simulate_model,
)

REPEATS = 5


def _best(f, reps):
    walls = []
    for _ in range(REPEATS):
        t0 = time.perf_counter()
        for _ in range(reps):
            f()
        walls.append((time.perf_counter() - t0) / reps)
    return min(walls)


#: the four-wave cost points: the issue's FPUT and Klein-Gordon points at k = pi / 2, a
#: two-field optical carrier, the paper chain
FOUR_WAVE_POINTS = (("fput", dict(alpha=0.5, beta=1.0), math.pi / 2, None),
                    ("klein-gordon", dict(alpha=0.5), math.pi / 2, None),
                    ("diatomic-fput", {}, 1.0, 1),
                    ("flexmm", {}, 1.0, None))


def four_wave_cost(reps=20) -> dict:
    """Wall time per point of the NLS row and the four-wave rows (ring of 256, chain), and
    their ratios (a = 0.1)."""
    out = {}
    for name, params, k, br in FOUR_WAVE_POINTS:
        model = load_model(name).with_params(**params) if params else load_model(name)
        four_wave(model, k, 0.1, br, N=256)  # first call: imports, generated module
        nls_s = _best(lambda m=model, k=k, b=br: model_coefficients(m, k, 0.1, b), reps)
        ring_s = _best(lambda m=model, k=k, b=br: four_wave(m, k, 0.1, b, N=256), reps)
        chain_s = _best(lambda m=model, k=k, b=br: four_wave(m, k, 0.1, b), reps)
        out[name] = {"nls_row_s": nls_s, "four_wave_ring_s": ring_s,
                     "four_wave_chain_s": chain_s, "ring_over_nls": ring_s / nls_s,
                     "chain_over_nls": chain_s / nls_s}
    return out


FPUT_BOND = """name = "fput-bond-lossy"
fields = ["u"]
[parameters]
beta = 1.0
eta = 0.004
[energy]
kinetic = "u_t**2/2"
bond = "(u_next - u)**2/2 + beta*(u_next - u)**4/4"
[dissipation]
bond = "eta*(u_next_t - u_t)**2/2"
"""

#: (label, lossless twin, lossy model, k, a): the paper's blue point (case II, a = 2 eps
#: A0 with A0 = 1.4) with weak damping, FPUT with bond damping (the per-mode flow)
LOSS_POINTS = (("flexmm blue, gamma 1e-4", ("flexmm", {}),
                ("flexmm-lossy", dict(gamma_theta=1e-4, gamma_U=1e-4)), 0.81681, 0.028),
               ("fput bond eta 0.004", ("fput", dict(alpha=0.0, beta=1.0)),
                (FPUT_BOND, {}), 2.5, 0.2))


def losses_cost(t_end=500.0, N=256) -> dict:
    """Wall times of a damped point against its lossless twin: the theories (with the
    amplifications) and a run of ``t_end`` (no early stop), each after a warm-up call,
    best of 3."""
    from energy import parse_model
    from numerics.models import (
        exact_amplification,
        four_wave_amplification,
        nls,
        nls_amplification,
    )

    def theories(m, k, a, lossy):
        e = exact_gain(m, k, a, N=N)
        f = four_wave(m, k, a, N=N)
        nls(m, k)
        if lossy:
            nls_amplification(m, k, a)
            four_wave_amplification(m, k, a, N=N, first=f)
            return exact_amplification(m, k, a, N=N, first=e)
        return e

    out = {}
    for label, (plain, pp), (lossy, lp), k, a in LOSS_POINTS:
        m0 = load_model(plain).with_params(**pp) if pp else load_model(plain)
        m1 = load_model(parse_model(lossy) if "\n" in lossy else lossy)
        m1 = m1.with_params(**lp) if lp else m1
        row = {}
        for key, m, is_lossy in (("lossless", m0, False), ("lossy", m1, True)):
            theories(m, k, a, is_lossy)  # warm-up: imports, generated module, JIT
            simulate_model(m, k, a, N=N, t_end=10.0)
            th_s, run_s = [], []
            for _ in range(3):  # best of 3 (a shared machine)
                t0 = time.perf_counter()
                th = theories(m, k, a, is_lossy)
                t1 = time.perf_counter()
                simulate_model(m, k, a, N=N, t_end=t_end)
                th_s.append(t1 - t0)
                run_s.append(time.perf_counter() - t1)
            row[f"{key}_theory_s"], row[f"{key}_run_s"] = min(th_s), min(run_s)
            if is_lossy:
                row["amplification"] = th.amplification
        row["theory_ratio"] = row["lossy_theory_s"] / row["lossless_theory_s"]
        row["run_ratio"] = row["lossy_run_s"] / row["lossless_run_s"]
        out[label] = row
        print(f"{label}: theory {row['lossless_theory_s']:.2f} s -> "
              f"{row['lossy_theory_s']:.2f} s ({row['theory_ratio']:.2f}x, exact "
              f"amplification {row['amplification']:.4g}); run of T = {t_end:g}, N = {N}: "
              f"{row['lossless_run_s']:.2f} s -> {row['lossy_run_s']:.2f} s "
              f"({row['run_ratio']:.2f}x)")
    return out


def main(quick=False, out=None):
    N = 500
    reps = 200 if quick else 2000
    rng = np.random.default_rng(0)
    flex = load_model("flexmm")
    p = flex.params
    th, U = rng.normal(0, 0.05, N), rng.normal(0, 1e-3, N)
    s, c, v, ath, aU = (np.empty(N) for _ in range(5))
    args = (th, U, True, p["alpha"] ** 2, p["K_s"], p["K_theta"], s, c, v, ath, aU)
    accel(*args)
    fused = _best(lambda: accel(*args), reps) / N * 1e9
    per_model = {}
    for name in ("flexmm", "flexmm-rotation", "fput", "klein-gordon", "sine-gordon",
                 "diatomic-fput"):
        model = load_model(name)
        d = model.n_fields
        u = np.ascontiguousarray(rng.normal(0, 0.05, (d, N)))
        force = compiled_force(model, N)
        outa = np.empty_like(u)
        force(u, outa)  # compile
        per_model[name] = _best(lambda f=force, u=u, o=outa: f(u, o), reps) / N * 1e9
    points = {}
    for name, params, k, br in (("fput", dict(alpha=0.0, beta=1.0), 2.0, None),
                                ("diatomic-fput", {}, 1.0, 0),
                                ("flexmm", {}, 1.0, None)):
        model = load_model(name).with_params(**params) if params else load_model(name)
        t0 = time.perf_counter()
        e = exact_gain(model, k, 0.1, br, N=256)
        t1 = time.perf_counter()
        r = simulate_model(model, k, 0.1, branch=br, N=256, wave=e.wave,
                           expected_gain=e.peak_gain, t_end=500.0 if quick else None)
        t2 = time.perf_counter()
        g = r.growth()
        points[name] = {"exact_s": t1 - t0, "simulation_s": t2 - t1, "t_end": r.t_end,
                        "exact_gain": e.peak_gain, "measured_rate": g.rate,
                        "energy_drift": r.energy_drift}
    cost = four_wave_cost(5 if quick else 20)
    losses = losses_cost(200.0 if quick else 500.0)
    res = {"machine": machine(), "quick": quick, "N": N, "repeats": REPEATS,
           "fused_flexmm_ns_per_site": fused, "generic_ns_per_site": per_model,
           "generic_flexmm_over_fused": per_model["flexmm"] / fused, "points": points,
           "four_wave_vs_nls": cost, "losses": losses}
    write_section("models", res, quick, out)
    print(f"force per site, N = {N}: fused flexMM kernel {fused:.2f} ns; generic:")
    for name, t in per_model.items():
        print(f"  {name:<16} {t:6.2f} ns ({t / fused:.2f}x the fused kernel)")
    for name, pt in points.items():
        print(f"point {name}: exact {pt['exact_s']:.2f} s, simulation {pt['simulation_s']:.2f} s "
              f"(T = {pt['t_end']:g}); gain {pt['exact_gain']:.4g} vs measured "
              f"{pt['measured_rate']:.4g}")
    for name, c in cost.items():
        print(f"four-wave {name}: NLS row {c['nls_row_s'] * 1e3:.2f} ms, four-wave ring "
              f"{c['four_wave_ring_s'] * 1e3:.2f} ms ({c['ring_over_nls']:.1f}x), chain "
              f"{c['four_wave_chain_s'] * 1e3:.2f} ms ({c['chain_over_nls']:.1f}x)")
    return res


if __name__ == "__main__":
    main(*arguments(__doc__))
