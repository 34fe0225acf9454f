"""The frozen pencil's starts for ``_strong.strong_modes``: at one offset, the central
harmonics' pencil with the outer ones folded in at lambda = 0 (``_strong``'s module
docstring), its growing and colliding eigenvalues (in real arithmetic where a diagonal
phase makes the pencil real, ``_real_gauge``), and each start's eigenvector, made only
for the starts the search reaches (most are left by its cut-off: flexmm's ring ~2 ms of
~30 saved, the chain's 440 offsets likewise).
"""

from __future__ import annotations

import numpy as np
from numba import njit

from ._cluster_solve import _fold
from ._frozen_roots import _small_pencil
from ._real_gauge import frozen_real, real_gauge
from ._small_algebra import _lu, _lu_solve

_KW = dict(cache=True, nogil=True, error_model="numpy", boundscheck=False)

#: a start whose frozen eigenvector weighs at least this share of its heaviest harmonic
#: at a central one is refined as central too (``_strong``): a mode spread over two
#: harmonics five apart (probe 98: stiff-hinge at k 0.308, a 0.103, q 2.686 weighs 0.170
#: at l = -1 and 0.170 at l = 4, kept, centred at -1) had its start's vector at 0.173
#: and 0.184 there (the frozen fold's distortion, 6%), was left as off centre, and the
#: chain read stable where the dense eigenproblem grows at 3.9e-3
SPREAD_SHARE = 0.5


@njit(**_KW)
def _frozen_starts(K, Om, cidx, ridx, omega, starts, gaps, F0, X, every):
    """The frozen pencil's starts at one offset: each growing eigenvalue, and each pair
    close on the axis from between them (half their gap into ``gaps``); K_CC - Sigma
    into ``F0`` and T_RR(0)^{-1} K_RC into ``X``, what a start's eigenvector is made of
    (``_start_vector``, asked only for the starts the search reaches); all 2 r_C
    eigenvalues into ``every`` (``_between``'s certificate). Returns how many starts;
    -1 where the fold is singular."""
    rc = cidx.size
    g = np.empty(K.shape[0], np.complex128)
    ok = False
    if real_gauge(K, g):  # in real arithmetic (``_real_gauge``): ~1/3 of the cost
        Sig = np.empty((rc, rc), np.complex128)
        lam0, ok = frozen_real(K, Om, cidx, ridx, g, X, Sig)
    if not ok:
        Sig, ok = _fold(K, Om, 0j, cidx, ridx, X)
        if not ok:
            return -1
        lam0 = _small_pencil(K, Om, cidx, Sig)
    every[:] = lam0
    ns = 0
    for s in range(lam0.size):
        if lam0[s].real > 1e-9 * omega:
            starts[ns] = lam0[s]
            gaps[ns] = 0.0
            ns += 1
    order = np.argsort(lam0.imag)
    for t in range(lam0.size - 1):
        a0, b0 = lam0[order[t]], lam0[order[t + 1]]
        if abs(a0.real) > 1e-9 * omega or abs(b0.real) > 1e-9 * omega:
            continue
        gap = b0.imag - a0.imag
        if gap < 1e-2 * omega and ns < starts.size:
            starts[ns] = 0.5 * (a0 + b0) + 0.5 * gap
            gaps[ns] = 0.5 * gap
            ns += 1
    for a in range(rc):
        for b in range(rc):
            F0[a, b] = K[cidx[a], cidx[b]] - Sig[a, b]
    return ns


@njit(**_KW)
def _start_vector(F0, X, Om, cidx, ridx, lvec, P, sq, start, vec):
    """A frozen start's eigenvector (one inverse-iteration step on the frozen pencil,
    F0 = K_CC - Sigma from ``_frozen_starts``, the rest -T_RR(0)^{-1} K_RC y_C: whole,
    into ``vec``); returns its heaviest harmonic over the C part and, of the harmonics
    that weigh at least ``SPREAD_SHARE`` of it, the one nearest l = 0 (both 0 where the
    step is singular)."""
    rc, nr = cidx.size, ridx.size
    F = np.empty((rc, rc), np.complex128)
    B = np.empty((rc, 1), np.complex128)
    piv = np.empty(rc, np.int64)
    for a in range(rc):
        for b in range(rc):
            F[a, b] = F0[a, b]
        z = start - 1j * Om[cidx[a]]
        F[a, a] += z * z
        B[a, 0] = 1.0
    larg = 0
    lnear = 0
    if _lu(F, piv):
        _lu_solve(F, piv, B)
        per_l = np.zeros(2 * P + 1)
        for a in range(rc):
            per_l[lvec[a] + P] += abs(B[a, 0] * sq[cidx[a] % sq.size]) ** 2
        larg = np.argmax(per_l) - P
        lnear = larg
        top = per_l[larg + P]
        for li in range(2 * P + 1):
            if per_l[li] >= SPREAD_SHARE * top and abs(li - P) < abs(lnear):
                lnear = li - P
    for a in range(rc):
        vec[cidx[a]] = B[a, 0]
    for a in range(nr):
        acc = 0j
        for b in range(rc):
            acc += X[a, b] * B[b, 0]
        vec[ridx[a]] = -acc
    return larg, lnear
