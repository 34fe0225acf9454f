"""MI maps by simulation: cells on a Dask cluster, results in a Zarr store, resumable.

A map is a grid of (delta, k) at fixed alpha, K_s, case and amplitude. Every cell gets the
verdicts of the three theories (paper NLS, semi-discrete NLS, exact lattice; computed in
one batch, in the client, in seconds) and, unless ``theory_only``, a simulated verdict
(``numerics.maps.simulate_cell``: the scenes' 20x growth criterion, with early stop).

Simulations are tasks on ``dask.distributed``: a ``LocalCluster`` of this machine's cores
by default, or an existing scheduler by address. A task is a block of cells (one delta, up
to ``block`` values of k: seconds of work, so scheduling costs little); a dying worker's
task is retried. The client writes each finished block into ``map.zarr`` at once (a Zarr
region write; one writer, no locks), with a ``done`` flag per cell: an interrupted map
loses at most the blocks in flight, and the same command resumes with the missing cells.
"""

from __future__ import annotations

import math
import time
from pathlib import Path

import numpy as np

from ..lattice import Material
from ..lattice._analysis import GROWTH_THRESHOLD, grows_beyond_threshold
from ._cells import PREDICTED_STATUS
from ._params import MapParameters, local_cores

FIELD_CODES = {"theta": 0, "U": 1}
#: Bloch offsets the exact theory searches per cell: the whole zone, densely. stability_map's
#: default (20 offsets in (0, 1.5], enough for the paper's sidebands) misses the narrow
#: resonances of case II and offsets beyond 1.5, where simulations found growth
EXACT_OFFSETS = np.linspace(0.005, math.pi, 400)
# --- one task: a block of cells --------------------------------------------------------------

def simulate_block(params: MapParameters, i: int, js: list, simulate: bool = True) -> dict:
    """Predict, and unless ``simulate`` is False simulate, the cells (i, j) for j in
    ``js`` (runs on a worker)."""
    from ._cells import predict_cell, simulate_cell

    mat = Material(params.alpha, params.K_s, params.K_s - params.delta[i])
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
            verdict = sum(r["verdict_simulated"] for r in runs) * 2 > len(runs)
            growths = [r["growth"] for r in runs]
            top = runs[int(np.argmax(growths))]
            row.update({
                "verdict_simulated": bool(verdict), "growth": float(np.median(growths)),
                "growth_field": FIELD_CODES[top["growth_field"]],
                "growth_q": float(top["growth_q"]),
                "t_simulated": float(max(r["t_simulated"] for r in runs)),
                "peak_gain": float(np.nanmedian([r["peak_gain"] for r in runs]))
                if any(np.isfinite(r["peak_gain"]) for r in runs) else float("nan")})
            # predicted and measured growth over the same span (a run stops early once
            # its verdict is certain): log10 of their ratio, first seed
            if pred is not None and runs[0]["growth"] > 0:
                row["growth_log_ratio"] = math.log10(
                    pred.growth_at(runs[0]["t_simulated"]) / runs[0]["growth"])
            else:
                row["growth_log_ratio"] = float("nan")
        rows.append(row)
    return {"i": i, "js": list(js), "rows": rows, "simulated": simulate}


# --- the store -------------------------------------------------------------------------------

