"""The map store opened: an existing one verified (its attributes, coordinates and every
cell's checksum; what is damaged repaired or marked to run again) or a new one written
beside and renamed into place. ``_store.run_map`` calls :func:`_open`."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from ._columns import MODEL_STORE_FORMAT, STORE_FORMAT
from ._integrity import CHECKSUM, consolidated_agrees, unsound_chunks
from ._params import MapParameters


def _write_new(path: Path, ds, params: MapParameters):
    """Write ``ds`` as the store at ``path``, beside and renamed into place: a failed
    write (disk full, Ctrl-C) leaves the previous store or none, never half of one."""
    import shutil

    chunks = (1, min(params.block, params.grid_shape[1]))  # one chunk per task block
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
    new one with the theory columns filled in (``overwrite``: discard the store there, this
    map's finished cells too, and start afresh; only a folder recognisably a map store,
    ``not_a_map_store``, is removed)."""
    return _open(path, params, overwrite, log)[0]


#: what a map store's folder holds besides its variables' folders (zarr v2's metadata)
_STORE_FILES = frozenset({".zgroup", ".zattrs", ".zmetadata"})


def not_a_map_store(path: Path) -> str | None:
    """Why the folder at ``path`` is not recognisably a map store (None where it is), the
    check before a store is removed: a folder (not a link) with zarr's ``.zgroup``, holding
    only zarr's metadata files and flat folders of files (a variable's chunks), among them
    a map's ``done``, ``done_predicted`` or ``checksum``. A damaged store (a garbled chunk
    or attribute file, a variable's metadata lost) still passes; a user's folder of other
    files, or one with subfolders, never does."""
    path = Path(path)
    if path.is_symlink():
        return "a symbolic link"
    if not path.is_dir():
        return "not a folder"
    if not (path / ".zgroup").is_file():
        return "no .zgroup: not a Zarr store"
    entries = list(path.iterdir())
    for entry in entries:
        if entry.name in _STORE_FILES and entry.is_file():
            continue
        if not entry.is_dir() or entry.is_symlink():
            return f"it holds {entry.name!r}, which a map store does not"
        inner = next((e for e in entry.iterdir() if e.is_dir() or e.is_symlink()), None)
        if inner is not None:
            return f"it holds {entry.name}/{inner.name}, a folder no map variable holds"
    if not {e.name for e in entries} & {"done", "done_predicted", CHECKSUM}:
        return "none of a map store's variables (done, done_predicted, checksum)"
    return None



def store_format_of(params) -> int:
    """The layout version a store of ``params`` is written in (a model map's, the paper
    chain's)."""
    return MODEL_STORE_FORMAT if hasattr(params, "lattice_model") else STORE_FORMAT


def _attrs_hold(attrs: dict, params: MapParameters) -> bool:
    return (attrs.get("store_format") == store_format_of(params)
            and all(attrs.get(n) == v for n, v in params.identity().items()))


