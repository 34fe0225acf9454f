"""Output folders and JSON files of the commands and the scenes: an OUT folder checked and
created before any computation (so a bad ``--out`` fails in one line, before the work is
announced), and JSON written strictly (NaN and inf as null)."""

from __future__ import annotations

import math
import os
import tempfile
from pathlib import Path

import numpy as np

from .files import write_text


def strict_json(x):
    """JSON-safe copy: NaN and inf become null (strict parsers reject bare NaN)."""
    if isinstance(x, dict):
        return {str(k): strict_json(v) for k, v in x.items()}
    if isinstance(x, (list, tuple)):
        return [strict_json(v) for v in x]
    if isinstance(x, np.ndarray):
        return strict_json(x.tolist())
    if isinstance(x, (np.floating, np.integer, np.bool_)):
        x = x.item()
    if isinstance(x, float) and not math.isfinite(x):
        return None
    return x


def check_output(out: Path | str, cache: bool = True) -> Path:
    """OUT as a Path, after the checks that write nothing (a file where a folder must be):
    for commands that announce their work before ``prepare_output`` creates the folder."""
    out = Path(out) if str(out) else Path(".")
    for folder in (out, out / ".cache") if cache else (out,):
        if folder.is_symlink() and not folder.exists():
            raise ValueError(f"{folder} is a symbolic link to {os.readlink(folder)}, which does "
                             "not exist; create that folder, remove the link, or give another "
                             "--out")
        if folder.exists() and not folder.is_dir():
            raise ValueError(f"{folder} is a file, not a folder")
    # the folder, or the nearest existing one it would be created in, must take new entries
    # (read-only file system, no permission, /proc): tried with an empty folder made and
    # removed at once, so nothing is left and the error comes before the work is announced
    base = out.absolute()
    while not base.exists() and base != base.parent:
        base = base.parent
    if not base.is_dir():
        raise ValueError(f"cannot create {out}: {base} is a file, not a folder")
    try:
        os.rmdir(tempfile.mkdtemp(prefix=".write-test-", dir=base))
    except OSError as exc:
        raise ValueError(f"cannot write to {out}: {exc.strerror or exc} ({base})") from None
    return out


def prepare_output(out: Path | str, cache: bool = True) -> Path:
    """Create OUT and (``cache``) OUT/.cache and prove them writable, before any computation.

    Raises ValueError naming the path and the cause (a file where a folder must be, a
    read-only or full file system, ...), so the CLI answers in one line.
    """
    out = check_output(out, cache)
    for folder in (out, out / ".cache") if cache else (out,):
        try:
            folder.mkdir(parents=True, exist_ok=True)
            probe = folder / f".write-test-{os.getpid()}"
            write_text(probe, "ok")
            probe.unlink()
        except OSError as exc:
            raise ValueError(f"cannot write to {folder}: {exc.strerror or exc}") from None
    return out