def _empty_dataset(params: MapParameters, theory: dict):
    import xarray as xr

    shape = (len(params.delta), len(params.k))
    dims = ("delta", "k")
    fl = lambda: np.full(shape, np.nan)  # noqa: E731
    data = {
        "verdict_simulated": (dims, np.zeros(shape, bool)),
        "growth": (dims, fl(), {"long_name": "largest growth factor over the run",
                                "units": "1"}),
        "growth_field": (dims, np.full(shape, -1, np.int8),
                         {"flag_values": [-1, 0, 1], "flag_meanings": "none theta U"}),
        "growth_q": (dims, fl(), {"long_name": "wavenumber of the largest growth",
                                  "units": "rad per site"}),
        "peak_gain": (dims, fl(), {"long_name": "measured peak growth rate (linear-stage "
                                   "fit) where the simulation says MI",
                                   "units": "1/T (lattice time)"}),
        "t_simulated": (dims, fl(), {"units": "T (lattice time)"}),
        "done": (dims, np.zeros(shape, bool), {"long_name": "cell simulated"}),
        "growth_predicted": (dims, fl(), {
            "long_name": "growth factor the simulation measures, predicted: linear response "
                         "of the cell's own initial state (numerics.theory.predict_growth; "
                         "median over the seeds)", "units": "1"}),
        "verdict_predicted": (dims, np.full(shape, -1, np.int8), {
            "long_name": f"predicted growth_predicted > {GROWTH_THRESHOLD:g}",
            "flag_values": [-1, 0, 1], "flag_meanings": "undetermined stable MI"}),
        "rate_predicted": (dims, fl(), {"long_name": "largest growth rate of the state's "
                                        "Hill modes", "units": "1/T (lattice time)"}),
        "predicted_status": (dims, np.full(shape, -1, np.int8), {
            "flag_values": [-1] + list(PREDICTED_STATUS.values()),
            "flag_meanings": " ".join(["not_computed"] + [n.replace(" ", "_")
                                                          for n in PREDICTED_STATUS])}),
        "growth_log_ratio": (dims, fl(), {
            "long_name": "log10(predicted / measured growth) over the span simulated "
                         "(first seed)", "units": "1"}),
        "done_predicted": (dims, np.zeros(shape, bool), {"long_name": "cell predicted"}),
    }
    for name, values in theory.items():
        attrs = ({"long_name": f"{name.removeprefix('peak_gain_')} theory: peak growth rate",
                  "units": "1/T (lattice time)"} if name.startswith("peak_gain") else
                 {"long_name": f"{name.removeprefix('verdict_')} theory: grows more than "
                               f"{GROWTH_THRESHOLD:g}x within t_end"})
        data[name] = (dims, values, attrs)
    coords = {"delta": ("delta", np.asarray(params.delta), {"long_name": "K_s - K_theta"}),
              "k": ("k", np.asarray(params.k), {"long_name": "k as requested",
                                                "units": "rad per site"}),
              "k_simulated": ("k", np.asarray(params.k_simulated),
                              {"long_name": "k snapped to 2 pi m / N: the wavenumber simulated "
                                            "and at which the theories are evaluated",
                               "units": "rad per site"})}
    return xr.Dataset(data, coords=coords, attrs=params.attrs())


def theory_columns(params: MapParameters) -> dict:
    """The theories on the whole grid, batched (seconds): their raw peak gains, and their
    verdicts on the simulation's question: does the plane wave grow more than
    GROWTH_THRESHOLD-fold within t_end (peak gain > ln(threshold) / t_end)?"""
    from generated import coefficients as continuum_nls
    from generated import lattice_coefficients as lattice_nls
    from ..theory import stability_map

    K, D = np.meshgrid(params.k_simulated, params.delta, indexing="xy")
    Kt = params.K_s - D
    gains = {}
    for name, nls in (("paper", continuum_nls), ("semidiscrete", lattice_nls)):
        with np.errstate(all="ignore"):
            g = getattr(nls, f"g_{params.case}")(K, params.alpha, params.K_s, Kt)
            g1 = nls.g1(K, params.alpha, params.K_s, Kt)
            gpos = np.where(g > 0, g, np.nan)
            peak = params.eps**2 * np.abs(g1) * nls.mi_growth_rate(
                nls.mi_fastest(gpos, params.A0), gpos, params.A0)
        gains[name] = np.where(np.isfinite(peak), peak, 0.0)
    args = (K, D, params.case, params.alpha, params.K_s, params.amplitude, EXACT_OFFSETS)
    gains["exact"] = np.nan_to_num(stability_map(*args))
    gains["exact_all"] = (np.nan_to_num(stability_map(*args, modes="all"))
                          if params.case == "coupled" else gains["exact"])
    out = {}
    for name, gain in gains.items():
        out[f"verdict_{name}"] = grows_beyond_threshold(gain, params.t_end)
        out[f"peak_gain_{name}"] = gain
    return out


def _holds(ds, params: MapParameters) -> bool:
    """Does the stored dataset ``ds`` hold the map ``params`` defines (same grid, same
    parameters; theory_only aside, so a theory-only map is resumed by simulations)?"""
    return (np.array_equal(ds["delta"].values, params.delta)
            and np.array_equal(ds["k"].values, params.k)
            and all(ds.attrs.get(n) == v for n, v in params.attrs().items()
                    if n not in ("theory_only",)))


