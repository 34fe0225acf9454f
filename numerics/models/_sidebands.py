"""The growing modes of the Hill pencil of ``_exact`` at many offsets, compiled: what the
dense eigenproblem per offset gave, at the cost of a few small solves.

At offset q the pencil is Q(lambda) = M (lambda - i Omega)^2 + L(q), Omega = diag(l omega),
L(q) Hermitian (the cell Hessian's Fourier coefficients, ``_exact``'s module docstring).
Scaled by M^{-1/2} and with each harmonic's diagonal block diagonalised
(V_l^* M^{-1/2} L_ll M^{-1/2} V_l = diag w_lj^2), it is

    T(lambda) = diag((lambda - i l omega)^2 + w_lj^2) + E,   E Hermitian, zero on the
                                                             diagonal blocks,

whose roots at E = 0 are lambda = i (l omega +- w_lj), each with the Krein sign +-.

Which offsets can grow (certified, not sampled). An eigenvalue lies where some
|(lambda - i l omega)^2 + w_lj^2| <= R_lj, R_lj the row sum of |E| (a Gershgorin bound for
the block-diagonal part), so in discs on the imaginary axis about the roots (radius
w - sqrt(w^2 - R), or one disc sqrt(|w^2| + R) about i l omega for both roots where
w^2 <= R). Along E -> t E, t in [0, 1] the discs only shrink, so each connected cluster of
discs holds as many eigenvalues as roots; the spectrum is symmetric under
lambda -> -conj(lambda) and so is each cluster: a cluster of one root keeps its eigenvalue
on the axis. So does a cluster whose roots all have one Krein sign (the form the pencil is
self-adjoint in is definite on its spectral subspace, for every t). Only a cluster with
roots of both signs, or a joint disc, can hold a growing mode. A mode the theory keeps has
its largest weight at l = -1, 0 or 1, and an eigenvector's largest coordinate lies in its
eigenvalue's cluster (outside it |y_i| = |(E y)_i| / |f_i| < max |y|, since |f_i| > R_i
there): only clusters holding a root of those harmonics are solved. (Exact for one field;
with several the weight sums a harmonic's fields over their masses, and the largest
coordinate and the heaviest harmonic could differ: the anchors hold it on two-field
models.)

Solving a cluster (``_cluster_solve``): the rest of the pencil folded in by its Schur
complement, the frozen pencil's eigenvalues as starts, Newton on det S from each that
grows; where Newton does not settle, or a cluster is larger than the caller allows, the
caller solves that offset densely.

Cost (measured, bench/README.md "Hill kernel per offset"): an offset costs its pencil
and discs (~8 us at one field, P = 10) plus one LU of the rest T_RR (n_R = d (2P + 1) -
r_C coordinates) per fold and per Newton step, and one for the eigenvector: ~4 for a
cluster with one growing mode. Offsets differ by their clusters (none, one without a
growing start, one or two growing), by n_R (two fields or the P + 4 check: n_R 27-39,
the LU 3-6x a one-field one), not by Newton's iterations (2-3 from the frozen pencil's
start) nor by dense fallbacks (none at the bench points). The LU skips exact zeros, and
the Hessian's harmonics below the DFT's round-off are made exact zeros
(``_small_algebra._drop_roundoff``): a symmetric potential's odd harmonics vanish, its
rest splits into odd and even copies, and each LU costs about a quarter. Where the
clusters chain (flexmm), the discs of the central harmonics alone already show the offset
given up (``_chaining``: the same discs, the same verdict, ~1/3 of the full pass).
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

from ._chaining import central_chain, pencil_parts
from ._cluster_solve import _offset
from ._small_algebra import _drop_roundoff, _eigh2

_KW = dict(cache=True, nogil=True, error_model="numpy", boundscheck=False)


@njit(**_KW)
def _pencil_from_parts(parts, P, k, q, eq, K):
    """K(q) of the scaled pencil into ``K`` from its q-independent parts
    (``_chaining.pencil_parts``): block (l, h) = AD_s + B_s e^{i (q + h k)} + C_s
    e^{-i (q + l k)}, s = l - h + 2P; ``eq`` gets the phases e^{i (q + l k)}. The same
    operations in the same order as ``_chaining.central_chain`` (the same bits). One field
    apart: the blocks are numbers (the generic loop's d x d inner loops cost ~5x there)."""
    d = parts.shape[2]
    nl = 2 * P + 1
    for li in range(nl):
        eq[li] = np.exp(1j * (q + (li - P) * k))
    if d == 1:
        AD, B, C = parts[0, :, 0, 0], parts[1, :, 0, 0], parts[2, :, 0, 0]
        for li in range(nl):
            el = np.conj(eq[li])
            for hi_ in range(nl):
                s = li - hi_ + 2 * P
                K[li, hi_] = AD[s] + B[s] * eq[hi_] + C[s] * el
        return
    if d == 2:  # unrolled: the same expressions, in registers
        for li in range(nl):
            el = np.conj(eq[li])
            r = 2 * li
            for hi_ in range(nl):
                s = li - hi_ + 2 * P
                eh = eq[hi_]
                c = 2 * hi_
                K[r, c] = parts[0, s, 0, 0] + parts[1, s, 0, 0] * eh + parts[2, s, 0, 0] * el
                K[r, c + 1] = (parts[0, s, 0, 1] + parts[1, s, 0, 1] * eh
                               + parts[2, s, 0, 1] * el)
                K[r + 1, c] = (parts[0, s, 1, 0] + parts[1, s, 1, 0] * eh
                               + parts[2, s, 1, 0] * el)
                K[r + 1, c + 1] = (parts[0, s, 1, 1] + parts[1, s, 1, 1] * eh
                                   + parts[2, s, 1, 1] * el)
        return
    for li in range(nl):
        el = np.conj(eq[li])
        for hi_ in range(nl):
            s = li - hi_ + 2 * P
            eh = eq[hi_]
            for a in range(d):
                for b in range(d):
                    K[li * d + a, hi_ * d + b] = (parts[0, s, a, b] + parts[1, s, a, b] * eh
                                                  + parts[2, s, a, b] * el)


@njit(**_KW)
def sideband_modes(Hh, masses, k, omega, P, offsets, floor, max_modes, max_cluster,
                   pretest=True, zero_only=False):
    """For each offset: the growing eigenvalues of every cluster that can hold a mode
    centred at l = -1, 0, 1 (module docstring), with their eigenvectors in the harmonics'
    coordinates (field-major inside a harmonic, as ``_exact``'s dense pencil).

    Returns lam (Q, max_modes) complex (count per offset in ``count``), vec
    (Q, max_modes, n) complex, count (Q,) int: -1 where the offset needs the dense
    eigenproblem (an iteration did not settle, more growing modes than max_modes, or a
    cluster of more than max_cluster coordinates: strong coupling or a flat branch whose
    copies l omega + w and (l + 2) omega - w meet at every harmonic chain the discs).
    ``pretest``: that last case told from the central harmonics' discs first where it can
    be (``_chaining``; False: the full pass at every offset, the same answers).
    ``zero_only``: only the clusters that hold a root of l = 0 (``_ring_copies``: on a
    ring the other central modes are copies found so at the offsets q +- k, q +- 2k).
    """
    d = masses.size
    nl = 2 * P + 1
    n = d * nl
    Q = offsets.size
    Hh = _drop_roundoff(Hh)
    lam_out = np.zeros((Q, max_modes), np.complex128)
    vec_out = np.zeros((Q, max_modes, n), np.complex128)
    count = np.zeros(Q, np.int64)
    sq = 1.0 / np.sqrt(masses)
    sq_n = np.empty(n)
    for i in range(n):
        sq_n[i] = sq[i % d]
    Om = np.empty(n)
    lvec = np.empty(n, np.int64)
    asked = np.empty(n, np.bool_)  # the coordinates whose clusters are solved
    for li in range(nl):
        for a in range(d):
            Om[li * d + a] = (li - P) * omega
            lvec[li * d + a] = li - P
            asked[li * d + a] = li == P if zero_only else abs(li - P) <= 1
    K = np.empty((n, n), np.complex128)
    V = np.zeros((n, n), np.complex128)
    w2 = np.empty(n)
    Rrow = np.empty(n)
    ed = np.empty(4 * P + 1, np.complex128)
    for s in range(4 * P + 1):
        ed[s] = np.exp(-1j * (s - 2 * P) * k)
    parts = pencil_parts(Hh, sq, ed)
    eq = np.empty(nl, np.complex128)
    W = np.empty((d, d), np.complex128)
    blk = np.empty((d, d), np.complex128)
    ev2 = np.empty(2)
    evec2 = np.empty((2, 2), np.complex128)
    Kt = np.empty((n, n), np.complex128)
    # a cluster's modes (``_offset`` writes every coordinate of each it reports)
    lam_c = np.empty(max_modes, np.complex128)
    vec_c = np.empty((max_modes, n), np.complex128)
    # the central harmonics |l| <= L, one more than needed to hold more than max_cluster
    # coordinates: their discs alone may already show the offset given up (``_chaining``:
    # the same discs, the same verdict), tried while the offset before was given up so.
    # Measured (ring of 256): flexmm's bench point shows it at 100 of 128 offsets with
    # L = 2, at all with 3 (its cost ~1/3 of the full pass's); stiff-hinge's at all with 2
    L = 2
    while d * (2 * L - 1) <= max_cluster:
        L += 1
    chained = pretest and L < P
    for iq in range(Q):
        q = offsets[iq]
        if chained:
            chained = central_chain(Hh, sq, k, P, q, omega, L, max_cluster, ed, eq)
            if chained:
                count[iq] = -1
                continue
        # L(q), scaled: block (l, h) = A + B e^{i th_h} + C e^{-i th_l} + D e^{-i (l-h) k}
        _pencil_from_parts(parts, P, k, q, eq, K)
        if d == 1:  # the diagonal "blocks" are numbers: no rotation
            for i in range(n):
                w2[i] = K[i, i].real
            Kt[:, :] = K
        else:  # each harmonic's diagonal block diagonalised
            for li in range(nl):
                for a in range(d):
                    for b in range(d):
                        blk[a, b] = 0.5 * (K[li * d + a, li * d + b]
                                           + np.conj(K[li * d + b, li * d + a]))
                if d == 2:
                    _eigh2(blk, ev2, evec2)
                    ev, evec = ev2, evec2
                else:
                    ev, evec = np.linalg.eigh(blk)
                for a in range(d):
                    w2[li * d + a] = ev[a]
                    for b in range(d):
                        V[li * d + b, li * d + a] = evec[b, a]
            # Kt = V^* K V, block by block (V is block diagonal); a zero block (its
            # harmonic dropped as round-off) stays exactly zero
            for li in range(nl):
                for hi_ in range(nl):
                    nz = False
                    for c in range(d):
                        for e in range(d):
                            nz |= K[li * d + c, hi_ * d + e] != 0
                    if not nz:
                        for a in range(d):
                            for b in range(d):
                                Kt[li * d + a, hi_ * d + b] = 0.0
                        continue
                    # K_lh V_h first, then V_l^* (2 d^3 products, not 2 d^4; the
                    # order ``_chaining.central_chain`` uses: the same bits)
                    for c in range(d):
                        for b in range(d):
                            acc = 0j
                            for e in range(d):
                                acc += K[li * d + c, hi_ * d + e] * V[hi_ * d + e, hi_ * d + b]
                            W[c, b] = acc
                    for a in range(d):
                        for b in range(d):
                            acc = 0j
                            for c in range(d):
                                acc += np.conj(V[li * d + c, li * d + a]) * W[c, b]
                            Kt[li * d + a, hi_ * d + b] = acc
        for i in range(n):
            # the other harmonics' columns, in order: [0, b0) and [b0 + d, n)
            b0 = (i // d) * d
            r = 0.0
            for j in range(b0):
                # |z| without hypot's scaling (entries are O(1)): ~8x cheaper,
                # within an ulp
                v = Kt[i, j]
                r += math.sqrt(v.real * v.real + v.imag * v.imag)
            for j in range(b0 + d, n):
                v = Kt[i, j]
                r += math.sqrt(v.real * v.real + v.imag * v.imag)
            Rrow[i] = r
            # the diagonal block is diag(w^2) exactly in these coordinates
            for j in range(b0, b0 + d):
                Kt[i, j] = w2[i] if i == j else 0.0
        # roots and their discs: (lo, hi, sign, coordinate); sign 0: a joint disc
        m = 0
        lo_ = np.empty(2 * n)
        hi2 = np.empty(2 * n)
        sg = np.empty(2 * n, np.int64)
        co = np.empty(2 * n, np.int64)
        for i in range(n):
            c = Om[i]
            if w2[i] > Rrow[i]:
                w = math.sqrt(w2[i])
                rho = w - math.sqrt(w2[i] - Rrow[i])
                for sgn in (1, -1):
                    lo_[m] = c + sgn * w - rho
                    hi2[m] = c + sgn * w + rho
                    sg[m] = sgn
                    co[m] = i
                    m += 1
            else:
                rho = math.sqrt(abs(w2[i]) + Rrow[i])
                lo_[m] = c - rho
                hi2[m] = c + rho
                sg[m] = 0
                co[m] = i
                m += 1
        order = np.argsort(lo_[:m])
        found = 0
        start = 0
        bad = False
        while start < m and not bad:
            end = start + 1
            top = hi2[order[start]]
            while end < m and lo_[order[end]] <= top:
                top = max(top, hi2[order[end]])
                end += 1
            plus = minus = joint = central = False
            for t in range(start, end):
                j = order[t]
                plus |= sg[j] == 1
                minus |= sg[j] == -1
                joint |= sg[j] == 0
                central |= asked[co[j]]
            if central and (joint or (plus and minus)):
                inC = np.zeros(n, np.bool_)
                for t in range(start, end):
                    inC[co[order[t]]] = True
                cidx = np.flatnonzero(inC)
                ridx = np.flatnonzero(~inC)
                if cidx.size > max_cluster:
                    bad = chained = True
                    break
                got = _offset(Kt, Om, lvec, cidx, ridx, lo_[order[start]], top, floor,
                              omega, lam_c, vec_c)
                if got < 0 or found + got > max_modes:
                    bad = True
                else:
                    for g in range(got):
                        lam_out[iq, found] = lam_c[g]
                        # back to the harmonics' coordinates: M^{-1/2} V y
                        if d == 1:
                            vec_out[iq, found] = vec_c[g] * sq_n
                        else:
                            vec_out[iq, found] = (V @ vec_c[g]) * sq_n
                        found += 1
            start = end
        count[iq] = -1 if bad else found
    return lam_out, vec_out, count
