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

from ._continuum import C1, C2, C3, C4, K_s, K_theta, alpha, k, lattice_accelerations

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


MODELS = ("continuum", "lattice")


def residuals(theta, U, model="continuum"):
    """Residuals (lhs - rhs) under multiple scales: of eqs. `eqnorm1`-`eqnorm2`
    (``model="continuum"``), or of the discrete eq. `norm` itself ("lattice").

    ``U`` is None for case (I): only the rotational equation exists.
    """
    if model == "lattice":
        return lattice_residuals(theta, U)
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
        fast = sp.Add(*[a for a in parts if a.has(X0, T0)])
        rest = sp.Add(*[a for a in parts if not a.has(X0, T0)])
        ratio = sp.simplify(fast / (sp.I * PHASE))
        if not ratio.is_integer:
            raise ValueError(f"not a carrier harmonic: {f}")
        repl[f] = marker ** int(ratio) * sp.exp(rest)
    out: dict[int, sp.Expr] = {}
    for term in sp.Add.make_args(sp.expand(expr.xreplace(repl))):
        coeff, m = term.as_coeff_exponent(marker)
        out[int(m)] = out.get(int(m), 0) + coeff
    test = sp.expand if fast else sp.simplify
    return {m: c for m, c in sorted(out.items()) if test(c) != 0}


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


def lattice_residuals(theta, U):
    """Residuals of eq. `norm` with neighbours from :func:`shift`, sin/cos to cubic order."""
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


def linear_symbol(eq, m, model="continuum"):
    """The linear operator L0 of equation ``eq`` acting on e^{i m sigma}."""
    if model == "lattice":
        if eq == "U":  # discrete1 at m k
            return -(m**2) * w**2 + 4 * sp.sin(m * k / 2) ** 2
        return -(m**2) * w**2 + alpha**2 * (K_theta * (4 + 2 * sp.cos(m * k))
                                            + 2 * K_s * (1 - sp.cos(m * k)))  # discrete2
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
    mean_flow: sp.Expr = sp.S.Zero  # mu in F_X1 = mu |B|^2 (lattice model, case II)
    g2_mean_flow: sp.Expr = sp.S.Zero  # the part of g2 the mean flow contributes

    @property
    def g(self):
        return sp.simplify(self.g2 / self.g1)


def _solve_nonsecular(eqname, src_harm, skip=(1, -1), model="continuum"):
    """Particular solution sum_m s_m/L0(m) e^{i m sigma} over non-resonant harmonics."""
    sol, notes = sp.S.Zero, []
    for m, s in src_harm.items():
        if m in skip:
            continue
        L = linear_symbol(eqname, m, model)
        if sp.simplify(L) == 0:
            if sp.simplify(s) != 0:
                raise ArithmeticError(f"resonant non-secular forcing in {eqname} at m={m}")
            notes.append(f"{eqname}: harmonic m={m} is homogeneous; set to zero")
            continue
        sol += sp.simplify(s / L) * sp.exp(sp.I * m * PHASE)
    return sol, notes


def _mean_flow(r_U, F, B, Bc, dB_T1, vg_expr):
    """Mean strain F_X1 = mu |B|^2 from the zeroth harmonic of the U equation at O(eps^3).

    In the frame moving with v_g, F_T1 = -v_g F_X1 (and B_T1 = -v_g B_X1, the O(eps^2)
    condition), so the equation reads a F_X1X1 + b (B Bbar)_X1 = 0: F_X1 = -b/a B Bbar
    (the integration constant is the mean strain of the unmodulated wave: zero on a
    periodic chain).
    """
    eq = harmonics(by_order(r_U)[3]).get(0, sp.S.Zero)
    Bc_T1 = dB_T1.subs(B.diff(X1), Bc.diff(X1))
    eq = eq.subs({F.diff(T1, 2): vg_expr**2 * F.diff(X1, 2),
                  F.diff(X1, T1): -vg_expr * F.diff(X1, 2),
                  B.diff(T1): dB_T1, Bc.diff(T1): Bc_T1})
    eq = sp.expand(eq)
    a = eq.coeff(F.diff(X1, 2))
    rest = sp.expand(eq - a * F.diff(X1, 2))
    b = sp.simplify(rest / sp.expand((B * Bc).diff(X1)))
    if b.has(B) or b.has(Bc) or a == 0:
        raise ArithmeticError(f"mean-flow equation not of the form a F'' + b (|B|^2)': {eq}")
    return sp.simplify(-b / a), eq


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


