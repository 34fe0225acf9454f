"""The damping of the exact theory's growing modes at t = 0, from the damped Hill pencil.

A mode e^{lambda t} e^{i q n} sum_l c_l e^{i l xi_n} of the held carrier with Rayleigh
damping: its harmonic l is a wave of wavenumber q + l k and time factor
e^{(lambda - i l omega) t}, damped by the force -C(q + l k) (lambda - i l omega) c_l
(``damping_matrix``). The pencil of ``_hill_dense`` gains C(q + l k) (lambda - i l omega)
per harmonic; its eigenvalue continued from the lossless growing one (from the compiled
path's eigenvalue, by a two-sided Rayleigh iteration of the quadratic pencil: a damping
moves it by ~G, its copies lie omega apart) gives the mode's net rate, every harmonic
damped at its own wavenumber: the time-domain monodromy of the damped ring (probe 102,
``bench/_floquet102_ref.py``) to 1e-12. Before, each offset was damped as the carrier
branch's sidebands k +- q, the mode's waves only where it is centred at l = +-1: a ring
shows the same pair at other offsets too (at k = pi on 10 sites the pair pi +- 0.628 also
at q = 2.513, centred at l = 0, damped at 1.6e-4 for the monodromy's 6.25e-4), and the
paper chain's theta pairs hold U harmonics, damped at U's rate (flexmm-lossy, k 1, a 0.1,
gamma_U 0: G 0.0040 for 0.0063). Cost: ~0.15 ms a mode (the copies of a mode on a ring
share it), 1.9-2.6x a lossless point's theory rows where 1.6-1.9x before
(``bench.losses_points``).
"""


from __future__ import annotations

import numpy as np

from ._hill_dense import _DensePencil

#: Rayleigh-quotient steps on the damped pencil from the lossless eigenvalue (converges
#: quadratically: two suffice at every probe-102 point; the rest is margin)
STEPS = 6


def _damping_blocks(S, B, kappas) -> np.ndarray:
    """C(kappa) for many kappa at once, shape (len, d, d): ``damping_matrix``'s
    C_site + B11 + B22 + B12 e^{i kappa} + B21 e^{-i kappa} (S, B: ``Model.damping``)."""
    d = S.shape[0]
    z = np.exp(1j * np.asarray(kappas, float))[:, None, None]
    return (S + B[:d, :d] + B[d:, d:])[None] + B[:d, d:][None] * z + B[d:, :d][None] / z


def _copies(offsets, gains, live, k) -> np.ndarray:
    """For each live offset, the live offset whose damping it takes: itself, or an
    earlier one where a copy of its mode sits (q +- k, q +- 2k folded into [0, pi]) with
    the same rate to 1e-12 (a ring shows one mode at each harmonic it is centred at)."""
    where = {round(float(q), 9): int(j) for j, q in zip(live, offsets[live])}
    rep = {}
    out = np.empty(len(live), int)
    for i, j in enumerate(live):
        q, g = float(offsets[j]), float(gains[j])
        out[i] = i
        for s_ in (-2, -1, 1, 2):
            c = abs((q + s_ * k + np.pi) % (2 * np.pi) - np.pi)
            h = where.get(round(c, 9))
            if h is not None and h in rep and abs(gains[h] - g) <= 1e-12 * g:
                out[i] = rep[h]
                break
        rep[int(j)] = int(out[i])
    return out


