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
            row["growth_log_ratio"] = (
                math.log10(pred.growth_at(runs[0]["t_simulated"]) / runs[0]["growth"])
                if pred is not None and runs[0]["growth"] > 0 else float("nan"))
        rows.append(row)
    return {"i": i, "js": list(js), "rows": rows, "simulated": simulate}


# --- the store -------------------------------------------------------------------------------

#: the verdict columns are tri-state (int8): these codes, and no _FillValue (xarray would
#: decode an integer variable with one to float)
MI, STABLE, UNDETERMINED = 1, 0, -1
VERDICT_ATTRS = {"flag_values": [UNDETERMINED, STABLE, MI],
                 "flag_meanings": "undetermined stable MI"}
#: the variables a simulated block writes (with ``done`` and the checksum); every other
#: data variable is written once, when the store is made (the theories)
SIMULATED = ("verdict_simulated", "growth", "growth_field", "growth_q", "t_simulated",
             "peak_gain", "growth_log_ratio")
#: the variables every block writes (with ``done_predicted``), theory-only maps included
PREDICTED = ("growth_predicted", "verdict_predicted", "rate_predicted", "predicted_status")
#: version of the store's layout (tri-state verdicts, checksums), in its attributes
STORE_FORMAT = 2


def _simulated_columns(shape) -> dict:
    """The simulated variables and ``done`` of cells not simulated yet."""
    fl = lambda: np.full(shape, np.nan)  # noqa: E731
    return {
        "verdict_simulated": (np.full(shape, UNDETERMINED, np.int8),
                              {"long_name": f"simulation: grows more than {GROWTH_THRESHOLD:g}x "
                                            "within t_end", **VERDICT_ATTRS,
                               "undetermined": "not simulated yet (done = False)"}),
        "growth": (fl(), {"long_name": "largest growth factor over the run", "units": "1"}),
        "growth_field": (np.full(shape, -1, np.int8),
                         {"flag_values": [-1, 0, 1], "flag_meanings": "none theta U"}),
        "growth_q": (fl(), {"long_name": "wavenumber of the largest growth",
                            "units": "rad per site"}),
        "peak_gain": (fl(), {"long_name": "measured peak growth rate (linear-stage fit) where "
                                          "the simulation says MI",
                             "units": "1/T (lattice time)"}),
        "t_simulated": (fl(), {"units": "T (lattice time)"}),
        "done": (np.zeros(shape, bool), {"long_name": "cell simulated (the record of complete "
                                                      "cells; covered by checksum)"}),
        "growth_log_ratio": (fl(), {
            "long_name": "log10(predicted / measured growth) over the span simulated "
                         "(first seed)", "units": "1"}),
        "growth_predicted": (fl(), {
            "long_name": "growth factor the simulation measures, predicted: linear response "
                         "of the cell's own initial state (numerics.theory.predict_growth; "
                         "median over the seeds; NaN: undetermined, see predicted_status)",
            "units": "1"}),
        "verdict_predicted": (np.full(shape, UNDETERMINED, np.int8), {
            "long_name": f"predicted: grows more than {GROWTH_THRESHOLD:g}x within t_end",
            **VERDICT_ATTRS,
            "undetermined": "not predicted yet (done_predicted = False), or no linear theory "
                            "(predicted_status)"}),
        "rate_predicted": (fl(), {"long_name": "largest growth rate of the launched state's "
                                               "Hill modes", "units": "1/T (lattice time)"}),
        "predicted_status": (np.full(shape, -1, np.int8), {
            "flag_values": [-1] + list(PREDICTED_STATUS.values()),
            "flag_meanings": " ".join(["not_computed"] + [n.replace(" ", "_")
                                                          for n in PREDICTED_STATUS])}),
        "done_predicted": (np.zeros(shape, bool), {"long_name": "cell predicted"}),
    }


