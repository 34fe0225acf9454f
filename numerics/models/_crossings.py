"""Narrow bands between the infinite chain's samples: where a pair of the Hill pencil's roots
of opposite Krein signs cross between two offsets that both hold no growing mode.

``exact_gain`` on the infinite chain samples the offsets (400 uniform in [pi / 400, pi] and
40 log-spaced below). A band narrower than a step (pi / 400 = 0.0079) can fall between two
samples: a weakly coupled crossing's four-wave band (probe 96's ``cross`` chain, eps 1e-3,
v carrier at k 2.659, a 0.079: 0.002 wide at q 2.056, rate 8.5e-4 by a dense Hill scan)
read "stable" where four-wave and a fine scan find MI.

A mode can grow only where two roots of opposite Krein signs meet (``_sidebands``' module
docstring). Each harmonic l's own block of the scaled pencil, K_ll(q) (the wave's mean
Hessian: its frequency shifts included), places them at l omega +- w_lj(q); with the rest of
the pencil a perturbation E, a band opens about the offset where two such roots cross,
within |E| of it in frequency. The weaker the coupling the narrower the band and the
closer it sits to that crossing: where the grid can miss a band, the crossing places it.
So between two neighbouring samples that hold no growing mode, each pair of opposite-sign
roots (one of them in a harmonic |l| <= 1, where a kept mode lives) whose difference
changes sign gives one more offset, at its linear crossing (``crossing_offsets``); the
caller solves the spectrum there and keeps the offsets that grow. A band wider than a
step holds a sample already, so this adds offsets only where the grid saw nothing.
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np
from numba import njit

from ._chaining import pencil_parts
from ._small_algebra import _drop_roundoff, _eigh2

_KW = dict(cache=True, nogil=True, error_model="numpy", boundscheck=False)


@njit(**_KW)
def _diagonal_roots(parts, P, k, omega, q):
    """The roots l omega + w_lj (Krein +) and l omega - w_lj (Krein -) of each harmonic's own
    block K_ll(q) (``_sidebands._pencil_from_parts``'s block (l, l)), shape (Q, d (2P + 1))
    each, field-major inside a harmonic; w = sqrt|w^2| (a negative w^2: the joint disc's
    centre, both roots at l omega)."""
    d = parts.shape[2]
    nl = 2 * P + 1
    Q = q.size
    plus = np.empty((Q, nl * d))
    minus = np.empty((Q, nl * d))
    blk = np.empty((d, d), np.complex128)
    ev2 = np.empty(2)
    vec2 = np.empty((2, 2), np.complex128)
    h = np.empty((2, 2), np.complex128)
    s = 2 * P
    for i in range(Q):
        for li in range(nl):
            e = np.exp(1j * (q[i] + (li - P) * k))
            for a in range(d):
                for b in range(d):
                    blk[a, b] = (parts[0, s, a, b] + parts[1, s, a, b] * e
                                 + parts[2, s, a, b] * np.conj(e))
            if d == 1:
                ev = np.array([blk[0, 0].real])
            elif d == 2:
                h[0, 0] = blk[0, 0].real
                h[1, 1] = blk[1, 1].real
                h[0, 1] = 0.5 * (blk[0, 1] + np.conj(blk[1, 0]))
                h[1, 0] = np.conj(h[0, 1])
                _eigh2(h, ev2, vec2)
                ev = ev2
            else:
                ev = np.linalg.eigvalsh(0.5 * (blk + np.conj(blk.T)))
            for a in range(d):
                w = math.sqrt(abs(ev[a]))
                plus[i, li * d + a] = (li - P) * omega + w
                minus[i, li * d + a] = (li - P) * omega - w
    return plus, minus


@njit(**_KW)
def _sign_changes(q, plus, minus, quiet, central):
    """The linear crossings, between q[j] and q[j + 1] with quiet[j], of each pair (plus a,
    minus b) with a or b central whose difference changes sign."""
    Q, n = plus.shape
    out = np.empty(64)
    m = 0
    for j in range(Q - 1):
        if not quiet[j]:
            continue
        for a in range(n):
            for b in range(n):
                if not (central[a] or central[b]):
                    continue
                d0 = plus[j, a] - minus[j, b]
                d1 = plus[j + 1, a] - minus[j + 1, b]
                if d0 * d1 < 0:
                    if m == out.size:
                        grown = np.empty(2 * m)
                        grown[:m] = out
                        out = grown
                    out[m] = q[j] + (q[j + 1] - q[j]) * d0 / (d0 - d1)
                    m += 1
    return out[:m]


def crossing_offsets(Hh, masses, k: float, omega: float, P: int, q: np.ndarray,
                     gain: np.ndarray) -> np.ndarray:
    """The offsets (sorted, unique, none of ``q``) where opposite-sign roots of the pencil
    at truncation P cross between two neighbouring samples of the sorted ``q`` whose
    ``gain`` is 0 (module docstring). ``Hh``: the cell Hessian's harmonics (``_exact``'s
    ``_Sidebands.Hh``)."""
    d = masses.size
    sq = 1.0 / np.sqrt(np.asarray(masses, float))
    ed = np.exp(-1j * (np.arange(4 * P + 1) - 2 * P) * k)
    parts = pencil_parts(_drop_roundoff(Hh), sq, ed)
    plus, minus = _diagonal_roots(parts, P, float(k), float(omega), q)
    central = np.repeat(np.abs(np.arange(-P, P + 1)) <= 1, d)
    quiet = (gain[:-1] <= 0) & (gain[1:] <= 0)
    found = np.unique(_sign_changes(q, plus, minus, quiet, central))
    return found[~np.isin(found, q)]


def merged(spec, more, keep=None):
    """The ``HillSpectrum`` ``spec`` with ``more``'s offsets (where ``keep``: all where
    None), sorted by offset; ``spec``'s truncations."""
    keep = np.ones(more.offsets.size, bool) if keep is None else keep
    order = np.argsort(np.concatenate([spec.offsets, more.offsets[keep]]), kind="stable")
    return dataclasses.replace(spec, **{
        f: np.concatenate([getattr(spec, f), getattr(more, f)[keep]])[order]
        for f in ("offsets", "gain", "harmonic", "sideband_offset")})


def with_crossings(engine, spec):
    """``spec`` (the infinite chain's samples, by ``engine``: ``_exact._Sidebands``) with
    the offsets of ``crossing_offsets`` that hold a growing mode."""
    more = crossing_offsets(engine.Hh, engine.masses, engine.wave.k, engine.wave.omega,
                            engine.P, spec.offsets, spec.gain)
    if not more.size:
        return spec
    grows = engine.spectrum(more)
    return merged(spec, grows, grows.gain > 0) if grows.peak_gain > 0 else spec


def band_bracket(rate, q, gain, i: int, halvings: int = 40) -> tuple:
    """Where the peak at sample ``i`` is refined: between its neighbours, but where a
    neighbour holds no growing mode (a band narrower than a step: the crossings'), the
    band's edge on that side to within a factor 2 of its distance from q[i] (halving the
    distance until ``rate`` grows there, the bracket's end twice as far): a bounded search
    over a whole step would probe only where nothing grows (a band 2e-5 wide in a step of
    0.0079: fput a 0.002, k 1.5)."""
    ends = []
    for j in (max(i - 1, 0), min(i + 1, q.size - 1)):
        step = q[j] - q[i]
        if j == i or gain[j] > 0:
            ends.append(q[j])
            continue
        for _ in range(halvings):
            step /= 2
            if rate(q[i] + step) > 0:
                break
        ends.append(q[i] + 2 * step)
    return ends[0], ends[1]
