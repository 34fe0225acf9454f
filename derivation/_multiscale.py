"""Multiple-scales expansion of the continuum equations, built programmatically.

Nothing of the paper's hierarchy (eq. `msm`) is typed here: the fields are expanded
in epsilon with slow scales X_i = eps^i X, T_i = eps^i T, the derivatives follow the
chain rule (appendix eq. `diff`), the orders are collected by SymPy, and each order
is solved by harmonic projection: the coefficient of e^{i sigma} in the rotational
equation is the secular term, set to zero (solvability); other harmonics are
inverted with the linear operator evaluated on that harmonic.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import sympy as sp

from ._continuum import C1, C2, C3, C4, k

eps = sp.Symbol("epsilon", positive=True)
X0, X1, X2, T0, T1, T2 = sp.symbols("X0 X1 X2 T0 T1 T2", real=True)
FAST_SLOW = (X0, T0, X1, T1, X2, T2)
SLOW = (X1, T1, X2, T2)
#: Carrier frequency, kept as a symbol while solving; eq. `continuum2` fixes it.
w = sp.Symbol("omega", positive=True)
#: Group velocity symbol (its value is a result of O(eps^2)).
v_g = sp.Symbol("v_g", real=True)
#: Moving-frame variables xi_i = X_i - v_g T_i, tau_i = T_i.
xi1, tau1, xi2, tau2 = sp.symbols("xi1 tau1 xi2 tau2", real=True)

ORDERS = (1, 2, 3)
CASES = ("rotation", "coupled")


def d_T(f):
    """d/dT = D0 + eps D1 + eps^2 D2 (eq. `diff`)."""
    return f.diff(T0) + eps * f.diff(T1) + eps**2 * f.diff(T2)


def d_X(f):
    """d/dX = D0X + eps D1X + eps^2 D2X (eq. `diff`)."""
    return f.diff(X0) + eps * f.diff(X1) + eps**2 * f.diff(X2)


def residuals(theta, U):
    """Residuals (lhs - rhs) of eqs. `eqnorm1`-`eqnorm2` under multiple scales.

    ``U`` is None for case (I): only the rotational equation exists.
    """
    r_th = d_T(d_T(theta)) - C1 * d_X(d_X(theta)) + C2 * theta + C3 * theta**3
    if U is None:
        return None, r_th
    r_th = r_th + C4 * theta * d_X(U)
    r_U = d_T(d_T(U)) - d_X(d_X(U)) - theta * d_X(theta)
    return r_U, r_th


def by_order(expr, orders=ORDERS):
    """Coefficients of eps^n, n in ``orders``, of an expression polynomial in eps."""
    # power_exp=False keeps each exp(i m sigma) whole for the harmonic projection
    expr = sp.expand(expr, power_exp=False)
    return {n: expr.coeff(eps, n) for n in orders}


def generic_hierarchy(case):
    """The hierarchy with unknown functions theta_i, u_i of all scales (eq. `msm`).

    Returns ``{n: (residual_U or None, residual_theta)}``: each residual is zero.
    """
    th = [sp.Function(f"theta{i}")(*FAST_SLOW) for i in ORDERS]
    u = [sp.Function(f"u{i}")(*FAST_SLOW) for i in ORDERS]
    theta = sum(eps**i * f for i, f in zip(ORDERS, th))
    U = None if case == "rotation" else sum(eps**i * f for i, f in zip(ORDERS, u))
    r_U, r_th = residuals(theta, U)
    o_th = by_order(r_th)
    o_U = by_order(r_U) if r_U is not None else {n: None for n in ORDERS}
    return {n: (o_U[n], o_th[n]) for n in ORDERS}


# --- harmonics ---------------------------------------------------------------------
PHASE = k * X0 - w * T0
E = sp.exp(sp.I * PHASE)


def harmonics(expr):
    """Project an expression on the harmonics e^{i m sigma}: ``{m: coefficient}``."""
    marker = sp.Dummy("E")
    repl = {}
    for f in expr.atoms(sp.exp):
        ratio = sp.simplify(f.exp / (sp.I * PHASE))
        if not ratio.is_integer:
            raise ValueError(f"not a carrier harmonic: {f}")
        repl[f] = marker ** int(ratio)
    out: dict[int, sp.Expr] = {}
    for term in sp.Add.make_args(sp.expand(expr.xreplace(repl))):
        coeff, m = term.as_coeff_exponent(marker)
        out[int(m)] = out.get(int(m), 0) + coeff
    return {m: c for m, c in sorted(out.items()) if sp.simplify(c) != 0}


def linear_symbol(eq, m):
    """The linear operator L0 of equation ``eq`` acting on e^{i m sigma}."""
    if eq == "U":  # L0^(1) = D0^2 - D0X^2
        return -(m**2) * w**2 + m**2 * k**2
    return -(m**2) * w**2 + C1 * m**2 * k**2 + C2  # L0^(2)


@dataclass
class OrderRecord:
    """What one order of the hierarchy gave (for the report)."""

    order: int
    source_theta: dict = field(default_factory=dict)  # harmonics of the theta source
    source_U: dict = field(default_factory=dict)
    secular: sp.Expr | None = None
    condition: object = None  # solved solvability condition
    theta_solution: sp.Expr = sp.S.Zero
    U_solution: sp.Expr = sp.S.Zero
    notes: list = field(default_factory=list)


@dataclass
class CaseResult:
    """Closed forms of one case, with every order's record."""

    case: str
    dispersion: sp.Expr  # omega(k), eq. continuum2
    group_velocity: sp.Expr
    g1: sp.Expr
    g2: sp.Expr
    u2_coefficient: sp.Expr  # c in u2 = c B^2 e^{2 i sigma} + c.c. (0 for case I)
    nls: sp.Expr  # the NLS residual in A(xi1, tau2)
    hierarchy: dict
    records: list

    @property
    def g(self):
        return sp.simplify(self.g2 / self.g1)


