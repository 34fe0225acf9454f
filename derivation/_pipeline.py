"""Run the whole derivation: continuum limit, both cases, MI analysis."""

from __future__ import annotations

from dataclasses import dataclass
from functools import lru_cache

import sympy as sp

from . import _continuum, _mi, _multiscale, paper_forms
from ._continuum import K_s, K_theta, alpha, k

#: Argument lists of the generated functions, by kind.
MATERIAL_ARGS = (k, alpha, K_s, K_theta)
MI_ARGS = (_mi.g, _mi.A0)
GROWTH_ARGS = (_mi.K, _mi.g, _mi.A0)


@dataclass(frozen=True)
class ClosedForm:
    """One derived quantity: its expression, arguments and documentation."""

    name: str
    expr: sp.Expr
    args: tuple
    doc: str
    label: str  # the paper's equation label it corresponds to
    #: names of arguments the quantity depends on through their size only, printed as
    #: |x| (the derivation assumes x > 0; the NLS's B -> -B symmetry makes |K_c| of
    #: A0 = -1 that of A0 = 1, where 2 A0 sqrt(g) printed as typed would be negative)
    even_in: tuple = ()


@dataclass(frozen=True)
class Derivation:
    continuum: _continuum.ContinuumLimit
    cases: dict  # case -> _multiscale.CaseResult
    mi: _mi.MIResult
    forms: tuple  # ClosedForm, in the order of the generated module
    lattice: dict  # case -> _multiscale.CaseResult of the semi-discrete derivation
    lattice_forms: tuple  # ClosedForm of generated/lattice_coefficients.py

    def form(self, name):
        return next(f for f in self.forms if f.name == name)


@lru_cache(maxsize=1)
def derive() -> Derivation:
    """Derive every closed form (about 3 s; cached per process)."""
    cont = _continuum.derive_continuum()
    mismatch = {n: sp.simplify(cont.C[n] - getattr(paper_forms, n)) for n in cont.C}
    if any(v != 0 for v in mismatch.values()):
        raise ArithmeticError(f"continuum limit disagrees with the paper's C_i: {mismatch}")
    cases = {c: _multiscale.solve_case(c) for c in _multiscale.CASES}
    rot, cpl = _same_linear_theory(cases, "")
    mi = _mi.analyse()
    # Omega_I is real inside the band; outside it the plane wave is stable: rate 0.
    R = sp.expand(mi.growth_rate**2 / _mi.K**2)
    growth = sp.Abs(_mi.K) * sp.sqrt(sp.Max(R, 0))

    forms = (
        ClosedForm("omega", rot.dispersion, MATERIAL_ARGS,
                   "Carrier frequency of the rotational branch, continuum limit.", "continuum2"),
        ClosedForm("group_velocity", rot.group_velocity, MATERIAL_ARGS,
                   "Group velocity v_g = d omega/dk, from the O(eps^2) solvability condition.",
                   "solvability_condition"),
        ClosedForm("g1", rot.g1, MATERIAL_ARGS,
                   "Dispersion coefficient of the NLS, g1 = d^2 omega/dk^2. Vanishes at "
                   "delta = 0 (alpha^2 delta = v_g^2).", "g_i"),
        ClosedForm("g2_rotation", rot.g2, MATERIAL_ARGS,
                   "Nonlinear coefficient of the NLS, case (I) (rotation only).", "g_i"),
        ClosedForm("g2_coupled", cpl.g2, MATERIAL_ARGS,
                   "Nonlinear coefficient of the NLS, case (II) (rotation + displacement). "
                   "Diverges at the resonance k^2 = omega^2.", "g_i"),
        ClosedForm("g_rotation", rot.g, MATERIAL_ARGS,
                   "g = g2/g1, case (I); g > 0: focusing (MI), g < 0: defocusing. "
                   "Diverges at delta = 0.", "g1"),
        ClosedForm("g_coupled", cpl.g, MATERIAL_ARGS,
                   "g = g2/g1, case (II). Diverges at delta = 0 and at k^2 = omega^2.", "g2"),
        ClosedForm("u2_coefficient", cpl.u2_coefficient, MATERIAL_ARGS,
                   "Complex c of the second-harmonic displacement, u2 = c B^2 e^{2 i sigma} + "
                   "c.c. (case II). Diverges at the resonance k^2 = omega^2.", "u1"),
        ClosedForm("mi_cutoff", mi.cutoff, MI_ARGS,
                   "Cutoff K_c of the unstable band |K| < K_c (NLS units, xi1 = eps X). "
                   "NaN for g < 0: there is no band. A0 enters as |A0| (B -> -B).", "kc",
                   even_in=("A0",)),
        ClosedForm("mi_fastest", mi.fastest, MI_ARGS,
                   "Fastest-growing perturbation wavenumber K_m. NaN for g < 0. A0 enters "
                   "as |A0| (B -> -B).", "K_m", even_in=("A0",)),
        ClosedForm("mi_growth_rate", growth, GROWTH_ARGS,
                   "Growth rate Omega_I(K) in the NLS time tilde-tau2 = g1 eps^2 T; 0 outside "
                   "the band (and for g <= 0). The lattice rate is eps^2 |g1| Omega_I.",
                   "Omega_I"),
    )
    lattice = {c: _multiscale.solve_case(c, "lattice") for c in _multiscale.CASES}
    return Derivation(continuum=cont, cases=cases, mi=mi, forms=forms, lattice=lattice,
                      lattice_forms=_lattice_forms(lattice, forms))