def solve_case(case: str, model: str = "continuum") -> CaseResult:
    """Solve the hierarchy to O(eps^3) for ``case`` in {"rotation", "coupled"}.

    ``model="continuum"`` is the paper's derivation (eqs. `eqnorm1`-`eqnorm2`, no mean
    flow). ``model="lattice"`` repeats it on eq. `norm` itself (semi-discrete NLS):
    exact carrier on the lattice, and in case (II) the induced mean flow u1 = F(X1, ...)
    (zeroth harmonic of U), fixed by the O(eps^3) zeroth harmonic of the U equation.
    """
    if case not in CASES:
        raise ValueError(f"case must be one of {CASES}, got {case!r}")
    if model not in MODELS:
        raise ValueError(f"model must be one of {MODELS}, got {model!r}")
    coupled = case == "coupled"
    lattice = model == "lattice"
    hierarchy = generic_hierarchy(case) if not lattice else {}

    def residuals_m(theta, U):
        return residuals(theta, U, model)

    def harm(expr):
        return harmonics(expr, fast=lattice)
    B = sp.Function("B")(*SLOW)
    Bc = sp.Function("Bbar")(*SLOW)  # complex conjugate of B, independent symbol
    records = []

    # O(eps): u1 = 0 (rotational wave only), theta1 = B e^{i sigma} + c.c.
    theta1 = B * E + Bc / E
    F = sp.Function("F")(*SLOW)  # mean flow (lattice model, case II)
    u1 = F if (lattice and coupled) else sp.S.Zero
    r_U, r_th = residuals_m(eps * theta1, eps * u1 if coupled else None)
    h1 = harm(by_order(r_th)[1])
    disp_eq = sp.simplify(h1[1] / B)
    omega = [s for s in sp.solve(disp_eq, w) if s.is_positive is not False][0]
    rec1 = OrderRecord(1, source_theta=h1, condition=sp.Eq(disp_eq, 0))
    rec1.notes.append("u1 = 0 and theta1 = B e^{i sigma} + c.c.; the O(eps) rotational "
                      "equation is satisfied iff omega solves the dispersion relation")
    records.append(rec1)

    # O(eps^2): unknowns theta2, u2 enter only through L0; source = -(residual at 0).
    theta_known = eps * theta1
    U_known = eps * u1
    r_U, r_th = residuals_m(theta_known, U_known if coupled else None)
    src_th = harm(-by_order(r_th)[2])
    secular2 = src_th.get(1, sp.S.Zero)
    dB_T1 = sp.solve(secular2, B.diff(T1))[0]
    vg_expr = sp.simplify(-dB_T1 / B.diff(X1))
    rec2 = OrderRecord(2, source_theta=src_th, secular=secular2,
                       condition=sp.Eq(B.diff(T1), dB_T1))
    theta2, notes = _solve_nonsecular("theta", src_th, model=model)
    rec2.notes += notes
    rec2.theta_solution = theta2
    u2 = sp.S.Zero
    if coupled:
        src_U = harm(-by_order(r_U)[2])
        u2, notes = _solve_nonsecular("U", src_U, skip=(), model=model)
        rec2.source_U = src_U
        rec2.notes += notes
        rec2.U_solution = u2
    records.append(rec2)
    u2_parts = harm(u2) if coupled else {}
    c_u2 = sp.simplify(u2_parts.get(2, sp.S.Zero) / B**2) if coupled else sp.S.Zero

    u2_values = {}
    if lattice and coupled:
        # carry u2 as symbols c_m B^2 e^{2 i sigma} through O(eps^3) (its lattice value has
        # trigonometric denominators that would swell every product); substitute at the end
        u2 = sp.S.Zero
        for m, c in u2_parts.items():
            sym = sp.Symbol(f"c_u{'m' if m < 0 else 'p'}{abs(m)}")
            amp = B**2 if m > 0 else Bc**2
            u2_values[sym] = c_u2 if m == 2 else (sp.simplify(c / amp) if m else c)
            u2 += sym * (amp if m else 1) * sp.exp(sp.I * m * PHASE)

    # O(eps^3): secular term of the rotational equation -> NLS.
    theta_known = eps * theta1 + eps**2 * theta2
    U_known = eps * u1 + eps**2 * u2
    r_U, r_th = residuals_m(theta_known, U_known if coupled else None)
    src_th3 = harm(-by_order(r_th)[3])
    secular3 = src_th3.get(1, sp.S.Zero)
    mean_flow = sp.S.Zero
    if lattice and coupled:
        mean_flow, mf_eq = _mean_flow(r_U, F, B, Bc, dB_T1, vg_expr)
        mu = sp.Symbol("mu")  # substituted at the end, like u2
        u2_values[mu] = mean_flow
        secular3 = secular3.subs(F.diff(X1), mu * B * Bc)
        if secular3.has(F):
            raise ArithmeticError("mean flow enters the secular term beyond its strain")
    # The secular term in the moving frame; d/dtau1 = 0 from O(eps^2).
    sec_frame, A = _moving_frame(secular3, B)
    Ab = sp.Function("Abar")(xi1, tau1, xi2, tau2)
    sec_frame = sec_frame.xreplace({Bc: Ab})
    sec_frame = sp.expand(sec_frame.subs(v_g, vg_expr))
    if lattice:  # linear in A_tau2; sympy.solve chokes on the lattice's trig terms
        c_tau = sec_frame.coeff(A.diff(tau2))
        A_tau = -sp.expand(sec_frame - c_tau * A.diff(tau2)) / c_tau
    else:
        A_tau = sp.solve(sec_frame, A.diff(tau2))[0]
    # i A_tau2 + g1/2 A_xi1xi1 + g2 |A|^2 A = 0  <=>  A_tau2 = i g1/2 A'' + i g2 |A|^2 A
    A_tau = sp.expand(A_tau)
    g1 = sp.simplify(2 * A_tau.coeff(A.diff(xi1, 2)) / sp.I)
    g2_raw = A_tau.coeff(A**2 * Ab) / sp.I
    g2 = sp.simplify(g2_raw.subs(u2_values))
    g2_mf = sp.S.Zero
    if lattice and coupled:
        g2_mf = sp.simplify(sp.expand(g2_raw).coeff(mu) * mean_flow)
    leftover = sp.simplify((A_tau - sp.I * g1 / 2 * A.diff(xi1, 2)).subs(u2_values)
                           - sp.I * g2 * A**2 * Ab)
    if leftover != 0:
        raise ArithmeticError(f"secular term not of NLS form: {leftover}")
    rec3 = OrderRecord(3, source_theta=src_th3, secular=secular3,
                       condition=sp.Eq(A.diff(tau2), A_tau))
    if lattice and coupled:
        rec3.notes.append("mean flow: zeroth harmonic of the U equation at O(eps^3), "
                          f"{sp.sstr(mf_eq)} = 0, gives F_X1 = mu |B|^2")
    records.append(rec3)

    on_shell = {w: omega}
    nls = sp.I * A.diff(tau2) + g1 / 2 * A.diff(xi1, 2) + g2 * A**2 * Ab
    return CaseResult(
        case=case,
        dispersion=omega,
        group_velocity=sp.simplify(vg_expr.subs(on_shell)),
        g1=sp.simplify(g1.subs(on_shell)),
        # on the lattice a full simplify of g2 costs ~10 s and gains little: substitute only
        g2=g2.subs(on_shell) if lattice else sp.simplify(g2.subs(on_shell)),
        u2_coefficient=sp.simplify(c_u2.subs(on_shell)),
        mean_flow=sp.simplify(sp.S(mean_flow).subs(on_shell)),
        g2_mean_flow=sp.S(g2_mf).subs(on_shell),
        nls=nls,
        hierarchy=hierarchy,
        records=records,
    )