def _solve_nonsecular(eqname, src_harm, skip=(1, -1)):
    """Particular solution sum_m s_m/L0(m) e^{i m sigma} over non-resonant harmonics."""
    sol, notes = sp.S.Zero, []
    for m, s in src_harm.items():
        if m in skip:
            continue
        L = linear_symbol(eqname, m)
        if sp.simplify(L) == 0:
            if sp.simplify(s) != 0:
                raise ArithmeticError(f"resonant non-secular forcing in {eqname} at m={m}")
            notes.append(f"{eqname}: harmonic m={m} is homogeneous; set to zero")
            continue
        sol += sp.simplify(s / L) * sp.exp(sp.I * m * PHASE)
    return sol, notes


def _moving_frame(expr, B):
    """Rewrite derivatives of B(X1,T1,X2,T2) in xi_i = X_i - v_g T_i, tau_i = T_i.

    Returns the expression in A(xi1, tau1, xi2, tau2) with d/dtau1 A = 0 (the
    O(eps^2) solvability condition).
    """
    A = sp.Function("A")(xi1, tau1, xi2, tau2)
    ops = {
        X1: lambda f: f.diff(xi1),
        T1: lambda f: f.diff(tau1) - v_g * f.diff(xi1),
        X2: lambda f: f.diff(xi2),
        T2: lambda f: f.diff(tau2) - v_g * f.diff(xi2),
    }
    repl = {}
    for d in expr.atoms(sp.Derivative):
        if d.expr != B:
            continue
        g = A
        for var, count in d.variable_count:
            for _ in range(count):
                g = ops[var](g)
        repl[d] = g
    out = expr.xreplace(repl).xreplace({B: A})
    # d/dtau1 A = 0, and so are all its derivatives
    zero = {d: 0 for d in out.atoms(sp.Derivative) if tau1 in d.variables}
    return sp.expand(out.xreplace(zero)), A


