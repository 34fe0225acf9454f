"""The growing modes of the Hill pencil where the Gershgorin clusters of ``_sidebands`` chain
(strong coupling, a flat branch: flexmm): the central harmonics' pencil, the outer ones
folded in, instead of the whole dense eigenproblem.

At offset q the scaled pencil is T(lambda) = (lambda - i Omega)^2 + K (``_sidebands``'s
module docstring), n = d (2 P + 1) coordinates. Split them into C, the harmonics
|l| <= P_C, and R, the outer ones. The eigenvalues are the zeros of the Schur complement
S(lambda) = T_CC(lambda) - K_CR T_RR(lambda)^{-1} K_RC. With the fold frozen at
lambda = 0 (the centre of the modes a kept mode can be: centred at l = -1, 0, 1), the
2 r_C eigenvalues of the frozen C pencil place the central spectrum at once (LAPACK on
2 r_C = 2 d (2 P_C + 1), against 2 n for the dense one; in real arithmetic where a
diagonal phase makes the pencil real, ``_real_gauge``); each of them that grows and
whose eigenvector is heaviest at |l| <= 2 (one inverse-iteration step) is refined
on the whole pencil at P, exact: nonlinear inverse iteration (``_refine``) from it and
its eigenvector (the C part from that step, the rest -T_RR(0)^{-1} K_RC y_C), whose
eigenvector gives the weights the kept modes are chosen by, as the dense eigenproblem's
do; where it does not settle, Newton on det S (``_cluster_solve._newton``: the mirror root
-conj(lambda) divided out, the eigenvector S's null vector and the rest
-T_RR^{-1} K_RC y_C). A step of the inverse iteration is one LAPACK solve of n x n, one
of Newton's on S two solves and two products (halves the refinement's cost). A pair of
the frozen eigenvalues close on the imaginary axis (a collision the frozen fold may place
just apart) is a start too, from between them.
Only the fastest kept mode matters: the starts go fastest first, and once a kept mode is
refined, a start whose rate cannot reach it (its frozen rate, or half its pair's gap,
plus 10x the largest move a refined start made at this offset) is left.

Not a certificate, as the clusters of ``_sidebands`` are: a growing mode the frozen
pencil moved off (its fold is frozen at 0 while the mode sits near +-2 omega) would be
missed. Measured against the dense spectrum (tests/test_exact_gain_anchors.py: the
flexmm anchors, the 36 random points of its slow test; tests/test_exact_strong.py; when
this was written, 24 random flexmm and stiff-hinge points with K_theta, alpha, k and a
drawn, and 40 random points of the seven built-in models, amplitudes up to 0.35, where
this path was taken, rings of 64; tests/test_exact_strong.py's random points since): equal
to 1e-6 relative (1e-12 at the bench points). A clearly growing central start (rate
> 1e-3 omega) that Newton takes to the axis is a pair the frozen fold split apart where
the whole pencil keeps it on the axis, or a mode Newton stepped past: Newton again, the
root found divided out (first from that root's reflection about the start, where a split
pair's partner sits; then from the start itself), finds the partner (a second root on the axis
within 4x the first one's distance from the start: the pair is accounted for) or the
growing mode (kept as any other). Where Newton does not settle, or the partner is neither,
the caller solves that offset densely (stiff-hinge's bench point: 24 of 128 ring offsets
before this check, none with it).

On a ring the frozen pencil is solved at half of the offsets: the pencil at q + k is the
one at q shifted one harmonic (``strong_modes``), so an offset between two sources takes
their starts, translated; each is refined at its own offset as any other. The sources go
first: their refined modes, translated, are starts too (the same eigenvalues but for the
truncation's edge: their rate known, so the cut-off leaves those that cannot reach the
fastest kept one), and a frozen start a source refined is not refined again (its mode
is among them); the frozen starts' cut-off keeps the sources' largest refinement move. On a fine grid
(the infinite chain's) it is solved at every other offset, the anchors; an offset between
two takes their refined modes and frozen starts, interpolated (``_between``), or solves
its own where a mode may appear between them.
"""

from __future__ import annotations

import numpy as np
from numba import njit

