"""TravellingWave.ring_profile (a run's records): the wave's profile on the ring's sites."""

from __future__ import annotations

import numpy as np
import pytest


@pytest.mark.parametrize("name, k", [("fput", 2.4), ("flexmm", 0.9), ("diatomic-fput", 1.0)])
def test_the_ring_profile_is_the_profile(name, k):
    """Equal to ``profile(k n - omega t)`` up to the round-off of the phases' arguments: the
    two forms round h (k n - omega t) differently, by ~eps H (k N + omega t) in phase, times
    the harmonics' size (sum |c|); 4x margin."""
    from energy import load_model
    from numerics.models import snap_ring, travelling_wave

    N = 64
    kr = snap_ring(k, N)[0]
    wave = travelling_wave(load_model(name), kr, 0.1)
    at = wave.ring_profile(N, kr)
    n = np.arange(N)
    size = np.abs(wave.coefficients).sum()
    for t in (0.0, 3.7, 99.1, 5.0e4):
        want = wave.profile(kr * n - wave.omega * t)
        tol = 4 * np.finfo(float).eps * wave.harmonics * (kr * N + abs(wave.omega) * t) * size
        assert at(t).shape == want.shape == (wave.coefficients.shape[0], N)
        np.testing.assert_allclose(at(t), want, rtol=0, atol=tol)
