"""The damped semi-discrete NLS's sideband pairs along the decaying carrier (issue 42;
split from ``_losses``, whose module docstring states the 2 x 2 system): the pairs
integrated per offset (``integrate_pairs``), their running maximum without the whole
array (``_pairs_best``), and the first largest of that array (``_first_max``). The steps
themselves are compiled in ``_losses_pairs``.
"""

from __future__ import annotations

import numpy as np


def integrate_pairs(P, Q, psi0, Gamma, G, q, t_end, steps=4000, carrier_decays=True):
    """|(x, y)(t)| / |(x, y)(0)| of the linearised damped NLS per offset q: array
    (steps + 1, len(q)), and the times. The carrier psi0 e^{-Gamma t} (constant where
    ``carrier_decays`` is False); start on the growing eigenvector at t = 0."""
    q2, G, x, y, h, a2 = _pairs_start(P, Q, psi0, Gamma, G, q, t_end, steps, carrier_decays)
    t = np.linspace(0.0, t_end, steps + 1)
    # one row per offset (the kernel walks each offset's steps in order), returned as
    # (steps + 1, len(q)) by a transposed view
    out = np.empty((q2.size, steps + 1))
    out[:, 0] = 1.0
    _pairs_compiled()(float(P), float(Q), a2, G, q2, h, x, y, out)
    return out.T, t


def _pairs_start(P, Q, psi0, Gamma, G, q, t_end, steps, carrier_decays=True):
    """(q^2, G, x, y, h, a2) of ``integrate_pairs``: the growing eigenvector at t = 0 per
    offset, the step and the carrier's psi0^2 e^{-2 Gamma t} at each step's midpoint."""
    h, a2 = _pairs_times(psi0, Gamma, t_end, steps, carrier_decays)
    return (*_pairs_columns(P, Q, psi0, G, q), h, a2)


def _pairs_times(psi0, Gamma, t_end, steps, carrier_decays=True):
    """(h, a2) of ``_pairs_start``: the step and psi0^2 e^{-2 Gamma t} at the midpoints."""
    h = t_end / steps
    tm = (np.arange(steps) + 0.5) * h
    return h, psi0**2 * (np.exp(-2 * Gamma * tm) if carrier_decays else np.ones(steps))


def _pairs_columns(P, Q, psi0, G, q):
    """(q^2, G, x, y) of ``_pairs_start``: each offset's growing eigenvector at t = 0."""
    q = np.atleast_1d(np.asarray(q, float))
    G = np.ascontiguousarray(np.broadcast_to(np.asarray(G, float), q.shape), dtype=float)
    q2 = q * q
    b = P * q2
    c0 = 2 * Q * psi0**2 - P * q2
    s0 = np.sqrt(np.maximum(b * c0, 0.0))
    # growing eigenvector of [[0, b], [c0, 0]]: (b, s0) (normalised); neutral: (1, 0)
    x = np.where(s0 > 0, b, 1.0)
    y = np.where(s0 > 0, s0, 0.0)
    n0 = np.hypot(x, y)
    return q2, G, x / n0, y / n0


def _pairs_best(P, Q, psi0, Gamma, G, q, t_end, steps, times=None):
    """Per offset of ``integrate_pairs``: its largest |(x, y)(t)| / |(x, y)(0)| and the
    first step index that reaches it, without the (steps + 1, len(q)) array (the same
    numbers: the same kernel, its writes replaced by the running maximum). ``times``:
    ``_pairs_times``' (h, a2, later) of these arguments, where already computed."""
    q2, G, x, y = _pairs_columns(P, Q, psi0, G, q)
    h, a2, later = _pairs_later(psi0, Gamma, t_end, steps) if times is None else times
    best = np.ones(q2.size)
    first = np.zeros(q2.size, np.int64)
    # where an offset's maximum is final: each step is e^{-G h} exp(h [[0, b], [c, 0]]),
    # whose 2-norm is at most e^{h mu}, mu = |b + c| / 2 - G = |Q| a2 - G (the
    # logarithmic norm); from the first step after which |Q| a2 <= G at every later one
    # (``calm``) no step lengthens (x, y), so once |(x, y)| is below the running maximum
    # (by more than the steps' round-off, ``_losses_pairs.CALM_MARGIN``) the maximum and its first
    # step are the ones the whole horizon gives, and the offset stops there
    calm = np.searchsorted(-later, -G / max(abs(float(Q)), 1e-300), side="left")
    _pairs_compiled(best=True)(float(P), float(Q), a2, G, q2, h, x, y, best, first,
                               calm.astype(np.int64))
    return best, first


def _pairs_later(psi0, Gamma, t_end, steps):
    """(h, a2, later) of ``_pairs_best``: ``_pairs_times``' and the largest a2 over the
    later steps (its calm test), once for every offset of a point."""
    h, a2 = _pairs_times(psi0, Gamma, t_end, steps)
    return h, a2, np.maximum.accumulate(a2[::-1])[::-1]


def _pairs_compiled(best=False):
    """The steps of ``integrate_pairs``, compiled (``_losses_pairs``, cached on disk): per
    offset, the product in order of each step's exp(h [[-G, b], [c, -G]]) = e^{-G h}
    [[ch, b sh/l], [c sh/l, ch]], l = sqrt(b c), b = P q^2, c = 2 Q a(t)^2 - b (cosh,
    sinh where b c > 0; cos, sin where b c < 0: l is real or imaginary). ``best``: each
    offset's running maximum and its first step instead of every step, each offset
    stopped where its maximum is final (``_pairs_best``)."""
    from ._losses_pairs import pairs_all, pairs_top

    return pairs_top if best else pairs_all


def _first_max(amp) -> tuple[int, int]:
    """(i, j) of ``np.argmax(amp)`` (the first largest in row-major order) of the
    transposed view ``integrate_pairs`` returns, without copying it: the largest along its
    contiguous base, then the earliest row among the equal ones."""
    base = amp.T  # (offsets, times), contiguous
    where = np.flatnonzero(base.ravel() == base.max())
    if not where.size:  # a nan: argmax's own answer
        i, j = np.unravel_index(int(np.argmax(amp)), amp.shape)
        return int(i), int(j)
    jj, ii = np.divmod(where, base.shape[1])
    first = int(np.lexsort((jj, ii))[0])
    return int(ii[first]), int(jj[first])
