"""The growing modes of the Hill pencil where the Gershgorin clusters of ``_sidebands`` chain
(strong coupling, a flat branch: flexmm): the central harmonics' pencil, the outer ones
folded in, instead of the whole dense eigenproblem.

At offset q the scaled pencil is T(lambda) = (lambda - i Omega)^2 + K (``_sidebands``'s
module docstring), n = d (2 P + 1) coordinates. Split them into C, the harmonics
|l| <= P_C, and R, the outer ones. The eigenvalues are the zeros of the Schur complement
S(lambda) = T_CC(lambda) - K_CR T_RR(lambda)^{-1} K_RC. With the fold frozen at
lambda = 0 (the centre of the modes a kept mode can be: centred at l = -1, 0, 1), the
2 r_C eigenvalues of the frozen C pencil place the central spectrum at once (LAPACK on
2 r_C = 2 d (2 P_C + 1), against 2 n for the dense one); each of them that grows and
whose eigenvector is heaviest at |l| <= 2 (one inverse-iteration step) is refined
on the whole pencil at P, exact: nonlinear inverse iteration (``_refine``) from it and
its eigenvector (the C part from that step, the rest -T_RR(0)^{-1} K_RC y_C), whose
eigenvector gives the weights the kept modes are chosen by, as the dense eigenproblem's
do; where it does not settle, Newton on det S (``_sidebands._newton``: the mirror root
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
the whole pencil keeps it on the axis, or a mode Newton stepped past: Newton again from
the same start, the root found divided out, finds the partner (a second root on the axis
within 4x the first one's distance from the start: the pair is accounted for) or the
growing mode (kept as any other). Where Newton does not settle, or the partner is neither,
the caller solves that offset densely (stiff-hinge's bench point: 24 of 128 ring offsets
before this check, none with it).
"""

from __future__ import annotations

import numpy as np
from numba import njit

from ._sidebands import STEPS, TOL, _fold, _lu, _lu_solve, _newton, _schur, _small_pencil

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
def _central(K, Om, cidx, Sig, lam, lvec, P, sq, F, piv, B):
    """Whether the frozen pencil's eigenvector at ``lam`` (one inverse-iteration step) has
    its largest weight at |l| <= 2: a kept mode's (|l| <= 1 at P) with a harmonic's margin
    (the frozen pencil's weights are close to the exact ones, not equal)."""
    rc = cidx.size
    for a in range(rc):
        for b in range(rc):
            F[a, b] = K[cidx[a], cidx[b]] - Sig[a, b]
        z = lam - 1j * Om[cidx[a]]
        F[a, a] += z * z
        B[a, 0] = 1.0
    if not _lu(F, piv):
        return True
    _lu_solve(F, piv, B)
    per_l = np.zeros(2 * P + 1)
    for a in range(rc):
        per_l[lvec[a] + P] += abs(B[a, 0] * sq[cidx[a] % sq.size]) ** 2
    return abs(np.argmax(per_l) - P) <= 2


