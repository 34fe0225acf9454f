"""MI maps by simulation: cells on a Dask cluster, results in a Zarr store, resumable.

A map is a grid of (delta, k) at fixed alpha, K_s, case and amplitude. Every cell gets the
verdicts of the three theories (paper NLS, semi-discrete NLS, exact lattice; computed in
one batch, in the client, in seconds), the growth factor its simulation will measure,
predicted from its own initial state (``numerics.maps.predict_cell``, a task per block of
cells), and, unless ``theory_only``, a simulated verdict (``numerics.maps.simulate_cell``:
the scenes' 20x growth criterion, with early stop).

Simulations are tasks on ``dask.distributed``: a ``LocalCluster`` of this machine's cores
by default, or an existing scheduler by address. A task is a block of cells (one delta, up
to ``block`` values of k: seconds of work, so scheduling costs little); a dying worker's
task is retried. The client writes each finished block into ``map.zarr`` at once (a Zarr
region write; one writer, no locks), with a ``done`` flag per cell: an interrupted map
loses at most the blocks in flight, and the same command resumes with the missing cells.

This module writes the store and runs the tasks; ``_store_open`` opens and verifies it, a
task is in ``_blocks``, the store's variables and theory columns in ``_columns``, the
comparison of the verdicts in ``_agreement``.
"""

from __future__ import annotations

import contextlib
import math
import os
import time
from pathlib import Path
from typing import NamedTuple

import numpy as np

from common.text import duration, plural

from ._agreement import agreement
from ._blocks import blocks, simulate_block
from ._columns import (
    THEORY_NAMES,
    theory_columns,
    tri_state,
)
from ._integrity import CHECKSUM, read_zarray, unsound_chunks
from ._params import MapParameters, local_cores
from ._store_open import _open, open_or_create

#: the theory columns: recomputed from the parameters where a store lost them
THEORY_SET = frozenset(THEORY_NAMES)


class _CellWriter:
    """The store's cell variables, opened once per run, written a block at a time.

    A variable stored as the store makes them (zarr v2, one Blosc codec, C order, no
    filters: ``_store_open``) has the chunks the block touches written here, each whole
    from the values in memory (``arrays``, which hold the store's current state) and
    encoded by the array's own codec, as the zarr v2 format defines a chunk; each file is
    replaced atomically. That is 15 -> 4 ms of the client's CPU per block of a flexmm
    map's 20 variables (zarr's asynchronous writes hop threads per array), time the
    client's core takes from the workers on a small machine. Any other variable, or a
    call without ``arrays``, goes through zarr's asynchronous API (one round trip)."""

    def __init__(self, path: Path):
        import zarr.api.asynchronous as za
        from zarr.core.sync import sync

        async def opened():
            group = await za.open_group(store=str(path), mode="r+")
            return {name: arr async for name, arr in group.arrays()}

        self.path = Path(path)
        self._sync = sync
        self.arrays = sync(opened())
        self.direct = {name: spec for name in self.arrays
                       if (spec := _v2_chunk_spec(self.path / name)) is not None}

    def write(self, region: dict, cells: tuple, arrays: dict | None = None):
        import asyncio

        rest = {n: v for n, v in region.items() if arrays is None or n not in self.direct}
        for name in region.keys() - rest.keys():
            _write_chunks(self.path / name, self.direct[name], arrays[name], cells)

        async def writes():
            await asyncio.gather(*[self.arrays[n].setitem(cells, v) for n, v in rest.items()])

        if rest:
            self._sync(writes())


class _ChunkSpec(NamedTuple):
    """What the client needs to write a chunk of a zarr v2 array itself: the array's codec,
    chunk shape and dtype, and a chunk of its fill value alone (read-only: each chunk
    starts as a copy of it, and a chunk equal to it is not stored)."""

    codec: object
    chunks: tuple
    dtype: np.dtype
    empty: np.ndarray


def _v2_chunk_spec(array_dir: Path) -> _ChunkSpec | None:
    """The chunk spec of a zarr v2 array whose chunk is the codec's encoding of its C-order
    bytes (Blosc, no filters, a numeric or bool dtype) in a file "i.j" beside its metadata
    (the "." key separator, as the store is written); None for any other, and where the
    metadata cannot be read (``_integrity.read_zarray``): zarr's own path, which says so."""
    import numcodecs

    meta = read_zarray(array_dir)
    if (meta is None or meta.zarr_format != 2 or meta.filters or meta.order != "C"
            or (meta.compressor or {}).get("id") != "blosc" or meta.dtype.kind not in "biuf"
            or meta.separator != "."):
        return None
    try:
        codec = numcodecs.get_codec(dict(meta.compressor))
        # no fill given: zarr pads a chunk with the dtype's zero, and so does its reader
        empty = np.full(meta.chunks, 0 if meta.fill_value is None else meta.fill_value,
                        meta.dtype)
    except Exception:  # noqa: BLE001 - a codec or fill this numcodecs cannot make: zarr's path
        return None
    empty.flags.writeable = False
    return _ChunkSpec(codec, meta.chunks, meta.dtype, empty)


