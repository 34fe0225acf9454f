"""The readable derivation report, generated/derivation.md (Markdown + LaTeX)."""

from __future__ import annotations

import sympy as sp

from common import paper

from . import paper_forms
from ._continuum import K_s, K_theta, alpha, k, lattice_accelerations
from ._scales import FAST_SLOW, SLOW, tau1, tau2, xi1, xi2
from .errata import ERRATA

#: The paper's two test points, as the arguments of the generated functions.
TEST_POINTS = {name: paper.parameters(name) for name in paper.POINTS}


def _arglist(args):
    """The LaTeX SymPy prints for an argument list, e.g. {\\left(X_{0},T_{0} \\right)}."""
    full = sp.latex(sp.Function("f")(*args))
    return full[full.index("{"):]


_ELIDED = tuple(_arglist(a) for a in (FAST_SLOW, SLOW, (xi1, tau1, xi2, tau2)))


def tex(expr):
    """LaTeX with the (X0, T0, ...) argument lists of the fields elided."""
    out = sp.latex(expr)
    for args in _ELIDED:
        out = out.replace(args, "")
    return out


def same(derived, typed):
    """True when derived - typed simplifies to exactly zero."""
    return sp.simplify(derived - typed) == 0


def compare_with_paper(derivation):
    """{name: (derived, paper, label, equal)} for every generated closed form."""
    out = {}
    for f in derivation.forms:
        paper, label = paper_forms.FORMS[f.name]
        derived = f.expr
        if f.name == "mi_growth_rate":
            derived = derivation.mi.growth_rate  # inside the band, where the paper's applies
        out[f.name] = (derived, paper, label, same(derived, paper))
    return out


def _eq(lhs, rhs="0"):
    return f"$$ {lhs} = {rhs} $$"


#: the closed forms tabulated at the test points (sections 6 and 8)
POINT_COLUMNS = ("omega", "group_velocity", "g1", "g_rotation", "g_coupled")


def _at_point(forms, point, names):
    """Values of the named closed forms (name -> ClosedForm) at a TEST_POINTS entry."""
    sub = {k: point["k"], alpha: point["alpha"], K_s: point["K_s"], K_theta: point["K_theta"]}
    return [forms[n].expr.subs(sub) for n in names]


def _section_discrete_equations(d):
    L = []
    add = L.append
    add("## 1. Discrete equations (eq. `norm`)")
    U, th = sp.symbols("U_{n-1} U_n U_{n+1}"), sp.symbols(r"\theta_{n-1} \theta_n \theta_{n+1}")
    aU, at = lattice_accelerations(*U, *th)
    add(_eq(r"\ddot U_n", tex(aU)))
    add(_eq(r"\ddot \theta_n", tex(at)))
    add("")
    return L


def _section_continuum_limit(d):
    L = []
    add = L.append
    add("## 2. Continuum limit (eqs. `eqnorm1`, `eqnorm2`), derived by Taylor expansion")
    add("Linear terms are kept to second order in the lattice spacing, nonlinear terms at "
        "their lowest order (weak nonlinearity, long waves), theta to cubic order, U counted "
        "as O(theta^2).")
    c = d.continuum
    add(_eq("U_{TT}", tex(c.eq_U)))
    add(_eq(r"\theta_{TT}", tex(c.eq_theta)))
    add("")
    add("| constant | derived | paper | equal |")
    add("|---|---|---|---|")
    for name, val in c.C.items():
        paper = getattr(paper_forms, name)
        add(f"| {name} | ${tex(val)}$ | ${tex(paper)}$ | {'yes' if same(val, paper) else 'NO'} |")
    add("")
    add(f"Terms discarded by the long-wave ordering ({len(c.dropped)}): "
        + ", ".join(f"${tex(t)}$" for t in c.dropped))
    add("")
    return L


