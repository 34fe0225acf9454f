"""Any model's compiled force against the fused flexMM kernel, and a model run's cost.

- ns per site of one force evaluation on a ring of N = 500: the fused kernel of eq. `norm`
  (``numerics.lattice`` accel, the paper chain's fast path) and the force compiled from the
  flexmm energy file (``numerics.models``: per cell, the generated gradient of
  W(u_n, u_{n+1}), subtracted from both sites). Same state, same run, best of REPEATS.
  The issue's bar: the generic force within 3x the fused kernel per site.
- The same for the other built-in models (one and two fields).
- The floor a person would write (issue 41): hand-written Numba forces of fput and
  klein-gordon (``_fput_by_hand``, ``_kg_by_hand``: one loop over the sites, the
  neighbours' differences in registers, the ring's ends outside the loop), timed as the
  generated ones; the generated force's ns per site over the hand-written one (goal: 1.3).
- A three-way point (exact theory, a simulation, the NLS) per model: wall times.
- The exact lattice theory against the run it predicts (issue 41), per built-in model at
  one point: CPU seconds of ``exact_gain`` on the ring of N = 256 and on the infinite
  chain, of one seeded run of that ring (``simulate_seeds(..., seeds=1)``, its default
  length), and their ratios (the goal: <= 0.1). Warm (compiled), one BLAS thread
  (``exact_gain``'s own), best of REPEATS_EXACT, ``time.process_time``. Beside them the
  chain's floor: the wave (``travelling_wave``) and one dense LU solve of the whole Hill
  pencil (fields x (2 P + 1) square) at each of the chain's 440 offsets, the least a method
  that must find each offset's growing modes does where no offset is certified stable
  without one (flexmm, stiff-hinge: growing copies at every offset at P = 10).
- A 64 x 64 theory-only ``--exact`` map of fput (N = 256) through the command line: wall
  and CPU seconds (the goal: <= 60 s; 8 x 8 with --quick).
- The four-wave row against the NLS row per point (``four_wave_cost``): the NLS row
  (``model_coefficients``), the four-wave theory on the ring of 256 sites (``point``'s
  row) and on the infinite chain (``coefficients``' row), best of REPEATS each. The
  issue's bar: the four-wave row within 20x the NLS row.
- A damped point against its lossless twin (``losses_cost``, issue 42): the theories'
  rows (NLS, four-wave, exact on the point's ring: 256, and 64 for a small Klein-Gordon
  ring) with and without the amplification along the decaying carrier, and a run of the
  same length (site damping: the exact flow per site; bond damping: per ring mode). The
  issue's bar: within 2x the lossless twin.
Writes the "models" section of results.json (results_quick.json with --quick).

    python -m bench.models [--quick] [--update | --out DIR]
    python -m bench.models --losses-only [--update | --out DIR]   (the losses_cost row alone)
    python -m bench.models --exact-only [--quick] [--update | --out DIR]
                                           (the exact_against_runs rows alone)
"""

from __future__ import annotations

import math
import os
import time

import numpy as np
from numba import njit

from bench.models_exact import (  # noqa: F401 (EXACT_POINTS: bench.exact_points')
    EXACT_POINTS,
    exact_against_runs,
    exact_map,
    print_exact_against_runs,
)
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
@njit(cache=True, fastmath={"contract"}, error_model="numpy", boundscheck=False)
def _fput_by_hand(u, alpha, beta, out):
    """a_n = V'(u_{n+1} - u_n) - V'(u_n - u_{n-1}), V'(r) = r + alpha r^2 + beta r^3."""
    N = u.shape[1]
    x = u[0]
    a = out[0]
    r = x[0] - x[N - 1]
    f_back = r + alpha * r * r + beta * r * r * r
    for n in range(N - 1):
        r = x[n + 1] - x[n]
        f = r + alpha * r * r + beta * r * r * r
        a[n] = f - f_back
        f_back = f
    r = x[0] - x[N - 1]
    a[N - 1] = r + alpha * r * r + beta * r * r * r - f_back


@njit(cache=True, fastmath={"contract"}, error_model="numpy", boundscheck=False)
def _kg_by_hand(u, C, w2, alpha, beta, out):
    """a_n = C (u_{n+1} - 2 u_n + u_{n-1}) - (w0^2 u_n + alpha u_n^2 + beta u_n^3)."""
    N = u.shape[1]
    x = u[0]
    a = out[0]
    for n in range(N):
        xm = x[n - 1] if n > 0 else x[N - 1]
        xp = x[n + 1] if n < N - 1 else x[0]
        xn = x[n]
        a[n] = C * (xp - 2.0 * xn + xm) - xn * (w2 + xn * (alpha + beta * xn))


