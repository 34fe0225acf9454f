"""The damping of the exact theory's growing modes at t = 0, from the damped Hill pencil.

A mode e^{lambda t} e^{i q n} sum_l c_l e^{i l xi_n} of the held carrier with Rayleigh
damping: its harmonic l is a wave of wavenumber q + l k and time factor
e^{(lambda - i l omega) t}, damped by the force -C(q + l k) (lambda - i l omega) c_l
(``damping_matrix``). The scaled pencil of ``_sidebands`` gains C(q + l k)
(lambda - i l omega) per harmonic; its eigenvalue continued from the lossless growing one
(``_damped_rayleigh``: the lossless eigenvalue from the compiled paths, its right and left
eigenvectors, the first-order damped eigenvalue from them, inverse iteration there, then
the two-sided Rayleigh iteration) gives the mode's net rate, every harmonic damped at its
own wavenumber: the time-domain monodromy of the damped ring (probe 102,
``bench/_floquet102_ref.py``) to 1e-12, and the dense damped pencil's eigenvalue followed
along the damping at 560 growing offsets of random flexmm-lossy, fput and Klein-Gordon
rings (damping 1e-3 to 0.2). Before, each offset was damped as the carrier
branch's sidebands k +- q, the mode's waves only where it is centred at l = +-1: a ring
shows the same pair at other offsets too (at k = pi on 10 sites the pair pi +- 0.628 also
at q = 2.513, centred at l = 0, damped at 1.6e-4 for the monodromy's 6.25e-4), and the
paper chain's theta pairs hold U harmonics, damped at U's rate (flexmm-lossy, k 1, a 0.1,
gamma_U 0: G 0.0040 for 0.0063). The offset's net rate is its fastest damped mode's,
not the fastest lossless mode's damped: the offset's other growing modes are continued
where their lossless rate passes that (review 102: theta damped, U not, a slower mode
holding less theta nets 0.0547 where the fastest nets 0.0056). Not covered: a mode
neutral without losses that the damping destabilises (negative energy; review 102's
strict xfail, tests/test_lossreview102.py). Cost: compiled, a few LUs of the pencil a mode (the
copies of a mode on a ring share it): 2 ms (Klein-Gordon, N 256) to 12 ms (flexmm,
N 256, 58 growing offsets, most of it their eigenvalues from the compiled paths again);
in numpy with the dense eigenvalues at flexmm's offsets it was 2-10x that.
"""


from __future__ import annotations

import numpy as np
from numba import njit

from ._chaining import pencil_parts
from ._hill_dense import _DensePencil
from ._linear import damping_matrices
from ._sidebands import _pencil_from_parts
from ._small_algebra import _drop_roundoff, _lu, _lu_solve, _lu_solve_t

#: Rayleigh-quotient steps on the damped pencil after its first-order start (converges
#: quadratically: two suffice at every probe-102 point; the rest is margin)
STEPS = 6


def _copies(offsets, gains, live, k) -> np.ndarray:
    """For each live offset, the live offset whose damping it takes: itself, or an
    earlier one where a copy of its mode sits (q +- k, q +- 2k folded into [0, pi]) with
    the same rate to 1e-12 (a ring shows one mode at each harmonic it is centred at)."""
    live = np.asarray(live, int)
    key = np.round(offsets[live], 9)
    order = np.argsort(key, kind="stable")
    # each live offset's copies' positions among the live ones (-1: none), s = -2..2
    c = np.round(np.abs((offsets[live][:, None] + np.array([-2, -1, 1, 2]) * k + np.pi)
                        % (2 * np.pi) - np.pi), 9)
    at = np.searchsorted(key[order], c)
    hit = (at < key.size) & (key[order][np.minimum(at, key.size - 1)] == c)
    pos = np.where(hit, order[np.minimum(at, key.size - 1)], -1)
    g = gains[live]
    out = np.arange(live.size)
    for i in range(live.size):
        for h in pos[i]:
            if 0 <= h < i and abs(g[h] - g[i]) <= 1e-12 * g[i]:
                out[i] = out[h]
                break
    return out


