"""Where ``_sidebands.sideband_modes`` must give up on an offset, told from the central
harmonics' discs alone (issue 41: flexmm's ring spent ~5 ms of its ~55 there, building the
whole rotated pencil at each of 128 offsets only to find its clusters chain).

``sideband_modes`` gives an offset up (count -1, the strong-coupling path's) where a
cluster of Gershgorin discs that can hold a growing central mode (a root of a harmonic
|l| <= 1, and roots of both Krein signs or a joint disc) has more than ``max_cluster``
coordinates. Each disc is its own coordinate's: its centre, its root w and its radius come
from that coordinate's row of the rotated pencil alone. So the discs of a subset of the
coordinates, those of the harmonics |l| <= L, computed with the same arithmetic (the same
bits), are a subset of the discs, and a cluster of the subset lies inside one cluster of
all of them, which holds its roots, its signs and more coordinates. Where the subset
already has such a cluster, the whole does too: the offset is given up, exactly as the full
pass would. Where it has none, nothing is concluded and the full pass runs. A row of the
rotated pencil costs its n entries, so the subset costs ~(2L + 1) / (2P + 1) of the full
pass (flexmm, P = 10, L = 2: ~1/4).
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

from ._small_algebra import _eigh2

_KW = dict(cache=True, nogil=True, error_model="numpy", boundscheck=False)


@njit(**_KW)
def pencil_parts(Hh, sq, ed):
    """The q-independent parts of the scaled pencil's blocks (K(q) from them:
    ``_sidebands._pencil_from_parts``, the one builder of the pencil):
    block (l, h) = AD_s + B_s e^{i (q + h k)} + C_s e^{-i (q + l k)}, s = l - h + 2P, with
    AD_s = M^{-1/2} (Hhat_s[:d, :d] + Hhat_s[d:, d:] e^{-i (l - h) k}) M^{-1/2} and B_s,
    C_s the off-diagonal quarters Hhat_s[:d, d:], Hhat_s[d:, :d], scaled alike. Shape
    (3, 4P + 1, d, d). Computed once per call of ``sideband_modes`` (and of
    ``_strong.strong_modes``): an entry then costs two complex products, not three and a
    scaling (and the q-independent phase e^{-i (l - h) k} is no longer taken per entry)."""
    ns = Hh.shape[0]
    d = sq.size
    out = np.empty((3, ns, d, d), np.complex128)
    for s in range(ns):
        for a in range(d):
            for b in range(d):
                f = sq[a] * sq[b]
                out[0, s, a, b] = (Hh[s, a, b] + Hh[s, d + a, d + b] * ed[s]) * f
                out[1, s, a, b] = Hh[s, a, d + b] * f
                out[2, s, a, b] = Hh[s, d + a, b] * f
    return out


@njit(**_KW)
def central_chain(Hh, sq, k, P, q, omega, L, max_cluster, ed, eq):
    """True where the discs of the harmonics |l| <= L at offset ``q`` already hold a cluster
    ``sideband_modes`` gives up on (module docstring): central, with roots of both Krein
    signs or a joint disc, more than ``max_cluster`` coordinates. ``Hh``: the Hessian's
    harmonics as ``sideband_modes`` uses them (round-off dropped); ``ed``: its
    e^{-i (s - 2P) k}; ``eq`` (shape (2P + 1,)) gets the copies' phases. Each number is
    computed as ``sideband_modes`` computes it (``pencil_parts``, then the same
    operations in the same order), so the discs are theirs to the bit."""
    d = sq.size
    nl = 2 * P + 1
    n = d * nl
    parts = pencil_parts(Hh, sq, ed)  # the same function, the same bits as the full pass
    for li in range(nl):
        eq[li] = np.exp(1j * (q + (li - P) * k))
    # each harmonic's diagonal block and its rotation V_l (every harmonic's: the columns)
    w2 = np.empty(n)
    V = np.zeros((n, d), np.complex128)  # V[l d + b, a] = (V_l)[b, a]
    blk = np.empty((d, d), np.complex128)
    Kll = np.empty((d, d), np.complex128)
    ev2 = np.empty(2)
    evec2 = np.empty((2, 2), np.complex128)
    for li in range(nl):
        el = np.conj(eq[li])
        s = 2 * P
        eh = eq[li]
        for a in range(d):
            for b in range(d):
                Kll[a, b] = parts[0, s, a, b] + parts[1, s, a, b] * eh + parts[2, s, a, b] * el
        if d == 1:
            w2[li] = Kll[0, 0].real
            V[li, 0] = 1.0
            continue
        for a in range(d):
            for b in range(d):
                blk[a, b] = 0.5 * (Kll[a, b] + np.conj(Kll[b, a]))
        if d == 2:
            _eigh2(blk, ev2, evec2)
            ev, evec = ev2, evec2
        else:
            ev, evec = np.linalg.eigh(blk)
        for a in range(d):
            w2[li * d + a] = ev[a]
            for b in range(d):
                V[li * d + b, a] = evec[b, a]
    # the rows of |l| <= L: their radii (the off-diagonal blocks' row sums), their discs
    lo_l = P - L
    m_rows = d * (2 * L + 1)
    lo_ = np.empty(2 * m_rows)
    hi_ = np.empty(2 * m_rows)
    sg = np.empty(2 * m_rows, np.int64)
    co = np.empty(2 * m_rows, np.int64)
    Krow = np.empty((d, n), np.complex128)
    m = 0
    for li in range(lo_l, P + L + 1):
        el = np.conj(eq[li])
        for hi2 in range(nl):
            s = li - hi2 + 2 * P
            eh = eq[hi2]
            for a in range(d):
                for b in range(d):
                    Krow[a, hi2 * d + b] = (parts[0, s, a, b] + parts[1, s, a, b] * eh
                                            + parts[2, s, a, b] * el)
        for a in range(d):
            i = li * d + a
            r = 0.0
            for hi2 in range(nl):
                if hi2 == li:
                    continue
                for b in range(d):
                    if d == 1:
                        v = Krow[0, hi2]
                    else:
                        nz = False
                        for c in range(d):
                            for e in range(d):
                                nz |= Krow[c, hi2 * d + e] != 0
                        if not nz:
                            v = 0j
                        else:  # K_lh V_h, then V_l^*: ``sideband_modes``' order
                            v = 0j
                            for c in range(d):
                                acc = 0j
                                for e in range(d):
                                    acc += Krow[c, hi2 * d + e] * V[hi2 * d + e, b]
                                v += np.conj(V[li * d + c, a]) * acc
                    r += math.sqrt(v.real * v.real + v.imag * v.imag)
            c0 = (li - P) * omega
            if w2[i] > r:
                w = math.sqrt(w2[i])
                rho = w - math.sqrt(w2[i] - r)
                for sgn in (1, -1):
                    lo_[m] = c0 + sgn * w - rho
                    hi_[m] = c0 + sgn * w + rho
                    sg[m] = sgn
                    co[m] = i
                    m += 1
            else:
                rho = math.sqrt(abs(w2[i]) + r)
                lo_[m] = c0 - rho
                hi_[m] = c0 + rho
                sg[m] = 0
                co[m] = i
                m += 1
    order = np.argsort(lo_[:m])
    start = 0
    mark = np.full(n, -1, np.int64)  # the cluster a coordinate was last counted in
    while start < m:
        end = start + 1
        top = hi_[order[start]]
        while end < m and lo_[order[end]] <= top:
            top = max(top, hi_[order[end]])
            end += 1
        plus = minus = joint = central = False
        size = 0
        for t in range(start, end):
            j = order[t]
            plus |= sg[j] == 1
            minus |= sg[j] == -1
            joint |= sg[j] == 0
            central |= abs(co[j] // d - P) <= 1
            if mark[co[j]] != start:
                mark[co[j]] = start
                size += 1
        if central and (joint or (plus and minus)) and size > max_cluster:
            return True
        start = end
    return False
