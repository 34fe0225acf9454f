"""Small dense linear algebra on one BLAS thread.

The theories solve batches of small eigenproblems and linear systems (10 x 10 to a few
hundred rows): a multithreaded BLAS (OpenBLAS' default, one thread per core) only adds
synchronisation to each call, and on a busy machine its threads spin against the work.
Measured on the 2-core machine of the benchmarks, shared with one other job: a cell's
predicted growth (eq. `IC`, case II) 0.43 s on one BLAS thread against 2.5 s with
OpenBLAS' default; the 200 x 200 exact map of case II 13.7 s against 30 s. Dask workers
already start with OPENBLAS_NUM_THREADS=1 (distributed's ``pre-spawn-environ``);
:func:`one_blas_thread` gives the same to the client, the command line and Python users,
scoped to the call (threadpoolctl restores the caller's setting on return).

The scan of the loaded libraries is kept (``threadpoolctl.ThreadpoolController``) and
redone only when a module was imported since (a BLAS arrives with an import): limiting
then costs ~13 us a call instead of ~0.7 ms (measured on the benchmarks' machine), which
matters to the exact theory of a model at ~10 ms a point.
"""

from __future__ import annotations

import functools
import sys

from threadpoolctl import ThreadpoolController

_CONTROLLER: list = [None, -1]  # the controller, len(sys.modules) when it scanned


def _controller() -> ThreadpoolController:
    if _CONTROLLER[0] is None or _CONTROLLER[1] != len(sys.modules):
        _CONTROLLER[:] = [ThreadpoolController(), len(sys.modules)]
    return _CONTROLLER[0]


def one_blas_thread(fn):
    """Run ``fn`` with the BLAS thread pools limited to one thread."""

    @functools.wraps(fn)
    def wrapper(*args, **kwargs):
        with _controller().limit(limits=1, user_api="blas"):
            return fn(*args, **kwargs)

    return wrapper


__all__ = ["one_blas_thread", "threaded_get"]


def threaded_get():
    """Dask's threaded scheduler, as a callable: ``dask.compute(..., scheduler=
    threaded_get())`` runs on this process' threads without asking distributed for a
    default client, which ``scheduler="threads"`` does first, and whose registry lookup
    races with the garbage collection of a closed client (distributed's
    ``_get_global_client``: a KeyError, seen in CI as 'KeyError: 4' while a map store's
    theory columns were computed)."""
    import dask.threaded

    return dask.threaded.get
