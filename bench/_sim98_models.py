"""Probe 98's model files and their physics written by hand (numpy only, nothing of the
code under test): each model's TOML text, its total energy and Rayleigh function from a
state (u, v), each shape (d, N), and its linear problem M, K(k) (the dynamical matrix of
the energy's quadratic part, derived by hand from the bond and site terms).
``bench.probe_sim98`` runs the checks."""

from __future__ import annotations

import numpy as np

FILES = {
    "pend": '''name = "pend98"
description = "cosine (pendulum) bond with a harmonic site"
fields = ["u"]
[parameters]
K = 1.3
w0 = 0.7
[energy]
kinetic = "u_t**2/2"
bond = "K*(1 - cos(u_next - u))"
site = "w0**2*u**2/2"
''',
    "morse": '''name = "morse98"
fields = ["u"]
[parameters]
D = 0.5
b = 1.5
w0 = 0.3
[energy]
kinetic = "u_t**2/2"
bond = "D*(1 - exp(-b*(u_next - u)))**2"
site = "w0**2*u**2/2 + u**4/8"
''',
    "quartic": '''name = "quartic98"
fields = ["u"]
[parameters]
beta = 2.0
w0 = 1.0
m = 1.5
[energy]
kinetic = "m*u_t**2/2"
bond = "beta*(u_next - u)**4/4"
site = "w0**2*u**2/2"
''',
    "toda": '''name = "toda98"
fields = ["u"]
[parameters]
a = 1.0
b = 1.0
[energy]
kinetic = "u_t**2/2"
bond = "a/b*(exp(-b*(u_next - u)) + b*(u_next - u) - 1)"
''',
    "grad": '''name = "grad98"
description = "two fields coupled through a gradient-squared term"
fields = ["u", "v"]
[parameters]
c1 = 1.0
c2 = 0.6
g = 0.3
mv = 2.0
wv = 0.8
lam = 0.5
[energy]
kinetic = "u_t**2/2 + mv*v_t**2/2"
bond = "c1*(u_next - u)**2/2 + c2*(v_next - v)**2/2 + g*(u_next - u)*(v_next - v) + lam*(u_next - u)**2*(v_next - v)**2/4"
site = "wv**2*v**2/2 + v**4/4"
''',
    "mim": '''name = "mim98"
description = "mass-in-mass with a stiff inner spring"
fields = ["u", "w"]
[parameters]
m = 0.01
kin = 36.0
beta = 1.0
[energy]
kinetic = "u_t**2/2 + m*w_t**2/2"
bond = "(u_next - u)**2/2 + beta*(u_next - u)**4/4"
site = "kin*(w - u)**2/2"
''',
    "tri": '''name = "tri98"
fields = ["a", "b", "c"]
[parameters]
k1 = 1.0
k2 = 0.5
kc = 0.4
w2 = 0.9
w3 = 1.4
m3 = 0.7
nu = 0.6
[energy]
kinetic = "a_t**2/2 + b_t**2/2 + m3*c_t**2/2"
bond = "k1*(a_next - a)**2/2 + k2*(b_next - b)**2/2 + nu*(a_next - a)**4/4"
site = "w2**2*b**2/2 + w3**2*c**2/2 + kc*(a - b)**2/2 + kc*(b - c)**2/2 + (b - c)**4/4"
''',
    "damped": '''name = "damped98"
fields = ["u"]
[parameters]
alpha = 0.4
beta = 1.0
w0 = 0.5
gamma = 0.003
eta = 0.002
[energy]
kinetic = "u_t**2/2"
bond = "(u_next - u)**2/2 + alpha*(u_next - u)**3/3 + beta*(u_next - u)**4/4"
site = "w0**2*u**2/2"
[dissipation]
site = "gamma*u_t**2/2"
bond = "eta*(u_next_t - u_t)**2/2"
''',
    "damp2": '''name = "damp2_98"
fields = ["u", "v"]
[parameters]
m = 2.0
kc = 0.5
gv = 0.004
eta = 0.003
beta = 1.0
[energy]
kinetic = "u_t**2/2 + m*v_t**2/2"
bond = "(u_next - u)**2/2 + beta*(u_next - u)**4/4 + (v_next - u)**2/2"
site = "kc*(u - v)**2/2"
[dissipation]
site = "gv*v_t**2/2"
bond = "eta*(u_next_t - u_t)**2/2 + eta*(v_next_t - v_t)**2/2"
''',
    "soft": '''name = "soft98"
description = "a softening bond: a barrier at r = 1, past it the energy falls without end"
fields = ["u"]
[parameters]
beta = 1.0
w0 = 0.5
[energy]
kinetic = "u_t**2/2"
bond = "(u_next - u)**2/2 - beta*(u_next - u)**4/4"
site = "w0**2*u**2/2"
''',
}


