"""The frozen pencil's eigenvalues for the compiled Hill kernel (``_sidebands``): the
r_c x r_c pencil (lambda - i Omega_C)^2 + K_CC - Sigma of a cluster, its fold Sigma frozen
at a point. Up to four coordinates the roots of its determinant (a polynomial of degree
2 r_c) by Aberth's iteration, from the uncoupled roots moved off the imaginary axis; beyond,
or where Aberth does not settle, LAPACK's eigenvalues of its linearisation. Numba-compiled
(LAPACK's call costs more than the algebra at these sizes)."""

from __future__ import annotations

import numpy as np
from numba import njit

#: how far (relative to the cluster's scale) ``_frozen`` moves Aberth's starts off the
#: imaginary axis: any distinct tilt breaks the mirror symmetry; 1e-3 of the scale is
#: ~1e-3 of omega, well inside a cluster's width yet far above round-off (measured
#: iterations at 1e-6, 1e-4, 1e-2: 8-15, 5-12, 4-11)
START_TILT = 1e-3

_KW = dict(cache=True, nogil=True, error_model="numpy", boundscheck=False)


@njit(**_KW)
def _small_pencil(Kt, Om, cidx, Sig):
    """Eigenvalues of the r_c x r_c pencil (lam - i Omega_C)^2 + K_CC - Sig."""
    rc = cidx.size
    A = np.zeros((2 * rc, 2 * rc), np.complex128)
    for a in range(rc):
        A[a, rc + a] = 1.0
        oa = Om[cidx[a]]
        for b in range(rc):
            A[rc + a, b] = -(Kt[cidx[a], cidx[b]] - Sig[a, b])
        A[rc + a, a] += oa * oa
        A[rc + a, rc + a] = 2j * oa
    return np.linalg.eigvals(A)


@njit(**_KW)
def _polymul(a, b):
    """Coefficients (ascending) of the product of two polynomials."""
    out = np.zeros(a.size + b.size - 1, np.complex128)
    for i in range(a.size):
        for j in range(b.size):
            out[i + j] += a[i] * b[j]
    return out


@njit(**_KW)
def _det4(quad, A):
    """det(diag(quad_c(z)) + A - diag(A)) of four coordinates, ascending coefficients
    (degree 8): sum over the subsets S of prod_{c in S} quad_c times the principal minor of
    the couplings (zero diagonal) on the others: pairs -A_ab A_ba, triples their two
    3-cycles, all four their nine derangements (three double transpositions +, six
    4-cycles -)."""
    poly = _polymul(_polymul(quad[0], quad[1]), _polymul(quad[2], quad[3]))
    for a in range(4):
        for b in range(a + 1, 4):
            c, d = [x for x in range(4) if x != a and x != b]
            cross = A[a, b] * A[b, a]
            two = _polymul(quad[c], quad[d])
            for m in range(5):
                poly[m] -= two[m] * cross
    for d in range(4):
        a, b, c = [x for x in range(4) if x != d]
        cyc = A[a, b] * A[b, c] * A[c, a] + A[a, c] * A[c, b] * A[b, a]
        for m in range(3):
            poly[m] += quad[d, m] * cyc
    poly[0] += (A[0, 1] * A[1, 0] * A[2, 3] * A[3, 2] + A[0, 2] * A[2, 0] * A[1, 3] * A[3, 1]
                + A[0, 3] * A[3, 0] * A[1, 2] * A[2, 1])
    poly[0] -= (A[0, 1] * A[1, 2] * A[2, 3] * A[3, 0] + A[0, 1] * A[1, 3] * A[3, 2] * A[2, 0]
                + A[0, 2] * A[2, 1] * A[1, 3] * A[3, 0] + A[0, 2] * A[2, 3] * A[3, 1] * A[1, 0]
                + A[0, 3] * A[3, 1] * A[1, 2] * A[2, 0] + A[0, 3] * A[3, 2] * A[2, 1] * A[1, 0])
    return poly


