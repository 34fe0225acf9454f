"""Write-then-rename: a file is either complete or absent, never half written.

The one helper every layer uses to write what it produces (generated code, the cache,
scene data, figures, summaries, reports). Files get the permissions of a normal
``open(..., "w")`` (0666 minus the umask), not the 0600 of ``tempfile.mkstemp``.
"""

from __future__ import annotations

import os
import tempfile
from contextlib import contextmanager
from pathlib import Path


def umask() -> int:
    """The process umask (read without changing it): new files get 0o666 & ~umask()."""
    mask = os.umask(0)
    os.umask(mask)
    return mask


@contextmanager
def atomic_write(path, mode: str = "w"):
    """Open a temporary file beside ``path``; rename it onto ``path`` on success.

    Yields the temporary file's path for ``mode=None`` (for writers that open by name,
    such as h5py or matplotlib), else an open file object (``"w"`` text, UTF-8, ``\\n``
    line ends; ``"wb"`` binary). On any exception, Ctrl-C included, the temporary file
    is removed and ``path`` is left as it was.
    """
    path = Path(path)
    fd, tmp = tempfile.mkstemp(dir=path.parent, prefix=f".{path.name}.", suffix=".tmp")
    try:
        os.chmod(tmp, 0o666 & ~umask())
        if mode is None:
            os.close(fd)
            fd = None
            yield tmp
        else:
            fh = (os.fdopen(fd, mode) if "b" in mode
                  else os.fdopen(fd, mode, encoding="utf-8", newline="\n"))
            fd = None  # owned by fh from here on
            with fh:
                yield fh
        os.replace(tmp, path)
    except OSError as exc:
        if exc.filename is None:  # a full disk says ENOSPC, not where: name the file
            raise OSError(exc.errno, exc.strerror or str(exc), str(path)) from exc
        raise
    finally:
        if fd is not None:
            os.close(fd)
        if os.path.exists(tmp):
            os.remove(tmp)


def write_text(path, text: str) -> Path:
    """Write ``text`` to ``path`` atomically; returns the path."""
    with atomic_write(path) as fh:
        fh.write(text)
    return Path(path)


def write_results(files: dict) -> None:
    """Write each ``path: text or bytes`` atomically, all of them with SIGINT and SIGTERM
    held (``common.signals.held``): a command's results land together or not at all
    (probe 99: a SIGTERM while soliton.png was drawn left soliton.json alone, and the
    command said that nothing was written). Render first, then call this."""
    from .signals import held

    with held():
        for path, data in files.items():
            with atomic_write(path, "wb" if isinstance(data, bytes) else "w") as fh:
                fh.write(data)
            _WRITTEN.append(Path(path))


#: what ``write_results`` wrote in this process (the CLI's interrupt message reads it)
_WRITTEN: list = []


def results_written() -> list:
    """The paths ``write_results`` has written in this process, in order."""
    return list(_WRITTEN)
