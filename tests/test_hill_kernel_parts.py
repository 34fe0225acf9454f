"""The compiled Hill kernel's cheaper parts (issue 41) against the algebra they replace: the
fold by L D L^* without pivoting against the pivoted LU's, the frozen pencil's roots by
Aberth from tilted starts against LAPACK's eigenvalues, a converged mode's eigenvector by
power iteration against the null vector, on matrices built here (not by the code under
test)."""

import numpy as np
import pytest

from numerics.models._cluster_solve import _fold, _fold_axis
from numerics.models._frozen_roots import _frozen, _small_pencil
from numerics.models._small_algebra import _ldlh, _ldlh_half, _null_vector


def _dominant(n, rng, margin=1.5, split=False):
    """A Hermitian matrix, strictly diagonally dominant by rows (|A_ii| = margin x the
    row's off-diagonal sum, diagonal signs mixed: indefinite, as the rest of the Hill
    pencil on the axis), optionally split into odd and even rows (a symmetric potential)."""
    A = rng.standard_normal((n, n)) + 1j * rng.standard_normal((n, n))
    A = A + A.conj().T
    if split:
        i = np.arange(n)
        A[(i[:, None] - i[None, :]) % 2 == 1] = 0
    np.fill_diagonal(A, 0)
    sign = np.where(rng.random(n) < 0.5, -1.0, 1.0)
    np.fill_diagonal(A, sign * margin * np.abs(A).sum(axis=1))
    return A


@pytest.mark.parametrize("n, split", [(18, False), (39, True), (5, False)])
def test_ldlh_folds_as_a_dense_solve(n, split):
    rng = np.random.default_rng(n)
    A = _dominant(n, rng, split=split)
    B = rng.standard_normal((n, 3)) + 1j * rng.standard_normal((n, 3))
    F = A.copy()
    assert _ldlh(F)
    Z = B.copy()
    _ldlh_half(F, Z)
    fold = Z.conj().T @ (Z / F.diagonal().real[:, None])
    want = B.conj().T @ np.linalg.solve(A, B)
    # tolerance: elimination without pivoting is backward stable on a diagonally dominant
    # matrix (growth <= 2), error ~ n eps cond(A) |B|^2 / |A|; cond < 10 at margin 1.5
    scale = np.abs(B).max() ** 2 / np.abs(A.diagonal()).min()
    assert np.abs(fold - want).max() <= 1e-14 * n * np.linalg.cond(A) * scale


def test_ldlh_reports_a_zero_pivot():
    A = np.eye(3, dtype=complex)
    A[1, 1] = 0
    assert not _ldlh(A)


def _pencil(rng, n=15, omega=1.3, coupling=0.05):
    """A scaled Hill pencil's pieces: K Hermitian with diag(w^2) on the diagonal and small
    couplings between harmonics (none inside one: one field), Omega = l omega."""
    lvec = np.arange(n) - n // 2
    E = coupling * (rng.standard_normal((n, n)) + 1j * rng.standard_normal((n, n)))
    E = E + E.conj().T
    np.fill_diagonal(E, 0)
    w = rng.uniform(0.3, 1.0, n)
    return E + np.diag(w**2), lvec * omega, w


def test_fold_on_the_axis_is_the_lu_fold():
    rng = np.random.default_rng(3)
    Kt, Om, w = _pencil(rng)
    cidx = np.array([6, 7, 8])
    ridx = np.setdiff1d(np.arange(Kt.shape[0]), cidx)
    X = np.empty((ridx.size, cidx.size), complex)
    R = np.abs(Kt - np.diag(Kt.diagonal())).sum(axis=1)
    checked = 0
    for mu in np.linspace(-1.5, 1.5, 61):
        f = np.abs(w[ridx] ** 2 - (mu - Om[ridx]) ** 2)
        if np.any(f <= R[ridx]):  # not outside every disc of the rest: not the claim
            continue
        checked += 1
        lu, ok = _fold(Kt, Om, 1j * mu, cidx, ridx, X)
        ax, ok2 = _fold_axis(Kt, Om, mu, cidx, ridx, X, mu, mu)
        assert ok and ok2
        # tolerance: two backward-stable eliminations of a dominant matrix, |Sigma| ~ 0.1
        assert np.abs(ax - lu).max() <= 1e-13 * max(np.abs(lu).max(), 1.0)
        np.testing.assert_array_equal(ax, ax.conj().T)  # Hermitian by construction
    assert checked >= 5
    # outside the span it is the LU fold itself
    lu, _ = _fold(Kt, Om, 0.3j, cidx, ridx, X)
    ax, _ = _fold_axis(Kt, Om, 0.3, cidx, ridx, X, 0.5, 0.6)
    np.testing.assert_array_equal(ax, lu)


@pytest.mark.parametrize("rc", [1, 2, 3, 4])
def test_frozen_roots_are_lapacks(rc):
    rng = np.random.default_rng(10 + rc)
    growing = 0
    for trial in range(40):
        # roots i (l omega +- w) that nearly meet: coupled, a pair leaves the axis
        n = 9
        Kt, Om, w = _pencil(rng, n=n, coupling=0.02 + 0.1 * rng.random())
        cidx = np.sort(rng.choice(n, rc, replace=False))
        Sig = 0.01 * (rng.standard_normal((rc, rc)) + 1j * rng.standard_normal((rc, rc)))
        Sig = Sig + Sig.conj().T
        centre = 1j * rng.uniform(-2, 2)
        mine = _frozen(Kt, Om, cidx, Sig, centre, 1.3)
        ref = _small_pencil(Kt, Om, cidx, Sig)
        assert mine.size == ref.size == 2 * rc
        # each root of one is a root of the other (a multiset: matched greedily, nearest
        # first). Tolerance: both settle simple roots of an O(1) polynomial to ~1e-13; a
        # close pair splits as sqrt(eps) (1.5e-8) in either
        left = list(ref)
        for z in mine:
            j = int(np.argmin(np.abs(np.array(left) - z)))
            assert abs(left.pop(j) - z) <= 1e-7, (trial, mine, ref)
        growing += np.any(ref.real > 1e-6)
    assert rc == 1 or growing >= 3  # pairs off the axis, the case the tilt is for


def test_null_vector_is_the_dominant_eigenvector():
    rng = np.random.default_rng(5)
    V = rng.standard_normal((3, 3)) + 1j * rng.standard_normal((3, 3))
    # 1 / step against 1 / distance: the ratio of a converged Newton step at the rate floor
    M = V @ np.diag([1e9, 1e6, -3e5]) @ np.linalg.inv(V)
    y = np.empty(3, complex)
    _null_vector(M, y)
    v = V[:, 0] / V[np.argmax(np.abs(V[:, 0])), 0]
    assert np.abs(y - v).max() <= 1e-12
