"""Work-precision of every integrator, scaling with N, derivation and import cost.

Measured in one run; ratios are what to read. Writes its sections of results.json and
work_precision.png, long_time.png (in out/bench/, or the committed bench/ with --update);
bench/README.md says how to read them.

    python -m bench.work_precision [--quick] [--update | --out DIR]
"""

from __future__ import annotations

import json
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np
from matplotlib.ticker import FuncFormatter, LogLocator, NullFormatter

from bench.simulator import arguments, machine, output_dir, write_sections
from common import paper
from numerics import Material, energy, initial_condition, integrate
from numerics.lattice import Stepper, get_method, numpy_rk4

ROOT = Path(__file__).resolve().parents[1]
CASES = {"blue-II": (Material.paper("blue"), "coupled", paper.k("blue")),
         "green-I": (Material.paper("green"), "rotation", paper.k("green"))}
SWEEP = {"rk4": [0.4, 0.2, 0.1, 0.05, 0.025], "verlet": [0.2, 0.1, 0.05, 0.025, 0.0125],
         "srkn6b": [0.8, 0.4, 0.2, 0.1, 0.05], "srkn11b": [0.8, 0.4, 0.2, 0.1],
         "dop853": [1e-5, 1e-7, 1e-9, 1e-11], "rk45": [1e-5, 1e-7, 1e-9],
         "numpy-rk4": [0.2, 0.1, 0.05]}
QUICK_SWEEP = {"rk4": [0.2, 0.1], "srkn11b": [0.4, 0.2], "dop853": [1e-6, 1e-8],
               "numpy-rk4": [0.2]}


def run_method(name, param, state, mat, case, t_end):
    """(final state, wall s, force evaluations) of one method at one dt or rtol."""
    if name == "numpy-rk4":
        t0 = time.perf_counter()
        out = numpy_rk4(state, mat, case, t_end, param)
        return out, time.perf_counter() - t0, 4 * int(np.ceil(t_end / param))
    m = get_method(name)
    if m.fixed_step:
        nsteps = int(np.ceil(t_end / param))
        st = Stepper(state, mat, case, m, t_end / nsteps, 1e-10, 1e-12)
    else:
        nsteps = 1
        st = Stepper(state, mat, case, m, t_end, param, param * 1e-3)
    t0 = time.perf_counter()
    st.advance(nsteps)
    wall = time.perf_counter() - t0
    return st.state(), wall, int(st.evaluations)


def state_error(a, b):
    """Max abs difference of theta and U over max |theta| of the reference."""
    err = np.max(np.abs(a.theta - b.theta))
    if a.U is not None:
        err = max(err, np.max(np.abs(a.U - b.U)))
    return float(err / np.max(np.abs(b.theta)))


def separation_rate(mat, case, k, t_probe=1000.0):
    """Growth rate of the distance between two runs 1e-9 apart (to pick t_end)."""
    s0 = initial_condition(mat, case, 500, k)
    s1 = initial_condition(mat, case, 500, k)
    th = s1.theta.copy()
    th[::7] += 1e-9
    s1 = type(s1)(s1.U, s1.U_dot, th, s1.theta_dot)
    ts, ds = [], []
    a, b = s0, s1
    for t in np.arange(100.0, t_probe + 1, 100.0):
        a = integrate(a, mat, case, 100.0, 0.05, "srkn11b")
        b = integrate(b, mat, case, 100.0, 0.05, "srkn11b")
        ts.append(t)
        ds.append(np.max(np.abs(a.theta - b.theta)))
    rate = float(np.polyfit(ts, np.log(ds), 1)[0])
    return rate, ts, [float(d) for d in ds]


def work_precision(quick):
    sweep = QUICK_SWEEP if quick else SWEEP
    out = {}
    for label, (mat, case, k) in CASES.items():
        if quick and label == "green-I":
            continue
        rate, ts, ds = separation_rate(mat, case, k, 300.0 if quick else 1000.0)
        # keep the instability's amplification of errors below 2x over the run
        t_end = float(min(500.0, np.log(2.0) / max(rate, 1e-6))) if not quick else 50.0
        state = initial_condition(mat, case, 500, k)
        ref, t_ref, _ = run_method("srkn11b", 0.01, state, mat, case, t_end)
        check, _, _ = run_method("dop853", 1e-13, state, mat, case, t_end)
        ref_err = state_error(check, ref)
        E0 = energy(state, mat, case)
        rows = []
        for name, params in sweep.items():
            if name != "numpy-rk4":
                run_method(name, params[0], state, mat, case, 1.0)  # compile / warm up
            for p in params:
                fin, wall, nev = run_method(name, p, state, mat, case, t_end)
                rows.append({"method": name, "dt_or_rtol": p, "wall_s": wall,
                             "force_evaluations": nev, "state_error": state_error(fin, ref),
                             "energy_error_end": abs(energy(fin, mat, case) / E0 - 1)})
        out[label] = {"t_end": t_end, "separation_rate": rate, "separation_t": ts,
                      "separation_distance": ds, "reference": "srkn11b dt = 0.01",
                      "reference_checked_by": "dop853 rtol = 1e-13",
                      "reference_difference": ref_err, "reference_wall_s": t_ref,
                      "rows": rows}
    return out