def _section_multiple_scales(d):
    L = []
    add = L.append
    add("## 3. Multiple scales (eq. `msm`)")
    add("Fields: $U = \\sum_i \\epsilon^i u_i$, $\\theta = \\sum_i \\epsilon^i \\theta_i$, "
        "functions of $X_0, T_0, X_1, T_1, X_2, T_2$ with $X_i = \\epsilon^i X$, "
        "$T_i = \\epsilon^i T$; $\\partial_T = D_0 + \\epsilon D_1 + \\epsilon^2 D_2$ "
        "(eq. `diff`). Residuals (lhs - rhs) collected at each order:")
    for case, res in d.cases.items():
        add("")
        add(f"### Case {'(I) rotation only' if case == 'rotation' else '(II) coupled'}")
        for n, (rU, rth) in res.hierarchy.items():
            add(f"**O(eps^{n})**")
            if rU is not None:
                add(_eq(tex(rU)))
            add(_eq(tex(rth)))
        for rec in res.records:
            add(f"**Solving O(eps^{rec.order})**")
            if rec.order == 1:
                add("Leading order $u_1 = 0$, $\\theta_1 = B e^{i\\sigma} + c.c.$, "
                    "$\\sigma = k X_0 - \\omega T_0$. The coefficient of $e^{i\\sigma}$ "
                    "vanishes iff (dispersion relation, eq. `continuum2`):")
                add(_eq(tex(rec.condition.lhs)))
                continue
            add("Harmonics of the rotational source (coefficient of $e^{im\\sigma}$):")
            for m, s in rec.source_theta.items():
                add(f"- m = {m}: ${tex(s)}$")
            if rec.source_U:
                add("Harmonics of the displacement source:")
                for m, s in rec.source_U.items():
                    add(f"- m = {m}: ${tex(s)}$")
            add("Secular term (m = 1) set to zero:")
            add(_eq(tex(rec.condition.lhs), tex(rec.condition.rhs)))
            if rec.order == 2:
                add(f"Non-secular solution: $\\theta_2 = {tex(rec.theta_solution)}$"
                    + (f", $u_2 = {tex(rec.U_solution)}$" if rec.source_U else ""))
            for note in rec.notes:
                add(f"- {note}")
            add("")
        add("Resulting NLS (eq. `NLS`) in $\\xi_1 = X_1 - v_g T_1$, $\\tau_2 = T_2$:")
        add(_eq(tex(res.nls)))
        add("")
    add("The zeroth harmonic of $u_2$ (the induced mean flow) satisfies the homogeneous "
        "equation at $O(\\epsilon^2)$ and is set to zero, as in the paper.")
    add("")
    return L


def _section_closed_forms(d):
    L = []
    add = L.append
    add("## 4. Closed forms (generated into `generated/coefficients.py`)")
    for f in d.forms:
        add(f"- `{f.name}{tuple(str(a) for a in f.args)}` (eq. `{f.label}`): "
            f"${tex(f.expr)}$")
    add("")
    return L


def _section_mi_analysis(d):
    L = []
    add = L.append
    add("## 5. Modulation instability of the NLS (eqs. `perturbed` .. `K_m`)")
    mi = d.mi
    add(f"Plane wave: $\\omega_0 = {tex(mi.omega0)}$. Linearised perturbation equations:")
    for e in mi.perturbation_equations:
        add(_eq(tex(e.lhs)))
    add(f"Perturbation dispersion: $\\Omega = {tex(mi.branches[0])}$ and "
        f"${tex(mi.branches[1])}$.")
    add(f"Cutoff $K_c = {tex(mi.cutoff)}$, fastest $K_m = {tex(mi.fastest)}$, growth "
        f"$\\Omega_I = {tex(mi.growth_rate)}$, peak $\\Omega_I(K_m) = {tex(mi.peak_growth)}$.")
    add("")
    return L


def _section_test_points(d):
    L = []
    add = L.append
    add(f"## 6. The paper's test points (alpha = {paper.ALPHA}, K_s = {paper.K_S})")
    add("| point | k | delta | omega | v_g | g1 | g (I) | g (II) | abs(u2 coefficient) |")
    add("|---|---|---|---|---|---|---|---|---|")
    continuum = {f.name: f for f in d.forms}
    for name, p in TEST_POINTS.items():
        vals = _at_point(continuum, p, POINT_COLUMNS)
        cu = sp.Abs(_at_point(continuum, p, ("u2_coefficient",))[0])
        cells = " | ".join(f"{float(v):.6g}" for v in (*vals, cu))
        add(f"| {name} | {p['k']} | {p['K_s'] - p['K_theta']:.3g} | {cells} |")
    add("")
    return L


def _section_paper_comparison(d):
    L = []
    add = L.append
    add("## 7. Comparison with the paper's typed forms (`derivation/paper_forms.py`)")
    add("| quantity | paper eq. | derived - paper simplifies to 0 |")
    add("|---|---|---|")
    for name, (_, _, label, ok) in compare_with_paper(d).items():
        add(f"| `{name}` | `{label}` | {'yes' if ok else '**NO**'} |")
    add("")
    return L


