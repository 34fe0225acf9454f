"""The frozen pencil of ``_strong`` in real arithmetic, where a diagonal phase makes the Hill
pencil real (issue 41: the frozen pencil's eigenvalues were ~90% of flexmm's exact theory).

At offset q the scaled pencil is T(lambda) = (lambda - i Omega)^2 + K(q), K Hermitian,
Omega = diag(l omega) (``_sidebands``). Where a diagonal unitary G (phases g_a) makes
R = G^* K G real (R_ab = conj(g_a) K_ab g_b), G commutes with Omega, and with lambda = i mu

    G^* T(i mu) G = R - (mu - Omega)^2,

a real pencil in mu: its eigenvalues are real (lambda on the imaginary axis) or come in
conjugate pairs (lambda and -conj(lambda), the Hamiltonian pair), and its linearisation
mu [y; x] = [[Omega, I], [A, Omega]] [y; x] (x = (mu - Omega) y) is real: LAPACK's dgeev
on it costs ~1/3 of zgeev's on the complex companion matrix (measured, 44 x 44: 0.25 ms
against 0.74 ms). The fold is gauge covariant (Sigma = G_C Sigma_R G_C^*, with
Sigma_R = R_CR (R_RR - Omega_R^2)^{-1} R_RC), so the whole frozen pencil is real.

When a gauge exists. The phases of a spanning tree of K's entries fix G (the heaviest
entries first, Prim's tree: g_b = g_a conj(K_ab) / |K_ab| makes R_ab = |K_ab| > 0); the
other entries must then come out real, checked: |Im R| <= GAUGE_TOL max |K|. A wave with
a reflection symmetry (each field even or odd in xi after a shift: every built-in model's,
measured at 5 offsets of 13 points of seven models, |Im R| <= 5e-16 max |K|) has one; where
the check fails, the caller solves the complex pencil as before. Dropping Im R (at most
GAUGE_TOL of the matrix) moves the frozen eigenvalues, which are starts refined on the
exact complex pencil (``_strong._refine``), by far less than the frozen fold's own error.
"""

from __future__ import annotations

import numpy as np
from numba import njit, types
from numba.np.linalg import _LAPACK

# one LU for both: compiled per argument type, real here, complex in the Hill kernel
from ._small_algebra import _lu, _lu_solve

#: |Im R| over max |K| below which the gauged pencil is taken as real (round-off is
#: ~5e-16 at P = 10: the margin is 200x; a wave without the symmetry has O(1) there)
GAUGE_TOL = 1e-13

_KW = dict(cache=True, nogil=True, error_model="numpy", boundscheck=False)

# LAPACK's dgeev as numba's own np.linalg.eigvals calls it (numba pinned in pyproject.toml):
# numba's eigvals of a real matrix raises where an eigenvalue is complex, which is the case
# that matters here. An external symbol resolved at load time, so the module stays cached.
_dgeev = _LAPACK().numba_ez_rgeev(types.float64)
_DOUBLE, _NO_VECTORS = ord("d"), ord("N")


@njit(**_KW)
def real_gauge(K, g):
    """Phases ``g`` (into it, shape (n,)) with conj(g_a) K_ab g_b real for every entry, by
    Prim's maximum spanning tree over |K_ab| (a new root, phase 1, for each connected
    component). True where the gauge holds: max |Im| <= GAUGE_TOL max |K|."""
    n = K.shape[0]
    intree = np.zeros(n, np.bool_)
    best = np.zeros(n)  # |K|^2: the same tree as |K|, without a square root per entry
    parent = np.full(n, -1, np.int64)
    big = 0.0
    for a in range(n):
        for b in range(n):
            big = max(big, K[a, b].real ** 2 + K[a, b].imag ** 2)
    for _ in range(n):
        j, w = -1, -1.0
        for a in range(n):
            if not intree[a] and best[a] > w:
                j, w = a, best[a]
        p = parent[j]
        if p >= 0 and w > 0:
            g[j] = g[p] * np.conj(K[p, j]) / abs(K[p, j])
        else:
            g[j] = 1.0
        intree[j] = True
        for a in range(n):
            m2 = K[j, a].real ** 2 + K[j, a].imag ** 2
            if not intree[a] and m2 > best[a]:
                best[a] = m2
                parent[a] = j
    worst = 0.0
    for a in range(n):
        for b in range(n):
            worst = max(worst, abs((np.conj(g[a]) * K[a, b] * g[b]).imag))
    return worst <= GAUGE_TOL * np.sqrt(big)


