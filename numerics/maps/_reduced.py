"""The reduced sideband problem of ``resonance_map``, in closed form (module docstring of
``_resonance``): the dressed frequencies omega_+- of a sideband pair k +- q, its coupling
L_+- L_-+ (the U modes folded in by a Schur complement) and the rotating-wave growth rate,
for every (cell, offset) at once, compiled.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit


def _reduced(C, k, W, q, coupled, poles=False):
    """Dressed sideband frequencies omega_+-, (B, Q), and L_+- L_-+ (U folded in); with
    ``poles``, also the U resonances' detunings omega_U(q + u k)^2 - (nu - u Omega)^2,
    u = -2, 0, 2 (zero where a U mode meets the pair: the reduction's poles), (3, B, Q).

    L[a, b] = sum_j c_{j, a - b} e^{i (q + b k) j} (j = -1, 0, 1) as in ``_hill``; the
    U modes u enter by a Schur complement, L[a, b] += L[a, u] L[u, b] / den_u. Compiled
    (``_reduced_points``): every (cell, offset) in one fused pass, no temporaries (the
    NumPy form of the same formulas is the reference in tests/test_resonance.py)."""
    q = np.asarray(q, float)
    B = k.size
    qq = np.ascontiguousarray(np.broadcast_to(q, (B, q.shape[-1])))
    wp, wm, c2 = (np.empty(qq.shape, complex) for _ in range(3))
    dens = np.zeros((3,) + qq.shape)
    _reduced_points(C["tt"], C["tU"], C["Ut"], np.asarray(k, float), np.asarray(W, float),
                    qq, bool(coupled), wp, wm, c2, dens)
    if poles:
        return wp, wm, c2, (dens if coupled else dens[:0])
    return wp, wm, c2


@njit(cache=True, nogil=True, error_model="numpy", boundscheck=False)
def _entry(c, l, e):
    """sum_j c_{j, l} e^{i j (q + p k)} for one cell: c (3, M), e = e^{i (q + p k)}."""
    M = c.shape[1]
    m = l % M
    return c[0, m] * e.conjugate() + c[1, m] + c[2, m] * e


@njit(cache=True, nogil=True, error_model="numpy", boundscheck=False)
def _reduced_points(tt, tU, Ut, k, W, q, coupled, wp, wm, c2, dens):
    B, Q = q.shape
    for b in range(B):
        ek = np.exp(1j * k[b])
        for iq in range(Q):
            eq = np.exp(1j * q[b, iq])
            # e^{i (q + p k)}, p = -2 .. 2 at index p + 2
            ekc = ek.conjugate()
            E = (eq * (ekc * ekc), eq * ekc, eq, eq * ek, eq * (ek * ek))
            L11 = _entry(tt[b], 0, E[3])
            L1m = _entry(tt[b], 2, E[1])
            Lm1 = _entry(tt[b], -2, E[3])
            Lmm = _entry(tt[b], 0, E[1])
            if coupled:
                lam0 = 0.5j * (np.sqrt(-Lmm) - np.sqrt(-L11))
                for iu in range(3):
                    u = 2 * iu - 2
                    wU = 2.0 * abs(math.sin(0.5 * (q[b, iq] + u * k[b])))  # omega_U
                    z = lam0 - 1j * u * W[b]
                    den = z * z + wU * wU
                    dens[iu, b, iq] = den.real
                    to_1 = _entry(Ut[b], u - 1, E[3])
                    to_m = _entry(Ut[b], u + 1, E[1])
                    from_1 = _entry(tU[b], 1 - u, E[u + 2]) / den
                    from_m = _entry(tU[b], -1 - u, E[u + 2]) / den
                    L11 += from_1 * to_1
                    L1m += from_1 * to_m
                    Lm1 += from_m * to_1
                    Lmm += from_m * to_m
            wp[b, iq] = np.sqrt(-L11)
            wm[b, iq] = np.sqrt(-Lmm)
            c2[b, iq] = L1m * Lm1


def _growth(coupling2, wp, wm, pump):
    """Rotating-wave growth rate of a pair pumped at frequency ``pump`` (B, Q)."""
    s2 = coupling2 / (4 * wp * wm) - (wp + wm - pump) ** 2 / 4
    return np.maximum(np.sqrt(s2 + 0j).real, 0.0)
