"""The four-wave kernel of a plane wave (``_fourwave``'s module docstring derives it),
split from ``_fourwave``: the carrier to O(a^2) (its second harmonic, optical mean and
own frequency Omega), the Fourier coefficients of the cell Hessian along it, and every
branch pair's rate, detuning and coupling at the offsets q, vectorised over q; the
carrier's second-harmonic size that ``travelling_wave`` checks its wave's family with.
"""

from __future__ import annotations

import math

import numpy as np

from energy import Model

from ._linear import carrier, dynamical_matrix

#: A driven wave whose operator has a singular value below this share of the largest is
#: resonant with a branch: the four-wave ordering fails there (a three-wave process).
RESONANT = 1e-8
#: A driven wave this large (the square root of its energy, y^H K y + phi^2 y^H M y,
#: against the pair's, omega1^2 + omega2^2: a long acoustic wave's displacement is large
#: for a small strain, its energy is not) is no longer slaved to the pair: it is a free
#: wave in a three-wave resonance with the carrier and the pair, which the four-wave
#: ordering does not treat (its rate is left nan).
DRIVEN_MAX = 0.5

#: A discriminant (Delta'/2)^2 - kappa12 kappa21 this small against its terms is round-off.
FLOOR = 1e-10


def _contract(T, x):
    return np.einsum("ijm,m->ij", T, x)


def _harmonic_ratio(H, M, k, w, e, v2) -> float:
    """sqrt of the energy of the second harmonic's response v2 over the carrier's e."""
    K1, K2 = dynamical_matrix(H, k), dynamical_matrix(H, 2 * k)
    e1 = np.real(e.conj() @ K1 @ e + w**2 * e.conj() @ M @ e)
    e2 = np.real(v2.conj() @ K2 @ v2 + (2 * w) ** 2 * v2.conj() @ M @ v2)
    return math.sqrt(abs(e2) / e1) if e1 > 0 else math.inf


def second_harmonic_size(model: Model, k: float, a: float, branch=None, car=None) -> float:
    """The carrier's second harmonic at amplitude a, to O(a^2), against its first
    harmonic (square root of their energies' ratio; inf at a resonance): small for a
    weakly nonlinear wave, O(1) where 2 omega(k) meets a branch at 2k. ``car``: the
    carrier ``carrier(model, k, branch)`` where the caller has it (``travelling_wave``:
    ~0.07 ms of its ~1.3 for fput)."""
    H, T, _ = model.code.taylor(model.p)
    d = model.n_fields
    M = np.diag(np.asarray(model.masses, float))
    c = carrier(model, k, branch) if car is None else car
    X1 = np.concatenate([c.e, np.exp(1j * k) * c.e])
    P2 = np.hstack([np.eye(d), np.eye(d) * np.exp(-2j * k)])
    D2 = dynamical_matrix(H, 2 * k) - (2 * c.omega) ** 2 * M
    f2 = -P2 @ np.einsum("ibc,b,c->i", T, X1, X1) / 2
    try:
        v2 = np.linalg.solve(D2, f2)
    except np.linalg.LinAlgError:
        return math.inf
    return a / 2 * _harmonic_ratio(H, M, k, c.omega, c.e, v2)


