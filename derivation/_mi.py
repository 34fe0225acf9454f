"""Modulation-instability analysis of the normalised NLS (eqs. `NLS_final` .. `K_m`).

The plane wave B = A0 e^{i(k0 xi - omega0 tau)} of i B_tau + B_xixi/2 + g|B|^2 B = 0
is perturbed in amplitude and phase (eq. `perturbed`), the perturbation equations are
linearised, and harmonic perturbations (eq. `b and theta`) give a 2x2 determinant whose
roots are Omega(K). Everything below is computed, not typed.
"""

from __future__ import annotations

from dataclasses import dataclass

import sympy as sp

g = sp.Symbol("g", real=True)
A0 = sp.Symbol("A0", positive=True)
K = sp.Symbol("K", real=True)
k0 = sp.Symbol("k0", real=True)
Omega = sp.Symbol("Omega")
xi, tau = sp.symbols("xi tau", real=True)


@dataclass(frozen=True)
class MIResult:
    """Closed forms of the MI analysis.

    Attributes
    ----------
    omega0 : plane-wave frequency omega0(k0, g, A0)
    branches : the two roots Omega(K) of the perturbation dispersion relation
    discriminant : the expression under the square root; MI where it is < 0
    cutoff : K_c (eq. `kc`), fastest : K_m (eq. `K_m`)
    growth_rate : Omega_I(K) inside the band (eq. `Omega_I`)
    peak_growth : Omega_I(K_m)
    """

    omega0: sp.Expr
    perturbation_equations: tuple
    branches: tuple
    discriminant: sp.Expr
    cutoff: sp.Expr
    fastest: sp.Expr
    growth_rate: sp.Expr
    peak_growth: sp.Expr


def analyse() -> MIResult:
    small = sp.Symbol("small", positive=True)  # perturbation book-keeping (not K_s - K_theta)
    w0 = sp.Symbol("omega0", real=True)
    b = sp.Function("b", real=True)(xi, tau)
    ph = sp.Function("phi", real=True)(xi, tau)
    phase = k0 * xi - w0 * tau + small * ph
    amp = A0 + small * b
    # B = amp e^{i phase}; divide the NLS residual by e^{i phase} analytically:
    # B_tau/e = amp_tau + i amp phase_tau, B_xixi/e = amp'' + 2 i amp' phase' + i amp phase''
    #           - amp phase'^2
    res = (sp.I * (amp.diff(tau) + sp.I * amp * phase.diff(tau))
           + sp.Rational(1, 2) * (amp.diff(xi, 2) + 2 * sp.I * amp.diff(xi) * phase.diff(xi)
                                  + sp.I * amp * phase.diff(xi, 2)
                                  - amp * phase.diff(xi) ** 2)
           + g * amp**3)
    res = sp.expand(res)
    zeroth = res.coeff(small, 0)
    omega0 = sp.solve(zeroth, w0)[0]
    first = sp.expand(res.coeff(small, 1).subs(w0, omega0))
    # b, phi and their derivatives are real: swap them for real symbols to split parts
    atoms = sorted(first.atoms(sp.Derivative) | {b, ph}, key=sp.default_sort_key)
    real = {a: sp.Dummy(real=True) for a in atoms}
    back = {v: a for a, v in real.items()}
    flat = first.xreplace(real)
    re_part = sp.expand(sp.re(flat)).xreplace(back)
    im_part = sp.expand(sp.im(flat)).xreplace(back)
    # harmonic perturbations b = f1 e^{i(K xi - Omega tau)}, phi = f2 e^{...}
    f1, f2 = sp.symbols("f1 f2")
    wave = sp.exp(sp.I * (K * xi - Omega * tau))
    rows = []
    for part in (re_part, im_part):
        e = part.subs({b: f1 * wave, ph: f2 * wave}).doit()
        e = sp.expand(sp.simplify(e / wave))
        rows.append([e.coeff(f1), e.coeff(f2)])
    M = sp.Matrix(rows)
    det = sp.expand(M.det())
    roots = sp.solve(det, Omega)
    # Omega = K k0 +- sqrt(D): read D off a root
    D = sp.expand((roots[0] - K * k0) ** 2)
    # D = K^2 R(K): Omega = K k0 +- |K| sqrt(R), checked against the determinant
    R = sp.cancel(D / K**2)
    if sp.cancel(D - K**2 * R) != 0 or R.has(sp.Pow(K, -1)):
        raise ArithmeticError(f"discriminant not of the form K^2 R: {D}")
    branches = (K * k0 + sp.Abs(K) * sp.sqrt(R), K * k0 - sp.Abs(K) * sp.sqrt(R))
    for br in branches:
        if sp.simplify(sp.expand(det.subs(Omega, br))) != 0:
            raise ArithmeticError(f"{br} is not a root of the MI determinant")
    nonzero = [r for r in sp.solve(R, K) if r != 0]
    cutoff = [r for r in nonzero if r.subs({g: 1, A0: 1}).is_positive][0]
    growth = sp.Abs(K) * sp.sqrt(-R)
    crit = [r for r in sp.solve(sp.diff(-D, K), K) if r != 0]  # extrema of Omega_I^2
    fastest = [r for r in crit if r.subs({g: 1, A0: 1}).is_positive][0]
    gp = sp.Symbol("g", positive=True)  # the peak exists only for g > 0
    peak = sp.simplify(growth.subs(g, gp).subs(K, fastest.subs(g, gp))).subs(gp, g)
    return MIResult(
        omega0=omega0,
        perturbation_equations=(sp.Eq(re_part, 0), sp.Eq(im_part, 0)),
        branches=branches,
        discriminant=D,
        cutoff=cutoff,
        fastest=fastest,
        growth_rate=growth,
        peak_growth=peak,
    )
