"""Probe 98's model files (TOML texts, ``MODELS``), each model's cell energy written again
by hand in numpy (``ENERGIES``: W(x_n, x_{n+1}) = site(x_n) + bond(x_n, x_{n+1}), and the
masses), and the independent Hill referee built from them (``own_rates``): exact second
derivatives by hyper-dual numbers (no finite differences, no SymPy), the Hessian's Fourier
coefficients along the project's travelling wave, and the dense quadratic pencil at one
offset solved by ``numpy.linalg.eig``. ``bench.probe_exact98`` uses them (its docstring
says which models and why); tests/test_probe98_exact.py too. ``exact_where_a_wave_is``:
the probes' (98, 102) exact ring or chain at the largest halved amplitude with a wave.
"""

from __future__ import annotations

import math
import time

import numpy as np

MODELS = {
    # a local resonator (mass-in-mass): a flat optical branch where kr / mr is small
    "res2": '''name = "res2"
fields = ["u", "v"]
branch = "u"
[parameters]
mr = 1.0
kr = 0.05
beta = 1.0
g = 1.0
[energy]
kinetic = "u_t**2/2 + mr*v_t**2/2"
bond = "(u_next - u)**2/2 + beta*(u_next - u)**4/4"
site = "kr*(v - u)**2/2 + g*(v - u)**3/3 + (v - u)**4/4"
''',
    # an acoustic u and a Klein-Gordon v with a tiny spring c, strongly coupled cubically
    "weak2": '''name = "weak2"
fields = ["u", "v"]
branch = "u"
[parameters]
c = 0.001
w0 = 1.0
g = 1.0
lam = 1.0
[energy]
kinetic = "u_t**2/2 + v_t**2/2"
bond = "(u_next - u)**2/2 + (u_next - u)**4/4 + c*(v_next - v)**2/2 + g*(u_next - u)*v**2"
site = "w0**2*v**2/2 + lam*v**4/4"
''',
    # one Klein-Gordon field with a tiny inter-site spring: a nearly flat branch
    "kgflat": '''name = "kgflat"
fields = ["u"]
[parameters]
C = 0.002
alpha = 0.5
beta = 1.0
[energy]
kinetic = "u_t**2/2"
bond = "C*(u_next - u)**2/2"
site = "u**2/2 + alpha*u**3/3 + beta*u**4/4"
''',
    # acoustic u and flat v whose branches cross (wv inside the acoustic band), a cubic
    # cross term of size g
    "cross2": '''name = "cross2"
fields = ["u", "v"]
branch = "u"
[parameters]
wv = 1.2
g = 1.0
eps = 0.0
[energy]
kinetic = "u_t**2/2 + v_t**2/2"
bond = "(u_next - u)**2/2 + (u_next - u)**4/4 + g*(u_next - u)**2*v + eps*(u_next - u)*v"
site = "wv**2*v**2/2 + v**4/4"
''',
    # three fields: a chain u and two resonators v, w (flat branches), cubic cross terms
    "tri-flat": '''name = "tri-flat"
fields = ["u", "v", "w"]
branch = "u"
[parameters]
kv = 0.1
kw = 0.3
g = 1.0
[energy]
kinetic = "u_t**2/2 + v_t**2/2 + 2*w_t**2/2"
bond = "(u_next - u)**2/2 + (u_next - u)**4/4 + 0.01*(w_next - w)**2/2"
site = "kv*(v - u)**2/2 + g*(v - u)**3/3 + (v - u)**4/4 + kw*(w - v)**2/2 + g*(w - v)**2*(v - u) + (w - v)**4/4"
''',
    # two Klein-Gordon fields, tiny springs, strong cubic coupling both ways
    "kg2": '''name = "kg2"
fields = ["u", "v"]
branch = "u"
[parameters]
C = 0.005
w2 = 1.5
g = 1.0
[energy]
kinetic = "u_t**2/2 + v_t**2/2"
bond = "C*(u_next - u)**2/2 + C*(v_next - v)**2/2"
site = "u**2/2 + w2**2*v**2/2 + g*u**2*v + g*u*v**2 + u**4/4 + v**4/4"
''',
    # one-field FPUT with both signs of alpha (the ring copies' path)
    "fput1": '''name = "fput1"
fields = ["u"]
[parameters]
alpha = 0.5
beta = 1.0
[energy]
kinetic = "u_t**2/2"
bond = "(u_next - u)**2/2 + alpha*(u_next - u)**3/3 + beta*(u_next - u)**4/4"
''',
    # a pendulum chain u with a weak spring and an acoustic v, coupled through cos
    "rotor-flat": '''name = "rotor-flat"
fields = ["u", "v"]
branch = "u"
[parameters]
C = 0.01
g = 1.0
[energy]
kinetic = "u_t**2/2 + v_t**2/2"
bond = "C*(u_next - u)**2/2 + (v_next - v)**2/2 + (v_next - v)**4/4 + g*(1 - cos(u))*(v_next - v)"
site = "1 - cos(u)"
''',
}