def time_to_error(rows, method, target=1e-6):
    """Wall time at state error = target, log-log interpolated (None if not bracketed)."""
    r = sorted((x for x in rows if x["method"] == method), key=lambda x: x["state_error"])
    for lo, hi in zip(r, r[1:]):
        if lo["state_error"] <= target <= hi["state_error"]:
            f = np.log(target / hi["state_error"]) / np.log(lo["state_error"] / hi["state_error"])
            return float(np.exp(np.log(hi["wall_s"]) + f * np.log(lo["wall_s"] / hi["wall_s"])))
    return None


def scaling(quick):
    mat, case, k = CASES["blue-II"]
    Ns = [64, 256, 1024, 4096] if quick else [64, 256, 1024, 4096, 16384, 100000]
    res = []
    for N in Ns:
        st = initial_condition(mat, case, N, 2 * np.pi * round(k * N / (2 * np.pi)) / N)
        steps = max(20, int(2e6 / N)) if not quick else max(10, int(2e5 / N))
        integrate(st, mat, case, 0.05 * 2, 0.05)
        t0 = time.perf_counter()
        integrate(st, mat, case, 0.05 * steps, 0.05)
        res.append({"N": N, "s_per_step": (time.perf_counter() - t0) / steps})
    for r in res:
        r["ns_per_site_per_step"] = r["s_per_step"] / r["N"] * 1e9
    # batching: many independent runs (e.g. seeds) as one long periodic chain is wrong
    # physics; we batch by running them back to back in one process (no re-compilation)
    runs = 8 if not quick else 2
    st = initial_condition(mat, case, 500, k)
    t0 = time.perf_counter()
    for s in range(runs):
        integrate(initial_condition(mat, case, 500, k, seed=s), mat, case, 50.0, 0.05)
    per_run = (time.perf_counter() - t0) / runs
    return {"per_N": res, "batched_runs": runs, "s_per_run_T50": per_run}


def long_time(quick):
    """Energy error over t_end = 1e5 at the paper's dt: RK4's drift vs symplectic bounds."""
    from numerics import simulate

    mat, case, k = CASES["green-I"]
    t_end = 2e3 if quick else 1e5
    out = {}
    for m in ("rk4", "verlet", "srkn6b"):
        t0 = time.perf_counter()
        run = simulate(mat, case, 500, k, t_end=t_end, dt=0.05, method=m, store="energy",
                       save_every=t_end / 200, progress=False)
        e = (run.energy - run.energy[0]) / run.energy[0]
        out[m] = {"wall_s": time.perf_counter() - t0, "t": run.t.tolist(),
                  "relative_energy_error": e.tolist(), "max_abs_error": float(np.abs(e).max()),
                  "drift_slope_per_T": float(np.polyfit(run.t, e, 1)[0])}
    return {"t_end": t_end, "dt": 0.05, "case": "green-I, N = 500, paper IC", "methods": out}


def derivation_cost(quick):
    t0 = time.perf_counter()
    if not quick:
        with tempfile.TemporaryDirectory() as tmp:
            subprocess.run([sys.executable, "-m", "derivation", "--out", tmp], check=True,
                           cwd=ROOT, capture_output=True)
    derive = time.perf_counter() - t0 if not quick else None
    code = ("import time, numpy; t = time.perf_counter(); import generated.coefficients, "
            "generated.lattice_coefficients; print(time.perf_counter() - t)")
    imp = float(subprocess.run([sys.executable, "-c", code], check=True, cwd=ROOT,
                               capture_output=True, text=True).stdout)
    return {"make_derive_s": derive, "import_generated_s": imp}


