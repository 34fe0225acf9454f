"""The refinement of ``_strong``'s starts on the whole Hill pencil at P (nonlinear inverse
iteration from a start and its vector, Newton on the Schur complement past a known root),
and its test of a mode the kept rule may keep, split from ``_strong`` (its module
docstring says how they are used)."""

from __future__ import annotations

import numpy as np
from numba import njit

from ._cluster_solve import STEPS, TOL, _newton_step
from ._small_algebra import _lu, _lu_solve

_KW = dict(cache=True, nogil=True, error_model="numpy", boundscheck=False)


@njit(**_KW)
def _kept(vec, P, d):
    """The dense spectrum's rule (``_exact``): largest weight at |l| <= 1, less than 1e-6
    of it in the outer three harmonics; here with a margin (the central weight 1e-6 over
    any other): where two harmonics tie (a mode its own mirror image one or two harmonics
    over, as at q = pi - k on a ring), round-off decides the rule, and a mode the caller's
    rule may drop must not stop the search for the next one."""
    per_l = np.zeros(2 * P + 1)
    tot = 0.0
    for i in range(vec.size):
        w = abs(vec[i]) ** 2
        per_l[i // d] += w
        tot += w
    outer = per_l[0] + per_l[1] + per_l[2] + per_l[-1] + per_l[-2] + per_l[-3]
    centre = max(per_l[P - 1], per_l[P], per_l[P + 1])
    rest = 0.0
    for li in range(2 * P + 1):
        if abs(li - P) > 1:
            rest = max(rest, per_l[li])
    return centre > (1 + 1e-6) * rest and outer < 1e-6 * tot


@njit(**_KW)
def _newton_past(Kt, Om, lam, cidx, ridx, scale, X, known):
    """Newton on det S(lambda) from ``lam`` with the root ``known`` divided out (Maehly,
    ``_cluster_solve._newton_step``, besides a growing iterate's mirror): the second root of a
    pair the frozen pencil placed off the axis. Returns (lambda, settled)."""
    rc = cidx.size
    S = np.empty((rc, rc), np.complex128)
    dS = np.empty((rc, rc), np.complex128)
    piv = np.empty(rc, np.int64)
    for _ in range(STEPS):
        state, lam = _newton_step(Kt, Om, lam, cidx, ridx, scale, X, S, dS, piv, True, True,
                                  known)
        if state != 0:
            return lam, state > 0  # 2: exactly singular, an eigenvalue
    return lam, False


@njit(**_KW)
def _refine(K, Om, lam, v, scale, split=False):
    """Nonlinear inverse iteration on the whole pencil T(lambda) = (lambda - i Omega)^2 + K
    (Ruhe's: w = T^{-1} T' v, lambda -= 1 / (v^* w), v = w / |w|; quadratic, Newton on det T
    for one coordinate) from ``lam`` and the frozen pencil's eigenvector ``v`` (unit norm,
    updated in place), until a step is below TOL, as ``_cluster_solve._newton``. One LAPACK
    solve of n x n a step, against the Schur complement's two solves and two products;
    ``split`` (the pencil's nonzeros in separate blocks): by the LU that skips zeros
    instead, which then costs what the blocks do (stiff-hinge's two halves: 12 us
    against LAPACK's 20; slower on a connected pencil). Returns (lambda, settled)."""
    n = Om.size
    T = np.empty((n, n), np.complex128)
    rhs = np.empty(n, np.complex128)
    B = np.empty((n, 1), np.complex128)
    piv = np.empty(n, np.int64)
    for _ in range(STEPS):
        for a in range(n):
            for b in range(n):
                T[a, b] = K[a, b]
            z = lam - 1j * Om[a]
            T[a, a] += z * z
            rhs[a] = 2 * z * v[a]
        if split:
            if not _lu(T, piv):
                return lam, False  # exactly singular, as below
            for a in range(n):
                B[a, 0] = rhs[a]
            _lu_solve(T, piv, B)
            w = B[:, 0]
        else:
            try:
                w = np.linalg.solve(T, rhs)
            except Exception:  # exactly singular: lam is an eigenvalue, v not yet its vector
                return lam, False
        vw = 0j
        nrm = 0.0
        for a in range(n):
            vw += np.conj(v[a]) * w[a]
            nrm += abs(w[a]) ** 2
        if vw == 0 or not nrm > 0:
            return lam, False
        step = -1.0 / vw
        lam += step
        nrm = np.sqrt(nrm)
        for a in range(n):
            v[a] = w[a] / nrm
        if abs(step) <= TOL * (abs(lam) + scale):
            return lam, True
    return lam, False
