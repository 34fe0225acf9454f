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
the growing eigenvector at t = 0; the amplification is |(x, y)(t)| / |(x, y)(0)|
(``_losses_nls``).

Exact lattice theory along the decaying carrier: the Hill gain sigma(q, a) of the exact
travelling wave (``exact_gain``, a black box) at a few amplitudes (``along_decay``:
s = (a/a0)^2 halved until nothing grows, sigma^2 piecewise linear in s), minus G_q,
the damping of the offset's growing mode at t = 0 from the damped Hill pencil (every
harmonic damped at its own wavenumber, ``_losses_hill``; probe 102: k +- q was a pair's
waves only at the offset where it is centred at l = +-1), integrated in time per ring
offset: amplification = max over q and t of
exp(int_0^t (sigma(q, a(s)) - G_q) ds). The lower amplitudes' spectra are computed coarse
to fine over the offsets (``_losses_sampling``). The four-wave theory the same way, per
pair, its rates at the lower amplitudes in closed form (``_losses_fourwave``: the kernel
is a polynomial in a^2). The damping rates kept per wavenumber: ``_losses_rates``.

The lossless limit (Gamma = 0): the carrier keeps its amplitude and a growing mode grows
without end: amplification inf at time inf, observable where MI (``_unbounded``).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from energy import Model, ModelError

from ._losses_nls import (  # noqa: F401  (re-exported: the pair integrator's tests)
    _first_max,
    _pairs_best,
    _pairs_later,
    integrate_pairs,
)
from ._losses_rates import (
    _carrier_damping,
    _sampling,
    overdamped_answer,
    rates_once,
    side_rates,
    sideband_damping,
)

#: amplification a theory calls observable (the runs' threshold)
OBSERVABLE = 20.0
#: the damped NLS's coarse offsets: every NLS_STRIDE-th of its 200 (one band, its
#: amplification smooth in q)
NLS_STRIDE = 8


@dataclass(frozen=True)
class Amplified:
    """A theory's answer with losses: ``carrier_damping`` (Gamma, 1/time),
    ``amplification`` (max over offsets and times), ``amplification_time``,
    ``offset`` (rad/site) of the mode that reaches it, ``observable``
    (amplification >= 20), ``initial_gain`` (the net rate at t = 0: gain minus damping),
    ``overdamped`` (the carrier's root does not oscillate: ``carrier_overdamped``)."""

    carrier_damping: float
    amplification: float
    amplification_time: float
    offset: float
    observable: bool
    initial_gain: float
    overdamped: bool = False

    def row(self) -> dict:
        return {"carrier_damping": self.carrier_damping, "amplification": self.amplification,
                "amplification_time": self.amplification_time,
                "observable": self.observable}

    def damped_verdict(self, verdict: str) -> dict:
        """A theory's ``verdict`` with these losses, the one rule for point, coefficients
        and map cells: {} where it stands; where the lossless chain's MI has no gain that
        beats its damping at t = 0 (the losses win from the start), {"verdict": "stable",
        "lossless_verdict": "MI", "net_gain": ``initial_gain`` (<= 0)}, and
        "carrier_overdamped": True where that is why."""
        if verdict == "MI" and not self.initial_gain > 0:
            return {"verdict": "stable", "lossless_verdict": "MI",
                    "net_gain": self.initial_gain} | (
                        {"carrier_overdamped": True} if self.overdamped else {})
        return {}


#: the words beside a JSON null amplification (inf: the lossless limit)
UNBOUNDED_NOTE = ("unbounded: the carrier is not damped (Gamma = 0), its sidebands grow "
                  "without end")


def amplified_row(verdict: str, f) -> dict:
    """A theory's JSON object's additions with losses (issue 42), as ``point`` and
    ``coefficients`` print them: ``Amplified.row``, its ``damped_verdict`` of ``verdict``
    and an ``amplification_note`` where it is unbounded; where ``f`` (the theory's
    amplification) raises ModelError, None for each number and ``amplification_reason``."""
    try:
        a = f()
    except ModelError as exc:  # no theory with losses here: why, in one sentence
        return {"carrier_damping": None, "amplification": None, "amplification_time": None,
                "observable": None, "amplification_reason": str(exc)}
    out = {**a.row(), **a.damped_verdict(verdict)}
    if a.amplification == math.inf:  # JSON null: said in words
        out["amplification_note"] = UNBOUNDED_NOTE
    return out