def mode_damping(spec, model, live) -> np.ndarray:
    """G at the offsets ``spec.offsets[live]``: each one's fastest lossless rate minus the
    damped pencil's rate of the same mode, at the spectrum's truncation P (``_copies``:
    once per mode a ring shows at several offsets)."""
    from ._exact import _Sidebands

    wave = spec.wave
    P = int(spec.truncations[0]) if spec.truncations else wave.harmonics + 4
    pencil = _DensePencil(wave, P)
    d, k, omega, l_, n = pencil.d, pencil.k, pencil.omega, pencil.l_, pencil.n
    offsets = np.asarray(spec.offsets, float)
    gains = np.asarray(spec.gain, float)
    live = np.asarray(live, int)
    rep = _copies(offsets, gains, live, k)
    own = np.flatnonzero(rep == np.arange(live.size))
    q_own, g_own = offsets[live[own]], gains[live[own]]
    R = own.size
    # the lossless modes' eigenvalues from the compiled paths (``_exact._Sidebands``: the
    # clusters, else the central pencil refined: flexmm's offsets, whose dense
    # eigenvalues cost ~3 ms each), every kept growing one, where they settle; else the
    # dense eigenvalues
    from ._exact import MAX_MODES

    lam_all = np.full((R, MAX_MODES), np.nan, complex)
    _Sidebands(wave, P, pencil.Hh).spectrum(q_own, eigenvalues=lam_all)
    re = np.where(np.isfinite(lam_all.real), lam_all.real, -np.inf)
    lam0 = lam_all[np.arange(R), np.argmax(re, axis=1)]
    with np.errstate(invalid="ignore"):
        found = np.abs(lam0.real - g_own) <= 1e-8 * np.maximum(g_own, omega)
    for r in np.flatnonzero(~found):  # the dense eigenvalues where none was found
        q, g = q_own[r], g_own[r]
        lam = np.linalg.eigvals(pencil.linearisation(q))
        # the mode of that rate, its copy nearest the centre (the copies lie omega apart
        # with one rate; a copy near the truncation is the distorted one)
        near = np.flatnonzero(np.abs(lam.real - g) <= 1e-8 * max(g, omega))
        lam0[r] = lam[near[np.argmin(np.abs(lam[near].imag))]] if near.size else \
            lam[np.argmin(np.abs(lam.real - g))]
        # the other growing modes: one copy each, the one nearest the centre
        lam = lam[(lam.real > 0) & (np.abs(lam.imag) <= omega / 2)][:MAX_MODES]
        lam_all[r] = np.nan
        lam_all[r, :lam.size] = lam
    # each harmonic's damping C(q + l k), scaled as the pencil M^{-1/2} C M^{-1/2}
    sq = 1 / np.sqrt(np.asarray(model.masses, float))
    blocks = damping_matrices(model, (q_own[:, None] + l_[None, :] * k).ravel())
    Cs = np.ascontiguousarray(blocks.reshape(R, 2 * P + 1, d, d) * np.outer(sq, sq))
    parts = pencil_parts(_drop_roundoff(pencil.Hh), sq, np.exp(
        -1j * (np.arange(4 * P + 1) - 2 * P) * k))
    start = np.random.default_rng(0).standard_normal(n) + 0j
    shift = np.empty(R, complex)
    _damped_rayleigh(parts, P, k, omega, q_own, lam0, Cs, start, STEPS, shift)
    best = shift.real.copy()
    # the offset's other growing modes, where one could outgrow the fastest damped (a
    # damping on one field leaves a slower mode of the other ahead: flexmm-lossy,
    # gamma_theta 0.043, gamma_U 0, k 2 pi 7/16, a 0.169: the theta mode nets -0.096,
    # a U-heavy one +0.018, the damped ring's monodromy 0.018; review 102). Not the
    # fastest's copies (lam0 + i l omega) nor a mode slower than the best already
    # damped (a damping that speeds a mode is rare: probe 102's one resonance was the
    # fastest mode)
    turns = np.abs((lam_all.imag - lam0.imag[:, None]) / omega)
    copy = (np.abs(lam_all.real - lam0.real[:, None]) <= 1e-8 * np.maximum(
        g_own, omega)[:, None]) & (np.abs(turns - np.round(turns)) <= 1e-6)
    with np.errstate(invalid="ignore"):
        rows, cols = np.nonzero((lam_all.real > best[:, None]) & ~copy)
    if rows.size:
        more = np.empty(rows.size, complex)
        _damped_rayleigh(parts, P, k, omega, q_own[rows], lam_all[rows, cols],
                         np.ascontiguousarray(Cs[rows]), start, STEPS, more)
        np.maximum.at(best, rows, more.real)
    return (g_own - best)[np.searchsorted(own, rep)]  # own: the representatives, sorted


