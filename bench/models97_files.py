"""Probe 97's model files (TOML texts, ``MODELS``) and what is known of them by hand: the
linear branches (``omega_by_hand``), the FPUT chain a unit-stiffness bond is to fourth
order (``bond_fput``) and FPUT's g2 with its mean flow (``fput_g2``). The checks that use
them are ``bench.probe_models97``'s (its docstring describes each model); tests import
the texts from there too.
"""

from __future__ import annotations

import math

import numpy as np

MODELS = {
    "tri3": '''name = "tri3"
description = "triatomic chain, masses 1, 2, 3, cubic-quartic springs"
fields = ["u", "v", "w"]
branch = "u"
[parameters]
m2 = 2.0
m3 = 3.0
alpha = 0.4
beta = 0.5
[energy]
kinetic = "u_t**2/2 + m2*v_t**2/2 + m3*w_t**2/2"
site = "(v - u)**2/2 + alpha*(v - u)**3/3 + beta*(v - u)**4/4 + (w - v)**2/2 + alpha*(w - v)**3/3 + beta*(w - v)**4/4"
bond = "(u_next - w)**2/2 + alpha*(u_next - w)**3/3 + beta*(u_next - w)**4/4"
''',
    # the same chain, fields reordered and renamed (w -> a, u -> b, v -> c)
    "tri3-relabelled": '''name = "tri3-relabelled"
fields = ["a", "b", "c"]
branch = "b"
[parameters]
m2 = 2.0
m3 = 3.0
alpha = 0.4
beta = 0.5
[energy]
kinetic = "m3*a_t**2/2 + b_t**2/2 + m2*c_t**2/2"
site = "(c - b)**2/2 + alpha*(c - b)**3/3 + beta*(c - b)**4/4 + (a - c)**2/2 + alpha*(a - c)**3/3 + beta*(a - c)**4/4"
bond = "(b_next - a)**2/2 + alpha*(b_next - a)**3/3 + beta*(b_next - a)**4/4"
''',
    "morse": '''name = "morse"
fields = ["u"]
[parameters]
b = 1.2
[energy]
kinetic = "u_t**2/2"
bond = "(1 - exp(-b*(u_next - u)))**2/(2*b**2)"
''',
    "lj": '''name = "lj"
fields = ["u"]
[parameters]
eps = 0.013888888888888888
[energy]
kinetic = "u_t**2/2"
bond = "eps*((1 + u_next - u)**(-12) - 2*(1 + u_next - u)**(-6) + 1)"
''',
    "hertz-pre": '''name = "hertz-pre"
description = "Hertz contact with precompression d0, 0 the equilibrium; it opens at r = d0"
fields = ["u"]
[parameters]
d0 = 0.5
[energy]
kinetic = "u_t**2/2"
bond = "(2/(3*sqrt(d0)))*((2/5)*((d0 - (u_next - u) + Abs(d0 - (u_next - u)))/2)**(5/2) - (2/5)*d0**(5/2) + d0**(3/2)*(u_next - u))"
''',
    "hertz-closed": '''name = "hertz-closed"
fields = ["u"]
[parameters]
d0 = 0.5
[energy]
kinetic = "u_t**2/2"
bond = "(2/(3*sqrt(d0)))*((2/5)*(d0 - (u_next - u))**(5/2) - (2/5)*d0**(5/2) + d0**(3/2)*(u_next - u))"
''',
    "bilinear": '''name = "bilinear"
fields = ["u"]
[parameters]
k1 = 1.0
k2 = 3.0
[energy]
kinetic = "u_t**2/2"
bond = "(k1 + k2)*(u_next - u)**2/4 + (k2 - k1)*(u_next - u)*Abs(u_next - u)/4"
''',
    "split": '''name = "split"
description = "u: inter-site quartic only; v: on-site quartic only; linear strain coupling"
fields = ["u", "v"]
branch = "u"
[parameters]
beta_bond_quartic_stiffness_of_the_u_chain = 1.0
Cv = 0.3
w0 = 1.5
lam = 1.0
eps_zero_by_default = 0.0
[energy]
kinetic = "u_t**2/2 + v_t**2/2"
bond = "(u_next - u)**2/2 + beta_bond_quartic_stiffness_of_the_u_chain*(u_next - u)**4/4 + Cv*(v_next - v)**2/2 + eps_zero_by_default*(u_next - u)*v"
site = "w0**2*v**2/2 + lam*v**4/4"
''',
    "stiff": '''name = "stiff"
fields = ["u"]
[parameters]
K = 1e6
m = 1e-3
alpha = 0.5
beta = 1.0
[energy]
kinetic = "m*u_t**2/2"
bond = "K*((u_next - u)**2/2 + alpha*(u_next - u)**3/3 + beta*(u_next - u)**4/4)"
''',
    "heavy": '''name = "heavy"
fields = ["u", "v"]
branch = "u"
[parameters]
M = 1000.0
beta = 1.0
[energy]
kinetic = "u_t**2/2 + M*v_t**2/2"
site = "(v - u)**2/2 + beta*(v - u)**4/4"
bond = "(u_next - v)**2/2 + beta*(u_next - v)**4/4"
''',
    "fput": '''name = "fput-ref"
fields = ["u"]
[parameters]
alpha = 0.4
beta = 0.5
[energy]
kinetic = "u_t**2/2"
bond = "(u_next - u)**2/2 + alpha*(u_next - u)**3/3 + beta*(u_next - u)**4/4"
''',
}


