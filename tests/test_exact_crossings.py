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
    stable fput carrier keep their offsets: the extra ones stand only where they grow."""
    fput = load_model("fput").with_params(alpha=0.5, beta=1.0)
    grows = exact_gain(fput, 2 * np.pi * 66 / 256, 0.1)
    assert grows.offsets.size == 441
    calm = exact_gain(fput, 0.6, 0.1)
    assert calm.verdict == "stable" and calm.offsets.size == 440
