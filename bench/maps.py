"""Maps on Dask, measured: cells per second per core, 1 -> 2 workers, worker layouts,
scheduling overhead, the 64 x 64 map's wall time, and the cells' accuracy.

- A cell is the paper's run (N = 500, T = 5000, paper IC, one seed) with the map's early
  stop, at the map's default step (``numerics.maps._cells.map_step``: method and dt for a
  1% growth-factor error) and, for the ratio, at the paper's RK4 dt = 0.05; measured
  serially (no Dask) on a row of stable and unstable cells of case II; beside it the cost
  of the cell's prediction (``predict_cell``), which ``run_map`` adds.
- The same 64-cell map (4 x 16 around the blue point, case II, block = 1, predictions
  included; 4 x 8 with --quick) on a LocalCluster of 1 and of 2 worker processes, and of 1
  worker with 2 threads (the compiled loops release the GIL): the speed-up of each layout,
  clusters warmed up first; over ``run_map``'s whole call and over its task phase (the
  store's opening, checksums and final load, ~1 s, do not use the workers).
- Scheduling overhead: no-op tasks through the same cluster against the cost of a task.
- The 64 x 64 map (fig3 plane: alpha = 2.5, delta in [-0.012, 0.012], k in [0.08, 0.92] pi,
  case II): its cells simulated in blocks of 4 on this machine's default cluster, measured
  wall time (full run only; --quick estimates it from the per-cell cost); and the same map
  through ``run_map`` as a user runs it (cluster start-up, every cell also predicted).
- The cells' accuracy (``bench.calibrate_growth.check_grid``): the full fig3-simulated
  grid, both cases, at the default step against a tight reference (srkn11b, dt = 0.1):
  verdict changes and the largest growth-factor error (full run only).
Writes the "maps" section of results.json (results_quick.json with --quick; in out/bench/,
or bench/ with --update). Reports the load average: the machine is shared.

- Issue 40's table: the same 3 x 3 map of case II (N 128, amplitude 0.1, T 2000, exact
  wave start, one worker) as `flexmm map` with the paper flags and with `--model flexmm`:
  wall and CPU time of each command (its worker processes included), and their ratio; a
  model map's task phase on 2 workers against 1 (2 x 8 flexmm cells; 2 x 4, T 500 with
  --quick); the 32 x 32 simulated fput map (N 128, T 2000, one seed) with its cells per
  second (``--model-row --fput-32`` only: minutes).

- Issue 44's estimates: commands of the paper chain (simulated, theory-only, the paper
  start's exact predictions) and of models (maps theory-only, with --exact, simulated; a
  point --simulate), each a fresh process: the estimate it prints before the work against
  the wall time it estimates, and their ratio (asked: within 2x both ways). --quick: the
  2 x 2 theory-only fput map only.

    python -m bench.maps [--quick] [--update | --out DIR]
    python -m bench.maps --model-row [--quick] [--fput-32 [--update]]
        (issue 40's rows alone, printed: the table, the model map on 2 workers against 1;
        the 32 x 32 fput map with --fput-32, written into bench/results.json with --update)
    python -m bench.maps --workers-row [--quick] [--update]
        (the model map on 2 workers against 1 alone, into results.json with --update)
    python -m bench.maps --estimates [--quick]   (issue 44's estimate rows, printed)
"""

from __future__ import annotations

import os
import shutil
import statistics
import tempfile
import time
from pathlib import Path

import numpy as np

from bench.model_maps import (  # issue 40's rows (their own module)
    fput_map_32,
    model_map_layouts,
    model_vs_paper_map,
    print_fput_32,
    print_model_layouts,
    print_model_row,
)
from bench.simulator import arguments, machine, write_section
from common import paper
from numerics import Material, maps


def _noop(x):
    return x


def _params(N, T, n_k=4, **kw):
    # distinct carriers of the ring (at the quick N = 100 fewer than n_k exist)
    kk = 2 * np.pi * np.unique(np.round(np.linspace(0.7, 1.0, n_k) * N / (2 * np.pi))) / N
    return maps.MapParameters(case="coupled", alpha=paper.ALPHA, K_s=paper.K_S,
                              delta=(-0.006, -0.002, 0.002, 0.006), k=tuple(kk),
                              amplitude=paper.AMPLITUDE, N=N, t_end=T, block=1, **kw)


