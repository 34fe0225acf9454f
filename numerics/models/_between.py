"""Offsets between two anchors on a fine grid of ``_strong.strong_modes`` (the infinite
chain's 440 offsets, where q +- k are not offsets and the ring's translation does not
apply): the frozen pencil solved at every other offset only (the anchors, ``STRIDE``),
each offset between two anchors started from what the anchors found.

The whole pencil's eigenvalues and the frozen pencil's move continuously with q. An
offset between two anchors (processed after them) takes, as its starts: (1) the modes
refined at the anchors, each mutually nearest pair of them interpolated to its q (an
eigenvalue of the whole pencil to O(dq^2), its vector the nearer anchor's), the others
as they are; (2) the anchors' frozen starts, matched and interpolated the same way,
leaving out a matched pair that both anchors refined (its modes are in (1)). The starts
are only starts: each is refined on the offset's own whole pencil (``_strong._refine``)
with the anchors' largest refinement move in its cut-off, so the answers are that
pencil's eigenvalues, as they were from the offset's own frozen starts.

A mode refined at both anchors is known to within its move between them: the search's
cut-off leaves it where its rate plus that move cannot reach the fastest kept mode found
(a frozen start keeps the cut-off's margin for the frozen pencil's error, 10x the largest
refinement move at the anchors).

Where a growing mode may appear between the anchors, the offset solves its own frozen
pencil as every offset did before: either anchor has a close pair on the axis
(``_frozen``: a collision) whose eigenvector is central (heaviest at |l| <= 2: it may
become a kept mode between them; measured: a stiff-hinge band of rate 1.05e-3 one grid
offset wide, whose pair's gap was 0.010 and 0.005 at the two anchors, was missed without
this), or an anchor went to the dense eigenproblem; also where the starts from the anchors
leave the offset unsure (it would go dense). A band edge where a growing frozen
eigenvalue appears between the anchors needs no more: the anchor inside the band brings
its refined mode and frozen start (a guard on the anchors' growing counts was tried:
no answer changed at 116 spectra without it). Not a certificate, as the frozen pencil
itself is not (``_strong``'s module docstring). Measured against main's answers (every
offset's rate within 1e-6 relative, peaks equal) and tested against the same spectrum
asked one offset at a time (tests/test_exact_between.py); bench/README.md.
"""

from __future__ import annotations

import numpy as np
from numba import njit

_KW = dict(cache=True, nogil=True, error_model="numpy", boundscheck=False)

#: every STRIDE-th offset (ascending q) of those that solve their own frozen pencil is an
#: anchor; the STRIDE - 1 between two anchors take the anchors' starts. Measured at 3
#: (with every rule here): 4 of 192 spectra (random flexmm / stiff-hinge points, ring and
#: chain) lost a growing offset (rates 6e-4 to 1.7e-2), and the chains were no cheaper
#: (more own solves and refinements): 2 it is
STRIDE = 2
#: anchors at most this far apart (rad/site): the infinite chain's grid (pi / 400 a
#: step, finer below it) is interpolated, a coarse ring's offsets (2 pi / N, N < ~600 at
#: STRIDE 2) solve their own pencils; a frozen eigenvalue moves by ~|v_g| dq (|v_g| <~ 1
#: for the built-in models: ~0.02 omega between anchors), well inside the gaps between
#: the starts it is matched across
MAX_SPAN = 0.02


@njit(**_KW)
def between_anchors(offsets, own):
    """For the offsets that solve their own frozen pencil (``own``), in ascending q: every
    ``STRIDE``-th one (and the last) an anchor, each other one between its two anchors
    where they are at most ``MAX_SPAN`` apart. Returns lo, hi (the anchors' indices, -1
    where the offset is none between) and frac (its q's fraction of the way from lo to
    hi)."""
    Q = offsets.size
    lo = np.full(Q, -1, np.int64)
    hi = np.full(Q, -1, np.int64)
    frac = np.zeros(Q)
    order = np.argsort(offsets)
    ow = np.empty(Q, np.int64)
    m = 0
    for t in range(Q):
        if own[order[t]]:
            ow[m] = order[t]
            m += 1
    for t in range(m):
        r = t % STRIDE
        if r == 0 or t == m - 1:
            continue
        a, b = ow[t - r], ow[min(t - r + STRIDE, m - 1)]
        span = offsets[b] - offsets[a]
        if span <= 0 or span > MAX_SPAN:
            continue
        i = ow[t]
        lo[i], hi[i] = a, b
        frac[i] = (offsets[i] - offsets[a]) / span
    return lo, hi, frac


@njit(**_KW)
def _nearest(x, gx, ys, gys, n):
    """The index of the start among ys[:n] nearest x of the same kind (growing: gap 0, or
    a close pair: gap > 0), or -1."""
    best, arg = np.inf, -1
    for t in range(n):
        if (gys[t] > 0) != (gx > 0):
            continue
        dist = abs(ys[t] - x)
        if dist < best:
            best, arg = dist, t
    return arg


@njit(**_KW)
def merged_starts(sa, ga, na, sb, gb, nb, frac, starts, gaps, which, index, other):
    """The starts of an offset a fraction ``frac`` of the way from anchor A (starts
    ``sa[:na]``, half gaps ``ga``) to anchor B (``sb[:nb]``, ``gb``): each mutually nearest
    pair of the same kind interpolated (its vector the nearer anchor's), every other start
    of either as it is. Into starts, gaps, which (0: A's vector, 1: B's), index (the
    start's index there) and other (a matched start's index at the other anchor, else
    -1); returns how many."""
    ns = 0
    near_b = frac > 0.5
    used_b = np.zeros(max(nb, 1), np.bool_)
    for s in range(na):
        t = _nearest(sa[s], ga[s], sb, gb, nb)
        if t >= 0 and _nearest(sb[t], gb[t], sa, ga, na) == s:
            used_b[t] = True
            starts[ns] = sa[s] + frac * (sb[t] - sa[s])
            gaps[ns] = ga[s] + frac * (gb[t] - ga[s])
            if near_b:
                which[ns], index[ns], other[ns] = 1, t, s
            else:
                which[ns], index[ns], other[ns] = 0, s, t
        else:
            starts[ns], gaps[ns], which[ns], index[ns], other[ns] = sa[s], ga[s], 0, s, -1
        ns += 1
    for t in range(nb):
        if not used_b[t]:
            starts[ns], gaps[ns], which[ns], index[ns], other[ns] = sb[t], gb[t], 1, t, -1
            ns += 1
    return ns
