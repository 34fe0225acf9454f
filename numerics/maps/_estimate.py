"""How long a map will take on this machine, said before it starts.

The estimate is the whole command's wall time: a fixed start-up (the command's imports, the
theory columns, the store, a LocalCluster's start and its workers' first imports, measured
here), plus the cells' predictions and simulations over the workers. The cells' costs come
from this machine's speed, measured once (one reference cell simulated and predicted,
about 1 s) and cached in ``~/.cache/flexmm-mi/speed.json``; the load average at the start
slows all of it down when the cores are shared.
"""

from __future__ import annotations

import json
import os
import platform
from dataclasses import dataclass
from pathlib import Path

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


def _cache_file() -> Path:
    root = os.environ.get("XDG_CACHE_HOME") or Path.home() / ".cache"
    return Path(root) / "flexmm-mi" / "speed.json"


def _key() -> str:
    import numpy

    return f"{platform.node()} {platform.machine()} py{platform.python_version()} " \
           f"numpy{numpy.__version__}"


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
    simulate_cell(mat, r["case"], k, r["N"], 10.0, **run)  # the kernels, loaded once
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


def load_slowdown(workers: int) -> tuple[float, float, int]:
    """(slowdown, load average, cores): how much slower the work runs because the cores
    are shared: (load - 1 + workers) / cores, at least 1 (this command counts as 1 of the
    load; its workers join it)."""
    cores = os.cpu_count() or 1
    try:
        load = os.getloadavg()[0]
    except OSError:
        load = 0.0
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

    def describe(self) -> str:
        return (f"start-up ~{self.startup * self.slowdown:.0f} s included"
                + (f"; load average {self.load:.1f} on {self.cores} cores counted"
                   if self.slowdown > 1 else ""))


def estimate_map(params, workers: int, scheduler: str | None = None,
                 speed: dict | None = None) -> MapEstimate:
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
    """
    from ..lattice import get_method

    speed = speed or machine_speed()
    workers = max(int(workers), 1)
    cells = len(params.k) * len(params.delta)
    scale_n = params.N / REFERENCE["N"]
    predict = cells * speed["predict"] * max(scale_n, 1.0) * (
        1.0 if params.start != "travelling" else TRAVELLING_SHARE)
    simulate = 0.0
    if not params.theory_only:
        method, dt = params.cell_step
        ref = get_method(REFERENCE["method"]).evaluations / REFERENCE["dt"]
        per_time = get_method(method).evaluations / dt / ref
        simulate = (cells * params.seeds * speed["simulate"] * per_time * scale_n
                    * params.t_end / REFERENCE["t_end"])
    startup = STARTUP_SECONDS["scheduler" if scheduler else "local"] + WORKER_WARMUP_SECONDS
    slowdown, load, cores = (1.0, float("nan"), 0) if scheduler else load_slowdown(workers)
    total = (startup + (predict + simulate) / workers) * slowdown
    return MapEstimate(total, startup, predict, simulate, slowdown, load, cores)


__all__ = ["MapEstimate", "estimate_map", "machine_speed", "measure_speed", "load_slowdown"]