def _horizon(rate0: float, Gamma: float) -> float:
    """How long to follow a decaying carrier: its gain ~ a^2 falls below the damping at
    ln(rate0 / Gamma) / (2 Gamma); beyond it nothing grows. Twice that, and 3 / Gamma."""
    if Gamma <= 0:
        return math.inf
    return 2 * max(math.log(max(rate0, Gamma) / Gamma), 0.0) / (2 * Gamma) + 3 / Gamma


def nls_amplification(model: Model, k: float, amplitude: float, branch=None, *,
                      offsets: int = 200, steps: int = 1000, first=None) -> Amplified:
    """The damped semi-discrete NLS's amplification (module docstring). ``first``: the
    point's ``nls(model, k, branch)``, where already computed."""
    from ._linear import check_amplitude
    from ._nls import nls
    from ._simulate import check_count

    # before: offsets = 0 or steps = 0 raised ZeroDivisionError from inside
    amplitude = check_amplitude(amplitude)
    offsets, steps = check_count("offsets", offsets), check_count("steps", steps)
    r = nls(model, k, branch) if first is None else first
    c = r.carrier
    P, Q = c.g1 / 2, r.g2
    psi0 = amplitude / 2
    # the sidebands' rates first: their call holds the carrier's (``side_rates``)
    if r.undefined or not (np.isfinite(Q) and P * Q > 0):  # defocusing: no band
        q = np.array([1e-3])
        G1 = float(sideband_damping(model, c.k, q, c.branch)[0])
        Gamma = max(_carrier_damping(model, c.k, c.branch), 0.0) + 0.0  # -0.0: no damping
        return Amplified(Gamma, 1.0, 0.0, math.nan, False, -G1)
    edge = math.sqrt(2 * Q / P) * psi0  # band edge of the carrier at t = 0
    q = np.linspace(edge / offsets, edge, offsets, endpoint=False)
    # its own offsets, shared with no other theory: one call, not kept (``rates_once``)
    G, Gamma = rates_once(model, c.k, q, c.branch)
    Gamma = max(Gamma, 0.0) + 0.0  # -0.0 at zero damping
    if (over := overdamped_answer(model, c.k, c.branch, Gamma)) is not None:
        return over
    rate0 = abs(P) * q * np.sqrt(np.maximum(q**2 * 0 + (2 * Q / P) * psi0**2 - q**2, 0))
    net0 = float(np.max(rate0 - G))
    if Gamma <= 0:  # the lossless limit: a constant carrier, growth never stops
        return _unbounded(Gamma, net0, float(q[int(np.argmax(rate0 - G))]))
    t_end = _horizon(float(np.max(rate0)), Gamma)
    # 8x the pairs' steps: the time of a peak ~20x the damping time resolved to 0.3%
    far = _nls_adiabatic(P, Q, psi0, Gamma, G, q, t_end, 8 * steps)
    if far is not None:  # beyond the float range: the pairs' product would overflow
        best, t_far, j = far
        return Amplified(Gamma, math.exp(min(best, LOG_CAP)), t_far, float(q[j]), True, net0)
    from ._losses_sampling import nls_first_max

    i, j, best = nls_first_max(P, Q, psi0, Gamma, G, q, t_end, steps)
    t = np.linspace(0.0, t_end, steps + 1)
    return Amplified(Gamma, best, float(t[i]), float(q[j]), best >= OBSERVABLE, net0)


#: the largest log amplification a theory reports: exp(700) ~ 1e304, near the float range
LOG_CAP = 700.0
#: the adiabatic log amplification above which the damped NLS answers from it alone
LOG_FAR = 650.0


