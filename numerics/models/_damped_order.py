"""Which damped root continues which lossless branch (probe 96).

``_linear._damped_many`` picks each wavenumber's d forward roots of the damped symbol
det(K - i w C - w^2 M) = 0 and listed them by ascending Re w, which is the lossless
branches' order (``branches``) only while no damping reorders them. A strong damping of an
upper branch makes it overdamped (Re w = 0) and lists it first: a mass-in-mass chain with
a dashpot c = 0.7 on its inner mass (k 0.5) gave its acoustic carrier the optical pair's
rate, 0.672 where its own is 0.0105 (65x; continuous in c up to 0.6, 0.0104). Here each
root goes to the lossless branch whose mode shape it keeps: the overlap of the root's null
vector of the (mass-weighted) symbol with each lossless eigenvector, assigned greedily
(largest overlap first), the oscillating roots (Re w > 0) before the overdamped ones
(probe 98: a resonator damped past critical, gamma 3 at k 0.3, leaves a slow relaxation of
the resonator with the chain following it, Re w = 0, whose shape overlaps the lower branch
as much as the chain's oscillation does, 0.947 against 0.921: the carrier took its rate,
0.210 where the root that continues the carrier from zero damping decays at 0.055, a jump
from 0.066 at gamma 2.5; an overdamped root continues a branch whose pair met on the
imaginary axis, never one that still oscillates). Where that is the ascending order
already (every weak damping), the roots are returned as they came, to the bit.
"""

from __future__ import annotations

import numpy as np


def lossless_order(K: np.ndarray, C: np.ndarray, w2: np.ndarray, roots: np.ndarray):
    """``roots`` (n, d), each row's damped forward roots, reordered so that column b
    continues lossless branch b; K, C (n, d, d) the symbol's stiffness and damping at each
    wavenumber, w2 the mass weights 1 / sqrt(m_a m_b) (1, d, d)."""
    n, d = roots.shape
    Kw, Cw = K * w2, C * w2
    _, U = np.linalg.eigh(Kw)  # ascending omega^2: the lossless branches' order
    eye = np.eye(d)
    w = roots[:, :, None, None]
    A = Kw[:, None] - 1j * w * Cw[:, None] - w * w * eye
    y = np.conj(np.linalg.svd(A)[2][:, :, -1, :])  # (n, root, d): each root's null vector
    O = np.abs(np.einsum("nab,nja->nbj", np.conj(U), y))  # branch b against root j
    # oscillating roots first: overlaps are <= 1, so + 2 puts every one of them before any
    # overdamped root (Re w ~ 1e-16 |w| there: LAPACK's round-off, not an oscillation)
    osc = np.real(roots) > 1e-9 * np.maximum(np.abs(roots), 1e-300)
    O = O + 2.0 * osc[:, None, :]
    perm = np.full((n, d), -1)
    rows = np.arange(n)
    for _ in range(d):
        flat = np.argmax(O.reshape(n, -1), axis=1)
        b, j = np.divmod(flat, d)
        perm[rows, b] = j
        O[rows, b, :] = -1.0
        O[rows, :, j] = -1.0
    same = np.all(perm == np.arange(d), axis=1)
    if same.all():
        return roots
    out = roots.copy()
    out[~same] = np.take_along_axis(roots[~same], perm[~same], axis=1)
    return out
