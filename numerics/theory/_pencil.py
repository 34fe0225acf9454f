"""The exact sideband eigenvalue at a probe, by Newton on the Hill matrix's quadratic pencil.

The first-order Hill matrix of ``_hill`` at harmonics H = 1 (``_quasiperiodic.hill_matrices``)
has the eigenvalues of the pencil

    Q(lambda) = (lambda - i F)^2 - L,    det Q(lambda) = 0,

with L (n x n) the couplings of the theta sidebands p = -1, +1 and (case II) the U modes
p = -2, 0, 2, and F = diag(p Omega). ``resonance_map`` needs, at each probe offset, the
growing sideband pair that the reduced problem (``_reduced``) places near

    lambda_0 = sigma_red + i (omega_- - omega_+) / 2.

Newton on det Q(lambda) = det S(lambda) prod_u den_u(lambda), with S the 2 x 2 theta block,
the U modes folded in exactly (the Schur complement S = (lambda - i p Omega)^2 - L_tt - L_tU
diag(1 / den_u) L_Ut, den_u = (lambda - i u Omega)^2 + omega_U^2), settles on it in a few
steps of a few dozen flops: 0.4 s of CPU for the 240 000 probes of a 200 x 200 case II map,
where the 10 x 10 eigenvalues (``np.linalg.eigvals``, 27 us each here) took 6.8 s of CPU
(summed over the map's two threads; the map took 7.4 s wall then). The eigenvector
(theta from S's null space, U by the Schur complement) gives the sideband test. Probes where
Newton does not settle, or settles on the decaying mirror of a pair (the spectrum is
symmetric under lambda -> -conj(lambda)), are left to the full eigenproblem by the caller.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

from ._reduced import _entry

#: Newton steps at most, and the step (relative to |lambda| + Omega) that counts as settled:
#: ~1e4 eps, above the round-off of det Q near a simple root (a double root, sigma -> 0 at a
#: band edge, converges only linearly and is left to the eigenproblem)
NEWTON_STEPS, NEWTON_TOL = 30, 1e-12


def pencil_eigenvalues(C, k, W, alpha, q, cell, lam0, coupled):
    """Newton on det Q (through the pencil's theta block, module docstring) from ``lam0``.

    Parameters
    ----------
    C : dict name -> ndarray, shape (B, 3, M)
        The couplings' Fourier coefficients of B plane waves (``_hill._coefficients``).
    k, W, alpha : ndarray, shape (B,)
        Carrier wavenumbers, frequencies and the materials' alpha.
    q, cell, lam0 : ndarray, shape (P,)
        Each probe's offset, its cell (index into B) and Newton's start.
    coupled : bool
        Case II (theta and U) or case I (theta only).

    Returns
    -------
    lam : ndarray of complex, shape (P,)
        The eigenvalue reached.
    share : ndarray, shape (P, 2)
        Kinetic-energy shares of the sidebands k + q, k - q in its eigenvector (as
        ``_quasiperiodic.sideband_shares``).
    settled : ndarray of bool, shape (P,)
        Newton settled within NEWTON_STEPS.
    """
    P = np.size(q)
    lam = np.empty(P, complex)
    share = np.empty((P, 2))
    settled = np.zeros(P, bool)
    _newton(C["tt"], C["tU"], C["Ut"], np.asarray(k, float), np.asarray(W, float),
            np.asarray(alpha, float) ** 2, np.asarray(q, float), np.asarray(cell, np.int64),
            np.asarray(lam0, complex), bool(coupled), NEWTON_STEPS, NEWTON_TOL, lam, share,
            settled)
    return lam, share, settled


@njit(cache=True, nogil=True, error_model="numpy", boundscheck=False)
def _schur(L, W, lam, coupled, S, dS, den):
    """The theta block S(lam) (2 x 2, U folded in) and dS/dlam into S, dS; den_u into den."""
    for a in range(2):
        for b in range(2):
            S[a, b] = -L[a, b]
            dS[a, b] = 0.0
        d = lam - 1j * (2 * a - 1) * W  # p = -1, +1
        S[a, a] += d * d
        dS[a, a] += 2 * d
    if coupled:
        for iu in range(3):
            z = lam - 1j * (2 * iu - 2) * W
            den[iu] = z * z - L[2 + iu, 2 + iu]
            dden = 2 * z / den[iu]
            for a in range(2):
                for b in range(2):
                    t = L[a, 2 + iu] * L[2 + iu, b] / den[iu]
                    S[a, b] -= t
                    dS[a, b] += t * dden


@njit(cache=True, nogil=True, error_model="numpy", boundscheck=False)
def _couplings(tt, tU, Ut, k, q, coupled, L):
    """L of one probe: L[a, b] = sum_j c_{j, p_a - p_b} e^{i (q + p_b k) j}, labels theta
    p = -1, 1, then U p = -2, 0, 2 with its diagonal -omega_U(q + p k)^2 (``hill_matrices``)."""
    E = np.empty(5, np.complex128)  # e^{i (q + p k)}, p = -2 .. 2 at p + 2
    for p in range(-2, 3):
        E[p + 2] = np.exp(1j * (q + p * k))
    th = (-1, 1)
    for r in range(2):
        for c in range(2):
            L[r, c] = _entry(tt, th[r] - th[c], E[th[c] + 2])
    if coupled:
        for iu in range(3):
            u = 2 * iu - 2
            for r in range(2):
                L[r, 2 + iu] = _entry(tU, th[r] - u, E[u + 2])
                L[2 + iu, r] = _entry(Ut, u - th[r], E[th[r] + 2])
            for c in range(3):
                L[2 + iu, 2 + c] = 0.0
            wU = 2.0 * abs(math.sin(0.5 * (q + u * k)))
            L[2 + iu, 2 + iu] = -wU * wU


@njit(cache=True, nogil=True, error_model="numpy", boundscheck=False)
def _newton(tt, tU, Ut, k, W, a2, q, cell, lam0, coupled, steps, tol, lam_out, share_out,
            settled):
    n = 5 if coupled else 2
    L = np.empty((n, n), np.complex128)
    S = np.empty((2, 2), np.complex128)
    dS = np.empty((2, 2), np.complex128)
    den = np.ones(3, np.complex128)
    x = np.zeros(n, np.complex128)
    for i in range(q.size):
        b = cell[i]
        w = W[b]
        _couplings(tt[b], tU[b], Ut[b], k[b], q[i], coupled, L)
        lam = lam0[i]
        for _ in range(steps):
            _schur(L, w, lam, coupled, S, dS, den)
            f = S[0, 0] * S[1, 1] - S[0, 1] * S[1, 0]
            df = (dS[0, 0] * S[1, 1] + S[0, 0] * dS[1, 1] - dS[0, 1] * S[1, 0]
                  - S[0, 1] * dS[1, 0])
            if f == 0:  # lam is the eigenvalue
                settled[i] = True
                break
            # the step of det Q = det S prod_u den_u, a polynomial: no poles to throw
            # Newton off where an uncoupled U mode sits near the root
            t = df / f
            if coupled:
                for iu in range(3):
                    t += 2 * (lam - 1j * (2 * iu - 2) * w) / den[iu]
            step = 1.0 / t
            lam -= step
            if abs(step) < tol * (abs(lam) + w):
                settled[i] = True
                break
        lam_out[i] = lam
        # the eigenvector: theta's from S's null space (its larger row), U's by the Schur
        # complement, X_u = sum_b L_ub X_b / den_u
        _schur(L, w, lam, coupled, S, dS, den)
        if abs(S[0, 0]) + abs(S[0, 1]) >= abs(S[1, 0]) + abs(S[1, 1]):
            x[0], x[1] = S[0, 1], -S[0, 0]
        else:
            x[0], x[1] = S[1, 1], -S[1, 0]
        if coupled:
            for iu in range(3):
                x[2 + iu] = (L[2 + iu, 0] * x[0] + L[2 + iu, 1] * x[1]) / den[iu]
        # kinetic energies of the lab velocities (lam - i p Omega) X, eq. `norm`'s weights
        total, plus, minus = 0.0, 0.0, 0.0
        for r in range(n):
            p = 2 * r - 1 if r < 2 else 2 * r - 6
            e = abs((lam - 1j * p * w) * x[r]) ** 2
            e = e / (2 * a2[b]) if r < 2 else 2 * e
            total += e
            if r == 1:
                plus += e
            elif r == 0:
                minus += e
        if not total > 0:  # S = 0: a double root, its eigenvectors not unique
            settled[i] = False
            total = 1.0
        share_out[i, 0] = plus / total
        share_out[i, 1] = minus / total