def _nls_adiabatic(P, Q, psi0, Gamma, G, q, t_end, steps):
    """(log amplification, its time, its offset index) of the damped NLS where its pairs
    grow past the float range, else None. The adiabatic (WKB) growth, max over q and t of
    int_0^t (sigma_q(a(t')) - G_q) dt', sigma_q^2 = P^2 q^2 (2 Q/P psi0^2 e^{-2 Gamma t'}
    - q^2) (trapezoids on ``steps`` intervals): the pairs' own log amplification to O(1),
    the eigenvector's turning, against a log above ``LOG_FAR``. Skipped (None) where its
    bound int_0^inf |Q| psi0^2 e^{-2 Gamma t} dt stays below: every damping of the tests
    and docs (the pairs' answers unchanged, to the bit). Before, a tiny damping
    (1e-6 .. 1e-9 of FPUT, Klein-Gordon, a mass-in-mass chain) overflowed the pairs'
    product: amplification inf at a time 60x early, or 3.4 (nan compared as smaller)."""
    if abs(Q) * psi0**2 / (2 * Gamma) < LOG_FAR:  # its bound, int |Q| a(t)^2 dt: within
        return None
    t = np.linspace(0.0, t_end, steps + 1)
    s = np.exp(-2 * Gamma * t)[:, None]
    q = np.asarray(q, float)[None, :]
    sig2 = P * P * q * q * (2 * Q / P * psi0**2 * s - q * q)
    rate = np.sqrt(np.maximum(sig2, 0.0)) - np.asarray(G, float)[None, :]
    log = np.concatenate([np.zeros((1, q.size)),
                          np.cumsum((rate[1:] + rate[:-1]) / 2 * np.diff(t)[:, None], axis=0)])
    i, j = np.unravel_index(int(np.argmax(log)), log.shape)
    if not log[i, j] >= LOG_FAR:
        return None
    return float(log[i, j]), float(t[i]), int(j)


def _unbounded(Gamma: float, net0: float, offset: float) -> Amplified:
    """The lossless limit (Gamma = 0: no [dissipation], or zero damping of the carrier):
    the carrier keeps its amplitude, so a mode whose net rate is positive grows without
    end. Convention: amplification inf at time inf, observable True where it grows (MI),
    else amplification 1 at time 0, observable False."""
    if net0 > 0:
        return Amplified(Gamma, math.inf, math.inf, offset, True, net0)
    return Amplified(Gamma, 1.0, 0.0, math.nan, False, net0)


def along_decay(gain_at, a0: float, gain0, G, Gamma: float, *, ratio: float = 0.5,
                most: int = 10, steps: int = 4000, linear_tol: float | None = 1e-3,
                positions=None):
    """(amplification, time, column, samples) of modes whose growth rates at carrier
    amplitude a are ``gain_at(a, cols)`` (an array over the columns ``cols``; ``gain0``
    the rates at a0, every column),
    each damped at its own rate G, along the carrier a(t) = a0 e^{-Gamma t} (Gamma > 0):
    max over columns and t of exp(int_0^t (sigma(a(s)) - G) ds).

    The gain is sampled at few amplitudes, s = (a / a0)^2 = 1, ratio, ratio^2, ... until
    no column grows at the last (or ``most`` samples); sigma^2 is taken piecewise linear
    in s between the samples and, below a column's lowest positive sample (a rate is
    clipped at 0), on the line through its two lowest positive ones (clipped at 0): exact
    for the NLS's gain, sigma^2 = P^2 q^2 (2 Q/P psi0^2 s - q^2), where the gain ~ a^2
    the samples are ~ ln(sigma0 / G) / ln(1 / ratio). Sampling also stops where the last
    three samples of every column still growing lie on a line in s (within ``linear_tol``
    of the largest sigma^2 at s = 1; None: never): below, that line is what a column
    follows. Measured: FPUT with bond damping 4 samples instead of 8, FPUT and
    Klein-Gordon with site damping 4 instead of 5, the paper's blue point 6 (unchanged),
    each the same amplification to the last bit; a synthetic gain with a curvature of
    4e-4 sigma0^2 stops at 3 and lands 2.2% low in log (9 samples: 5.4% high;
    tests/test_dissipation.py).

    ``positions`` (integers, one per column, adjacent where the columns' offsets are):
    the lower amplitudes computed coarse to fine (``_losses_sampling``), the columns
    between the coarse ones only where their amplification may reach the largest; None:
    every column. ``column`` indexes every column either way."""
    from ._losses_sampling import Samples, coarse_columns, refine_columns

    gain0 = np.asarray(gain0, float)
    G = np.broadcast_to(np.asarray(G, float), gain0.shape)
    samples = Samples(gain_at, a0, gain0, G, ratio, most, linear_tol)
    # time: the horizon of the gain at t = 0 against the carrier's damping
    t_end = _horizon(float(np.max(gain0)), Gamma)
    t = np.linspace(0.0, t_end, steps + 1)
    s_t = np.exp(-2 * Gamma * t)
    if positions is None:
        samples.complete(np.arange(gain0.size))
    else:  # coarse to fine (``_losses_sampling``)
        positions = np.asarray(positions, int)
        coarse = coarse_columns(positions)
        samples.complete(coarse)
        if coarse.size < gain0.size:
            s_arr, g2 = samples.arrays(coarse)
            log_amp = _integrate(s_arr, g2, s_t, t, G[coarse], per_column=True)[3]
            samples.complete(refine_columns(positions, coarse, log_amp))
    cols = np.flatnonzero(samples.done)
    s_arr, g2 = samples.arrays(cols)
    best, i, j = _integrate(s_arr, g2, s_t, t, G[cols])
    return math.exp(min(best, LOG_CAP)), float(t[i]), int(cols[j]), len(samples.s)


