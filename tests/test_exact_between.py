"""The strongly coupled exact theory on a fine grid of offsets (the infinite chain's, pi / 400
a step): there the frozen pencil is solved at every other offset only, and an offset
between two takes their refined modes and frozen starts, interpolated
(``numerics/models/_between.py``). Held here to the same spectrum asked one offset at a
time (each offset alone solves its own frozen pencil, as every chain offset did before)
and, at one point, to the dense eigenproblem.
"""

import numpy as np

from energy import ModelError, load_model
from numerics.models import exact_gain, hill_spectrum, travelling_wave

#: issue 41's bar against the implementation before; a rate within ~1e-9 omega of a double
#: eigenvalue is Newton's tolerance (1e-9 (|lambda| + omega)), as in test_exact_strong.py
RTOL, ATOL_OMEGA = 1e-6, 1e-9
#: the infinite chain's uniform step (``exact_gain``: 400 offsets in [pi / 400, pi])
STEP = np.pi / 400


def _same_one_at_a_time(name, params, k, a, q):
    model = load_model(name).with_params(**params)
    try:
        wave = travelling_wave(model, k, a)
    except ModelError:  # no wave there (the check names why): nothing to compare
        return None
    grid = hill_spectrum(wave, q)
    alone = [hill_spectrum(wave, q[i:i + 1]) for i in range(q.size)]
    gain = np.array([s.gain[0] for s in alone])
    where = f"{name} {params} k={k} a={a}"
    np.testing.assert_allclose(grid.gain, gain, rtol=RTOL, atol=ATOL_OMEGA * wave.omega,
                               err_msg=where)
    grows = gain > 0
    # the same mode named: its wavenumber q + l k (a mode tied with its mirror image names
    # +-kappa, as at q = pi; none of these windows reaches pi)
    harm = np.array([s.harmonic[0] for s in alone])
    np.testing.assert_allclose(np.exp(1j * (q + grid.harmonic * k))[grows],
                               np.exp(1j * (q + harm * k))[grows], atol=1e-9, err_msg=where)
    return int(grows.sum())


def test_fine_grid_is_each_offset_alone_at_random_points(flexmm_points):
    """Six seeded random points of flexmm and flexmm-stiff-hinge (~5 s), each with a window
    of 40 chain offsets somewhere in (0, pi], asked at once (anchors and offsets between
    them): equal to the offsets asked one at a time, rate by rate."""
    grown = [_same_one_at_a_time(name, params, k, a, STEP * np.arange(start, start + 40))
             for name, params, k, a, start in flexmm_points(4103, 6, window=True)]
    assert sum(g for g in grown if g) >= 40  # growing offsets were compared


def test_a_band_one_offset_wide_is_kept():
    """A stiff-hinge band of rate 1.05e-3 that holds one chain offset (q = 274 pi / 400;
    none at its neighbours), whose colliding pair was not growing at either anchor: the
    offset between them must solve its own frozen pencil (a central close pair at an
    anchor), or the band is lost (measured: it was, before that rule)."""
    params = {"K_theta": 0.02632693900238456, "K_s": 0.027989925051829324,
              "alpha": 2.8339238496862094, "K_3": 0.04072787857817184}
    k, a = 1.8326718460103193, 0.055179192330599036
    q = STEP * np.arange(270, 279)
    assert _same_one_at_a_time("flexmm-stiff-hinge", params, k, a, q) >= 1
    wave = travelling_wave(load_model("flexmm-stiff-hinge").with_params(**params), k, a)
    spec = hill_spectrum(wave, q)
    dense = hill_spectrum(wave, q[3:6], harmonics=wave.harmonics + 4)
    assert spec.gain[4] > 1e-3 and spec.gain[3] == 0 and spec.gain[5] == 0
    np.testing.assert_allclose(spec.gain[3:6], dense.gain, rtol=RTOL,
                               atol=ATOL_OMEGA * wave.omega)


def test_fine_grid_is_the_dense_spectrum():
    """The bench flexmm point's chain (issue 41), 40 offsets around its fastest one: the
    fast path equals the dense eigenproblem at the wave's H + 4, offset by offset."""
    model = load_model("flexmm").with_params(K_theta=0.016)
    wave = travelling_wave(model, 2 * np.pi * 36 / 256, 0.1)
    chain = exact_gain(model, wave.k, 0.1)
    peak = chain.offsets[np.argmax(chain.gain)]
    q = STEP * np.arange(1, 401)
    q = q[max(0, np.searchsorted(q, peak) - 20):][:40]
    fast = hill_spectrum(wave, q)
    dense = hill_spectrum(wave, q, harmonics=wave.harmonics + 4)
    assert dense.peak_gain > 0
    np.testing.assert_allclose(fast.gain, dense.gain, rtol=RTOL, atol=ATOL_OMEGA * wave.omega)
