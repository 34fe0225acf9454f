"""The kept modes' rule of the compiled Hill spectrum (``_exact._Sidebands._keep``) for the
rates alone, compiled: a damped point's lower amplitudes ask only the growth rate per
offset (issue 42), and numpy's dozen array passes over (offsets, modes, coordinates) cost
more there than the rule's arithmetic.

The rule, the dense spectrum's (``_exact._centre``): a mode is kept where its
eigenvector's harmonic weights (|y|^2 summed over the fields of a harmonic, normalised)
are centred at |l| <= 1 (the mean of the harmonics within ``CENTRE_TIE`` of the largest
weight: the heaviest one where none ties) and less than 1e-6 of it lies in the outer
three harmonics on each side; an offset's rate is the largest real part of its kept
modes, where above ``floor``.
"""

from __future__ import annotations

import numpy as np
from numba import njit


@njit(cache=True, nogil=True, error_model="numpy", boundscheck=False)
def kept_gains(lam, vec, count, P, d, floor, gains, tie):
    """Each offset's kept rate into ``gains`` (left as it is where no kept mode grows, or
    where ``count`` is -1: the caller's dense path). lam (Q, modes) complex, vec
    (Q, modes, (2P + 1) d) complex (harmonic-major, field-minor), count (Q,): the modes
    found per offset (``_sidebands.sideband_modes``); ``tie``: ``_exact.CENTRE_TIE``."""
    nl = 2 * P + 1
    per_l = np.empty(nl)
    for i in range(count.size):
        best = -np.inf
        for m in range(count[i]):
            total = 0.0
            for j in range(nl * d):
                a = abs(vec[i, m, j])
                total += a * a
            total = max(total, 1e-300)
            top = -1.0
            for li in range(nl):
                w = 0.0
                for f in range(d):
                    a = abs(vec[i, m, li * d + f])
                    w += (a * a) / total
                per_l[li] = w
                top = max(top, w)
            # the tie's mean harmonic (``_exact._centre``; integer sums: exact)
            level = (1 - tie) * top
            n_tied, l_sum = 0, 0
            for li in range(nl):
                if per_l[li] >= level:
                    n_tied += 1
                    l_sum += li - P
            outer = (per_l[0] + per_l[1] + per_l[2]) + (per_l[nl - 3] + per_l[nl - 2]
                                                        + per_l[nl - 1])
            if abs(l_sum / n_tied) <= 1 and outer < 1e-6 and lam[i, m].real > best:
                best = lam[i, m].real
        if best > floor:
            gains[i] = best