# --- the same energies by hand, on hyper-dual numbers ------------------------------------

class HD:
    """f + f1 e1 + f2 e2 + f12 e1 e2 (e1^2 = e2^2 = 0): f12 is the exact mixed second
    derivative of whatever is computed (no truncation error)."""

    __slots__ = ("f", "a", "b", "ab")

    def __init__(self, f, a=0.0, b=0.0, ab=0.0):
        self.f, self.a, self.b, self.ab = f, a, b, ab

    def __add__(self, o):
        o = _hd(o)
        return HD(self.f + o.f, self.a + o.a, self.b + o.b, self.ab + o.ab)

    __radd__ = __add__

    def __neg__(self):
        return HD(-self.f, -self.a, -self.b, -self.ab)

    def __sub__(self, o):
        return self + (-_hd(o))

    def __rsub__(self, o):
        return _hd(o) + (-self)

    def __mul__(self, o):
        o = _hd(o)
        return HD(self.f * o.f, self.a * o.f + self.f * o.a, self.b * o.f + self.f * o.b,
                  self.ab * o.f + self.a * o.b + self.b * o.a + self.f * o.ab)

    __rmul__ = __mul__

    def __truediv__(self, c):  # by a constant only
        return HD(self.f / c, self.a / c, self.b / c, self.ab / c)

    def __pow__(self, n: int):
        out = HD(np.ones_like(self.f))
        for _ in range(n):
            out = out * self
        return out


def _hd(x):
    return x if isinstance(x, HD) else HD(x)


def cos(x):
    c, s = np.cos(x.f), np.sin(x.f)
    return HD(c, -s * x.a, -s * x.b, -c * x.a * x.b - s * x.ab)


def sin(x):
    c, s = np.cos(x.f), np.sin(x.f)
    return HD(s, c * x.a, c * x.b, -s * x.a * x.b + c * x.ab)


def _res2(x, y, p):
    (u, v), (un, _) = x, y
    r, s = un - u, v - u
    return (r**2 / 2 + p["beta"] * r**4 / 4
            + p["kr"] * s**2 / 2 + p["g"] * s**3 / 3 + s**4 / 4)


def _weak2(x, y, p):
    (u, v), (un, vn) = x, y
    r = un - u
    return (r**2 / 2 + r**4 / 4 + p["c"] * (vn - v)**2 / 2 + p["g"] * r * v**2
            + p["w0"]**2 * v**2 / 2 + p["lam"] * v**4 / 4)


def _kgflat(x, y, p):
    (u,), (un,) = x, y
    return p["C"] * (un - u)**2 / 2 + u**2 / 2 + p["alpha"] * u**3 / 3 + p["beta"] * u**4 / 4


