"""Where numerical stability ends, and what the code does there. `make stress`.

Each check records what was measured and pass/fail; writes stress.json and stress.md (in
out/bench/, or the committed bench/ with --update; stress_quick.* with --quick). The fast
checks are also assertions in tests/test_bench.py.

    python -m bench.stress [--quick] [--update | --out DIR]
"""

from __future__ import annotations

import json
import math
import signal
import subprocess
import sys
import time
import warnings
from pathlib import Path

import numpy as np

from bench.simulator import arguments, output_dir
from common import paper
from common.files import write_text
from numerics import (
    AccuracyWarning,
    BlowUpError,
    LatticeState,
    Material,
    energy,
    integrate,
    simulate,
)
from numerics.lattice import get_method

ROOT = Path(__file__).resolve().parents[1]
BLUE, GREEN = Material.paper("blue"), Material.paper("green")


def random_state(N, case, amp=1e-3, seed=0):
    """Small random state: every lattice mode, including omega_max, is present."""
    rng = np.random.default_rng(seed)
    th, thd = amp * rng.standard_normal(N), amp * rng.standard_normal(N)
    if case == "coupled":
        Ud = amp * rng.standard_normal(N)
        # no net momentum: a uniform drift of U would grow without bound, unstable or not
        return LatticeState(amp * rng.standard_normal(N), Ud - Ud.mean(), th, thd)
    return LatticeState(None, None, th, thd)


def is_stable(method, dt, material, case, N=16, t_end=3000.0):
    """Bounded: the state stays finite and below 10x its initial size after t_end from a
    small random state. (RK4 damps the modes it resolves badly and symplectic methods
    conserve a modified energy far from E at large omega dt, so neither "accurate" nor
    "energy conserved" is the test; just above the limit the growth per step is
    ~(omega dt - limit), so a long run resolves the limit to ~1e-3.)"""
    st = random_state(N, case)
    size = lambda s: max(np.max(np.abs(s.theta)), 0 if s.U is None
                         else np.max(np.abs(s.U)))
    try:
        with warnings.catch_warnings():  # near the limit a run is inaccurate by design
            warnings.simplefilter("ignore", AccuracyWarning)
            end = integrate(st, material, case, t_end, dt, method)
    except BlowUpError:
        return False
    return bool(np.isfinite(size(end)) and size(end) < 10 * size(st))


def largest_stable_dt(method, material, case, rel=1e-3, **kw):
    """Bisection between a stable dt (0.5 x prediction) and an unstable one (2 x)."""
    pred = get_method(method).stability_limit() / material.omega_max(case)
    # composition methods have stable windows again beyond their first limit: bisect
    # within [0.8, 1.25] x the prediction, where the first crossing is
    lo, hi = 0.8 * pred, 1.25 * pred
    if not is_stable(method, lo, material, case, **kw) or is_stable(method, hi, material, case, **kw):
        return float("nan"), pred
    while hi - lo > rel * pred:
        mid = 0.5 * (lo + hi)
        if is_stable(method, mid, material, case, **kw):
            lo = mid
        else:
            hi = mid
    return lo, pred


def check(name, ok, **measured):
    return {"check": name, "pass": bool(ok), **measured}


def step_size_checks(quick):
    out = []
    methods = ["rk4"] if quick else ["rk4", "verlet"]
    for case, mat in (("coupled", BLUE), ("rotation", GREEN)):
        # the composition methods' first instability (the prediction) is a narrow window
        # of omega dt (srkn6b: [3.165, 3.169], then stable to 5.03); a lattice run only
        # meets it if one of its N frequencies falls inside: we record, not bisect
        for m in ("srkn6b", "srkn11b"):
            pred = get_method(m).stability_limit() / mat.omega_max(case)
            st = {f: is_stable(m, f * pred, mat, case, t_end=1000.0) for f in (0.95, 1.25)}
            out.append(check(f"{m}, case {case}: stable below its predicted first instability "
                             "(narrow window; stable again above it)", st[0.95],
                             predicted_dt=pred, stable_at_0_95=st[0.95], stable_at_1_25=st[1.25]))
        for m in methods:
            dt, pred = largest_stable_dt(m, mat, case, t_end=1000.0 if quick else 3000.0)
            out.append(check(f"largest stable dt, {m}, case {case}: bisection vs "
                             f"limit / omega_max (omega_max = {mat.omega_max(case):.4g})",
                             bool(abs(dt / pred - 1) < 0.05), measured_dt=dt, predicted_dt=pred,
                             ratio=dt / pred))
    return out


