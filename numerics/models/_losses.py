"""Losses (issue 42): the sidebands' amplification along a decaying carrier.

With a Rayleigh dissipation the carrier decays, a(t) = a0 exp(-Gamma t) (Gamma its
branch's damping rate), and growth is transient: a theory reports the largest
amplification of a sideband over offsets and times, when it peaks, and whether it passes
the runs' 20x (``observable``). The verdict stays physical: MI where the gain at t = 0
exceeds the sidebands' own damping.

Semi-discrete NLS with its loss term, i psi_t + P psi_xx + Q |psi|^2 psi + i Gamma psi = 0
(P = g1/2, Q = g2, psi0 = a/2 in lattice units, ``_nls``). Linearised about the carrier
psi0(t) e^{i theta(t)} with b = (x + i y) cos(q X), each offset q obeys the 2 x 2 system

    x' = -G_q x + P q^2 y,   y' = (2 Q psi0(t)^2 - P q^2) x - G_q y,

G_q the sidebands' own damping (the mean of Gamma_b(k + q) and Gamma_b(k - q)). It is
integrated with exact exponentials of the matrix at each step's midpoint (order 2), from
the growing eigenvector at t = 0; the amplification is |(x, y)(t)| / |(x, y)(0)|.

Exact lattice theory along the decaying carrier: the Hill gain sigma(q, a) of the exact
travelling wave (``exact_gain``, a black box) on a grid of amplitudes a(t), minus G_q,
integrated in time per ring offset: amplification = max over q and t of
exp(int_0^t (sigma(q, a(s)) - G_q) ds).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from energy import Model

#: amplification a theory calls observable (the runs' threshold)
OBSERVABLE = 20.0


@dataclass(frozen=True)
class Amplified:
    """A theory's answer with losses: ``carrier_damping`` (Gamma, 1/time),
    ``amplification`` (max over offsets and times), ``amplification_time``,
    ``offset`` (rad/site) of the mode that reaches it, ``observable``
    (amplification >= 20), ``initial_gain`` (the net rate at t = 0: gain minus damping)."""

    carrier_damping: float
    amplification: float
    amplification_time: float
    offset: float
    observable: bool
    initial_gain: float

    def row(self) -> dict:
        return {"carrier_damping": self.carrier_damping, "amplification": self.amplification,
                "amplification_time": self.amplification_time,
                "observable": self.observable}


def sideband_damping(model: Model, k: float, q, branch: int) -> np.ndarray:
    """G_q: the mean amplitude decay rate of the sidebands k + q and k - q on the branch."""
    from ._linear import damping_rates

    q = np.atleast_1d(np.asarray(q, float))
    return 0.5 * (damping_rates(model, k + q)[:, branch] + damping_rates(model, k - q)[:, branch])


def _pair_step(P, q2, c, G, h):
    """exp(h [[-G, P q2], [c, -G]]) for arrays of offsets: e^{-G h} [[ch, b sh/l],
    [c sh/l, ch]], l = sqrt(b c)."""
    b = P * q2
    lam = np.sqrt((b * c).astype(complex))
    lh = lam * h
    ch = np.cosh(lh)
    shl = np.where(np.abs(lh) > 1e-12, np.sinh(lh) / np.where(lam == 0, 1, lam), h)
    e = np.exp(-G * h)
    return (e * np.real(ch), e * np.real(b * shl), e * np.real(c * shl), e * np.real(ch))


def integrate_pairs(P, Q, psi0, Gamma, G, q, t_end, steps=4000, carrier_decays=True):
    """|(x, y)(t)| / |(x, y)(0)| of the linearised damped NLS per offset q: array
    (steps + 1, len(q)), and the times. The carrier psi0 e^{-Gamma t} (constant where
    ``carrier_decays`` is False); start on the growing eigenvector at t = 0."""
    q = np.atleast_1d(np.asarray(q, float))
    G = np.broadcast_to(np.asarray(G, float), q.shape)
    q2 = q * q
    b = P * q2
    c0 = 2 * Q * psi0**2 - P * q2
    s0 = np.sqrt(np.maximum(b * c0, 0.0))
    # growing eigenvector of [[0, b], [c0, 0]]: (b, s0) (normalised); neutral: (1, 0)
    x = np.where(s0 > 0, b, 1.0)
    y = np.where(s0 > 0, s0, 0.0)
    n0 = np.hypot(x, y)
    x, y = x / n0, y / n0
    h = t_end / steps
    t = np.linspace(0.0, t_end, steps + 1)
    out = np.empty((steps + 1, q.size))
    out[0] = 1.0
    for i in range(steps):
        tm = (i + 0.5) * h
        a2 = psi0**2 * (math.exp(-2 * Gamma * tm) if carrier_decays else 1.0)
        m11, m12, m21, m22 = _pair_step(P, q2, 2 * Q * a2 - P * q2, G, h)
        x, y = m11 * x + m12 * y, m21 * x + m22 * y
        out[i + 1] = np.hypot(x, y)
    return out, t


def _horizon(rate0: float, Gamma: float) -> float:
    """How long to follow a decaying carrier: its gain ~ a^2 falls below the damping at
    ln(rate0 / Gamma) / (2 Gamma); beyond it nothing grows. Twice that, and 3 / Gamma."""
    if Gamma <= 0:
        return math.inf
    return 2 * max(math.log(max(rate0, Gamma) / Gamma), 0.0) / (2 * Gamma) + 3 / Gamma


def nls_amplification(model: Model, k: float, amplitude: float, branch=None, *,
                      offsets: int = 200, steps: int = 4000) -> Amplified:
    """The damped semi-discrete NLS's amplification (module docstring)."""
    from ._linear import carrier_damping
    from ._nls import nls

    r = nls(model, k, branch)
    c = r.carrier
    Gamma = carrier_damping(model, c.k, c.branch)
    P, Q = c.g1 / 2, r.g2
    psi0 = amplitude / 2
    if r.undefined or not (np.isfinite(Q) and P * Q > 0):  # defocusing: no band
        q = np.array([1e-3])
        return Amplified(Gamma, 1.0, 0.0, math.nan, False, -float(
            sideband_damping(model, c.k, q, c.branch)[0]))
    edge = math.sqrt(2 * Q / P) * psi0  # band edge of the carrier at t = 0
    q = np.linspace(edge / offsets, edge, offsets, endpoint=False)
    G = sideband_damping(model, c.k, q, c.branch)
    rate0 = abs(P) * q * np.sqrt(np.maximum(q**2 * 0 + (2 * Q / P) * psi0**2 - q**2, 0))
    t_end = _horizon(float(np.max(rate0)), Gamma)
    if not math.isfinite(t_end):
        raise ValueError("the NLS's amplification needs losses (Gamma > 0)")
    amp, t = integrate_pairs(P, Q, psi0, Gamma, G, q, t_end, steps)
    i, j = np.unravel_index(int(np.argmax(amp)), amp.shape)
    best = float(amp[i, j])
    return Amplified(Gamma, best, float(t[i]), float(q[j]), best >= OBSERVABLE,
                     float(np.max(rate0 - G)))