from ._between import between_anchors, merged_starts
from ._chaining import pencil_parts
from ._cluster_solve import _newton
from ._frozen import _frozen_starts, _start_vector
from ._real_gauge import _components
from ._refine import _kept, _newton_past, _refine
from ._ring_shift import _neighbours, _translate
from ._sidebands import _pencil_from_parts
from ._small_algebra import _drop_roundoff

_KW = dict(cache=True, nogil=True, error_model="numpy", boundscheck=False)

#: the frozen pencil holds the harmonics |l| <= P - CENTRAL_MARGIN (5 at P = 10: its
#: eigenvalues, 44 x 44, cost ~0.6 of the 52 x 52 ones at P_C = 6). Measured against the
#: dense spectrum at H + 4 (flexmm and stiff-hinge, parameters, k and a drawn as in
#: tests/test_exact_strong.py, with the pair check below): P_C = 5 equal at 24 points
#: (rings of 64), at 30 others and the two bench points (rings of 128); P_C = 4 equal at
#: the 24 but differs at 2 of the 32 (one offset each: a kept mode's start too far from
#: it; the bench flexmm point is one), P_C = 3 at 13 (73 offsets). 5 keeps one harmonic
#: of margin over the first that failed (P_C = 6 before)
CENTRAL_MARGIN = 5


