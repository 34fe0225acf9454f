"""Where the error of the time-to-1e-6 runs sits, and what it would take to reach the
DOP853 goals of issue 23 (100x with the NumPy force, 15x with our kernel).

The problem of ``speed.py``'s time to 1e-6 (blue point, case II, N = 500, T = 200, the
paper's noisy start; reference srkn11b at dt = 0.0025). Every number here is a count or an
error, not a time, so it does not depend on the machine's load:

1. Force evaluations to a state error of 1e-6 for each fixed-step method (dt from a sweep,
   log-log interpolated, then checked) and for scipy's DOP853 (rtol likewise; its nfev).
2. The error budget of srkn11b at that dt: the share of the error at the carrier's bin (theta
   at k) and at U's second harmonic (2k); the same dt without U (case I) and at a tenth of
   the amplitude (relative error). How much of the error a device aimed at one part (the
   stiff U mode at 2k, the nonlinearity) could remove; at order 6 removing a share s of
   the error lengthens the step by only (1 / (1 - s))^(1/6).
3. The bound: with the force at its stencil-only floor (``speed.py``'s "stencil only", the
   trig values given for free), how many force evaluations the goals allow, against the
   evaluations srkn11b and DOP853 need. Uses the ``speed`` section of the same results.json
   (its wall times were measured in one run); skipped when that section is missing.

    python -m bench.error_budget [--quick] [--update | --out DIR]
"""

from __future__ import annotations

import json

import numpy as np

from bench.simulator import arguments, machine, results_path, write_section
from bench.speed import (
    CASE,
    MAT,
    SWEEPS,
    TARGET,
    K,
    N,
    _interpolate,
    fixed_run,
    scipy_run,
    state_error,
)
from numerics import initial_condition
from numerics.lattice import get_method

GOALS = {"dop853 (numpy force)": 100.0, "dop853 (kernel force)": 15.0}


def _bin(k):
    q = 2 * np.pi * np.arange(N // 2 + 1) / N
    return int(np.argmin(np.abs(q - k)))


def evaluations_to_target(state, ref, T):
    out = {}
    for name in ("srkn6b", "srkn11b", "kahanli8"):
        errs = [state_error(st.th, st.U, ref)
                for st in (fixed_run(name, dt, state, T) for dt in SWEEPS[name])]
        dt, _ = _interpolate(SWEEPS[name], errs, TARGET)
        steps = int(np.ceil(T / dt - 1e-9))
        st = fixed_run(name, dt, state, T)
        out[name] = {"dt": dt, "error": state_error(st.th, st.U, ref),
                     "evaluations": steps * get_method(name).evaluations}
    rtols = [1e-7, 1e-8, 1e-9]
    errs = [state_error(*scipy_run(state, T, r, "kernel")[:2], ref) for r in rtols]
    rtol, _ = _interpolate(rtols, errs, TARGET)
    th, U, nfev = scipy_run(state, T, rtol, "kernel")
    out["dop853"] = {"rtol": rtol, "error": state_error(th, U, ref), "evaluations": int(nfev)}
    return out


def budget(dt, T, amplitude=None, case=CASE, state=None, ref=None):
    """srkn11b's error at ``dt``: total, and the shares at the carrier and at U's 2k
    (``state`` and its reference ``ref`` when already run, else made here)."""
    if state is None:
        kw = {} if amplitude is None else {"amplitude": amplitude}
        state = initial_condition(MAT, case, N, K, **kw)
        ref = fixed_run("srkn11b", 0.0025, state, T, case).state()
    st = fixed_run("srkn11b", dt, state, T, case)
    scale = np.max(np.abs(ref.theta))
    e_th = np.abs(np.fft.rfft(st.th - ref.theta)) * 2 / N / scale
    e_U = (np.abs(np.fft.rfft(st.U - ref.U)) * 2 / N / scale if case == "coupled"
           else np.zeros(N // 2 + 1))  # case I carries no U
    b1, b2 = _bin(K), _bin(2 * K)
    total = np.sqrt(np.sum(e_th**2) + np.sum(e_U**2))
    err = (state_error(st.th, st.U, ref) if case == "coupled"
           else float(np.max(np.abs(st.th - ref.theta)) / scale))
    return {"state_error": err,
            "theta_carrier_bin": float(e_th[b1]), "U_second_harmonic_bin": float(e_U[b2]),
            "share_at_theta_carrier": float(e_th[b1] ** 2 / total**2),
            "share_at_U_2k": float(e_U[b2] ** 2 / total**2)}


def bound(evals, quick, out):
    """Force evaluations the goals allow with the force at its stencil-only floor."""
    path = results_path(quick, out)
    speed = json.loads(path.read_text()).get("speed") if path.exists() else None
    if not speed or speed.get("quick") != quick:
        return None
    floor_s = speed["force"]["ns_per_site"]["stencil only"] * N * 1e-9
    runs = speed["time_to_1e-6"]["runs"]
    res = {"stencil_floor_s_per_evaluation": floor_s}
    for name, goal in GOALS.items():
        allowed = runs[name]["wall_s"] / goal / floor_s
        res[name] = {"goal": goal, "wall_s": runs[name]["wall_s"],
                     "evaluations_allowed_at_floor": allowed,
                     "srkn11b_evaluations_over_allowed":
                         evals["srkn11b"]["evaluations"] / allowed,
                     "dop853_evaluations_over_allowed":
                         evals["dop853"]["evaluations"] / allowed}
    return res


def main(quick=False, out=None):
    T = 50.0 if quick else 200.0
    state = initial_condition(MAT, CASE, N, K)
    ref = fixed_run("srkn11b", 0.0025, state, T).state()
    evals = evaluations_to_target(state, ref, T)
    dt = evals["srkn11b"]["dt"]
    res = {"machine": machine(), "quick": quick, "T": T, "target": TARGET,
           "evaluations_to_target": evals,
           "budget": {"coupled": budget(dt, T, state=state, ref=ref),
                      "rotation (no U)": budget(dt, T, case="rotation"),
                      "coupled, amplitude / 10": budget(dt, T, amplitude=0.002)},
           "bound": bound(evals, quick, out)}
    write_section("error_budget", res, quick, out)
    print(f"force evaluations to a state error of {TARGET:g} (blue II, N = {N}, T = {T:g}):")
    for name, r in evals.items():
        knob = f"dt = {r['dt']:.4g}" if "dt" in r else f"rtol = {r['rtol']:.3g}"
        print(f"  {name:<10} {knob:<16} error {r['error']:.2e}  {r['evaluations']:6d}")
    print(f"srkn11b's error at dt = {dt:.4g}:")
    for name, b in res["budget"].items():
        print(f"  {name:<24} state error {b['state_error']:.2e}; share at theta(k) "
              f"{b['share_at_theta_carrier']:.1%}, at U(2k) {b['share_at_U_2k']:.1%}")
    if res["bound"]:
        for name in GOALS:
            b = res["bound"][name]
            print(f"  {b['goal']:g}x {name}: at most {b['evaluations_allowed_at_floor']:.0f} "
                  f"evaluations with the force at its stencil floor; srkn11b needs "
                  f"{b['srkn11b_evaluations_over_allowed']:.2f}x that, DOP853 "
                  f"{b['dop853_evaluations_over_allowed']:.2f}x")
    return res


if __name__ == "__main__":
    main(*arguments(__doc__))
