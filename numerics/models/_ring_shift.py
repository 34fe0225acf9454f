"""The ring's translation along the wave for ``_strong.strong_modes``: the pencil at
q + k is the one at q shifted one harmonic (and the one at -q its mirror image), so an
offset takes its neighbours' starts and refined modes, moved over (``_strong``'s module
docstring). Split from ``_strong``.
"""

from __future__ import annotations

import numpy as np
from numba import njit

_KW = dict(cache=True, nogil=True, error_model="numpy", boundscheck=False)


@njit(**_KW)
def _neighbours(offsets, k):
    """For each offset t and sign sigma (+1, -1): the index j of the offset s with
    t = s' + sigma k (mod 2 pi), s' = s or -s (``mirror``), or -1. A mode at s' is one at
    s' + sigma k, one harmonic over and i sigma omega lower; at -s, its mirror image
    (lambda -> conj(lambda), l -> -l): the real lattice."""
    Q = offsets.size
    nb = np.full((Q, 2), -1, np.int64)
    mirror = np.zeros((Q, 2), np.bool_)
    for i in range(Q):
        for c in range(2):
            sigma = 1.0 if c == 0 else -1.0
            x = (offsets[i] - sigma * k) % (2 * np.pi)
            mir = x > np.pi
            if mir:
                x = 2 * np.pi - x
            for j in range(Q):
                if j != i and abs(offsets[j] - x) <= 1e-9:
                    nb[i, c] = j
                    mirror[i, c] = mir
                    break
    return nb, mirror


@njit(inline="always")
def _translate(c_s, v, P, d, sigma, mir):
    """A start's vector ``c_s`` moved from its source to this offset, into ``v``: the
    pencil at q + sigma k is the one at q shifted one harmonic, c_t[l] = c'[l + sigma]
    (zero past the truncation's edge), c'[l] = conj(c_s[-l]) where mirrored (the source
    at -q: lambda -> conj(lambda), l -> -l); sigma 0: the vector itself."""
    for li in range(2 * P + 1):
        ls = li - P + sigma
        if abs(ls) > P:
            for a in range(d):
                v[li * d + a] = 0.0
            continue
        if mir:
            ls = -ls
        for a in range(d):
            val = c_s[(ls + P) * d + a]
            v[li * d + a] = np.conj(val) if mir else val