def _section_semi_discrete(d):
    L = []
    add = L.append
    add("## 8. Semi-discrete NLS: the same derivation on the lattice (`generated/lattice_coefficients.py`)")
    add("The hierarchy is rebuilt from eq. `norm` itself: a neighbour is the exact shift "
        "$e^{i m k j}$ of each carrier harmonic times the Taylor shift of the slow scales, "
        "$B(X_1 \\pm \\epsilon, X_2 \\pm \\epsilon^2)$; sin and cos are expanded to cubic "
        "order; every other step (harmonic projection, secular terms, moving frame) is the "
        "code of sections 3-4. Terms the lattice adds to the paper's derivation, and why "
        "each belongs:")
    add("- **discrete dispersion** (eq. `discrete2`) and its curvature: the carrier is "
        "$e^{i(kn - \\omega t)}$ exactly, so omega, v_g, g1 are those of the lattice branch, "
        "not their $O(k^2)$ Taylor forms (k = 0.8-0.93 at the test points is not small).")
    add("- **lattice cubic terms**: $\\theta_n \\theta_{n\\pm1}^2$, "
        "$\\cos\\theta_n \\sin\\theta_{n\\pm1}$ project on $e^{i\\sigma}$ with factors "
        "$e^{\\pm 2ik}$, $\\cos k$ that the continuum sets to 1.")
    add("- **discrete second harmonic of U**: its operator is eq. `discrete1` at 2k, "
        "$4\\sin^2 k - 4\\omega^2$, not $4k^2 - 4\\omega^2$; at the green point the two "
        "even differ in sign.")
    add("- **induced mean flow**: the zeroth harmonic $u_1 = F$ of U is not set to zero; the "
        "$O(\\epsilon^3)$ zeroth harmonic of the U equation fixes its strain, "
        "$F_{X_1} = \\mu |B|^2$, which feeds back through $\\theta_n (U_{n+1} - U_{n-1})$.")
    add("")
    for case, res in d.lattice.items():
        add(f"**Case {'(I)' if case == 'rotation' else '(II)'}**, order by order:")
        for rec in res.records[1:]:
            add(f"- O(eps^{rec.order}) secular condition: "
                f"${tex(rec.condition.lhs)} = {tex(rec.condition.rhs)}$")
            for note in rec.notes:
                add(f"  - {note}")
        add("")
    add("| quantity | continuum (paper) | lattice |")
    add("|---|---|---|")
    continuum = {f.name: f for f in d.forms}
    lat = {f.name: f for f in d.lattice_forms}
    for f in d.forms:
        if f.name in lat and not f.name.startswith("mi_"):
            add(f"| `{f.name}` | ${tex(f.expr)}$ | ${tex(lat[f.name].expr)}$ |")
    add(f"| `mean_flow_coefficient` | 0 (omitted) | ${tex(lat['mean_flow_coefficient'].expr)}$ |")
    add(f"| mean-flow part of `g2_coupled` | 0 | "
        f"${tex(sp.simplify(d.lattice['coupled'].g2_mean_flow))}$ |")
    add("")
    add(f"At the test points (alpha = {paper.ALPHA}, K_s = {paper.K_S}):")
    add("")
    add("| point | model | omega | v_g | g1 | g (I) | g (II) | mean flow mu |")
    add("|---|---|---|---|---|---|---|---|")
    for name, p in TEST_POINTS.items():
        for model, forms in (("continuum", continuum), ("lattice", lat)):
            vals = [float(v) for v in _at_point(forms, p, POINT_COLUMNS)]
            mu = (float(_at_point(lat, p, ("mean_flow_coefficient",))[0])
                  if model == "lattice" else 0.0)
            add(f"| {name} | {model} | " + " | ".join(f"{v:.6g}" for v in vals) + f" | {mu:.4g} |")
    add("")
    return L


def _section_errata(d):
    L = []
    add = L.append
    add("## 9. Errata")
    for i, e in enumerate(ERRATA, 1):
        add(f"{i}. **{e['where']}.** Says: {e['says']}. Right: {e['right']}. "
            f"How we know: {e['how']}.")
    return L

#: The report's sections, in order; each returns its Markdown lines.
SECTIONS = (_section_discrete_equations, _section_continuum_limit, _section_multiple_scales,
            _section_closed_forms, _section_mi_analysis, _section_test_points,
            _section_paper_comparison, _section_semi_discrete, _section_errata)


def render(derivation) -> str:
    """The whole of generated/derivation.md."""
    L = [f"<!-- GENERATED FILE - DO NOT EDIT BY HAND. Written by `make derive` "
         f"(SymPy {sp.__version__}). -->",
         "# Derivation report: NLS for rotational waves in a flexible mechanical metamaterial",
         "",
         "Every expression below is computed by `derivation/` from the equations of motion; "
         "nothing is copied from the paper except in the last section, where the paper's "
         "typed forms are compared with the derived ones.",
         ""]
    for section in SECTIONS:
        L += section(derivation)
    return "\n".join(L).rstrip() + "\n"
