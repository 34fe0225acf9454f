"""Three-wave decays of a plane wave, which the four-wave theory (``_fourwave``) does not
rate: where its energy has cubic terms, the carrier (k, Omega) can decay into two linear
waves (k + q, b1) and (-q, b3) whose frequencies sum to Omega, at a rate of order a (the
four-wave pairs grow at a^2). Issue 94's probe found them: a rotor chain with a cubic
cross term grew at 0.043 /time (exact theory and a run) where the four-wave theory said
stable, an unequal-mass chain's optical carrier at 0.0084 where it named a backward pair
at 0.00068.

In Hill's frame (``_fourwave``'s docstring) the decay is the pair of harmonics l = 1 (the
wave (k + q, omega1)) and l = 0 (the conjugate of (-q, omega3)), coupled at first order
through the Hessian's harmonic Hhat_{+-1} = T(x1); as for a four-wave pair,

    sigma = Im sqrt((Delta/2)^2 - kappa13 kappa31),   kappa_ij = C_ij / (2 omega_i),
    C13 = e1^H B_{1,0} e3,   C31 = e3^H B_{0,1} e1,   Delta = omega1 + omega3 - omega,

e3 the branch-b3 mode of K(q) (e^H M e = 1), omega the carrier's linear frequency (the
order a theory's; a decay must survive its detuning moved by the O(a^2) shift Omega - omega). Measured against the exact theory: 0.0435
against 0.0431 (the rotor chain, k 1.52, a 0.082), 0.00841 against 0.00844 (the optical
carrier, k 1.69, a 0.066).

The two-harmonic truncation holds for an isolated triad only: near the carrier (q -> 0,
the acoustic l = 0 wave is the mean flow) the l = -1 wave (k - q) is as resonant (with
wave 1 the long wave, the l = 2 one), and the four-wave theory's Schur complement treats
them all (FPUT alpha 0.5 at k = pi/2, a 0.1: a "decay" into 0.098 and 1.473, a sideband
pair and its mean flow, would read 0.0105 against the exact 0.0087). A decay counts
where the harmonics l = -2, -1, 2, 3 (wavenumber q + l k, frequency (l - 1) Omega +
omega1) are detuned from every branch, and both waves' frequencies exceed, ``ISOLATED``
times its coupling or its own detuning, whichever is larger (a cubic-quartic bond at k 1.52, a 0.15, with its frequency shifted
by 8%: a "decay" into a long wave at -0.098 (frequency 0.098, coupling 0.07) and a wave
at 1.62 would read 0.065 against the exact 0.011).
"""

from __future__ import annotations

import numpy as np

from energy import Model

#: a triad with another harmonic closer to a branch than this many couplings
#: sqrt|kappa13 kappa31| is not isolated: the four-wave theory's
ISOLATED = 4.0