def _inspect(path: Path, params: MapParameters):
    """What the store at ``path`` is, read piece by piece (a damaged piece named, never
    taken for another map): ("this", [damaged names]) when its attributes are this map's and
    its coordinates are this grid's or damaged; ("other", finished) when it holds another
    map (``finished``: cells done or predicted, None if unreadable); ("unreadable", why)
    when which map it holds cannot be read."""
    import json

    import zarr

    try:
        group = zarr.open_group(str(path), mode="r", use_consolidated=False)
        attrs = dict(group.attrs)
    except Exception as exc:  # a missing or garbled .zgroup/.zattrs
        first = str(exc).splitlines()[0] if str(exc) else type(exc).__name__
        return "unreadable", f".zgroup/.zattrs ({first[:100]})"

    def finished():
        try:
            if any(unsound_chunks(path / f) for f in ("done", "done_predicted")):
                return None
            return int(sum(np.asarray(group[f][...]).sum() for f in ("done", "done_predicted")
                           if f in group))
        except Exception:  # unreadable flags: unknown
            return None

    if not _attrs_hold(attrs, params):
        return "other", finished()
    damaged = []
    for name, values in params.store_coords().items():
        want = np.asarray(values, float)
        if name == "K_theta" and not (path / name).exists():  # written before it was stored
            damaged.append("K_theta (absent: written before it was a coordinate)")
            continue
        try:
            arr = group[name]
            if not _dims_named(arr, None):
                raise ValueError("no _ARRAY_DIMENSIONS: xarray cannot open it")
            whole = arr.nchunks_initialized == arr.nchunks
            if unsound_chunks(path / name):
                raise ValueError("a chunk's Blosc header does not match its file")
            got = np.asarray(arr[...], float)
        except Exception:  # missing metadata, a chunk that does not decode
            damaged.append(name)
            continue
        if not whole:
            damaged.append(name)
        elif not np.array_equal(got, want):
            return "other", finished()
    shape = params.grid_shape
    for name in empty_dataset_names(params):
        try:
            arr = group[name]
            if tuple(arr.shape) != shape or not _dims_named(arr, params.dims):
                raise ValueError
        except Exception:  # a variable's metadata missing or garbled
            damaged.append(name)
    try:
        meta = json.loads((path / ".zmetadata").read_text())["metadata"]
        if not isinstance(meta, dict) or not consolidated_agrees(path, meta, damaged):
            raise ValueError
    except Exception:  # what xr.open_zarr reads first, and all it reads (probe 97)
        damaged.append(".zmetadata")
    return "this", damaged


def _dims_named(arr, dims) -> bool:
    """Whether the zarr array ``arr`` names its dimensions as xarray needs
    (``_ARRAY_DIMENSIONS``: one name per axis; ``dims`` those names where given): a
    variable whose ``.zattrs`` was lost or garbled made ``xr.open_zarr`` raise KeyError,
    a traceback of the resumed map (probe 97)."""
    named = arr.attrs.get("_ARRAY_DIMENSIONS")
    return (isinstance(named, list) and len(named) == arr.ndim
            and all(isinstance(n, str) for n in named)
            and (dims is None or tuple(named) == tuple(dims)))


def _axes_differ(path: Path, params) -> str:
    """The axes of the store at ``path`` that differ from this map's, in words (its
    values, then this map's); "" where none differs or they cannot be read."""
    import zarr

    try:
        group = zarr.open_group(str(path), mode="r", use_consolidated=False)
    except Exception:  # unreadable: the caller names the map without them
        return ""

    def span(v):
        return f"{v.size} value{'s' * (v.size != 1)} {v.min():g} to {v.max():g}"

    said = []
    # the axes as the user gave them (not derived coordinates such as k_simulated)
    for name, values in zip(params.dims, params.axis_values()):
        want = np.asarray(values, float)
        try:
            if unsound_chunks(path / name):  # never decoded (_integrity.unsound_chunks)
                continue
            got = np.asarray(group[name][...], float)
        except Exception:  # another map's axes (other names) or unreadable: not compared
            continue
        if got.shape == want.shape and np.array_equal(got, want):
            continue
        if got.shape == want.shape and got.size and got.min() == want.min() \
                and got.max() == want.max():
            i = int(np.flatnonzero(got != want)[0])
            said.append(f"{name}: value {i + 1} is {got[i]:.6g} stored, {want[i]:.6g} asked")
        else:
            said.append(f"{name}: {span(got)} stored, {span(want)} asked")
    return "; ".join(said)


def _stored_attrs(path: Path) -> dict:
    """The store's attributes, or {} where they cannot be read."""
    import zarr

    try:
        return dict(zarr.open_group(str(path), mode="r", use_consolidated=False).attrs)
    except Exception:  # unreadable: the caller names the map without them
        return {}


def empty_dataset_names(params: MapParameters) -> list:
    """The data variables a store of ``params`` holds."""
    flags = params.flag_columns()
    return sorted({*(n for cols in flags.values() for n in cols), *flags, CHECKSUM,
                   *params.theory_names()})