def mode_damping(spec, model, live) -> np.ndarray:
    """G at the offsets ``spec.offsets[live]``: each one's fastest lossless rate minus the
    damped pencil's rate of the same mode, at the spectrum's truncation P (``_copies``:
    once per mode a ring shows at several offsets)."""
    from ._exact import MAX_CLUSTER, MAX_MODES
    from ._sidebands import sideband_modes

    wave = spec.wave
    P = int(spec.truncations[0]) if spec.truncations else wave.harmonics + 4
    pencil = _DensePencil(wave, P)
    d, k, omega, l_, n = pencil.d, pencil.k, pencil.omega, pencil.l_, pencil.n
    Minv, ll, m = pencil.Minv, pencil.ll, pencil.m
    S, B = model.damping
    offsets = np.asarray(spec.offsets, float)
    gains = np.asarray(spec.gain, float)
    live = np.asarray(live, int)
    rep = _copies(offsets, gains, live, k)
    own = np.flatnonzero(rep == np.arange(live.size))
    q_own, g_own = offsets[live[own]], gains[live[own]]
    R = own.size
    # the lossless modes' eigenvalues from the compiled path (``_sidebands``), where it
    # settles; else the dense eigenvalues
    lam_c, _, count = sideband_modes(pencil.Hh, np.asarray(model.masses, float), k, omega,
                                     P, q_own, pencil.floor, MAX_MODES, MAX_CLUSTER, True,
                                     False)
    K0 = np.zeros((R, n, n), complex)
    lam0 = np.zeros(R, complex)
    for r, (q, g) in enumerate(zip(q_own, g_own)):
        K0[r] = pencil.stiffness(q) - np.diag(ll**2 * omega**2 * m)
        lam = lam_c[r, :count[r]] if count[r] > 0 else np.zeros(0, complex)
        if not np.any(np.abs(lam.real - g) <= 1e-8 * max(g, omega)):
            A = np.zeros((2 * n, 2 * n), complex)
            A[:n, n:] = np.eye(n)
            A[n:, :n] = -Minv[:, None] * K0[r]
            A[n:, n:] = np.diag(2j * omega * ll)
            lam = np.linalg.eigvals(A)
        # the mode of that rate, its copy nearest the centre (the copies lie omega apart
        # with one rate; a copy near the truncation is the distorted one)
        near = np.flatnonzero(np.abs(lam.real - g) <= 1e-8 * max(g, omega))
        lam0[r] = lam[near[np.argmin(np.abs(lam[near].imag))]] if near.size else \
            lam[np.argmin(np.abs(lam.real - g))]
    # the pencil Q(lam) = m lam^2 + lam D1 + D0 of each harmonic's wave: m (lam - i l w)^2
    # + C (lam - i l w) + L, C block diagonal over the harmonics at their wavenumbers
    # q + l k
    blocks = _damping_blocks(S, B, (q_own[:, None] + l_[None, :] * k).ravel())
    blocks = blocks.reshape(R, 2 * P + 1, d, d)
    C = np.zeros((R, 2 * P + 1, d, 2 * P + 1, d), complex)
    h = np.arange(2 * P + 1)
    C[:, h, :, h, :] = blocks.transpose(1, 0, 2, 3)
    C = C.reshape(R, n, n)
    D1 = C + np.diag(-2j * omega * ll * m)[None]
    D0 = K0 - 1j * omega * ll[None, None, :] * C
    Mm = np.diag(m).astype(complex)[None]
    # the damped eigenvalue continued from lam0 (a damping moves it by ~G, its copies lie
    # omega away): two-sided Rayleigh iteration of the quadratic pencil,
    # x <- Q^-1 Q' x, y <- Q^-H Q'^H y, lam <- lam - y^H Q x / y^H Q' x
    start = np.random.default_rng(0).standard_normal(n) + 0j
    x = np.broadcast_to(start, (R, n))[..., None]
    y = x
    shift = lam0.copy()
    for _ in range(STEPS):
        lam_ = shift[:, None, None]
        Q = lam_**2 * Mm + lam_ * D1 + D0
        dQ = 2 * lam_ * Mm + D1
        x = np.linalg.solve(Q + 1e-14 * omega**2 * Mm, dQ @ x)
        y = np.linalg.solve(np.conj(Q.transpose(0, 2, 1)) + 1e-14 * omega**2 * Mm,
                            np.conj(dQ.transpose(0, 2, 1)) @ y)
        x /= np.linalg.norm(x, axis=1, keepdims=True)
        y /= np.linalg.norm(y, axis=1, keepdims=True)
        yH = np.conj(y.transpose(0, 2, 1))
        step = (yH @ Q @ x)[:, 0, 0] / (yH @ dQ @ x)[:, 0, 0]
        shift = shift - step
        if np.all(np.abs(step) <= 1e-12 * (np.abs(shift) + omega)):
            break
    G_own = g_own - shift.real
    where = {int(o): r for r, o in enumerate(own)}
    return np.array([G_own[where[int(rep[i])]] for i in range(live.size)])
