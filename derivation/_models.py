"""The two models the multiple-scales code is run on: the continuum limit and the lattice.

A model says what the hierarchy needs to know about the equations and nothing else:

- ``residuals(theta, U)``: lhs - rhs of its equations for multiple-scales fields;
- ``linear_symbol(eq, m)``: its linear operator acting on the harmonic e^{i m sigma};
- ``fast_harmonics``: whether zero harmonics are recognised by ``expand`` (lattice: its
  coefficients carry trigonometric functions of k, where ``simplify`` costs minutes)
  rather than ``simplify``;
- ``leading_U(coupled)``: u1, the O(eps) displacement (0, or the mean flow F);
- ``has_mean_flow(coupled)``: whether the zeroth harmonic of U is solved for at O(eps^3).
"""

from __future__ import annotations

import sympy as sp

from ._continuum import K_s, K_theta, alpha, k, lattice_accelerations
from ._scales import PHASE, SLOW, X1, X2, E, d_T, d_X, eps, harmonics, w


class ContinuumModel:
    """The paper's eqs. `eqnorm1`-`eqnorm2`, with the constants C1..C4 given (derived
    from the lattice by :func:`derivation.derive_continuum`)."""

    name = "continuum"
    fast_harmonics = False

    def __init__(self, C: dict):
        self.C1, self.C2, self.C3, self.C4 = (C[n] for n in ("C1", "C2", "C3", "C4"))

    def residuals(self, theta, U):
        """Residuals of eqs. `eqnorm1`-`eqnorm2`; ``U`` is None for case (I)."""
        r_th = (d_T(d_T(theta)) - self.C1 * d_X(d_X(theta)) + self.C2 * theta
                + self.C3 * theta**3)
        if U is None:
            return None, r_th
        r_th = r_th + self.C4 * theta * d_X(U)
        r_U = d_T(d_T(U)) - d_X(d_X(U)) - theta * d_X(theta)
        return r_U, r_th

    def linear_symbol(self, eq, m):
        """L0 on e^{i m sigma}: L0^(1) = D0^2 - D0X^2 (U), L0^(2) (theta)."""
        if eq == "U":
            return -(m**2) * w**2 + m**2 * k**2
        return -(m**2) * w**2 + self.C1 * m**2 * k**2 + self.C2

    def leading_U(self, coupled):
        return sp.S.Zero

    def has_mean_flow(self, coupled):
        return False


def shift(expr, j):
    """Value at site n + j of a multiple-scales expression (sum of harmonics).

    The carrier moves exactly, e^{i m sigma} -> e^{i m k j} e^{i m sigma}; the slow
    scales X_i = eps^i n move by eps^i j, Taylor-expanded to O(eps^2) (enough for
    fields that start at O(eps), up to O(eps^3)).
    """
    out = sp.S.Zero
    for m, c in harmonics(expr, fast=True).items():
        c = (c + eps * j * c.diff(X1)
             + eps**2 * (j**2 * c.diff(X1, 2) / 2 + j * c.diff(X2)))
        out += c * (sp.cos(m * k * j) + sp.I * sp.sin(m * k * j)) * sp.exp(sp.I * m * PHASE)
    return out


def _sin3(x):
    return x - x**3 / 6


def _cos3(x):
    return 1 - x**2 / 2


class LatticeModel:
    """Eq. `norm` itself: neighbours by :func:`shift`, sin/cos to cubic order, the lattice
    dispersion (eqs. `discrete1`, `discrete2`), and in case (II) the induced mean flow
    u1 = F(X1, ...) (zeroth harmonic of U)."""

    name = "lattice"
    fast_harmonics = True
    #: the mean flow F(X1, T1, X2, T2), O(eps) part of U in case (II)
    F = sp.Function("F")(*SLOW)

    def residuals(self, theta, U):
        tm, tp = shift(theta, -1), shift(theta, 1)
        if U is None:
            Um = U0 = Up = sp.S.Zero
        else:
            Um, U0, Up = shift(U, -1), U, shift(U, 1)
        acc_U, acc_t = lattice_accelerations(Um, U0, Up, tm, theta, tp, cos=_cos3, sin=_sin3)
        r_th = d_T(d_T(theta)) - acc_t
        if U is None:
            return None, r_th
        return d_T(d_T(U)) - acc_U, r_th

    def linear_symbol(self, eq, m):
        if eq == "U":  # discrete1 at m k
            return -(m**2) * w**2 + 4 * sp.sin(m * k / 2) ** 2
        return -(m**2) * w**2 + alpha**2 * (K_theta * (4 + 2 * sp.cos(m * k))
                                            + 2 * K_s * (1 - sp.cos(m * k)))  # discrete2

    def leading_U(self, coupled):
        return self.F if coupled else sp.S.Zero

    def has_mean_flow(self, coupled):
        return coupled


__all__ = ["ContinuumModel", "LatticeModel", "shift", "E"]
