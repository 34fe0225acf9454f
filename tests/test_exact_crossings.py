"""The infinite chain's narrow bands between its samples (``numerics.models._crossings``):
a band narrower than the sample step found at the crossing of two opposite-sign roots.

Probe 96's ``cross`` chain (u and a flat v, linear coupling eps 1e-3), v carrier at
k 2.659, a 0.079: a four-wave band 0.002 wide at q 2.056, between two of the 400 samples
(step pi / 400 = 0.0079). ``exact_gain`` said "stable" there; a dense Hill scan (LAPACK's
eig of the whole pencil, ``hill_spectrum(..., harmonics=P)``, not the compiled kernel)
on a fine grid finds MI.
"""

from __future__ import annotations

import numpy as np

from bench.probe_fourwave96 import MODELS
from energy import load_model
from numerics.models import exact_gain, four_wave, hill_spectrum


def test_a_band_between_the_samples_is_found():
    model = load_model(MODELS["cross-1e-3"])
    spec = exact_gain(model, 2.659, 0.079, "v")
    # the referee: the dense eigenproblem at the same truncation on a grid of 2e-5 across
    # the band (its peak to ~(2e-5)^2 x the curvature: < 1e-5 relative)
    q = np.linspace(2.050, 2.062, 601)
    dense = hill_spectrum(spec.wave, q, harmonics=spec.truncations[0])
    assert dense.peak_gain > 5e-4  # the band is there
    assert spec.verdict == "MI"
    # 1e-4: the dense grid's own resolution of the peak and eig's round-off (~1e-8 omega)
    assert abs(spec.peak_gain - dense.peak_gain) <= 1e-4 * dense.peak_gain
    assert abs(spec.fastest_offset - q[np.argmax(dense.gain)]) <= 1e-4
    # the four-wave theory saw it too (probe 96: 8.7e-4): within its O(a^2) error
    assert abs(four_wave(model, 2.659, 0.079, "v").gain / spec.peak_gain - 1) < 0.1


def test_no_offsets_are_added_where_the_samples_grow_or_nothing_can():
    """The bench's fput point (MI, 441 offsets: the samples and the refined peak) and a
    stable carrier keep their offsets: the extra ones stand only where they grow. (The
    stable carrier was fput at k 0.6, a 0.1 until probe 100: it grows at 2.0e-4 by a
    resonant pair in a band its crossings' diagonal roots misplaced, four-wave 2.09e-4:
    tests/test_exact_shifted_crossing.py. Klein-Gordon's at k 0.6 is stable by four-wave
    too.)"""
    fput = load_model("fput").with_params(alpha=0.5, beta=1.0)
    grows = exact_gain(fput, 2 * np.pi * 66 / 256, 0.1)
    assert grows.offsets.size == 441
    calm = exact_gain(load_model("klein-gordon"), 0.6, 0.1)
    assert calm.verdict == "stable" and calm.offsets.size == 440


THREE = '''name = "three"
fields = ["u", "v", "w"]
branch = "u"
[parameters]
kv = 0.7
kw = 1.3
[energy]
kinetic = "u_t**2/2 + v_t**2/2 + w_t**2/2"
bond = "(u_next - u)**2/2 + (u_next - u)**4/4 + 0.1*(u_next - u)*v**2 + (w_next - w)**2/2"
site = "kv*(v - u)**2/2 + kw*(w - v)**2/2 + 0.3*w**2/2"
'''


def test_three_fields_take_the_general_block_path():
    """Three fields: each harmonic's own block's roots by LAPACK (the 1 x 1 and 2 x 2 ones
    in closed form); the offsets the crossings add grow, at the dense eigenproblem's rate
    there (1e-6 relative: the compiled kernel against LAPACK, as the anchors)."""
    model = load_model(THREE)
    spec = exact_gain(model, 1.0, 0.05)
    grid = np.concatenate([np.geomspace(1e-5, np.pi / 400, 40, endpoint=False),
                           np.linspace(np.pi / 400, np.pi, 400)])
    added = ~np.isclose(spec.offsets[:, None], grid[None, :], rtol=1e-12, atol=0).any(axis=1)
    assert added.sum() >= 2  # measured 9: the refined peak and 8 crossings
    assert np.all(spec.gain[added] > 0)
    q = spec.offsets[added]
    dense = hill_spectrum(spec.wave, q, harmonics=spec.truncations[0])
    np.testing.assert_allclose(spec.gain[added], dense.gain, rtol=1e-6)