def _simulate_cells(params, i, js):
    """The simulation part of ``simulate_block`` alone (its prediction is timed apart)."""
    from numerics.maps import simulate_cell

    mat = Material(params.alpha, params.K_s, params.K_s - params.delta[i])
    method, dt = params.cell_step
    return [simulate_cell(mat, params.case, params.k_simulated[j], params.N, params.t_end,
                          params.amplitude, params.noise, 0, params.start, dt, method)
            for j in js]


def cell_costs(params, paper_params):
    """Serial cost of the first row's cells: simulated at the default step and at RK4
    dt = 0.05, and the prediction ``simulate_block`` adds to each cell."""
    import dataclasses

    from numerics.maps import predict_cell

    for p in (params, paper_params):  # compile (or load) the kernels outside the timing
        _simulate_cells(dataclasses.replace(p, t_end=300.0, k=p.k[:1]), 0, [0])
    mat = Material(params.alpha, params.K_s, params.K_s - params.delta[0])
    rows = []
    for j, k in enumerate(params.k_simulated):
        row = {"k": float(k), "delta": params.delta[0]}
        for label, p in (("default", params), ("rk4 dt = 0.05", paper_params)):
            t0 = time.perf_counter()
            r = _simulate_cells(p, 0, [j])[0]
            row[label] = {"s": time.perf_counter() - t0, "mi": r["verdict_simulated"],
                          "growth": r["growth"], "t_simulated": r["t_simulated"]}
        t0 = time.perf_counter()
        predict_cell(mat, params.case, k, params.N, params.t_end, params.amplitude)
        row["prediction_s"] = time.perf_counter() - t0
        rows.append(row)
    return rows


def layout_walls(params):
    """Wall time of the layouts' map per cluster layout (fresh stores, warmed clusters), and
    of its task phase."""
    import dask
    from dask.distributed import Client, LocalCluster

    layouts = {"1 process": dict(n_workers=1, threads_per_worker=1, processes=True),
               "2 processes": dict(n_workers=2, threads_per_worker=1, processes=True),
               "1 process, 2 threads": dict(n_workers=1, threads_per_worker=2,
                                             processes=True)}
    tiny = maps.MapParameters(case="coupled", alpha=paper.ALPHA, K_s=paper.K_S,
                              delta=(0.003,), k=(2 * np.pi * 13 / 100,), amplitude=0.02,
                              N=100, t_end=300.0)
    walls, tasks = {}, {}
    for name, kw in layouts.items():
        d = Path(tempfile.mkdtemp())
        try:
            maps.open_or_create(d / "map.zarr", params)  # theory columns outside the timing
            # the settings of run_map's own cluster (maps.LOCAL_CLUSTER_CONFIG)
            with dask.config.set(maps.LOCAL_CLUSTER_CONFIG), \
                    LocalCluster(dashboard_address=":0", silence_logs=40, **kw) as cluster, \
                    Client(cluster) as client:
                client.gather([client.submit(maps.simulate_block, tiny, 0, [0], pure=False)
                               for _ in range(2)])  # load the compiled kernels
                said = []
                t0 = time.perf_counter()
                maps.run_map(params, d, scheduler=cluster.scheduler_address, progress=False,
                             log=said.append)
                walls[name] = time.perf_counter() - t0
                # the task phase alone (run_map's own log: "simulated n cells in x s"): the
                # store's opening, checksums and final load (~1 s) do not use the workers
                tasks[name] = float(said[-1].rsplit(" in ", 1)[1].split()[0])
        finally:
            shutil.rmtree(d, ignore_errors=True)
    return walls, tasks


def scheduling_overhead():
    from dask.distributed import Client, LocalCluster

    with LocalCluster(n_workers=2, threads_per_worker=1, dashboard_address=":0",
                      silence_logs=40) as cluster, Client(cluster) as client:
        client.gather(client.map(_noop, range(10)))  # warm up
        n = 200
        t0 = time.perf_counter()
        client.gather([client.submit(_noop, i, pure=False) for i in range(n)])
        return (time.perf_counter() - t0) / n