@njit(cache=True, nogil=True, error_model="numpy", boundscheck=False)
def _pencil_at(K, Cs_r, z, d, damped, Q):
    """Q(lam) = (lam - i l omega)^2 + K + [damped] C_l (lam - i l omega) into ``Q``; ``z``
    holds lam - i l omega per harmonic."""
    n = K.shape[0]
    for i in range(n):
        for j in range(n):
            Q[i, j] = K[i, j]
    for li in range(z.size):
        for a in range(d):
            i = li * d + a
            Q[i, i] += z[li] * z[li]
            if damped:
                for b in range(d):
                    Q[i, li * d + b] += Cs_r[li, a, b] * z[li]


@njit(cache=True, nogil=True, error_model="numpy", boundscheck=False)
def _derivative_products(Cs_r, z, d, damped, x, y, bx, by):
    """Q'(lam) x into ``bx`` and conj(Q'(lam)^H y) into ``by`` (the right side of the
    transposed solve: Q^H u = c is Q^T conj(u) = conj(c)); Q' = 2 (lam - i l omega)
    + [damped] C_l, block diagonal."""
    for li in range(z.size):
        for a in range(d):
            i = li * d + a
            ax = 2 * z[li] * x[i]
            ay = np.conj(2 * z[li]) * y[i]
            if damped:
                for b in range(d):
                    ax += Cs_r[li, a, b] * x[li * d + b]
                    ay += np.conj(Cs_r[li, b, a]) * y[li * d + b]
            bx[i, 0] = ax
            by[i, 0] = np.conj(ay)


@njit(cache=True, nogil=True, error_model="numpy", boundscheck=False)
def _factor(Q, omega, F, piv):
    """The LU of Q + 1e-14 omega^2 (a shift at an eigenvalue stays solvable) into F."""
    n = Q.shape[0]
    for i in range(n):
        for j in range(n):
            F[i, j] = Q[i, j]
        F[i, i] += 1e-14 * omega * omega
    return _lu(F, piv)


@njit(cache=True, nogil=True, error_model="numpy", boundscheck=False)
def _inverse_step(F, piv, bx, by, x, y):
    """x <- Q^-1 Q' x, y <- Q^-H Q'^H y from the products in bx, by; both normalised."""
    _lu_solve(F, piv, bx)
    _lu_solve_t(F, piv, by)
    nx = 0.0
    ny = 0.0
    for i in range(x.size):
        nx += bx[i, 0].real ** 2 + bx[i, 0].imag ** 2
        ny += by[i, 0].real ** 2 + by[i, 0].imag ** 2
    nx, ny = np.sqrt(nx), np.sqrt(ny)
    for i in range(x.size):
        x[i] = bx[i, 0] / nx
        y[i] = np.conj(by[i, 0]) / ny


