"""The dense Hill paths' resolution (``numerics.models._hill_dense._DensePencil.resolved``):
eig splits a near-double eigenvalue by ~sqrt(eps) times the pencil's largest frequency, so
a rate below twice that counts only where its eigenvalue is well conditioned (10x its
first-order error eps ||A|| kappa), also above the carrier-relative floor GAIN_FLOOR omega
(an acoustic carrier's omega is far below the pencil's scale)."""

from __future__ import annotations

import math

import numpy as np

from energy import load_model
from numerics.models import exact_gain, hill_spectrum
from numerics.models._hill_dense import RESOLUTION


def test_an_acoustic_carriers_dense_round_off_is_no_growth():
    """Probe 98 (seed 98003, point 76): diatomic-fput m 2.584, alpha -0.293, beta 0.646,
    k 0.056, a 0.0265 on 128 sites goes dense at P = 36 and read 2.85e-8 (1.6e-6 omega, 5x
    GAIN_FLOOR) at one offset, where the probe's own Hill pencil (hyper-dual Hessians,
    numpy eig) reads 0 at P = 36 and 2.2e-8 at P = 40: no persistent rate. The pencil's
    largest |lambda| is ~2.4 (the optical branch, 36 harmonics of omega 0.018): resolution
    2 sqrt(eps) 2.4 = 7e-8."""
    m = load_model("diatomic-fput", m=2.584115661529004, alpha=-0.2932588067723314,
                   beta=0.646159640810575)
    spec = exact_gain(m, 0.05598869035352587, 0.026502554510586057, 0, N=128)
    assert spec.peak_gain == 0.0, (spec.peak_gain, spec.truncations)


def test_a_slow_real_rate_stays_on_the_dense_path():
    """A weak FPUT wave (alpha 0.5, beta 1, k 2 pi 66 / 256, a 0.01: rate ~6e-5, 100x the
    dense resolution at P = 14) reads the same rate on the dense path as on the compiled
    one (1e-6 relative, the exactness bar of issue 41)."""
    m = load_model("fput", alpha=0.5, beta=1.0)
    k = 2 * math.pi * 66 / 256
    fast = exact_gain(m, k, 0.01, N=256)
    assert fast.peak_gain > 0
    i = int(np.argmax(fast.gain))
    dense = hill_spectrum(fast.wave, fast.offsets[i:i + 1], harmonics=fast.wave.harmonics + 4)
    assert dense.gain[0] > 50 * 2 * RESOLUTION * (fast.wave.harmonics + 6) * fast.wave.omega
    assert abs(dense.gain[0] / fast.gain[i] - 1) < 1e-6, (dense.gain[0], fast.gain[i])


def test_a_real_rate_below_the_sqrt_eps_scale_is_kept():
    """The review's case: diatomic-fput m 2.58 (alpha 0, beta 1), acoustic carrier k 0.056,
    a 0.09: the compiled path reads 4.97e-8 (persisting at P + 4, ~a^2), below 2 sqrt(eps)
    max |lambda| (5e-8) but a well-conditioned eigenvalue (kappa 27: error 2e-14); the
    dense path at P = 14 and 24 reads it too (a cut at the scale alone read 0)."""
    m = load_model("diatomic-fput", m=2.58)
    fast = exact_gain(m, 0.056, 0.09, 0)
    i = int(np.argmax(fast.gain))
    assert 4e-8 < fast.peak_gain < 6e-8
    for P in (14, 24):
        dense = hill_spectrum(fast.wave, fast.offsets[i:i + 1], harmonics=P)
        assert abs(dense.gain[0] / fast.gain[i] - 1) < 1e-6, (P, dense.gain[0], fast.gain[i])
