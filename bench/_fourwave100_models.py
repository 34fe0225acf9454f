"""probe 100's model files for the four-wave theory (``probe_fourwave100``) and, for each,
its quadratic energy written by hand as a mass-weighted dynamical matrix D(kappa) (numpy,
not the code's), the referee of each wave's branch and field content.

nnn       FPUT with next-nearest-neighbour springs, as a two-site cell (a = site 2n,
          b = site 2n + 1; the format has no second neighbour): the monatomic chain's
          omega(K)^2 = 4 sin^2(K/2) + 4 c2 sin^2 K folded, K = kappa/2 (and + pi)
nnnres    the same with c2 = -0.07 < -1/16: the monatomic dispersion convex at small K, so
          omega(2K) = 2 omega(K) on the acoustic branch at some K (a resonant second harmonic)
morse     a Morse chain, V = D (1 - exp(-b r))^2, D b^2 = 1/2
kgeven    Klein-Gordon with an even on-site potential (no cubic) and a cubic bond
tri       acoustic u, optical v and w: v's branch crosses 2 omega_u at k ~ 1 (u'^2 v: 1:2),
          w's crosses 3 omega_u at k ~ 0.5 (u'^3 w: 1:3)
decay2    acoustic u and optical v with only a cubic-energy cross term g u'^2 v (no quartic):
          three-wave decays are the only instabilities of order a
dia20     diatomic FPUT with masses 1 and 20 (u light, w heavy)
"""

from __future__ import annotations

import math

import numpy as np

NNN = '''name = "{name}"
description = "FPUT with next-nearest-neighbour springs c2, two-site cell (a, b)"
fields = ["a", "b"]
[parameters]
alpha = 0.3
beta = 1.0
c2 = {c2}
beta2 = 0.5
[energy]
kinetic = "a_t**2/2 + b_t**2/2"
site = "(b - a)**2/2 + alpha*(b - a)**3/3 + beta*(b - a)**4/4"
bond = "(a_next - b)**2/2 + alpha*(a_next - b)**3/3 + beta*(a_next - b)**4/4 + c2*(a_next - a)**2/2 + beta2*(a_next - a)**4/4 + c2*(b_next - b)**2/2 + beta2*(b_next - b)**4/4"
'''

MORSE = '''name = "morse"
description = "Morse chain, D b^2 = 1/2"
fields = ["u"]
[parameters]
D = 0.5
b = 1.0
[energy]
kinetic = "u_t**2/2"
bond = "D*(1 - exp(-b*(u_next - u)))**2"
'''

KGEVEN = '''name = "kgeven"
description = "Klein-Gordon, even on-site potential, cubic bond"
fields = ["u"]
[parameters]
C = 1.0
w0 = 1.0
beta = 1.0
alpha = 1.0
[energy]
kinetic = "u_t**2/2"
bond = "C*((u_next - u)**2/2 + alpha*(u_next - u)**3/3)"
site = "w0**2*u**2/2 + beta*u**4/4"
'''

TRI = '''name = "tri"
description = "acoustic u; optical v (1:2 with u at k ~ 1) and w (1:3 at k ~ 0.5)"
fields = ["u", "v", "w"]
branch = "u"
[parameters]
bu = 1.0
wv = 1.842392
cv = 0.1
ww = 1.420464
cw = 0.1
g2 = 0.3
g3 = 0.3
[energy]
kinetic = "u_t**2/2 + v_t**2/2 + w_t**2/2"
bond = "(u_next - u)**2/2 + bu*(u_next - u)**4/4 + cv*(v_next - v)**2/2 + cw*(w_next - w)**2/2 + g2*(u_next - u)**2*v + g3*(u_next - u)**3*w"
site = "wv**2*v**2/2 + v**4/4 + ww**2*w**2/2 + w**4/4"
'''

DECAY2 = '''name = "decay2"
description = "acoustic u, optical v, only a cubic cross term g (u_next - u)^2 v"
fields = ["u", "v"]
branch = "u"
[parameters]
wv = 0.6
cv = 0.05
g = 0.5
[energy]
kinetic = "u_t**2/2 + v_t**2/2"
bond = "(u_next - u)**2/2 + cv*(v_next - v)**2/2 + g*(u_next - u)**2*v"
site = "wv**2*v**2/2"
'''

DIA20 = '''name = "dia20"
description = "diatomic FPUT, masses 1 (u) and 20 (w)"
fields = ["u", "w"]
[parameters]
M = 20.0
alpha = 0.4
beta = 1.0
[energy]
kinetic = "u_t**2/2 + M*w_t**2/2"
site = "(w - u)**2/2 + alpha*(w - u)**3/3 + beta*(w - u)**4/4"
bond = "(u_next - w)**2/2 + alpha*(u_next - w)**3/3 + beta*(u_next - w)**4/4"
'''

FILES = {"nnn": NNN.format(name="nnn", c2=0.25), "nnnres": NNN.format(name="nnnres", c2=-0.07),
         "morse": MORSE, "kgeven": KGEVEN, "tri": TRI, "decay2": DECAY2, "dia20": DIA20}


def hand_matrix(name: str, p: dict, kap: float) -> np.ndarray:
    """The mass-weighted dynamical matrix of ``name`` at wavenumber kap, from its
    quadratic energy by hand (x_n = X e^{i kap n}; D X = omega^2 X)."""
    s2 = 4 * math.sin(kap / 2) ** 2
    e = np.exp(1j * kap)
    if name in ("nnn", "nnnres"):
        # dE/da_n = (a - b) + (a - b_{n-1}) + c2 (2a - a_{n+1} - a_{n-1})
        d = 2 + p["c2"] * s2
        return np.array([[d, -(1 + 1 / e)], [-(1 + e), d]], complex)
    if name == "morse":  # V''(0) = 2 D b^2
        return np.array([[2 * p["D"] * p["b"] ** 2 * s2]], complex)
    if name == "kgeven":
        return np.array([[p["C"] * s2 + p["w0"] ** 2]], complex)
    if name == "tri":
        return np.diag([s2, p["wv"] ** 2 + p["cv"] * s2, p["ww"] ** 2 + p["cw"] * s2]
                       ).astype(complex)
    if name == "decay2":
        return np.diag([s2, p["wv"] ** 2 + p["cv"] * s2]).astype(complex)
    if name == "dia20":
        # dE/du_n = (u - w_n) + (u - w_{n-1}); dE/dw_n = (w - u_n) + (w - u_{n+1})
        K = np.array([[2, -(1 + 1 / e)], [-(1 + e), 2]], complex)
        s = 1 / np.sqrt(np.array([1.0, p["M"]]))
        return s[:, None] * K * s[None, :]
    raise KeyError(name)


def hand_branches(name, p, kap):
    """(frequencies ascending, their eigenvectors' field weights: rows = branches)."""
    w2, V = np.linalg.eigh(hand_matrix(name, p, kap))
    return np.sqrt(np.maximum(w2, 0)), (np.abs(V) ** 2).T
