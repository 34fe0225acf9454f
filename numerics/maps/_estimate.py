"""How long a map will take on this machine, said before it starts.

The estimate is the whole command's wall time: a fixed start-up (the command's imports, the
theory columns, the store, a LocalCluster's start and its workers' first imports, measured
here), plus the cells' predictions and simulations over the workers. The paper chain's
cells' costs come from this machine's speed, measured once (one reference cell simulated
and predicted, about 1 s) and cached in ``~/.cache/flexmm-mi/speed.json``; a model's from
one of its cells measured before the work (:func:`probe_model_cell`; a model point's runs:
:func:`estimate_model_point`). Where the cores are shared, all of it slows down by the
share of a core a busy process gets at the start (:func:`cpu_share`, 0.2 s).
"""

from __future__ import annotations

import contextlib
import json
import math
import os
import platform
import warnings
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from common import paper

#: the command's fixed cost (imports, theory columns, store, cluster start and its workers'
#: first imports and kernels), fitted on this machine (2 cores, 2026-11-24): a simulated
#: 8-cell map at T = 1000 takes 7.1 s wall at load average 2 (2.4 s of it the cells), a
#: 1-cell theory-only map 8.8 s and an 8-cell one 13.7 s at load 3
STARTUP_SECONDS = {"local": 4.5, "scheduler": 2.0}
WORKER_WARMUP_SECONDS = 1.0
#: the reference cell the speed is measured on (N = 500, T = 1000, case II, srkn6b)
REFERENCE = dict(alpha=paper.ALPHA, K_s=paper.K_S, K_theta=paper.POINTS["blue"]["K_theta"],
                 case="coupled", N=paper.N, t_end=1000.0, method="srkn6b",
                 dt=0.7217454817376319)
#: a prediction for the travelling-wave start costs this share of the paper start's (no
#: torus to find first: PREDICT_SECONDS in _params, 0.15 s against 0.35 s)
TRAVELLING_SHARE = 0.15 / 0.35
#: the reference cell's k (``measure_speed``'s carrier)
REFERENCE_K = 0.73
#: the reference cell's prediction, warm (``measure_speed``), on the 2-core VM: what the
#: constants below are ratios to (2026-11-26)
REFERENCE_PREDICT_SECONDS = 0.057
#: a map cell's prediction costs this many times the reference cell's, typically: the 18
#: cells of a 3 x 6 paper-start map (N 500, T 5000, delta -0.003..0.003, k 0.5..1.5) took
#: 0.10-0.50 s, mean 0.20 s, warm, on the 2-core VM (their Bloch families and resonances,
#: which the reference cell at the paper's blue point has few of)
PREDICT_CELL_OVER_REFERENCE = 0.20 / REFERENCE_PREDICT_SECONDS
#: the theory columns (computed in the client, serially, before the tasks: the exact
#: theory's stability_map over EXACT_OFFSETS per cell) cost about this many times the
#: reference cell's prediction per cell: 0.03 s a cell on the 2-core VM (travelling start,
#: 32 and 128 cells; the paper start 0.012-0.015 s a cell), plus a fixed 0.25 s
THEORY_COLUMNS_PER_CELL = 0.03 / REFERENCE_PREDICT_SECONDS
THEORY_COLUMNS_FIXED = 0.25 / REFERENCE_PREDICT_SECONDS


def _predict_scale(k, N: int, start: str) -> float:
    """A cell's prediction cost over the reference cell's (N = 500, k = 0.73): its Bloch
    families grow with k N. Measured on the 2-core VM (N = 128 .. 1000, k = 0.3 .. 2.5): the
    travelling start's cost is linear in k N (at least a quarter of the reference's),
    the paper start's (a torus found first) about its square root."""
    x = np.asarray(k, float) * N / (REFERENCE_K * REFERENCE["N"])
    if start == "travelling":
        return float(np.mean(np.maximum(x, 0.25))) * TRAVELLING_SHARE
    return float(np.mean(np.sqrt(x)))