def open_or_create(path: Path, params: MapParameters, overwrite: bool = False):
    """The store's dataset: an existing one with the same parameters (to resume), or a
    new one with the theory columns filled in (``overwrite``: replace a store that holds
    another map, or an unreadable one)."""
    import shutil

    import xarray as xr

    if path.exists():
        try:
            ds = xr.open_zarr(path, consolidated=False)
        except Exception as exc:  # noqa: BLE001 - any unreadable store
            if not overwrite:
                raise ValueError(f"{path} exists but is not a readable map ({exc}); replace "
                                 "it with --overwrite, or choose another --out") from None
            ds = None
        if ds is not None and _holds(ds, params):
            return ds
        if not overwrite:
            raise ValueError(f"{path} holds a map with other parameters; replace it with "
                             "--overwrite, or choose another --out")
        shutil.rmtree(path)
    ds = _empty_dataset(params, theory_columns(params))
    # one chunk per task block: every region write covers whole chunks
    chunks = (1, min(params.block, len(params.k)))
    # written beside and renamed into place: a failed write (disk full, Ctrl-C) leaves no
    # half store that would block the same command; consolidated metadata, so that a
    # user's xr.open_zarr(path) opens it without a warning (region writes keep it valid)
    tmp = path.with_name(f".{path.name}.partial")
    if tmp.exists():
        shutil.rmtree(tmp)
    try:
        ds.to_zarr(tmp, mode="w", consolidated=True, zarr_format=2,
                   encoding={n: {"chunks": chunks} for n in ds.data_vars})
        tmp.rename(path)
    finally:
        if tmp.exists():
            shutil.rmtree(tmp, ignore_errors=True)
    return xr.open_zarr(path, consolidated=False)


def _write_block(path: Path, params: MapParameters, result: dict):
    import xarray as xr

    i, js = result["i"], result["js"]
    j0, j1 = min(js), max(js) + 1
    arrays = {}
    for name in result["rows"][0]:
        arrays[name] = (("delta", "k"), np.array([[r[name] for r in result["rows"]]]))
    flags = {"done_predicted": (("delta", "k"), np.ones((1, j1 - j0), bool))}
    if result["simulated"]:
        flags["done"] = (("delta", "k"), np.ones((1, j1 - j0), bool))
    region = {"delta": slice(i, i + 1), "k": slice(j0, j1)}
    xr.Dataset(arrays).to_zarr(path, consolidated=False, region=region)
    # the done flags only after every value is on disk: a client killed between the two
    # writes leaves the cells not done (computed again on resume), never done with a
    # value missing (tests/test_cluster_faults.py found one when both went in one write)
    xr.Dataset(flags).to_zarr(path, consolidated=False, region=region)


# --- running ---------------------------------------------------------------------------------

def blocks(params: MapParameters, done: np.ndarray) -> list:
    """(i, [j, ...]) blocks of the cells not done, aligned with the store's chunks."""
    out = []
    for i in range(len(params.delta)):
        for j0 in range(0, len(params.k), params.block):
            js = [j for j in range(j0, min(j0 + params.block, len(params.k)))]
            if not np.all(done[i, js]):
                out.append((i, js))
    return out


def run_map(params: MapParameters, out: Path, scheduler: str | None = None,
            workers: int | None = None, progress: bool | None = None, log=print,
            overwrite: bool = False):
    """Compute (or resume) ``OUT/map.zarr``; returns the dataset (loaded)."""
    import xarray as xr

    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    path = out / "map.zarr"
    ds = open_or_create(path, params, overwrite)
    # a theory-only map predicts its cells; a simulated one simulates (and predicts) them
    flag = "done_predicted" if params.theory_only else "done"
    what = "predict" if params.theory_only else "simulate"
    done = ds[flag].values
    todo = blocks(params, done)
    n_cells, n_done = done.size, int(done.sum())
    if n_done:
        log(f"resuming {path}: {n_done} of {n_cells} cells already done, "
            f"{n_cells - n_done} to {what}")
    if todo:
        _run_tasks(params, path, todo, n_cells - n_done, scheduler, workers, progress, log)
    return xr.open_zarr(path, consolidated=False).load()


class MapCellError(ValueError):
    """A cell's simulation failed on a worker: the message names the cell, in one line."""


