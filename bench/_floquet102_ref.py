"""Probe 102's time-domain Floquet referee of the exact lattice theory: the monodromy
matrix of the whole ring, sharing nothing with ``numerics.models`` but the energy file.

The model file (TOML) is read here with ``tomllib`` and its expressions with SymPy (never
``energy``): masses from the kinetic energy, the ring's force and Hessian from the bond and
site energies differentiated by SymPy and lambdified to numpy, the damping matrix from the
Rayleigh function's Hessian. Along the travelling wave (``state`` given: positions and
velocities at t = 0) the ring's 2 d N x 2 d N fundamental matrix is integrated with the
wave itself over one period T = 2 pi / omega (scipy DOP853): M x'' = F(x) for the wave
(the lossless one: with losses the carrier is held, the "rate at t = 0" of a decaying
carrier), M dx'' = -H(x(t)) dx - C dx' for the perturbations. Its multipliers mu give the
rates ln|mu| / T of every mode of the ring, not only those a Hill truncation keeps.
"""

from __future__ import annotations

import tomllib

import numpy as np
import sympy as sp
from scipy.integrate import solve_ivp

_FUNCS = {"sin": sp.sin, "cos": sp.cos, "tan": sp.tan, "exp": sp.exp, "log": sp.log,
          "sqrt": sp.sqrt, "sinh": sp.sinh, "cosh": sp.cosh, "tanh": sp.tanh,
          "atan": sp.atan, "Abs": sp.Abs, "pi": sp.pi}


class RingReferee:
    """One model file at given parameter values, on a ring of ``N`` sites."""

    def __init__(self, text: str, params: dict, N: int):
        data = tomllib.loads(text)
        self.fields = list(data["fields"])
        d = self.d = len(self.fields)
        self.N = N
        values = {**data.get("parameters", {}), **params}
        x = sp.symbols(self.fields)
        xn = sp.symbols([f + "_next" for f in self.fields])
        v = sp.symbols([f + "_t" for f in self.fields])
        vn = sp.symbols([f + "_next_t" for f in self.fields])
        names = {str(s): s for s in (*x, *xn, *v, *vn)} | _FUNCS
        names |= {p: sp.Float(val, 30) for p, val in values.items()}

        def parse(expr):
            return sp.sympify(expr, locals=names) if expr else sp.Integer(0)

        energy = data["energy"]
        kin = parse(energy["kinetic"])
        self.masses = np.array([float(sp.diff(kin, vi, 2)) for vi in v])
        bond, site = parse(energy.get("bond", "")), parse(energy.get("site", ""))
        args = (*x, *xn)

        def fn(expr):
            f = sp.lambdify(args, expr, "numpy")
            return lambda a, b: np.broadcast_to(np.asarray(f(*a, *b), float), a[0].shape)

        # gradients of bond (in x_n, x_{n+1}) and site (in x_n); Hessian blocks
        self._gb = [fn(sp.diff(bond, s)) for s in args]
        self._gs = [fn(sp.diff(site, s)) for s in x]
        self._hb = [[fn(sp.diff(bond, s, t)) for t in args] for s in args]
        self._hs = [[fn(sp.diff(site, s, t)) for t in x] for s in x]
        # damping: the Rayleigh function's (constant) Hessian in the velocities
        C = np.zeros((d * N, d * N))
        diss = data.get("dissipation", {})
        rs, rb = parse(diss.get("site", "")), parse(diss.get("bond", ""))
        cs = np.array([[float(sp.diff(rs, a, b)) for b in v] for a in v])
        cb = np.array([[float(sp.diff(rb, a, b)) for b in (*v, *vn)] for a in (*v, *vn)])
        for n in range(N):
            i, j = n * d, ((n + 1) % N) * d
            C[i:i + d, i:i + d] += cs + cb[:d, :d]
            C[j:j + d, j:j + d] += cb[d:, d:]
            C[i:i + d, j:j + d] += cb[:d, d:]
            C[j:j + d, i:i + d] += cb[d:, :d]
        self.damping = C
        self.minv = np.tile(1 / self.masses, N)

    def _split(self, q):
        X = q.reshape(self.N, self.d)
        here = [X[:, i] for i in range(self.d)]
        nxt = [np.roll(X[:, i], -1) for i in range(self.d)]
        return here, nxt

    def force(self, q):
        """-dV/dx on every site, shape (d N,)."""
        here, nxt = self._split(q)
        d = self.d
        F = np.zeros((self.N, d))
        for i in range(d):
            F[:, i] -= self._gs[i](here, here) + self._gb[i](here, nxt)
            F[:, i] -= np.roll(self._gb[d + i](here, nxt), 1)  # bond n-1 -> n
        return F.ravel()

    def hessian(self, q):
        """d^2 V / dx dx of the ring, shape (d N, d N)."""
        here, nxt = self._split(q)
        d, N = self.d, self.N
        Hn = np.zeros((N, d, d))
        Hc = np.zeros((N, d, d))  # block (n, n + 1)
        for i in range(d):
            for j in range(d):
                Hn[:, i, j] = (self._hs[i][j](here, here) + self._hb[i][j](here, nxt)
                               + np.roll(self._hb[d + i][d + j](here, nxt), 1))
                Hc[:, i, j] = self._hb[i][d + j](here, nxt)
        H = np.zeros((d * N, d * N))
        for n in range(N):
            i, j = n * d, ((n + 1) % N) * d
            H[i:i + d, i:i + d] += Hn[n]
            H[i:i + d, j:j + d] += Hc[n]
            H[j:j + d, i:i + d] += Hc[n].T
        return H

    def flow(self, state, T, rtol=1e-11, variational=True):
        """Integrate the wave (lossless) and, with ``variational``, the fundamental matrix
        of its damped linearisation over [0, T]: (state(T), Phi(T) or None)."""
        D = self.d * self.N
        minv, C = self.minv, self.damping
        damped = bool(np.any(C))

        def rhs(t, y):
            q, p = y[:D], y[D:2 * D]
            out = np.empty_like(y)
            out[:D] = p
            out[D:2 * D] = minv * self.force(q)
            if variational:
                P = y[2 * D:].reshape(2 * D, 2 * D)
                dP = out[2 * D:].reshape(2 * D, 2 * D)
                dP[:D] = P[D:]
                acc = self.hessian(q) @ P[:D]
                if damped:
                    acc += C @ P[D:]
                dP[D:] = -minv[:, None] * acc
            return out

        y0 = np.concatenate([state, np.eye(2 * D).ravel()]) if variational else state
        sol = solve_ivp(rhs, (0.0, T), y0, method="DOP853", rtol=rtol, atol=rtol * 1e-3)
        y = sol.y[:, -1]
        Phi = y[2 * D:].reshape(2 * D, 2 * D) if variational else None
        return y[:2 * D], Phi

    def spatial_weights(self, vec):
        """A mode's weight over the ring's wavenumbers 2 pi j / N (j = 0..N-1): the
        mass-weighted positions' DFT over the sites, summed over the fields, normalised."""
        D = self.d * self.N
        X = (vec[:D] * np.sqrt(np.tile(self.masses, self.N))).reshape(self.N, self.d)
        w = (np.abs(np.fft.fft(X, axis=0)) ** 2).sum(axis=1)
        return w / w.sum()