def decay_rates(model: Model, k: float, wave, offsets, *, margin: bool = False,
                isolated_only: bool = True) -> tuple[np.ndarray, np.ndarray]:
    """Every isolated three-wave decay's rate at the offsets q (any sign, rad/site).

    Parameters
    ----------
    model : Model
    k : float
        The carrier's wavenumber.
    wave : tuple
        ``_fourwave_kernel._plane_wave``'s (carrier, Omega, x1, x2, x0).
    offsets : array_like, shape (n,)
    margin : bool
        Also the decays that the carrier's own shift |Omega - omega| could bring into
        resonance (their detuning less that shift beaten by the coupling): the rate they
        would have at resonance, sqrt(kappa13 kappa31 - (max(|Delta| - shift, 0)/2)^2).
        Probe 96: opt (mass-in-mass, tests/test_fourwave96.py) at k pi/2 decays at 6.3e-3
        (exact) into waves each moved up by the carrier (0.03, 0.02): linearly detuned
        by -0.013, resonant once the daughters' and the carrier's shifts are counted.
    isolated_only : bool
        False: the triads that grow but are not isolated too (another harmonic near a
        branch), at the two-wave reduction's rate: an estimate of a process neither this
        truncation nor the four-wave ordering treats (``four_wave``'s note).

    Returns
    -------
    rates : ndarray, shape (n, d, d)
        sigma of the decay into (k + q, b1) and (-q, b3), [:, b1, b3]; 0 where it does
        not grow or is not isolated.
    detuning : ndarray, shape (n, d, d)
        Delta = omega1 + omega3 - omega (nan where a wave has zero frequency).
    """
    car, Omega, x1, _, _ = wave
    H, T, _ = model.code.taylor(model.p)
    d = model.n_fields
    m = np.asarray(model.masses, float)
    s = 1 / np.sqrt(m)
    q = np.atleast_1d(np.asarray(offsets, dtype=float))
    eye = np.eye(d)
    Hh1 = np.einsum("ijm,m->ij", T, x1)

    def P(kap):  # (n, d, 2d)
        return np.concatenate([np.broadcast_to(eye, (kap.size, d, d)),
                               eye * np.exp(-1j * kap)[:, None, None]], axis=2)

    def X(kap):  # (n, 2d, d)
        return np.concatenate([np.broadcast_to(eye, (kap.size, d, d)),
                               eye * np.exp(1j * kap)[:, None, None]], axis=1)

    def modes(kap):
        z = np.exp(1j * kap)[:, None, None]
        K = (H[:d, :d] + H[d:, d:]) + H[:d, d:] * z + H[d:, :d] / z
        lam, phi = np.linalg.eigh(s[None, :, None] * K * s[None, None, :])
        return np.sqrt(np.maximum(lam, 0.0)), s[None, :, None] * phi

    w1, E1 = modes(k + q)
    w3, E3 = modes(q)
    # C13[n, b1, b3] = e1^H B10 e3, C31[n, b1, b3] = e3^H B01 e1
    B10 = P(k + q) @ Hh1 @ X(q)
    B01 = P(q) @ Hh1.conj() @ X(k + q)
    C13 = np.einsum("nib,nij,njc->nbc", E1.conj(), B10, E3)
    C31 = np.einsum("nic,nij,njb->nbc", E3.conj(), B01, E1)
    with np.errstate(invalid="ignore", divide="ignore", over="ignore"):
        W1, W3 = w1[:, :, None], w3[:, None, :]
        live = (W1 > 1e-9 * car.omega) & (W3 > 1e-9 * car.omega)
        kk = np.where(live, C13 * C31 / (4 * W1 * W3), 0.0)
        delta = np.where(live, W1 + W3 - car.omega, np.nan)
        sig = np.abs(np.imag(np.sqrt(delta**2 / 4 - kk + 0j)))
        # a decay the next order can detune away is none: it must grow with its detuning
        # moved by the carrier's own frequency shift |Omega - omega| (O(a^2)). FPUT alpha 1
        # at k = pi/2, a 0.1 (a concave branch: no linear triad) would read 8e-4 at its
        # band's edge, 0.49 and 1.08; the diatomic chain at k 1.64, a 0.09, 1e-4 for a
        # long wave at 0.001 (the mean flow)
        shift = abs(Omega - car.omega)
        near = np.maximum(np.abs(delta) - shift, 0.0) if margin else np.abs(delta) + shift
        robust = near**2 / 4 < np.real(kk)
        if margin:
            sig = np.sqrt(np.maximum(np.real(kk) - near**2 / 4, 0.0))
        # the other harmonics l (wavenumber q + l k, frequency (l - 1) Omega + omega1):
        # each one's distance from every branch
        apart = np.full(w1.shape, np.inf)
        for l_ in (-2, -1, 2, 3):
            wl, _ = modes(q + l_ * k)
            gap = np.abs(wl[:, None, :] - np.abs((l_ - 1) * Omega + w1[:, :, None]))
            apart = np.minimum(apart, np.min(gap, axis=2))
        # and each wave's own frequency: the resonant truncation averages the rest out
        # over periods short against the decay (a long acoustic wave is the mean flow)
        apart = np.minimum(apart[:, :, None], np.minimum(W1, W3))
        # (the triad's own detuning too: in the long-wave limit every harmonic is about as
        # near a branch as the triad is, and they all share the energy; Toda at k 0.56,
        # a 0.053, integrable, would read 1.7e-3 with its l = 2 wave twice as far out)
        isolated = apart > ISOLATED * np.maximum(np.sqrt(np.abs(kk)), np.abs(delta))
    if not isolated_only:
        isolated = True
    rates = np.where(live & isolated & robust & np.isfinite(sig), sig, 0.0)
    return rates, delta


def fastest_decay(model: Model, k: float, wave, offsets, *, refine: bool,
                  margin: bool = False, isolated_only: bool = True) -> tuple | None:
    """The fastest isolated decay over ``offsets`` (``_fastest_decay``)."""
    return _fastest_decay(model, k, wave, offsets, refine, margin, isolated_only)


def _fastest_decay(model, k, wave, offsets, refine, margin, isolated_only=True):
    """The fastest isolated decay over ``offsets`` as (rate, (b1, k1), (b3, k3)), or None
    where none grows. ``refine``: the offsets are a grid of the infinite chain, and the
    detuning's roots between them are added (a decay's band is O(a) wide); False for a
    ring's own offsets. ``margin``: ``decay_rates``'s."""
    q = np.atleast_1d(np.asarray(offsets, dtype=float))
    rates, delta = decay_rates(model, k, wave, q, margin=margin, isolated_only=isolated_only)
    roots = []
    for b1 in range(delta.shape[1]):
        for b3 in range(delta.shape[2]):
            dl = delta[:, b1, b3]
            i = np.flatnonzero(np.isfinite(dl[:-1]) & np.isfinite(dl[1:])
                               & (np.sign(dl[:-1]) * np.sign(dl[1:]) < 0))
            roots.extend(q[i] - dl[i] * (q[i + 1] - q[i]) / (dl[i + 1] - dl[i]))
    if roots and refine:
        q = np.concatenate([q, roots])
        rates = np.concatenate([rates, decay_rates(model, k, wave, np.array(roots),
                                                   margin=margin,
                                                   isolated_only=isolated_only)[0]])
    if not np.max(rates, initial=0.0) > 0:
        return None
    n, b1, b3 = np.unravel_index(int(np.argmax(rates)), rates.shape)
    wrap = lambda x: float((x + np.pi) % (2 * np.pi) - np.pi)  # noqa: E731
    return float(rates[n, b1, b3]), (int(b1), wrap(k + q[n])), (int(b3), wrap(-q[n]))


def fastest_near_decay(model: Model, k: float, wave, offsets, *, refine: bool):
    """``fastest_decay`` of the decays the carrier's own shift could bring into resonance
    too (``decay_rates``' ``margin``): their rate at resonance."""
    return _fastest_decay(model, k, wave, offsets, refine, True)