def map_64(N, T):
    """The 64 x 64 map of the fig3 plane, case II: its cells simulated (one task per
    block of 4, as run_map) on this machine's default cluster, wall time. The predictions
    ``run_map`` adds per cell are timed apart (``cell_costs``)."""
    from dask.distributed import Client

    m = np.unique(np.round(np.linspace(0.08, 0.92, 64) * N / 2).astype(int))
    params = maps.MapParameters(case="coupled", alpha=paper.ALPHA, K_s=paper.K_S,
                                delta=tuple(np.linspace(-0.012, 0.012, 64)),
                                k=tuple(2 * np.pi * m / N), amplitude=paper.AMPLITUDE,
                                N=N, t_end=T)
    params.cell_step  # chosen once, in the client (as run_map does)
    todo = maps._store.blocks(params, np.zeros((len(params.delta), len(params.k)), bool))
    with maps.local_cluster(maps.local_cores()) as cluster, Client(cluster) as client:
        client.gather([client.submit(_simulate_cells, params, 0, [0], pure=False)
                       for _ in range(2)])  # load the compiled kernels
        t0 = time.perf_counter()
        rows = [r for rs in client.gather([client.submit(_simulate_cells, params, i, js,
                                                         retries=2, pure=False)
                                           for i, js in todo]) for r in rs]
        wall = time.perf_counter() - t0
    return {"cells": len(rows), "wall_s": wall, "workers": maps.local_cores(),
            "method": params.cell_step[0], "dt": params.cell_step[1],
            "mi_cells": int(sum(r["verdict_simulated"] for r in rows)),
            "stopped_early_cells": int(sum(r["stopped_early"] for r in rows))}


def map_64_run_map(N, T):
    """The same 64 x 64 map as a user runs it: ``run_map`` into a fresh store, its cluster
    started by it (start-up included), every cell simulated and predicted, wall time."""
    m = np.unique(np.round(np.linspace(0.08, 0.92, 64) * N / 2).astype(int))
    params = maps.MapParameters(case="coupled", alpha=paper.ALPHA, K_s=paper.K_S,
                                delta=tuple(np.linspace(-0.012, 0.012, 64)),
                                k=tuple(2 * np.pi * m / N), amplitude=paper.AMPLITUDE,
                                N=N, t_end=T)
    d = Path(tempfile.mkdtemp())
    try:
        t0 = time.perf_counter()
        ds = maps.run_map(params, d, progress=False, log=lambda *_: None)
        wall = time.perf_counter() - t0
        agree = maps.agreement(ds)
    finally:
        shutil.rmtree(d, ignore_errors=True)
    return {"cells": int(ds["verdict_simulated"].size), "wall_s": wall,
            "workers": maps.local_cores(),
            "predicted_agreement": agree.get("predicted"),
            "predicted_undetermined_cells": agree.get("predicted_undetermined_cells")}


_PAPER = ["--alpha", "2.5", "--K-s", "0.01851", "--case", "coupled"]
_FPUT = ["--model", "fput", "--param", "alpha=1"]
#: issue 44 items 1-2: commands whose estimate line is checked against their wall time
#: (name -> (argv, in the quick run))
ESTIMATE_ROWS = {
    "paper, simulated 3 x 3, travelling, N 128, T 2000, 1 worker": (_PAPER + [
        "--K-theta", "0.012,0.016,0.020", "--k", "0.6,0.9,1.2", "--start", "travelling",
        "--N", "128", "--amplitude", "0.1", "--t-end", "2000", "--workers", "1"], False),
    "paper, theory-only 3 x 6, paper start (exact predictions), N 500": (_PAPER + [
        "--delta", "-0.003,0,0.003", "--k", "0.5:1.5:6", "--amplitude", "0.02",
        "--theory-only"], False),
    "paper, simulated 2 x 4, paper start, N 500, T 1000": (_PAPER + [
        "--delta", "-0.003,0.003", "--k", "0.5,0.8,1.1,1.4", "--amplitude", "0.02",
        "--t-end", "1000"], False),
    "paper, theory-only 4 x 8, travelling, N 256": (_PAPER + [
        "--delta", "-0.003:0.003:4", "--k", "0.3:2.5:8", "--start", "travelling", "--N",
        "256", "--amplitude", "0.05", "--theory-only"], False),
    "model fput, theory-only 2 x 2": (_FPUT + [
        "--param", "beta=0.8,1.6", "--k", "2.6,2.8", "--amplitude", "0.1", "--theory-only",
        "--workers", "1"], True),
    "model fput, theory-only --exact 4 x 8, N 128": (_FPUT + [
        "--param", "beta=0.5:2:4", "--k", "0.3:3.0:8", "--amplitude", "0.1", "--theory-only",
        "--exact", "--N", "128"], False),
    "model flexmm, simulated 3 x 3, N 128, T 2000, 1 worker": ([
        "--model", "flexmm", "--param", "K_theta=0.012,0.016,0.020", "--k", "0.6,0.9,1.2",
        "--N", "128", "--amplitude", "0.1", "--t-end", "2000", "--seeds", "1",
        "--workers", "1"], False),
    "model flexmm, point --simulate, N 128, 4 seeds": ([
        "--model", "flexmm", "--k", "0.6", "--amplitude", "0.1", "--N", "128", "--simulate"],
        False),
}


