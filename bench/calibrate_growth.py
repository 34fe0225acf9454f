"""Growth-factor error constants of the map cells (numerics/maps/_cells.py), measured, and
the check that cells run at the chosen step keep the tight reference's verdicts.

A map cell measures one number, the growth factor of the theta (and U) spectrum; its error
follows the same model as the state's (``numerics.lattice._accuracy``),
e = C_m (w dt)^p (w T), but with much smaller constants: the carrier's phase error, which
dominates the state error, does not change the spectrum's magnitudes.

- ``calibrate``: on CALIBRATION cells (both cases; deltas and k between those of the
  fig3-simulated grid, so that the check below runs on other cells), the growth curve
  (growth factor at every record up to the reference's early stop) at one probe step per
  method against the tight reference (srkn11b, dt = REFERENCE_DT); C_m = the largest
  relative curve error over (w dt)^p (w T). GROWTH_ERROR_CONSTANTS keeps these maxima.
- ``check_grid``: the full fig3-simulated grid (both cases, N = 500, T = 5000): every cell
  at the map's step (``MapParameters.cell_step``, what ``run_map`` runs: method and step
  from GROWTH_TOL at the grid's fastest carrier) against the tight reference: verdict changes, the largest relative growth-curve error (to compare with
  GROWTH_TOL), and the cost per cell of both.

    python -m bench.calibrate_growth            # the constants (a few minutes)
"""

from __future__ import annotations

import time
from concurrent.futures import ProcessPoolExecutor

import numpy as np

from common import paper
from numerics import Material, get_method, initial_condition
from numerics.lattice import dominant_frequency
from numerics.maps import GROWTH_ERROR_CONSTANTS, GROWTH_TOL, cell_records, growth_of

#: the tight reference: srkn11b at this step (its own growth error ~1e-9: the constants
#: below at dt = 0.1)
REFERENCE_DT = 0.1
#: one probe step per method (errors 1e-5 .. 1e-2, well above the reference's)
PROBES = {"srkn11b": 1.6, "srkn6b": 0.4, "kahanli8": 1.0}


def calibration_cells():
    """Both cases on a 4 x 4 grid between the fig3-simulated grid's deltas and k."""
    delta = np.linspace(-0.0105, 0.0105, 4)
    m = np.round(np.linspace(0.12, 0.88, 4) * 250).astype(int) + 3
    ks = 2 * np.pi * m / paper.N
    return [(case, float(d), float(k)) for case in ("rotation", "coupled") for d in delta
            for k in ks]


def _curve(rec, n, t_end):
    U = rec["U_hat"]
    return np.array([growth_of(rec["t"][:j + 1], rec["theta_hat"][:j + 1],
                               None if U is None else U[:j + 1], rec["m"], paper.N,
                               t_end)["growth"] for j in range(1, n)])


def _material(delta):
    return Material(paper.ALPHA, paper.K_S, paper.K_S - delta)


def _reference(case, delta, k, t_end):
    t0 = time.perf_counter()
    ref = cell_records(_material(delta), case, k, paper.N, t_end, paper.AMPLITUDE,
                       dt=REFERENCE_DT, method="srkn11b")
    return ref, time.perf_counter() - t0


def _calibrate_cell(cell):
    case, delta, k = cell
    t_end = paper.T_END
    mat = _material(delta)
    w = dominant_frequency(initial_condition(mat, case, paper.N, k, paper.AMPLITUDE))
    ref, _ = _reference(case, delta, k, t_end)
    n = len(ref["t"])
    g_ref = _curve(ref, n, t_end)
    out = {"case": case, "delta": delta, "k": k, "w": w, "records": n,
           "growth": float(g_ref[-1]), "C": {}}
    for name, dt in PROBES.items():
        rec = cell_records(mat, case, k, paper.N, t_end, paper.AMPLITUDE, dt=dt,
                           method=name, early_stop=False, stop_at=n - 1)
        err = float(np.max(np.abs(_curve(rec, n, t_end) - g_ref) / g_ref))
        out["C"][name] = err / ((w * rec["dt"]) ** get_method(name).order * w * t_end)
    return out


