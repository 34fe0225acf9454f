"""On-disk cache of simulations, keyed by every parameter that affects them."""

from __future__ import annotations

import hashlib
import json
from pathlib import Path

import h5py

from derivation.files import atomic_write

from ._model import Material
from ._simulate import SIMULATOR_VERSION, Run, simulate

#: How many simulations actually ran in this process (cache misses); tests read it.
STATS = {"simulations": 0, "hits": 0}
_ARRAYS = ("t", "theta", "U", "theta_hat", "U_hat", "energy")
_SCALARS = ("N", "k", "m", "k_requested", "eps", "A0", "noise", "seed", "method", "dt",
            "t_end", "save_every", "store", "omega_model", "force_evaluations", "case")


def cache_key(params: dict) -> str:
    blob = json.dumps({"params": params, "simulator": SIMULATOR_VERSION}, sort_keys=True)
    return hashlib.sha256(blob.encode()).hexdigest()[:24]


def _save(path: Path, run: Run, params: dict):
    # atomic: an interrupted write leaves no cache entry
    with atomic_write(path, mode=None) as tmp, h5py.File(tmp, "w") as f:
        for name in _ARRAYS:
            arr = getattr(run, name)
            if arr is not None:
                f.create_dataset(name, data=arr, compression="gzip", compression_opts=1)
        for name in _SCALARS:
            f.attrs[name] = getattr(run, name)
        f.attrs["params"] = json.dumps(params, sort_keys=True)
        f.attrs["simulator_version"] = SIMULATOR_VERSION


def _load(path: Path, material: Material) -> Run:
    with h5py.File(path, "r") as f:
        arrays = {n: (f[n][()] if n in f else None) for n in _ARRAYS}
        s = {n: f.attrs[n] for n in _SCALARS}
    s = {n: (v.item() if hasattr(v, "item") else v) for n, v in s.items()}
    s = {n: (v.decode() if isinstance(v, bytes) else v) for n, v in s.items()}
    return Run(material=material, **arrays, **s)


def cached_simulate(cache_dir: Path | None, force: bool = False, **params) -> Run:
    """``simulate(**params)`` through the cache in ``cache_dir`` (None: no cache)."""
    mat = params["material"]
    key_params = dict(params, material=[mat.alpha, mat.K_s, mat.K_theta])
    key_params.pop("progress", None)
    if cache_dir is not None:
        cache_dir = Path(cache_dir)
        cache_dir.mkdir(parents=True, exist_ok=True)
        path = cache_dir / f"{cache_key(key_params)}.h5"
        if path.exists() and not force:
            try:
                run = _load(path, mat)
                STATS["hits"] += 1
                return run
            except (OSError, KeyError):
                path.unlink(missing_ok=True)  # corrupt entry: recompute
    STATS["simulations"] += 1
    run = simulate(**params)
    if cache_dir is not None:
        _save(path, run, key_params)
    return run