def amplitude_checks(quick):
    out = []
    epss = [0.01, 0.05, 0.2, 0.5] if quick else [0.01, 0.03, 0.1, 0.2, 0.35, 0.5]
    for eps in epss:
        amp = 2 * eps
        for case, mat, k in (("coupled", BLUE, paper.k("blue")), ("rotation", GREEN, paper.k("green"))):
            dt = 0.05 if amp < 0.5 else 0.02  # frequencies grow with amplitude
            try:
                run = simulate(mat, case, 128, 2 * np.pi * round(k * 128 / 2 / np.pi) / 128,
                               eps=eps, t_end=200.0 if quick else 1000.0, dt=dt,
                               store="energy", progress=False)
                err = float(run.relative_energy_error.max())
                finite = bool(np.all(np.isfinite(run.energy)))
                out.append(check(f"amplitude theta_max = {amp:.2f} rad, case {case}, dt = {dt}: "
                                 "energy conserved, no NaN", finite and err < 1e-3,
                                 energy_error=err))
            except BlowUpError as e:
                out.append(check(f"amplitude {amp:.2f} rad, case {case}: blow-up reported",
                                 True, message=str(e)[:200]))
    return out


def singular_checks():
    from generated import coefficients as co
    from generated import lattice_coefficients as la

    out = []
    # k at the continuum resonance k^2 = omega^2: u2 diverges, with a RuntimeWarning
    al, Ks, Kt = BLUE.alpha, BLUE.K_s, BLUE.K_theta
    ks = np.linspace(0.5, 1.2, 200001)
    kres = ks[np.argmin(np.abs(ks**2 - co.omega(ks, al, Ks, Kt) ** 2))]
    with warnings.catch_warnings(record=True):
        warnings.simplefilter("always")
        big = abs(co.u2_coefficient(kres, al, Ks, Kt))
    out.append(check("continuum u2 near k = omega diverges (|c| > 1e3)", big > 1e3,
                     k=float(kres), abs_u2=float(big)))
    with warnings.catch_warnings(record=True) as w:
        warnings.simplefilter("always")
        g = co.g_rotation(0.8, al, Ks, Ks)  # delta = 0
        la.g_rotation(0.8, al, Ks, Ks)
    out.append(check("delta = 0: g = g2/g1 is inf/nan with a RuntimeWarning, no exception",
                     (not np.isfinite(g)) and len(w) > 0, g=str(g), warnings=len(w)))
    # K_theta -> 0 and large alpha: the simulator runs (dt scaled by omega_max)
    for mat, label in ((Material(paper.ALPHA, paper.K_S, 1e-8), "K_theta = 1e-8"),
                       (Material(50.0, paper.K_S, BLUE.K_theta), "alpha = 50")):
        dt = 0.1 / mat.omega_max("coupled")  # omega_max dt = 0.1: RK4 error ~ 1e-7
        st = random_state(64, "coupled", 1e-3)
        E0 = energy(st, mat, "coupled")
        end = integrate(st, mat, "coupled", 100.0, dt)
        err = abs(energy(end, mat, "coupled") / E0 - 1)
        out.append(check(f"{label}: RK4 at omega_max dt = 0.1 conserves energy (1e-4)",
                         err < 1e-4, energy_error=float(err), dt=dt))
    return out


def long_run_check(quick):
    t_end = 1e4 if quick else 1e5
    run = simulate(GREEN, "rotation", 64, 2 * np.pi * 10 / 64, t_end=t_end, dt=0.05,
                   store="energy", save_every=t_end / 200, progress=False)
    e = run.relative_energy_error
    slope = float(np.polyfit(run.t, e, 1)[0])
    return [check(f"long run t_end = {t_end:g}, RK4 dt = 0.05, N = 64: energy drift recorded",
                  bool(np.all(np.isfinite(e))) and e.max() < 1e-3,
                  max_energy_error=float(e.max()), drift_per_unit_time=slope)]


def bad_input_checks():
    out = []
    cases = {
        "NaN in theta": lambda: LatticeState(None, None, np.array([0, np.nan, 0.0]), np.zeros(3)),
        "inf parameter": lambda: Material(np.inf, 0.01, 0.01),
        "negative K_theta": lambda: Material(2.5, 0.01, -0.1),
        "N = 2": lambda: simulate(BLUE, "coupled", 2, 0.8),
        "N = 1e9": lambda: simulate(BLUE, "coupled", 10**9, 0.8),
        "dt = -1": lambda: simulate(BLUE, "coupled", 64, 2 * np.pi * 8 / 64, dt=-1),
        "dt = nan": lambda: simulate(BLUE, "coupled", 64, 2 * np.pi * 8 / 64, dt=np.nan),
        "t_end = 1e30": lambda: simulate(BLUE, "coupled", 64, 2 * np.pi * 8 / 64, t_end=1e30),
        "k = 4": lambda: simulate(BLUE, "coupled", 64, 4.0),
    }
    for name, fn in cases.items():
        try:
            fn()
            out.append(check(f"bad input ({name}) raises ValueError", False, message="no error"))
        except ValueError as e:
            out.append(check(f"bad input ({name}) raises ValueError", True, message=str(e)[:160]))
    # blow-up: RK4 above its limit stops with the time and a safe dt in the message
    dt = 1.3 * 2 * math.sqrt(2) / BLUE.omega_max("coupled")
    try:
        simulate(BLUE, "coupled", 64, 2 * np.pi * 8 / 64, t_end=400.0, dt=dt,
                 initial=random_state(64, "coupled"), store="energy", progress=False)
        out.append(check("blow-up above the RK4 limit is reported", False))
    except BlowUpError as e:
        msg = str(e)
        out.append(check("blow-up above the RK4 limit: BlowUpError names the time and a "
                         "safe dt", "dt" in msg and "T =" in msg, message=msg[:240]))
    return out