def _cross2(x, y, p):
    (u, v), (un, _) = x, y
    r = un - u
    return (r**2 / 2 + r**4 / 4 + p["g"] * r**2 * v + p["eps"] * r * v
            + p["wv"]**2 * v**2 / 2 + v**4 / 4)


def _tri_flat(x, y, p):
    (u, v, w), (un, _, wn) = x, y
    r, s, t = un - u, v - u, w - v
    return (r**2 / 2 + r**4 / 4 + 0.01 * (wn - w)**2 / 2
            + p["kv"] * s**2 / 2 + p["g"] * s**3 / 3 + s**4 / 4
            + p["kw"] * t**2 / 2 + p["g"] * t**2 * s + t**4 / 4)


def _kg2(x, y, p):
    (u, v), (un, vn) = x, y
    g = p["g"]
    return (p["C"] * (un - u)**2 / 2 + p["C"] * (vn - v)**2 / 2 + u**2 / 2
            + p["w2"]**2 * v**2 / 2 + g * u**2 * v + g * u * v**2 + u**4 / 4 + v**4 / 4)


def _fput1(x, y, p):
    r = y[0] - x[0]
    return r**2 / 2 + p["alpha"] * r**3 / 3 + p["beta"] * r**4 / 4


def _rotor_flat(x, y, p):
    (u, v), (un, vn) = x, y
    r = vn - v
    return (p["C"] * (un - u)**2 / 2 + r**2 / 2 + r**4 / 4 + p["g"] * (1 - cos(u)) * r
            + (1 - cos(u)))


def _flexmm(x, y, p, K3=0.0):
    (th, U), (thn, Un) = x, y
    Kt = p["K_theta"]
    phi = thn + th
    e = (2 * (Un - U + 1 - (cos(thn) + cos(th)) / 2)**2
         + p["K_s"] / 2 * (sin(thn) - sin(th))**2 + Kt * phi**2 / 2 + Kt * th**2)
    if K3:
        e = e + K3 * phi**4 / 4 + K3 * th**4 / 2
    return e


def _stiff_hinge(x, y, p):
    return _flexmm(x, y, p, K3=p["K_3"])


def _diatomic(x, y, p):
    (u, v), (un, _) = x, y

    def V(r):
        return r**2 / 2 + p["alpha"] * r**3 / 3 + p["beta"] * r**4 / 4

    return V(v - u) + V(un - v)


#: name -> (cell energy W(x, y, params), masses(params))
ENERGIES = {
    "res2": (_res2, lambda p: [1.0, p["mr"]]),
    "weak2": (_weak2, lambda p: [1.0, 1.0]),
    "kgflat": (_kgflat, lambda p: [1.0]),
    "cross2": (_cross2, lambda p: [1.0, 1.0]),
    "tri-flat": (_tri_flat, lambda p: [1.0, 1.0, 2.0]),
    "kg2": (_kg2, lambda p: [1.0, 1.0]),
    "fput1": (_fput1, lambda p: [1.0]),
    "rotor-flat": (_rotor_flat, lambda p: [1.0, 1.0]),
    "flexmm": (_flexmm, lambda p: [1 / p["alpha"]**2, 4.0]),
    "flexmm-stiff-hinge": (_stiff_hinge, lambda p: [1 / p["alpha"]**2, 4.0]),
    "diatomic-fput": (_diatomic, lambda p: [1.0, p["m"]]),
}


def cell_hessian(name, params, X):
    """The Hessian of the cell energy at the points X (shape (2d, M): x_n then x_{n+1}),
    shape (2d, 2d, M), exact (hyper-dual)."""
    W = ENERGIES[name][0]
    n2, M = X.shape
    d = n2 // 2
    H = np.empty((n2, n2, M))
    for i in range(n2):
        for j in range(i, n2):
            z = [HD(X[m]) for m in range(n2)]
            z[i] = HD(X[i], 1.0, 0.0, 0.0) if i != j else HD(X[i], 1.0, 1.0, 0.0)
            if i != j:
                z[j] = HD(X[j], 0.0, 1.0, 0.0)
            e = W(z[:d], z[d:], params)
            H[i, j] = H[j, i] = np.broadcast_to(e.ab, (M,))
    return H