def plot(wp, path):
    """Work-precision diagrams: state error against wall time and force evaluations."""
    fig, axes = plt.subplots(len(wp), 2, figsize=(12.5, 4 * len(wp)), squeeze=False,
                             layout="constrained")
    for row, (label, d) in zip(axes, wp.items()):
        for name in dict.fromkeys(r["method"] for r in d["rows"]):
            rs = [r for r in d["rows"] if r["method"] == name]
            e = [max(r["state_error"], 1e-16) for r in rs]
            row[0].loglog([r["wall_s"] for r in rs], e, "o-", label=name)
            row[1].loglog([r["force_evaluations"] for r in rs], e, "o-", label=name)
        for ax, xl in zip(row, ("wall time (s)", "force evaluations (1)")):
            ax.set_xlabel(xl)
            ax.set_ylabel(r"state error at $t_{end}$ (relative, 1)")
            ax.axhline(1e-6, color="gray", lw=0.5, label=r"$10^{-6}$ (headline target)")
            ax.xaxis.set_minor_formatter(NullFormatter())  # minor labels collide on log x
            ax.set_title(fr"{label}, $N = 500$, $t_{{end}} = {d['t_end']:.0f}$ T "
                         "(measured)", fontsize=10)
        # force evaluations span under two decades: label 1-2-5 steps in plain numbers
        row[1].xaxis.set_major_locator(LogLocator(subs=(1.0, 2.0, 5.0)))
        row[1].xaxis.set_major_formatter(FuncFormatter(lambda v, _: f"{v:.0f}"))
    fig.legend(*axes[0, 0].get_legend_handles_labels(), loc="outside right center", fontsize=9)
    fig.savefig(path, dpi=100)
    plt.close(fig)


def plot_long_time(long_run, path):
    """Relative energy error over a long run, per method (log scale)."""
    fig, ax = plt.subplots(figsize=(6, 4), layout="constrained")
    for m, d in long_run["methods"].items():
        ax.plot(d["t"], np.abs(d["relative_energy_error"]), label=m)
    ax.set_yscale("log")
    ax.set_xlabel(r"$T$ (lattice units)")
    ax.set_ylabel(r"$|E(T)/E(0) - 1|$ (1)")
    ax.set_title(r"long run (measured), green point, case I, $N = 500$, $dt = 0.05$",
                 fontsize=9)
    ax.legend()
    fig.savefig(path, dpi=100)
    plt.close(fig)


def main(quick=False, out=None):
    out = output_dir(out=out)
    t_all = time.perf_counter()
    wp = work_precision(quick)
    head = {}
    for label, d in wp.items():
        ours = {m: time_to_error(d["rows"], m) for m in ("rk4", "verlet", "srkn6b", "srkn11b")}
        theirs = {m: time_to_error(d["rows"], m) for m in ("dop853", "rk45")}
        ok_o = {m: t for m, t in ours.items() if t}
        ok_t = {m: t for m, t in theirs.items() if t}
        if ok_o and ok_t:
            bo, bt = min(ok_o, key=ok_o.get), min(ok_t, key=ok_t.get)
            head[label] = {"best_ours": bo, "best_scipy": bt, "t_ours_s": ok_o[bo],
                           "t_scipy_s": ok_t[bt], "speedup_at_1e-6": ok_t[bt] / ok_o[bo],
                           "time_to_1e-6_s": {**ours, **theirs}}
    res = {"machine": machine(), "quick": quick, "work_precision": wp,
           "headline_time_to_1e-6": head, "scaling": scaling(quick),
           "derivation": derivation_cost(quick), "long_time": long_time(quick),
           "units": {"wall_s": "s", "state_error": "max |x - x_ref| / max |theta_ref|",
                     "energy_error_end": "|E(t_end)/E(0) - 1|", "separation_rate": "1/T",
                     "s_per_step": "s", "ns_per_site_per_step": "ns"}}
    sim = out / ("simulator_quick.json" if quick else "simulator.json")  # this run's
    if sim.exists():
        res["simulator"] = json.loads(sim.read_text())
    res["bench_wall_s"] = time.perf_counter() - t_all
    write_sections(res, quick, out)  # top-level sections, beside speed/maps/exact_maps
    if not quick:
        plot(wp, out / "work_precision.png")
        plot_long_time(res["long_time"], out / "long_time.png")
    for label, h in head.items():
        print(f"{label}: time to state error 1e-6: {h['best_ours']} {h['t_ours_s']:.3g} s, "
              f"{h['best_scipy']} {h['t_scipy_s']:.3g} s -> {h['speedup_at_1e-6']:.1f}x")
    for label, d in wp.items():
        print(f"{label}: t_end = {d['t_end']:.0f} (separation rate {d['separation_rate']:.2e}), "
              f"reference checked to {d['reference_difference']:.1e}")
    print("scaling ns/site/step: " + ", ".join(
        f"N={r['N']}: {r['ns_per_site_per_step']:.0f}" for r in res["scaling"]["per_N"]))
    print(f"derive {res['derivation']['make_derive_s']}, import "
          f"{res['derivation']['import_generated_s']:.4f} s")
    for m, d in res["long_time"]["methods"].items():
        print(f"long run {m}: max energy error {d['max_abs_error']:.2e}, drift slope "
              f"{d['drift_slope_per_T']:.2e}/T, {d['wall_s']:.1f} s")
    return res


if __name__ == "__main__":
    main(*arguments(__doc__))