def _integrate(s_arr, g2, s_t, t, G, per_column=False):
    """(max log amplification, its time index, its column) of the rates
    sqrt(sigma^2) - G along the carrier's s_t (sigma^2 as ``_piecewise``), integrated by
    the trapezoid rule on t: the same arithmetic as ``_piecewise`` and a cumsum over all
    columns at once, compiled, one column at a time (no (times, cols) arrays: ~10x
    faster, the same numbers to the last bit; ties to the first in row-major order, as
    argmax). ``per_column``: also each column's own largest (array, 0 where it never
    grows)."""
    from ._losses_quadrature import quadrature_tables

    G = np.ascontiguousarray(G, float)
    lo, j, lo_j, w, dt, cold, s_hot, ok = quadrature_tables(
        np.ascontiguousarray(s_arr, float), np.ascontiguousarray(g2, float),
        np.ascontiguousarray(s_t, float), np.ascontiguousarray(t, float), G)
    colbest = np.zeros(g2.shape[1])
    best, i, col = _integrate_compiled()(
        np.ascontiguousarray(g2.T), s_arr, s_t, dt, G, lo, j, lo_j, w, colbest, cold, s_hot,
        ok)
    if per_column:
        return float(best), int(i), int(col), colbest
    return float(best), int(i), int(col)


def _calm(s_arr, g2, G, lo):
    """Where a column of ``_integrate`` stops (its rate negative from then on: its log
    amplification only falls, its maximum and the largest's place are final): its sigma^2
    below ``cold`` = G^2 less 1e-12 of the column's scale (the interpolation's round-off)
    at the time, every sample below it cold (``s_hot``: the lowest sample that is not),
    and the line below the lowest positive sample cold at s = 0 (``ok``); sigma^2 is
    linear between those points, so it stays below G^2."""
    n = s_arr.size
    scale = np.maximum(G * G, np.max(g2, axis=0, initial=0.0))
    cold = G * G - 1e-12 * scale
    s_hot = np.min(np.where(g2 > cold[None, :], s_arr[:, None], np.inf), axis=0,
                   initial=np.inf)
    cols = np.arange(g2.shape[1])
    b = np.minimum(lo + 1, n - 1)
    a = np.where(b == lo, np.maximum(lo - 1, 0), lo)
    ds = s_arr[b] - s_arr[a]
    slope = np.where(ds != 0, (g2[b, cols] - g2[a, cols]) / np.where(ds != 0, ds, 1.0), 0.0)
    ok = (g2[b, cols] - slope * s_arr[b] <= cold) & (G > 0)
    return cold, s_hot, ok


_INTEGRATE = []


def _integrate_compiled():
    """The loop of ``_integrate`` (numba, cached on disk)."""
    if not _INTEGRATE:
        import numba

        @numba.njit(cache=True, error_model="numpy", boundscheck=False)
        def integrate(g2t, s_arr, s_t, dt, G, lo, j, lo_j, w, colbest, cold, s_hot, ok):
            n = s_arr.size
            best, bi, bj = 0.0, 0, 0  # row 0: every column at 0
            for c in range(g2t.shape[0]):
                g = g2t[c]
                # below the lowest positive sample: the line through (a, b)
                b_ = min(lo[c] + 1, n - 1)
                a_ = lo[c]
                if b_ == lo[c]:
                    a_ = max(lo[c] - 1, 0)
                ds = s_arr[b_] - s_arr[a_]
                slope = (g[b_] - g[a_]) / ds if ds != 0 else 0.0
                s_lo = s_arr[lo[c]]
                acc = 0.0
                prev = 0.0
                for i in range(s_t.size):
                    if s_t[i] >= s_lo:
                        sig2 = g[lo_j[i]] + w[i] * (g[j[i]] - g[lo_j[i]])
                    else:
                        sig2 = g[b_] + slope * (s_t[i] - s_arr[b_])
                    rate = math.sqrt(max(sig2, 0.0)) - G[c]
                    if i > 0:
                        acc = acc + dt[i - 1] * (rate + prev) / 2
                        if acc > colbest[c]:
                            colbest[c] = acc
                        if acc > best or (acc == best and (i < bi or (i == bi and c < bj))):
                            best, bi, bj = acc, i, c
                    prev = rate
                    if ok[c] and sig2 <= cold[c] and s_t[i] < s_hot[c]:
                        break  # the rate stays negative (``_calm``): nothing more to find
            return best, bi, bj

        _INTEGRATE.append(integrate)
    return _INTEGRATE[0]