def by_hand(rng, N, reps):
    """(generated, hand-written) ns per site for fput and klein-gordon at their default
    parameters with alpha = 0.5 (every term of the energy present), same state."""
    out = {}
    for name in ("fput", "klein-gordon"):
        model = load_model(name).with_params(alpha=0.5)
        p = model.params
        u = np.ascontiguousarray(rng.normal(0, 0.05, (1, N)))
        gen, hand = np.empty_like(u), np.empty_like(u)
        force = compiled_force(model, N)
        if name == "fput":
            def f_hand(u=u, o=hand, p=p):
                _fput_by_hand(u, p["alpha"], p["beta"], o)
        else:
            def f_hand(u=u, o=hand, p=p):
                _kg_by_hand(u, p["C"], p["omega0"] ** 2, p["alpha"], p["beta"], o)
        force(u, gen)
        f_hand()
        np.testing.assert_allclose(gen, hand, rtol=1e-12, atol=1e-15)
        t_gen = _best(lambda f=force, u=u, o=gen: f(u, o), reps) / N * 1e9
        t_hand = _best(f_hand, reps) / N * 1e9
        out[name] = {"generated_ns_per_site": t_gen, "by_hand_ns_per_site": t_hand,
                     "generated_over_by_hand": t_gen / t_hand}
    return out


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

KG_SITE = """name = "kg-lossy"
fields = ["u"]
[parameters]
C = 1.0
omega0 = 1.0
beta = 1.0
gamma = 0.001
[energy]
kinetic = "u_t**2/2"
bond = "C*(u_next - u)**2/2"
site = "omega0**2*u**2/2 + beta*u**4/4"
[dissipation]
site = "gamma*u_t**2/2"
"""

#: (label, lossless twin, lossy model, k, a, ring N): the paper's blue point (case II,
#: a = 2 eps A0 with A0 = 1.4) with weak damping, FPUT with bond damping (the per-mode
#: flow), and the cheap Klein-Gordon chain (phi^4, the built-in klein-gordon's energy)
#: with site damping on a large and a small ring: there the damped theories' extra
#: samples weigh most against the lossless point
LOSS_POINTS = (("flexmm blue, gamma 1e-4", ("flexmm", {}),
                ("flexmm-lossy", dict(gamma_theta=1e-4, gamma_U=1e-4)), 0.81681, 0.028,
                256),
               ("fput bond eta 0.004", ("fput", dict(alpha=0.0, beta=1.0)),
                (FPUT_BOND, {}), 2.5, 0.2, 256),
               ("klein-gordon site gamma 0.001", ("klein-gordon", {}), (KG_SITE, {}), 2.0,
                0.4, 256),
               ("klein-gordon site gamma 0.004, N 64", ("klein-gordon", {}),
                (KG_SITE, dict(gamma=0.004)), 2.0, 0.4, 64))


def losses_cost(t_end=500.0, reps=7) -> dict:
    """CPU seconds (``time.process_time``: every part runs on one thread, and on a shared
    machine the wall clock counts the others' work) of a damped point against its
    lossless twin: the theories (with the amplifications) and a run of ``t_end`` (no
    early stop), each after a warm-up call, on the point's ring; the lossless and the
    lossy point alternate within each of ``reps`` rounds, best of ``reps``."""
    from energy import parse_model
    from numerics.models import (
        exact_amplification,
        four_wave_amplification,
        nls,
        nls_amplification,
    )

    def theories(m, k, a, lossy, N):
        e = exact_gain(m, k, a, N=N)
        f = four_wave(m, k, a, N=N)
        r = nls(m, k)
        if lossy:
            nls_amplification(m, k, a, first=r)
            four_wave_amplification(m, k, a, N=N, first=f)
            return exact_amplification(m, k, a, N=N, first=e)
        return e

    out = {}
    for label, (plain, pp), (lossy, lp), k, a, N in LOSS_POINTS:
        m0 = load_model(plain).with_params(**pp) if pp else load_model(plain)
        m1 = load_model(parse_model(lossy) if "\n" in lossy else lossy)
        m1 = m1.with_params(**lp) if lp else m1
        twins = (("lossless", m0, False), ("lossy", m1, True))
        for _, m, is_lossy in twins:
            theories(m, k, a, is_lossy, N)  # warm-up: imports, generated module, JIT
            simulate_model(m, k, a, N=N, t_end=10.0)
        times = {f"{key}_{part}": [] for key, _, _ in twins for part in ("theory_s", "run_s")}
        row = {}
        for _ in range(reps):
            for key, m, is_lossy in twins:
                # a fresh model object each round: nothing a theory keeps for its model
                # (the sidebands' damping rates) carries over from the round before
                m = m.with_params()
                t0 = time.process_time()
                th = theories(m, k, a, is_lossy, N)
                t1 = time.process_time()
                simulate_model(m, k, a, N=N, t_end=t_end)
                times[f"{key}_theory_s"].append(t1 - t0)
                times[f"{key}_run_s"].append(time.process_time() - t1)
                if is_lossy:
                    row["amplification"] = th.amplification
        row.update({name: min(v) for name, v in times.items()})
        row["theory_ratio"] = row["lossy_theory_s"] / row["lossless_theory_s"]
        row["run_ratio"] = row["lossy_run_s"] / row["lossless_run_s"]
        # what `point --simulate` pays: its theories and its run (each part's best round)
        row["point_ratio"] = ((row["lossy_theory_s"] + row["lossy_run_s"])
                              / (row["lossless_theory_s"] + row["lossless_run_s"]))
        out[label] = row
        print(f"{label}: theory {row['lossless_theory_s'] * 1e3:.1f} ms -> "
              f"{row['lossy_theory_s'] * 1e3:.1f} ms ({row['theory_ratio']:.2f}x, exact "
              f"amplification {row['amplification']:.4g}); run of T = {t_end:g}, N = {N}: "
              f"{row['lossless_run_s'] * 1e3:.1f} ms -> {row['lossy_run_s'] * 1e3:.1f} ms "
              f"({row['run_ratio']:.2f}x); the point, theories and run, "
              f"{row['point_ratio']:.2f}x")
    return out