def _plane_wave(model: Model, k: float, a: float, branch):
    """The carrier to O(a^2): (Carrier, Omega, x1, x2, x0) with x_h the cell's (u_n,
    u_{n+1}) harmonic h; or a reason string where the expansion fails."""
    H, T, Q = model.code.taylor(model.p)
    d = model.n_fields
    M = np.diag(np.asarray(model.masses, float))
    c = carrier(model, k, branch)
    e, w = c.e, c.omega
    if c.gap < 1e-7 * max(w, 1e-300):
        return f"degenerate carrier: another branch has the frequency {w:.6g} at k = {k:.6g}"
    z = np.exp(1j * k)
    X1 = np.concatenate([e, z * e])
    scale = max(1.0, float(np.max(np.abs(H))))

    def P(kap):
        return np.hstack([np.eye(d), np.eye(d) * np.exp(-1j * kap)])

    D2 = dynamical_matrix(H, 2 * k) - (2 * w) ** 2 * M
    f2 = -P(2 * k) @ np.einsum("ibc,b,c->i", T, X1, X1) / 2
    sv = np.linalg.svd(D2, compute_uv=False)
    if sv[-1] < RESONANT * max(sv[0], scale) and np.linalg.norm(f2) > RESONANT * scale:
        return f"second harmonic resonant with a branch at 2k = {2 * k:.6g}"
    v2 = np.linalg.lstsq(D2, f2, rcond=None)[0]
    # near (not at) that resonance the second harmonic is no longer slaved: its energy
    # against the first harmonic's, as DRIVEN_MAX measures a pair's driven waves
    size = a / 2 * _harmonic_ratio(H, M, k, w, e, v2)
    if size > DRIVEN_MAX:
        return (f"second harmonic near resonance with a branch at 2k = {2 * k:.6g}: its energy "
                f"{size**2:.3g} x the carrier's at amplitude {a:.6g}; the four-wave ordering "
                "fails there (a three-wave process; the exact theory holds)")
    K0 = np.real(dynamical_matrix(H, 0.0))
    f0 = -np.real(P(0.0) @ np.einsum("ibc,b,c->i", T, X1, X1.conj()))
    w0 = np.linalg.pinv(K0, rcond=1e-10, hermitian=True) @ f0  # optical mean: no strain
    X2 = np.concatenate([v2, z**2 * v2])
    X0 = np.concatenate([w0, w0]).astype(complex)
    F1 = -P(k) @ (np.einsum("ibc,b,c->i", T, X0, X1) + np.einsum("ibc,b,c->i", T, X2, X1.conj())
                  + np.einsum("ibcd,b,c,d->i", Q, X1, X1, X1.conj()) / 2)
    g2_wave = float(np.real(e.conj() @ F1)) / (2 * w * float(np.real(e.conj() @ M @ e)))
    Omega = w - g2_wave * a**2 / 4
    return c, Omega, a / 2 * X1, a**2 / 4 * X2, a**2 / 4 * X0


def _kernel(model: Model, k: float, a: float, branch):
    """(rates, pairs, carrier, Omega): rates(q) -> (rate, detuning, coupling) of every
    branch pair at the offsets q; or the reason the expansion fails."""
    wave = _plane_wave(model, k, a, branch)
    if isinstance(wave, str):
        return wave
    car, Omega, x1, x2, x0 = wave
    H, T, Q = model.code.taylor(model.p)
    d = model.n_fields
    pairs = [(b1, b2) for b1 in range(d) for b2 in range(d)]
    Hh = {1: _contract(T, x1), -1: _contract(T, x1.conj()),
          2: _contract(T, x2) + np.einsum("ijmn,m,n->ij", Q, x1, x1) / 2}
    Hh[-2] = Hh[2].conj()
    Hh[0] = _contract(T, x0) + np.einsum("ijmn,m,n->ij", Q, x1, x1.conj())
    return (lambda offsets: _rates(model, k, car, Omega, Hh, pairs, offsets)), pairs, car, Omega


