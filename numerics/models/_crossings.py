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

The diagonal roots leave out the O(a^2) shifts the couplings to the other harmonics give
each root, which can move the crossing by more than a narrow band's width (probe 100: 7.5e-4
against a band 1.3e-4 wide on a Morse chain). Where a linear crossing holds no growing
mode, the same pair's crossing with each root's second-order (Feshbach) shift, the pair's
own coupling left out, is found by regula falsi between quiet samples and solved too
(``corrected_crossings``).
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
def _harmonic_block(parts, s, x, blk, herm):
    """Harmonic l's own block K_ll(q) into ``blk`` (x = q + l k), and for two fields its
    Hermitian part into ``herm`` (the closed-form ``_eigh2``'s input)."""
    d = parts.shape[2]
    e = np.exp(1j * x)
    for a in range(d):
        for b in range(d):
            blk[a, b] = (parts[0, s, a, b] + parts[1, s, a, b] * e
                         + parts[2, s, a, b] * np.conj(e))
    if d == 2:
        herm[0, 0] = blk[0, 0].real
        herm[1, 1] = blk[1, 1].real
        herm[0, 1] = 0.5 * (blk[0, 1] + np.conj(blk[1, 0]))
        herm[1, 0] = np.conj(herm[0, 1])


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
            _harmonic_block(parts, s, q[i] + (li - P) * k, blk, h)
            if d == 1:
                ev = np.array([blk[0, 0].real])
            elif d == 2:
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
    quiet = more[grows.gain <= 0]
    if quiet.size:  # the crossings the diagonal roots misplace: with their shifts
        again = corrected_crossings(engine, spec.offsets, spec.gain, quiet)
        if again.size:
            more2 = engine.spectrum(again)
            grows = merged(grows, more2)
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


@njit(**_KW)
def _block_basis(parts, P, k, q, w2, V):
    """Each harmonic's own block K_ll(q), Hermitian part, diagonalised as
    ``_diagonal_roots`` does (ascending; the 2 x 2 ones in closed form): w2 (n,), V
    (2P + 1, d, d) its eigenvectors (columns)."""
    d = parts.shape[2]
    nl = 2 * P + 1
    blk = np.empty((d, d), np.complex128)
    h = np.empty((2, 2), np.complex128)
    ev2 = np.empty(2)
    vec2 = np.empty((2, 2), np.complex128)
    s = 2 * P
    for li in range(nl):
        _harmonic_block(parts, s, q + (li - P) * k, blk, h)
        if d == 1:
            w2[li] = blk[0, 0].real
            V[li, 0, 0] = 1.0
        elif d == 2:
            _eigh2(h, ev2, vec2)
            for a in range(2):
                w2[li * 2 + a] = ev2[a]
                for b in range(2):
                    V[li, b, a] = vec2[b, a]
        else:
            ev, vec = np.linalg.eigh(0.5 * (blk + np.conj(blk.T)))
            for a in range(d):
                w2[li * d + a] = ev[a]
                for b in range(d):
                    V[li, b, a] = vec[b, a]


@njit(**_KW)
def _shifted_gap(parts, P, k, omega, q, ia, ib):
    """Im of root ia (Krein +: i (l omega + w)) minus Im of root ib (Krein -: i (l omega -
    w)) of the pencil at offset q, each moved by its second-order (Feshbach) shift
    sum_j |E_ij|^2 / (T_jj(lambda_0) T_ii'(lambda_0)) over the other harmonics' coordinates,
    the pair's own coupling left out (it is what opens the band). Coordinates as
    ``_diagonal_roots``' (each harmonic's block diagonalised, ascending); the rows of the
    rotated pencil as ``_sidebands``' Kt: block (l, h) = AD_s + B_s e^{i (q + h k)} + C_s
    e^{-i (q + l k)}, s = l - h + 2P, turned by V_l^* and V_h."""
    d = parts.shape[2]
    nl = 2 * P + 1
    n = nl * d
    w2 = np.empty(n)
    V = np.zeros((nl, d, d), np.complex128)
    _block_basis(parts, P, k, q, w2, V)
    out = 0.0
    for r in range(2):
        i = ia if r == 0 else ib
        other = ib if r == 0 else ia
        sgn = 1.0 if r == 0 else -1.0
        li, ja = i // d, i % d
        Om_i = (li - P) * omega
        lam0 = 1j * (Om_i + sgn * math.sqrt(abs(w2[i])))
        el = np.exp(-1j * (q + (li - P) * k))
        acc = 0j
        for hi_ in range(nl):
            if hi_ == li:
                continue
            sidx = li - hi_ + 2 * P
            eh = np.exp(1j * (q + (hi_ - P) * k))
            Om_h = (hi_ - P) * omega
            for jb in range(d):
                j = hi_ * d + jb
                if j == other:
                    continue
                e_ij = 0j
                for c in range(d):
                    for f in range(d):
                        kcf = parts[0, sidx, c, f] + parts[1, sidx, c, f] * eh + parts[2, sidx, c, f] * el
                        e_ij += np.conj(V[li, c, ja]) * kcf * V[hi_, f, jb]
                a2 = e_ij.real * e_ij.real + e_ij.imag * e_ij.imag
                if a2 > 0:
                    z = lam0 - 1j * Om_h
                    den = z * z + w2[j]
                    if den == 0:  # another root exactly on this one: no second order
                        return math.nan
                    acc += a2 / den
        if w2[i] == 0:  # a zero root (the acoustic mode at rest): no second order
            return math.nan
        lam = lam0 + acc / (2 * (lam0 - 1j * Om_i))
        out += sgn * lam.imag
    return out