def exact_amplification(model: Model, k: float, amplitude: float, branch=None, *,
                        N: int = 256, amplitudes: int = 24) -> Amplified:
    """The exact lattice theory along the decaying carrier (module docstring): the Hill
    gain on a ring of N sites at ``amplitudes`` carrier amplitudes a0 e^{-Gamma t}."""
    from ._exact import exact_gain
    from ._linear import carrier_damping

    first = exact_gain(model, k, amplitude, branch, N=N)
    c = first.wave.carrier
    Gamma = carrier_damping(model, c.k, c.branch)
    q = np.asarray(first.offsets, float)
    G = sideband_damping(model, c.k, q, c.branch)
    net0 = np.asarray(first.gain, float) - G
    t_end = _horizon(max(first.peak_gain, 0.0), Gamma)
    if first.peak_gain <= 0 or float(np.max(net0)) <= 0:
        return Amplified(Gamma, 1.0, 0.0, math.nan, False, float(np.max(net0)))
    t = np.linspace(0.0, t_end, amplitudes)
    gains = [np.asarray(first.gain, float)]
    for ti in t[1:]:
        gains.append(np.asarray(exact_gain(model, k, amplitude * math.exp(-Gamma * ti),
                                           branch, N=N).gain, float))
    net = np.array(gains) - G[None, :]
    # trapezoids of the net rate, on a finer grid (linear between the amplitudes)
    fine = np.linspace(0.0, t_end, 20 * amplitudes)
    rate = np.array([np.interp(fine, t, net[:, j]) for j in range(q.size)]).T
    log_amp = np.concatenate([np.zeros((1, q.size)), np.cumsum(
        np.diff(fine)[:, None] * (rate[1:] + rate[:-1]) / 2, axis=0)])
    i, j = np.unravel_index(int(np.argmax(log_amp)), log_amp.shape)
    best = float(math.exp(min(log_amp[i, j], 700.0)))
    return Amplified(Gamma, best, float(fine[i]), float(q[j]), best >= OBSERVABLE,
                     float(np.max(net0)))