def _write_chunks(array_dir: Path, spec: _ChunkSpec, values: np.ndarray, cells: tuple):
    """The chunks of ``values`` (the whole array, in memory) that ``cells`` touch, each
    encoded whole (an edge chunk padded with the fill value, which no read sees) into its
    file, replaced atomically; a chunk of the fill value alone is not stored (zarr's
    default, ``write_empty_chunks`` False)."""
    chunks = spec.chunks
    nan_is_fill = spec.dtype.kind == "f"
    ranges = [range(c.start // n, (c.stop - 1) // n + 1) for c, n in zip(cells, chunks)]
    for index in np.ndindex(*(len(r) for r in ranges)):
        at = tuple(r[x] for r, x in zip(ranges, index))
        part = values[tuple(slice(a * n, (a + 1) * n) for a, n in zip(at, chunks))]
        chunk = spec.empty.copy()
        chunk[tuple(slice(0, m) for m in part.shape)] = part
        f = array_dir / ".".join(str(a) for a in at)
        if np.array_equal(chunk, spec.empty, equal_nan=nan_is_fill):
            f.unlink(missing_ok=True)  # as zarr: a chunk of the fill value is not stored
            continue
        tmp = f.with_name(f".{f.name}.{os.getpid()}.tmp")
        try:
            tmp.write_bytes(spec.codec.encode(chunk))
            os.replace(tmp, f)
        except OSError as exc:  # a full disk, a quota: said of the store (_named_os_errors)
            tmp.unlink(missing_ok=True)
            raise OSError(exc.errno, exc.strerror) from None


def _write_block(path: Path, params: MapParameters, result: dict, arrays: dict | None = None,
                 writer: _CellWriter | None = None):
    """Write a finished block into the store (a region write: whole chunks, or a cell of
    one at a map's end, ``_finer_tail``): its
    predicted and simulated variables, their flags and the cells' checksums. ``arrays``:
    the store's values in memory (name -> array), updated here; read from the store when
    not given. ``writer``: the store opened once for a run (else opened here)."""
    import xarray as xr

    from ._integrity import cell_checksums

    if arrays is None:
        with xr.open_zarr(path, consolidated=False, chunks=None) as ds:
            arrays = {n: ds[n].values for n in ds.data_vars}
    i, js = result["i"], result["js"]
    j0, j1 = min(js), max(js) + 1
    cells = (slice(i, i + 1), slice(j0, j1))
    region = {}
    for name in result["rows"][0]:
        arrays[name][cells] = np.array([[r[name] for r in result["rows"]]],
                                       dtype=arrays[name].dtype)
        region[name] = arrays[name][cells]
    for flag in ("done_predicted",) + (("done",) if result["simulated"] else ()):
        arrays[flag][cells] = True
        region[flag] = arrays[flag][cells]
    arrays[CHECKSUM][cells] = cell_checksums(arrays, cells)
    region[CHECKSUM] = arrays[CHECKSUM][cells]
    # one concurrent write; a client killed in the middle of it leaves cells whose
    # checksum does not match, recomputed on resume (tests/test_cluster_faults.py kills
    # it mid-map)
    (writer or _CellWriter(path)).write(region, cells, arrays)


@contextlib.contextmanager
def _named_os_errors(path: Path):
    """An OSError that names no file (zarr's writes: a full disk, a quota) names the store,
    and says that its finished cells are kept (each block is written whole or not at all)."""
    try:
        yield
    except OSError as exc:
        if exc.filename:
            raise
        raise OSError(exc.errno, f"{exc.strerror or exc} (writing the map store; the cells "
                                 "finished before are kept, and the same command continues "
                                 "once there is room)", str(path)) from None


def run_map(params: MapParameters, out: Path, scheduler: str | None = None,
            workers: int | None = None, progress: bool | None = None, log=print,
            overwrite: bool = False, timeout: float = 20.0, device: str = "cpu",
            estimate: float | None = None):
    """Compute (or resume) ``OUT/map.zarr``; returns the dataset (loaded). One writer at a
    time (``OUT/map.zarr.lock``); ``timeout``: seconds to reach ``scheduler``. ``progress``:
    a bar on stderr (None: where it is a terminal), or a callable given each finished
    block's number of cells. ``device``
    "gpu" (or "auto" where a GPU is usable) simulates the cells on the GPU in batches
    (``simulate_map_cells_gpu``; the theories on this CPU), with the same store, checksums
    and resume as on the CPU. ``estimate``: the caller's estimate of the seconds its cells
    left take, the workers' start-up included (a resumed map's line says it instead of the
    parameters' rough figure)."""
    from ._devices import resolve_device
    from ._integrity import store_lock
    from ._model_params import ModelMapParameters
    from ._params import MapParameters

    if not isinstance(params, (MapParameters, ModelMapParameters)):
        raise TypeError(f"params must be a MapParameters or a ModelMapParameters "
                        f"(ModelMapParameters.from_model(...)), got {type(params).__name__}")
    if workers is not None and (isinstance(workers, bool) or not isinstance(
            workers, (int, np.integer)) or workers < 1):  # 0 ran as the default, said nowhere
        raise ValueError(f"workers must be an integer >= 1 (None: the cores), got {workers!r}")
    if not (isinstance(timeout, (int, float)) and math.isfinite(timeout) and timeout > 0):
        raise ValueError(f"timeout must be a finite time > 0 in seconds, got {timeout!r}")
    if not isinstance(out, (str, os.PathLike)):
        raise TypeError(f"out must be a folder (str or os.PathLike), got {type(out).__name__}")
    if Path(out).exists() and not Path(out).is_dir():  # was FileExistsError from mkdir
        raise ValueError(f"out {str(out)!r} is a file, not a folder: give a folder for "
                         "map.zarr")
    device = resolve_device(device, params.theory_only, log, scheduler)

    if scheduler:
        from ._cluster import probe

        probe(scheduler, timeout)  # before any work: a wrong address fails in seconds
    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    path = out / "map.zarr"
    with store_lock(path, log), _named_os_errors(path):
        ds, arrays = _open(path, params, overwrite, log)
        # a theory-only map predicts its cells; a simulated one simulates (and predicts)
        done = arrays["done_predicted" if params.theory_only else "done"]
        what = "predict" if params.theory_only else "simulate"
        todo = blocks(params, done)
        n_cells, n_done = done.size, int(done.sum())
        if n_done:
            # the estimate on this machine's cores (a scheduler's workers are unknown here)
            # nothing left: no time (it said "0 to simulate (about 12 s)", the start-up
            # of workers it does not start)
            left = None if n_done >= n_cells else estimate if estimate is not None else (
                params.estimated_seconds(workers or local_cores()) * (n_cells - n_done)
                / n_cells) if not scheduler else None
            log(f"resuming {path}: {n_done} of {n_cells} cells already done (checksums "
                f"verified), {n_cells - n_done} to {what}"
                + (f" (about {duration(left)})" if left is not None else ""))
        if todo and device == "gpu":
            from ._devices import run_gpu

            run_gpu(params, path, todo, n_cells - n_done, progress, log, arrays, workers,
                    timeout)
        elif todo:
            _run_tasks(params, path, todo, n_cells - n_done, scheduler, workers, progress,
                       log, arrays, timeout, estimate)
        import zarr

        derived = getattr(params, "derived_variables", lambda arrays: {})(arrays)
        if derived:  # computed from the finished cells (a model map's critical damping)
            import xarray as xr

            group = zarr.open_group(str(path), mode="r", use_consolidated=False)
            kept = dict(group.attrs)  # an xarray append puts the dataset's own attributes
            # and the store's own from them (a model map's count of unsampled NLS bands)
            kept.update(getattr(params, "derived_attrs", lambda derived: {})(derived))
            xr.Dataset(derived).to_zarr(path, mode="a", zarr_format=2, consolidated=False)
            zarr.open_group(str(path), mode="r+", use_consolidated=False).attrs.put(kept)
            arrays.update({n: np.asarray(v[1]) for n, v in derived.items()})
            ds = ds.assign({n: (v[0], np.asarray(v[1]), v[2]) for n, v in derived.items()})
            ds.attrs.update(kept)
        if not params.theory_only and (todo or _unsaid(path, params)):
            # who simulated (the last run's cells); also where a run stopped (Ctrl-C, kill)
            # after its last cell and before these lines: the rerun has no cell left to
            # simulate and the store lacked them (device, device_name) for good
            from ._devices import device_attrs

            who = device_attrs(device, scheduler)
            # a theory-only store resumed by a simulated map now holds runs: its own flag
            # and what its simulated variables say follow (they said "no run made")
            who["theory_only"] = params.attrs()["theory_only"]
            group = zarr.open_group(str(path), mode="r+", use_consolidated=False)
            group.attrs.update(who)
            ds.attrs.update(who)
            for name, attrs in getattr(params, "simulated_attrs", dict)().items():
                group[name].attrs.update(attrs)
                ds[name].attrs.update(attrs)
        # .zmetadata is derived from the arrays' own metadata: rebuilt on every run, so a
        # stale or damaged copy never keeps xr.open_zarr(path) from reading the store

        zarr.consolidate_metadata(str(path), zarr_format=2)
        # the store's metadata and coordinates read; its variables are ``arrays``, which
        # every block written has updated (tests/test_maps.py: identical to a fresh read)
        return ds.copy(data={n: arrays[n] for n in ds.data_vars}).load()


def _unsaid(path: Path, params) -> bool:
    """Whether a simulated map's store lacks what its last run writes after the cells
    (``device``, or its ``theory_only`` flag still the theory-only map's it resumed)."""
    import zarr

    attrs = zarr.open_group(str(path), mode="r", use_consolidated=False).attrs
    return "device" not in attrs or attrs.get("theory_only") != params.attrs()["theory_only"]


def _spread(rank: int) -> float:
    """The van der Corput fraction of ``rank`` (its bits reversed after the binary point):
    0, 1/2, 1/4, 3/4, 1/8, ...: the first n ranks so ordered sample the whole range."""
    out, scale = 0.0, 0.5
    while rank:
        out += scale * (rank & 1)
        rank >>= 1
        scale /= 2
    return out


def _longest_first(params, todo, arrays=None) -> list:
    """The blocks in decreasing expected cost: a cell the exact theory calls stable runs the
    whole t_end (an MI cell stops once it passed 20x), and a prediction's Bloch families
    grow with k (one per 2 pi / N up to k). Ties (every block of a fresh model map, whose
    theories the tasks compute) spread over the grid, not in its order: cells of one
    region cost alike (a map's low-amplitude rows run all of T), and the progress lines'
    pace is the whole grid's from its first blocks (in grid order a 100-cell fput map
    said 49 s left at 36% where 13 s were)."""
    n = len(todo)
    place = {r: _spread(r) for r in range(n)}
    order = sorted(range(n), key=lambda r: (params.block_cost(*todo[r], arrays),
                                            -place[r]), reverse=True)
    return [todo[r] for r in order]


def _finer_tail(order: list, workers: int) -> list:
    """``order`` (blocks, longest first) with its last ``workers`` blocks split into single
    cells: a map ends when its last task does, and at its end each worker holds about one
    block, so a worker whose block ended early idled while another ran a whole block
    (a flexmm model map of 8 blocks on 2 workers: 0.23 s of its 1.5 s). Cells of one
    block then reach the store one at a time (part of a chunk each: the client writes
    them in turn, each cell with its checksum)."""
    n = min(max(int(workers), 0), len(order))
    if n == 0:
        return list(order)
    return list(order[:len(order) - n]) + [(i, [j]) for i, js in order[len(order) - n:]
                                           for j in js]


class MapCellError(ValueError):
    """A cell's simulation failed on a worker: the message names the cell, in one line."""


def _run_tasks(params, path, todo, n_todo, scheduler, workers, progress, log, arrays=None,
               timeout=20.0, estimate=None):
    from dask.distributed import as_completed

    from common.progress import progress_class
    tqdm = progress_class()

    from ._cluster import ClusterLost, Watchdog, connect, signals_held
    from ._progress import progress_lines

    # no bar (stderr a log file or a pipe): a plain line every 30 s at most, the first
    # after 10 s (a 100-cell map said nothing for minutes), counted from before the
    # cluster's start, as the estimate is (probe 97: the first line came 10 s after a
    # start-up of 13-50 s on a busy machine)
    lines = progress_lines(progress, n_todo,
                           "predicted" if params.theory_only else "simulated", estimate)
    if not scheduler and workers and workers > n_todo:
        # a worker more than the cells has nothing to do (probe 99: --workers 1000 on a
        # 4-cell map started 1000 processes on 2 cores, no answer in 60 s)
        log(f"map: {n_todo} cell(s) to compute: starting {n_todo} of the {workers} workers "
            "asked")
        workers = n_todo
    client, cluster = connect(scheduler, workers, timeout)
    writer = _CellWriter(path)
    report = progress if callable(progress) else None
    bar = tqdm(total=n_todo, unit="cell", desc="map",
               disable=True if report else None if progress is None else not progress)
    t0 = time.perf_counter()
    address = scheduler or "of this machine's LocalCluster"
    watch = Watchdog(client, scheduler or getattr(cluster, "scheduler_address", "local"),
                     timeout)

    def kept() -> str:
        n = int(arrays["done_predicted" if params.theory_only else "done"].sum()) \
            if arrays is not None else None
        total = int(np.prod(params.grid_shape))
        return (f"{n} of {total} cells are done and kept in {path}" if n
                else f"no cell is done yet ({path} holds the theories)")

    try:
        # longest first (fewer idle workers at the end of a map): dask runs the highest
        # priority first
        order = _finer_tail(_longest_first(params, todo, arrays),
                            sum(client.nthreads().values()))
        futures = [client.submit(params.task, params, i, js, not params.theory_only,
                                 retries=2, pure=False, priority=len(order) - rank)
                   for rank, (i, js) in enumerate(order)]
        cells = dict(zip(futures, order))
        finished = as_completed(futures)
        while not finished.is_empty():
            ready = finished.next_batch(block=False) if finished.has_ready() else []
            if not ready:
                # nothing finished: is the cluster still able to finish the map?
                if (why := watch.check()) is not None:
                    raise ClusterLost(f"{why}: {kept()}; the same command continues the map "
                                      "once the cluster works again") from None
                if lines is not None:
                    lines.tick()
                time.sleep(0.05)
                continue
            for fut in ready:
                try:
                    result = fut.result()
                except Exception as exc:  # one line naming the cell
                    from distributed.comm import CommClosedError

                    # the connection to the scheduler closed under the gather: the cluster
                    # failed, not the cell (the client may not know yet: status "running")
                    lost = isinstance(exc, (CommClosedError, ConnectionError))
                    if (why := f"lost the scheduler {address}" if lost or
                            client.status != "running" else watch.check()) is not None:
                        raise ClusterLost(f"{why}: {kept()}; the same command continues the "
                                          "map once the cluster works again") from None
                    i, js = cells[fut]
                    for f in futures:
                        f.cancel()
                    rows, cols = params.axis_values()
                    ydim, xdim = params.dims
                    raise MapCellError(
                        f"cells {ydim} = {rows[i]:g}, {xdim} = "
                        f"{', '.join(f'{cols[j]:g}' for j in js)}: "
                        f"{type(exc).__name__}: "
                        f"{str(exc).splitlines()[0] if str(exc) else ''}; {kept()}") from None
                # Ctrl-C or SIGTERM while a block is written: held until it is written
                # whole (a SIGTERM between its done flags and its checksums lost the cell
                # of a finished block: flagged, its checksum failed, computed again)
                with signals_held():
                    _write_block(path, params, result, arrays, writer)
                bar.update(len(result["js"]))
                if lines is not None:
                    lines.update(len(result["js"]))
                if report is not None:
                    report(len(result["js"]))
    finally:
        bar.close()
        from ._cluster import close

        close(client, cluster)
    log(f"{'predicted' if params.theory_only else 'simulated'} {plural(n_todo, 'cell')} in "
        f"{time.perf_counter() - t0:.2f} s")


#: the store's own names, and those it gathers (the map engine's internals under test:
#: tests/test_maps.py, bench/)
def cells_done(store, flag: str = "done", params=None) -> tuple[int, int] | None:
    """(cells done, cells) of the map store at ``store`` (a path), or None when it holds
    none or cannot be read (what an interrupted ``flexmm map`` reports it kept);
    ``flag``: the done flag counted ("done_predicted" for a theory-only map).
    ``params``: the map's parameters, to count only the cells whose checksum holds over
    its variables (what a resumed map keeps: a tampered cell flagged done is computed
    again, and its time estimated)."""
    try:
        import zarr

        # a garbled chunk is never decoded: what Blosc makes of it depends on the memory
        # beside it (_integrity.unsound_chunks)
        if unsound_chunks(Path(store) / flag):
            return None
        group = zarr.open_group(str(store), mode="r", use_consolidated=False)
        done = np.asarray(group[flag][...], bool)
        if params is not None:
            from ._integrity import verify
            from ._store_open import empty_dataset_names

            names = [n for n in empty_dataset_names(params) if n != CHECKSUM]
            done &= ~verify(Path(store), names, done.shape)[0]
        return int(done.sum()), int(done.size)
    except Exception:  # no store, or not readable: nothing to report
        return None


__all__ = ["open_or_create", "run_map", "MapCellError", "blocks", "simulate_block",
           "agreement", "tri_state", "theory_columns", "cells_done"]
