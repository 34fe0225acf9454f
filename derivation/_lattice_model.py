"""Eq. `norm` as generated code: accelerations, their Jacobian, the linear dispersion.

Everything here is computed from ``lattice_accelerations`` (the one SymPy text of
eq. `norm`): the Jacobian by ``sympy.diff``, the two branches of the linear lattice by
inserting a plane wave e^{i q n} into the Jacobian at rest. ``make derive`` prints them
into ``generated/lattice_model.py``, which Hill's method and the plain NumPy force use;
the hand-tuned Numba kernel is tested against it.
"""

from __future__ import annotations

import sympy as sp

from ._continuum import K_s, K_theta, alpha, lattice_accelerations

U_m, U_0, U_p = sp.symbols("U_m U_0 U_p", real=True)
theta_m, theta_0, theta_p = sp.symbols("theta_m theta_0 theta_p", real=True)
q = sp.Symbol("q", real=True)
#: the neighbourhood of site n: U_{n-1}, U_n, U_{n+1}, theta_{n-1}, theta_n, theta_{n+1}
NEIGHBOURS = (U_m, U_0, U_p, theta_m, theta_0, theta_p)
MATERIAL = (alpha, K_s, K_theta)

MODULE_DOC = """Eq. `norm` of Demiquel, Achilleos, Theocharis & Tournat as NumPy functions.

Generated from the SymPy text of the discrete equations (derivation/_continuum.py,
``lattice_accelerations``): the accelerations of site n from its neighbourhood
(U_m, U_0, U_p) = (U_{n-1}, U_n, U_{n+1}), likewise theta; their Jacobian with respect
to the six neighbour values (by ``sympy.diff``); and the two branches of the linear
lattice (eqs. `discrete1`, `discrete2`), derived from the Jacobian at rest.
Arguments broadcast like NumPy; theta in rad, time in units of sqrt(m / k_l).
"""


def forms(closed_form):
    """The ClosedForm tuple of generated/lattice_model.py (``closed_form`` is the class)."""
    acc_U, acc_t = lattice_accelerations(*NEIGHBOURS)
    args = NEIGHBOURS + MATERIAL
    jac = sp.Matrix([[sp.diff(a, v) for v in NEIGHBOURS] for a in (acc_U, acc_t)])
    rest = {v: 0 for v in NEIGHBOURS}
    # plane wave x_{n+j} = e^{i q j} x_n: omega^2 = -(sum_j J_j e^{i q j}) on each branch
    shifts = (sp.exp(-sp.I * q), 1, sp.exp(sp.I * q))
    w2_U = -sum(jac[0, j].subs(rest) * s for j, s in enumerate(shifts))
    w2_t = -sum(jac[1, 3 + j].subs(rest) * s for j, s in enumerate(shifts))
    # half-angle form, cos q = 1 - 2 sin^2(q/2): no cancellation as q -> 0
    half = {sp.cos(q): 1 - 2 * sp.sin(q / 2) ** 2}
    w2_U = sp.factor(sp.expand(sp.expand_complex(w2_U).rewrite(sp.cos).subs(half)))
    w2_t = sp.collect(sp.expand(sp.expand_complex(w2_t).rewrite(sp.cos).subs(half)),
                      sp.sin(q / 2) ** 2)
    coupling = [jac[0, 3 + j].subs(rest) for j in range(3)] + \
               [jac[1, j].subs(rest) for j in range(3)]
    if any(c != 0 for c in coupling):
        raise ArithmeticError("U and theta are coupled at rest: the branches do not split")
    return (
        closed_form("acceleration_U", acc_U, args,
                    "d^2 U_n / dT^2 from the neighbourhood of site n.", "norm"),
        closed_form("acceleration_theta", acc_t, args,
                    "d^2 theta_n / dT^2 (alpha^2 included) from the neighbourhood of site n.",
                    "norm"),
        closed_form("jacobian", jac, args,
                    "Jacobian of (acceleration_U, acceleration_theta) with respect to "
                    "(U_m, U_0, U_p, theta_m, theta_0, theta_p): shape (2, 6) + the "
                    "broadcast shape of the arguments.", "norm"),
        closed_form("omega_longitudinal", sp.sqrt(w2_U), (q,),
                    "Longitudinal branch of the linear lattice, omega_U(q) >= 0.", "discrete1"),
        closed_form("omega_rotation", sp.sqrt(w2_t), (q,) + MATERIAL,
                    "Rotational branch of the linear lattice, omega_theta(q) > 0.",
                    "discrete2"),
    )
