"""The discrete equations (eq. `norm`) and their long-wave, weakly nonlinear limit.

Eq. `norm` is written once here (``lattice_accelerations``), and the continuum equations
(eqs. `eqnorm1`, `eqnorm2`) are *derived* from it by Taylor expansion, so the constants
C1..C4 are a result, not an input; the paper's typed C1..C4 live in ``paper_forms``.
"""

from __future__ import annotations

from dataclasses import dataclass

import sympy as sp

# Material parameters and independent variables, shared by the whole derivation.
alpha, K_s, K_theta = sp.symbols("alpha K_s K_theta", positive=True)
k = sp.Symbol("k", real=True)
X, T = sp.symbols("X T", real=True)


def lattice_accelerations(Um, U0, Up, tm, t0, tp, *, cos=sp.cos, sin=sp.sin):
    r"""Right-hand sides of eq. `norm` for site n, given the neighbours.

    Returns ``(d^2 U_n/dT^2, d^2 theta_n/dT^2)``; the second already carries the
    factor :math:`\alpha^2` of the left-hand side. ``cos``/``sin`` are injectable so
    that the same text serves SymPy and truncated series.
    """
    acc_U = Up - 2 * U0 + Um - (cos(tp) - cos(tm)) / 2
    acc_t = alpha**2 * (
        -K_theta * (tp + 4 * t0 + tm)
        + K_s * cos(t0) * (sin(tp) + sin(tm) - 2 * sin(t0))
        - sin(t0) * (2 * (Up - Um) + 4 - 2 * cos(t0) - cos(tp) - cos(tm))
    )
    return acc_U, acc_t


@dataclass(frozen=True)
class ContinuumLimit:
    """Result of :func:`derive_continuum`.

    Attributes
    ----------
    eq_U, eq_theta : sympy.Expr
        Right-hand sides of U_TT = eq_U and theta_TT = eq_theta (functions of X, T).
    C : dict[str, sympy.Expr]
        C1..C4 read off ``eq_theta`` in the form of eq. `eqnorm2`.
    dropped : list[sympy.Expr]
        Terms of the expansion that the long-wave ordering discards (for the report).
    """

    eq_U: sp.Expr
    eq_theta: sp.Expr
    C: dict
    dropped: tuple


def fields():
    """The continuum fields U(X, T) and theta(X, T)."""
    return sp.Function("U")(X, T), sp.Function("theta")(X, T)


def derive_continuum(order_h: int = 3) -> ContinuumLimit:
    r"""Taylor-expand eq. `norm` for long waves and weak nonlinearity.

    Book-keeping: lattice spacing ``h`` (theta_{n+-1} = theta(X +- h)), amplitude
    ``eta`` for theta and ``eta_U`` for U. Every monomial eta^a eta_U^b h^c is classified:
    linear terms (a + b = 1) are kept up to h^2 (the lowest order that carries
    dispersion), nonlinear terms only at the lowest power of h at which their
    amplitude class appears (long waves: a derivative on a nonlinear term is a
    higher-order correction). Then h = eta = eta_U = 1 (X is measured in lattice units).
    """
    h, eta, eta_U = sp.symbols("h eta eta_U", positive=True)
    # Derivatives of the fields as plain symbols: d[j] = d^j/dX^j.
    th_d = sp.symbols(f"th0:{order_h + 1}")
    U_d = sp.symbols(f"U0:{order_h + 1}")

    def shifted(d, s):
        return sum((s * h) ** j / sp.factorial(j) * d[j] for j in range(order_h + 1))

    # Truncated trigonometric series: enough for total amplitude order 3.
    def cos_s(x):
        return 1 - x**2 / 2 + x**4 / 24

    def sin_s(x):
        return x - x**3 / 6

    tm, t0, tp = (eta * shifted(th_d, s) for s in (-1, 0, 1))
    Um, U0, Up = (eta_U * shifted(U_d, s) for s in (-1, 0, 1))
    accs = lattice_accelerations(Um, U0, Up, tm, t0, tp, cos=cos_s, sin=sin_s)

    U, th = fields()
    to_fun = {th_d[j]: th.diff(X, j) if j else th for j in range(order_h + 1)}
    to_fun.update({U_d[j]: U.diff(X, j) if j else U for j in range(order_h + 1)})

    kept_all, dropped = [], []
    for acc in accs:
        poly = sp.Poly(sp.expand(acc), eta, eta_U, h)
        classes: dict[tuple[int, int], list] = {}
        for (a, b, c), coeff in poly.terms():
            if a + 2 * b > 3 or c > order_h:
                continue  # beyond cubic order; U counts as O(eta^2) (u1 = 0, u2 ~ theta1^2)
            classes.setdefault((a, b), []).append((c, coeff))
        kept = 0
        for (a, b), terms in sorted(classes.items()):
            if a + b == 1:
                cmax = 2
            else:
                cmax = min(c for c, _ in terms)
            for c, coeff in terms:
                if c <= cmax:
                    kept += coeff
                else:
                    dropped.append(coeff.subs(to_fun))
        kept_all.append(sp.expand(kept.subs(to_fun)))

    eq_U, eq_th = kept_all
    # Read C1..C4 off eq_theta = C1 th_XX - C2 th - C3 th^3 - C4 th U_X.
    th_xx, U_x = th.diff(X, 2), U.diff(X)
    C = {
        "C1": eq_th.coeff(th_xx),
        "C2": -eq_th.subs({th_xx: 0, U_x: 0}).coeff(th, 1),
        "C3": -eq_th.coeff(th, 3),
        "C4": -eq_th.coeff(U_x).coeff(th, 1),
    }
    C = {key: sp.factor(v) for key, v in C.items()}
    return ContinuumLimit(eq_U=eq_U, eq_theta=eq_th, C=C, dropped=tuple(dropped))
