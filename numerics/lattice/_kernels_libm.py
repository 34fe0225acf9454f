"""The libm reference kernels: sin/cos from libm, 1 - cos = sin^2 / (1 + cos).

Used beyond ``_kernels.TRIG_LIMIT`` (where the polynomial's accuracy is not tested) and as
the reference the vectorised kernels are tested against (tests/test_kernels.py).
"""

from __future__ import annotations

import math

from numba import njit


@njit(cache=True, nogil=True, fastmath=False, boundscheck=False)
def accel_libm(th, U, coupled, a2, Ks, Kt, s, c, v, ath, aU):
    """Accelerations with libm sin/cos and 1 - cos = sin^2/(1 + cos) (the reference)."""
    n = th.size
    for i in range(n):
        si = math.sin(th[i])
        ci = math.cos(th[i])
        s[i] = si
        c[i] = ci
        v[i] = si * si / (1.0 + ci) if ci > 0.0 else 1.0 - ci
    for i in range(n):
        ip = i + 1 if i + 1 < n else 0
        im = i - 1 if i > 0 else n - 1
        bracket = 2.0 * v[i] + v[ip] + v[im]
        if coupled:
            bracket += 2.0 * (U[ip] - U[im])
            aU[i] = U[ip] - 2.0 * U[i] + U[im] + 0.5 * (v[ip] - v[im])
        ath[i] = a2 * (-Kt * (th[ip] + 4.0 * th[i] + th[im])
                       + Ks * c[i] * (s[ip] + s[im] - 2.0 * s[i])
                       - s[i] * bracket)


@njit(cache=True)
def _finite(x):
    acc = 0.0
    for i in range(x.size):
        acc += x[i]
    return math.isfinite(acc)


@njit(cache=True, nogil=True, fastmath=False, boundscheck=False)
def srkn_steps_libm(th, w, U, V, ath, aU, coupled, a2, Ks, Kt, acoef, bcoef, dt, nsteps,
                    s, c, v):
    """Symplectic RKN steps with the libm force (same contract as ``srkn_steps``)."""
    n = th.size
    nst = acoef.size
    for step in range(nsteps):
        for j in range(nst):
            hb = bcoef[j] * dt
            for i in range(n):
                w[i] += hb * ath[i]
            if coupled:
                for i in range(n):
                    V[i] += hb * aU[i]
            if j == nst - 1:
                break
            ha = acoef[j] * dt
            for i in range(n):
                th[i] += ha * w[i]
            if coupled:
                for i in range(n):
                    U[i] += ha * V[i]
            accel_libm(th, U, coupled, a2, Ks, Kt, s, c, v, ath, aU)
        if not _finite(th):
            return step
    return nsteps


@njit(cache=True, nogil=True, fastmath=False, boundscheck=False)
def rk4_steps_libm(th, w, U, V, coupled, a2, Ks, Kt, dt, nsteps, s, c, v, work):
    """Classical RK4 with the libm force; ``work`` has shape (10, N)."""
    n = th.size
    h2 = 0.5 * dt
    h6 = dt / 6.0
    qt, qw, kt_, sq, sw = work[0], work[1], work[2], work[3], work[4]
    qU, qV, kU, sU, sV = work[5], work[6], work[7], work[8], work[9]
    for step in range(nsteps):
        accel_libm(th, U, coupled, a2, Ks, Kt, s, c, v, kt_, kU)
        for i in range(n):
            sq[i] = w[i]
            sw[i] = kt_[i]
            qt[i] = th[i] + h2 * w[i]
            qw[i] = w[i] + h2 * kt_[i]
        if coupled:
            for i in range(n):
                sU[i] = V[i]
                sV[i] = kU[i]
                qU[i] = U[i] + h2 * V[i]
                qV[i] = V[i] + h2 * kU[i]
        for stage in range(2):
            h = h2 if stage == 0 else dt
            accel_libm(qt, qU, coupled, a2, Ks, Kt, s, c, v, kt_, kU)
            for i in range(n):
                sq[i] += 2.0 * qw[i]
                sw[i] += 2.0 * kt_[i]
                vel = qw[i]
                qt[i] = th[i] + h * vel
                qw[i] = w[i] + h * kt_[i]
            if coupled:
                for i in range(n):
                    sU[i] += 2.0 * qV[i]
                    sV[i] += 2.0 * kU[i]
                    vel = qV[i]
                    qU[i] = U[i] + h * vel
                    qV[i] = V[i] + h * kU[i]
        accel_libm(qt, qU, coupled, a2, Ks, Kt, s, c, v, kt_, kU)
        for i in range(n):
            th[i] += h6 * (sq[i] + qw[i])
            w[i] += h6 * (sw[i] + kt_[i])
        if coupled:
            for i in range(n):
                U[i] += h6 * (sU[i] + qV[i])
                V[i] += h6 * (sV[i] + kU[i])
        if not _finite(th):
            return step
    return nsteps