def _r(x):
    """x_{n+1} - x_n on the ring."""
    return np.roll(x, -1, axis=-1) - x


def energy(name: str, u, v) -> float:
    """The total energy of the ring at (u, v), written by hand from FILES[name]."""
    if name == "pend":
        (x,), (y,) = u, v
        return float(np.sum(y**2 / 2 + 1.3 * (1 - np.cos(_r(x))) + 0.49 * x**2 / 2))
    if name == "morse":
        (x,), (y,) = u, v
        return float(np.sum(y**2 / 2 + 0.5 * (1 - np.exp(-1.5 * _r(x)))**2 + 0.09 * x**2 / 2
                            + x**4 / 8))
    if name == "quartic":
        (x,), (y,) = u, v
        return float(np.sum(1.5 * y**2 / 2 + 2.0 * _r(x)**4 / 4 + x**2 / 2))
    if name == "toda":
        (x,), (y,) = u, v
        r = _r(x)
        return float(np.sum(y**2 / 2 + np.exp(-r) + r - 1))
    if name == "grad":
        (x, z), (y, w) = u, v
        a, b = _r(x), _r(z)
        return float(np.sum(y**2 / 2 + 2 * w**2 / 2 + a**2 / 2 + 0.6 * b**2 / 2 + 0.3 * a * b
                            + 0.5 * a**2 * b**2 / 4 + 0.64 * z**2 / 2 + z**4 / 4))
    if name == "mim":
        (x, z), (y, w) = u, v
        a = _r(x)
        return float(np.sum(y**2 / 2 + 0.01 * w**2 / 2 + a**2 / 2 + a**4 / 4
                            + 36 * (z - x)**2 / 2))
    if name == "tri":
        (a, b, c), (ya, yb, yc) = u, v
        ra, rb = _r(a), _r(b)
        return float(np.sum(ya**2 / 2 + yb**2 / 2 + 0.7 * yc**2 / 2 + ra**2 / 2
                            + 0.5 * rb**2 / 2 + 0.6 * ra**4 / 4 + 0.81 * b**2 / 2
                            + 1.96 * c**2 / 2 + 0.4 * (a - b)**2 / 2 + 0.4 * (b - c)**2 / 2
                            + (b - c)**4 / 4))
    if name == "damped":
        (x,), (y,) = u, v
        r = _r(x)
        return float(np.sum(y**2 / 2 + r**2 / 2 + 0.4 * r**3 / 3 + r**4 / 4
                            + 0.25 * x**2 / 2))
    if name == "soft":
        (x,), (y,) = u, v
        r = _r(x)
        return float(np.sum(y**2 / 2 + r**2 / 2 - r**4 / 4 + 0.25 * x**2 / 2))
    if name == "damp2":
        (x, z), (y, w) = u, v
        r = _r(x)
        return float(np.sum(y**2 / 2 + 2 * w**2 / 2 + r**2 / 2 + r**4 / 4
                            + (np.roll(z, -1) - x)**2 / 2 + 0.5 * (x - z)**2 / 2))
    raise KeyError(name)