def own_rates(name, params, wave, q, P, M=512):
    """The fastest kept growth rate at offset q by this module's own Hill pencil at
    truncation P: numpy.linalg.eig of the 2n x 2n linearisation of
    m (lambda - i l omega)^2 c_l + sum_h L_lh(q) c_h = 0, with
    L_lh = A_{l-h} + B_{l-h} e^{i (q + h k)} + C_{l-h} e^{-i (q + l k)} + D_{l-h} e^{-i (l-h) k}
    (the linearised m u_n'' = -[d1 W(u_n, u_{n+1}) + d2 W(u_{n-1}, u_n)], derived here by
    hand; A, B, C, D the Hessian's blocks, hats their Fourier coefficients along
    xi = k n - omega t). A mode is kept as the theory's rule says: heaviest at |l| <= 1 (a
    tie within 1e-6 counted at its mean), < 1e-6 of its weight in the outer three harmonics,
    rate above 3e-7 omega. Returns (rate, the kept mode's heaviest harmonic)."""
    k, omega = wave.k, wave.omega
    d = wave.coefficients.shape[0]
    xi = 2 * math.pi * np.arange(M) / M
    X = np.concatenate([wave.profile(xi), wave.profile(xi + k)])
    H = cell_hessian(name, params, X)
    Hhat = np.fft.fft(H, axis=-1) / M          # Hhat[..., s] multiplies e^{i s xi}
    mass = np.asarray(ENERGIES[name][1](params), float)
    L_ = np.arange(-P, P + 1)
    n = d * L_.size
    L = np.zeros((n, n), complex)
    for a, l in enumerate(L_):
        for b, h in enumerate(L_):
            s = (l - h) % M
            blk = (Hhat[:d, :d, s] + Hhat[:d, d:, s] * np.exp(1j * (q + h * k))
                   + Hhat[d:, :d, s] * np.exp(-1j * (q + l * k))
                   + Hhat[d:, d:, s] * np.exp(-1j * (l - h) * k))
            L[a * d:(a + 1) * d, b * d:(b + 1) * d] = blk
    m = np.tile(mass, L_.size)
    ll = np.repeat(L_, d) * omega
    A = np.zeros((2 * n, 2 * n), complex)
    A[:n, n:] = np.eye(n)
    A[n:, :n] = -(L - np.diag(ll**2 * m)) / m[:, None]
    A[n:, n:] = np.diag(2j * ll)
    lam, vec = np.linalg.eig(A)
    best, harm = 0.0, 0
    for j in np.argsort(-lam.real):
        if lam[j].real <= 3e-7 * omega:
            break
        w = np.abs(vec[:n, j])**2
        per_l = w.reshape(L_.size, d).sum(axis=1) / w.sum()
        tied = per_l >= (1 - 1e-6) * per_l.max()
        if abs((L_[tied]).mean()) > 1 or per_l[:3].sum() + per_l[-3:].sum() >= 1e-6:
            continue
        best, harm = float(lam[j].real), int(L_[np.argmax(per_l)])
        break
    return best, harm


def exact_where_a_wave_is(model, k, a, branch, N, tries=6):
    """``exact_gain`` at amplitude a, halved (at most ``tries`` times) until the model
    carries a travelling wave there: (spectrum, a, wall seconds, ""), or (None, a, nan,
    the last ModelError's text) where none was found."""
    from energy import ModelError
    from numerics.models import exact_gain

    why = ""
    for _ in range(tries):
        try:
            t0 = time.perf_counter()
            spec = exact_gain(model, k, a, branch, N=N)
            return spec, a, time.perf_counter() - t0, ""
        except ModelError as e:
            why = str(e)
            a /= 2
    return None, a, math.nan, why