def wave_state(wave, N):
    """The project's travelling wave on the ring's sites at t = 0: (x, x_t), flattened
    site-major. x_n = U(k n), x_n_t = -omega U'(k n)."""
    xi = wave.k * np.arange(N)
    X = wave.profile(xi).T  # (N, d)
    V = -wave.omega * wave.slope(xi).T
    return np.concatenate([X.ravel(), V.ravel()])


def neutral_directions(ref: RingReferee, state):
    """The directions the monodromy leaves in place exactly (multiplier 1 with a Jordan
    partner): the wave's own time derivative (its phase) and, for each field the energy
    does not pin, a uniform shift of it. A Jordan block split by the integrator's error
    eps gives multipliers 1 +- sqrt(eps) (rates ~1e-6 / T) whose eigenvectors lie along
    these: they are recognised by that, not by a rate threshold."""
    D = ref.d * ref.N
    out = [np.concatenate([state[D:], ref.minv * ref.force(state[:D])])]
    H = ref.hessian(state[:D])
    for i in range(ref.d):
        e = np.zeros(2 * D)
        e[i:D:ref.d] = 1.0
        if np.max(np.abs(H @ e[:D])) < 1e-9 * max(1.0, np.max(np.abs(H))):
            out.append(e)
    return np.array(out).T


def monodromy(ref: RingReferee, state, omega, rtol=1e-11):
    """(multipliers, eigenvectors, T, the wave's return error |y(T) - y(0)| / |y(0)|):
    multipliers of the neutral directions (``neutral_directions``: eigenvectors within
    1e-2 of their span, |ln|mu|| < 1e-3) set to 1."""
    T = 2 * np.pi / omega
    end, Phi = ref.flow(state, T, rtol=rtol)
    back = float(np.max(np.abs(end - state)) / np.max(np.abs(state)))
    mu, vec = np.linalg.eig(Phi)
    B = neutral_directions(ref, state)
    Q, _ = np.linalg.qr(B)
    for i in np.flatnonzero(np.abs(np.log(np.abs(mu))) < 1e-3):
        v = vec[:, i] / np.linalg.norm(vec[:, i])
        if np.linalg.norm(v - Q @ (Q.T @ v)) < 1e-2:
            mu[i] = 1.0
    return mu, vec, T, back