SIGINT_SCRIPT = """
import sys, numpy as np
from numerics import Material, simulate, SimulationInterrupted
simulate(Material(2.5, 0.01851, 0.01551), "coupled", 16, 2*np.pi*2/16, t_end=1.0)  # compile
print("START", flush=True)
try:
    simulate(Material(2.5, 0.01851, 0.01551), "coupled", 2000, 2*np.pi*260/2000,
             t_end=1e6, dt=0.05, store="energy", save_every=10.0, progress=False)
except SimulationInterrupted as e:
    print("INTERRUPTED", len(e.run.t), e.run.t[-1], str(e)[:200])
    sys.exit(0)
"""


def sigint_check():
    p = subprocess.Popen([sys.executable, "-c", SIGINT_SCRIPT], cwd=ROOT,
                         stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    first = p.stdout.readline()  # "START": past import and compilation
    time.sleep(2.0)  # into the time loop
    p.send_signal(signal.SIGINT)
    try:
        out, err = p.communicate(timeout=60)
    except subprocess.TimeoutExpired:
        p.kill()
        out, err = p.communicate()
        return [check("SIGINT: the run stops", False, stdout=first + out, stderr=err[-300:])]
    ok = first.startswith("START") and out.startswith("INTERRUPTED") and int(out.split()[1]) > 1
    return [check("SIGINT: SimulationInterrupted keeps the records and says how to resume",
                  ok, stdout=out.strip()[:300], stderr=err.strip()[-300:])]


def fault_counts():
    """The fault catalogue (bench/faults.py): tried / clear error / worked / problems."""
    from bench import faults

    rows = faults.run_catalogue()
    counts = {k: sum(r[1] == k for r in rows) for k in ("clear error", "worked", "problem")}
    return {"tried": len(rows), **counts, "rows": rows}


def main(quick=False, out=None):
    t0 = time.perf_counter()
    checks = (step_size_checks(quick) + amplitude_checks(quick) + singular_checks()
              + long_run_check(quick) + bad_input_checks() + sigint_check())
    fc = fault_counts()
    res = {"quick": quick, "wall_s": time.perf_counter() - t0, "checks": checks,
           "passed": sum(c["pass"] for c in checks), "total": len(checks), "faults": fc}
    name = "stress_quick" if quick else "stress"
    out = output_dir(out=out)
    write_text(out / f"{name}.json", json.dumps(res, indent=1) + "\n")
    lines = [f"# Stress tests ({'quick' if quick else 'full'}): {res['passed']}/{res['total']} "
             f"pass, {res['wall_s']:.0f} s", "", "| check | result | measured |", "|---|---|---|"]
    for c in checks:
        meas = ", ".join(f"{k} = {v:.4g}" if isinstance(v, float) else f"{k} = {v}"
                         for k, v in c.items() if k not in ("check", "pass"))
        lines.append(f"| {c['check']} | {'pass' if c['pass'] else '**FAIL**'} | "
                     f"{meas.replace('|', '/')[:300]} |")
    lines += ["", "## Fault catalogue (bench/faults.py, bench/faults_maps.py, bench/faults_round3.py; "
              f"tests/test_faults.py adds the signal, file and CLI faults): {fc['tried']} tried, {fc['clear error']} clear errors, "
              f"{fc['worked']} worked, {fc['problem']} problems", "",
              "| fault | outcome | what happened |", "|---|---|---|"]
    for n, outcome, detail in fc["rows"]:
        shown = outcome if outcome != "problem" else "**problem**"
        lines.append(f"| {n} | {shown} | {detail.replace('|', '/')[:200]} |")
    write_text(out / f"{name}.md", "\n".join(lines) + "\n")
    print("\n".join(lines))
    return res


if __name__ == "__main__":
    main(*arguments(__doc__))
