"""The sideband eigenvalue by Newton on the Hill pencil (numerics.theory._pencil) against the
full eigenproblem of the same Hill matrices."""

from __future__ import annotations

import numpy as np
import pytest

from common import paper
from numerics.theory import _resonance
from numerics.theory._hill import _coefficients, _hill_batch, _sideband_share
from numerics.theory._pencil import pencil_eigenvalues
from numerics.theory._plane_wave import _solve_plane_waves


def _waves(case, amplitude=0.05):
    k = np.array([0.4, 1.2, 2.0, 2.7])
    B = k.size
    al, Ks = np.full(B, paper.ALPHA), np.full(B, paper.K_S)
    Kt = Ks - np.array([0.012, -0.004, 0.008, -0.01])
    x, _ = _solve_plane_waves(k, np.full(B, amplitude), al, Ks, Kt, case == "coupled", 1,
                              points=_resonance.PHASES)
    a, b, W = x[:, :1], x[:, 1:2], x[:, -1]
    C = _coefficients(a, b, k, al, Ks, Kt, _resonance.PHASES)
    return a, b, k, W, al, Ks, Kt, C


@pytest.mark.parametrize("case", ["rotation", "coupled"])
def test_newton_reaches_every_theta_eigenvalue_with_its_eigenvector(case):
    """Started 1e-3 Omega off any theta-dominated eigenvalue of the 2n x 2n Hill matrix,
    Newton settles on that eigenvalue (to 1e-9 Omega: the matrices' entries are O(1), LAPACK's
    eigenvalues good to ~1e-14, Newton's stop at 1e-12) and its sideband shares equal the
    full eigenvector's (1e-6: shares are ratios of squared components, conditioned by the
    eigenvalue's separation, >= 1e-3 here)."""
    a, b, k, W, al, Ks, Kt, C = _waves(case)
    q = np.linspace(0.05, 3.1, 25)
    A, labels = _hill_batch(a, b, k, W, al, Ks, Kt, q, 1, case == "coupled", C=C)
    lam, vec = np.linalg.eig(A)  # (B, nq, 2n), (B, nq, 2n, 2n)
    share = _sideband_share(vec, labels, al[:, None] ** 2)  # (B, nq, 2n, 2)
    n = A.shape[-1] // 2
    theta = np.sum(np.abs(vec[..., n:n + 2, :]) ** 2 / (2 * al[:, None, None, None] ** 2),
                   axis=-2)
    energy = theta + 2 * np.sum(np.abs(vec[..., n + 2:, :]) ** 2, axis=-2)
    pick = theta / energy > 0.5  # theta-dominated modes; U modes are left to eig
    cell, iq, mode = np.nonzero(pick)
    gap = np.sort(np.abs(lam[cell, iq][:, :, None] - lam[cell, iq][:, None, :]).reshape(
        cell.size, -1), axis=1)[:, 2 * n]  # distance to the nearest other eigenvalue
    ok = gap > 1e-2 * W[cell]  # Newton from 1e-3 Omega off needs a simple, separated root
    cell, iq, mode = cell[ok], iq[ok], mode[ok]
    assert cell.size > 100
    target = lam[cell, iq, mode]
    got, sh, settled = pencil_eigenvalues(C, k, W, al, q[iq], cell,
                                          target + 1e-3 * W[cell] * (1 + 1j), case == "coupled")
    assert settled.all()
    assert np.max(np.abs(got - target) / W[cell]) < 1e-9
    assert np.max(np.abs(sh - share[cell, iq, mode])) < 1e-6


@pytest.mark.parametrize("start", ["travelling", "paper"])
def test_map_rates_equal_the_full_eigenproblem(start, monkeypatch):
    """resonance_map with every probe sent to the full eigenproblem gives the same map: the
    rates agree to round-off: 1e-12 absolute, ~100 eps times the Hill matrix's norm (~4),
    the accuracy of an eigenvalue from either method (a different root would differ by
    the rates themselves, >= 1e-6)."""
    k = np.linspace(0.05, np.pi - 0.05, 24)
    d = np.linspace(-0.015, 0.015, 12)
    K, D = np.meshgrid(k, d)
    args = (K, D, "coupled", paper.ALPHA, paper.K_S, 0.05)
    fast = resonance_map_peak(*args, start=start)
    exact = _resonance._exact_rates

    def eig_only(a, b, kk, W, al, Ks, Kt, C, probes, s_red, coupled, eig):
        return exact(a, b, kk, W, al, Ks, Kt, C, probes, s_red, coupled,
                     np.ones_like(eig))
    monkeypatch.setattr(_resonance, "_exact_rates", eig_only)
    slow = resonance_map_peak(*args, start=start)
    assert np.array_equal(np.isnan(fast), np.isnan(slow))
    assert np.sum(np.nan_to_num(fast) > 0) > 20
    np.testing.assert_allclose(np.nan_to_num(fast), np.nan_to_num(slow), rtol=0, atol=1e-12)


def resonance_map_peak(*args, start):
    return _resonance.resonance_map(*args, start=start)["peak_gain"]


@pytest.mark.parametrize("amplitude, alpha", [(0.1, 2.5), (0.1, 5.0), (0.2, 2.5)])
def test_map_equals_the_full_eigenproblem_at_large_amplitude(amplitude, alpha, monkeypatch):
    """Up to NEWTON_AMPLITUDE (0.1) Newton serves the probes and the map equals the full
    eigenproblem's (checked at the bound, at two alphas); above it, where the reduced
    pair's start can sit nearer another root (0.2: 8 of 3 600 cells lost their band in a
    review), every probe gets the full eigenproblem (atol as above)."""
    k = np.linspace(0.05, np.pi - 0.05, 30)
    d = np.linspace(-0.015, 0.015, 10)
    K, D = np.meshgrid(k, d)
    # and the review's cell where Newton from the reduced pair settles on a neutral root
    # at 0.2 while the Hill spectrum holds an MI mode growing at 0.042
    K, D = np.append(K, 1.5966), np.append(D, -0.00229)
    args = (K, D, "coupled", alpha, paper.K_S, amplitude)
    fast = resonance_map_peak(*args, start="travelling")
    exact = _resonance._exact_rates

    def eig_only(a, b, kk, W, al, Ks, Kt, C, probes, s_red, coupled, eig):
        return exact(a, b, kk, W, al, Ks, Kt, C, probes, s_red, coupled,
                     np.ones_like(eig))
    monkeypatch.setattr(_resonance, "_exact_rates", eig_only)
    slow = resonance_map_peak(*args, start="travelling")
    assert np.array_equal(np.isnan(fast), np.isnan(slow))
    assert np.sum(np.nan_to_num(fast) > 0) > 20
    np.testing.assert_allclose(np.nan_to_num(fast), np.nan_to_num(slow), rtol=0, atol=1e-12)