@njit(**_KW)
def strong_modes(Hh, masses, k, omega, P, Pc, offsets, floor, max_modes):
    """For each offset: the growing eigenvalues refined from the central frozen pencil's
    growing (or colliding) eigenvalues, with their eigenvectors in the harmonics'
    coordinates (field-major inside a harmonic, as ``_exact``'s dense pencil).

    Where the offsets q - k and q + k (mod 2 pi, up to sign: a ring's, k on it) are asked
    too, the frozen pencil is solved at about half of the offsets (sources): an offset
    that is none takes both neighbouring sources' starts, moved one harmonic over (the
    pencil at q + k is the one at q, shifted: translation along the wave), each refined
    at its own offset as any other.

    Returns lam (Q, max_modes) complex, vec (Q, max_modes, n) complex, count (Q,) int:
    -1 where the offset needs the dense eigenproblem.
    """
    d = masses.size
    nl = 2 * P + 1
    n = d * nl
    Q = offsets.size
    # the Hessian's harmonics below the DFT's round-off made exact zeros, as the Gershgorin
    # pass has them (``_sidebands``): where the pencil splits, its frozen pencil's
    # eigenvalues are found block by block (``_real_gauge.frozen_real``)
    Hh = _drop_roundoff(Hh)
    lam_out = np.zeros((Q, max_modes), np.complex128)
    vec_out = np.zeros((Q, max_modes, n), np.complex128)
    count = np.zeros(Q, np.int64)
    sq = 1.0 / np.sqrt(masses)
    Om = np.empty(n)
    inC = np.zeros(n, np.bool_)
    for li in range(nl):
        for a in range(d):
            Om[li * d + a] = (li - P) * omega
            inC[li * d + a] = abs(li - P) <= Pc
    cidx = np.flatnonzero(inC)
    ridx = np.flatnonzero(~inC)
    rc, nr = cidx.size, ridx.size
    ed = np.empty(4 * P + 1, np.complex128)
    for s in range(4 * P + 1):
        ed[s] = np.exp(-1j * (s - 2 * P) * k)
    parts = pencil_parts(Hh, sq, ed)  # K(q) as ``sideband_modes`` builds it
    eq = np.empty(nl, np.complex128)
    K = np.empty((n, n), np.complex128)
    X = np.empty((nr, rc), np.complex128)
    y = np.empty(rc, np.complex128)
    v = np.empty(n, np.complex128)
    scale = omega
    lvec = np.empty(rc, np.int64)
    for a in range(rc):
        lvec[a] = cidx[a] // d - P
    width = 4 * rc
    # sources: every other offset along each chain of neighbours (2-coloured), so that an
    # offset that is none has both neighbours sources: a mode kept at it (|l| <= 1) is
    # centred at |l| <= 1 at one of them (at l = 0 at q + l k). Measured: one source only
    # (a third of the offsets) misses flexmm's fastest mode at one bench offset (its start
    # from a source where it sits at l = 2, as the frozen pencil at |l| <= P - 6 misses it)
    nb, mirror = _neighbours(offsets, k)
    colour = np.full(Q, -1, np.int64)
    stack = np.empty(Q, np.int64)
    for i0 in range(Q):
        if colour[i0] >= 0:
            continue
        colour[i0] = 1
        top = 0
        stack[top] = i0
        top += 1
        while top > 0:
            top -= 1
            i = stack[top]
            for e in range(2):
                j = nb[i, e]
                if j >= 0 and colour[j] < 0:
                    colour[j] = 1 - colour[i]
                    stack[top] = j
                    top += 1
    source = colour == 1
    for i in range(Q):
        if not source[i]:
            for e in range(2):
                if nb[i, e] < 0 or not source[nb[i, e]]:
                    source[i] = True
    # stored: the sources an offset that is none takes starts from; every other offset
    # (each on the infinite chain's grid, where q +- k are not offsets) solves its own in
    # the last slot as it comes
    slot = np.full(Q, -1, np.int64)
    nsrc = 0
    for i in range(Q):
        if not source[i]:
            for e in range(2):
                j = nb[i, e]
                if slot[j] < 0:
                    slot[j] = nsrc
                    nsrc += 1
    # the offsets that solve their own pencil, on a fine grid (the infinite chain's): at
    # every STRIDE-th (the anchors, stored) only, the others between two anchors take
    # both anchors' starts (``_between``)
    lo, hi, frac = between_anchors(offsets, source & (slot < 0))
    for i in range(Q):
        if lo[i] >= 0:
            for j in (lo[i], hi[i]):
                if slot[j] < 0:
                    slot[j] = nsrc
                    nsrc += 1
    s_starts = np.zeros((nsrc + 1, width), np.complex128)
    s_gaps = np.zeros((nsrc + 1, width))
    s_larg = np.zeros((nsrc + 1, width), np.int64)  # ``_start_vector``'s two answers
    s_near = np.zeros((nsrc + 1, width), np.int64)
    # written before they are read (a slot's frozen pencil; a start's vector where
    # ``s_made`` says so): not cleared (the chain's anchors: ~200 slots)
    s_vecs = np.empty((nsrc + 1, width, n), np.complex128)
    s_count = np.zeros(nsrc + 1, np.int64)
    s_every = np.empty((nsrc + 1, 2 * rc), np.complex128)
    # each slot's frozen pencil and fold, its starts' eigenvectors made from them when the
    # search first reaches them (``s_made``): most starts are left by the cut-off
    s_F0 = np.empty((nsrc + 1, rc, rc), np.complex128)
    s_X = np.empty((nsrc + 1, nr, rc), np.complex128)
    s_made = np.zeros((nsrc + 1, width), np.bool_)
    for i in range(Q):
        if slot[i] >= 0:
            _pencil_from_parts(parts, P, k, offsets[i], eq, K)
            j = slot[i]
            s_count[j] = _frozen_starts(K, Om, cidx, ridx, omega, s_starts[j], s_gaps[j],
                                        s_F0[j], s_X[j], s_every[j])
    m_starts = np.empty(2 * width, np.complex128)
    m_gaps = np.empty(2 * width)
    m_which = np.empty(2 * width, np.int64)
    m_index = np.empty(2 * width, np.int64)
    m_other = np.empty(2 * width, np.int64)
    src_alt = np.full(3 * width, -1, np.int64)
    no_gaps = np.zeros(max_modes)
    sure = np.zeros(3 * width, np.bool_)
    s_done = np.zeros((nsrc + 1, width), np.bool_)  # a slot's start refined at its offset
    s_moved = np.zeros(Q)  # each offset's largest refinement move
    ja, jb = 0, 0
    starts = np.empty(3 * width, np.complex128)
    gaps = np.empty(3 * width)
    src = np.empty(3 * width, np.int64)  # each start's slot, index there, sigma, mirror
    src_s = np.empty(3 * width, np.int64)
    src_sigma = np.empty(3 * width, np.int64)
    src_mir = np.zeros(3 * width, np.bool_)
    # the sources first, the offsets between anchors last: the others start from their
    # sources' or anchors' refined modes
    order = np.concatenate((np.flatnonzero(source & (lo < 0)), np.flatnonzero(~source),
                            np.flatnonzero(lo >= 0)))
    w = np.empty(n, np.complex128)
    for iq in order:
        # between two anchors: first from their starts; where that is unsure (the
        # dense eigenproblem would be asked), again from its own frozen pencil
        use_anchors = lo[iq] >= 0
        _pencil_from_parts(parts, P, k, offsets[iq], eq, K)
        split = _components(K).max() > 0
        for _attempt in range(2):
            # this offset's starts: between two anchors, both anchors' where their frozen
            # pencils grow alike; its own where it is a source, else its neighbours'
            ns = 0
            merged = False
            ring_moved = 0.0
            if use_anchors:
                ja, jb = slot[lo[iq]], slot[hi[iq]]
                qa, qb = lo[iq], hi[iq]
                # a collision between the anchors (a close pair that may be central at
                # either) or an anchor gone dense: its own pencil
                alike = (s_count[ja] >= 0 and s_count[jb] >= 0 and count[qa] >= 0
                         and count[qb] >= 0)
                for j in (ja, jb):
                    for js in range(s_count[j] if alike else 0):
                        if s_gaps[j, js] > 0:
                            if not s_made[j, js]:
                                s_larg[j, js], s_near[j, js] = _start_vector(
                                    s_F0[j], s_X[j], Om, cidx, ridx, lvec, P, sq,
                                    s_starts[j, js], s_vecs[j, js])
                                s_made[j, js] = True
                            alike = alike and abs(s_larg[j, js]) > 2
                if alike:
                    # the anchors' refined modes first (the whole pencil's eigenvalues,
                    # interpolated: its own modes' starts to O(dq^2)), then their frozen
                    # starts (gaps: the refined ones none)
                    ns = merged_starts(lam_out[qa], no_gaps, count[qa], lam_out[qb], no_gaps,
                                       count[qb], frac[iq], m_starts, m_gaps, m_which,
                                       m_index, m_other)
                    for s in range(ns):
                        starts[s], gaps[s] = m_starts[s], 0.0
                        src[s] = -1 - (qb if m_which[s] else qa)
                        src_s[s], src_sigma[s], src_mir[s] = m_index[s], 0, False
                        # a mode refined at both: its rate known to within its move
                        # between them (gaps), not the frozen pencil's error (the cut-off)
                        sure[s] = m_other[s] >= 0
                        if sure[s]:
                            gaps[s] = abs(lam_out[qa, m_index[s]] - lam_out[qb, m_other[s]])
                            if m_which[s]:
                                gaps[s] = abs(lam_out[qb, m_index[s]]
                                              - lam_out[qa, m_other[s]])
                    nf = merged_starts(s_starts[ja], s_gaps[ja], s_count[ja], s_starts[jb],
                                       s_gaps[jb], s_count[jb], frac[iq], m_starts, m_gaps,
                                       m_which, m_index, m_other)
                    for s in range(nf):
                        # refined at both anchors: its modes are among their refined ones
                        jw = jb if m_which[s] else ja
                        if (m_other[s] >= 0 and s_done[jw, m_index[s]]
                                and s_done[ja + jb - jw, m_other[s]]):
                            continue
                        starts[ns], gaps[ns] = m_starts[s], m_gaps[s]
                        src[ns] = jb if m_which[s] else ja
                        src_s[ns], src_sigma[ns], src_mir[ns] = m_index[s], 0, False
                        src_alt[ns] = m_other[s]
                        sure[ns] = False
                        ns += 1
                    merged = True
            for c in range(3):
                if merged:
                    break
                if source[iq]:
                    if c != 2:
                        continue
                    j, sigma, mir = slot[iq], 0, False
                    if j < 0:
                        j = nsrc
                        s_count[j] = _frozen_starts(K, Om, cidx, ridx, omega, s_starts[j],
                                                    s_gaps[j], s_F0[j], s_X[j], s_every[j])
                        s_made[j, :] = False
                else:
                    if c == 2 or nb[iq, c] < 0 or not source[nb[iq, c]]:
                        continue
                    j, sigma, mir = slot[nb[iq, c]], 1 - 2 * c, mirror[iq, c]
                    # the source's refined modes, translated (its pencil is this one
                    # shifted: the same eigenvalues but for the truncation's edge)
                    qs = nb[iq, c]
                    for f in range(max(count[qs], 0)):
                        lam = np.conj(lam_out[qs, f]) if mir else lam_out[qs, f]
                        starts[ns], gaps[ns], sure[ns] = lam - 1j * sigma * omega, 0.0, True
                        src[ns], src_s[ns], src_sigma[ns], src_mir[ns] = -1 - qs, f, sigma, mir
                        ns += 1
                    ring_moved = max(ring_moved, s_moved[qs])
                if s_count[j] < 0:
                    ns = -1
                    break
                for s in range(s_count[j]):
                    if not source[iq] and count[nb[iq, c]] >= 0 and s_done[j, s]:
                        continue  # refined at its source: its mode is among those above
                    sure[ns] = False
                    lam = s_starts[j, s]
                    if mir:  # the mirror image at -q: conj(lambda), harmonic l -> -l
                        lam = np.conj(lam)
                    starts[ns] = lam - 1j * sigma * omega
                    gaps[ns] = s_gaps[j, s]
                    src[ns], src_s[ns], src_sigma[ns], src_mir[ns] = j, s, sigma, mir
                    ns += 1
            if ns < 0:
                count[iq] = -1
                break
            # fastest first: once a kept mode is refined, a start whose rate cannot reach it
            # (its frozen rate, or half its pair's gap, plus 10x the largest move a refined
            # start made at this offset) is left
            reach = np.empty(ns)
            for s in range(ns):
                reach[s] = starts[s].real if starts[s].real > 1e-9 * omega else 0.0
            first = np.argsort(-reach)
            found, bad, kept, moved = 0, False, 0.0, 1e-9 * omega
            if merged:  # the anchors' refinements measured the frozen starts' error
                moved = max(moved, s_moved[lo[iq]], s_moved[hi[iq]])
            moved = max(moved, ring_moved)  # and a ring's sources theirs
            # the starts whose frozen vector is heaviest off the centre but weighs half that
            # at a central harmonic (``_frozen.SPREAD_SHARE``) after the others, cut off as
            # they are (refined first, they doubled flexmm's ring)
            later = np.empty(ns, np.int64)
            nlater, t, deferred = 0, 0, False
            while True:
                if t >= (nlater if deferred else ns):
                    if deferred:
                        break
                    deferred, t = True, 0
                    continue
                s = later[t] if deferred else first[t]
                t += 1
                if kept > 0 and sure[s] and reach[s] + gaps[s] < kept:
                    continue
                if kept > 0 and reach[s] + gaps[s] + 10 * moved < kept:
                    if deferred:
                        break
                    deferred, t = True, 0
                    continue
                j, js, sigma, mir = src[s], src_s[s], src_sigma[s], src_mir[s]
                if j < 0:  # a refined mode: an anchor's (``_between``) or a ring source's
                    for a in range(n):
                        w[a] = vec_out[-1 - j, js, a] / sq[a % d]
                    _translate(w, v, P, d, sigma, mir)
                else:
                    if not s_made[j, js]:
                        s_larg[j, js], s_near[j, js] = _start_vector(
                            s_F0[j], s_X[j], Om, cidx, ridx, lvec, P, sq, s_starts[j, js],
                            s_vecs[j, js])
                        s_made[j, js] = True
                    lq = -s_larg[j, js] if mir else s_larg[j, js]
                    ln = -s_near[j, js] if mir else s_near[j, js]
                    if merged and abs(lq) > 2 and src_alt[s] >= 0:
                        # a matched pair: the other anchor's vector where it is central (a
                        # mode whose weight moves between harmonics across the anchors)
                        j = ja if j == jb else jb
                        js = src_alt[s]
                        if not s_made[j, js]:
                            s_larg[j, js], s_near[j, js] = _start_vector(
                                s_F0[j], s_X[j], Om, cidx, ridx, lvec, P, sq, s_starts[j, js],
                                s_vecs[j, js])
                            s_made[j, js] = True
                        lq, ln = s_larg[j, js], s_near[j, js]
                    if abs(lq - sigma) > 2 and abs(ln - sigma) > 2:
                        continue  # off the centre, none central near as heavy: not kept
                    if abs(lq - sigma) > 2 and not deferred:
                        later[nlater] = s
                        nlater += 1
                        continue
                    # the whole frozen eigenvector refined on the whole pencil; Newton on the
                    # Schur complement where that does not settle
                    _translate(s_vecs[j, js], v, P, d, sigma, mir)
                nrm = 0.0
                for a in range(n):
                    nrm += abs(v[a]) ** 2
                for a in range(n):
                    v[a] /= np.sqrt(nrm)
                lam, settled = _refine(K, Om, starts[s], v, scale, split)
                if j >= 0 and j == slot[iq]:
                    s_done[j, js] = True
                whole = settled and lam.real >= -floor
                if not whole:
                    lam, settled = _newton(K, Om, starts[s], cidx, ridx, scale, y, True, X)
                if not whole and (not settled or lam.real < -floor):
                    lam, settled = _newton(K, Om, starts[s], cidx, ridx, scale, y, False, X)
                if not settled:
                    if deferred:  # a spread start is a guess: unsure is no mode here
                        continue
                    bad = True
                    break
                if lam.real <= floor:
                    if starts[s].real <= 1e-3 * omega:
                        continue
                    # a clearly growing start ended on the axis: the frozen fold may have split
                    # a pair the whole pencil keeps on the axis. Its partner, Newton from the
                    # same start with the root found divided out: a second root on the axis as
                    # near the start accounts for the pair (no growth there); a growing one is
                    # a mode; anything else, unsure (the dense eigenproblem)
                    near = 4 * max(abs(lam - starts[s]), starts[s].real)
                    # first from the root's reflection about the start on the axis, where a
                    # split pair's partner sits (measured: within ~1e-5 omega of it on
                    # stiff-hinge's bench chain; ~2 steps against ~12 from the start, whose
                    # iterate crawls to the axis against its mirror's deflation); the partner
                    # found on the axis, and near, accounts for the pair as from the start
                    guess = 1j * (2 * starts[s].imag - lam.imag)
                    lam2, settled = _newton_past(K, Om, guess, cidx, ridx, scale, X, lam)
                    if (settled and abs(lam2.real) <= floor and abs(lam2 - starts[s]) <= near
                            and abs(lam2 - lam) > 1e-6 * (abs(lam) + scale)):
                        continue
                    lam2, settled = _newton_past(K, Om, starts[s], cidx, ridx, scale, X, lam)
                    if (not settled or abs(lam2 - starts[s]) > near
                            or abs(lam2 - lam) <= 1e-6 * (abs(lam) + scale)):
                        if deferred:
                            continue
                        bad = True
                        break
                    if lam2.real <= floor:
                        continue
                    lam, settled = _newton(K, Om, lam2, cidx, ridx, scale, y, True, X)
                    whole = False
                    if not settled or lam.real <= floor:
                        if deferred:
                            continue
                        bad = True
                        break
                dup = False
                for f in range(found):
                    if abs(lam_out[iq, f] - lam) <= 1e-9 * (abs(lam) + scale):
                        dup = True
                if dup:
                    continue
                if found >= max_modes:
                    if deferred:
                        continue
                    bad = True
                    break
                if whole:
                    for a in range(n):
                        vec_out[iq, found, a] = v[a] * sq[a % d]
                else:
                    for a in range(rc):  # X: T_RR^{-1} K_RC at lam, from Newton's last step
                        vec_out[iq, found, cidx[a]] = y[a] * sq[cidx[a] % d]
                    for a in range(nr):
                        acc = 0j
                        for b in range(rc):
                            acc += X[a, b] * y[b]
                        vec_out[iq, found, ridx[a]] = -acc * sq[ridx[a] % d]
                if deferred and not _kept(vec_out[iq, found], P, d):
                    continue  # a spread start counts only where it finds a kept mode
                lam_out[iq, found] = lam
                moved = max(moved, abs(lam - starts[s]))
                if lam.real > kept and _kept(vec_out[iq, found], P, d):
                    kept = lam.real
                found += 1
            count[iq] = -1 if bad else found
            s_moved[iq] = moved
            if not (bad and merged):
                break
            use_anchors = False
    return lam_out, vec_out, count
