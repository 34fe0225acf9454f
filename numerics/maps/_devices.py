"""Where a map's cells are simulated: the device choice (cpu, gpu, auto) and the GPU path
of ``run_map``, which writes each block into the store as a Dask worker's would be."""

from __future__ import annotations

import time
from collections.abc import Callable
from dataclasses import dataclass

from ._cluster import signals_held
from ._store import _CellWriter, _write_block

DEVICES = ("cpu", "gpu", "auto")


def resolve_device(device: str, theory_only: bool = False, log=print,
                   scheduler: str | None = None) -> str:
    """'cpu' or 'gpu' for ``device`` ("cpu", "gpu" or "auto": the GPU where one is usable,
    never the CUDA simulator), or ValueError in one line: an unknown device, a GPU asked
    where there is none (the reason: no device, or the gpu extra missing), a GPU for a
    theory-only map (it runs no simulation) or with a ``scheduler`` (its workers simulate
    on their CPUs)."""
    from ._gpu import gpu_status, simulated

    if device not in DEVICES:
        raise ValueError(f"device must be one of {', '.join(DEVICES)}, got {device!r}")
    if device == "cpu":
        return "cpu"
    if theory_only:
        if device == "gpu":
            raise ValueError("--device gpu: a theory-only map runs no simulation (its "
                             "theories run on the CPU); drop --device or --theory-only")
        return "cpu"
    ok, why = gpu_status()
    if device == "gpu":
        if not ok:
            raise ValueError(f"--device gpu: {why}")
        if scheduler:
            raise ValueError("--device gpu runs on this machine's GPU: drop --scheduler (a "
                             "cluster's workers simulate on their CPUs)")
        return "gpu"
    use = ok and not simulated()
    log(f"device auto: {'GPU, ' + why if use else 'CPU (' + why + ')'}")
    return "gpu" if use else "cpu"


def device_attrs(device: str, scheduler: str | None) -> dict:
    """The store's record of where its last cells were simulated: ``device`` ("cpu" or
    "gpu") and ``device_name`` (the GPU's name, or the CPU's with the cluster's address).
    Not part of the map's identity: a store resumes on either device."""
    import platform

    if device == "gpu":
        from ._gpu import gpu_name

        return {"device": "gpu", "device_name": gpu_name()}
    cpu = platform.processor() or platform.machine()
    return {"device": "cpu", "device_name": f"{cpu}, Dask cluster {scheduler}" if scheduler
            else f"{cpu}, LocalCluster"}


#: cells simulated on the GPU in one launch (each a chain per seed; the launch's spectra
#: are bounded by simulate_cells_gpu's max_spectra_bytes too): enough to fill an H100's
#: SMs at N = 500, few enough that an interrupted map loses at most one batch
GPU_BATCH_CELLS = 4096


def _paper_rows(params, batch: list, theories: list, log=print) -> list:
    """The paper chain's blocks on the GPU: its theories (``predict_block``, computed on the
    CPU workers) and its cells in one launch of the fused flexMM kernel
    (``simulate_map_cells_gpu``)."""
    from ._blocks import simulated_row
    from ._gpu import simulate_map_cells_gpu

    sims = simulate_map_cells_gpu(params, [(i, j) for i, js in batch for j in js])
    out = []
    for (i, js), (rows, preds) in zip(batch, theories):
        for j, row, pred in zip(js, rows, preds):
            row.update(simulated_row(sims[(i, j, "runs")], pred))
        out.append((i, list(js), rows))
    return out


def _model_rows(params, batch: list, theories: list, log=print) -> list:
    """Any model's blocks on the GPU: its own kernel (the generated site force)."""
    from ._gpu_models import model_rows_gpu

    return model_rows_gpu(params, batch, log, theories=theories)


def _paper_theories(params, i: int, js: list):
    from ._blocks import predict_block

    return predict_block(params, i, js)


def _model_theories(params, i: int, js: list):
    from ._gpu_models import model_theories

    return model_theories(params, i, js)


@dataclass(frozen=True)
class DevicePath:
    """A map kind's GPU path: ``theories(params, i, js)``, a block's theories on a CPU (a
    task of the CPU workers: module-level, its result picklable), and
    ``rows(params, batch, theories, log)`` -> [(i, js, rows)], the blocks' store rows with
    their simulated columns from one GPU launch."""

    theories: Callable
    rows: Callable


