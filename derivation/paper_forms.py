"""Closed forms typed by hand from the paper, as SymPy expressions.

Each is cited by the paper's equation label. They are *not* used by the pipeline:
tests check that the derived expressions minus these simplify to exactly zero, and
that the generated NumPy functions agree with them numerically. Where the paper is
wrong, the typed form is still the paper's and the erratum says so (see README).
"""

import sympy as sp

from ._continuum import K_s, K_theta, alpha, k
from ._mi import A0, K, g

#: Constants below eq. `eqnorm2`.
C1 = alpha**2 * (K_s - K_theta)
C2 = 6 * K_theta * alpha**2
C3 = 2 * alpha**2
C4 = 4 * alpha**2
delta = K_s - K_theta

#: eq. `continuum2`
omega = sp.sqrt(C1 * k**2 + C2)
#: text below eq. `solvability_condition`
group_velocity = C1 * k / sp.sqrt(C1 * k**2 + C2)
#: eq. `g_i`, first line
g1 = (C1 - group_velocity**2) / sp.sqrt(C1 * k**2 + C2)
#: eq. `g_i`, second line (case II)
g2_coupled = -1 / (2 * sp.sqrt(C1 * k**2 + C2)) * (
    3 * C3 + C4 * k**2 / (2 * k**2 * (C1 - 1) + 2 * C2))
#: eq. `g_i` without the U coupling (C4 -> 0): case I has no displacement field.
#: The paper gives g for case I (eq. `g1`) but not g2; this is g2 = g * g1.
g2_rotation = -1 / (2 * sp.sqrt(C1 * k**2 + C2)) * 3 * C3
#: eq. `g1` (case I)
g_rotation = -3 * alpha**2 / (delta * alpha**2 - group_velocity**2)
#: eq. `g2` (case II)
g_coupled = -3 * alpha**2 / (delta * alpha**2 - group_velocity**2) * (
    1 + k**2 / (3 * k**2 * (alpha**2 * delta - 1) + 18 * K_theta * alpha**2))
#: eq. `u1`: u2 = i k B^2 / (4 (k^2 - omega^2)) e^{2 i sigma} + c.c.
u2_coefficient = sp.I * k / (4 * (k**2 - omega**2))
#: eq. `kc`
mi_cutoff = 2 * A0 * sp.sqrt(g)
#: eq. `K_m`
mi_fastest = A0 * sp.sqrt(2 * g)
#: eq. `Omega_I`, inside the band |K| < K_c
mi_growth_rate = sp.Abs(K) * A0 * sp.sqrt(g - K**2 / (4 * A0**2))

#: name -> (expression, equation label), for the report and the tests
FORMS = {
    "omega": (omega, "continuum2"),
    "group_velocity": (group_velocity, "solvability_condition"),
    "g1": (g1, "g_i"),
    "g2_rotation": (g2_rotation, "g_i (C4 = 0)"),
    "g2_coupled": (g2_coupled, "g_i"),
    "g_rotation": (g_rotation, "g1"),
    "g_coupled": (g_coupled, "g2"),
    "u2_coefficient": (u2_coefficient, "u1"),
    "mi_cutoff": (mi_cutoff, "kc"),
    "mi_fastest": (mi_fastest, "K_m"),
    "mi_growth_rate": (mi_growth_rate, "Omega_I"),
}