def _seconds(text: str) -> float:
    """'42 s', '17 min', '2.5 h' (``common.text.duration``) -> seconds."""
    value, unit = text.split()
    return float(value) * {"s": 1, "min": 60, "h": 3600}[unit]


def estimates(quick: bool = False) -> dict:
    """Each ESTIMATE_ROWS command (its quick ones with --quick), a fresh `flexmm` process:
    the estimate it prints before the work against the wall time it claims to estimate (a
    map: the whole command; a point: what follows its estimate line, its own "took"), and
    their ratio (issue 44 asks 0.5 to 2)."""
    import re
    import subprocess
    import sys

    rows = {}
    for name, (argv, in_quick) in ESTIMATE_ROWS.items():
        if quick and not in_quick:
            continue
        cmd = "point" if "--simulate" in argv and "point" in name else "map"
        with tempfile.TemporaryDirectory() as tmp:
            load = os.getloadavg()[0]
            t0 = time.perf_counter()
            proc = subprocess.run([sys.executable, "-m", "cli", cmd, *argv, "--out",
                                   str(Path(tmp) / "out")], capture_output=True, text=True,
                                  env={**os.environ, "OMP_NUM_THREADS": "1"})
            wall = time.perf_counter() - t0
        if proc.returncode:
            raise RuntimeError(f"{name}: exit {proc.returncode}: {proc.stderr[-500:]}")
        said = re.search(r"about (\d+(?:\.\d+)? (?:s|min|h))", proc.stdout)
        took = re.search(r"took (\d+(?:\.\d+)? (?:s|min|h)) after", proc.stdout)
        estimate = _seconds(said.group(1))
        actual = _seconds(took.group(1)) if cmd == "point" else wall
        rows[name] = {"argv": [cmd, *argv], "estimate_s": estimate, "wall_s": actual,
                      "wall_over_estimate": actual / estimate,
                      "load_average_before": load}
    return rows


def print_estimates(rows: dict):
    for name, r in rows.items():
        print(f"{name}: estimated {r['estimate_s']:.0f} s, took {r['wall_s']:.1f} s: "
              f"{r['wall_over_estimate']:.2f}x (load average {r['load_average_before']:.1f})")


