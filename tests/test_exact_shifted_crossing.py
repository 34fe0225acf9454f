"""A narrow band the diagonal roots misplace (``numerics.models._crossings``,
``corrected_crossings``): probe 100's Morse chain (V = D (1 - e^{-b r})^2, D b^2 = 1/2) at
k 1.2855, a 0.015 has a backward pair (waves at 2.979 and -0.408, 2 Omega = w1 + w2) growing
at 3.6e-5 in a band 1.3e-4 wide about q 1.6938 (and its copy about 0.4083). The harmonics'
own blocks put the crossing of its roots at 1.69299, 7.5e-4 off: their O(a^2) shifts from the
couplings to the other harmonics were left out, and ``exact_gain`` read the chain "stable"
at 400, 2000 and 8000 samples where four-wave said MI at 3.59e-5 and a dense Hill scan finds
it. With the roots' second-order shifts the crossing lands inside the band.
"""

from __future__ import annotations

import numpy as np
import pytest

from bench._fourwave100_models import MORSE
from energy import load_model
from numerics.models import exact_gain, four_wave, hill_spectrum


@pytest.fixture(scope="module")
def morse(tmp_path_factory):
    path = tmp_path_factory.mktemp("morse") / "morse.toml"
    path.write_text(MORSE)
    return load_model(path)


@pytest.mark.parametrize("samples", [400, 8000])
def test_a_band_the_diagonal_roots_misplace_is_found(morse, samples):
    k, a = 1.2855, 0.015
    spec = exact_gain(morse, k, a, samples=samples)
    # the referee: LAPACK's eig of the whole pencil at the same truncation on a grid of
    # 1e-6 across both copies of the band (the peak to ~(1e-6)^2 x curvature)
    dense = [hill_spectrum(spec.wave, np.linspace(c - 2e-4, c + 2e-4, 401),
                           harmonics=spec.truncations[0]) for c in (0.40832, 1.69382)]
    best = max(d.peak_gain for d in dense)
    assert best > 3e-5  # the band is there
    assert spec.verdict == "MI"
    # 1e-3: the dense grid's resolution of a band 1.3e-4 wide (~1e-5 relative) with margin
    assert abs(spec.peak_gain - best) <= 1e-3 * best
    # its fastest offset q is in one of the band's two copies
    q = spec.offsets[np.argmax(spec.gain)]
    assert min(abs(q - c) for c in (0.40832, 1.69382)) < 1e-4
    # the four-wave theory sees the same pair (3.59e-5: within its O(a^2) error)
    assert abs(four_wave(morse, k, a).gain / spec.peak_gain - 1) < 0.05


def test_fput_at_k_0_6_grows_by_its_resonant_pair():
    """fput (alpha 0.5, beta 1) at k 0.6, a 0.1: the NLS says stable (defocusing, its mean
    flow), tests/test_exact_crossings.py took it as the stable carrier; four-wave finds a
    resonant pair (waves at 1.23 and -0.03, 2 omega(k) = w1 + w2) at 2.09e-4 and a dense
    Hill scan at P 10, 14 and 20 alike 2.0016e-4 at q 0.02999, a band narrower than a
    sample step whose linear crossing missed it."""
    fput = load_model("fput").with_params(alpha=0.5, beta=1.0)
    spec = exact_gain(fput, 0.6, 0.1)
    q = np.linspace(0.0298, 0.0302, 401)  # 1e-6 a step across the band
    dense = hill_spectrum(spec.wave, q, harmonics=spec.truncations[0])
    assert dense.peak_gain > 1.5e-4
    assert spec.verdict == "MI"
    assert abs(spec.peak_gain - dense.peak_gain) <= 1e-3 * dense.peak_gain
    # within four-wave's O(a^2) error (a 0.1: 4.5% measured)
    assert abs(four_wave(fput, 0.6, 0.1).gain / spec.peak_gain - 1) < 0.1
