"""The carrier's dispersion sheet followed through avoided crossings, by its eigenvector.

Where every field is linearly coupled to the others (``field_groups``: one group) the branch
indices are the adiabatic sheets: a weak linear coupling turns a crossing of two fields'
branches into an avoided one, and the lower index passes from one field's wave to the
other's inside a window of width w ~ gap / |v1 - v2| about the crossing. A pair whose waves
lie farther from that crossing than w is a pair of the carrier's own field's waves, on the
other index past the crossing (the cross chain with a bond term 1e-3 (u_next - u) v: both
waves of the fastest pair are u waves, 0.03 past the crossing, the window 1e-3 wide).

The rule (no threshold on the gap): walk the wavenumber from the carrier's k to the wave's;
at each local minimum kc of the separation of the followed branch c from a neighbour c'
(the centre of a possible avoided crossing), look at the eigenvectors as far on either side
as the walk allows, kc -+ D, D = min(|kc - k|, |end - kc|): the walk passes to c' where
the followed wave's (mass-weighted) eigenvector at kc - D overlaps c' at kc + D more than c.
That is where the window is narrower than the distance to both ends (the mixing angle
theta at kc + D has tan 2 theta < 1): the wave at the far end carries the carrier's field;
a gap wider than that (a strongly hybridised branch, diatomic FPUT's gap at pi, where the
eigenvectors do not swap) keeps the index.
"""

from __future__ import annotations

import math

import numpy as np

from energy import Model

#: the walk's grid step (rad/site): it only locates the separation's local minima (each
#: minimum, however narrow its gap, lies between a grid point's two neighbours); the
#: decision at each is the eigenvectors' at kc -+ D, not the step's
_STEP = math.pi / 512


def _eig(model, kappas):
    """omega^2 (ascending) and the mass-weighted eigenvectors at each of ``kappas``
    (``model``: the pair (rest Hessian, 1 / sqrt(masses)))."""
    from ._linear import dynamical_matrix

    H, s = model
    D = np.stack([s[:, None] * dynamical_matrix(H, float(x)) * s[None, :]
                  for x in np.atleast_1d(kappas)])
    return np.linalg.eigh(D)


def _minimum(model, a, b, c, c2, iters=60):
    """The separation |omega_c^2 - omega_c2^2|'s minimum in [a, b] (golden section)."""
    g = (math.sqrt(5) - 1) / 2

    def sep(x):
        w = _eig(model, [x])[0][0]
        return abs(w[c2] - w[c])

    x1, x2 = b - g * (b - a), a + g * (b - a)
    f1, f2 = sep(x1), sep(x2)
    for _ in range(iters):
        if abs(b - a) < 1e-12:
            break
        if f1 <= f2:
            b, x2, f2 = x2, x1, f1
            x1 = b - g * (b - a)
            f1 = sep(x1)
        else:
            a, x1, f1 = x1, x2, f2
            x2 = a + g * (b - a)
            f2 = sep(x2)
    return (a + b) / 2


def _candidates(model, k: float, span: float):
    """The local minima (kc, lower branch index) of each adjacent branch pair's
    separation along the walk k -> k + span (span signed), nearest to k first."""
    d = model[1].size
    if d < 2 or span == 0:
        return []
    n = max(8, int(math.ceil(abs(span) / _STEP))) + 1
    x = k + np.linspace(0.0, span, n)
    w2 = _eig(model, x)[0]
    sep = np.diff(w2, axis=1)  # (n, d - 1): branch c + 1 minus c
    out = []
    for c in range(d - 1):
        s = sep[:, c]
        for i in np.flatnonzero((s[1:-1] < s[:-2]) & (s[1:-1] <= s[2:])) + 1:
            lo, hi = sorted((x[i - 1], x[i + 1]))
            out.append((_minimum(model, lo, hi, c, c + 1), c))
    out.sort(key=lambda t: abs(t[0] - k))
    return out


def _follow(model, k: float, branch: int, end: float, cands) -> int:
    """The branch index at ``end`` (unwrapped) of the carrier's sheet (k, branch)."""
    c = int(branch)
    for kc, lower in cands:
        if not (min(k, end) < kc < max(k, end)):
            continue
        if c not in (lower, lower + 1):
            continue
        other = lower + 1 if c == lower else lower
        D = min(abs(kc - k), abs(end - kc))
        if D < 1e-9:  # a crossing at an end: its eigenvectors there are either wave's
            continue
        sgn = 1.0 if end > k else -1.0
        vecs = _eig(model, [kc - sgn * D, kc + sgn * D])[1]
        before, after = vecs[0][:, c], vecs[1]
        if abs(np.vdot(before, after[:, other])) > abs(np.vdot(before, after[:, c])):
            c = other
    return c


def followed_branches(model: Model, k: float, branch: int, ends) -> np.ndarray:
    """The branch index of the carrier's sheet (k, ``branch``) at each of ``ends``,
    followed by its eigenvector from k (module docstring): ``ends`` are unwrapped
    wavenumbers (k + q, k - q for a pair of offset q; the walk goes the short way
    through them). ``branch`` itself where no avoided crossing lies between."""
    ends = np.atleast_1d(np.asarray(ends, dtype=float))
    out = np.full(ends.size, int(branch))
    if model.n_fields < 2 or ends.size == 0:
        return out
    model = (model.code.taylor(model.p)[0], 1 / np.sqrt(model.masses))
    up = ends > k
    for mask, sgn in ((up, 1.0), (~up, -1.0)):
        if not mask.any():
            continue
        span = float(np.max(np.abs(ends[mask] - k))) * sgn
        cands = _candidates(model, float(k), span)
        if not cands:
            continue
        for i in np.flatnonzero(mask):
            out[i] = _follow(model, float(k), int(branch), float(ends[i]), cands)
    return out
