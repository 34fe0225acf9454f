"""A map store you can trust: a checksum per cell over every variable the store holds,
verified on resume; one writer at a time (a lock file naming its holder).

Checksums. ``checksum`` (uint64, dims delta x k, chunked like every variable, so one per
cell of each block) is a BLAKE2b digest of the cell's values in *all* the store's data
variables but itself, in name order. It is generic: a variable added to the store (a new
theory column) is covered without a change here. The ``done`` variable is the record of
complete cells; it is covered too. A deleted chunk reads as its fill value, an overwritten
or truncated one as other values or an error: either way the cell's digest differs, and
:func:`verify` names it.

Lock. ``OUT/map.zarr.lock`` holds host, pid, start time and command of the writer; the
holder touches it every HEARTBEAT seconds. Another command refuses to write while it is
held, naming the holder; a lock whose process is gone (same host) or that was not touched
for STALE_SECONDS (another host) is stale and taken over, with a note.
"""

from __future__ import annotations

import contextlib
import hashlib
import json
import math
import os
import socket
import sys
import threading
import time
from pathlib import Path
from typing import NamedTuple

import numpy as np

CHECKSUM = "checksum"
CHECKSUM_ATTRS = {
    "long_name": "BLAKE2b-64 digest of the cell's values in every other data variable "
                 "(name order; bool as uint8, integers as int64, floats as float64 with "
                 "one NaN); verified on resume",
}
#: seconds between two touches of the lock by its holder
HEARTBEAT = 10.0
#: a lock of another host not touched for this long is stale (12 missed heartbeats)
STALE_SECONDS = 120.0
#: a lock file without a record, younger than this, is a writer's between its creation and
#: its record (microseconds apart; seconds on a loaded machine): held, not foreign
FRESH_SECONDS = 5.0


def _canonical(a: np.ndarray) -> np.ndarray:
    a = np.asarray(a)
    if a.dtype == bool:
        return a.astype(np.uint8)
    if a.dtype.kind in "iu":
        return a.astype("<i8")
    if a.dtype.kind == "f":
        out = a.astype("<f8")
        out[np.isnan(out)] = np.nan  # one NaN bit pattern
        return out
    raise TypeError(f"cannot checksum a variable of dtype {a.dtype}")


def cell_checksums(arrays: dict, cells=None) -> np.ndarray:
    """uint64 digest per cell over ``arrays`` (name -> (n_delta, n_k) values), all names
    but CHECKSUM; ``cells``: an index (tuple of slices) to digest a part only."""
    names = sorted(n for n in arrays if n != CHECKSUM)
    parts = []
    for n in names:
        a = np.asarray(arrays[n])
        a = a if cells is None else a[cells]
        c = _canonical(a)
        parts.append(np.ascontiguousarray(c).view(np.uint8).reshape(c.shape + (-1,)))
    shape = parts[0].shape[:-1]
    rows = np.concatenate(parts, axis=-1).reshape(-1, sum(p.shape[-1] for p in parts))
    salt = ",".join(names).encode()
    out = np.fromiter((int.from_bytes(hashlib.blake2b(salt + r.tobytes(), digest_size=8)
                                      .digest(), "little") for r in rows),
                      dtype=np.uint64, count=len(rows))
    return out.reshape(shape)


class ZarrayMeta(NamedTuple):
    """The fields of a zarr v2 array's ``.zarray`` that the store's readers and its writer
    act on: ``compressor`` and ``filters`` as stored (a codec's config dict, or None),
    ``dtype`` and ``chunks`` decoded, ``fill_value`` decoded as the v2 format writes a
    float's ("NaN", "Infinity", "-Infinity"; None stays None: no fill given)."""

    zarr_format: object
    compressor: dict | None
    filters: list | None
    order: object
    dtype: np.dtype
    chunks: tuple
    fill_value: object
    separator: str


#: the v2 format's JSON spelling of the floats JSON has no literal for
_FLOAT_FILLS = {"NaN": math.nan, "Infinity": math.inf, "-Infinity": -math.inf}


