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



def test_a_models_run_records_its_wave_on_one_blas_thread(monkeypatch):
    """simulate_model (a point's runs in the client, a map's probe) builds the wave on the
    ring at each record by a small complex matrix product: on OpenBLAS' threads of a loaded
    2-core machine 3.8 ms a call, and a map's probe read a 0.07 s run as 3.2-3.7 s (a new
    user's map: estimated 4 min, took 34 s). The product runs on one thread, whatever
    the caller's limit (here 2, as OpenBLAS' default on 2 cores)."""
    from threadpoolctl import threadpool_limits

    from energy import load_model
    from numerics.models import TravellingWave, simulate_model

    seen = []
    real = TravellingWave.ring_profile

    def ring_profile(self, *a, **kw):
        seen.append(_blas_threads())
        return real(self, *a, **kw)

    monkeypatch.setattr(TravellingWave, "ring_profile", ring_profile)
    with threadpool_limits(limits=2, user_api="blas"):
        simulate_model(load_model("fput"), 2.0, 0.1, N=16, t_end=5.0, records=4)
    assert seen and all(n == 1 for threads in seen for n in threads), seen
