"""Speed near the hardware: the force kernel, time to a given error, the paper's run.

Measured in one run, interleaved (every configuration once per round, median over rounds),
so that a noisy machine slows all of them alike; read the ratios. Writes the "speed"
section of results.json (results_quick.json with --quick; in out/bench/, or bench/ with
--update) and prints a table.

1. Cost of one force evaluation per site (N = 500): our kernel (polynomial sin/cos,
   vectorised), the libm kernel it replaced, NumPy's sin + cos alone, the plain NumPy
   force (np.roll and the generated right-hand sides), and the stencil alone with the trig
   values given (the floor no kernel can beat); and the cost per site per force evaluation
   inside the fused RK4 and SRKN loops.
2. Time to a relative state error of 1e-6 (blue point, case II, N = 500, T = 200): every
   fixed-step method (with the order-8 kahanli8) at the dt that gives 1e-6 (log-log interpolation of a dt sweep, then
   checked), scipy's DOP853 at the rtol that gives 1e-6, fed (a) the plain NumPy force and
   (b) our compiled kernel. Reference: srkn11b at dt = 0.0025, checked by DOP853 at
   rtol = 1e-13.
3. The paper's run (case II, N = 500, T = 5000): RK4 at dt = 0.05 with the old libm loops
   and with the fused loops, and srkn11b at the dt whose error over T = 200 equals RK4's
   at dt = 0.05 (the paper's accuracy).

    python -m bench.speed [--quick] [--update | --out DIR]
"""

from __future__ import annotations

import statistics
import time

import numpy as np

from bench.simulator import arguments, machine, write_section
from common import paper
from numerics import Material, initial_condition
from numerics.lattice import Stepper, get_method, numpy_accel
from numerics.lattice import _kernels as kernels

MAT, CASE, K = Material.paper("blue"), "coupled", paper.k("blue")
N = paper.N
TARGET = 1e-6
FIXED = ("rk4", "verlet", "srkn6b", "srkn11b", "kahanli8")
SWEEPS = {"rk4": [0.1, 0.05, 0.025], "verlet": [0.02, 0.01, 0.005],
          "srkn6b": [0.2, 0.1, 0.05], "srkn11b": [0.8, 0.4, 0.2],
          "kahanli8": [0.6, 0.45, 0.3]}


def interleaved(configs: dict, rounds: int) -> dict:
    """Median wall time of each zero-argument callable, timed round-robin."""
    times = {name: [] for name in configs}
    for _ in range(rounds):
        for name, fn in configs.items():
            t0 = time.perf_counter()
            fn()
            times[name].append(time.perf_counter() - t0)
    return {name: statistics.median(t) for name, t in times.items()}


# --- 1. force cost -------------------------------------------------------------------------