def read_zarray(array_dir: Path) -> ZarrayMeta | None:
    """The ``.zarray`` of the zarr v2 array at ``array_dir``, or None when it cannot be read
    or is malformed (no such file, not JSON, a dtype or chunk shape that does not parse, a
    compressor that is not a codec's config): the one reader of it, for the chunk checks
    (:func:`unsound_chunks`) and the client's own chunk writes (``_store._CellWriter``),
    each of which then leaves such an array to zarr, whose own read says what is wrong."""
    try:
        meta = json.loads((array_dir / ".zarray").read_text())
        compressor = meta.get("compressor")
        if compressor is not None and not isinstance(compressor, dict):
            return None
        fill = meta.get("fill_value")
        return ZarrayMeta(
            zarr_format=meta.get("zarr_format"), compressor=compressor,
            filters=meta.get("filters"), order=meta.get("order"),
            dtype=np.dtype(meta["dtype"]), chunks=tuple(int(n) for n in meta["chunks"]),
            fill_value=_FLOAT_FILLS.get(fill, fill) if isinstance(fill, str) else fill,
            separator=meta.get("dimension_separator", "."))
    except Exception:  # noqa: BLE001 - any malformed metadata: the caller leaves it to zarr
        return None


def unsound_chunks(array_dir: Path) -> set:
    """The chunk keys of the zarr v2 array at ``array_dir`` ("i.j") whose Blosc frame does
    not match the file: a damaged chunk, never handed to the decoder, because Blosc trusts
    the offsets in its frame and reads past the end of a garbled buffer (numcodecs#228),
    which makes the error it raises (KeyError, MemoryError for a header that asks for
    1.7 GB, or values) depend on the memory beside it. Checked: the format version, stored
    size = file size, decompressed size = the chunk's, a block size in [1, that size], and
    either a copied chunk (16 header bytes + the data) or every block's start inside the
    file after the table of starts. Empty for other codecs, and when the metadata cannot be
    read (the caller's read fails and says so)."""
    meta = read_zarray(array_dir)
    if meta is None or (meta.compressor or {}).get("id") != "blosc" or meta.filters:
        return set()
    want = int(meta.dtype.itemsize * np.prod(meta.chunks))
    bad = set()
    for f in array_dir.iterdir():
        if f.name.startswith("."):
            continue
        try:
            frame = f.read_bytes()
        except OSError:
            bad.add(f.name)
            continue
        if not _sound_blosc_frame(frame, want):
            bad.add(f.name)
    return bad


