"""The compiled Hill kernel's LU skips exact zeros (a split or banded rest) and its Hessian
harmonics below the DFT's round-off are set to zero: both must leave the algebra what a
dense solve gives, to round-off."""

import numpy as np
import pytest

from numerics.models._small_algebra import (
    ROUNDOFF,
    _drop_roundoff,
    _lu,
    _lu_solve,
    _lu_solve_t,
)


def _split(n, rng, band=None):
    """A complex matrix whose odd and even rows/columns do not couple (a symmetric
    potential's pencil), optionally banded, diagonally weak so that pivoting happens."""
    A = rng.standard_normal((n, n)) + 1j * rng.standard_normal((n, n))
    i = np.arange(n)
    A[(i[:, None] - i[None, :]) % 2 == 1] = 0
    if band is not None:
        A[np.abs(i[:, None] - i[None, :]) > band] = 0
    return A


@pytest.mark.parametrize("n, band", [(19, None), (27, 8), (39, None), (8, 2)])
def test_sparse_lu_solves_as_dense(n, band):
    rng = np.random.default_rng(n)
    A = _split(n, rng, band)
    B = rng.standard_normal((n, 3)) + 1j * rng.standard_normal((n, 3))
    B[1::2, 0] = 0  # a right side that reaches one block only: the solves skip the other
    F, piv = A.copy(), np.empty(n, np.int64)
    assert _lu(F, piv)
    X, Y = B.copy(), B.copy()
    _lu_solve(F, piv, X)
    _lu_solve_t(F, piv, Y)
    # tolerance: backward-stable LU, error ~ n eps cond(A); these matrices have cond < 1e4
    cond = np.linalg.cond(A)
    assert np.abs(X - np.linalg.solve(A, B)).max() <= 1e-14 * n * cond * np.abs(X).max()
    assert np.abs(Y - np.linalg.solve(A.T, B)).max() <= 1e-14 * n * cond * np.abs(Y).max()
    assert np.all(X[1::2, 0] == 0)  # the untouched block stays exactly zero


def test_singular_is_reported():
    A = np.zeros((4, 4), complex)
    A[0, 0] = A[1, 1] = A[3, 3] = 1.0
    assert not _lu(A, np.empty(4, np.int64))


def test_roundoff_harmonics_dropped_and_only_they():
    rng = np.random.default_rng(1)
    Hh = rng.standard_normal((9, 2, 2)) + 1j * rng.standard_normal((9, 2, 2))
    Hh[1::2, 0, 0] = 3e-16       # a symmetric potential's odd harmonics: round-off
    Hh[2, 1, 1] = 1e-12          # a small but resolved harmonic: kept
    Hh[:, 0, 1] = 0.0            # a pair of fields that never couples: stays zero
    out = _drop_roundoff(Hh)
    assert np.all(out[1::2, 0, 0] == 0)
    assert out[2, 1, 1] == Hh[2, 1, 1]
    kept = np.abs(Hh) > ROUNDOFF * np.abs(Hh).max(axis=0)
    np.testing.assert_array_equal(out[kept], Hh[kept])
    assert np.all(out[~kept] == 0)