def solve_case(case: str) -> CaseResult:
    """Solve the hierarchy to O(eps^3) for ``case`` in {"rotation", "coupled"}."""
    if case not in CASES:
        raise ValueError(f"case must be one of {CASES}, got {case!r}")
    coupled = case == "coupled"
    hierarchy = generic_hierarchy(case)
    B = sp.Function("B")(*SLOW)
    Bc = sp.Function("Bbar")(*SLOW)  # complex conjugate of B, independent symbol
    records = []

    # O(eps): u1 = 0 (rotational wave only), theta1 = B e^{i sigma} + c.c.
    theta1 = B * E + Bc / E
    u1 = sp.S.Zero
    r_U, r_th = residuals(eps * theta1, eps * u1 if coupled else None)
    h1 = harmonics(by_order(r_th)[1])
    disp_eq = sp.simplify(h1[1] / B)
    omega = [s for s in sp.solve(disp_eq, w) if s.is_positive is not False][0]
    rec1 = OrderRecord(1, source_theta=h1, condition=sp.Eq(disp_eq, 0))
    rec1.notes.append("u1 = 0 and theta1 = B e^{i sigma} + c.c.; the O(eps) rotational "
                      "equation is satisfied iff omega solves the dispersion relation")
    records.append(rec1)

    # O(eps^2): unknowns theta2, u2 enter only through L0; source = -(residual at 0).
    theta_known = eps * theta1
    U_known = eps * u1
    r_U, r_th = residuals(theta_known, U_known if coupled else None)
    src_th = harmonics(-by_order(r_th)[2])
    secular2 = src_th.get(1, sp.S.Zero)
    dB_T1 = sp.solve(secular2, B.diff(T1))[0]
    vg_expr = sp.simplify(-dB_T1 / B.diff(X1))
    rec2 = OrderRecord(2, source_theta=src_th, secular=secular2,
                       condition=sp.Eq(B.diff(T1), dB_T1))
    theta2, notes = _solve_nonsecular("theta", src_th)
    rec2.notes += notes
    rec2.theta_solution = theta2
    u2 = sp.S.Zero
    if coupled:
        src_U = harmonics(-by_order(r_U)[2])
        u2, notes = _solve_nonsecular("U", src_U, skip=())
        rec2.source_U = src_U
        rec2.notes += notes
        rec2.U_solution = u2
    records.append(rec2)
    c_u2 = sp.simplify(harmonics(u2).get(2, sp.S.Zero) / B**2) if coupled else sp.S.Zero

    # O(eps^3): secular term of the rotational equation -> NLS.
    theta_known = eps * theta1 + eps**2 * theta2
    U_known = eps * u1 + eps**2 * u2
    r_U, r_th = residuals(theta_known, U_known if coupled else None)
    src_th3 = harmonics(-by_order(r_th)[3])
    secular3 = src_th3.get(1, sp.S.Zero)
    # The secular term in the moving frame; d/dtau1 = 0 from O(eps^2).
    sec_frame, A = _moving_frame(secular3, B)
    Ab = sp.Function("Abar")(xi1, tau1, xi2, tau2)
    sec_frame = sec_frame.xreplace({Bc: Ab})
    sec_frame = sp.expand(sec_frame.subs(v_g, vg_expr))
    A_tau = sp.solve(sec_frame, A.diff(tau2))[0]
    # i A_tau2 + g1/2 A_xi1xi1 + g2 |A|^2 A = 0  <=>  A_tau2 = i g1/2 A'' + i g2 |A|^2 A
    A_tau = sp.expand(A_tau)
    g1 = sp.simplify(2 * A_tau.coeff(A.diff(xi1, 2)) / sp.I)
    g2 = sp.simplify(A_tau.coeff(A**2 * Ab) / sp.I)
    leftover = sp.simplify(A_tau - sp.I * g1 / 2 * A.diff(xi1, 2) - sp.I * g2 * A**2 * Ab)
    if leftover != 0:
        raise ArithmeticError(f"secular term not of NLS form: {leftover}")
    rec3 = OrderRecord(3, source_theta=src_th3, secular=secular3,
                       condition=sp.Eq(A.diff(tau2), A_tau))
    records.append(rec3)

    on_shell = {w: omega}
    nls = sp.I * A.diff(tau2) + g1 / 2 * A.diff(xi1, 2) + g2 * A**2 * Ab
    return CaseResult(
        case=case,
        dispersion=omega,
        group_velocity=sp.simplify(vg_expr.subs(on_shell)),
        g1=sp.simplify(g1.subs(on_shell)),
        g2=sp.simplify(g2.subs(on_shell)),
        u2_coefficient=sp.simplify(c_u2.subs(on_shell)),
        nls=nls,
        hierarchy=hierarchy,
        records=records,
    )