@njit(cache=True, nogil=True, error_model="numpy", boundscheck=False)
def _rayleigh_step(Q, Cs_r, z, d, x, y):
    """y^H Q x / y^H Q'(damped) x: the two-sided Rayleigh quotient's correction."""
    num = 0j
    den = 0j
    n = x.size
    for li in range(z.size):
        for a in range(d):
            i = li * d + a
            qx = 0j
            for j in range(n):
                qx += Q[i, j] * x[j]
            dx = 2 * z[li] * x[i]
            for b in range(d):
                dx += Cs_r[li, a, b] * x[li * d + b]
            num += np.conj(y[i]) * qx
            den += np.conj(y[i]) * dx
    return num / den


@njit(cache=True, nogil=True, error_model="numpy", boundscheck=False)
def _damped_rayleigh(parts, P, k, omega, offsets, lam0, Cs, start, most, out):
    """Each mode's damped eigenvalue into ``out``, continued from its lossless ``lam0``
    on the scaled quadratic pencil Q(lam) = (lam - i l omega)^2 + K(q) + C_l (lam - i l
    omega) (K: ``_sidebands._pencil_from_parts``; C_l = ``Cs``, each harmonic's damping
    at q + l k). The lossless pencil's right and left eigenvectors at lam0 (inverse
    iteration there, one LU), the first-order damped eigenvalue from them (one Rayleigh
    correction: a start whose error is second order in the damping), one inverse step at
    that start, then the two-sided Rayleigh iteration x <- Q^-1 Q' x, y <- Q^-H Q'^H y, lam <- lam - y^H Q x /
    y^H Q' x, until a step is below 1e-12 (|lam| + omega) or after ``most`` steps."""
    d = parts.shape[2]
    nl = 2 * P + 1
    n = d * nl
    K = np.empty((n, n), np.complex128)
    Q = np.empty((n, n), np.complex128)
    F = np.empty((n, n), np.complex128)
    eq = np.empty(nl, np.complex128)
    piv = np.empty(n, np.int64)
    bx = np.empty((n, 1), np.complex128)
    by = np.empty((n, 1), np.complex128)
    x = np.empty(n, np.complex128)
    y = np.empty(n, np.complex128)
    z = np.empty(nl, np.complex128)
    for r in range(offsets.size):
        _pencil_from_parts(parts, P, k, offsets[r], eq, K)
        Cs_r = Cs[r]
        shift = lam0[r]
        x[:] = start
        y[:] = start
        for li in range(nl):
            z[li] = shift - 1j * (li - P) * omega
        # the start: the lossless right and left eigenvectors at lam0 (one inverse step:
        # lam0 is an eigenvalue) and the first-order damped eigenvalue from them. From a
        # random vector, the Rayleigh iteration's first shift landed on the growing mode's
        # decaying partner (-conj(lam0), 2 sigma away) at 12 of 369 random growing offsets
        # (flexmm-lossy, gamma 0.002 each, k 2 pi 23/64, a 0.18: G 0.052 for 0.0063); an
        # inverse iteration at lam0 alone, the damped eigenvalue nearest it, is another
        # mode where the damping is as large as the rate (fput gamma 0.3: G 0.133 for
        # 0.150)
        _pencil_at(K, Cs_r, z, d, False, Q)
        if _factor(Q, omega, F, piv):  # (an exact zero pivot: from the random vectors)
            _derivative_products(Cs_r, z, d, False, x, y, bx, by)
            _inverse_step(F, piv, bx, by, x, y)
            _pencil_at(K, Cs_r, z, d, True, Q)
            shift = shift - _rayleigh_step(Q, Cs_r, z, d, x, y)
        for _ in range(1 + most):  # an inverse step at the start, then Rayleigh's
            for li in range(nl):
                z[li] = shift - 1j * (li - P) * omega
            _pencil_at(K, Cs_r, z, d, True, Q)
            if not _factor(Q, omega, F, piv):
                break
            _derivative_products(Cs_r, z, d, True, x, y, bx, by)
            _inverse_step(F, piv, bx, by, x, y)
            step = _rayleigh_step(Q, Cs_r, z, d, x, y)
            shift = shift - step
            if abs(step) <= 1e-12 * (abs(shift) + omega):
                break
        out[r] = shift