#: how many samples the bracket of a shifted crossing may widen by on a fine grid
WIDEN = 8


def corrected_crossings(engine, q, gain, more, steps: int = 30):
    """Where a linear crossing of ``crossing_offsets`` (``more``) held no growing mode: the
    crossing of the same pair's roots with their second-order shifts (``_shifted_gap``),
    by regula falsi between the quiet samples around it. The diagonal roots leave out the
    shifts the couplings to the other harmonics give (O(a^2) in frequency): a band narrower
    than the offset they move the crossing by is missed (probe 100: a Morse chain, k 1.2855,
    a 0.015, its backward pair 3.6e-5 in a band 1.3e-4 wide at q 1.6938, the linear crossing
    7.5e-4 off, the corrected one inside it)."""
    P = engine.P
    d = engine.masses.size
    sq = 1.0 / np.sqrt(np.asarray(engine.masses, float))
    ed = np.exp(-1j * (np.arange(4 * P + 1) - 2 * P) * engine.wave.k)
    parts = pencil_parts(_drop_roundoff(engine.Hh), sq, ed)
    order = np.argsort(q)
    qs, gs = q[order], gain[order]
    plus, minus = _diagonal_roots(parts, P, float(engine.wave.k), float(engine.wave.omega), qs)
    central = np.repeat(np.abs(np.arange(-P, P + 1)) <= 1, d)
    found = []
    kk, om = float(engine.wave.k), float(engine.wave.omega)
    for x in np.atleast_1d(more):
        j = int(np.searchsorted(qs, x)) - 1
        if j < 0 or j + 1 >= qs.size or gs[j] > 0 or gs[j + 1] > 0:
            continue
        d0 = plus[j][:, None] - minus[j][None, :]
        d1 = plus[j + 1][:, None] - minus[j + 1][None, :]
        cen = central[:, None] | central[None, :]
        with np.errstate(divide="ignore", invalid="ignore"):  # d0 = d1: not a crossing
            lin = np.where(cen & (d0 * d1 < 0), qs[j] + (qs[j + 1] - qs[j]) * d0 / (d0 - d1),
                           np.nan)
        for a, b in zip(*np.nonzero(np.abs(lin - x) <= 1e-12 * max(1.0, abs(x)))):
            # the shifted crossing may lie a few samples over (a fine grid): the bracket
            # widened over quiet samples towards the smaller |f|, at most WIDEN steps
            i_lo, i_hi = j, j + 1
            f_lo, f_hi = (_shifted_gap(parts, P, kk, om, qs[i_lo], a, b),
                          _shifted_gap(parts, P, kk, om, qs[i_hi], a, b))
            for _ in range(WIDEN):
                if f_lo * f_hi < 0:
                    break
                if abs(f_lo) <= abs(f_hi) and i_lo > 0 and gs[i_lo - 1] <= 0:
                    i_lo -= 1
                    f_lo = _shifted_gap(parts, P, kk, om, qs[i_lo], a, b)
                elif i_hi + 1 < qs.size and gs[i_hi + 1] <= 0:
                    i_hi += 1
                    f_hi = _shifted_gap(parts, P, kk, om, qs[i_hi], a, b)
                else:
                    break
            if not f_lo * f_hi < 0:
                continue
            lo, hi = qs[i_lo], qs[i_hi]
            side, y = 0, math.nan
            for _ in range(steps):  # regula falsi, Illinois: superlinear, inside [lo, hi]
                y, y_was = lo + (hi - lo) * f_lo / (f_lo - f_hi), y
                if abs(y - y_was) <= 1e-10 * max(1.0, abs(y)):
                    break  # settled far below any band's width (~rate / |v1 - v2|)
                f = _shifted_gap(parts, P, kk, om, y, a, b)
                if not math.isfinite(f) or f == 0 or hi - lo <= 1e-12 * max(1.0, abs(y)):
                    break
                if f * f_lo < 0:
                    hi, f_hi = y, f
                    f_lo = f_lo / 2 if side == -1 else f_lo
                    side = -1
                else:
                    lo, f_lo = y, f
                    f_hi = f_hi / 2 if side == 1 else f_hi
                    side = 1
            if math.isfinite(y):
                found.append(y)
    out = np.unique(np.asarray(found, float))
    return out[~np.isin(out, q) & ~np.isin(out, more)]