def main(quick=False, out=None):
    from bench.calibrate_growth import check_grid

    load_before = os.getloadavg()
    N, T = (100, 1000.0) if quick else (paper.N, paper.T_END)
    params = _params(N, T)
    paper_params = _params(N, T, method="rk4", dt=paper.DT)
    costs = cell_costs(params, paper_params)
    serial = statistics.mean(c["default"]["s"] for c in costs)
    serial_rk4 = statistics.mean(c["rk4 dt = 0.05"]["s"] for c in costs)
    predict = statistics.mean(c["prediction_s"] for c in costs)
    n_k = 8 if quick else 16  # the layouts' map: 4 x n_k cells, one task each
    layout = _params(N, T, n_k=n_k)
    walls, tasks = layout_walls(layout)
    overhead = scheduling_overhead()
    n_cells = len(layout.delta) * len(layout.k)
    per_cell = walls["1 process"] / n_cells  # run_map on one worker: prediction included
    res = {"machine": machine(), "quick": quick, "N": N, "t_end": T,
           "method": params.cell_step[0], "dt": params.cell_step[1],
           "per_cell_s": per_cell, "per_cell_serial_s": serial,
           "prediction_per_cell_serial_s": predict,
           "per_cell_serial_rk4_s": serial_rk4, "default_over_rk4": serial_rk4 / serial,
           "cells": costs, "cells_per_second_per_core": 1 / serial,
           "layout_map_cells": n_cells, "layout_map_wall_s": walls,
           "layout_map_task_phase_s": tasks,
           "speedup_2_workers": walls["1 process"] / walls["2 processes"],
           "speedup_2_threads": walls["1 process"] / walls["1 process, 2 threads"],
           "speedup_2_workers_task_phase": tasks["1 process"] / tasks["2 processes"],
           "speedup_2_threads_task_phase": tasks["1 process"] / tasks["1 process, 2 threads"],
           "scheduling_overhead_per_task_s": overhead,
           "overhead_fraction_of_a_task": overhead / (per_cell * params.block),
           "map_64x64_estimated_here_s": 64 * 64 * serial / 2}
    if not quick:
        res["map_64x64"] = map_64(N, T)
        res["map_64x64_run_map"] = map_64_run_map(N, T)
        res["cell_accuracy"] = check_grid()
    res["model_vs_paper_map"] = model_vs_paper_map()
    res["model_map_workers"] = model_map_layouts(quick)
    res["estimates"] = estimates(quick)
    res["load_average_before_after"] = [load_before, os.getloadavg()]
    write_section("maps", res, quick, out)
    print_model_row(res["model_vs_paper_map"])
    print_model_layouts(res["model_map_workers"])
    print_estimates(res["estimates"])
    print(f"per cell (N = {N}, T = {T:g}, {res['method']} dt = {res['dt']:.3g}): simulated "
          f"in {serial:.3f} s serially = {1 / serial:.1f} cells/s/core (RK4 at dt = 0.05 "
          f"{serial_rk4:.3f} s: {serial_rk4 / serial:.1f}x); its prediction {predict:.3f} s; "
          f"both in run_map on one worker {per_cell:.3f} s")
    print(f"{n_cells}-cell map: " + ", ".join(f"{k} {v:.2f} s" for k, v in walls.items())
          + f" -> 2 processes {res['speedup_2_workers']:.2f}x, 2 threads "
          f"{res['speedup_2_threads']:.2f}x; its task phase: "
          + ", ".join(f"{k} {v:.2f} s" for k, v in tasks.items())
          + f" -> 2 processes {res['speedup_2_workers_task_phase']:.2f}x, 2 threads "
          f"{res['speedup_2_threads_task_phase']:.2f}x")
    print(f"scheduling overhead {overhead * 1e3:.2f} ms per task = "
          f"{100 * res['overhead_fraction_of_a_task']:.2f}% of a {params.block}-cell task")
    if "map_64x64" in res:
        m = res["map_64x64"]
        print(f"64 x 64 map ({m['cells']} cells simulated, {m['workers']} workers): "
              f"{m['wall_s'] / 60:.1f} min measured; as run_map runs it (cluster start-up, "
              f"every cell also predicted): {res['map_64x64_run_map']['wall_s'] / 60:.1f} min")
        acc = res["cell_accuracy"]
        for case in ("rotation", "coupled"):
            a = acc[case]
            print(f"fig3 grid, case {case}: {a['cells']} cells ({a['mi_cells']} MI), "
                  f"{a['verdict_changes']} verdict changes, largest growth error "
                  f"{a['largest_growth_curve_error']:.2g} (tolerance {acc['growth_tol']:g})")
    else:
        print(f"64 x 64 map: ~{res['map_64x64_estimated_here_s'] / 60:.1f} min here "
              "(estimated; measured in the full run)")
    print(f"load average before/after: {load_before[0]:.1f} / {os.getloadavg()[0]:.1f} "
          f"on {os.cpu_count()} cores")
    return res


if __name__ == "__main__":
    import sys

    if "--estimates" in sys.argv:  # issue 44's estimate rows alone (printed, not written)
        print_estimates(estimates("--quick" in sys.argv))
    elif "--workers-row" in sys.argv:  # issue 40's 2-workers row alone
        layouts = model_map_layouts("--quick" in sys.argv)
        print_model_layouts(layouts)
        if "--update" in sys.argv:  # into the committed maps section, its rest kept
            import json

            from bench.simulator import output_dir, results_path, write_sections

            here = output_dir(update=True)
            section = json.loads(results_path(False, here).read_text()).get("maps", {})
            section.update(model_map_workers=layouts)
            write_sections({"maps": section}, False, here)
    elif "--model-row" in sys.argv:  # issue 40's rows alone (printed, not written)
        load = os.getloadavg()[0]
        row = model_vs_paper_map()
        print_model_row(row)
        layouts = model_map_layouts("--quick" in sys.argv)
        print_model_layouts(layouts)
        if "--fput-32" in sys.argv:  # the 32 x 32 fput map (minutes), into results.json
            fput = fput_map_32(row)
            print_fput_32(fput)
            if "--update" in sys.argv:  # into the committed maps section, its rest kept
                import json

                from bench.simulator import output_dir, results_path, write_sections

                here = output_dir(update=True)
                section = json.loads(results_path(False, here).read_text()).get("maps", {})
                section.update(fput_map_32x32=fput, model_vs_paper_map=row,
                               model_map_workers=layouts)
                write_sections({"maps": section}, False, here)
        print(f"load average before/after: {load:.1f} / {os.getloadavg()[0]:.1f} on "
              f"{os.cpu_count()} cores")
    else:
        main(*arguments(__doc__))
