"""Multiple-scales expansion to O(eps^3), built programmatically, for either model.

Nothing of the paper's hierarchy (eq. `msm`) is typed here: the fields are expanded in
eps (``_scales``), a model (``_models``: the continuum limit or the lattice itself)
gives the residuals, the orders are collected by SymPy, and each order is solved by
harmonic projection: the coefficient of e^{i sigma} in the rotational equation is the
secular term, set to zero (solvability); other harmonics are inverted with the model's
linear operator on that harmonic. One function per order.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from functools import lru_cache

import sympy as sp

from ._models import ContinuumModel, LatticeModel
from ._scales import (
    FAST_SLOW,
    ORDERS,
    PHASE,
    SLOW,
    T1,
    X1,
    E,
    by_order,
    eps,
    harmonics,
    tau1,
    tau2,
    v_g,
    w,
    xi1,
    xi2,
)

CASES = ("rotation", "coupled")
MODELS = ("continuum", "lattice")


@lru_cache(maxsize=1)
def _continuum_model():
    from ._continuum import derive_continuum

    return ContinuumModel(derive_continuum().C)


def get_model(model):
    """A model object from its name ("continuum", "lattice"), or the object itself."""
    if model == "continuum":
        return _continuum_model()
    if model == "lattice":
        return LatticeModel()
    if isinstance(model, (ContinuumModel, LatticeModel)):
        return model
    raise ValueError(f"model must be one of {MODELS}, got {model!r}")


def generic_hierarchy(case, model="continuum"):
    """The hierarchy with unknown functions theta_i, u_i of all scales (eq. `msm`).

    Returns ``{n: (residual_U or None, residual_theta)}``: each residual is zero.
    """
    th = [sp.Function(f"theta{i}")(*FAST_SLOW) for i in ORDERS]
    u = [sp.Function(f"u{i}")(*FAST_SLOW) for i in ORDERS]
    theta = sum(eps**i * f for i, f in zip(ORDERS, th))
    U = None if case == "rotation" else sum(eps**i * f for i, f in zip(ORDERS, u))
    r_U, r_th = get_model(model).residuals(theta, U)
    o_th = by_order(r_th)
    o_U = by_order(r_U) if r_U is not None else {n: None for n in ORDERS}
    return {n: (o_U[n], o_th[n]) for n in ORDERS}


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
    dispersion: sp.Expr  # omega(k), eq. continuum2 (or discrete2)
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


@dataclass
class _Problem:
    """One case on one model, and the envelope B(X1, T1, X2, T2) and its conjugate."""

    case: str
    model: object
    B = sp.Function("B")(*SLOW)
    Bc = sp.Function("Bbar")(*SLOW)  # complex conjugate of B, an independent symbol

    @property
    def coupled(self):
        return self.case == "coupled"

    def residuals(self, theta, U):
        """Residuals of the known fields; U is dropped in case (I)."""
        return self.model.residuals(theta, U if self.coupled else None)

    def harmonics(self, expr):
        return harmonics(expr, fast=self.model.fast_harmonics)


def _solve_nonsecular(problem, eqname, src_harm, skip=(1, -1)):
    """Particular solution sum_m s_m/L0(m) e^{i m sigma} over non-resonant harmonics."""
    sol, notes = sp.S.Zero, []
    for m, s in src_harm.items():
        if m in skip:
            continue
        L = problem.model.linear_symbol(eqname, m)
        if sp.simplify(L) == 0:
            if sp.simplify(s) != 0:
                raise ArithmeticError(f"resonant non-secular forcing in {eqname} at m={m}")
            notes.append(f"{eqname}: harmonic m={m} is homogeneous; set to zero")
            continue
        sol += sp.simplify(s / L) * sp.exp(sp.I * m * PHASE)
    return sol, notes


def order1(p: _Problem):
    """O(eps): theta1 = B e^{i sigma} + c.c. solves it iff omega is on the branch."""
    theta1 = p.B * E + p.Bc / E
    u1 = p.model.leading_U(p.coupled)
    _, r_th = p.residuals(eps * theta1, eps * u1)
    h1 = p.harmonics(by_order(r_th)[1])
    disp_eq = sp.simplify(h1[1] / p.B)
    omega = [s for s in sp.solve(disp_eq, w) if s.is_positive is not False][0]
    rec = OrderRecord(1, source_theta=h1, condition=sp.Eq(disp_eq, 0))
    rec.notes.append("u1 = 0 and theta1 = B e^{i sigma} + c.c.; the O(eps) rotational "
                     "equation is satisfied iff omega solves the dispersion relation")
    return {"theta1": theta1, "u1": u1, "omega": omega, "record": rec}


def order2(p: _Problem, o1):
    """O(eps^2): the secular term gives B_T1 = -v_g B_X1; theta2, u2 from the rest."""
    r_U, r_th = p.residuals(eps * o1["theta1"], eps * o1["u1"])
    src_th = p.harmonics(-by_order(r_th)[2])
    secular = src_th.get(1, sp.S.Zero)
    dB_T1 = sp.solve(secular, p.B.diff(T1))[0]
    rec = OrderRecord(2, source_theta=src_th, secular=secular,
                      condition=sp.Eq(p.B.diff(T1), dB_T1))
    theta2, notes = _solve_nonsecular(p, "theta", src_th)
    rec.notes += notes
    rec.theta_solution = theta2
    u2 = sp.S.Zero
    if p.coupled:
        rec.source_U = p.harmonics(-by_order(r_U)[2])
        u2, notes = _solve_nonsecular(p, "U", rec.source_U, skip=())
        rec.notes += notes
        rec.U_solution = u2
    u2_parts = p.harmonics(u2) if p.coupled else {}
    c_u2 = sp.simplify(u2_parts.get(2, sp.S.Zero) / p.B**2) if p.coupled else sp.S.Zero
    return {"dB_T1": dB_T1, "v_g": sp.simplify(-dB_T1 / p.B.diff(X1)), "theta2": theta2,
            "u2": u2, "u2_parts": u2_parts, "c_u2": c_u2, "record": rec}


def _symbolic_u2(p, o2):
    """u2 as symbols c_m B^2 e^{2 i sigma}, and their values.

    On the lattice the value of u2 has trigonometric denominators that would swell every
    product at O(eps^3): carry symbols, substitute at the end."""
    u2, values = sp.S.Zero, {}
    for m, c in o2["u2_parts"].items():
        sym = sp.Symbol(f"c_u{'m' if m < 0 else 'p'}{abs(m)}")
        amp = p.B**2 if m > 0 else p.Bc**2
        values[sym] = o2["c_u2"] if m == 2 else (sp.simplify(c / amp) if m else c)
        u2 += sym * (amp if m else 1) * sp.exp(sp.I * m * PHASE)
    return u2, values


def _mean_flow(p, r_U, dB_T1, vg_expr):
    """Mean strain F_X1 = mu |B|^2 from the zeroth harmonic of the U equation at O(eps^3).

    In the frame moving with v_g, F_T1 = -v_g F_X1 (and B_T1 = -v_g B_X1, the O(eps^2)
    condition), so the equation reads a F_X1X1 + b (B Bbar)_X1 = 0: F_X1 = -b/a B Bbar
    (the integration constant is the mean strain of the unmodulated wave: zero on a
    periodic chain).
    """
    F, B, Bc = p.model.F, p.B, p.Bc
    eq = p.harmonics(by_order(r_U)[3]).get(0, sp.S.Zero)
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
        SLOW[2]: lambda f: f.diff(xi2),
        SLOW[3]: lambda f: f.diff(tau2) - v_g * f.diff(xi2),
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


def order3(p: _Problem, o1, o2):
    """O(eps^3): the secular term, in the frame moving with v_g, is the NLS."""
    u2, values = _symbolic_u2(p, o2) if p.model.has_mean_flow(p.coupled) else (o2["u2"], {})
    r_U, r_th = p.residuals(eps * o1["theta1"] + eps**2 * o2["theta2"],
                            eps * o1["u1"] + eps**2 * u2)
    src = p.harmonics(-by_order(r_th)[3])
    secular = src.get(1, sp.S.Zero)
    rec = OrderRecord(3, source_theta=src, secular=secular)
    mean_flow, mu = sp.S.Zero, sp.Symbol("mu")  # mu: substituted at the end, like u2
    if p.model.has_mean_flow(p.coupled):
        mean_flow, mf_eq = _mean_flow(p, r_U, o2["dB_T1"], o2["v_g"])
        values[mu] = mean_flow
        secular = secular.subs(p.model.F.diff(X1), mu * p.B * p.Bc)
        if secular.has(p.model.F):
            raise ArithmeticError("mean flow enters the secular term beyond its strain")
        rec.secular = secular
        rec.notes.append("mean flow: zeroth harmonic of the U equation at O(eps^3), "
                         f"{sp.sstr(mf_eq)} = 0, gives F_X1 = mu |B|^2")
    sec_frame, A = _moving_frame(secular, p.B)
    Ab = sp.Function("Abar")(xi1, tau1, xi2, tau2)
    sec_frame = sp.expand(sec_frame.xreplace({p.Bc: Ab}).subs(v_g, o2["v_g"]))
    if p.model.fast_harmonics:  # linear in A_tau2; sympy.solve chokes on trig terms
        c_tau = sec_frame.coeff(A.diff(tau2))
        A_tau = -sp.expand(sec_frame - c_tau * A.diff(tau2)) / c_tau
    else:
        A_tau = sp.solve(sec_frame, A.diff(tau2))[0]
    # i A_tau2 + g1/2 A_xi1xi1 + g2 |A|^2 A = 0  <=>  A_tau2 = i g1/2 A'' + i g2 |A|^2 A
    A_tau = sp.expand(A_tau)
    g1 = sp.simplify(2 * A_tau.coeff(A.diff(xi1, 2)) / sp.I)
    g2_raw = A_tau.coeff(A**2 * Ab) / sp.I
    g2 = sp.simplify(g2_raw.subs(values))
    leftover = sp.simplify((A_tau - sp.I * g1 / 2 * A.diff(xi1, 2)).subs(values)
                           - sp.I * g2 * A**2 * Ab)
    if leftover != 0:
        raise ArithmeticError(f"secular term not of NLS form: {leftover}")
    rec.condition = sp.Eq(A.diff(tau2), A_tau)
    g2_mf = sp.simplify(sp.expand(g2_raw).coeff(mu) * mean_flow) if mu in values else 0
    return {"g1": g1, "g2": g2, "g2_mean_flow": g2_mf, "mean_flow": mean_flow, "A": A,
            "Abar": Ab, "record": rec}


def solve_case(case: str, model="continuum") -> CaseResult:
    """Solve the hierarchy to O(eps^3) for ``case`` in {"rotation", "coupled"}.

    ``model="continuum"`` is the paper's derivation (eqs. `eqnorm1`-`eqnorm2`, no mean
    flow). ``model="lattice"`` repeats it on eq. `norm` itself (semi-discrete NLS):
    exact carrier on the lattice, and in case (II) the induced mean flow u1 = F(X1, ...)
    (zeroth harmonic of U), fixed by the O(eps^3) zeroth harmonic of the U equation.
    """
    if case not in CASES:
        raise ValueError(f"case must be one of {CASES}, got {case!r}")
    m = get_model(model)
    p = _Problem(case, m)
    o1 = order1(p)
    o2 = order2(p, o1)
    o3 = order3(p, o1, o2)
    on_shell = {w: o1["omega"]}
    A, Ab = o3["A"], o3["Abar"]
    lattice = m.fast_harmonics
    return CaseResult(
        case=case,
        dispersion=o1["omega"],
        group_velocity=sp.simplify(o2["v_g"].subs(on_shell)),
        g1=sp.simplify(o3["g1"].subs(on_shell)),
        # on the lattice a full simplify of g2 costs ~10 s and gains little: substitute only
        g2=o3["g2"].subs(on_shell) if lattice else sp.simplify(o3["g2"].subs(on_shell)),
        u2_coefficient=sp.simplify(o2["c_u2"].subs(on_shell)),
        mean_flow=sp.simplify(sp.S(o3["mean_flow"]).subs(on_shell)),
        g2_mean_flow=sp.S(o3["g2_mean_flow"]).subs(on_shell),
        nls=sp.I * A.diff(tau2) + o3["g1"] / 2 * A.diff(xi1, 2) + o3["g2"] * A**2 * Ab,
        hierarchy={} if lattice else generic_hierarchy(case, m),
        records=[o1["record"], o2["record"], o3["record"]],
    )