def rayleigh(name: str, v) -> float:
    """The Rayleigh function R of the ring's velocities, by hand."""
    if name == "damped":
        (y,) = v
        return float(np.sum(0.003 * y**2 / 2 + 0.002 * _r(y)**2 / 2))
    if name == "damp2":
        y, w = v
        return float(np.sum(0.004 * w**2 / 2 + 0.003 * _r(y)**2 / 2 + 0.003 * _r(w)**2 / 2))
    return 0.0


def linear(name: str, k: float):
    """(M, K(k)) of the energy's quadratic part about rest, by hand: a plane wave
    x_n = X e^{i k n} of every field; s = 4 sin^2(k/2) = |e^{ik} - 1|^2."""
    s = 4 * np.sin(k / 2) ** 2
    if name == "pend":  # K (1 - cos r) ~ K r^2 / 2
        return np.eye(1), np.array([[0.49 + 1.3 * s]])
    if name == "morse":  # D (b r)^2 = 2 D b^2 r^2 / 2: stiffness 2 D b^2 = 2.25
        return np.eye(1), np.array([[0.09 + 2.25 * s]])
    if name == "quartic":  # no quadratic bond: a flat branch w0 / sqrt(m)
        return np.array([[1.5]]), np.array([[1.0]])
    if name == "toda":  # a/b (b^2 r^2 / 2): stiffness a b = 1
        return np.eye(1), np.array([[s]])
    if name == "grad":
        return np.diag([1.0, 2.0]), np.array([[s, 0.3 * s], [0.3 * s, 0.6 * s + 0.64]])
    if name == "mim":
        return np.diag([1.0, 0.01]), np.array([[s + 36, -36.0], [-36.0, 36.0]])
    if name == "tri":
        return np.diag([1.0, 1.0, 0.7]), np.array([
            [s + 0.4, -0.4, 0.0], [-0.4, 0.5 * s + 0.81 + 0.8, -0.4], [0.0, -0.4, 1.96 + 0.4]])
    if name in ("damped", "soft"):
        return np.eye(1), np.array([[0.25 + s]])
    if name == "damp2":  # (v_{n+1} - u_n)^2 / 2: K_uv = -e^{ik} - kc (Hermitian)
        e = np.exp(1j * k)
        return np.diag([1.0, 2.0]).astype(complex), np.array(
            [[s + 1 + 0.5, -0.5 - e], [-0.5 - np.conj(e), 1 + 0.5]])
    raise KeyError(name)


def omega_hand(name: str, k: float) -> np.ndarray:
    """The branches at k, ascending: 1 field omega^2 = K / M; 2 fields the quadratic
    det(K - w^2 M) = 0 by the quadratic formula; 3 fields (tri) numpy's eigvalsh of
    M^-1/2 K M^-1/2 of the hand K."""
    M, K = linear(name, k)
    if len(M) == 1:
        return np.sqrt(np.real(K[0, 0] / M[0, 0]))[None]
    if len(M) == 2:
        m1, m2 = np.real(M[0, 0]), np.real(M[1, 1])
        a, d, b2 = np.real(K[0, 0]), np.real(K[1, 1]), abs(K[0, 1]) ** 2
        # m1 m2 W^2 - (a m2 + d m1) W + (a d - b2) = 0, W = omega^2
        B, C = a * m2 + d * m1, a * d - b2
        disc = np.sqrt(B * B - 4 * m1 * m2 * C)
        W = np.array([2 * C / (B + disc), (B + disc) / (2 * m1 * m2)])  # stable roots
        return np.sqrt(W)
    Mh = np.diag(1 / np.sqrt(np.diag(M)))
    return np.sqrt(np.linalg.eigvalsh(Mh @ K @ Mh))


def mode_shape(name: str, k: float, b: int) -> np.ndarray:
    """The hand eigenvector X of branch b at k: (K - w^2 M) X = 0."""
    M, K = linear(name, k)
    w2 = omega_hand(name, k)[b] ** 2
    _, _, vh = np.linalg.svd(K - w2 * M)
    x = np.conj(vh[-1])
    return x / np.linalg.norm(x)