def _run_tasks(params, path, todo, n_todo, scheduler, workers, progress, log):
    import logging

    from dask.distributed import Client, LocalCluster, as_completed

    for name in ("distributed", "distributed.worker", "distributed.scheduler",
                 "distributed.nanny", "distributed.core"):
        logging.getLogger(name).setLevel(logging.CRITICAL)  # worker tracebacks stay off
    from tqdm.auto import tqdm

    cluster = None
    if scheduler:
        client = Client(scheduler, timeout="20s")
    else:
        n = workers or local_cores()
        # one single-threaded process per core: measured against one process with a
        # thread per core (bench/maps.py, "map_16_cells_wall_s"), which gains less
        cluster = LocalCluster(n_workers=n, threads_per_worker=1, processes=True,
                               dashboard_address=":0", silence_logs=logging.CRITICAL)
        client = Client(cluster)
    bar = tqdm(total=n_todo, unit="cell", disable=None if progress is None else not progress,
               desc="map")
    t0 = time.perf_counter()
    try:
        futures = [client.submit(simulate_block, params, i, js, not params.theory_only,
                                 retries=2, pure=False) for i, js in todo]
        cells = dict(zip(futures, todo))
        for fut in as_completed(futures):
            try:
                result = fut.result()
            except Exception as exc:  # noqa: BLE001 - one line naming the cell, no traceback
                i, js = cells[fut]
                for f in futures:
                    f.cancel()
                raise MapCellError(
                    f"cells delta = {params.delta[i]:g}, k = "
                    f"{', '.join(f'{params.k[j]:g}' for j in js)}: "
                    f"{type(exc).__name__}: {str(exc).splitlines()[0] if str(exc) else ''}; "
                    f"the finished cells are kept in {path}") from None
            _write_block(path, params, result)
            bar.update(len(result["js"]))
    finally:
        bar.close()
        client.close()
        if cluster is not None:
            cluster.close()
    log(f"{'predicted' if params.theory_only else 'simulated'} {n_todo} cells in "
        f"{time.perf_counter() - t0:.1f} s")


#: a theory's verdict is "marginal" at a cell when its predicted growth exp(sigma t_end) is
#: within this factor of the threshold: the noise's share in the unstable mode and the time
#: the linear stage takes to set in change the measured factor by about that much
MARGIN = 3.0


def agreement(ds, margin: float = MARGIN) -> dict:
    """Percent of the simulated cells where each theory's verdict equals the simulation's:
    over all of them, and over the cells where the theory is not marginal (its predicted
    growth over t_end not within ``margin`` of the threshold).

    "predicted" (the growth factor predicted from each cell's initial state) is marginal
    where ``growth_predicted`` is within ``margin`` of the threshold; its undetermined cells
    (no linear theory: ``predicted_status``) are left out and counted
    (``predicted_undetermined_cells``). ``predicted_growth_within_2x``: percent of the
    cells whose measured growth lies in [2, 1000] where the predicted one is within 2x of
    it (over the same span; ``growth_log_ratio``), out of ``predicted_growth_cells``.
    """
    done = ds["done"].values
    sim = ds["verdict_simulated"].values
    t_end, thr = float(ds.attrs["t_end"]), float(ds.attrs["growth_threshold"])
    out = {}

    def pct(v, m):
        return float(100 * np.mean(v[m] == sim[m])) if m.any() else float("nan")

    for name in ("paper", "semidiscrete", "exact", "exact_all"):
        v = ds[f"verdict_{name}"].values
        gain = ds[f"peak_gain_{name}"].values
        decided = done & (np.abs(gain * t_end - math.log(thr)) > math.log(margin))
        out[name] = pct(v, done)
        out[f"{name}_decided"] = pct(v, decided)
        out[f"{name}_decided_cells"] = int(decided.sum())
    if "verdict_predicted" in ds:
        v = ds["verdict_predicted"].values.astype(int)
        growth = ds["growth_predicted"].values
        known = done & (v >= 0)
        with np.errstate(invalid="ignore", divide="ignore"):
            decided = known & (np.abs(np.log(growth) - math.log(thr)) > math.log(margin))
        out["predicted"] = pct(v == 1, known)
        out["predicted_decided"] = pct(v == 1, decided)
        out["predicted_decided_cells"] = int(decided.sum())
        out["predicted_undetermined_cells"] = int((done & (v < 0)).sum())
        measured = ds["growth"].values
        ratio = ds["growth_log_ratio"].values
        mid = known & (measured >= 2) & (measured <= 1000) & np.isfinite(ratio)
        out["predicted_growth_cells"] = int(mid.sum())
        out["predicted_growth_within_2x"] = (
            float(100 * np.mean(np.abs(ratio[mid]) <= math.log10(2))) if mid.any()
            else float("nan"))
    return out