def _checked(path: Path, params: MapParameters, overwrite: bool):
    """``_inspect``'s (what, detail), after refusing what only --overwrite may replace: an
    unreadable store, or another map with finished cells; ("discard", why) where
    ``overwrite`` discards the store (only one ``not_a_map_store`` recognises: else a
    ValueError, and nothing is removed)."""
    if overwrite and (path.exists() or path.is_symlink()):
        why = not_a_map_store(path)
        if why is not None:
            raise ValueError(f"{path} is not a map store ({why}): --overwrite removes only "
                             "a map store; move it away, or choose another --out")
        return "discard", None
    # without --overwrite this map's store is resumed, another map's or an unreadable one
    # refused
    try:
        what, detail = _inspect(path, params) if path.exists() else ("none", None)
    except Exception as exc:  # any other failure to read it: named, never a traceback
        first = str(exc).splitlines()[0][:100] if str(exc) else ""
        what, detail = "unreadable", f"{type(exc).__name__}{': ' * bool(first)}{first}"
    if what == "unreadable" and (why := not_a_map_store(path)) is not None:
        raise ValueError(f"{path} is not a map store ({why}); move it away, or choose "
                         "another --out")
    if what == "unreadable" and not overwrite:
        raise ValueError(f"{path}: damaged: {detail}; which map it holds cannot be read, so "
                         "nothing in it can be trusted; replace it with --overwrite, or "
                         "choose another --out")
    if what == "other" and detail != 0 and not overwrite:
        axes = _axes_differ(path, params)
        raise ValueError(f"{path} holds {params.other_map(_stored_attrs(path))}"
                         + (f" (its axes differ: {axes})" if axes else "")
                         + "; replace it with --overwrite, or choose another --out")
    return what, detail


def check_store(path: Path, params: MapParameters, overwrite: bool = False) -> None:
    """Refuse, before any work, a store at ``path`` that ``run_map`` would refuse (an
    unreadable one, another map with finished cells; ``overwrite`` allows both): the
    command says so before its estimate, not after it. Reads only the store's metadata,
    its coordinates and its done flags; changes nothing. A store another live process
    is writing (its lock held) is refused here too, with or without ``overwrite``."""
    from ._integrity import refuse_if_held

    refuse_if_held(Path(path))
    _checked(Path(path), params, overwrite)


def _open(path: Path, params: MapParameters, overwrite: bool = False, log=print):
    """``open_or_create``'s dataset (lazy) and its variables' values in memory, the store
    read once: on a 64 x 64 map each full read costs ~6 s (zarr reads 22 variables of 1 024
    chunks each), and the checksums' verification has read every variable already."""
    import xarray as xr

    def values(ds, raw=None):  # a derived variable (not a cell's) is read from the store
        return {n: (ds[n].values if raw is None or n not in raw else
                    np.asarray(raw[n], ds[n].dtype)) for n in ds.data_vars}

    old = path.with_name(f".{path.name}.old")
    if not path.exists() and not path.is_symlink() and old.is_dir():
        # a rebuild stopped between its two renames (_write_new: the store set aside, the
        # new one not yet in place): the store set aside is the map's, its cells kept
        old.rename(path)
        log(f"note: {path} restored from {old.name} (a rewrite of it was stopped between "
            "setting it aside and putting its successor in place)")
    what, detail = _checked(path, params, overwrite)
    if what == "discard":  # --overwrite: the user asked for the map afresh
        done = _finished_cells(path)
        log(f"--overwrite: {path} discarded"
            + (f" ({done} finished cell{'s' * (done != 1)} of its map)" if done else "")
            + "; the map is computed afresh")
    if what == "other" and detail == 0:  # no finished cell: nothing is lost by replacing it
        why = not_a_map_store(path)
        if why is not None:  # a Zarr group of the user's, say: never removed unasked
            raise ValueError(f"{path} is not a map store ({why}); move it away, or choose "
                             "another --out")
        log(f"note: {path} held another map with no finished cell (every cell failed, "
            "or none ran): replaced")
    if what == "this":
        ds = None
        if not detail:
            try:
                ds = xr.open_zarr(path, consolidated=False, chunks=None)
            except Exception as exc:  # noqa: BLE001 - metadata xarray cannot read: rebuilt
                detail = [f"xarray cannot open it ({type(exc).__name__})"]
        if detail:
            log(f"{path}: damaged: {', '.join(detail)}; rebuilt from this map's parameters, "
                "keeping every cell whose data and checksum survive")
            ds, raw = _verified(path, None, params, log, rebuild=True)
            return ds, values(ds, raw)
        ds, raw = _verified(path, ds, params, log)
        return ds, values(ds, raw)  # raw None: rewritten, read afresh
    ds = params.new_dataset()
    _write_new(path, ds, params)
    ds = xr.open_zarr(path, consolidated=False, chunks=None)
    return ds, values(ds)