@njit(**_KW)
def frozen_real(K, Om, cidx, ridx, g, X, Sig):
    """The frozen pencil at lambda = 0 in the gauge ``g`` (``real_gauge``): its 2 r_C
    eigenvalues lambda (returned), the fold Sigma (into ``Sig``) and T_RR(0)^{-1} K_RC
    (into ``X``), both back in the pencil's own coordinates, as ``_cluster_solve._fold`` gives
    them. Returns (lambda, ok): ok False where T_RR(0) is singular or dgeev fails."""
    rc, nr = cidx.size, ridx.size
    # R_RR - Omega_R^2 and R_RC, real (R symmetric: R_CR = R_RC^T, gauged once)
    T = np.empty((nr, nr))
    Y = np.empty((nr, rc))
    RRC = np.empty((nr, rc))
    for a in range(nr):
        ia = ridx[a]
        ga = np.conj(g[ia])
        for b in range(nr):
            T[a, b] = (ga * K[ia, ridx[b]] * g[ridx[b]]).real
        T[a, a] -= Om[ia] * Om[ia]
        for b in range(rc):
            RRC[a, b] = (ga * K[ia, cidx[b]] * g[cidx[b]]).real
            Y[a, b] = RRC[a, b]
    lam = np.empty(2 * rc, np.complex128)
    if nr:
        piv = np.empty(nr, np.int64)
        if not _lu(T, piv):
            return lam, False
        _lu_solve(T, piv, Y)
    # L^T with L = [[Omega_C, I], [A, Omega_C]], A = R_CC - R_CR Y (same eigenvalues)
    m = 2 * rc
    L = np.zeros((m, m))
    for a in range(rc):
        ca = cidx[a]
        ga = np.conj(g[ca])
        for b in range(rc):
            s = 0.0
            for c in range(nr):
                s += RRC[c, a] * Y[c, b]
            Sig[a, b] = g[ca] * s * np.conj(g[cidx[b]])
            L[b, rc + a] = (ga * K[ca, cidx[b]] * g[cidx[b]]).real - s
        L[a, a] = Om[ca]
        L[rc + a, a] = 1.0
        L[rc + a, rc + a] = Om[ca]
    for a in range(nr):
        for b in range(rc):
            X[a, b] = g[ridx[a]] * Y[a, b] * np.conj(g[cidx[b]])
    # where the pencil splits (its nonzeros two or more separate sets of coordinates: a
    # symmetric potential's copies, the Hessian's round-off harmonics dropped), so does L
    # (T_RR's LU keeps the split: Sigma is zero across it): its eigenvalues are each
    # block's, for two halves at ~1/4 of the cost
    comp = _components(K)
    ncomp = 0
    for a in range(rc):
        ncomp = max(ncomp, comp[cidx[a]] + 1)
    got = 0
    ok = True
    idx = np.empty(m, np.int64)
    for c in range(ncomp):
        mc = 0
        for half in range(2):
            for a in range(rc):
                if comp[cidx[a]] == c:
                    idx[mc] = half * rc + a
                    mc += 1
        if mc == 0:
            continue
        Lc = np.empty((mc, mc))
        for a in range(mc):
            for b in range(mc):
                Lc[a, b] = L[idx[a], idx[b]]
        wr = np.empty(mc)
        wi = np.empty(mc)
        vl = np.empty(1)
        vr = np.empty(1)
        info = _dgeev(_DOUBLE, _NO_VECTORS, _NO_VECTORS, mc, Lc.ctypes, mc, wr.ctypes,
                      wi.ctypes, vl.ctypes, 1, vr.ctypes, 1)
        for s in range(mc):
            lam[got] = complex(-wi[s], wr[s])  # lambda = i mu
            got += 1
        # keep the arrays alive past the LAPACK call (``.ctypes`` does not)
        ok = ok and info == 0 and Lc.size + wr.size + wi.size + vl.size + vr.size > 0
    return lam, ok and got == m


@njit(**_KW)
def _components(K):
    """The connected components of K's nonzeros: a label 0, 1, ... per coordinate."""
    n = K.shape[0]
    comp = np.full(n, -1, np.int64)
    stack = np.empty(n, np.int64)
    nc = 0
    for a0 in range(n):
        if comp[a0] >= 0:
            continue
        comp[a0] = nc
        top = 1
        stack[0] = a0
        while top > 0:
            top -= 1
            a = stack[top]
            for b in range(n):
                if comp[b] < 0 and (K[a, b] != 0 or K[b, a] != 0):
                    comp[b] = nc
                    stack[top] = b
                    top += 1
        nc += 1
    return comp
