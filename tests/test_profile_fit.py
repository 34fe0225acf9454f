"""The one sech^2 fit of a soliton's intensity on a ring (``numerics.lattice.
fit_soliton_profile``), behind the paper chain's and every model's soliton measurement:
exact profiles give back their parameters, across the ring's seam, in both depth
conventions; added radiation is measured as such; bad input is named."""

from __future__ import annotations

import math

import numpy as np
import pytest

from numerics.lattice import RADIATION_WINDOW, fit_soliton_profile


def _profile(kind, N, centre, a, w, D=1.0):
    n = np.arange(N)
    d = (n - centre + N / 2) % N - N / 2
    sech2 = 1 / np.cosh(d / w) ** 2
    return a**2 * sech2 if kind == "bright" else a**2 * (1 - D * sech2)


@pytest.mark.parametrize("kind,N,centre,a,w,D", [
    ("bright", 256, 100.3, 0.02, 9.5, None),
    ("bright", 128, 1.7, 1.3, 4.2, None),      # the soliton straddles the seam
    ("dark", 300, 287.6, 0.05, 12.0, 1.0),     # black, near the seam
    ("dark", 200, 60.2, 0.4, 6.5, 0.55),       # grey
])
def test_an_exact_profile_gives_back_its_parameters(kind, N, centre, a, w, D):
    guess_c, guess_w = centre + 1.4, 1.2 * w  # off by more than a site and 20 %
    fit = fit_soliton_profile(_profile(kind, N, centre, a, w, D or 0.0), kind,
                              guess_c + 3 * N, guess_w)  # the guess on another lap
    # an exact profile is fitted to the solver's tolerance (1e-12, on O(1) numbers): 1e-9
    # leaves room for its conditioning (a flat dip bottom, a wide bright tail)
    assert fit.kind == kind
    assert (fit.centre - 3 * N) == pytest.approx(centre, abs=1e-9 * w)
    assert fit.amplitude == pytest.approx(a, rel=1e-9)
    assert fit.width == pytest.approx(w, rel=1e-9)
    if kind == "bright":
        assert fit.dip == 0.0 and fit.depth == 0.0
    else:  # D and 1 - D: the two conventions of the two measurements
        assert fit.dip == pytest.approx(D, abs=1e-9)
        assert fit.depth == pytest.approx(1 - D, abs=1e-9)
        assert fit.depth == 1 - fit.dip
    assert fit.radiation < 1e-9 and fit.shape_misfit < 1e-9


def test_an_even_floor_of_radiation_is_measured_as_such():
    """A bright soliton on a floor of height h (spread evenly: radiation) reads, outside
    the window, sum(h) scaled to the whole ring over the soliton's own 2 a^2 w."""
    N, a, w, h = 512, 0.1, 5.0, 1e-6
    amp2 = _profile("bright", N, 200.0, a, w) + h
    fit = fit_soliton_profile(amp2, "bright", 200.0, w)
    expected = N * h / (2 * a**2 * w)  # sum of a^2 sech^2(n / w) over the ring = 2 a^2 w
    # the fit absorbs a little of the floor into a and w (h / a^2 = 1e-4 of the peak; a
    # 3e-5 and w 2e-4 off): the radiation it reads is within 1 % of the floor's share
    assert fit.radiation == pytest.approx(expected, rel=0.01)
    assert 6 * w * 2 < N and RADIATION_WINDOW == 6.0


def test_a_window_over_the_whole_ring_has_no_radiation_reading():
    fit = fit_soliton_profile(_profile("bright", 40, 20.0, 1.0, 5.0), "bright", 20.0, 5.0)
    assert math.isnan(fit.radiation) and fit.width == pytest.approx(5.0, rel=1e-9)


@pytest.mark.parametrize("args,match", [
    ((np.ones(64), "grey", 10.0, 3.0), "kind must be 'bright' or 'dark', got 'grey'"),
    ((np.ones((2, 64)), "dark", 10.0, 3.0), "intensity must be a 1-d array"),
    ((np.ones(64), "dark", 10.0, 0.0), "width_guess must be > 0, got 0.0"),
])
def test_bad_input_is_named(args, match):
    with pytest.raises(ValueError, match=match):
        fit_soliton_profile(*args)