def _sound_blosc_frame(frame: bytes, want: int) -> bool:
    """Whether ``frame`` is a Blosc 1 frame of ``want`` bytes that the decoder can read
    without leaving it (c-blosc's frame layout: 16 header bytes, then a copy of the data
    when flag 0x02 is set, else one uint32 start per block and the blocks)."""
    if len(frame) < 16 or frame[0] not in (1, 2, 3, 4):
        return False
    flags = frame[2]
    nbytes, blocksize, cbytes = (int.from_bytes(frame[i:i + 4], "little") for i in (4, 8, 12))
    if nbytes != want or cbytes != len(frame) or not 1 <= blocksize <= max(nbytes, 1):
        return False
    if flags & 0x02:  # copied, not compressed
        return cbytes == nbytes + 16
    nblocks = -(-nbytes // blocksize)
    table = 16 + 4 * nblocks
    if table > cbytes:
        return False
    starts = np.frombuffer(frame, "<u4", count=nblocks, offset=16)
    return bool(np.all((starts >= table) & (starts < cbytes)))


def consolidated_agrees(path: Path, meta: dict, damaged=()) -> bool:
    """Whether ``meta`` (the ``metadata`` of the store's ``.zmetadata``) is the store's
    metadata files, each entry equal to its file and every file entered: ``xr.open_zarr``
    reads the consolidated copy alone, so a flipped byte there ("<f8" read as "<f4") made
    the user's read of a verified store fail, or read other values, while the engine,
    which reads the files, resumed it (probe 97). Entries of the variables in ``damaged``
    (named damaged already: a deleted .zarray, a lost variable) are not compared: the
    rebuild rewrites them, and the store's report names their variable, not .zmetadata."""
    skip = set(damaged)
    entered = set()
    for f in [*path.glob(".z*"), *path.glob("*/.z*")]:  # the store's folders are flat
        key = f.relative_to(path).as_posix()
        if key == ".zmetadata" or key.split("/")[0] in skip:
            continue
        if key not in meta or json.loads(f.read_text()) != meta[key]:
            return False
        entered.add(key)
    return entered == {key for key in meta if key.split("/")[0] not in skip}


def read_raw(path: Path, names, shape) -> tuple[dict, np.ndarray]:
    """The store's variables ``names`` as stored, and a mask of the cells that could not
    be read (a missing variable, a chunk that does not decode): those get a value no
    digest matches."""
    import zarr

    unreadable = np.zeros(shape, bool)
    out = {}
    try:
        group = zarr.open_group(str(path), mode="r", use_consolidated=False)
    except Exception:  # no readable group: nothing can be trusted
        return {}, np.ones(shape, bool)
    for name in names:
        try:
            arr = group[name]
            if tuple(arr.shape) != tuple(shape):
                raise ValueError("shape")
        except Exception:  # a missing or malformed variable
            unreadable[:] = True
            continue
        garbled = unsound_chunks(Path(path) / name)
        if not garbled:
            try:
                out[name] = np.asarray(arr[...])
                continue
            except Exception:  # some chunk is damaged: read them one by one
                pass
        values = np.zeros(shape, arr.dtype)
        ci, cj = arr.chunks
        for i0 in range(0, shape[0], ci):
            for j0 in range(0, shape[1], cj):
                idx = (slice(i0, i0 + ci), slice(j0, j0 + cj))
                if f"{i0 // ci}.{j0 // cj}" in garbled:
                    unreadable[idx] = True
                    continue
                try:
                    values[idx] = arr[idx]
                except Exception:  # this chunk only
                    unreadable[idx] = True
        out[name] = values
    return out, unreadable


def verify(path: Path, names, shape) -> tuple[np.ndarray, dict]:
    """(bad, raw): a mask of the cells whose values do not match their stored checksum or
    could not be read, and the raw values read (``names``: the data variables expected)."""
    raw, unreadable = read_raw(path, list(names) + [CHECKSUM], shape)
    if CHECKSUM not in raw or any(n not in raw for n in names):
        return np.ones(shape, bool), raw
    digest = cell_checksums({n: raw[n] for n in names})
    bad = unreadable | (digest != raw[CHECKSUM].astype(np.uint64))
    return bad, raw


def describe_cells(mask: np.ndarray, delta, k, dims=("delta", "k"), most: int = 4) -> str:
    """'delta = .., k = ..; ...' for the first ``most`` cells of ``mask`` (and how many
    more); ``dims``: the names of the rows and the columns."""
    ii, jj = np.nonzero(mask)
    shown = "; ".join(f"{dims[0]} = {delta[i]:g}, {dims[1]} = {k[j]:g}"
                      for i, j in zip(ii[:most], jj[:most]))
    return shown + (f"; and {len(ii) - most} more" if len(ii) > most else "")


# --- the lock ------------------------------------------------------------------------------

class StoreLocked(ValueError):
    """Another process writes this store (one line naming it and the lock file)."""


def _alive(pid: int) -> bool:
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except PermissionError:
        return True
    return True


#: how every lock record of ours begins (``store_lock``'s json.dumps of a dict whose first
#: key is "host"): a file that is empty or a prefix of it may be a record being written
RECORD_START = b'{"host": '


def lock_holder(lock: Path) -> dict | None:
    """The lock's record, with ``stale`` (True when its holder is gone), or None."""
    try:
        data = lock.read_bytes()
        age = time.time() - lock.stat().st_mtime
    except FileNotFoundError:
        return None
    except OSError as exc:  # a folder, no permission: named, not a traceback
        raise StoreLocked(f"cannot read the lock file {lock} ({exc.strerror or exc}); remove "
                          "it if no map is being written there") from None
    try:
        info = json.loads(data.decode("utf-8"))
        host, pid = str(info["host"]), int(info["pid"])
    except (ValueError, KeyError, TypeError, AttributeError):
        # not a record of ours: a torn write whose writer died mid-way, or a foreign file,
        # nobody holding it; but a lock younger than FRESH_SECONDS that is empty or the
        # start of a record may be one a live writer has created and not yet written
        # (O_EXCL, then the record): taken over, two maps wrote one store (probe 97). A
        # file no writer of ours makes (bytes 0..255, a JSON list) is replaced at any age
        writing = RECORD_START.startswith(data[:len(RECORD_START)])
        return {"host": "?", "pid": -1, "since": "just now",
                "stale": age > FRESH_SECONDS or not writing,
                "age": age, "foreign": True, "bytes": data}
    same_host = host == socket.gethostname()
    stale = (not _alive(pid)) if same_host else age > STALE_SECONDS
    return {"since": "an unknown time", **info, "host": host, "pid": pid, "stale": stale,
            "age": age, "bytes": data}


def _held(store: Path, lock: Path, holder: dict) -> str:
    if holder.get("foreign"):
        return (f"{store}: its lock {lock} was created {holder['age']:.1f} s ago and holds "
                "no record yet (another map starting on it?); wait a few seconds and run "
                "the command again: it continues the map, or says who holds it")
    return (f"{store} is being written by pid {holder['pid']} on {holder['host']} since "
            f"{holder['since']} (lock {lock}); wait for it to finish, or stop it: the same "
            "command then continues its map")


def refuse_if_held(store: Path) -> None:
    """StoreLocked where a live process holds ``STORE.lock`` now: the map commands ask
    before their estimate (a second map on the same OUT measured a cell and estimated its
    map, seconds, before ``store_lock`` refused it); ``store_lock`` still decides."""
    lock = store.with_name(store.name + ".lock")
    holder = lock_holder(lock)
    if holder is not None and not holder["stale"]:
        raise StoreLocked(_held(store, lock, holder))


@contextlib.contextmanager
def store_lock(store: Path, log=print):
    """Hold ``STORE.lock`` while writing ``store``; StoreLocked if a live process holds it."""
    lock = store.with_name(store.name + ".lock")
    record = json.dumps({"host": socket.gethostname(), "pid": os.getpid(),
                         "since": time.strftime("%Y-%m-%d %H:%M:%S %Z"),
                         "command": " ".join(sys.argv)[:300]})
    for _ in range(3):
        try:
            fd = os.open(lock, os.O_CREAT | os.O_EXCL | os.O_WRONLY, 0o644)
        except FileExistsError:
            holder = lock_holder(lock)
            if holder is None:
                continue  # released meanwhile
            if not holder["stale"]:
                raise StoreLocked(_held(store, lock, holder)) from None
            if holder.get("foreign"):
                log(f"note: replaced the lock file {lock}: it holds no flexmm lock record "
                    "(a torn write, or a file of something else), so nobody holds it")
            else:
                log(f"note: took over the stale lock {lock} of pid {holder['pid']} on "
                    f"{holder['host']} (since {holder['since']}; that process is gone)")
            # removed only while it still holds what was judged stale: another command
            # may have taken it over meanwhile and written its own record (probe 97)
            with contextlib.suppress(FileNotFoundError):
                if lock.read_bytes() == holder["bytes"]:
                    lock.unlink()
            continue
        with os.fdopen(fd, "w") as f:
            f.write(record)
        break
    else:
        raise StoreLocked(f"cannot take the lock {lock} of {store}: it keeps changing hands")
    stop = threading.Event()

    def beat():
        while not stop.wait(HEARTBEAT):
            with contextlib.suppress(OSError):
                os.utime(lock)

    thread = threading.Thread(target=beat, name="map-store-lock", daemon=True)
    thread.start()
    try:
        yield lock
    finally:
        stop.set()
        with contextlib.suppress(FileNotFoundError):
            lock.unlink()