def _empty_dataset(params: MapParameters, theory: dict):
    import xarray as xr

    from ._integrity import CHECKSUM, CHECKSUM_ATTRS, cell_checksums

    shape = (len(params.delta), len(params.k))
    dims = ("delta", "k")
    data = {name: (dims, values, attrs)
            for name, (values, attrs) in _simulated_columns(shape).items()}
    for name, values in theory.items():
        theory_name = name.removeprefix("peak_gain_").removeprefix("verdict_")
        if name.startswith("peak_gain"):
            attrs = {"long_name": f"{theory_name} theory: peak growth rate (NaN: "
                                  "undetermined)", "units": "1/T (lattice time)"}
        else:
            attrs = {"long_name": f"{theory_name} theory: grows more than "
                                  f"{GROWTH_THRESHOLD:g}x within t_end", **VERDICT_ATTRS}
        if name in UNDETERMINED_REASONS:
            attrs["undetermined"] = UNDETERMINED_REASONS[name]
        data[name] = (dims, values, attrs)
    data[CHECKSUM] = (dims, cell_checksums({n: v[1] for n, v in data.items()}), CHECKSUM_ATTRS)
    coords = {"delta": ("delta", np.asarray(params.delta), {"long_name": "K_s - K_theta"}),
              "k": ("k", np.asarray(params.k), {"long_name": "k as requested",
                                                "units": "rad per site"}),
              "k_simulated": ("k", np.asarray(params.k_simulated),
                              {"long_name": "k snapped to 2 pi m / N: the wavenumber simulated "
                                            "and at which the theories are evaluated",
                               "units": "rad per site"})}
    return xr.Dataset(data, coords=coords, attrs={**params.attrs(), "store_format": STORE_FORMAT})


_NLS_REASON = ("the NLS coefficients are not finite there (delta = 0: g1 = 0, or a resonance "
               "k^2 = omega^2)")
_EXACT_REASON = ("no plane wave of this amplitude (harmonic balance finds no travelling wave "
                 "near a resonance of a harmonic with a lattice mode)")
#: why a theory column can be undetermined (NaN gain, verdict UNDETERMINED) at a cell
UNDETERMINED_REASONS = {f"{kind}_{name}": reason for kind in ("verdict", "peak_gain")
                        for name, reason in (("paper", _NLS_REASON),
                                             ("semidiscrete", _NLS_REASON),
                                             ("exact", _EXACT_REASON),
                                             ("exact_all", _EXACT_REASON))}


def tri_state(gain: np.ndarray, t_end: float) -> np.ndarray:
    """int8 verdicts from peak gains: MI, STABLE, or UNDETERMINED where the gain is NaN."""
    return np.where(np.isfinite(gain), np.where(grows_beyond_threshold(
        np.nan_to_num(gain), t_end), MI, STABLE), UNDETERMINED).astype(np.int8)


def theory_columns(params: MapParameters) -> dict:
    """The theories on the whole grid, batched (seconds): their raw peak gains, and their
    verdicts on the simulation's question: does the plane wave grow more than
    GROWTH_THRESHOLD-fold within t_end (peak gain > ln(threshold) / t_end)? Where a theory
    cannot be evaluated its gain is NaN and its verdict UNDETERMINED (the reason is the
    variable's ``undetermined`` attribute), never "stable"."""
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
        # g <= 0: stable, no gain; g or g1 not finite: undetermined (NaN), never "stable"
        defined = np.isfinite(g) & np.isfinite(g1)
        gains[name] = np.where(defined, np.where(g > 0, peak, 0.0), np.nan)
    # stability_map: NaN where there is no plane wave of this amplitude (undetermined)
    args = (K, D, params.case, params.alpha, params.K_s, params.amplitude, EXACT_OFFSETS)
    gains["exact_all"] = stability_map(*args, modes="all") if params.case == "coupled" \
        else None
    if params.start == "paper":
        # the exact theory of the state the map's runs start in: eq. `IC`'s launched state
        # (its free U waves pump bands of their own in case II), sampling-independent
        from ._resonance import resonance_map

        gains["exact"] = resonance_map(K, D, params.case, params.alpha, params.K_s,
                                       params.amplitude, start="paper")["peak_gain"]
    else:
        gains["exact"] = stability_map(*args)
    if gains["exact_all"] is None:
        gains["exact_all"] = gains["exact"]
    out = {}
    for name, gain in gains.items():
        out[f"verdict_{name}"] = tri_state(gain, params.t_end)
        out[f"peak_gain_{name}"] = gain
    return out


