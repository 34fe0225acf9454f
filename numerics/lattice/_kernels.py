"""Compiled force evaluation and time loops (Numba), vectorised; fast for two reasons.

1. **Branch-free sin, cos and 1 - cos** (``_sincosvers``): Cody-Waite reduction by pi/2
   (four-part split of pi/2, exact products for |n| < 2^20) and fdlibm's minimax
   polynomials on |r| <= pi/4, the quadrant chosen by arithmetic, not branches. The
   versine 1 - cos comes from its own polynomial (no cancellation, no division), so the
   cubic nonlinearity 4 - 2 cos th_n - cos th_{n+1} - cos th_{n-1} = O(theta^2) is exact to
   round-off. Measured: sin and cos within 1 ulp of libm for |theta| <= TRIG_LIMIT, the
   versine within 4 ulp of 2 sin^2(theta/2) (tests/test_kernels.py). Unlike libm calls,
   this inlines into the site loops, which LLVM then vectorises (checked on this machine:
   ``<8 x double>`` operations in the loops' LLVM IR, see ``vectorised()``).
2. **Fused sweeps**: each force evaluation is one pass over the sites that computes the
   stencil from the current stage's positions and trig values, updates the velocities,
   and writes the next stage's positions *and their trig values* into the other half of a
   double buffer. Boundary sites are done outside the main loop, so it has no index
   wrapping. RK4 does 4 passes per step, an SRKN method with s kicks s - 1 passes.

The entry points (``accel``, ``rk4_steps``, ``srkn_steps``, their libm references) release
the GIL (``nogil``).

Only the ``contract`` fast-math flag is used (fused multiply-add): never ``nnan``/``ninf``,
so NaN and inf propagate and the blow-up check sees them. Case "rotation" runs no U work.

Every loop returns the steps it completed; it stops after the first step whose state is not
finite or leaves |theta| <= TRIG_LIMIT (the caller then continues, or reports the blow-up,
with the libm reference loops of ``_kernels_libm``).
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

from ._kernels_libm import _finite, accel_libm, rk4_steps_libm, srkn_steps_libm

#: |theta| up to which the polynomial sin/cos is used (accuracy tested up to here); beyond
#: it the loops hand over to the libm reference loops.
TRIG_LIMIT = 1.0e4
_FAST = {"contract"}

# Cody-Waite split of pi/2 (fdlibm e_rem_pio2.c): three 33-bit parts (n * part exact for
# |n| < 2^20) and the rest, so that r keeps full relative accuracy next to multiples of pi/2
_PIO2_1 = 1.57079632673412561417e+00
_PIO2_2 = 6.07710050630396597660e-11
_PIO2_3 = 2.02226624871116645580e-21
_PIO2_3T = 8.47842766036889956997e-32
_TWO_OVER_PI = 6.36619772367581382433e-01
# fdlibm k_sin.c / k_cos.c minimax coefficients on |r| <= pi/4
_S1, _S2, _S3 = -1.66666666666666324348e-01, 8.33333333332248946124e-03, \
    -1.98412698298579493134e-04
_S4, _S5, _S6 = 2.75573137070700676789e-06, -2.50507602534068634195e-08, \
    1.58969099521155010221e-10
_C1, _C2, _C3 = 4.16666666666666019037e-02, -1.38888888888741095749e-03, \
    2.48015872894767294178e-05
_C4, _C5, _C6 = -2.75573143513906633035e-07, 2.08757232129817482790e-09, \
    -1.13596475577881948265e-11


@njit(inline="always", fastmath=_FAST)
def _sincosvers(x):
    """(sin x, cos x, 1 - cos x) without branches (see the module docstring)."""
    n = math.floor(x * _TWO_OVER_PI + 0.5)
    r = (((x - n * _PIO2_1) - n * _PIO2_2) - n * _PIO2_3) - n * _PIO2_3T
    z = r * r
    sr = r + r * z * (_S1 + z * (_S2 + z * (_S3 + z * (_S4 + z * (_S5 + z * _S6)))))
    vr = 0.5 * z - z * z * (_C1 + z * (_C2 + z * (_C3 + z * (_C4 + z * (_C5 + z * _C6)))))
    cr = 1.0 - vr
    q = np.int64(n) & 3
    odd = q & 1
    sign_s = 1.0 - 2.0 * ((q >> 1) & 1)  # + in quadrants 0, 1
    sign_c = 1.0 - 2.0 * (((q + 1) >> 1) & 1)  # + in quadrants 0, 3
    s = sign_s * (sr if odd == 0 else cr)
    c = sign_c * (cr if odd == 0 else sr)
    # 1 - cos: vr, 1 + sr, 2 - vr, 1 - sr in quadrants 0..3: never a difference of
    # nearly equal numbers (|sr| <= sin(pi/4))
    v = (2.0 * ((q >> 1) & 1) + sign_s * vr) if odd == 0 else (1.0 + sign_s * sr)
    return s, c, v


@njit(cache=True, fastmath=_FAST, boundscheck=False)
def sincosvers(x, s, c, v):
    """sin, cos and 1 - cos of every x into s, c, v (the polynomial; for tests/benches)."""
    for i in range(x.size):
        a, b, d = _sincosvers(x[i])
        s[i] = a
        c[i] = b
        v[i] = d


@njit(inline="always", fastmath=_FAST)
def _bad(x):
    """1 if x is not finite or beyond TRIG_LIMIT (NaN compares false), else 0."""
    return 0 if abs(x) <= TRIG_LIMIT else 1


@njit(inline="always", fastmath=_FAST)
def _acc(i, im, ip, th, U, s, c, v, coupled, a2, Ks, Kt):
    """Accelerations (theta with alpha^2, U) of site i with neighbours im, ip."""
    bracket = 2.0 * v[i] + v[ip] + v[im]
    aU = 0.0
    if coupled:
        bracket += 2.0 * (U[ip] - U[im])
        aU = U[ip] - 2.0 * U[i] + U[im] + 0.5 * (v[ip] - v[im])
    at = a2 * (-Kt * (th[ip] + 4.0 * th[i] + th[im]) + Ks * c[i] * (s[ip] + s[im] - 2.0 * s[i])
               - s[i] * bracket)
    return at, aU


#: the public names of the site formula, for the torus (numerics.theory) that evaluates
#: the same force on a quasi-periodic state: the fastmath flags, sin/cos/versine of a
#: rotation, and the acceleration of site i (``_acc``)
FASTMATH = _FAST
sincos_vers = _sincosvers
site_acceleration = _acc


@njit(inline="always", fastmath=_FAST)
def _accel_passes(th, U, coupled, a2, Ks, Kt, s, c, v, ath, aU):
    """A whole chain's force in two passes: sin, cos and 1 - cos of every theta into
    ``s, c, v``, then the stencil (``_acc``) into ``ath`` and ``aU``; the libm reference
    where some |theta| is beyond TRIG_LIMIT or not finite. Inlined into ``accel`` and into
    the fused force of ``_fast_forces`` (a call into a compiled stencil costs 0.5 ns a site
    of 2.7, measured at N = 128). In case "rotation" ``U`` and ``aU`` are never touched."""
    n = th.size
    near = True
    for i in range(n):
        x = th[i]
        near &= abs(x) <= TRIG_LIMIT  # NaN compares false
        s[i], c[i], v[i] = _sincosvers(x)
    if not near:
        accel_libm(th, U, coupled, a2, Ks, Kt, s, c, v, ath, aU)
    elif coupled:
        for i in range(1, n - 1):
            ath[i], aU[i] = _acc(i, i - 1, i + 1, th, U, s, c, v, True, a2, Ks, Kt)
        ath[0], aU[0] = _acc(0, n - 1, 1, th, U, s, c, v, True, a2, Ks, Kt)
        ath[n - 1], aU[n - 1] = _acc(n - 1, n - 2, 0, th, U, s, c, v, True, a2, Ks, Kt)
    else:
        for i in range(1, n - 1):
            ath[i] = _acc(i, i - 1, i + 1, th, U, s, c, v, False, a2, Ks, Kt)[0]
        ath[0] = _acc(0, n - 1, 1, th, U, s, c, v, False, a2, Ks, Kt)[0]
        ath[n - 1] = _acc(n - 1, n - 2, 0, th, U, s, c, v, False, a2, Ks, Kt)[0]


@njit(cache=True, nogil=True, fastmath=_FAST, boundscheck=False)
def accel(th, U, coupled, a2, Ks, Kt, s, c, v, ath, aU):
    """Accelerations of eq. `norm` into ``ath`` (includes alpha^2) and ``aU``.

    ``s, c, v`` receive sin, cos, 1 - cos of theta. Uses the libm reference when some
    |theta| exceeds TRIG_LIMIT (or is not finite).
    """
    _accel_passes(th, U, coupled, a2, Ks, Kt, s, c, v, ath, aU)


# --- RK4: four fused passes per step -------------------------------------------------------

@njit(inline="always", fastmath=_FAST)
def _rk4_site(i, im, ip, Pc, Sc, Cc, Vc, PUc, Pn, Sn, Cn, Vn, th, w, vs, sx, sw, coupled, a2,
              Ks, Kt, keep, weight, cn):
    """theta at one site of an inner RK4 stage: the stencil on the current buffers (c), the
    sums (times ``keep``, plus ``weight`` times this stage), the next stage's position
    th + cn * v_stage and its trig into the next buffers (n); 1 if that position is bad.
    No branches on the stage: the refcount pruning and the vectoriser need straight code."""
    at = _acc(i, im, ip, Pc, PUc, Sc, Cc, Vc, coupled, a2, Ks, Kt)[0]
    sx[i] = keep * sx[i] + weight * vs[i]
    sw[i] = keep * sw[i] + weight * at
    x = th[i] + cn * vs[i]
    vs[i] = w[i] + cn * at
    Pn[i] = x
    Sn[i], Cn[i], Vn[i] = _sincosvers(x)
    return _bad(x)


@njit(inline="always", fastmath=_FAST)
def _rk4_site_U(i, im, ip, Vc, PUc, PUn, U, Vu, Vs, sU, sV, keep, weight, cn):
    """U at one site of an inner RK4 stage (a loop of its own: fewer arrays per loop keep
    LLVM's runtime alias checks within its limits, so both loops vectorise)."""
    aU = PUc[ip] - 2.0 * PUc[i] + PUc[im] + 0.5 * (Vc[ip] - Vc[im])
    sU[i] = keep * sU[i] + weight * Vs[i]
    sV[i] = keep * sV[i] + weight * aU
    PUn[i] = U[i] + cn * Vs[i]
    Vs[i] = Vu[i] + cn * aU


@njit(inline="always", fastmath=_FAST)
def _rk4_last_site(i, im, ip, Pc, Sc, Cc, Vc, PUc, Pn, Sn, Cn, Vn, th, w, vs, sx, sw, coupled,
                   a2, Ks, Kt, h6):
    """theta at one site of the last RK4 stage: the step's result, which is also the next
    step's first stage position (with its trig, into the next buffers)."""
    at = _acc(i, im, ip, Pc, PUc, Sc, Cc, Vc, coupled, a2, Ks, Kt)[0]
    x = th[i] + h6 * (sx[i] + vs[i])
    w[i] += h6 * (sw[i] + at)
    th[i] = x
    vs[i] = w[i]
    Pn[i] = x
    Sn[i], Cn[i], Vn[i] = _sincosvers(x)
    return _bad(x)


@njit(inline="always", fastmath=_FAST)
def _rk4_last_site_U(i, im, ip, Vc, PUc, PUn, U, Vu, Vs, sU, sV, h6):
    aU = PUc[ip] - 2.0 * PUc[i] + PUc[im] + 0.5 * (Vc[ip] - Vc[im])
    U[i] += h6 * (sU[i] + Vs[i])
    Vu[i] += h6 * (sV[i] + aU)
    PUn[i] = U[i]
    Vs[i] = Vu[i]


@njit(cache=True, fastmath=_FAST, boundscheck=False)
def _rk4_pass(Pc, Sc, Cc, Vc, PUc, Pn, Sn, Cn, Vn, PUn, th, w, U, Vu, vs, Vs, sx, sw, sU, sV,
              coupled, a2, Ks, Kt, keep, weight, cn):
    n = th.size
    bad = 0
    if coupled:
        for i in range(1, n - 1):
            bad += _rk4_site(i, i - 1, i + 1, Pc, Sc, Cc, Vc, PUc, Pn, Sn, Cn, Vn, th, w, vs,
                             sx, sw, True, a2, Ks, Kt, keep, weight, cn)
        for i in range(1, n - 1):
            _rk4_site_U(i, i - 1, i + 1, Vc, PUc, PUn, U, Vu, Vs, sU, sV, keep, weight, cn)
    else:
        for i in range(1, n - 1):
            bad += _rk4_site(i, i - 1, i + 1, Pc, Sc, Cc, Vc, PUc, Pn, Sn, Cn, Vn, th, w, vs,
                             sx, sw, False, a2, Ks, Kt, keep, weight, cn)
    for i, im, ip in ((0, n - 1, 1), (n - 1, n - 2, 0)):
        bad += _rk4_site(i, im, ip, Pc, Sc, Cc, Vc, PUc, Pn, Sn, Cn, Vn, th, w, vs, sx, sw,
                         coupled, a2, Ks, Kt, keep, weight, cn)
        if coupled:
            _rk4_site_U(i, im, ip, Vc, PUc, PUn, U, Vu, Vs, sU, sV, keep, weight, cn)
    return bad


@njit(cache=True, fastmath=_FAST, boundscheck=False)
def _rk4_last_pass(Pc, Sc, Cc, Vc, PUc, Pn, Sn, Cn, Vn, PUn, th, w, U, Vu, vs, Vs, sx, sw, sU,
                   sV, coupled, a2, Ks, Kt, h6):
    n = th.size
    bad = 0
    if coupled:
        for i in range(1, n - 1):
            bad += _rk4_last_site(i, i - 1, i + 1, Pc, Sc, Cc, Vc, PUc, Pn, Sn, Cn, Vn, th, w,
                                  vs, sx, sw, True, a2, Ks, Kt, h6)
        for i in range(1, n - 1):
            _rk4_last_site_U(i, i - 1, i + 1, Vc, PUc, PUn, U, Vu, Vs, sU, sV, h6)
    else:
        for i in range(1, n - 1):
            bad += _rk4_last_site(i, i - 1, i + 1, Pc, Sc, Cc, Vc, PUc, Pn, Sn, Cn, Vn, th, w,
                                  vs, sx, sw, False, a2, Ks, Kt, h6)
    for i, im, ip in ((0, n - 1, 1), (n - 1, n - 2, 0)):
        bad += _rk4_last_site(i, im, ip, Pc, Sc, Cc, Vc, PUc, Pn, Sn, Cn, Vn, th, w, vs, sx,
                              sw, coupled, a2, Ks, Kt, h6)
        if coupled:
            _rk4_last_site_U(i, im, ip, Vc, PUc, PUn, U, Vu, Vs, sU, sV, h6)
    return bad


@njit(cache=True, nogil=True, fastmath=_FAST, boundscheck=False)
def rk4_steps(th, w, U, V, coupled, a2, Ks, Kt, dt, nsteps, work, work_U):
    """Classical RK4 on the first-order system (q, q') of eq. `norm`, fused.

    ``work`` has shape (11, N): double-buffered stage positions and trig values, stage
    velocities and the RK sums; ``work_U`` (5, N) the same for U, (5, 0) in case
    "rotation". Returns the number of steps completed in range.
    """
    n = th.size
    Pc, Pn, Sc, Sn, Cc, Cn, Vc, Vn = (work[0], work[1], work[2], work[3], work[4], work[5],
                                      work[6], work[7])
    vs, sx, sw = work[8], work[9], work[10]
    PUc, PUn, Vs, sU, sV = work_U[0], work_U[1], work_U[2], work_U[3], work_U[4]
    bad = 0
    for i in range(n):
        Pc[i] = th[i]
        vs[i] = w[i]
        sx[i] = sw[i] = 0.0  # finite start for the sums (stage 1 multiplies them by 0)
        bad += _bad(th[i])
        Sc[i], Cc[i], Vc[i] = _sincosvers(th[i])
    if coupled:
        for i in range(n):
            PUc[i] = U[i]
            Vs[i] = V[i]
            sU[i] = sV[i] = 0.0
    if bad:
        return 0
    # stage k: sums = keep * sums + weight * k_k, next position th + c_{k+1} dt v_k
    keep, weight, cnext = (0.0, 1.0, 1.0), (1.0, 2.0, 2.0), (0.5 * dt, 0.5 * dt, dt)
    for step in range(nsteps):
        bad = 0
        for stage in range(3):
            bad += _rk4_pass(Pc, Sc, Cc, Vc, PUc, Pn, Sn, Cn, Vn, PUn, th, w, U, V, vs, Vs,
                             sx, sw, sU, sV, coupled, a2, Ks, Kt, keep[stage], weight[stage],
                             cnext[stage])
            Pc, Pn, Sc, Sn, Cc, Cn, Vc, Vn, PUc, PUn = Pn, Pc, Sn, Sc, Cn, Cc, Vn, Vc, PUn, PUc
        bad += _rk4_last_pass(Pc, Sc, Cc, Vc, PUc, Pn, Sn, Cn, Vn, PUn, th, w, U, V, vs, Vs,
                              sx, sw, sU, sV, coupled, a2, Ks, Kt, dt / 6.0)
        Pc, Pn, Sc, Sn, Cc, Cn, Vc, Vn, PUc, PUn = Pn, Pc, Sn, Sc, Cn, Cc, Vn, Vc, PUn, PUc
        if bad:
            return step + 1 if _finite(th) and _finite(w) else step
    return nsteps


# --- symplectic RKN: one fused pass per force evaluation ---------------------------------

@njit(inline="always", fastmath=_FAST)
def _srkn_site(i, im, ip, Pc, Sc, Cc, Vc, PUc, Pn, Sn, Cn, Vn, PUn, w, Vu, ath, aU, coupled,
               a2, Ks, Kt, hb, ha):
    """Stencil on the current buffers, kick by hb, drift by ha into the next buffers."""
    at, au = _acc(i, im, ip, Pc, PUc, Sc, Cc, Vc, coupled, a2, Ks, Kt)
    ath[i] = at
    w[i] += hb * at
    x = Pc[i] + ha * w[i]
    if coupled:
        aU[i] = au
        Vu[i] += hb * au
        PUn[i] = PUc[i] + ha * Vu[i]
    Pn[i] = x
    Sn[i], Cn[i], Vn[i] = _sincosvers(x)
    return _bad(x)


@njit(cache=True, fastmath=_FAST, boundscheck=False)
def _srkn_pass(Pc, Sc, Cc, Vc, PUc, Pn, Sn, Cn, Vn, PUn, w, Vu, ath, aU, coupled, a2, Ks, Kt,
               hb, ha):
    n = w.size
    bad = 0
    if coupled:
        for i in range(1, n - 1):
            bad += _srkn_site(i, i - 1, i + 1, Pc, Sc, Cc, Vc, PUc, Pn, Sn, Cn, Vn, PUn, w, Vu,
                              ath, aU, True, a2, Ks, Kt, hb, ha)
    else:
        for i in range(1, n - 1):
            bad += _srkn_site(i, i - 1, i + 1, Pc, Sc, Cc, Vc, PUc, Pn, Sn, Cn, Vn, PUn, w, Vu,
                              ath, aU, False, a2, Ks, Kt, hb, ha)
    for i, im, ip in ((0, n - 1, 1), (n - 1, n - 2, 0)):
        bad += _srkn_site(i, im, ip, Pc, Sc, Cc, Vc, PUc, Pn, Sn, Cn, Vn, PUn, w, Vu, ath, aU,
                          coupled, a2, Ks, Kt, hb, ha)
    return bad


@njit(cache=True, fastmath=_FAST, boundscheck=False)
def _kick_drift(P0, Pn, Sn, Cn, Vn, PU0, PUn, w, Vu, ath, aU, coupled, hb, ha):
    """The step's first kick (known accelerations) and drift from P0 into the next buffers."""
    bad = 0
    for i in range(w.size):
        w[i] += hb * ath[i]
        x = P0[i] + ha * w[i]
        Pn[i] = x
        Sn[i], Cn[i], Vn[i] = _sincosvers(x)
        bad += _bad(x)
    if coupled:
        for i in range(w.size):
            Vu[i] += hb * aU[i]
            PUn[i] = PU0[i] + ha * Vu[i]
    return bad


@njit(cache=True, nogil=True, fastmath=_FAST, boundscheck=False)
def srkn_steps(th, w, U, V, ath, aU, coupled, a2, Ks, Kt, acoef, bcoef, dt, nsteps, work,
               work_U):
    """Symplectic RKN steps, BAB composition (kick b0, drift a0, kick b1, ...), fused.

    ``ath``/``aU`` must hold the accelerations at the current state on entry; they hold
    those of the final state on exit (first same as last). ``work`` has shape (8, N),
    ``work_U`` (2, N), or (2, 0) in case "rotation". Verlet is a = (1, 0), b = (1/2, 1/2).
    The last kick's pass drifts by 0 (it only stores the final positions).
    Returns the number of steps completed in range.
    """
    nst = acoef.size
    Pc, Pn, Sc, Sn, Cc, Cn, Vc, Vn = (work[0], work[1], work[2], work[3], work[4], work[5],
                                      work[6], work[7])
    PUc, PUn = work_U[0], work_U[1]
    done = nsteps
    for step in range(nsteps):
        # the step starts from (th, U): kick b0 + drift a0 into the current buffers
        bad = _kick_drift(th, Pc, Sc, Cc, Vc, U, PUc, w, V, ath, aU, coupled, bcoef[0] * dt,
                          acoef[0] * dt)
        for j in range(1, nst):
            ha = acoef[j] * dt if j < nst - 1 else 0.0
            bad += _srkn_pass(Pc, Sc, Cc, Vc, PUc, Pn, Sn, Cn, Vn, PUn, w, V, ath, aU,
                              coupled, a2, Ks, Kt, bcoef[j] * dt, ha)
            Pc, Pn, Sc, Sn, Cc, Cn, Vc, Vn, PUc, PUn = Pn, Pc, Sn, Sc, Cn, Cc, Vn, Vc, PUn, PUc
        th[:] = Pc
        if coupled:
            U[:] = PUc
        if bad:
            done = step + 1 if _finite(th) and _finite(w) else step
            break
    return done


def empty_u():
    return np.zeros(0)


def vectorised_loops(coupled: bool = True) -> dict:
    """Which fused passes compile to SIMD code: {name: True if their LLVM IR holds
    ``<N x double>`` operations}. How the loops were checked (and are, in the tests):
    an uncached copy of each pass is compiled for representative arguments and its IR
    searched; on this machine it shows ``<8 x double>`` (AVX-512), ``<4 x ...>`` on AVX2.
    """
    import re

    n = 16
    arr = [np.zeros(n) for _ in range(20)]
    par = (coupled, 1.0, 0.02, 0.01)
    calls = {"_rk4_pass": (_rk4_pass, (*arr, *par, 1.0, 2.0, 0.05)),
             "_rk4_last_pass": (_rk4_last_pass, (*arr, *par, 0.01)),
             "_srkn_pass": (_srkn_pass, (*arr[:14], *par, 0.1, 0.1)),
             "accel": (accel, (arr[0], arr[1], coupled, 1.0, 0.02, 0.01, *arr[2:7]))}
    out = {}
    for name, (fn, args) in calls.items():
        copy = njit(fastmath=_FAST, boundscheck=False)(fn.py_func)
        copy(*args)
        out[name] = bool(re.search(r"<\d+ x double>", copy.inspect_llvm(copy.signatures[0])))
    return out
