"""The theories' small linear algebra runs on one BLAS thread (common/threads.py)."""

from __future__ import annotations

import numpy as np
from threadpoolctl import threadpool_info

from common.threads import one_blas_thread


def _blas_threads():
    return [p["num_threads"] for p in threadpool_info() if p["user_api"] == "blas"]


def test_one_blas_thread_limits_inside_and_restores_after():
    before = _blas_threads()
    assert before, "numpy's BLAS is not visible to threadpoolctl"

    @one_blas_thread
    def inside(a):
        np.linalg.eigvals(a)
        return _blas_threads()

    assert all(n == 1 for n in inside(np.eye(4)))
    assert _blas_threads() == before


def test_the_theory_entry_points_are_limited():
    """The entries that solve batches of small eigenproblems carry the limit (the
    decorator keeps the signature and docstring: ``__wrapped__``)."""
    from numerics.maps import resonance_map
    from numerics.theory import mi_gain, predict_growth, stability_map

    for fn in (predict_growth, resonance_map, stability_map, mi_gain):
        assert hasattr(fn, "__wrapped__"), fn.__name__