@njit(**_KW)
def _frozen(Kt, Om, cidx, Sig, centre, scale):
    """The eigenvalues of the frozen pencil (``_small_pencil``). Up to three coordinates:
    the roots of its determinant, a polynomial of degree 2 r_c in z = lambda - centre
    (products of each coordinate's quadratic (z + centre - i Omega_c)^2 + A_cc and the
    couplings A = K_CC - Sigma), by Aberth's iteration from the uncoupled roots: LAPACK's
    zgeev takes 12 us on 4 x 4 and 28 us on 6 x 6, this ~1 us. Beyond four coordinates
    (four: ``_det4``, fput's clusters at ~1 offset in 10), or where Aberth does not
    settle, LAPACK."""
    rc = cidx.size
    if rc > 4:
        return _small_pencil(Kt, Om, cidx, Sig)
    A = np.empty((rc, rc), np.complex128)
    for a in range(rc):
        for b in range(rc):
            A[a, b] = Kt[cidx[a], cidx[b]] - Sig[a, b]
    quad = np.empty((rc, 3), np.complex128)
    for c in range(rc):
        bc = centre - 1j * Om[cidx[c]]
        quad[c, 0] = bc * bc + A[c, c]
        quad[c, 1] = 2 * bc
        quad[c, 2] = 1.0
    if rc == 1:
        poly = quad[0].copy()
    elif rc == 2:
        poly = _polymul(quad[0], quad[1])
        poly[0] -= A[0, 1] * A[1, 0]
    elif rc == 4:
        poly = _det4(quad, A)
    else:
        poly = _polymul(_polymul(quad[0], quad[1]), quad[2])
        for c, (a, b) in enumerate(((1, 2), (0, 2), (0, 1))):
            cross = A[a, b] * A[b, a]
            for m in range(3):
                poly[m] -= quad[c, m] * cross
        poly[0] += A[0, 1] * A[1, 2] * A[2, 0] + A[0, 2] * A[1, 0] * A[2, 1]
    D = 2 * rc
    z = np.empty(D, np.complex128)
    for c in range(rc):
        r = 1j * np.sqrt(A[c, c] + 0j)
        z[2 * c] = -(centre - 1j * Om[cidx[c]]) + r
        z[2 * c + 1] = -(centre - 1j * Om[cidx[c]]) - r
    for k in range(D):  # Aberth needs distinct starts
        for j in range(k):
            if abs(z[k] - z[j]) < 1e-9 * scale:
                z[k] += 1e-6 * scale * (k + 1) * (0.6 + 0.8j)
    for k in range(D):
        # off the axis, each its own way: the uncoupled roots lie on the imaginary axis,
        # and the polynomial is mirror symmetric (lambda -> -conj(lambda)), so starts on
        # the axis stay there until round-off breaks the symmetry, and a growing pair
        # took ~55 of the 60 iterations (measured, sine-gordon); tilted: ~5
        z[k] += START_TILT * scale * np.exp(1j * (0.3 + 0.7 * k))
    for _ in range(60):
        big = 0.0
        for k in range(D):
            pv = poly[D]
            dp = 0j
            for m in range(D - 1, -1, -1):
                dp = dp * z[k] + pv
                pv = pv * z[k] + poly[m]
            if pv == 0:
                continue
            if dp == 0:
                return _small_pencil(Kt, Om, cidx, Sig)
            w = pv / dp
            rep = 0j
            for j in range(D):
                if j != k:
                    rep += 1.0 / (z[k] - z[j])
            den = 1.0 - w * rep
            if den == 0:
                return _small_pencil(Kt, Om, cidx, Sig)
            corr = w / den
            z[k] -= corr
            big = max(big, abs(corr) / (abs(z[k]) + scale))
        if big <= 1e-15:
            return z + centre
    return _small_pencil(Kt, Om, cidx, Sig)
