"""Where Numba caches the compiled kernels: beside the sources when that folder is
writable (Numba's default), else in a user-writable folder, so that a read-only install
(a system site-packages, a container image) works instead of dying with Numba's "cannot
cache function" before reading its input. Runs before any kernel is compiled (imported
first by ``numerics.lattice``)."""

from __future__ import annotations

import os
import sys
import tempfile
from pathlib import Path

#: the folders holding @njit(cache=True) functions
SOURCE_DIRS = (Path(__file__).resolve().parent, Path(__file__).resolve().parents[1] / "theory")


def _writable(folder: Path) -> bool:
    """Can this process create files in ``folder`` (its __pycache__, where Numba writes)?"""
    cache = folder / "__pycache__"
    target = cache if cache.is_dir() else folder
    return os.access(target, os.W_OK | os.X_OK)


def _usable(folder: Path) -> bool:
    try:
        folder.mkdir(parents=True, exist_ok=True)
    except OSError:
        return False
    return os.access(folder, os.W_OK | os.X_OK)


def user_cache_dir() -> Path:
    """$XDG_CACHE_HOME/flexmm-mi/numba (default ~/.cache/flexmm-mi/numba)."""
    base = os.environ.get("XDG_CACHE_HOME") or os.path.join(os.path.expanduser("~"), ".cache")
    return Path(base) / "flexmm-mi" / "numba"


def configure(source_dirs=SOURCE_DIRS, environ=os.environ) -> str | None:
    """Set NUMBA_CACHE_DIR when a source folder is not writable and the user has not set
    it; returns the folder chosen (None: Numba's default is fine or the user chose)."""
    if environ.get("NUMBA_CACHE_DIR") or all(_writable(d) for d in source_dirs):
        return None
    fallback = Path(tempfile.gettempdir()) / f"flexmm-mi-numba-{os.getuid()}"
    for folder in (user_cache_dir(), fallback):
        if _usable(folder):
            environ["NUMBA_CACHE_DIR"] = str(folder)
            if "numba" in sys.modules:  # imported already: its config is read at import
                sys.modules["numba"].config.CACHE_DIR = str(folder)
            return str(folder)
    print("flexmm: note: no writable folder for Numba's cache (the package folder, "
          f"{user_cache_dir()}, {fallback}); kernels are compiled anew in each process",
          file=sys.stderr)
    return None


configure()