def _holds(ds, params: MapParameters) -> bool:
    """Does the stored dataset ``ds`` hold the map ``params`` defines (same grid, same
    parameters; theory_only aside, so a theory-only map is resumed by simulations)?"""
    return (np.array_equal(ds["delta"].values, params.delta)
            and np.array_equal(ds["k"].values, params.k)
            and ds.attrs.get("store_format") == STORE_FORMAT
            and all(ds.attrs.get(n) == v for n, v in params.attrs().items()
                    if n not in ("theory_only",)))


def _write_new(path: Path, ds, params: MapParameters):
    """Write ``ds`` as the store at ``path``, beside and renamed into place: a failed
    write (disk full, Ctrl-C) leaves the previous store or none, never half of one."""
    import shutil

    chunks = (1, min(params.block, len(params.k)))  # one chunk per task block
    tmp = path.with_name(f".{path.name}.partial")
    old = path.with_name(f".{path.name}.old")
    for p in (tmp, old):
        if p.exists():
            shutil.rmtree(p)
    try:
        # consolidated metadata, so that a user's xr.open_zarr(path) opens it without a
        # warning (region writes touch chunks only, so it stays valid)
        ds.to_zarr(tmp, mode="w", consolidated=True, zarr_format=2,
                   encoding={n: {"chunks": chunks} for n in ds.data_vars})
        if path.exists():
            path.rename(old)
        tmp.rename(path)
    finally:
        for p in (tmp, old):
            if p.exists():
                shutil.rmtree(p, ignore_errors=True)


def open_or_create(path: Path, params: MapParameters, overwrite: bool = False, log=print):
    """The store's dataset: an existing one with the same parameters (to resume; its
    checksums verified and what is damaged repaired or marked for simulation again), or a
    new one with the theory columns filled in (``overwrite``: replace a store that holds
    another map, or an unreadable one)."""
    import xarray as xr

    if path.exists():
        try:
            ds = xr.open_zarr(path, consolidated=False)
            ds.attrs  # noqa: B018 - metadata read
        except Exception as exc:  # noqa: BLE001 - any unreadable store
            if not overwrite:
                first = str(exc).splitlines()[0] if str(exc) else type(exc).__name__
                raise ValueError(f"{path} exists but its metadata is not readable ({first[:120]}"
                                 "); replace it with --overwrite, or choose another --out") \
                    from None
            ds = None
        if ds is not None and _holds(ds, params):
            return _verified(path, ds, params, log)
        if ds is not None and not overwrite:
            raise ValueError(f"{path} holds a map with other parameters (or of an older "
                             "format); replace it with --overwrite, or choose another --out")
    ds = _empty_dataset(params, theory_columns(params))
    _write_new(path, ds, params)
    return xr.open_zarr(path, consolidated=False)