def force_rows(rng, N, reps, args=None):
    """(fused flexMM kernel, {model: generated force}) ns per site on a ring of N."""
    if args is None:
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
    return fused, per_model


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
    fused, per_model = force_rows(rng, N, reps, args=args)
    # compile the exact theory's kernels outside every timing (numba caches them on disk:
    # ~12 s once per install on an idle machine, 57 s measured under a load of 6)
    exact_gain(load_model("fput"), 2.0, 0.1, N=32)
    exact_gain(load_model("diatomic-fput"), 1.0, 0.1, 0, N=32)
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
    floor = by_hand(rng, N, reps)
    against = exact_against_runs(quick)
    emap = exact_map(quick)
    res = {"machine": machine(), "quick": quick, "N": N, "repeats": REPEATS,
           "load_average": list(os.getloadavg()),
           "fused_flexmm_ns_per_site": fused, "generic_ns_per_site": per_model,
           "generic_flexmm_over_fused": per_model["flexmm"] / fused, "points": points,
           "four_wave_vs_nls": cost, "losses": losses,
           "generated_against_by_hand": floor, "exact_against_runs": against,
           "exact_map_fput": emap}
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
    for name, r in floor.items():
        print(f"  {name:<16} generated {r['generated_ns_per_site']:.2f} ns, by hand "
              f"{r['by_hand_ns_per_site']:.2f} ns: {r['generated_over_by_hand']:.2f}x "
              "(goal: <= 1.3x)")
    print_exact_against_runs(against)
    print(f"theory-only --exact map of fput, {emap['cells']} cells, N = {emap['N']}: "
          f"{emap['wall_s']:.1f} s wall, {emap['cpu_s']:.1f} s CPU (goal: <= 60 s at 64 x 64)")
    return res


def force_only(reps=2000, N=500):
    """The force rows alone (``python -m bench.models --force-only``): printed, not written."""
    rng = np.random.default_rng(0)
    fused, per_model = force_rows(rng, N, reps)
    floor = by_hand(rng, N, reps)
    print(f"force per site, N = {N}: fused flexMM kernel {fused:.2f} ns; generic:")
    for name, t in per_model.items():
        print(f"  {name:<16} {t:6.2f} ns ({t / fused:.2f}x the fused kernel)")
    for name, r in floor.items():
        print(f"  {name:<16} generated {r['generated_ns_per_site']:.2f} ns, by hand "
              f"{r['by_hand_ns_per_site']:.2f} ns: {r['generated_over_by_hand']:.2f}x "
              "(goal: <= 1.3x)")
    return fused, per_model, floor


def losses_only(argv):
    """The damped points alone (``python -m bench.models --losses-only [--update | --out
    DIR]``): ``losses_cost`` printed and put into the "models" section's ``losses`` entry
    of results.json, the rest of the section kept (with the load average it ran at)."""
    import json

    from bench.simulator import results_path, write_sections

    quick, out = arguments(__doc__, argv)
    losses = losses_cost(200.0 if quick else 500.0)
    path = results_path(quick, out)
    models = json.loads(path.read_text()).get("models", {}) if path.exists() else {}
    models["losses"] = losses
    models["losses_load_average"] = list(os.getloadavg())
    write_sections({"models": models}, quick, out)


def exact_only(argv):
    """The exact theory against one run alone (``python -m bench.models --exact-only
    [--quick] [--update | --out DIR]``): ``exact_against_runs`` printed and put into the
    "models" section's ``exact_against_runs`` entry, the rest of the section kept (with the
    load average it ran at)."""
    import json

    from bench.simulator import results_path, write_sections

    quick, out = arguments(__doc__, argv)
    against = exact_against_runs(quick)
    print_exact_against_runs(against)
    path = results_path(quick, out)
    models = json.loads(path.read_text()).get("models", {}) if path.exists() else {}
    models["exact_against_runs"] = against
    models["exact_load_average"] = list(os.getloadavg())
    write_sections({"models": models}, quick, out)
    return against


if __name__ == "__main__":
    import sys

    if "--force-only" in sys.argv:
        force_only()
    elif "--losses-only" in sys.argv:
        losses_only([a for a in sys.argv[1:] if a != "--losses-only"])
    elif "--exact-only" in sys.argv:
        exact_only([a for a in sys.argv[1:] if a != "--exact-only"])
    else:
        main(*arguments(__doc__))
