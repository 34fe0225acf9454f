"""The samples ``along_decay`` integrates (issue 42): each column's gain at the carrier
amplitudes s = (a / a0)^2 = 1, ratio, ratio^2, ..., and which columns it computes.

A column is computed at a sample only where it grew net of its damping at the one before
(below, it only decays: the maximum over t is reached before). Sampling stops where no
computed column grows at the last sample, or the last three samples of every growing
column lie on a line in s (``linear_tol`` of the largest sigma^2 at s = 1), or at ``most``
samples.

Coarse to fine (``positions``: the exact theory's ring offsets, where a lower amplitude's
Hill spectrum costs per offset, and the damped NLS's offsets): the samples are first
computed on every STRIDE-th column of each run of adjacent offsets (and each run's last),
then on the columns of each interval between two coarse neighbours whose log
amplification can reach the largest found: at most the larger end plus four times the
midpoint error of a smooth profile, |f''| h^2 / 2, f'' the larger of the two ends'
coarse second differences (divided). A mode switching along q makes a convex kink (the
gain is a maximum over modes): it hides no peak, and its large second difference only
refines its neighbours. Measured: no miss on 3000 random profiles (sums of bumps >= 3
columns wide), 10% of the in-between columns refined (tests/test_dissipation.py). The
answer (amplification, time, offset) is the every-column one, to the bit, whenever its
column is computed (at 11 points of fput, Klein-Gordon and flexmm-lossy; where two
offsets tie to round-off, 1e-15, either may be named); the refined columns take part in
the stop rule, so sampling goes on where they still grow or curve (the samples stop at
or before the every-column ones, and only where every computed column lies on a line).
"""

from __future__ import annotations

import functools
import math

import numpy as np

from common.threads import one_blas_thread

#: the coarse columns' spacing (every STRIDE-th column of a run of adjacent offsets)
STRIDE = 3


class Samples:
    """The samples of ``along_decay``: ``s`` (descending from 1) and ``g`` (one row of
    rates per sample over every column, 0 where not computed), ``done`` the columns whose
    samples are complete."""

    def __init__(self, gain_at, a0, gain0, G, ratio, most, linear_tol):
        self.gain_at, self.a0, self.G = gain_at, a0, G
        self.ratio, self.most, self.linear_tol = ratio, most, linear_tol
        self.s = [1.0]
        self.g = [np.asarray(gain0, float)]
        self.top2 = float(np.max(self.g[0] ** 2)) if self.g[0].size else 0.0
        self.done = np.zeros(self.g[0].size, bool)

    def _compute(self, i, cols):
        if cols.size:
            self.g[i][cols] = np.asarray(self.gain_at(self.a0 * math.sqrt(self.s[i]), cols),
                                         float)

    def complete(self, cols) -> None:
        """Bring ``cols`` up to date on the samples taken, in order, then sample on while
        the stop rule over every complete column says so."""
        cols = np.asarray(cols, int)
        cols = cols[~self.done[cols]]
        for i in range(1, len(self.s)):
            self._compute(i, cols[self.g[i - 1][cols] > self.G[cols]])
        self.done[cols] = True
        while not self._stopped():
            s = self.s[-1] * self.ratio
            grew = np.flatnonzero(self.done & (self.g[-1] > self.G))
            self.s.append(s)
            self.g.append(np.zeros_like(self.g[0]))
            self._compute(len(self.s) - 1, grew)

    def _stopped(self) -> bool:
        if len(self.s) == 1:
            return self.most <= 1
        if len(self.s) >= self.most:
            return True
        live = self.done & (self.g[-1] > self.G)
        if not live.any():
            return True
        if self.linear_tol is not None and len(self.s) >= 3:
            (s1, s2, s3), (y1, y2, y3) = self.s[-3:], [g**2 for g in self.g[-3:]]
            line = y1 + (y3 - y1) * (s2 - s1) / (s3 - s1)
            return bool(np.all(np.abs(line - y2)[live] <= self.linear_tol * self.top2))
        return False

    def arrays(self, cols):
        """(s ascending, sigma^2 of ``cols`` per sample (samples, len(cols)))."""
        order = np.argsort(self.s, kind="stable")
        return (np.asarray(self.s)[order], np.array([self.g[i][cols] ** 2 for i in order]))


def coarse_columns(positions: np.ndarray, stride: int = STRIDE) -> np.ndarray:
    """Every ``stride``-th column of each run of adjacent ``positions`` (ascending
    integers) from its first, and each run's last: the indices of the coarse columns."""
    n = positions.size
    if n <= 8 * stride:  # few columns: the second call costs more than it saves
        return np.arange(n)
    start = np.r_[True, np.diff(positions) != 1]
    run_start = np.maximum.accumulate(np.where(start, np.arange(n), 0))
    end = np.r_[start[1:], True]
    return np.flatnonzero(((np.arange(n) - run_start) % stride == 0) | end)