def _verified(path: Path, ds, params: MapParameters, log):
    """``ds`` if every cell matches its checksum; else the store rewritten with the
    damaged cells' theory recomputed and their simulations marked not done (named)."""
    import xarray as xr

    from ._integrity import CHECKSUM, describe_cells, verify

    names = [n for n in ds.data_vars if n != CHECKSUM]
    for n in SIMULATED + PREDICTED + ("done", "done_predicted"):
        if n not in names:
            names.append(n)
    shape = (len(params.delta), len(params.k))
    bad, raw = verify(path, names, shape)
    if not bad.any():
        return ds
    log(f"{path}: {int(bad.sum())} of {bad.size} cells fail their checksum or cannot be "
        f"read ({describe_cells(bad, params.delta, params.k)}): their theories are "
        "recomputed and their simulations run again")
    fresh = _empty_dataset(params, theory_columns(params))
    for flag, columns in (("done", SIMULATED), ("done_predicted", PREDICTED)):
        done = np.asarray(raw.get(flag, np.zeros(shape, bool)), bool) & ~bad
        for name in columns + (flag,):
            if name in raw:
                kept = np.where(done, raw[name].astype(fresh[name].dtype), fresh[name].values)
                fresh[name] = (fresh[name].dims, kept, fresh[name].attrs)
    from ._integrity import cell_checksums

    fresh[CHECKSUM] = (fresh[CHECKSUM].dims,
                       cell_checksums({n: fresh[n].values for n in fresh.data_vars}),
                       fresh[CHECKSUM].attrs)
    _write_new(path, fresh, params)
    return xr.open_zarr(path, consolidated=False)


def _write_block(path: Path, params: MapParameters, result: dict, arrays: dict | None = None):
    """Write a finished block into the store (a region write of whole chunks): its
    predicted and simulated variables, their flags and the cells' checksums. ``arrays``: the store's values
    in memory (name -> array), updated here; read from the store when not given."""
    import xarray as xr

    from ._integrity import CHECKSUM, cell_checksums

    if arrays is None:
        with xr.open_zarr(path, consolidated=False) as ds:
            arrays = {n: ds[n].values for n in ds.data_vars}
    i, js = result["i"], result["js"]
    j0, j1 = min(js), max(js) + 1
    cells = (slice(i, i + 1), slice(j0, j1))
    region = {}
    for name in result["rows"][0]:
        arrays[name][cells] = np.array([[r[name] for r in result["rows"]]],
                                       dtype=arrays[name].dtype)
        region[name] = (("delta", "k"), arrays[name][cells])
    for flag in ("done_predicted",) + (("done",) if result["simulated"] else ()):
        arrays[flag][cells] = True
        region[flag] = (("delta", "k"), arrays[flag][cells])
    arrays[CHECKSUM][cells] = cell_checksums(arrays, cells)
    region[CHECKSUM] = (("delta", "k"), arrays[CHECKSUM][cells])
    # one write; a client killed in the middle of it leaves cells whose checksum does not
    # match, recomputed on resume (tests/test_cluster_faults.py kills it mid-map)
    xr.Dataset(region).to_zarr(path, consolidated=False,
                               region={"delta": slice(i, i + 1), "k": slice(j0, j1)})


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
            overwrite: bool = False, timeout: float = 20.0):
    """Compute (or resume) ``OUT/map.zarr``; returns the dataset (loaded). One writer at a
    time (``OUT/map.zarr.lock``); ``timeout``: seconds to reach ``scheduler``."""
    import xarray as xr

    from ._integrity import store_lock

    if scheduler:
        from ._cluster import probe

        probe(scheduler, timeout)  # before any work: a wrong address fails in seconds
    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    path = out / "map.zarr"
    with store_lock(path, log):
        ds = open_or_create(path, params, overwrite, log)
        arrays = {n: ds[n].values for n in ds.data_vars}
        # a theory-only map predicts its cells; a simulated one simulates (and predicts)
        done = arrays["done_predicted" if params.theory_only else "done"]
        what = "predict" if params.theory_only else "simulate"
        todo = blocks(params, done)
        n_cells, n_done = done.size, int(done.sum())
        if n_done:
            log(f"resuming {path}: {n_done} of {n_cells} cells already done (checksums "
                f"verified), {n_cells - n_done} to {what}")
        if todo:
            _run_tasks(params, path, todo, n_cells - n_done, scheduler, workers, progress,
                       log, arrays, timeout)
        return xr.open_zarr(path, consolidated=False).load()