#: the GPU path of each kind of map (a DevicePath). The paper flags' map (MapParameters)
#: runs today's fused flexMM kernel; a model's map (ModelMapParameters, the paper chain's
#: models included) its generated force's kernel
DEVICE_PATHS: dict = {}


def register_device_path(params_type: type, rows, theories=None) -> None:
    """Register the GPU path of the maps of ``params_type`` (see DEVICE_PATHS and
    DevicePath). Without ``theories``, ``rows(params, batch, log)`` computes the blocks'
    theories itself, in this process."""
    if theories is None:
        plain = rows

        def rows(params, batch, theories, log=print):  # noqa: ARG001
            return plain(params, batch, log)

        theories = _none_theories
    DEVICE_PATHS[params_type] = DevicePath(theories, rows)


def _none_theories(params, i, js):  # noqa: ARG001 - a path whose rows compute them
    return None


def device_path(params) -> DevicePath:
    """The GPU path of ``params``' map (``DEVICE_PATHS``), or ValueError in one line."""
    for kind in type(params).__mro__:
        if kind in DEVICE_PATHS:
            return DEVICE_PATHS[kind]
    raise ValueError(f"--device gpu: no GPU path for a map of {type(params).__name__}")


def _register_builtin() -> None:
    from ._model_params import ModelMapParameters
    from ._params import MapParameters

    register_device_path(MapParameters, _paper_rows, _paper_theories)
    register_device_path(ModelMapParameters, _model_rows, _model_theories)


_register_builtin()


#: a GPU map computes its blocks' theories on CPU workers (a LocalCluster) from this many
#: cells to do, unless ``workers`` says otherwise: a cell's theories cost ~0.1-0.3 s on
#: one core against ~1 ms of GPU time, so on one core they, not the GPU, set the pace
#: (measured: a 64 x 64 paper map, 4096 cells, 2 s on an H200, ~18 min of theories)
GPU_CLUSTER_MIN_CELLS = 32


def run_gpu(params, path, todo, n_todo, progress, log, arrays, workers=None, timeout=20.0):
    """The GPU path of run_map: blocks in batches of about GPU_BATCH_CELLS cells; the
    blocks' theories as tasks of this machine's CPU workers (a LocalCluster of ``workers``
    processes, all submitted at once so that they run while the GPU simulates; in this
    process for one worker or a small map, see GPU_CLUSTER_MIN_CELLS), each batch's
    simulations in one launch (the map's registered ``device_path``), then each block
    written (checksummed) as a worker's would be: an interrupted map keeps every batch
    written."""
    from common.progress import progress_class
    from common.text import plural
    tqdm = progress_class()

    from ._params import local_cores

    device = device_path(params)
    n_workers = workers or local_cores()
    on_cluster = n_workers > 1 and (workers is not None or n_todo >= GPU_CLUSTER_MIN_CELLS)
    writer = _CellWriter(path)
    report = progress if callable(progress) else None  # as run_map's CPU path
    bar = tqdm(total=n_todo, unit="cell", desc="map (GPU)",
               disable=True if report else None if progress is None else not progress)
    t0 = time.perf_counter()
    client = cluster = None
    try:
        if on_cluster:
            from ._cluster import connect

            client, cluster = connect(None, n_workers, timeout)
            # in the order the batches need them: dask runs the highest priority first
            futures = [client.submit(device.theories, params, i, js, pure=False, retries=1,
                                     priority=len(todo) - rank)
                       for rank, (i, js) in enumerate(todo)]
            log(f"device gpu: the cells' theories on {n_workers} CPU workers, their "
                "simulations on the GPU")

            def theories_of(first, batch):
                return client.gather(futures[first:first + len(batch)])
        else:
            def theories_of(first, batch):
                return [device.theories(params, i, js) for i, js in batch]

        batch: list = []
        first = 0
        for n, block in enumerate(todo):
            batch.append(block)
            if sum(len(js) for _, js in batch) < GPU_BATCH_CELLS and n + 1 < len(todo):
                continue
            theories = theories_of(first, batch)
            for i, js, rows in device.rows(params, batch, theories, log):
                with signals_held():  # a block written whole, as on the CPU path
                    _write_block(path, params, {"i": i, "js": js, "rows": rows,
                                                "simulated": True}, arrays, writer)
                bar.update(len(js))
                if report is not None:
                    report(len(js))
            first += len(batch)
            batch = []
    finally:
        bar.close()
        if client is not None:
            from ._cluster import close

            close(client, cluster)
    log(f"simulated {plural(n_todo, 'cell')} on the GPU in {time.perf_counter() - t0:.1f} s")