def force_costs(quick):
    rng = np.random.default_rng(0)
    th, U = rng.normal(0, 0.02, N), rng.normal(0, 1e-4, N)
    s, c, v, a1, a2 = (np.empty(N) for _ in range(5))
    p = (MAT.alpha**2, MAT.K_s, MAT.K_theta)
    reps = 2000 if quick else 20000
    kernels.sincosvers(th, s, c, v)

    def loop(fn, n=reps):
        def run():
            for _ in range(n):
                fn()
        return run

    configs = {
        "kernel": loop(lambda: kernels.accel(th, U, True, *p, s, c, v, a1, a2)),
        "libm kernel": loop(lambda: kernels.accel_libm(th, U, True, *p, s, c, v, a1, a2)),
        "stencil only": loop(lambda: kernels._stencil(th, U, True, *p, s, c, v, a1, a2)),
        "polynomial sin+cos+vers only": loop(lambda: kernels.sincosvers(th, s, c, v)),
        "NumPy sin+cos": loop(lambda: (np.sin(th, out=s), np.cos(th, out=c))),
        "plain NumPy force": loop(lambda: numpy_accel(th, U, MAT, True), reps // 10),
    }
    for fn in configs.values():
        fn()  # compile and warm up
    med = interleaved(configs, 3 if quick else 7)
    per_site = {name: t / (reps // 10 if name == "plain NumPy force" else reps) / N * 1e9
                for name, t in med.items()}
    # inside the fused loops: per site per force evaluation
    state = initial_condition(MAT, CASE, N, K)
    T = 20.0 if quick else 100.0
    loops = {}
    for name in ("rk4", "srkn11b"):
        m = get_method(name)
        nsteps = int(round(T / 0.05))

        def run(m=m, nsteps=nsteps):
            Stepper(state, MAT, CASE, m, 0.05).advance(nsteps)
        loops[name] = run
        run()
    med = interleaved(loops, 3 if quick else 5)
    in_loop = {name: t / (int(round(T / 0.05)) * get_method(name).evaluations) / N * 1e9
               for name, t in med.items()}
    return {"ns_per_site": per_site, "ns_per_site_per_evaluation_in_loop": in_loop,
            "kernel_over_stencil": per_site["kernel"] / per_site["stencil only"],
            "libm_over_kernel": per_site["libm kernel"] / per_site["kernel"],
            "vectorised": kernels.vectorised_loops(True)}


# --- 2. time to 1e-6 -------------------------------------------------------------------------

def state_error(th, U, ref):
    return float(max(np.max(np.abs(th - ref.theta)), np.max(np.abs(U - ref.U)))
                 / np.max(np.abs(ref.theta)))


def fixed_run(name, dt, state, T, case=CASE):
    nsteps = int(np.ceil(T / dt - 1e-9))
    st = Stepper(state, MAT, case, get_method(name), T / nsteps)
    st.advance(nsteps)
    return st


def scipy_run(state, T, rtol, force):
    """DOP853 with our kernel ("kernel") or the plain NumPy force ("numpy")."""
    from scipy.integrate import solve_ivp

    if force == "kernel":
        st = Stepper(state, MAT, CASE, get_method("dop853"), T, rtol, rtol * 1e-3)
        st.advance(1)
        return st.th, st.U, st.evaluations
    n = state.N
    y0 = np.concatenate([state.theta, state.theta_dot, state.U, state.U_dot])

    def rhs(_t, y):
        ath, aU = numpy_accel(y[:n], y[2 * n:3 * n], MAT, True)
        return np.concatenate([y[n:2 * n], ath, y[3 * n:], aU])

    sol = solve_ivp(rhs, (0.0, T), y0, method="DOP853", rtol=rtol, atol=rtol * 1e-3)
    y = sol.y[:, -1]
    return y[:n], y[2 * n:3 * n], sol.nfev


def _interpolate(xs, errs, target):
    """x at which the error is ``target``: log-log line through the sweep."""
    slope, icpt = np.polyfit(np.log(xs), np.log(errs), 1)
    return float(np.exp((np.log(target) - icpt) / slope)), float(slope)


def time_to_error(quick):
    T = 50.0 if quick else 200.0
    state = initial_condition(MAT, CASE, N, K)
    ref = fixed_run("srkn11b", 0.0025, state, T).state()
    th_c, U_c, _ = scipy_run(state, T, 1e-13, "kernel")
    ref_check = state_error(th_c, U_c, ref)
    chosen, configs = {}, {}
    for name in (("rk4", "srkn11b") if quick else FIXED):
        errs = [state_error(*_fields(fixed_run(name, dt, state, T)), ref)
                for dt in SWEEPS[name]]
        dt, slope = _interpolate(SWEEPS[name], errs, TARGET)
        err = state_error(*_fields(fixed_run(name, dt, state, T)), ref)
        chosen[name] = {"dt": dt, "error": err, "slope": slope}
        configs[name] = lambda name=name, dt=dt: fixed_run(name, dt, state, T)
    rtols = [1e-7, 1e-8, 1e-9]
    errs = [state_error(*scipy_run(state, T, r, "kernel")[:2], ref) for r in rtols]
    rtol, slope = _interpolate(rtols, errs, TARGET)
    for force in ("numpy", "kernel"):
        th, U, nfev = scipy_run(state, T, rtol, force)
        chosen[f"dop853 ({force} force)"] = {"rtol": rtol, "error": state_error(th, U, ref),
                                             "evaluations": int(nfev), "slope": slope}
        configs[f"dop853 ({force} force)"] = \
            lambda force=force: scipy_run(state, T, rtol, force)
    med = interleaved(configs, 2 if quick else 5)
    for name, t in med.items():
        chosen[name]["wall_s"] = t
    best = min(FIXED if not quick else ("rk4", "srkn11b"), key=lambda n: med[n])
    return {"T": T, "target": TARGET, "reference": "srkn11b dt = 0.0025",
            "reference_vs_dop853_1e-13": ref_check, "runs": chosen, "best": best,
            "speedup_vs_dop853_numpy": med["dop853 (numpy force)"] / med[best],
            "speedup_vs_dop853_kernel": med["dop853 (kernel force)"] / med[best]}


def _fields(st):
    return st.th, st.U


# --- 3. the paper's run ----------------------------------------------------------------------

def paper_run(quick):
    state = initial_condition(MAT, CASE, N, K)
    T_acc = 50.0 if quick else 200.0
    ref = fixed_run("srkn11b", 0.0025, state, T_acc).state()
    err_rk4 = state_error(*_fields(fixed_run("rk4", paper.DT, state, T_acc)), ref)
    dts = [0.8, 0.4, 0.2]
    errs = [state_error(*_fields(fixed_run("srkn11b", dt, state, T_acc)), ref) for dt in dts]
    dt_same, _ = _interpolate(dts, errs, err_rk4)
    dt_same = min(dt_same, 0.8 * get_method("srkn11b").stability_limit() / MAT.omega_max(CASE))
    T = 500.0 if quick else paper.T_END
    nsteps = int(round(T / paper.DT))

    def libm_rk4():
        st = Stepper(state, MAT, CASE, get_method("rk4"), paper.DT)
        st._libm(nsteps)

    configs = {"rk4 dt = 0.05, libm loops (before)": libm_rk4,
               "rk4 dt = 0.05, fused loops": lambda: fixed_run("rk4", paper.DT, state, T),
               "srkn11b, same accuracy": lambda: fixed_run("srkn11b", dt_same, state, T)}
    med = interleaved(configs, 1 if quick else 3)
    return {"T": T, "rk4_error_over_T_acc": err_rk4, "T_acc": T_acc,
            "srkn11b_dt_same_accuracy": dt_same, "wall_s": med}


def main(quick=False, out=None):
    res = {"machine": machine(), "quick": quick, "force": force_costs(quick),
           "time_to_1e-6": time_to_error(quick), "paper_run": paper_run(quick)}
    write_section("speed", res, quick, out)
    f, t, p = res["force"], res["time_to_1e-6"], res["paper_run"]
    print("ns per site per force evaluation (N = 500):")
    for name, ns in f["ns_per_site"].items():
        print(f"  {name:<30} {ns:8.2f}")
    for name, ns in f["ns_per_site_per_evaluation_in_loop"].items():
        print(f"  in the fused {name} loop{'':<13} {ns:8.2f}")
    print(f"kernel / stencil floor = {f['kernel_over_stencil']:.2f}; libm kernel / kernel = "
          f"{f['libm_over_kernel']:.2f}; vectorised: {f['vectorised']}")
    print(f"time to a state error of {TARGET:g} (blue II, N = 500, T = {t['T']:g}):")
    for name, r in t["runs"].items():
        knob = f"dt = {r['dt']:.4g}" if "dt" in r else f"rtol = {r['rtol']:.3g}"
        print(f"  {name:<22} {knob:<16} error {r['error']:.2e}  {r['wall_s'] * 1e3:9.1f} ms")
    print(f"best ({t['best']}) vs DOP853 with the NumPy force: "
          f"{t['speedup_vs_dop853_numpy']:.0f}x; with our kernel: "
          f"{t['speedup_vs_dop853_kernel']:.1f}x")
    print(f"the paper's run (case II, N = 500, T = {p['T']:g}); RK4 dt = 0.05 error over "
          f"T = {p['T_acc']:g}: {p['rk4_error_over_T_acc']:.2e}")
    for name, s in p["wall_s"].items():
        print(f"  {name:<40} {s:7.2f} s")
    return res


if __name__ == "__main__":
    main(*arguments(__doc__))
