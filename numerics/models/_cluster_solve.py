"""The compiled Hill kernel's solve of one cluster of Gershgorin discs
(``_sidebands.sideband_modes`` finds the clusters; ``_sidebands``' module docstring says
which can hold a growing mode), split from ``_sidebands``: the fold of the rest of the
pencil by its Schur complement, the frozen pencil's starts and Newton on det S.

Solving a cluster. With C its coordinates (r_c of them) and the rest folded in by the Schur
complement, S(lambda) = T_CC(lambda) - E_CR (T_RR(lambda))^{-1} E_RC, whose zeros near the
cluster are the pencil's eigenvalues there. The fold Sigma(lambda) = E_CR T_RR^{-1} E_RC
changes slowly across the cluster (the other roots are outside it): the r_c x r_c pencil
with Sigma frozen at the cluster's centre places all the cluster's eigenvalues at once;
Newton on det S from each that grows (and from where two that nearly meet on the axis
grow once the fold is frozen again between them) settles on the exact ones, the growing
root's mirror -conj(lambda) divided out. Its eigenvector (S's null vector, the rest -T_RR^{-1} E_RC y_C) gives the weights the kept
modes are chosen by, as the dense eigenproblem's did. Where Newton does not settle, or a
cluster is larger than the caller allows, the caller solves that offset densely.
"""

from __future__ import annotations

import numpy as np
from numba import njit

from ._frozen_roots import _frozen
from ._small_algebra import _ldlh, _ldlh_half, _lu, _lu_solve, _lu_solve_t, _null_vector

#: Newton steps at most per eigenvalue, and the step (relative to |lambda| + omega)
#: after which it has settled: Newton's next error is ~ its square, below round-off
STEPS, TOL = 40, 1e-9

_KW = dict(cache=True, nogil=True, error_model="numpy", boundscheck=False)


@njit(**_KW)
def _pencil_block(Kt, Om, lam, idx, out):
    """T(lam) = K + (lam - i Omega)^2 on the coordinates ``idx`` (rows and columns), into
    ``out``: the blocks T_RR and T_CC that the Schur complement and the fold factor."""
    n = idx.size
    for a in range(n):
        ia = idx[a]
        for b in range(n):
            out[a, b] = Kt[ia, idx[b]]
        z = lam - 1j * Om[ia]
        out[a, a] += z * z


@njit(**_KW)
def _schur(Kt, Om, lam, cidx, ridx, X, S, dS):
    """S(lam) = T_CC - E_CR T_RR^{-1} E_RC and dS/dlam into S, dS; X = T_RR^{-1} E_RC;
    False where T_RR is singular."""
    nr = ridx.size
    rc = cidx.size
    A = np.empty((nr, nr), np.complex128)
    Yt = np.empty((nr, rc), np.complex128)
    _pencil_block(Kt, Om, lam, ridx, A)
    for a in range(nr):
        ia = ridx[a]
        for b in range(rc):
            X[a, b] = Kt[ia, cidx[b]]
            Yt[a, b] = Kt[cidx[b], ia]
    _pencil_block(Kt, Om, lam, cidx, S)
    for a in range(rc):
        for b in range(rc):
            dS[a, b] = 0.0
        dS[a, a] = 2 * (lam - 1j * Om[cidx[a]])
    if nr == 0:
        return True
    piv = np.empty(nr, np.int64)
    if not _lu(A, piv):
        return False
    _lu_solve(A, piv, X)
    _lu_solve_t(A, piv, Yt)
    for a in range(rc):
        for b in range(rc):
            s = 0j
            t = 0j
            for c in range(nr):
                s += Kt[cidx[a], ridx[c]] * X[c, b]
                t += Yt[c, a] * (2 * (lam - 1j * Om[ridx[c]])) * X[c, b]
            S[a, b] -= s
            dS[a, b] += t
    return True


@njit(**_KW)
def _newton_step(Kt, Om, lam, cidx, ridx, scale, X, S, dS, piv, mirror, past, known):
    """One step of Newton on det S(lambda) from ``lam``, -1 / tr(S^{-1} S'), with roots
    divided out (Maehly): ``known`` where ``past``, then the mirror -conj(lambda) where
    ``mirror`` and lambda grows. Returns (state, lambda): state 1 settled (the step below
    TOL: quadratic convergence, the step after it is below round-off), 0 not yet, 2 S
    exactly singular at ``lam`` (an eigenvalue; not moved), -1 failed (T_RR singular,
    the iterate on ``known``, or a zero trace). At states 0 and 1 it leaves, at the
    ``lam`` it stepped from, X = T_RR^{-1} E_RC, S factored and dS = S^{-1} S'
    (``_newton``'s null vector)."""
    if not _schur(Kt, Om, lam, cidx, ridx, X, S, dS):
        return -1, lam
    if not _lu(S, piv):
        return 2, lam
    _lu_solve(S, piv, dS)
    tr = 0j
    for a in range(cidx.size):
        tr += dS[a, a]
    if past:
        if lam == known:
            return -1, lam
        tr -= 1.0 / (lam - known)
    if mirror and lam.real > 1e-9 * scale:
        # the mirror root -conj(lambda) deflated: a growing pair's roots are 2 Re lambda
        # apart, and Newton on det S alone crawls between them
        tr -= 1.0 / (2.0 * lam.real)
    if tr == 0:
        return -1, lam
    step = -1.0 / tr
    lam += step
    return (1 if abs(step) <= TOL * (abs(lam) + scale) else 0), lam


