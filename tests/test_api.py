"""The public API reads like SciPy's: plain values back, options as keywords, one name per
concept (issue 36 item 4)."""

from __future__ import annotations

import math

import pytest

from numerics import snap_wavenumber


def test_snap_wavenumber_snaps_and_returns_a_float():
    k = snap_wavenumber(0.8, 500)
    assert isinstance(k, float) and k == pytest.approx(2 * math.pi * 64 / 500, rel=1e-15)
    assert snap_wavenumber(0.8, 500, return_index=True) == (k, 64)


def test_snap_wavenumber_strictness_is_an_option():
    assert snap_wavenumber(0.8, 500, rel_tol=1e-2) == snap_wavenumber(0.8, 500)
    with pytest.raises(ValueError, match="not commensurate.*0.804248"):
        snap_wavenumber(0.8, 500, rel_tol=1e-3)


@pytest.mark.parametrize("N, error", [(0, ValueError), (-100, ValueError), (True, TypeError),
                                      (8.0, TypeError)])
def test_snap_wavenumber_checks_N(N, error):
    with pytest.raises(error, match="N must"):
        snap_wavenumber(0.8, N)


def test_snap_wavenumber_refuses_a_nan_tolerance():
    with pytest.raises(ValueError, match="rel_tol"):
        snap_wavenumber(0.8, 500, rel_tol=float("nan"))