def _rates(model, k, car, Omega, Hh, pairs, offsets):
    H = model.code.taylor(model.p)[0]
    d = model.n_fields
    m = np.asarray(model.masses, float)
    s = 1 / np.sqrt(m)
    q = np.atleast_1d(np.asarray(offsets, dtype=float))
    n = q.size
    eye = np.eye(d)

    def Pm(kap):  # (n, d, 2d)
        ph = np.exp(-1j * kap)[:, None, None]
        return np.concatenate([np.broadcast_to(eye, (kap.size, d, d)), eye * ph], axis=2)

    def Xm(kap):  # (n, 2d, d)
        ph = np.exp(1j * kap)[:, None, None]
        return np.concatenate([np.broadcast_to(eye, (kap.size, d, d)), eye * ph], axis=1)

    kap = {l: q + l * k for l in (-2, -1, 0, 1, 2)}
    P_ = {l: Pm(kap[l]) for l in kap}
    X_ = {l: Xm(kap[l]) for l in kap}

    def B(l, h):
        return P_[l] @ Hh[l - h] @ X_[h]

    def K(kp):  # (n, d, d)
        z = np.exp(1j * kp)[:, None, None]
        return (H[:d, :d] + H[d:, d:]) + H[:d, d:] * z + H[d:, :d] / z

    def modes(kp):
        A = s[None, :, None] * K(kp) * s[None, None, :]
        lam, phi = np.linalg.eigh(A)
        om = np.where(lam >= 0, np.sqrt(np.abs(lam)), np.nan)
        return om, s[None, :, None] * phi  # e^H M e = 1

    om1, E1 = modes(q + k)
    om2, E2 = modes(k - q)
    Bs = {(l, h): B(l, h) for l, h in ((1, 1), (-1, -1), (1, -1), (-1, 1), (1, 0), (0, 1),
                                        (0, -1), (-1, 0), (1, 2), (2, 1), (-1, -2), (-2, -1))}
    Kd = {l: K(kap[l]) for l in (0, 2, -2)}
    M = np.diag(m)
    # the driven second harmonics at the carrier's linear 2 omega, as the carrier's own
    # (_plane_wave): the same denominator at q -> 0, where the pair is the carrier
    w = car.omega
    rate = np.full((n, len(pairs)), np.nan)
    det = np.full_like(rate, np.nan)
    coup = np.full_like(rate, np.nan)

    def mv(A, v):
        return np.einsum("nij,nj->ni", A, v)

    def solve(D, f):
        # a nearly singular D shows as a driven wave too large to be slaved (DRIVEN_MAX);
        # an exactly singular one (rare) is found by the SVD
        try:
            y = np.linalg.solve(D, f[..., None])[..., 0]
            return y, ~np.all(np.isfinite(y), axis=1)
        except np.linalg.LinAlgError:
            sv = np.linalg.svd(D, compute_uv=False)
            bad = sv[:, -1] < RESONANT * np.maximum(sv[:, 0], 1.0)
            Dr = np.where(bad[:, None, None], np.eye(d), D)
            return np.linalg.solve(Dr, f[..., None])[..., 0], bad

    # nan where a wave has zero frequency, or its coupling overflows (a branch at 1e150)
    with np.errstate(invalid="ignore", divide="ignore", over="ignore"):
        for j, (b1, b2) in enumerate(pairs):
            w1, w2 = om1[:, b1], om2[:, b2]
            e1, e2c = E1[:, :, b1], E2[:, :, b2].conj()
            t1 = Omega + (w1 - w2) / 2  # the pair's frequencies, summing to 2 Omega
            t2 = Omega + (w2 - w1) / 2
            D0 = Kd[0] - ((t1 - Omega) ** 2)[:, None, None] * M
            D2 = Kd[2] - ((t1 - Omega + 2 * w) ** 2)[:, None, None] * M
            Dm2 = Kd[-2] - ((t2 - Omega + 2 * w) ** 2)[:, None, None] * M
            y01, r0 = solve(D0, mv(Bs[0, 1], e1))
            y0m, _ = solve(D0, mv(Bs[0, -1], e2c))
            y2, r2 = solve(D2, mv(Bs[2, 1], e1))
            ym2, rm2 = solve(Dm2, mv(Bs[-2, -1], e2c))
            f1 = mv(Bs[1, 1], e1) - mv(Bs[1, 0], y01) - mv(Bs[1, 2], y2)
            c12 = mv(Bs[1, -1], e2c) - mv(Bs[1, 0], y0m)
            fm = mv(Bs[-1, -1], e2c) - mv(Bs[-1, 0], y0m) - mv(Bs[-1, -2], ym2)
            c21 = mv(Bs[-1, 1], e1) - mv(Bs[-1, 0], y01)
            S1 = np.real(np.einsum("ni,ni->n", e1.conj(), f1))
            S2 = np.real(np.einsum("ni,ni->n", e2c.conj(), fm))
            C12 = np.einsum("ni,ni->n", e1.conj(), c12)
            C21 = np.einsum("ni,ni->n", e2c.conj(), c21)
            kk = C12 * C21 / (4 * w1 * w2)
            delta = w1 + S1 / (2 * w1) + w2 + S2 / (2 * w2) - 2 * Omega
            disc = delta**2 / 4 - kk
            sig = np.abs(np.imag(np.sqrt(disc + 0j)))
            # a pair at the edge of its band: the discriminant is round-off, not growth
            sig[np.abs(disc) <= FLOOR * np.maximum(np.abs(kk), delta**2 / 4)] = 0.0
            size = np.max([np.sqrt(np.abs(_energy(Kd[l], m, y, f)) / (w1**2 + w2**2))
                           for l, y, f in ((0, y01, t1 - Omega), (0, y0m, t1 - Omega),
                                           (2, y2, t1 - Omega + 2 * w), (-2, ym2, t2 - Omega + 2 * w))],
                           axis=0)
            resonant = r0 | r2 | rm2 | (size > DRIVEN_MAX)
            # a zero-frequency wave (a uniform translation, kappa = 0) is no wave
            still = ~(np.minimum(w1, w2) > 1e-9 * max(car.omega, 1e-300))
            rate[:, j] = np.where(resonant | still | ~np.isfinite(sig), np.nan, sig)
            det[:, j] = delta
            coup[:, j] = np.sqrt(np.abs(kk))
    return rate, det, coup


def _energy(K, m, y, phi):
    return (np.einsum("ni,nij,nj->n", y.conj(), K, y)
            + phi**2 * np.einsum("ni,i,ni->n", y.conj(), m, y)).real
