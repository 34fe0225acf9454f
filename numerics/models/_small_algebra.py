"""Small dense complex algebra for the compiled Hill kernel (``_sidebands``, ``_strong``):
a 2 x 2 Hermitian eigensolver in closed form, an LU that skips exact zeros, its solves,
and the round-off threshold on the Hessian's harmonics that makes those zeros exact.
Numba-compiled: LAPACK's call costs more than the algebra at these sizes (n <= ~60)."""

from __future__ import annotations

import math

import numpy as np
from numba import njit

_KW = dict(cache=True, nogil=True, error_model="numpy", boundscheck=False)

#: power-iteration sweeps at most for a converged mode's eigenvector (``_null_vector``):
#: each leaves the ratio step / distance of the other roots' part, <= 1e-3 even at the
#: rate floor (step <= 1e-9 scale, the mirror 2 x 3e-7 omega away): 5 sweeps reach 1e-15
ITERATIONS = 8


@njit(**_KW)
def _eigh2(A, ev, vec):
    """Eigenvalues (ascending) and orthonormal eigenvectors (columns) of a 2 x 2
    Hermitian matrix, in closed form (LAPACK's call costs more than the algebra)."""
    a, c, b = A[0, 0].real, A[1, 1].real, A[0, 1]
    mid, half = 0.5 * (a + c), 0.5 * (a - c)
    r = math.sqrt(half * half + abs(b) ** 2)
    ev[0], ev[1] = mid - r, mid + r
    if abs(b) == 0.0:
        lo_first = a <= c
        vec[0, 0], vec[1, 0] = (1.0, 0.0) if lo_first else (0.0, 1.0)
        vec[0, 1], vec[1, 1] = (0.0, 1.0) if lo_first else (1.0, 0.0)
        return
    for j in range(2):
        lam = ev[j]
        x0, x1 = b, lam - a + 0j             # from the first row
        y0, y1 = lam - c + 0j, np.conj(b)    # from the second
        if abs(x0) ** 2 + abs(x1) ** 2 < abs(y0) ** 2 + abs(y1) ** 2:
            x0, x1 = y0, y1
        nrm = math.sqrt(abs(x0) ** 2 + abs(x1) ** 2)
        vec[0, j], vec[1, j] = x0 / nrm, x1 / nrm


@njit(**_KW)
def _lu(A, piv):
    """In-place LU with partial pivoting of a square complex matrix; False if singular.
    The pivot by |Re| + |Im| (LAPACK's izamax: no square root per entry); the update
    runs over the pivot row's nonzero columns only and skips zero multipliers, so a rest
    that splits (a symmetric potential's odd and even harmonics) or is banded (the
    Hessian's harmonics below round-off, ``_drop_roundoff``) costs what its blocks do,
    with the same arithmetic on every nonzero."""
    n = A.shape[0]
    cols = np.empty(n, np.int64)
    for j in range(n):
        p = j
        big = abs(A[j, j].real) + abs(A[j, j].imag)
        for i in range(j + 1, n):
            v = abs(A[i, j].real) + abs(A[i, j].imag)
            if v > big:
                big = v
                p = i
        piv[j] = p
        if big == 0.0:
            return False
        if p != j:
            for c in range(n):
                t = A[j, c]
                A[j, c] = A[p, c]
                A[p, c] = t
        nc = 0
        for c in range(j + 1, n):
            if A[j, c] != 0:
                cols[nc] = c
                nc += 1
        inv = 1.0 / A[j, j]
        for i in range(j + 1, n):
            if A[i, j] == 0:
                continue
            f = A[i, j] * inv
            A[i, j] = f
            for t in range(nc):
                c = cols[t]
                A[i, c] -= f * A[j, c]
    return True


@njit(**_KW)
def _ldlh(A):
    """In-place A = L D L^* of a Hermitian matrix, its lower triangle read (L unit lower
    below the diagonal, D real on it), without pivoting: for a strictly diagonally
    dominant one (the Hill kernel's rest at a point of the imaginary axis outside every
    disc of its own: ``_cluster_solve._fold``) elimination keeps the dominance and every
    pivot is nonzero, at half an LU's products. False where a pivot is not positive in
    modulus. Zeros skipped as ``_lu`` does."""
    n = A.shape[0]
    cols = np.empty(n, np.int64)
    for j in range(n):
        dj = A[j, j].real
        if dj == 0.0:
            return False
        nc = 0
        for i in range(j + 1, n):
            if A[i, j] != 0:
                cols[nc] = i
                nc += 1
        inv = 1.0 / dj
        # the trailing lower triangle: A_ic -= A_ij conj(A_cj) / d_j, c <= i
        for t in range(nc):
            i = cols[t]
            f = A[i, j] * inv
            for u in range(t + 1):
                c = cols[u]
                A[i, c] -= f * np.conj(A[c, j])
        for t in range(nc):
            A[cols[t], j] *= inv
        A[j, j] = dj
    return True


