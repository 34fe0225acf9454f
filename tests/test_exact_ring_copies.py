"""A one-field wave's ring spectrum from its modes' copies at l = 0
(``numerics/models/_ring_copies.py``), held to the spectrum solved offset by offset (every
cluster of a central root at every ring offset: the compiled path before it)."""

import numpy as np
import pytest

from energy import load_model
from numerics.models import exact_gain, travelling_wave
from numerics.models._exact import _Sidebands, ring_offsets
from numerics.models._ring_copies import ring_copies

#: a copy's rate differs from the mode's by the truncation window moving with it (a kept
#: mode holds < 1e-6 of its weight in the outer three harmonics): measured <= 2e-10 of the
#: rate at these and the bench points; the bar 1e-9 relative (1e-12 omega near zero)
RTOL, ATOL_OMEGA = 1e-9, 1e-12

POINTS = [  # (model, params, ring site m of k = 2 pi m / N, amplitude, N)
    ("fput", dict(alpha=0.5, beta=1.0), 66, 0.1, 256),     # bench.models' point
    ("fput", dict(alpha=0.035, beta=0.963), 20, 0.249, 128),  # a copy at q = k / 2
    ("fput", dict(alpha=0.51, beta=1.91), 14, 0.24, 128),   # H = 32: P = 36
    ("klein-gordon", {}, 44, 0.2, 128),
    ("sine-gordon", {}, 41, 0.3, 256),
    ("fput", dict(alpha=0.8, beta=1.0), 64, 0.1, 256),      # README's k = pi / 2
]


@pytest.mark.parametrize("name,params,m,a,N", POINTS)
def test_copies_give_the_offset_by_offset_spectrum(name, params, m, a, N):
    model = load_model(name).with_params(**params) if params else load_model(name)
    k = 2 * np.pi * m / N
    wave = travelling_wave(model, k, a)
    engine = _Sidebands(wave)
    q = ring_offsets(N)
    each = engine.spectrum(q)
    copies = ring_copies(engine, N, m)
    np.testing.assert_array_equal(copies.offsets, q)
    np.testing.assert_allclose(copies.gain, each.gain, rtol=RTOL,
                               atol=ATOL_OMEGA * wave.omega)
    grows = each.gain > 0
    np.testing.assert_array_equal(copies.gain > 0, grows)
    assert grows.any() or name == "klein-gordon"
    # the mode named at each offset: the same, or (where a mode and its mirror image
    # share the offset with one rate: q = k / 2 and the like) its reflection, the
    # wavenumber kappa = q + l k up to its sign
    kap_each = np.exp(1j * (q + each.harmonic * k))[grows]
    kap_copy = np.exp(1j * (q + copies.harmonic * k))[grows]
    same = np.isclose(kap_copy, kap_each, rtol=0, atol=1e-9)
    mirrored = np.isclose(kap_copy, np.conj(kap_each), rtol=0, atol=1e-9)
    assert np.all(same | mirrored)
    side_each, side_copy = each.sideband_offset[grows], copies.sideband_offset[grows]
    np.testing.assert_array_equal(np.isnan(side_copy), np.isnan(side_each))
    ok = ~np.isnan(side_each)
    np.testing.assert_allclose(side_copy[ok], side_each[ok], rtol=1e-9, atol=1e-12)


def test_exact_gain_uses_the_copies_on_a_one_field_ring_only():
    """``exact_gain``'s ring answer is the copies' (checked at P + 4 as before); a
    two-field wave's ring is solved offset by offset."""
    model = load_model("fput").with_params(alpha=0.5, beta=1.0)
    spec = exact_gain(model, 2 * np.pi * 66 / 256, 0.1, N=256)
    engine = _Sidebands(spec.wave)
    np.testing.assert_array_equal(spec.gain, ring_copies(engine, 256, 66).gain)
    assert spec.truncations == (engine.P, engine.P + 4)
    two = exact_gain(load_model("diatomic-fput"), 2 * np.pi * 20 / 128, 0.1, 0, N=128)
    each = _Sidebands(two.wave).spectrum(ring_offsets(128))
    np.testing.assert_array_equal(two.gain, each.gain)