def _check_cell(cell):
    case, delta, k, t_end, method, dt = cell
    mat = _material(delta)
    ref, t_ref = _reference(case, delta, k, t_end)
    t0 = time.perf_counter()
    rec = cell_records(mat, case, k, paper.N, t_end, paper.AMPLITUDE, dt=dt, method=method)
    t_cell = time.perf_counter() - t0
    n = min(len(ref["t"]), len(rec["t"]))
    g_ref, g = _curve(ref, len(ref["t"]), t_end), _curve(rec, len(rec["t"]), t_end)
    from numerics.lattice import GROWTH_THRESHOLD
    return {"case": case, "delta": delta, "k": k,
            "verdict_reference": bool(g_ref.max() > GROWTH_THRESHOLD),
            "verdict": bool(g.max() > GROWTH_THRESHOLD),
            "growth_reference": float(g_ref[-1]), "growth": float(g[-1]),
            "curve_error": float(np.max(np.abs(g[:n - 1] - g_ref[:n - 1]) / g_ref[:n - 1])),
            "method": rec["method"], "dt": rec["dt"], "s_reference": t_ref, "s": t_cell}


def _pool_map(fn, items, workers):
    if workers <= 1:
        return [fn(x) for x in items]
    with ProcessPoolExecutor(workers) as pool:
        return list(pool.map(fn, items))


def calibrate(workers=2):
    rows = _pool_map(_calibrate_cell, calibration_cells(), workers)
    worst = {name: max(r["C"][name] for r in rows) for name in PROBES}
    return {"cells": rows, "largest_C": worst}


def check_grid(quick=False, workers=2):
    """Every cell of the fig3-simulated grid (full unless ``quick``) at the map's step (what
    ``run_map`` runs: ``MapParameters.cell_step``) against the tight reference."""
    from numerics.maps import MapParameters
    from scenes.fig3_simulated import grid

    ks, deltas, g = grid(quick)
    if quick:  # the quick grid's N = 100 is not the cells' calibrated setting: keep N 500
        ks = 2 * np.pi * np.round(ks * paper.N / (2 * np.pi)) / paper.N
    t_end = g["t_end"]
    steps = {case: MapParameters(case=case, alpha=paper.ALPHA, K_s=paper.K_S,
                                 delta=tuple(float(d) for d in deltas),
                                 k=tuple(float(k) for k in ks), amplitude=paper.AMPLITUDE,
                                 N=paper.N, t_end=t_end).cell_step
             for case in ("rotation", "coupled")}
    cells = [(case, float(d), float(k), t_end, *steps[case])
             for case in ("rotation", "coupled") for d in deltas for k in ks]
    rows = _pool_map(_check_cell, cells, workers)
    out = {"cells": len(rows), "t_end": t_end, "N": paper.N, "growth_tol": GROWTH_TOL,
           "reference": f"srkn11b dt = {REFERENCE_DT}"}
    for case in ("rotation", "coupled"):
        rs = [r for r in rows if r["case"] == case]
        out[case] = {
            "cells": len(rs), "mi_cells": sum(r["verdict_reference"] for r in rs),
            "verdict_changes": sum(r["verdict"] != r["verdict_reference"] for r in rs),
            "largest_growth_curve_error": max(r["curve_error"] for r in rs),
            "method": sorted({r["method"] for r in rs}),
            "dt_range": [min(r["dt"] for r in rs), max(r["dt"] for r in rs)],
            "s_per_cell": float(np.mean([r["s"] for r in rs])),
            "s_per_cell_reference": float(np.mean([r["s_reference"] for r in rs]))}
    return out


def main():
    res = calibrate()
    for r in res["cells"]:
        print(f"{r['case']:8} delta = {r['delta']:+.4f} k = {r['k']:.3f} w = {r['w']:.3f} "
              f"records {r['records']:3d} growth {r['growth']:7.3g}  " + "  ".join(
                  f"{n} C = {c:.2g}" for n, c in r["C"].items()))
    print("largest C_m:", {n: float(f"{c:.2g}") for n, c in res["largest_C"].items()})
    print("numerics.maps._cells.GROWTH_ERROR_CONSTANTS:", GROWTH_ERROR_CONSTANTS)


if __name__ == "__main__":
    main()
