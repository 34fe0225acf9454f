"""The damped NLS's sideband pairs stepped along the decaying carrier, compiled
(``_losses._pairs_compiled``): module-level functions, cached on disk. (They were closures
made on the first call, which Numba compiled anew in every process: ~0.7 s on a process's
first damped point; a closure calling another is not cached.) The arithmetic is
``_losses``' (its module docstring and ``_pairs_best``).
"""

from __future__ import annotations

import math

from numba import njit

#: the relative round-off allowed to the remaining steps of an offset that stops early
#: (``_losses._pairs_best``): ~1e-13 after 1000 steps of a few ulp each; 1e-9 of margin
CALM_MARGIN = 1e-9

_KW = dict(cache=True, error_model="numpy", boundscheck=False)


@njit(inline="always", **_KW)
def step(P, Q, a2i, b, e, h, xj, yj):
    """One step of a pair: (x, y) <- e^{-G h} exp(h [[0, b], [c, 0]]) (x, y), and the new
    |(x, y)|."""
    c = 2 * Q * a2i - b
    bc = b * c
    r = math.sqrt(abs(bc))
    rh = r * h
    if bc > 0:
        # cosh and sinh from one expm1 (half the exponentials of math.cosh and math.sinh;
        # no cancellation: em1 >= 0), each to a few ulp
        em1 = math.expm1(rh)
        ex = 1.0 + em1
        ch = 1.0 + em1 * em1 / (2.0 * ex)
        sh = em1 * (em1 + 2.0) / (2.0 * ex)
    else:
        ch, sh = math.cos(rh), math.sin(rh)
    shl = sh / r if rh > 1e-12 else h
    xj, yj = e * ch * xj + e * b * shl * yj, e * c * shl * xj + e * ch * yj
    # sqrt of the sum (2/3 of hypot's time), hypot where it would overflow
    r2 = xj * xj + yj * yj
    return xj, yj, (math.sqrt(r2) if r2 < 1e300 else math.hypot(xj, yj))


@njit(**_KW)
def pairs_top(P, Q, a2, G, q2, h, x, y, top, first, calm):
    """Each offset's running maximum of |(x, y)| and its first step, stopped where the
    maximum is final (from step ``calm`` on no step lengthens (x, y))."""
    grow = 1.0 + CALM_MARGIN
    for j in range(q2.size):
        b = P * q2[j]
        e = math.exp(-G[j] * h)
        xj, yj = x[j], y[j]
        for i in range(a2.size):
            xj, yj, n = step(P, Q, a2[i], b, e, h, xj, yj)
            if n > top[j]:
                top[j], first[j] = n, i + 1
            elif i + 1 >= calm[j] and n * grow < top[j]:
                break  # no later step lengthens (x, y): the maximum is final


@njit(**_KW)
def pairs_all(P, Q, a2, G, q2, h, x, y, out):
    """|(x, y)| after every step, per offset, into ``out`` (offsets, steps + 1)."""
    for j in range(q2.size):
        b = P * q2[j]
        e = math.exp(-G[j] * h)
        xj, yj = x[j], y[j]
        for i in range(a2.size):
            xj, yj, out[j, i + 1] = step(P, Q, a2[i], b, e, h, xj, yj)
