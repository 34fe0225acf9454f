"""On-disk cache of simulations, keyed by every parameter that affects them."""

from __future__ import annotations

import hashlib
import json
from pathlib import Path

import h5py
import numpy as np

from common.files import atomic_write

from ._integrate import SimulationInterrupted
from ._model import LatticeState, Material
from ._run import RECORDS as _ARRAYS
from ._run import Run, joined
from ._simulate import resume, simulate
from ._version import SIMULATOR_VERSION

#: How many simulations actually ran in this process (cache misses); tests read it.
STATS = {"simulations": 0, "hits": 0, "checkpoints": 0}
_SCALARS = ("N", "k", "m", "k_requested", "amplitude", "noise", "seed", "method", "dt",
            "t_end", "save_every", "store", "start", "force_evaluations", "case")


def cache_key(params: dict) -> str:
    blob = json.dumps({"params": params, "simulator": SIMULATOR_VERSION}, sort_keys=True)
    return hashlib.sha256(blob.encode()).hexdigest()[:24]


def _checksum(arrays: dict) -> str:
    h = hashlib.sha256()
    for name in sorted(arrays):
        a = np.ascontiguousarray(arrays[name])
        h.update(f"{name}{a.dtype.str}{a.shape}".encode() + a.tobytes())
    return h.hexdigest()


def _write_run(path: Path, run: Run, params: dict, extra_arrays=None, extra_attrs=None):
    """One HDF5 file for a run (a cache entry or a checkpoint), written atomically: its
    records, its scalars, the key parameters and a checksum of every array."""
    arrays = {n: getattr(run, n) for n in _ARRAYS if getattr(run, n) is not None}
    arrays.update(extra_arrays or {})
    # atomic: an interrupted write leaves no entry
    with atomic_write(path, mode=None) as tmp, h5py.File(tmp, "w") as f:
        for name, arr in arrays.items():
            f.create_dataset(name, data=arr, compression="gzip", compression_opts=1)
        for name in _SCALARS:
            f.attrs[name] = getattr(run, name)
        for name, value in (extra_attrs or {}).items():
            f.attrs[name] = value
        f.attrs["params"] = json.dumps(params, sort_keys=True)
        f.attrs["simulator_version"] = SIMULATOR_VERSION
        f.attrs["checksum"] = _checksum(arrays)


def _read(path: Path) -> tuple[dict, dict]:
    """(arrays, plain attributes) of a file written by ``_write_run``; CorruptEntry when
    its arrays do not match their checksum."""
    with h5py.File(path, "r") as f:
        arrays = {n: f[n][()] for n in f}
        attrs = {n: f.attrs[n] for n in f.attrs}
    if attrs.pop("checksum", None) != _checksum(arrays):
        raise CorruptEntry("checksum mismatch")
    attrs = {n: (v.item() if hasattr(v, "item") else v) for n, v in attrs.items()}
    return arrays, {n: (v.decode() if isinstance(v, bytes) else v) for n, v in attrs.items()}


class CorruptEntry(Exception):
    """A cache entry that is unreadable, altered or inconsistent: it is recomputed."""


def _load(path: Path, material: Material) -> Run:
    arrays, attrs = _read(path)
    run = Run(material=material, **{n: arrays.get(n) for n in _ARRAYS},
              **{n: attrs[n] for n in _SCALARS})
    _check_shapes(run)
    return run


def _check_shapes(run: Run):
    nt = run.t.shape[0]
    expect = {"energy": (nt,), "theta": (nt, run.N), "U": (nt, run.N),
              "theta_hat": (nt, run.N // 2 + 1), "U_hat": (nt, run.N // 2 + 1)}
    for name, shape in expect.items():
        arr = getattr(run, name)
        if arr is not None and arr.shape != shape:
            raise CorruptEntry(f"{name} has shape {arr.shape}, expected {shape}")
    if not (nt >= 2 and abs(run.t[-1] - run.t_end) <= 1e-9 * run.t_end):
        raise CorruptEntry("records do not reach t_end")


def cached_simulate(cache_dir: Path | None, force: bool = False, **params) -> Run:
    """``simulate(**params)`` through the cache in ``cache_dir`` (None: no cache).

    An interrupted run (Ctrl-C) is checkpointed as ``KEY.partial.h5`` (its records and the
    state it stopped at) before the interrupt propagates; the next call with the same
    parameters resumes from it (``numerics.resume``) instead of starting over.
    """
    mat = params["material"]
    key_params = dict(params, material=[mat.alpha, mat.K_s, mat.K_theta])
    key_params.pop("progress", None)
    if cache_dir is None:
        STATS["simulations"] += 1
        return simulate(**params)
    cache_dir = Path(cache_dir)
    cache_dir.mkdir(parents=True, exist_ok=True)
    key = cache_key(key_params)
    path, partial = cache_dir / f"{key}.h5", cache_dir / f"{key}.partial.h5"
    if path.exists() and not force:
        try:
            run = _load(path, mat)
            STATS["hits"] += 1
            return run
        except (OSError, KeyError, ValueError, TypeError, CorruptEntry):
            path.unlink(missing_ok=True)  # corrupt or altered entry: recompute
    STATS["simulations"] += 1
    checkpoint = None if force else _load_checkpoint(partial, mat)
    try:
        run = resume(checkpoint, **params) if checkpoint else simulate(**params)
    except SimulationInterrupted as exc:
        if checkpoint:  # the resumed part was interrupted in turn: merge the two parts
            exc = _merged(checkpoint, exc)
        _save_checkpoint(partial, exc, key_params)
        STATS["checkpoints"] += 1
        exc.checkpoint = partial  # where it was kept (the CLI's message says so)
        raise exc from None
    _write_run(path, run, key_params)
    partial.unlink(missing_ok=True)
    return run


def _save_checkpoint(path: Path, exc: SimulationInterrupted, params: dict):
    s = exc.state
    fields = {"state_theta": s.theta, "state_theta_dot": s.theta_dot}
    if s.U is not None:
        fields.update(state_U=s.U, state_U_dot=s.U_dot)
    _write_run(path, exc.run, params, fields,
               {f"interrupt_{n}": getattr(exc, n) for n in _INTERRUPT})


_INTERRUPT = ("time", "remaining", "dt", "record_phase")


def _load_checkpoint(path: Path, material: Material):
    """The SimulationInterrupted saved in ``path``, or None (absent or unusable)."""
    if not path.exists():
        return None
    try:
        data, attrs = _read(path)
        state = LatticeState(data.get("state_U"), data.get("state_U_dot"),
                             data["state_theta"], data["state_theta_dot"])
        run = Run(material=material, **{n: data.get(n) for n in _ARRAYS},
                  **{n: attrs[n] for n in _SCALARS}, completed=False)
        return SimulationInterrupted("checkpoint", run=run, state=state,
                                     **{n: attrs[f"interrupt_{n}"] for n in _INTERRUPT})
    except (OSError, KeyError, ValueError, TypeError, CorruptEntry):
        path.unlink(missing_ok=True)
        return None


def _merged(first: SimulationInterrupted, second: SimulationInterrupted):
    """One interruption from two: the first's records, then the resumed part's."""
    run = joined(first.run, second.run, first.time, completed=False)
    return SimulationInterrupted("interrupted", run=run, state=second.state,
                                 time=first.time + second.time, remaining=second.remaining,
                                 dt=second.dt, record_phase=second.record_phase,
                                 signum=second.signum)