def _piecewise(s_arr, g2, s_t):
    """sigma^2 at the carrier's s_t (times,) of every column of the samples g2 (samples,
    cols) at s_arr (ascending, the last 1): linear between the samples; the samples are
    clipped rates (0 where stable), so below a column's lowest positive sample its sigma^2
    follows the line through its two lowest positive ones (through its top two where only
    s = 1 grows). All columns at once; shape (times, cols)."""
    n = s_arr.size
    cols = np.arange(g2.shape[1])
    pos = g2 > 0
    lo = np.where(pos.any(axis=0), np.argmax(pos, axis=0), n - 1)  # lowest positive
    # within the samples: the segment [s_arr[j - 1], s_arr[j]] that holds s_t
    j = np.clip(np.searchsorted(s_arr, s_t), 1, n - 1) if n > 1 else np.zeros(s_t.size, int)
    lo_j = np.maximum(j - 1, 0)
    w = ((s_t - s_arr[lo_j]) / np.where(j != lo_j, s_arr[j] - s_arr[lo_j], 1.0))[:, None]
    inside = g2[lo_j] + w * (g2[j] - g2[lo_j])
    # below: the line through samples (a, b) = (lo, lo + 1), or (lo - 1, lo) at the top
    b = np.minimum(lo + 1, n - 1)
    a = np.where(b == lo, np.maximum(lo - 1, 0), lo)
    b = np.where(b == lo, lo, b)
    ds = s_arr[b] - s_arr[a]
    slope = np.where(ds != 0, (g2[b, cols] - g2[a, cols]) / np.where(ds != 0, ds, 1.0), 0.0)
    below = g2[b, cols][None, :] + slope[None, :] * (s_t[:, None] - s_arr[b][None, :])
    return np.where(s_t[:, None] >= s_arr[lo][None, :], inside, below)


def exact_amplification(model: Model, k: float, amplitude: float, branch=None, *,
                        N: int = 256, first=None, ratio: float = 0.5,
                        most: int = 10) -> Amplified:
    """The exact lattice theory along the decaying carrier (module docstring): the Hill
    gain on a ring of N sites at the carrier amplitudes a0 e^{-Gamma t} (``along_decay``:
    a few amplitudes, the gain interpolated between them), for the offsets that grow net
    of their damping at t = 0, each damped at t = 0 as the damped Hill pencil says (every
    harmonic of the mode at its own wavenumber: ``_losses_hill``), along the decay at
    that rate. ``first``: ``exact_gain`` at a0 on this
    ring, where already computed."""
    from ._exact import exact_gain

    ratio, most = _sampling(ratio, most)
    if first is None:
        first = exact_gain(model, k, amplitude, branch, N=N)
    c = first.wave.carrier
    q = np.asarray(first.offsets, float)
    gain0 = np.asarray(first.gain, float)
    G = sideband_damping(model, c.k, q, c.branch) if model.lossy else np.zeros(q.size)
    Gamma = max(_carrier_damping(model, c.k, c.branch), 0.0) + 0.0  # -0.0 at zero damping
    # an overdamped carrier first, as the NLS's: its modes' damping from the pencil (a
    # relaxation's, huge) would beat every gain, which is not why nothing grows
    if first.peak_gain > 0 and (over := overdamped_answer(model, c.k, c.branch,
                                                          Gamma)) is not None:
        return over
    if model.lossy and (grow := np.flatnonzero(gain0 > 0)).size:
        # a growing mode damped at every wave it holds, from the damped Hill pencil
        # (``_losses_hill``): the sidebands k +- q only where it is centred at l = +-1
        from ._losses_hill import mode_damping

        G[grow] = mode_damping(first, model, grow)
    net0 = gain0 - G
    top = float(np.max(net0)) if q.size else 0.0
    if first.peak_gain <= 0 or top <= 0:
        return Amplified(Gamma, 1.0, 0.0, math.nan, False, top)
    if Gamma <= 0:
        return _unbounded(Gamma, top, float(q[int(np.argmax(net0))]))
    live = np.flatnonzero(net0 > 0)
    qk = q[live]

    from ._losses_sampling import exact_along_decay

    # along the decay each mode keeps its damping at t = 0, but not below 0: a damping
    # that speeds a pumped mode (probe 102: fput, eta 0.02, k 1.52, a 0.3 on 128 sites, a
    # resonance of a long and a short wave at q = 1.914 grows at 0.0236 damped, 0.0089
    # without; the damped ring's monodromy the same) does so only while the carrier
    # pumps, and held as a negative damping it would grow without end as a -> 0
    amp, t, j, _ = exact_along_decay(first, model, c, q[live], live, amplitude,
                                     gain0[live], np.maximum(G[live], 0.0), Gamma, ratio,
                                     most)
    return Amplified(Gamma, amp, t, float(qk[j]), amp >= OBSERVABLE, top)


