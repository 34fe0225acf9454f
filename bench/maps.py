"""Maps on Dask, measured: cells per second per core, 1 -> 2 workers, scheduling overhead.

- A cell is the paper's run (N = 500, T = 5000, RK4 dt = 0.05) with the map's early stop;
  its cost is measured serially (no Dask) on stable and unstable cells of case II.
- The same 16-cell map (4 x 4 around the blue point, case II) on a LocalCluster of 1 and of
  2 workers (fresh stores each): the speed-up.
- Scheduling overhead: no-op tasks through the same cluster (time per task round trip)
  against the cost of a task (a block of 4 cells).
- From the per-cell cost: a 64 x 64 map here (2 cores) and on 100 cores.
Writes the "maps" section of results.json (results_quick.json with --quick; in out/bench/,
or bench/ with --update).

    python -m bench.maps [--quick] [--update | --out DIR]
"""

from __future__ import annotations

import shutil
import statistics
import tempfile
import time
from pathlib import Path

import numpy as np

from bench.simulator import arguments, machine, write_section
from common import paper
from numerics import maps


def _noop(x):
    return x


def main(quick=False, out=None):
    N, T = (100, 1000.0) if quick else (paper.N, paper.T_END)
    kk = 2 * np.pi * np.round(np.linspace(0.7, 1.0, 4) * N / (2 * np.pi)) / N
    params = maps.MapParameters(case="coupled", alpha=paper.ALPHA, K_s=paper.K_S,
                                delta=(-0.006, -0.002, 0.002, 0.006), k=tuple(kk),
                                amplitude=0.02, N=N, t_end=T, block=1)
    # per-cell cost, serial, on the map's own cells (a row of it)
    costs = []
    for j, k in enumerate(kk):
        t0 = time.perf_counter()
        r = maps.simulate_block(params, 0, [j])["rows"][0]
        costs.append({"k": float(k), "delta": params.delta[0], "s": time.perf_counter() - t0,
                      "mi": r["verdict_simulated"], "t_simulated": r["t_simulated"]})
    serial = statistics.mean(c["s"] for c in costs)
    # the same map on 1 and 2 workers: clusters started and warmed up first (the start-up,
    # ~3 s, is paid once per map, not per cell)
    from dask.distributed import Client, LocalCluster

    walls = {}
    for workers in (1, 2):
        d = Path(tempfile.mkdtemp())
        try:
            maps.open_or_create(d / "map.zarr", params)  # theory columns outside the timing
            with LocalCluster(n_workers=workers, threads_per_worker=1, dashboard_address=":0",
                              silence_logs=40) as cluster, Client(cluster) as client:
                tiny = maps.MapParameters(case="coupled", alpha=paper.ALPHA, K_s=paper.K_S,
                                          delta=(0.003,), k=(2 * np.pi * 13 / 100,),
                                          amplitude=0.02, N=100, t_end=10.0)
                client.gather([client.submit(maps.simulate_block, tiny, 0, [0], pure=False)
                               for _ in range(workers)])  # load the compiled kernels
                t0 = time.perf_counter()
                maps.run_map(params, d, scheduler=cluster.scheduler_address, progress=False,
                             log=lambda *_: None)
                walls[workers] = time.perf_counter() - t0
        finally:
            shutil.rmtree(d, ignore_errors=True)
    # scheduling overhead: no-op round trips on a running cluster
    with LocalCluster(n_workers=2, threads_per_worker=1, dashboard_address=":0",
                      silence_logs=40) as cluster, Client(cluster) as client:
        client.gather(client.map(_noop, range(10)))  # warm up
        n = 200
        t0 = time.perf_counter()
        client.gather([client.submit(_noop, i, pure=False) for i in range(n)])
        overhead = (time.perf_counter() - t0) / n
    n_cells = len(params.delta) * len(params.k)
    per_cell = walls[1] / n_cells  # one worker, everything included
    task = per_cell * params.block
    cells = 64 * 64
    res = {"machine": machine(), "quick": quick, "N": N, "t_end": T,
           "per_cell_s": per_cell, "per_cell_serial_s": serial, "cells": costs,
           "cells_per_second_per_core": 1 / per_cell,
           "map_16_cells_wall_s": walls, "speedup_2_workers": walls[1] / walls[2],
           "scheduling_overhead_per_task_s": overhead,
           "overhead_fraction_of_a_task": overhead / task,
           "map_64x64_here_s": cells * per_cell / 2,
           "map_64x64_on_100_cores_s": cells * per_cell / 100}
    write_section("maps", res, quick, out)
    print(f"per cell (N = {N}, T = {T:g}): {per_cell:.2f} s in the map on one worker "
          f"({serial:.2f} s serially, one row) = {1 / per_cell:.2f} cells/s/core")
    print(f"16-cell map: 1 worker {walls[1]:.1f} s, 2 workers {walls[2]:.1f} s -> "
          f"{walls[1] / walls[2]:.2f}x")
    print(f"scheduling overhead {overhead * 1e3:.2f} ms per task = "
          f"{100 * overhead / task:.3f}% of a {params.block}-cell task")
    print(f"64 x 64 map: {res['map_64x64_here_s'] / 60:.0f} min here, "
          f"{res['map_64x64_on_100_cores_s'] / 60:.1f} min on 100 cores")
    return res


if __name__ == "__main__":
    main(*arguments(__doc__))