#: the version of ``measure_speed``'s measurement, part of the cache's key
SPEED_VERSION = 2


def _cache_file() -> Path:
    root = os.environ.get("XDG_CACHE_HOME") or Path.home() / ".cache"
    return Path(root) / "flexmm-mi" / "speed.json"


def _key() -> str:
    import numpy

    # SPEED_VERSION: a speed measured the old way (its prediction's compile counted) is
    # measured again
    return f"{platform.node()} {platform.machine()} py{platform.python_version()} " \
           f"numpy{numpy.__version__} v{SPEED_VERSION}"


def measure_speed() -> dict:
    """Seconds one core takes for the reference cell: ``simulate`` (its run, warm kernels)
    and ``predict`` (its growth prediction); measured now."""
    import time

    from ..lattice import Material, snap_wavenumber
    from ._cells import predict_cell, simulate_cell

    r = REFERENCE
    mat = Material(r["alpha"], r["K_s"], r["K_theta"])
    k = snap_wavenumber(0.73, r["N"])
    run = dict(method=r["method"], dt=r["dt"], early_stop=False)
    # the kernels of both, compiled or loaded once: on a machine whose numba cache is
    # empty the first prediction compiles them (2.3 s here, 3.7 s on a fresh H200 host,
    # against 0.055 s warm), which a cached speed then counted in every cell of every map
    simulate_cell(mat, r["case"], k, r["N"], 10.0, **run)
    predict_cell(mat, r["case"], k, r["N"], r["t_end"])
    t0 = time.process_time()
    simulate_cell(mat, r["case"], k, r["N"], r["t_end"], **run)
    t1 = time.process_time()
    predict_cell(mat, r["case"], k, r["N"], r["t_end"])
    t2 = time.process_time()
    return {"simulate": max(t1 - t0, 1e-3), "predict": max(t2 - t1, 1e-3)}


def machine_speed(refresh: bool = False) -> dict:
    """:func:`measure_speed`, measured once per machine and Python and cached."""
    path = _cache_file()
    key = _key()
    if not refresh:
        try:
            cached = json.loads(path.read_text())
            if cached.get("key") == key:
                return {"simulate": float(cached["simulate"]),
                        "predict": float(cached["predict"])}
        except (OSError, ValueError, KeyError, TypeError):
            pass
    speed = measure_speed()
    try:
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_text(json.dumps({"key": key, **speed}) + "\n")
    except OSError:  # a read-only home: measured again next time, no harm
        pass
    return speed


#: wall seconds the share probe spins (the scheduler's time slices are ~4 ms: 50 of them)
SHARE_PROBE_SECONDS = 0.2


#: (when, seconds, share) of the last probe: a command's estimates (its workers' slowdown
#: and its own) read one probe, not one each (0.2 s of spinning apiece)
_LAST_SHARE: list = [None]
#: how long a probe stands for the machine's state (seconds)
SHARE_REUSE_SECONDS = 2.0


def cpu_share(seconds: float = SHARE_PROBE_SECONDS) -> float:
    """The share of one core a busy thread of this process gets now: CPU time over wall
    time of a short spin, at most 1; the better of two halves (another process' burst of a
    few time slices is not the machine's state: both halves slow means the cores are
    shared). A probe of the same length within SHARE_REUSE_SECONDS is reused."""
    import time

    last = _LAST_SHARE[0]
    if last is not None and last[1] == seconds and time.monotonic() - last[0] < \
            SHARE_REUSE_SECONDS:
        return last[2]

    def spin(t):
        w0, c0 = time.perf_counter(), time.process_time()
        x = 0
        while time.perf_counter() - w0 < t:
            for i in range(2000):
                x += i
        return max(time.process_time() - c0, 1e-3) / (time.perf_counter() - w0)

    share = min(1.0, max(spin(seconds / 2), spin(seconds / 2)))
    _LAST_SHARE[0] = (time.monotonic(), seconds, share)
    return share