def _finished_cells(path: Path) -> int:
    """The cells a store's ``done`` or ``done_predicted`` flags mark (0 where unreadable):
    what --overwrite discards, said."""
    import zarr

    try:
        group = zarr.open_group(str(path), mode="r", use_consolidated=False)
        flags = [np.asarray(group[f][...], bool) for f in ("done", "done_predicted")
                 if f in group and not unsound_chunks(path / f)]
        return int(np.logical_or.reduce(flags).sum()) if flags else 0
    except Exception:  # a damaged store: its count unknown, it is discarded all the same
        return 0


def _verified(path: Path, ds, params: MapParameters, log, rebuild: bool = False):
    """(ds, raw): ``ds`` if every cell matches its checksum, with the values read to check
    them (None when the store was rewritten); else (or ``rebuild``: its metadata is
    damaged) the store rewritten with the damaged cells' theory recomputed and their
    simulations marked not done (named). A theory column that cannot be read is taken
    from the recomputed theories (it is what they give), so the cells' own data decide."""
    import xarray as xr

    from ._integrity import CHECKSUM, cell_checksums, describe_cells, read_raw

    shape = params.grid_shape
    rows, cols = params.axis_values()
    theory_set = params.theory_names()
    names = [n for n in empty_dataset_names(params) if n != CHECKSUM]
    fresh = None
    raw, unreadable = {}, np.zeros(shape, bool)
    recomputed, theory_lost = [], np.zeros(shape, bool)
    for name in names + [CHECKSUM]:
        got, bad_cells = read_raw(path, [name], shape)
        if name in theory_set and (name not in got or bad_cells.any()):
            if fresh is None:
                fresh = params.new_dataset()
            value = np.asarray(got.get(name, fresh[name].values))
            got = {name: np.where(bad_cells, fresh[name].values, value).astype(
                fresh[name].dtype)}
            recomputed.append(name)
            theory_lost |= bad_cells
            bad_cells = np.zeros(shape, bool)
        raw.update(got)
        unreadable |= bad_cells
    if recomputed:
        log(f"{path}: damaged: {', '.join(recomputed)} at {int(theory_lost.sum())} of "
            f"{theory_lost.size} cells ({describe_cells(theory_lost, rows, cols, params.dims)})"
            ": recomputed from the map's parameters; the cells' simulations are kept where "
            "their checksums hold")
    if CHECKSUM in raw and all(n in raw for n in names):
        bad = unreadable | (cell_checksums({n: raw[n] for n in names})
                            != raw[CHECKSUM].astype(np.uint64))
    else:
        bad = np.ones(shape, bool)
    if not bad.any() and not rebuild and fresh is None:
        return ds, raw
    if bad.any():
        log(f"{path}: {int(bad.sum())} of {bad.size} cells fail their checksum or cannot be "
            f"read ({describe_cells(bad, rows, cols, params.dims)}): their theories are "
            "recomputed and their simulations run again")
    if fresh is None:
        fresh = params.new_dataset()
    for flag, columns in params.flag_columns().items():
        done = np.asarray(raw.get(flag, np.zeros(shape, bool)), bool) & ~bad
        for name in columns + (flag,):
            if name in raw:
                kept = np.where(done, raw[name].astype(fresh[name].dtype), fresh[name].values)
                fresh[name] = (fresh[name].dims, kept, fresh[name].attrs)
    fresh[CHECKSUM] = (fresh[CHECKSUM].dims,
                       cell_checksums({n: fresh[n].values for n in fresh.data_vars}),
                       fresh[CHECKSUM].attrs)
    _write_new(path, fresh, params)
    return xr.open_zarr(path, consolidated=False, chunks=None), None


__all__ = ["open_or_create", "empty_dataset_names", "not_a_map_store"]