def _same_linear_theory(cases, label):
    """Both cases must share omega, v_g and g1 (U does not enter the linear theta wave)."""
    rot, cpl = cases["rotation"], cases["coupled"]
    for name in ("dispersion", "group_velocity", "g1"):
        if sp.simplify(getattr(rot, name) - getattr(cpl, name)) != 0:
            raise ArithmeticError(f"{label}{name} differs between the two cases")
    return rot, cpl


def _lattice_forms(lattice, forms):
    """The semi-discrete NLS closed forms, same names and arguments as the continuum's."""
    rot, cpl = _same_linear_theory(lattice, "lattice ")
    note = " Semi-discrete: derived from eq. `norm` itself (exact carrier on the lattice)."
    out = (
        ClosedForm("omega", rot.dispersion, MATERIAL_ARGS,
                   "Carrier frequency, the lattice's rotational branch." + note, "discrete2"),
        ClosedForm("group_velocity", rot.group_velocity, MATERIAL_ARGS,
                   "Group velocity d omega/dk of the lattice branch." + note,
                   "solvability_condition"),
        ClosedForm("g1", rot.g1, MATERIAL_ARGS,
                   "Dispersion coefficient g1 = d^2 omega/dk^2 of the lattice branch." + note,
                   "g_i"),
        ClosedForm("g2_rotation", rot.g2, MATERIAL_ARGS,
                   "Nonlinear coefficient, case (I): the lattice's own cubic terms "
                   "(neighbour products, shear nonlinearity)." + note, "g_i"),
        ClosedForm("g2_coupled", cpl.g2, MATERIAL_ARGS,
                   "Nonlinear coefficient, case (II): lattice cubic terms, the discrete "
                   "second harmonic of U (eq. `discrete1` at 2k) and the induced mean flow "
                   "(mean_flow_coefficient)." + note, "g_i"),
        ClosedForm("g_rotation", rot.g2 / rot.g1, MATERIAL_ARGS,
                   "g = g2/g1, case (I), lattice." + note, "g1"),
        ClosedForm("g_coupled", cpl.g2 / cpl.g1, MATERIAL_ARGS,
                   "g = g2/g1, case (II), lattice, mean flow included." + note, "g2"),
        ClosedForm("u2_coefficient", cpl.u2_coefficient, MATERIAL_ARGS,
                   "c in u2 = c B^2 e^{2 i sigma} + c.c. on the lattice: i sin 2k / "
                   "(8 (sin^2 k - omega^2)). Diverges at sin^2 k = omega^2." + note, "u1"),
        ClosedForm("mean_flow_coefficient", cpl.mean_flow, MATERIAL_ARGS,
                   "mu in the induced mean strain U_n+1 - U_n = eps^2 mu |A|^2 (zeroth "
                   "harmonic of U, driven by gradients of |A|^2): mu = 1/(v_g^2 - 1). The "
                   "paper sets it to zero; it adds -2 alpha^2 mu / omega = 2 alpha^2 / "
                   "(omega (1 - v_g^2)) > 0 to g2_coupled." + note, "u1"),
    )
    mi = tuple(f for f in forms if f.name.startswith("mi_"))
    return out + mi