def refine_columns(positions: np.ndarray, coarse: np.ndarray, log_amp: np.ndarray):
    """The in-between columns whose log amplification may reach the coarse columns'
    largest (module docstring): those of each interval between two coarse neighbours
    where the larger end plus the slack reaches it; ``log_amp`` the coarse columns' (same
    order as ``coarse``)."""
    if coarse.size == positions.size:
        return np.zeros(0, int)
    x = positions[coarse].astype(float)
    y = np.asarray(log_amp, float)
    best = float(np.max(y))
    # |f''| at each coarse column from its coarse neighbours in the same run (0 at ends)
    curv = np.zeros(x.size)
    same = np.diff(coarse) == np.diff(positions[coarse])  # no gap between: one run
    if x.size >= 3:
        slope = np.diff(y) / np.diff(x)
        inner = same[:-1] & same[1:]
        curv[1:-1] = np.where(inner, np.abs(2 * np.diff(slope) / (x[2:] - x[:-2])), 0.0)
    i = np.flatnonzero(same & (np.diff(coarse) > 1))  # the intervals with columns inside
    h = x[i + 1] - x[i]
    slack = np.maximum(curv[i], curv[i + 1]) * h * h / 2
    hit = i[np.maximum(y[i], y[i + 1]) + slack >= best]
    if not hit.size:
        return np.zeros(0, int)
    return np.concatenate([np.arange(coarse[j] + 1, coarse[j + 1]) for j in hit])


@functools.lru_cache(maxsize=16)
def _contiguous(n: int, stride: int):
    """(arange(n), its ``coarse_columns``), read only: the damped NLS's offsets are one
    run of n, the same every call."""
    where = np.arange(n)
    coarse = coarse_columns(where, stride)
    where.flags.writeable = coarse.flags.writeable = False
    return where, coarse


def nls_first_max(P, Q, psi0, Gamma, G, q, t_end, steps):
    """(i, j, value) of the first largest of ``integrate_pairs``' array in row-major order
    (``_first_max``), its offsets coarse to fine (``_losses_sampling``: every eighth, then
    those between whose log amplification may reach the largest; the NLS's is smooth in
    q, one band): the same numbers wherever the largest's offset is computed."""
    from ._losses import NLS_STRIDE
    from ._losses_nls import _pairs_best, _pairs_later

    top, first = np.ones(q.size), np.zeros(q.size, np.int64)
    done = np.zeros(q.size, bool)
    times = _pairs_later(psi0, Gamma, t_end, steps)  # the same for every offset

    def run(cols):
        top[cols], first[cols] = _pairs_best(P, Q, psi0, Gamma, G[cols], q[cols], t_end,
                                             steps, times)
        done[cols] = True

    where, coarse = _contiguous(q.size, NLS_STRIDE)
    run(coarse)
    run(refine_columns(where, coarse, np.log(top[coarse])))
    cols = np.flatnonzero(done)
    ties = cols[top[cols] == top[cols].max()]
    i = int(first[ties].min())
    return i, int(ties[first[ties] == i].min()), float(top[ties[0]])


@one_blas_thread
def exact_along_decay(first, model, c, qk, positions, amplitude, gain0, G, Gamma, ratio,
                      most):
    """``along_decay`` of the exact theory's live ring offsets ``qk`` (ring indices
    ``positions``: coarse to fine): at each lower amplitude one travelling wave (its
    harmonic balance started from the last, scaled) and one Hill engine (the Hessian's
    harmonics once), asked for the coarse columns, then for the refined ones.

    The truncation: where the full amplitude's fastest mode persisted at P + 4
    (``first.truncations``, ``exact_gain``'s check), each lower amplitude's spectrum is
    taken at P unchecked: a weaker wave's Hessian harmonics fall as a^|s|, so its modes
    are resolved at least as well (and each mode still passes the weight rule, < 1e-6 of
    it in the outer three harmonics). Else as ``hill_spectrum``: the P + 4 check at the
    fastest offset asked (again in a later call only where it holds a faster one), the
    dense spectrum at H + 4 where it fails."""
    from ._exact import _Sidebands, continued_wave, hill_spectrum
    from ._linear import field_of
    from ._losses import along_decay

    persisted = len(first.truncations) == 2
    waves = [first.wave]
    at = {}  # a -> [engine, its first call's top gain, dense]
    fast = {}  # the wave solve's set-up, once for every amplitude (``continued_wave``)
    if field_of(model, c.e) == c.field:
        # ``carrier(model, c.k, c.branch)`` is c itself (the same eigenproblem; the
        # field, the only thing a branch given by field name could change, the same)
        fast["car"] = c

    def gain_at(a, cols):
        q = qk[cols]
        if a not in at:
            # the amplitudes fall in turn: each wave's harmonic balance starts from the last
            waves.append(continued_wave(model, c, a, waves[-1], fast))
            engine = _Sidebands(waves[-1])
            spec = engine.spectrum(q, gains_only=True) if persisted else engine.checked(q)
            at[a] = [engine, spec.peak_gain, len(spec.truncations) == 1 and not persisted]
            return spec.gain
        engine, top, dense = at[a]
        if dense:
            return hill_spectrum(engine.wave, q, harmonics=engine.wave.harmonics + 4).gain
        spec = engine.spectrum(q, gains_only=persisted)
        if not persisted and spec.peak_gain > top:  # a faster offset: checked here
            spec = engine.checked(q)
            at[a][1] = spec.peak_gain
        return spec.gain

    return along_decay(gain_at, amplitude, gain0, G, Gamma, ratio=ratio, most=most,
                       positions=positions)