@njit(**_KW)
def _newton(Kt, Om, lam, cidx, ridx, scale, y, deflate, X):
    """Newton on det S(lambda) from ``lam`` (``_newton_step``; with ``deflate`` the
    mirror root -conj(lambda) divided out) until a step is below TOL; the eigenvalue and
    its C part into y, T_RR^{-1} E_RC at it into X (shape (n_R, r_C): the eigenvector's
    rest is -X y). Returns (lambda, settled)."""
    rc = cidx.size
    S = np.empty((rc, rc), np.complex128)
    dS = np.empty((rc, rc), np.complex128)
    piv = np.empty(rc, np.int64)
    state = 0
    for _ in range(STEPS):
        state, lam = _newton_step(Kt, Om, lam, cidx, ridx, scale, X, S, dS, piv, deflate,
                                  False, 0j)
        if state != 0:
            break
    if state <= 0:
        return lam, False
    if state == 1:
        # the null vector from the last step's factors (S and X at lambda - step): the
        # eigenvector of the pencil S(lambda - step) + mu S' nearest mu = step, by
        # power iteration on dS = S^{-1} S' (its dominant eigenvalue ~ 1 / step; the next,
        # the mirror's or another root's, ~ 1 / distance: each sweep leaves their ratio
        # of the others), until it no longer moves. It differs from S(lambda)'s null
        # vector by O(step^2), the rest -X y by O(step) (~1e-9 of |X|): what one more
        # Schur complement and LU of the rest cost
        _null_vector(dS, y)
        return lam, True
    # the null vector of S(lambda): one inverse-iteration step
    _schur(Kt, Om, lam, cidx, ridx, X, S, dS)
    B = np.ones((rc, 1), np.complex128)
    if _lu(S, piv):
        _lu_solve(S, piv, B)
        nrm = 0.0
        for a in range(rc):
            nrm = max(nrm, abs(B[a, 0]))
        for a in range(rc):
            y[a] = B[a, 0] / nrm
    else:  # a zero pivot: its column is free
        for a in range(rc):
            y[a] = 0.0
        j = 0
        for a in range(rc):
            if S[a, a] == 0:
                j = a
        y[j] = 1.0
        for i in range(j - 1, -1, -1):
            t = 0j
            for c in range(i + 1, rc):
                t += S[i, c] * y[c]
            y[i] = -t / S[i, i] if S[i, i] != 0 else 0.0
    return lam, True


@njit(**_KW)
def _fold(Kt, Om, lam, cidx, ridx, X):
    """Sigma(lam) (r_c x r_c) and X = T_RR(lam)^{-1} E_RC (into ``X``); ok flag."""
    nr = ridx.size
    rc = cidx.size
    A = np.empty((nr, nr), np.complex128)
    _pencil_block(Kt, Om, lam, ridx, A)
    for a in range(nr):
        for b in range(rc):
            X[a, b] = Kt[ridx[a], cidx[b]]
    piv = np.empty(nr, np.int64)
    Sig = np.zeros((rc, rc), np.complex128)
    if nr == 0:
        return Sig, True
    if not _lu(A, piv):
        return Sig, False
    _lu_solve(A, piv, X)
    for a in range(rc):
        for b in range(rc):
            s = 0j
            for c in range(nr):
                s += Kt[cidx[a], ridx[c]] * X[c, b]
            Sig[a, b] = s
    return Sig, True


@njit(**_KW)
def _fold_axis(Kt, Om, mu, cidx, ridx, X, lo, hi):
    """Sigma(i mu) as ``_fold``'s, for mu in the cluster's span [lo, hi]: there every
    coordinate of the rest lies outside its own discs, |(i mu - i Omega_j)^2 + w_j^2| >
    R_j (the discs hold every point of the axis where it is not), so T_RR(i mu) =
    K_RR - (mu - Omega_R)^2 is Hermitian and strictly diagonally dominant by rows, and
    its L D L^* needs no pivoting (``_ldlh``: half an LU's products), Sigma = Z^* D^{-1} Z
    with Z = L^{-1} E_RC. Elsewhere, or where a pivot vanishes, ``_fold``."""
    nr = ridx.size
    rc = cidx.size
    if nr == 0 or not (lo <= mu <= hi):
        return _fold(Kt, Om, 1j * mu, cidx, ridx, X)
    A = np.empty((nr, nr), np.complex128)
    for a in range(nr):
        ia = ridx[a]
        for b in range(a):
            A[a, b] = Kt[ia, ridx[b]]
        z = mu - Om[ia]
        A[a, a] = Kt[ia, ia].real - z * z
    if not _ldlh(A):
        return _fold(Kt, Om, 1j * mu, cidx, ridx, X)
    for a in range(nr):
        for b in range(rc):
            X[a, b] = Kt[ridx[a], cidx[b]]
    _ldlh_half(A, X)
    # Sigma = Z^* D^{-1} Z with D^{-1} taken once a row (a product, not a division, in
    # the inner loop)
    for c in range(nr):
        A[c, c] = 1.0 / A[c, c].real
    Sig = np.zeros((rc, rc), np.complex128)
    for a in range(rc):
        r = 0.0  # the diagonal: real
        for c in range(nr):
            x = X[c, a]
            r += (x.real * x.real + x.imag * x.imag) * A[c, c].real
        Sig[a, a] = r
        for b in range(a + 1, rc):
            s = 0j
            for c in range(nr):
                s += np.conj(X[c, a]) * (X[c, b] * A[c, c].real)
            Sig[a, b] = s
            Sig[b, a] = np.conj(s)
    return Sig, True