def fput_g2(alpha: float, beta: float, k: float) -> float:
    """FPUT's g2 with its mean flow, bond r^2/2 + alpha r^3/3 + beta r^4/4 (docs/models.md,
    derived by hand in probe 95): -12 beta s^3 + 8 alpha^2 s (1 + s^2), s = sin(k/2)."""
    s = abs(math.sin(k / 2))
    return -12 * beta * s**3 + 8 * alpha**2 * s * (1 + s * s)


def bond_fput(name: str, p: dict) -> tuple:
    """(alpha, beta) of the FPUT chain a unit-stiffness bond V(r) is to fourth order:
    alpha = V'''(0)/2, beta = V''''(0)/6, derived by hand."""
    if name == "morse":  # V''' = -3 b, V'''' = 7 b^2
        return -1.5 * p["b"], 7 * p["b"] ** 2 / 6
    if name == "lj":  # V''' = -1512 eps, V'''' = 26712 eps
        return -756 * p["eps"], 4452 * p["eps"]
    if name in ("hertz-pre", "hertz-closed"):  # V''' = -1/(2 d0), V'''' = -1/(4 d0^2)
        return -1 / (4 * p["d0"]), -1 / (24 * p["d0"] ** 2)
    raise KeyError(name)


def omega_by_hand(name: str, p: dict, k: float) -> np.ndarray:
    """Each model's linear branches, from its quadratic energy written by hand."""
    s2 = math.sin(k / 2) ** 2
    if name in ("morse", "lj", "hertz-pre", "hertz-closed", "fput"):
        return np.array([2 * math.sqrt(s2)])
    if name == "stiff":
        return np.array([2 * math.sqrt(p["K"] / p["m"] * s2)])
    if name == "tri3":  # springs u-v, v-w, w-u_next; M = diag(1, m2, m3)
        z = np.exp(1j * k)
        Kk = np.array([[2, -1, -np.conj(z)], [-1, 2, -1], [-z, -1, 2]])
        Mi = np.diag(1 / np.sqrt([1.0, p["m2"], p["m3"]]))
        return np.sqrt(np.abs(np.linalg.eigvalsh(Mi @ Kk @ Mi)))
    if name == "heavy":  # masses 1, M; unit springs
        s = 1 + 1 / p["M"]
        r = math.sqrt(s * s - 4 * s2 / p["M"])
        return np.sqrt([s - r, s + r])
    if name == "split":  # |K_uv|^2 = 4 eps^2 s^2
        A, B = 4 * s2, p["w0"] ** 2 + 4 * p["Cv"] * s2
        c2 = 4 * p["eps_zero_by_default"] ** 2 * s2
        r = math.sqrt((A - B) ** 2 / 4 + c2)
        return np.sqrt([(A + B) / 2 - r, (A + B) / 2 + r])
    raise KeyError(name)