def load_slowdown(workers: int) -> tuple[float, float, int]:
    """(slowdown, load average, cores): how much slower the work runs because the cores
    are shared, measured now (:func:`cpu_share`). Where a busy thread gets less than a
    core, the cores are contended, and this command's processes (its workers are of its
    session) share what one of them gets (Linux' autogroup gives each session a fair
    part, whatever its thread count): ``workers / share``. Else, from the load average:
    (load - 1 + workers) / cores, at least 1 (this command counts as 1 of the load)."""
    cores = os.cpu_count() or 1
    try:
        load = os.getloadavg()[0]
    except OSError:
        load = 0.0
    share = cpu_share()
    if share < 0.9:
        return max(1.0, workers / share), load, cores
    return max(1.0, (max(load - 1.0, 0.0) + workers) / cores), load, cores


@dataclass(frozen=True)
class MapEstimate:
    """A map's expected wall time (``seconds``) and its parts (seconds, before the load's
    ``slowdown``)."""

    seconds: float
    startup: float
    predict: float
    simulate: float
    slowdown: float
    load: float
    cores: int
    #: the start-up's slowdown: the client alone is busy then (``slowdown``: its workers)
    startup_slowdown: float = 1.0

    def describe(self) -> str:
        return (f"start-up ~{self.startup * self.startup_slowdown:.0f} s included"
                + (f"; the cores shared (load average {self.load:.1f} on {self.cores}): "
                   f"{self.slowdown:.1f}x slower, counted" if self.slowdown > 1 else ""))


def estimate_map(params, workers: int, scheduler: str | None = None,
                 speed: dict | None = None, cells: int | None = None) -> MapEstimate:
    """Wall time of ``flexmm map`` for ``params`` (a MapParameters) on ``workers``.

    Parameters
    ----------
    params : MapParameters
    workers : int
        Worker processes the cells share.
    scheduler : str, optional
        A running scheduler's address (no cluster to start here).
    speed : dict, optional
        :func:`machine_speed`'s answer (measured and cached when not given).
    cells : int, optional
        The cells still to compute (a resumed map's); default every cell of the map.
    """
    from ..lattice import get_method

    speed = speed or machine_speed()
    workers = max(int(workers), 1)
    cells = len(params.k) * len(params.delta) if cells is None else int(cells)
    scale_n = params.N / REFERENCE["N"]
    predict = cells * speed["predict"] * PREDICT_CELL_OVER_REFERENCE * _predict_scale(
        params.k_simulated, params.N, params.start)
    simulate = 0.0
    if not params.theory_only:
        method, dt = params.cell_step
        ref = get_method(REFERENCE["method"]).evaluations / REFERENCE["dt"]
        per_time = get_method(method).evaluations / dt / ref
        simulate = (cells * params.seeds * speed["simulate"] * per_time * scale_n
                    * params.t_end / REFERENCE["t_end"])
    # the client's theory columns are part of the start-up: serial, before any task
    columns = speed["predict"] * (THEORY_COLUMNS_FIXED + THEORY_COLUMNS_PER_CELL * cells)
    startup = (STARTUP_SECONDS["scheduler" if scheduler else "local"] + WORKER_WARMUP_SECONDS
               + columns)
    slowdown, load, cores = (1.0, float("nan"), 0) if scheduler else load_slowdown(workers)
    alone = 1.0 if scheduler else load_slowdown(1)[0]  # the client's start-up
    total = startup * alone + (predict + simulate) / workers * slowdown
    return MapEstimate(total, startup, predict, simulate, slowdown, load, cores, alone)


@dataclass(frozen=True)
class ModelCellCost:
    """One cell of a model's map, measured on this machine (CPU seconds, one core).

    ``theory``: its theories (the NLS; with the ring the exact lattice and four-wave
    theories); ``run``: one seeded run of the ring over ``t_end`` (0 without runs);
    ``warmup``: what a fresh process spends before its first cell (imports, the model's
    compiled kernels); ``probe``: the wall time the measurement took."""

    theory: float
    run: float
    t_end: float
    warmup: float
    probe: float