@njit(**_KW)
def _offset(Kt, Om, lvec, cidx, ridx, lo, hi, floor, om, out_lam, out_vec):
    """The eigenvalues of one cluster (roots in [lo, hi] on the imaginary axis) with
    Re lambda > floor: into out_lam / out_vec (full coordinates); their count, or -1 where
    Newton did not settle. Starts: the pencil with the fold frozen at the cluster's centre
    (all its eigenvalues there at once): each that grows, and, for two of them close on
    the axis (a collision the fold frozen at the centre may not resolve), each that grows
    with the fold frozen again between them."""
    rc = cidx.size
    nr = ridx.size
    X = np.empty((nr, rc), np.complex128)
    width = hi - lo
    scale = width + om
    Sig, ok = _fold_axis(Kt, Om, 0.5 * (lo + hi), cidx, ridx, X, lo, hi)
    if not ok:
        return -1
    lam0 = _frozen(Kt, Om, cidx, Sig, 0.5j * (lo + hi), scale)
    inside = np.zeros(lam0.size, np.bool_)
    for s in range(lam0.size):
        inside[s] = (lo - 0.5 * width <= lam0[s].imag <= hi + 0.5 * width
                     and lam0[s].real >= -1e-9 * om)
    starts = np.empty(lam0.size * lam0.size, np.complex128)
    ns = 0
    for s in range(lam0.size):
        if inside[s] and lam0[s].real > 1e-9 * om:
            starts[ns] = lam0[s]
            ns += 1
    for s in range(lam0.size):
        for t in range(s + 1, lam0.size):
            gap = abs(lam0[s] - lam0[t])
            if not (inside[s] and inside[t] and gap < 0.1 * width + 1e-6 * om):
                continue
            if lam0[s].real > 1e-9 * om or lam0[t].real > 1e-9 * om:
                continue  # a growing pair: already a start
            # two close on the axis: the fold frozen again between them (its error is
            # then second order in their distance) says whether they meet
            mid = 0.5 * (lam0[s] + lam0[t])
            Sig, ok = _fold_axis(Kt, Om, mid.imag, cidx, ridx, X, lo, hi)
            if not ok:
                return -1
            lam1 = _frozen(Kt, Om, cidx, Sig, 1j * mid.imag, scale)
            # the growing one nearest them, wherever in the cluster: a pair that meets
            # splits by its coupling, not by its frozen gap (probe 98: stiff-hinge, a
            # pair 5.5e-4 apart frozen at the centre grew at 2.4e-3 refrozen between
            # them; a bound of 2x the gap left it and certified the offset stable). Only
            # a start: Newton on the whole pencil decides
            best, near = -1, np.inf
            for u in range(lam1.size):
                if (lam1[u].real > 1e-9 * om and abs(lam1[u] - mid) < near
                        and lo - 0.5 * width <= lam1[u].imag <= hi + 0.5 * width):
                    best, near = u, abs(lam1[u] - mid)
            if best >= 0:
                starts[ns] = lam1[best]
                ns += 1
    found = 0
    y = np.empty(rc, np.complex128)
    for s in range(ns):
        lam, settled = _newton(Kt, Om, starts[s], cidx, ridx, scale, y, True, X)
        if not settled or not (lo - 0.5 * width <= lam.imag <= hi + 0.5 * width):
            lam, settled = _newton(Kt, Om, starts[s], cidx, ridx, scale, y, False, X)
        if not settled:
            return -1
        if lam.real <= floor:
            continue
        if not (lo - 0.5 * width <= lam.imag <= hi + 0.5 * width):
            return -1  # Newton left the cluster: let the dense eigenproblem decide
        dup = False
        for f in range(found):
            if abs(out_lam[f] - lam) <= 1e-9 * scale:
                dup = True
        if dup:
            continue
        if found >= out_lam.size:
            return -1
        for a in range(rc):  # X: T_RR^{-1} E_RC at lam, from Newton's last step
            out_vec[found, cidx[a]] = y[a]
        for a in range(nr):
            acc = 0j
            for b in range(rc):
                acc += X[a, b] * y[b]
            out_vec[found, ridx[a]] = -acc
        out_lam[found] = lam
        found += 1
    return found
