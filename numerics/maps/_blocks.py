"""One task of a map: a block of cells (one delta, up to ``block`` values of k), predicted
and, unless the map is theory-only, simulated, on a worker; and the blocks of the cells a
store has not done yet."""

from __future__ import annotations

import functools
import math

import numpy as np

from ._params import MapParameters

FIELD_CODES = {"theta": 0, "U": 1}

#: glibc's mallopt parameters, and the values a map worker runs with: arrays up to 32 MB
#: (the largest glibc allows) from the heap, which keeps up to 128 MB of freed memory
M_TRIM_THRESHOLD, M_MMAP_THRESHOLD = -1, -3
MMAP_THRESHOLD, TRIM_THRESHOLD = 1 << 25, 1 << 27


@functools.cache
def keep_freed_memory() -> bool:
    """Let this process reuse freed memory instead of returning it to the OS (glibc only;
    elsewhere a no-op, False).

    Dask's workers start with MALLOC_TRIM_THRESHOLD_=65536 (``distributed.nanny.
    pre-spawn-environ``), which also freezes glibc's adaptive mmap threshold at 128 kB: every
    array above it (a prediction's Hill matrices and responses, 1-15 MB) is then a fresh
    mmap whose pages the kernel faults in and zeroes. Measured on 16 cells of a map on one
    worker: 0.75 s system time against 0.2 s serially, the cells' wall time 10-20% longer;
    with these values 0.2 s. Called by every task (once per process), so that workers a
    user starts with ``dask worker`` get it too."""
    import ctypes
    import ctypes.util

    name = ctypes.util.find_library("c")
    if not name:
        return False
    try:
        mallopt = ctypes.CDLL(name).mallopt
    except (OSError, AttributeError):
        return False
    return bool(mallopt(M_MMAP_THRESHOLD, MMAP_THRESHOLD)
                and mallopt(M_TRIM_THRESHOLD, TRIM_THRESHOLD))


def simulated_row(runs: list, pred) -> dict:
    """A cell's simulated columns from its seeds' runs (``simulate_cell``'s answers, on the
    CPU or the GPU): the verdict of the exponential readings by the point's rule
    (``cell_verdict``: algebraic growth is no MI; a run that grew, but less than the
    threshold, is undetermined, never stable), the median growth and median
    exponential reading, field and q of the seed that grew most, the longest time
    simulated, the median measured peak gain, and log10(predicted / measured growth) over
    the first seed's span (a run stops early once its verdict is certain)."""
    from ._cells import cell_verdict

    growths = [r["growth"] for r in runs]
    # a run dict without the exponential reading (one a caller assembled, as before issue
    # 96) is read by its factor
    expo = [r.get("growth_exponential", r["growth"]) for r in runs]
    top = runs[int(np.argmax(growths))]
    row = {
        "verdict_simulated": cell_verdict(expo, max(r["t_simulated"] for r in runs)),
        "growth": float(np.median(growths)),
        "growth_exponential": float(np.median(expo)),
        "growth_field": FIELD_CODES[top["growth_field"]],
        "growth_q": float(top["growth_q"]),
        "t_simulated": float(max(r["t_simulated"] for r in runs)),
        "peak_gain": float(np.nanmedian([r["peak_gain"] for r in runs]))
        if any(np.isfinite(r["peak_gain"]) for r in runs) else float("nan")}
    row["growth_log_ratio"] = (
        math.log10(pred.growth_at(runs[0]["t_simulated"]) / runs[0]["growth"])
        if pred is not None and runs[0]["growth"] > 0 else float("nan"))
    return row


def predict_block(params: MapParameters, i: int, js: list) -> tuple[list, list]:
    """(rows, predictions) of the cells (i, j), j in ``js``: the theory columns, and the
    predicted growth each simulation is compared with."""
    from ._cells import predict_cell

    mat = params.material_at(i)
    rows, preds = [], []
    for j in js:
        row, pred = predict_cell(mat, params.case, params.k_simulated[j], params.N,
                                 params.t_end, params.amplitude, params.noise, params.seeds,
                                 params.start)
        rows.append(row)
        preds.append(pred)
    return rows, preds


def simulate_block(params: MapParameters, i: int, js: list, simulate: bool = True) -> dict:
    """Predict, and unless ``simulate`` is False simulate, the cells (i, j) for j in
    ``js`` (runs on a worker)."""
    from ._cells import predict_cell, simulate_cell

    keep_freed_memory()
    mat = params.material_at(i)
    method, dt = params.cell_step
    rows = []
    for j in js:
        k = params.k_simulated[j]
        row, pred = predict_cell(mat, params.case, k, params.N, params.t_end,
                                 params.amplitude, params.noise, params.seeds, params.start)
        if simulate:
            runs = [simulate_cell(mat, params.case, k, params.N, params.t_end,
                                  params.amplitude, params.noise, seed, params.start,
                                  dt, method) for seed in range(params.seeds)]
            row.update(simulated_row(runs, pred))
        rows.append(row)
    return {"i": i, "js": list(js), "rows": rows, "simulated": simulate}


def blocks(params: MapParameters, done: np.ndarray) -> list:
    """(i, [j, ...]) blocks of the cells not done, aligned with the store's chunks."""
    out = []
    rows, cols = params.grid_shape
    for i in range(rows):
        for j0 in range(0, cols, params.block):
            js = [j for j in range(j0, min(j0 + params.block, cols))]
            if not np.all(done[i, js]):
                out.append((i, js))
    return out


__all__ = ["simulate_block", "blocks", "FIELD_CODES"]