@njit(**_KW)
def _kept(vec, P, d):
    """The dense spectrum's rule (``_exact``): largest weight at |l| <= 1, less than 1e-6
    of it in the outer three harmonics."""
    per_l = np.zeros(2 * P + 1)
    tot = 0.0
    for i in range(vec.size):
        w = abs(vec[i]) ** 2
        per_l[i // d] += w
        tot += w
    outer = per_l[0] + per_l[1] + per_l[2] + per_l[-1] + per_l[-2] + per_l[-3]
    return abs(np.argmax(per_l) - P) <= 1 and outer < 1e-6 * tot


@njit(**_KW)
def _newton_past(Kt, Om, lam, cidx, ridx, scale, X, known):
    """Newton on det S(lambda) from ``lam`` with the root ``known`` divided out (Maehly, as
    ``_sidebands._newton`` divides out a growing iterate's mirror): the second root of a
    pair the frozen pencil placed off the axis. Returns (lambda, settled)."""
    rc = cidx.size
    S = np.empty((rc, rc), np.complex128)
    dS = np.empty((rc, rc), np.complex128)
    piv = np.empty(rc, np.int64)
    for _ in range(STEPS):
        if not _schur(Kt, Om, lam, cidx, ridx, X, S, dS):
            return lam, False
        if not _lu(S, piv):
            return lam, True  # exactly singular: an eigenvalue
        _lu_solve(S, piv, dS)
        tr = 0j
        for a in range(rc):
            tr += dS[a, a]
        if lam == known:
            return lam, False
        tr -= 1.0 / (lam - known)
        if lam.real > 1e-9 * scale:
            tr -= 1.0 / (2.0 * lam.real)
        if tr == 0:
            return lam, False
        step = -1.0 / tr
        lam += step
        if abs(step) <= TOL * (abs(lam) + scale):
            return lam, True
    return lam, False


@njit(**_KW)
def _refine(K, Om, lam, v, scale):
    """Nonlinear inverse iteration on the whole pencil T(lambda) = (lambda - i Omega)^2 + K
    (Ruhe's: w = T^{-1} T' v, lambda -= 1 / (v^* w), v = w / |w|; quadratic, Newton on det T
    for one coordinate) from ``lam`` and the frozen pencil's eigenvector ``v`` (unit norm,
    updated in place), until a step is below TOL, as ``_sidebands._newton``. One LAPACK
    solve of n x n a step, against the Schur complement's two solves and two products.
    Returns (lambda, settled)."""
    n = Om.size
    T = np.empty((n, n), np.complex128)
    rhs = np.empty(n, np.complex128)
    for _ in range(STEPS):
        for a in range(n):
            for b in range(n):
                T[a, b] = K[a, b]
            z = lam - 1j * Om[a]
            T[a, a] += z * z
            rhs[a] = 2 * z * v[a]
        try:
            w = np.linalg.solve(T, rhs)
        except Exception:  # exactly singular: lam is an eigenvalue, v not yet its vector
            return lam, False
        vw = 0j
        nrm = 0.0
        for a in range(n):
            vw += np.conj(v[a]) * w[a]
            nrm += abs(w[a]) ** 2
        if vw == 0 or not nrm > 0:
            return lam, False
        step = -1.0 / vw
        lam += step
        nrm = np.sqrt(nrm)
        for a in range(n):
            v[a] = w[a] / nrm
        if abs(step) <= TOL * (abs(lam) + scale):
            return lam, True
    return lam, False


@njit(**_KW)
def strong_modes(Hh, masses, k, omega, P, Pc, offsets, floor, max_modes):
    """For each offset: the growing eigenvalues Newton reaches from the central frozen
    pencil's growing (or colliding) eigenvalues, with their eigenvectors in the
    harmonics' coordinates (field-major inside a harmonic, as ``_exact``'s dense pencil).

    Returns lam (Q, max_modes) complex, vec (Q, max_modes, n) complex, count (Q,) int:
    -1 where the offset needs the dense eigenproblem.
    """
    d = masses.size
    nl = 2 * P + 1
    n = d * nl
    Q = offsets.size
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
    eq = np.empty(nl, np.complex128)
    K = np.empty((n, n), np.complex128)
    X = np.empty((nr, rc), np.complex128)
    X0 = np.empty((nr, rc), np.complex128)
    y = np.empty(rc, np.complex128)
    v = np.empty(n, np.complex128)
    scale = omega
    lvec = np.empty(rc, np.int64)
    for a in range(rc):
        lvec[a] = cidx[a] // d - P
    F = np.empty((rc, rc), np.complex128)
    B = np.empty((rc, 1), np.complex128)
    piv = np.empty(rc, np.int64)
    for iq in range(Q):
        q = offsets[iq]
        for li in range(nl):
            eq[li] = np.exp(1j * (q + (li - P) * k))
        for li in range(nl):
            el = np.conj(eq[li])
            for hi_ in range(nl):
                s = li - hi_ + 2 * P
                eh = eq[hi_]
                for a in range(d):
                    for b in range(d):
                        val = (Hh[s, a, b] + Hh[s, a, d + b] * eh + Hh[s, d + a, b] * el
                               + Hh[s, d + a, d + b] * ed[s])
                        K[li * d + a, hi_ * d + b] = val * sq[a] * sq[b]
        Sig, ok = _fold(K, Om, 0j, cidx, ridx, X)
        if not ok:
            count[iq] = -1
            continue
        X0[:, :] = X  # the fold's T_RR(0)^{-1} K_RC: the frozen eigenvectors' rest
        lam0 = _small_pencil(K, Om, cidx, Sig)
        # starts: each growing frozen eigenvalue; each pair close on the axis, from between
        starts = np.empty(lam0.size * 2, np.complex128)
        gaps = np.empty(lam0.size * 2)
        ns = 0
        for s in range(lam0.size):
            if lam0[s].real > 1e-9 * omega:
                starts[ns] = lam0[s]
                gaps[ns] = 0.0
                ns += 1
        order = np.argsort(lam0.imag)
        for t in range(lam0.size - 1):
            a0, b0 = lam0[order[t]], lam0[order[t + 1]]
            if abs(a0.real) > 1e-9 * omega or abs(b0.real) > 1e-9 * omega:
                continue
            gap = b0.imag - a0.imag
            if gap < 1e-2 * omega and ns < starts.size:
                starts[ns] = 0.5 * (a0 + b0) + 0.5 * gap
                gaps[ns] = 0.5 * gap
                ns += 1
        # fastest first: once a kept mode is refined, a start whose rate cannot reach it
        # (its frozen rate, or half its pair's gap, plus 10x the largest move a refined
        # start made at this offset) is left
        reach = np.empty(ns)
        for s in range(ns):
            reach[s] = starts[s].real if starts[s].real > 1e-9 * omega else 0.0
        first = np.argsort(-reach)
        found = 0
        bad = False
        kept = 0.0
        moved = 1e-9 * omega
        for t in range(ns):
            s = first[t]
            if kept > 0 and reach[s] + gaps[s] + 10 * moved < kept:
                break
            if not _central(K, Om, cidx, Sig, starts[s], lvec, P, sq, F, piv, B):
                continue
            # the whole eigenvector from the frozen one (B: its C part), refined on the
            # whole pencil; Newton on the Schur complement where that does not settle
            nrm = 0.0
            for a in range(rc):
                v[cidx[a]] = B[a, 0]
            for a in range(nr):
                acc = 0j
                for b in range(rc):
                    acc += X0[a, b] * B[b, 0]
                v[ridx[a]] = -acc
            for a in range(n):
                nrm += abs(v[a]) ** 2
            for a in range(n):
                v[a] /= np.sqrt(nrm)
            lam, settled = _refine(K, Om, starts[s], v, scale)
            whole = settled and lam.real >= -floor
            if not whole:
                lam, settled = _newton(K, Om, starts[s], cidx, ridx, scale, y, True, X)
            if not whole and (not settled or lam.real < -floor):
                lam, settled = _newton(K, Om, starts[s], cidx, ridx, scale, y, False, X)
            if not settled:
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
                lam2, settled = _newton_past(K, Om, starts[s], cidx, ridx, scale, X, lam)
                if (not settled or abs(lam2 - starts[s]) > near
                        or abs(lam2 - lam) <= 1e-6 * (abs(lam) + scale)):
                    bad = True
                    break
                if lam2.real <= floor:
                    continue
                lam, settled = _newton(K, Om, lam2, cidx, ridx, scale, y, True, X)
                whole = False
                if not settled or lam.real <= floor:
                    bad = True
                    break
            dup = False
            for f in range(found):
                if abs(lam_out[iq, f] - lam) <= 1e-9 * (abs(lam) + scale):
                    dup = True
            if dup:
                continue
            if found >= max_modes:
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
            lam_out[iq, found] = lam
            moved = max(moved, abs(lam - starts[s]))
            if lam.real > kept and _kept(vec_out[iq, found], P, d):
                kept = lam.real
            found += 1
        count[iq] = -1 if bad else found
    return lam_out, vec_out, count
