"""Probe 100: two model files that differ only in the order of their parameters share one
content hash and so one generated module; the values must reach it in its own order (before,
the second file's values went in its order: a and b swapped, silently)."""

from __future__ import annotations

import math

import numpy as np

from energy import Lattice, load_model
from numerics.models import branches


def _lattice(order):
    values = {"a": 1.0, "b": 0.1}
    return Lattice(name="order-probe", fields=("u",),
                   parameters={p: values[p] for p in order}, kinetic="u_t**2/2",
                   bond="a*(u_next - u)**2/2 + b*(u_next - u)**4/4")


def test_parameter_order_does_not_swap_values():
    ks = np.array([0.3, 1.0, 2.5])
    # by hand: a harmonic bond of stiffness a and unit mass, w = 2 sqrt(a) sin(k/2)
    want = 2 * math.sqrt(1.0) * np.sin(ks / 2)
    for order in (("a", "b"), ("b", "a")):
        m = load_model(_lattice(order))
        got = np.asarray(branches(m, ks), float).ravel()
        assert np.allclose(got, want, rtol=1e-12, atol=0), (order, got)  # round-off only
