"""Multiple scales: slow variables, the chain rule, orders in eps, carrier harmonics.

The fields depend on X_i = eps^i X and T_i = eps^i T (i = 0, 1, 2); derivatives follow
the chain rule of the paper's appendix (eq. `diff`). ``harmonics`` projects an
expression on e^{i m sigma}, sigma = k X0 - omega T0: the coefficient of m = 1 in the
rotational equation is the secular term.
"""

from __future__ import annotations

import sympy as sp

from ._continuum import k

eps = sp.Symbol("epsilon", positive=True)
X0, X1, X2, T0, T1, T2 = sp.symbols("X0 X1 X2 T0 T1 T2", real=True)
FAST_SLOW = (X0, T0, X1, T1, X2, T2)
SLOW = (X1, T1, X2, T2)
#: Carrier frequency, kept as a symbol while solving; the O(eps) condition fixes it.
w = sp.Symbol("omega", positive=True)
#: Group velocity symbol (its value is a result of O(eps^2)).
v_g = sp.Symbol("v_g", real=True)
#: Moving-frame variables xi_i = X_i - v_g T_i, tau_i = T_i.
xi1, tau1, xi2, tau2 = sp.symbols("xi1 tau1 xi2 tau2", real=True)

ORDERS = (1, 2, 3)
PHASE = k * X0 - w * T0
E = sp.exp(sp.I * PHASE)


def d_T(f):
    """d/dT = D0 + eps D1 + eps^2 D2 (eq. `diff`)."""
    return f.diff(T0) + eps * f.diff(T1) + eps**2 * f.diff(T2)


def d_X(f):
    """d/dX = D0X + eps D1X + eps^2 D2X (eq. `diff`)."""
    return f.diff(X0) + eps * f.diff(X1) + eps**2 * f.diff(X2)


def by_order(expr, orders=ORDERS):
    """Coefficients of eps^n, n in ``orders``, of an expression polynomial in eps."""
    # power_exp=False keeps each exp(i m sigma) whole for the harmonic projection
    expr = sp.expand(expr, power_exp=False)
    return {n: expr.coeff(eps, n) for n in orders}


def harmonics(expr, fast=False):
    """Project an expression on the harmonics e^{i m sigma}: ``{m: coefficient}``.

    Zero coefficients are dropped after ``simplify`` (or, ``fast=True``, after
    ``expand``: the lattice coefficients carry trigonometric functions of k, where a
    full simplify of every harmonic costs minutes).
    """
    marker = sp.Dummy("E")
    repl = {}
    for f in expr.atoms(sp.exp):
        if not f.has(X0, T0):
            continue  # a constant phase such as e^{i k j}
        # SymPy merges e^{i k j} e^{i m sigma} into one exponential: split it again
        parts = sp.Add.make_args(sp.expand(f.exp))
        carrier = sp.Add(*[a for a in parts if a.has(X0, T0)])
        rest = sp.Add(*[a for a in parts if not a.has(X0, T0)])
        ratio = sp.simplify(carrier / (sp.I * PHASE))
        if not ratio.is_integer:
            raise ValueError(f"not a carrier harmonic: {f}")
        repl[f] = marker ** int(ratio) * sp.exp(rest)
    out: dict[int, sp.Expr] = {}
    for term in sp.Add.make_args(sp.expand(expr.xreplace(repl))):
        coeff, m = term.as_coeff_exponent(marker)
        out[int(m)] = out.get(int(m), 0) + coeff
    is_zero = (lambda c: sp.expand(c) == 0) if fast else (lambda c: sp.simplify(c) == 0)
    return {m: c for m, c in sorted(out.items()) if not is_zero(c)}