#: CPU seconds a worker spends on its first cell of a model's map beyond the cell (imports,
#: the model's generated module and kernels): a fresh process pays 3.0-4.0 s (fput and
#: flexmm, NLS alone or with the exact theory; 2-core VM, 2026-11-26), a LocalCluster's
#: worker less, having preloaded the imports while the client worked (a whole 2 x 2
#: theory-only fput map takes 4.4-4.9 s): the middle. A simulated map's probe measures
#: the runs' compile on top (the client has not run the ring before)
MODEL_WORKER_WARMUP_SECONDS = 1.5
#: a probe run of the ring takes this many steps (~0.1 s for a two-field chain of 128
#: sites): enough that the timer's resolution and a time slice lost to another process
#: stay a few per cent of it
PROBE_STEPS = 4000


def probe_model_run(model, k: float, amplitude: float, branch=None, *, N: int, t_end: float,
                    wave=None, energy: bool = True) -> tuple[float, float]:
    """(CPU seconds of one run of ``t_end`` on the ring of ``N`` sites, CPU seconds of the
    first call's compile and load), measured: a short run (loads the kernels), then
    PROBE_STEPS steps timed, scaled to ``t_end`` (the run's cost is its steps' force
    evaluations; its 400 records are kept in the same proportion). ``energy``: whether the
    runs record the energy (a point's do; a map cell's do not, ``simulate_model``)."""
    import time

    from ..models import simulate_model, snap_ring, travelling_wave

    if wave is None:
        wave = travelling_wave(model, snap_ring(k, N)[0], amplitude, branch)
    t0 = time.process_time()
    # a ten-thousandth of T loads the kernels (T itself where that underflows: probe 99's
    # --t-end 5e-324 was refused as "t_end ... got 0.0", naming neither option nor value)
    first = simulate_model(model, k, amplitude, branch=branch, N=N,
                           t_end=t_end / 1e4 if t_end / 1e4 > 0 else t_end,
                           wave=wave, records=2, energy=energy)
    warm = time.process_time() - t0
    probe_t = min(t_end, PROBE_STEPS * first.dt)
    records = max(2, round(400 * probe_t / t_end))
    from ..lattice import BlowUpError

    t0 = time.process_time()
    try:
        simulate_model(model, k, amplitude, branch=branch, N=N, t_end=probe_t, wave=wave,
                       records=records, energy=energy)
    except BlowUpError:
        # the probe's steps outran the sidebands' saturation and the state left the
        # lattice's range (a softening bond past its barrier: soft-pi at k = pi, a = 0.3,
        # blew up at t = 272 of its 644, and the point ended in an error before its
        # table): time the run up to saturation, scaled by how far it got
        t0 = time.process_time()
        ran = simulate_model(model, k, amplitude, branch=branch, N=N, t_end=probe_t,
                             wave=wave, records=records, energy=energy,
                             until_saturated=True)
        probe_t = max(float(ran.t[-1]), first.dt)
    run = (time.process_time() - t0) * t_end / probe_t
    return run, max(warm - run / 1e4, 0.0)  # the first call ran 1e-4 of the run


#: the ring of the probe's warm-up call (its exact and four-wave theories, as a cell's)
WARMUP_RING = 16
#: a first cell cheaper than this many CPU seconds is followed by the other picks, timed
#: (what the first call still loaded, ~0.5 s, would dominate its time)
PROBE_MORE_BELOW = 2.0