def four_wave_amplification(model: Model, k: float, amplitude: float, branch=None, *,
                            N: int | None = None, first=None, ratio: float = 0.5,
                            most: int = 10) -> Amplified:
    """The four-wave theory along the decaying carrier: every pair (offset q, branches
    b1, b2) at its rate at a(t), damped at the mean of its two waves' rates
    (Gamma_b1(k + q) + Gamma_b2(k - q)) / 2 (``along_decay``)."""
    from ._fourwave import four_wave
    from ._fourwave_kernel import _kernel

    ratio, most = _sampling(ratio, most)
    if first is None:
        first = four_wave(model, k, amplitude, branch, N=N)
    if first.undefined:  # no rate, no amplification: the reason instead (issue 43)
        raise ModelError(first.undefined)
    if not first.gain > 0:
        Gamma = max(_carrier_damping(model, first.k, first.branch), 0.0) + 0.0
        return Amplified(Gamma, 1.0, 0.0, math.nan, False, 0.0)
    q = np.asarray(first.offsets, float)
    rates0 = np.nan_to_num(np.asarray(first.rates, float), nan=0.0)  # (n, m)
    if model.lossy:  # the sidebands' rates first: their call holds the carrier's
        up, down = side_rates(model, first.k, q)
        G = np.array([0.5 * (up[:, b1] + down[:, b2]) for b1, b2 in first.pairs]).T
    else:
        G = np.zeros_like(rates0)
    Gamma = max(_carrier_damping(model, first.k, first.branch), 0.0) + 0.0  # -0.0 at zero damping
    net0 = rates0 - G
    top = float(np.max(net0))
    col_q = np.repeat(q, rates0.shape[1])
    if top <= 0:
        return Amplified(Gamma, 1.0, 0.0, math.nan, False, top)
    if (over := overdamped_answer(model, first.k, first.branch, Gamma)) is not None:
        return over
    if Gamma <= 0:
        return _unbounded(Gamma, top, float(col_q[int(np.argmax(net0))]))
    live = net0.ravel() > 0
    live_q = np.flatnonzero(live) // rates0.shape[1]  # the offset (row) of each live pair

    from ._losses_fourwave import rates_at

    closed = rates_at(model, first, live_q, np.flatnonzero(live) % rates0.shape[1])

    def gain_at(a, cols):
        if closed is not None:  # the kernel's exact scaling in a^2 (``_losses_fourwave``)
            return closed((a / amplitude) ** 2)[cols]
        # the pairs' rates at a only at the offsets of the columns asked (a rate at q
        # depends on q alone: the same numbers as four_wave's over every offset), at
        # ``first``'s offsets (the infinite chain's refined ones included)
        kernel = _kernel(model, first.k, a, first.branch)
        if isinstance(kernel, str):  # the expansion fails at a: no rate (four_wave's nan)
            return np.zeros(len(cols))
        rows, where = np.unique(live_q[cols], return_inverse=True)
        rates = np.nan_to_num(np.asarray(kernel[0](q[rows])[0], float), nan=0.0)
        return rates.reshape(rows.size, -1)[where, np.flatnonzero(live)[cols]
                                            % rates0.shape[1]]

    amp, t, j, _ = along_decay(gain_at, amplitude, rates0.ravel()[live], G.ravel()[live],
                               Gamma, ratio=ratio, most=most)
    return Amplified(Gamma, amp, t, float(col_q[live][j]), amp >= OBSERVABLE, top)