class MapCellError(ValueError):
    """A cell's simulation failed on a worker: the message names the cell, in one line."""


def _run_tasks(params, path, todo, n_todo, scheduler, workers, progress, log, arrays=None,
               timeout=20.0):
    from dask.distributed import as_completed
    from tqdm.auto import tqdm

    from ._cluster import connect

    client, cluster = connect(scheduler, workers, timeout)
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
            _write_block(path, params, result, arrays)
            bar.update(len(result["js"]))
    finally:
        bar.close()
        from ._cluster import close

        close(client, cluster)
    log(f"{'predicted' if params.theory_only else 'simulated'} {n_todo} cells in "
        f"{time.perf_counter() - t0:.1f} s")


#: a theory's verdict is "marginal" at a cell when its predicted growth exp(sigma t_end) is
#: within this factor of the threshold: the noise's share in the unstable mode and the time
#: the linear stage takes to set in change the measured factor by about that much
MARGIN = 3.0


def agreement(ds, margin: float = MARGIN) -> dict:
    """Percent of the simulated cells where each theory's verdict equals the simulation's:
    over the cells where the theory is determined (``<name>_undetermined_cells`` says how
    many simulated cells it could not evaluate), and over those where it is not marginal
    either (its predicted growth over t_end not within ``margin`` of the threshold).

    "predicted" (the growth factor predicted from each cell's own initial state) is
    marginal where ``growth_predicted`` is within ``margin`` of the threshold.
    ``predicted_growth_within_2x``: percent of the cells whose measured growth lies in
    [2, 1000] where the predicted one is within 2x of it (over the same span:
    ``growth_log_ratio``), out of ``predicted_growth_cells``."""
    done = ds["done"].values
    sim = ds["verdict_simulated"].values.astype(np.int8)
    t_end, thr = float(ds.attrs["t_end"]), float(ds.attrs["growth_threshold"])
    names = [n.removeprefix("verdict_") for n in ds.data_vars
             if n.startswith("verdict_") and n != "verdict_simulated"
             and f"peak_gain_{n.removeprefix('verdict_')}" in ds.data_vars]
    out = {}

    def pct(v, m):
        return float(100 * np.mean(v[m] == sim[m])) if m.any() else float("nan")

    for name in names:
        v = ds[f"verdict_{name}"].values.astype(np.int8)
        gain = ds[f"peak_gain_{name}"].values
        determined = done & (v != UNDETERMINED)
        with np.errstate(invalid="ignore"):
            decided = determined & (np.abs(gain * t_end - math.log(thr)) > math.log(margin))
        out[name] = pct(v, determined)
        out[f"{name}_undetermined_cells"] = int((done & (v == UNDETERMINED)).sum())
        out[f"{name}_decided"] = pct(v, decided)
        out[f"{name}_decided_cells"] = int(decided.sum())
    if "verdict_predicted" in ds:
        v = ds["verdict_predicted"].values.astype(np.int8)
        growth = ds["growth_predicted"].values
        determined = done & (v != UNDETERMINED)
        with np.errstate(invalid="ignore", divide="ignore"):
            decided = determined & (np.abs(np.log(growth) - math.log(thr)) > math.log(margin))
        out["predicted"] = pct(v, determined)
        out["predicted_undetermined_cells"] = int((done & (v == UNDETERMINED)).sum())
        out["predicted_decided"] = pct(v, decided)
        out["predicted_decided_cells"] = int(decided.sum())
        measured, ratio = ds["growth"].values, ds["growth_log_ratio"].values
        with np.errstate(invalid="ignore"):
            mid = determined & (measured >= 2) & (measured <= 1000) & np.isfinite(ratio)
        out["predicted_growth_cells"] = int(mid.sum())
        out["predicted_growth_within_2x"] = (
            float(100 * np.mean(np.abs(ratio[mid]) <= math.log10(2))) if mid.any()
            else float("nan"))
    return out