def probe_model_cell(params) -> ModelCellCost:
    """One cell of the model map ``params`` (a ModelMapParameters), its middle one,
    measured here: its theories as a task computes them, and, for a simulated map, a
    short run of its ring (:func:`probe_model_run`; T as the task takes it: ``t_end`` or
    ``run_length`` of the cell's exact rate)."""
    import time

    from ..lattice import run_length
    from ..models import map_cells, saturation_time

    w0 = time.perf_counter()
    rows, cols = params.grid_shape
    # distinct cells (other parameter values cost a new model each): the middle, the
    # corners; the first timed also loads what a cell's theories need once
    picks = list(dict.fromkeys([(rows // 2, cols // 2), (0, 0), (rows - 1, cols - 1)]))
    cells = [(*params.cell(i, j), params.amplitude_at(i, j)) for i, j in picks]
    values, k, amplitude = cells[0]
    model = params.lattice_model.with_params(**values)  # the warm-up's

    def theories(values, k, amplitude):
        t0 = time.process_time()
        row = map_cells(params.lattice_model, [(values, k)], amplitude, params.branch_value,
                        exact=params.ring, simulate=False, N=params.N,
                        start=getattr(params, "start", "exact"),
                        lossy=getattr(params, "lossy", None))[0]
        return time.process_time() - t0, row

    t0 = time.process_time()  # the NLS alone first: the imports a worker pays once
    map_cells(model, [({}, k)], amplitude, params.branch_value, N=params.N)
    if params.ring:
        # the ring's theories on a small ring: their kernels compiled (an empty numba
        # cache: 33 s on a fresh H200 host, a cell 0.5 s) or loaded, which a worker pays
        # once; their types, not N, decide what compiles
        from energy import ModelError

        with contextlib.suppress(ModelError, ValueError, ArithmeticError):
            map_cells(model, [({}, k)], amplitude, params.branch_value, exact=True,
                      N=min(params.N, WARMUP_RING), start=getattr(params, "start", "exact"))
    warmup = time.process_time() - t0
    first, row = theories(*cells[0])
    rows = {0: row}  # each pick's theory row, as timed (the runs' T reads its rate)
    times = [first]
    if first < PROBE_MORE_BELOW:  # cheap cells: what the first still loaded would dominate
        timed = [theories(*c) for c in cells[1:]]
        rows.update({n + 1: r for n, (_, r) in enumerate(timed)})
        times = [t for t, _ in timed] or [theories(*cells[0])[0]]
        warmup += max(first - float(np.mean(times)), 0.0)
    theory = float(np.mean(times))
    run, t_end = 0.0, 0.0
    if not params.theory_only:
        from energy import ModelError

        start = getattr(params, "start", "exact")  # the runs' T follows their start's theory
        # the middle cell's run, else a corner's: a cell with no wave to run (Toda's exp
        # overflowing at amplitude 2000) or whose run blows up would count the runs as 0 s
        for n, (values, k, amplitude) in enumerate(cells):
            row = rows[n] if n in rows else theories(values, k, amplitude)[1]
            rate = row.get("peak_gain_exact" if start == "exact"
                           else f"peak_gain_{start}_start", math.nan)
            from numerics.models import time_scale
            t_end = (float(params.t_end) if params.t_end is not None
                     else run_length(rate, time_scale=time_scale(
                         params.lattice_model.with_params(**values))).t_end)
            try:
                # the solver's overflow at a cell with no wave is no warning of the map's
                with warnings.catch_warnings(), np.errstate(all="ignore"):
                    warnings.simplefilter("ignore", RuntimeWarning)
                    run, compile_s = probe_model_run(
                        params.lattice_model.with_params(**values), k, amplitude,
                        params.branch_value, N=params.N, t_end=t_end, energy=False)
            except (ModelError, FloatingPointError, ValueError):  # no wave here to run
                # (ValueError: scipy's least_squares on non-finite residuals at its start)
                run = 0.0
                continue
            warmup += compile_s
            # a cell's run stops once its linear stage saturated (until_saturated): the
            # cell's exact rate says about when
            run *= min(1.0, saturation_time(rate) / t_end) if t_end > 0 else 1.0
            break
    return ModelCellCost(theory, run, t_end, warmup, time.perf_counter() - w0)


#: a model map's end after its cells (summary, figure, cluster closed, interpreter exit):
#: 2.4 s wall at load 5 on the 2-core VM (1.2 s from the cells' line to 'wrote', 1.2 s to
#: the exit; probe 100), ~1 s of one core; it was not counted
MODEL_MAP_TAIL_SECONDS = 1.0


def estimate_model_map(params, workers: int, scheduler: str | None = None,
                       cost: ModelCellCost | None = None,
                       cells: int | None = None) -> MapEstimate:
    """Wall time of ``flexmm map --model`` for ``params`` (a ModelMapParameters) on
    ``workers``: the start-up (as the paper chain's, plus each worker's warm-up), and every
    cell at the measured cost of one (:func:`probe_model_cell`; measured when not given),
    over the workers, slowed by the load; ``cells``: how many are still to compute (a
    resumed map's; default every cell of the map).

    Returns
    -------
    MapEstimate
        ``predict``: the cells' theories, ``simulate``: their runs (CPU seconds, summed
        over the cells).
    """
    cost = cost or probe_model_cell(params)
    workers = max(int(workers), 1)
    cells = int(np.prod(params.grid_shape)) if cells is None else int(cells)
    theory = cells * cost.theory
    runs = 0.0 if params.theory_only else cells * params.seeds * cost.run
    startup = STARTUP_SECONDS["scheduler" if scheduler else "local"]
    # each worker's first cell, at once on every worker: its imports and compiled kernels
    # (the client's probe has loaded some of them before, so at least what a fresh
    # process pays)
    warmup = max(cost.warmup, MODEL_WORKER_WARMUP_SECONDS)
    slowdown, load, cores = (1.0, float("nan"), 0) if scheduler else load_slowdown(workers)
    alone = 1.0 if scheduler else load_slowdown(1)[0]  # the client's start-up
    # the summary, the figure and the cluster's close after the cells, in the client
    total = (startup + MODEL_MAP_TAIL_SECONDS) * alone \
        + (warmup + (theory + runs) / workers) * slowdown
    startup += warmup + MODEL_MAP_TAIL_SECONDS  # the fixed costs, the end among them
    return MapEstimate(total, startup, theory, runs, slowdown, load, cores, alone)



#: a point's figure and files (matplotlib's import and drawing), CPU seconds measured
#: (0.65-0.7 s on the 2-core VM)
POINT_FIGURE_SECONDS = 0.7


@dataclass(frozen=True)
class PointEstimate:
    """The rest of ``flexmm point --model --simulate`` once its theories are done
    (``seconds``, wall) and its parts (CPU seconds, before the load's ``slowdown``):
    ``theories`` still to compute (as given), one run of ``t_end`` (measured), the
    figure."""

    seconds: float
    theories: float
    run: float
    seeds: int
    t_end: float
    slowdown: float
    load: float
    cores: int
    at_most: bool = False  # t_end a lossy run's cap: it stops once A(t) has halved


def estimate_model_point(model, k: float, amplitude: float, branch=None, *, N: int,
                         seeds: int, t_end: float, theories: float = 0.0,
                         figure: bool = True, wave=None, at_most: bool = False
                         ) -> PointEstimate:
    """The wall time of a model point's runs and what follows them: ``seeds`` runs of
    ``t_end`` on the ring of ``N`` sites (one measured here, :func:`probe_model_run`; its
    kernels stay compiled for the runs), ``theories`` CPU seconds still to compute and the
    figure, slowed by the load."""
    run, _ = probe_model_run(model, k, amplitude, branch, N=N, t_end=t_end, wave=wave)
    slowdown, load, cores = load_slowdown(1)
    total = (theories + seeds * run + (POINT_FIGURE_SECONDS if figure else 0.0)) * slowdown
    return PointEstimate(total, theories, run, int(seeds), float(t_end), slowdown, load,
                         cores, at_most)


__all__ = ["MapEstimate", "estimate_map", "machine_speed", "measure_speed", "load_slowdown",
           "ModelCellCost", "probe_model_cell", "probe_model_run", "estimate_model_map",
           "PointEstimate", "estimate_model_point"]