@njit(**_KW)
def _ldlh_half(A, B):
    """Z = L^{-1} B in place (B, shape (n, m)), L the unit lower triangle stored below
    A's diagonal: with ``_ldlh``'s factors B^* A^{-1} B = Z^* D^{-1} Z, Hermitian by
    construction; with ``_lu``'s, after the row swaps, ``_lu_solve``'s forward sweep.
    By columns of L, skipping the solution's zeros."""
    n, m = B.shape
    for c in range(m):
        for k in range(n):
            x = B[k, c]
            if x != 0:
                for i in range(k + 1, n):
                    B[i, c] -= A[i, k] * x


@njit(**_KW)
def _lu_solve(A, piv, B):
    """Solves A X = B in place (B, shape (n, m)) with ``_lu``'s factors; by columns of
    the factors, skipping the solution's zeros (a block the right side does not reach)."""
    n, m = B.shape
    for j in range(n):
        p = piv[j]
        if p != j:
            for c in range(m):
                t = B[j, c]
                B[j, c] = B[p, c]
                B[p, c] = t
    _ldlh_half(A, B)
    for c in range(m):
        for k in range(n - 1, -1, -1):
            x = B[k, c] / A[k, k]
            B[k, c] = x
            if x != 0:
                for i in range(k):
                    B[i, c] -= A[i, k] * x


@njit(**_KW)
def _lu_solve_t(A, piv, B):
    """Solves A^T X = B in place with ``_lu``'s factors (P A = L U: A^T = U^T L^T P), by
    rows of the factors, skipping the solution's zeros."""
    n, m = B.shape
    for c in range(m):
        for k in range(n):
            x = B[k, c] / A[k, k]
            B[k, c] = x
            if x != 0:
                for i in range(k + 1, n):
                    B[i, c] -= A[k, i] * x
        for k in range(n - 1, -1, -1):
            x = B[k, c]
            if x != 0:
                for i in range(k):
                    B[i, c] -= A[k, i] * x
    for j in range(n - 1, -1, -1):
        p = piv[j]
        if p != j:
            for c in range(m):
                t = B[j, c]
                B[j, c] = B[p, c]
                B[p, c] = t


#: a Hessian harmonic below ROUNDOFF times its field pair's largest is the DFT's
#: round-off (``_exact._hessian_harmonics`` sums M >= 128 samples: the error of each
#: coefficient is ~ sqrt(M) eps of the largest sample, 11 eps at M = 128, and no
#: coefficient's magnitude is known better than that; 16 eps = 3.6e-15 stays above the
#: odd harmonics of a symmetric potential, measured 1e-16 to 7e-16 of the largest)
ROUNDOFF = 16 * 2.220446049250313e-16


@njit(**_KW)
def _drop_roundoff(Hh):
    """A copy of the Hessian's harmonics (shape (4P + 1, 2d, 2d)) with those below the
    DFT's round-off (``ROUNDOFF``) set to zero: the pencil's couplings they carry are
    noise, and exact zeros let ``_lu`` skip them (a symmetric potential's odd harmonics
    decouple the odd and even copies; a weak wave's far harmonics band the pencil).
    Moving an entry by its own round-off moves the eigenvalues by round-off."""
    out = Hh.copy()
    ns, da, db = Hh.shape
    for a in range(da):
        for b in range(db):
            big = 0.0
            for s in range(ns):
                big = max(big, abs(Hh[s, a, b]))
            for s in range(ns):
                if abs(Hh[s, a, b]) <= ROUNDOFF * big:
                    out[s, a, b] = 0.0
    return out


@njit(**_KW)
def _null_vector(M, y):
    """The dominant eigenvector of the small matrix ``M`` into ``y`` (largest entry 1), by
    power iteration from ones until the vector moves by < 1e-14 (ITERATIONS at most)."""
    rc = y.size
    for a in range(rc):
        y[a] = 1.0
    z = np.empty(rc, np.complex128)
    for _ in range(ITERATIONS):
        nrm = 0.0
        for a in range(rc):
            acc = 0j
            for b in range(rc):
                acc += M[a, b] * y[b]
            z[a] = acc
            nrm = max(nrm, abs(acc))
        if nrm == 0:
            return
        # normalised by the largest entry's phase too, so that a converged vector repeats
        big = 0
        for a in range(rc):
            if abs(z[a]) > abs(z[big]):
                big = a
        ph = z[big]
        moved = 0.0
        for a in range(rc):
            v = z[a] / ph
            moved = max(moved, abs(v - y[a]))
            y[a] = v
        if moved <= 1e-14:
            return
