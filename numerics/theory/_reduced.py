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
def _point(tt, tU, Ut, k, W, q, coupled, dens, ek, eq):
    """omega_+, omega_-, L_+- L_-+ of one (cell, offset); the U detunings into dens (3,).
    ek, eq: e^{i k}, e^{i q} (computed once per cell and per grid offset by the callers)."""
    # e^{i (q + p k)}, p = -2 .. 2 at index p + 2
    ekc = ek.conjugate()
    E = (eq * (ekc * ekc), eq * ekc, eq, eq * ek, eq * (ek * ek))
    L11 = _entry(tt, 0, E[3])
    L1m = _entry(tt, 2, E[1])
    Lm1 = _entry(tt, -2, E[3])
    Lmm = _entry(tt, 0, E[1])
    if coupled:
        lam0 = 0.5j * (np.sqrt(-Lmm) - np.sqrt(-L11))
        for iu in range(3):
            u = 2 * iu - 2
            wU = 2.0 * abs(math.sin(0.5 * (q + u * k)))  # omega_U
            z = lam0 - 1j * u * W
            den = z * z + wU * wU
            dens[iu] = den.real
            to_1 = _entry(Ut, u - 1, E[3])
            to_m = _entry(Ut, u + 1, E[1])
            from_1 = _entry(tU, 1 - u, E[u + 2]) / den
            from_m = _entry(tU, -1 - u, E[u + 2]) / den
            L11 += from_1 * to_1
            L1m += from_1 * to_m
            Lm1 += from_m * to_1
            Lmm += from_m * to_m
    return np.sqrt(-L11), np.sqrt(-Lmm), L1m * Lm1


@njit(cache=True, nogil=True, error_model="numpy", boundscheck=False)
def _reduced_points(tt, tU, Ut, k, W, q, coupled, wp, wm, c2, dens):
    B, Q = q.shape
    d = np.zeros(3)
    eq = np.empty(Q, np.complex128)
    for b in range(B):
        # a row equal to the previous one (a common grid) reuses its phases
        same = b > 0
        if same:
            for iq in range(Q):
                if q[b, iq] != q[b - 1, iq]:
                    same = False
                    break
        if not same:
            for iq in range(Q):
                eq[iq] = np.exp(1j * q[b, iq])
        ek = np.exp(1j * k[b])
        for iq in range(Q):
            wp[b, iq], wm[b, iq], c2[b, iq] = _point(tt[b], tU[b], Ut[b], k[b], W[b],
                                                     q[b, iq], coupled, d, ek, eq[iq])
            for iu in range(3):
                dens[iu, b, iq] = d[iu]


def _refine_roots(C, k, W, x, coupled, pump, steps, h, move, floor):
    """Finite-difference Newton steps on the detuning omega_+ + omega_- - pump from x
    (B, n), each root until its step is below round-off of x (further steps would move
    it by an ulp or so) or ``steps`` are done; steps clipped to ``move``, x to [floor, pi]."""
    x = np.array(x, float)
    _refine_points(C["tt"], C["tU"], C["Ut"], np.asarray(k, float), np.asarray(W, float),
                   np.asarray(pump, float), bool(coupled), int(steps), float(h), float(move),
                   float(floor), x)
    return x


@njit(cache=True, nogil=True, error_model="numpy", boundscheck=False)
def _refine_points(tt, tU, Ut, k, W, pump, coupled, steps, h, move, floor, x):
    B, n = x.shape
    d = np.zeros(3)
    eps = np.finfo(np.float64).eps
    for b in range(B):
        start = x[b].copy()
        ek = np.exp(1j * k[b])
        for j in range(n):
            xx = x[b, j]
            seen = -1  # the same start in this row (missing roots' placeholders): same root
            for jj in range(j):
                if start[jj] == xx:
                    seen = jj
                    break
            if seen >= 0:
                x[b, j] = x[b, seen]
                continue
            for _ in range(steps):
                wp, wm, _c = _point(tt[b], tU[b], Ut[b], k[b], W[b], xx, coupled, d, ek,
                                    np.exp(1j * xx))
                f0 = (wp + wm).real - pump[b]
                wp, wm, _c = _point(tt[b], tU[b], Ut[b], k[b], W[b], xx + h, coupled, d, ek,
                                    np.exp(1j * (xx + h)))
                f1 = (wp + wm).real - pump[b]
                step = f0 * h / (f1 - f0) if f1 != f0 else 0.0
                if step != step:  # no reduced problem here (NaN): no root
                    xx = np.nan
                    break
                step = min(max(step, -move), move)
                xn = min(max(xx - step, floor), np.pi)
                done = abs(xn - xx) <= 2 * eps * abs(xx)
                xx = xn
                if done:
                    break
            x[b, j] = xx


def _growth(coupling2, wp, wm, pump):
    """Rotating-wave growth rate of a pair pumped at frequency ``pump`` (B, Q)."""
    s2 = coupling2 / (4 * wp * wm) - (wp + wm - pump) ** 2 / 4
    return np.maximum(np.sqrt(s2 + 0j).real, 0.0)
