"""Which ring of n sites samples a band of sideband offsets: one rule for the advice a model's
point gives (``numerics.models.ring_misses``) and the paper chain's (``cli.point``).

A ring of n sites carries the offsets 2 pi j / n; a band [lo, hi] (rad/site) is sampled where
one of them lies in it. A ring that carries the same carrier k = 2 pi m / N is a multiple of
the reduced denominator of m / N: on any other ring k snaps elsewhere and a narrow band moves
with it.
"""

from __future__ import annotations

import math


def advised_ring(lo: float, hi: float, N: int, m: int) -> tuple:
    """The smallest ring above ``N`` sites with an offset 2 pi j / n in [lo, hi] (rad/site)
    for a carrier k = 2 pi m / N: (n, True) for a multiple of the ring's period of k (the
    reduced denominator of m / N) up to 64 N, which carries this k, so this band; else
    (n, False) for any n up to 64 N, where k snaps elsewhere and the band moves with it
    (newuser99: a Lennard-Jones chain's advised N = 132 snapped k = 0.9817 to 0.9996,
    whose band that ring missed again); (None, False) where no ring up to 64 N has one."""
    step = N // math.gcd(m, N)
    n = next((n for n in range(step * (N // step + 1), 64 * N + 1, step)
              if ring_samples(lo, hi, n)), None)
    if n is not None:
        return n, True
    return next((n for n in range(N + 1, 64 * N + 1) if ring_samples(lo, hi, n)), None), False


def ring_samples(lo: float, hi: float, n: int) -> bool:
    """Whether an offset 2 pi j / n of a ring of n sites lies in [lo, hi]."""
    return math.floor(hi * n / (2 * math.pi)) >= math.ceil(lo * n / (2 * math.pi))


__all__ = ["advised_ring", "ring_samples"]
