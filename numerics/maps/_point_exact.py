"""A point's exact rows resolved: the paper-start curve's offsets (a coarse zone grid plus a
window around the peak the bands' resonance conditions locate) and the zoom on an exact
curve's band (``refine_band``: its peak, the fastest pair a ring carries, its half-gain
edge), for ``_point.theory_curves``."""

from __future__ import annotations

import math

import numpy as np

from ..theory import resonance_map

#: points of the paper-start exact curve (Hill's method on the torus: ~0.13 s per offset):
#: this many over the zone, and as many again around the peak resonance_map locates
START_CURVE_POINTS = 24
#: rounds of zooming on an exact curve's peak (refine_band): the bracket shrinks ~4.5x a
#: round, from the grid's spacing to ~1e-4 rad after 4, where a 0.014 rad wide band's peak
#: is within 1e-4 of its top
REFINE_ROUNDS = 4


def _start_grid(material, case, k, amplitude):
    """q of the paper-start curve: a coarse zone grid plus a dense window around the peak
    that ``resonance_map`` finds from the bands' resonance conditions (a coarse grid alone
    misses bands narrower than its spacing)."""
    res = resonance_map(k, case=case, material=material, K_theta=material.K_theta,
                        amplitude=amplitude, start="paper")
    qp = abs(float(res["q_peak"]))
    Q = [np.linspace(0.02, math.pi, START_CURVE_POINTS)]
    if math.isfinite(qp) and qp != 0:
        Q.append(qp * np.linspace(0.0, 2.5, 2 * START_CURVE_POINTS + 1))
        Q.append([qp])
    Q = np.unique(np.concatenate(Q))
    return Q[(Q > 1e-6) & (Q <= math.pi)]


def refine_band(gain, Q, curve, N: int | None = None, rounds: int = REFINE_ROUNDS,
                points: int = 8, most: int = 64):
    """(Q, curve, ring_peak): the curve with its band's peak and outer half-gain edge
    resolved. A band narrower than the grid's spacing (a resonant pair far from the
    carrier: 0.014 rad wide at q - k = 1.33 where the paper-start grid steps 0.047) read
    its peak 1.3% low at a grid value and its edge outside the band.

    ``gain(offsets)`` evaluates the curve. With ``N`` (a ring of N sites) the offsets
    2 pi j / N inside the peak's band are evaluated (at most ``most``, nearest the peak
    first) and ``ring_peak`` is (gain, offset) of the best: what a run on that ring can
    show, not a spike narrower than its spacing (the README point's 1e-3 rad wide spike
    1% above its band) nor an offset below 2 pi / N. Without ``N`` (``ring_peak`` None),
    ``rounds`` zooms of ``points`` offsets between the best value's two neighbours (the
    bracket shrinks ~4.5x a round). Then the outer half-gain crossing of the curve is
    bisected (band_summary's level)."""
    Q, curve = np.asarray(Q, float), np.asarray(curve, float)

    def merge(Q, curve, x):
        x = np.setdiff1d(np.asarray(x, float), Q)
        if x.size == 0:
            return Q, curve
        order = np.argsort(np.concatenate([Q, x]), kind="stable")
        return (np.concatenate([Q, x])[order],
                np.concatenate([curve, np.asarray(gain(x), float).ravel()])[order])

    if not (curve.size > 2 and np.all(np.isfinite(curve)) and curve.max() > 0):
        return Q, curve, None
    ring_peak = None
    j = int(np.argmax(curve))
    if N is not None:
        # the peak's band: the run of positive values around it, out to the zero beyond
        pos = curve > 0
        lo = j - int(np.argmin(pos[j::-1])) if not pos[:j + 1].all() else 0
        hi = j + int(np.argmin(pos[j:])) if not pos[j:].all() else Q.size - 1
        ring = 2 * math.pi * np.arange(1, N // 2 + 1) / N
        ring = ring[(ring > Q[lo]) & (ring < Q[hi])]
        ring = ring[np.argsort(np.abs(ring - Q[j]))][:most]
        Q, curve = merge(Q, curve, ring)
        if ring.size:
            at = curve[np.searchsorted(Q, ring)]
            ring_peak = (float(at.max()), float(ring[np.argmax(at)]))
    else:
        for _ in range(rounds):
            j = int(np.argmax(curve))
            lo, hi = Q[max(j - 1, 0)], Q[min(j + 1, Q.size - 1)]
            Q, curve = merge(Q, curve, np.linspace(lo, hi, points + 2)[1:-1])
    j = int(np.argmax(curve))
    level = 0.5 * curve[j]
    below = np.flatnonzero(curve[j:] < level)
    if below.size:
        a, b = Q[j + below[0] - 1], Q[j + below[0]]
        for _ in range(2 * rounds):
            mid = 0.5 * (a + b)
            Q, curve = merge(Q, curve, [mid])
            a, b = (mid, b) if curve[np.searchsorted(Q, mid)] >= level else (a, mid)
    return Q, curve, ring_peak
