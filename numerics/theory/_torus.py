"""The launched state as a torus: its trajectory, its frequencies, its Fourier coefficients.

A state whose fields at t = 0 are functions of k n only (a carrier and waves at its
harmonics m k) stays so: theta_n(T) = F(k n, T) with F 2 pi-periodic, because a shift of
one site is a shift of the phase by k. The lattice then reduces *exactly* to a chain of
M phase points x_j = 2 pi j / M whose neighbours are x_j +- k (trigonometric interpolation,
spectrally accurate): ``trajectory`` integrates eq. `norm` there. Perturbations at other
wavenumbers (the MI sidebands) do not exist in this reduced chain, so the launched state
can be followed for thousands of periods without the MI that would destroy it on a lattice.

The free waves interact with the carrier: their frequencies are not the linear ones
(the free U wave at 2k of eq. `IC` is shifted by ~0.4% at the blue point, A0 = 1, and the
carrier by ~7% of its nonlinear shift). ``torus`` therefore measures the frequencies from
the trajectory (a NAFF-style frequency analysis: windowed-Fourier peak near each wave's
linear frequency, then a joint least-squares fit) and projects the trajectory on the
quasi-periodic basis e^{i (p phi + m . psi)}, phi = k n - Omega T, psi_j = -nu_j T.

References
----------
J. Laskar, Physica D 67 (1993) 257 (frequency analysis of quasi-periodic orbits).
"""

from __future__ import annotations

import itertools
from dataclasses import dataclass

import numpy as np

from ..lattice import checks
from numba import njit

from generated import lattice_model as model

from ..lattice._integrators import get_method
from ..lattice._kernels import _FAST, _acc, _sincosvers

#: phase points of the reduced chain (harmonics up to M/2 - 1 are kept exactly): the
#: launched state is integrated on the first that resolves it (its top harmonic below
#: SPECTRAL_TAIL of the carrier along the whole trajectory; at the paper's amplitude 16
#: points leave ~1e-14), else on the last
PHASE_POINTS_TRIED = (16, 32)
PHASE_POINTS = PHASE_POINTS_TRIED[-1]
SPECTRAL_TAIL = 1e-5
#: the trajectory is sampled this many times per carrier period
SAMPLES_PER_PERIOD = 8
#: it lasts this many periods of the slowest beat (and at least MIN_CARRIER_PERIODS)
BEATS, MIN_CARRIER_PERIODS, MAX_DURATION = 25, 200, 20000.0
#: torus Fourier indices kept per free phase, |m_j| <= FIT_ORDER (one free phase) or
#: FIT_ORDER - 1 (more); harmonics of the carrier kept, |p| <= TORUS_HARMONICS
FIT_ORDER, TORUS_HARMONICS = 3, 8
#: the reduced chain is integrated by SRKN11b (order 6) with omega_max dt below this: its
#: error model (``_accuracy.ERROR_CONSTANTS``) gives ~6e-6 relative over 20 000 T (the
#: tori last ~2000 T); halving it changes predicted growth factors by < 3e-6 (60 fig3 cells)
OMEGA_DT = 0.8


@dataclass(frozen=True)
class Torus:
    """A quasi-periodic state of the lattice: fields = sum F[p, m] e^{i (p phi + m . psi)}.

    Attributes
    ----------
    k : float
        Carrier wavenumber (phi = k n - Omega T).
    omega : float
        Carrier frequency Omega, measured.
    nu : ndarray, shape (d,)
        Frequencies of the free phases, psi_j = -nu_j T (lab frequency of a free wave at
        harmonic m: nu_j + m Omega).
    modes : ndarray of int, shape (nm, d)
        The multi-indices m kept.
    theta, U : ndarray, complex, shape (2 P + 1, nm)
        F[p, m] for p = -P .. P (row p + P); F[-p, -m] = conj F[p, m].
    residual : float
        Relative misfit of the quasi-periodic representation on the trajectory.
    duration : float
        Length of the trajectory the torus was measured on.
    tail : float
        Largest amplitude of the reduced chain's top harmonic (M/2 - 1) over the carrier's,
        along the trajectory: the phase points resolve the state where it is tiny.
    """

    k: float
    omega: float
    nu: np.ndarray
    modes: np.ndarray
    theta: np.ndarray
    U: np.ndarray
    residual: float
    duration: float
    tail: float = 0.0

    @property
    def P(self):
        return (self.theta.shape[0] - 1) // 2

    def harmonic(self, field: str, p: int, t):
        """Complex amplitude of ``field`` at wavenumber p k (x = Re sum_p c_p e^{i p k n}),
        p >= 1, at times t."""
        F = getattr(self, field)[p + self.P]
        t = np.asarray(t, float)
        ph = np.exp(-1j * (p * self.omega + self.modes @ self.nu)[None, :] * t.reshape(-1, 1))
        return (2 * ph @ F).reshape(t.shape)

    def on_grid(self, field: str, phi, psi, shift: float = 0.0):
        """Field on a torus grid: phi (Mp,), psi (Mq,) per free phase -> shape
        (Mp, Mq, ..); ``shift`` moves phi by shift * k (a neighbour site)."""
        F = getattr(self, field)
        p = np.arange(-self.P, self.P + 1)
        out = np.einsum("pm,pa->am", F * np.exp(1j * p * self.k * shift)[:, None],
                        np.exp(1j * np.outer(p, phi)))
        grids = np.meshgrid(*([psi] * self.nu.size), indexing="ij") if self.nu.size else []
        shape = (phi.size,) + (psi.size,) * self.nu.size
        res = np.zeros(shape, complex)
        for j, m in enumerate(self.modes):
            ph = np.exp(1j * sum(mi * g for mi, g in zip(m, grids))) if grids else 1.0
            res += out[:, j].reshape((-1,) + (1,) * self.nu.size) * ph
        return res.real


def _shift_matrices(k, M):
    """Real M x M matrices S+, S-: (S+ F)(x_j) = F(x_j + k) for trigonometric polynomials
    of degree < M / 2 (the Nyquist harmonic is dropped)."""
    p = np.arange(M // 2 + 1)
    keep = (p < M / 2).astype(float)
    I = np.eye(M)
    out = []
    for s in (1.0, -1.0):
        ph = np.exp(1j * s * p * k) * keep
        out.append(np.fft.irfft(np.fft.rfft(I, axis=0) * ph[:, None], n=M, axis=0))
    return out


@njit(cache=True, fastmath=_FAST, boundscheck=False)
def _reduced_accel(th, U, SpT, SmT, coupled, a2, Ks, Kt, X, XU, s, c, v, ath, aU):
    """Accelerations of the reduced chain: neighbours by the shift matrices (stored
    transposed, so the inner loop runs over contiguous rows and vectorises while every
    sum keeps its order), the site formula of the lattice kernel (``_kernels._acc``) on
    blocks [x - k | x | x + k]."""
    M = th.size
    X[:M] = 0.0
    X[2 * M:] = 0.0
    XU[:M] = 0.0
    XU[2 * M:] = 0.0
    for j in range(M):
        tj, uj = th[j], U[j]
        for i in range(M):
            X[i] += SmT[j, i] * tj
            X[2 * M + i] += SpT[j, i] * tj
            XU[i] += SmT[j, i] * uj
            XU[2 * M + i] += SpT[j, i] * uj
    for i in range(M):
        X[M + i] = th[i]
        XU[M + i] = U[i]
    for i in range(3 * M):
        s[i], c[i], v[i] = _sincosvers(X[i])
    for i in range(M):
        ath[i], aU[i] = _acc(M + i, i, 2 * M + i, X, XU, s, c, v, coupled, a2, Ks, Kt)


@njit(cache=True, fastmath=_FAST, boundscheck=False)
def _reduced_run(y0, Sp, Sm, coupled, a2, Ks, Kt, acoef, bcoef, dt, steps_per_sample,
                 samples):
    """SRKN (kick b_j, drift a_j) of the reduced chain, sampled every steps_per_sample."""
    M = Sp.shape[0]
    SpT, SmT = np.ascontiguousarray(Sp.T), np.ascontiguousarray(Sm.T)
    th, w, U, V = y0[0].copy(), y0[1].copy(), y0[2].copy(), y0[3].copy()
    X, XU = np.empty(3 * M), np.empty(3 * M)
    s, c, v = np.empty(3 * M), np.empty(3 * M), np.empty(3 * M)
    ath, aU = np.empty(M), np.empty(M)
    out = np.empty((samples, 4, M))
    nst = acoef.size
    _reduced_accel(th, U, SpT, SmT, coupled, a2, Ks, Kt, X, XU, s, c, v, ath, aU)
    for n in range(samples):
        out[n, 0], out[n, 1], out[n, 2], out[n, 3] = th, w, U, V
        for _ in range(steps_per_sample):
            for j in range(nst):
                for i in range(M):
                    w[i] += bcoef[j] * dt * ath[i]
                    V[i] += bcoef[j] * dt * aU[i]
                if j < nst - 1:
                    for i in range(M):
                        th[i] += acoef[j] * dt * w[i]
                        U[i] += acoef[j] * dt * V[i]
                    _reduced_accel(th, U, SpT, SmT, coupled, a2, Ks, Kt, X, XU, s, c, v, ath,
                                   aU)
    return out


def trajectory(material, case, k, fields0, t_end, samples, M=PHASE_POINTS):
    """Integrate the reduced chain from ``fields0`` = (theta, theta_dot, U, U_dot) on the
    M phase points (U ignored in case "rotation"). Returns (t, y), y shape (nt, 4, M)."""
    Sp, Sm = _shift_matrices(k, M)
    y0 = np.array([np.asarray(f, float) for f in fields0])
    coupled = case == "coupled"
    if not coupled:
        y0[2:] = 0.0
    if np.max(np.abs(y0[0])) > 1e3:
        raise ValueError("the reduced chain needs |theta| < 1e3")
    # fastest linear wave: the U branch peaks at 2 (q = pi); the rotation branch may peak
    # anywhere in the zone (at q = 0 when K_theta > K_s), so take its maximum
    w_max = max(2.0, float(np.max(model.omega_rotation(np.linspace(0.0, np.pi, 65),
                                                       material.alpha, material.K_s,
                                                       material.K_theta))))
    interval = t_end / (samples - 1)
    per = max(1, int(np.ceil(interval * w_max / OMEGA_DT)))
    meth = get_method("srkn11b")
    y = _reduced_run(y0, Sp, Sm, coupled, material.alpha**2, material.K_s, material.K_theta,
                     np.array(meth.a), np.array(meth.b), interval / per, per, samples)
    if not np.all(np.isfinite(y)):
        raise ArithmeticError("the reduced chain blew up: the launched state is not a "
                              "bounded quasi-periodic state")
    return interval * np.arange(samples), y


def _harmonics(y, P):
    """Complex amplitudes c_p(t), p = 0 .. P, of theta and U (x = Re sum c_p e^{i p x})."""
    M = y.shape[-1]
    c = np.fft.rfft(y[:, (0, 2)], axis=-1)[..., :P + 1] * (2.0 / M)
    c[..., 0] /= 2
    return c  # (nt, 2, P + 1)


def _peak(t, c, guess, window, span):
    """Frequency near ``guess`` maximising |sum w c e^{i nu t}| (a NAFF step): a coarse
    grid finds the peak, a bounded scalar search refines it to 1e-9 of the span."""
    from scipy.optimize import minimize_scalar

    wc = window * c
    power = lambda nu: -abs(np.exp(1j * nu * t) @ wc)  # noqa: E731
    grid = guess + np.linspace(-span, span, 61)
    best = grid[np.argmin([power(nu) for nu in grid])]
    step = grid[1] - grid[0]
    res = minimize_scalar(power, bounds=(best - step, best + step), method="bounded",
                          options={"xatol": 1e-9 * span})
    return float(res.x) if -res.fun >= -power(best) else float(best)


def _basis(t, base, nu, modes):
    return np.exp(-1j * (base + modes @ nu)[None, :] * t[:, None])


def torus(material, case, k, fields0, free, omega_guess, P=TORUS_HARMONICS, M=PHASE_POINTS,
          order=None):
    """Measure the torus of the state ``fields0`` (values on the M phase points).

    ``free``: list of (field, harmonic m, lab frequency guess) of the free waves to give a
    phase of their own. Returns a :class:`Torus`.
    """
    d = len(free)
    order = (FIT_ORDER if d <= 1 else FIT_ORDER - 1) if order is None else order
    nu0 = np.array([f - m * omega_guess for _, m, f in free], float)
    slow = min([abs(n) for n in nu0] + [omega_guess])
    duration = min(MAX_DURATION, max(BEATS * 2 * np.pi / slow,
                                     MIN_CARRIER_PERIODS * 2 * np.pi / omega_guess))
    # sampling: the frequency searches need the carrier and each free wave's harmonic
    # (with the sidebands of the fit around it) unaliased; the fit of harmonic p does not:
    # it is demodulated by e^{i p Omega t} exactly, and a torus's harmonic p holds only
    # p Omega + m . nu, so its samples may alias without harm
    searched = [omega_guess + order * sum(abs(nu0))] + [
        abs(f) + order * sum(abs(nu0)) for _, _, f in free]
    samples = int(np.ceil(duration * max(SAMPLES_PER_PERIOD * omega_guess,
                                         2.5 * max(searched)) / (2 * np.pi))) + 1
    # the fit's basis: samples x (2 order + 1)^d complex values (a state with many free
    # waves, e.g. no carrier, would ask for terabytes)
    checks.memory("initial", 16.0 * samples * (2 * order + 1) ** d,
                  f"the torus of a state with {d} free waves ({samples} samples)")
    t, y = trajectory(material, case, k, fields0, duration, samples, M)
    P = min(P, M // 2 - 1)
    c = _harmonics(y, M // 2 - 1)
    tail = float(np.max(np.abs(c[:, :, -1])) / max(np.max(np.abs(c[:, 0, 1])), 1e-300))
    c = c[..., :P + 1]
    window = np.sin(np.pi * t / duration) ** 2
    span = 3 * 2 * np.pi / duration
    # carrier: theta at k; free waves: their own field and harmonic
    omega = _peak(t, c[:, 0, 1], omega_guess, window, span)
    nu = np.array([_peak(t, c[:, 0 if fld == "theta" else 1, m], f, window, span) - m * omega
                   for fld, m, f in free], float)
    combos = list(itertools.product(range(-order, order + 1), repeat=d))
    modes = np.array(combos, int).reshape(len(combos), d)
    F = np.zeros((2, 2 * P + 1, modes.shape[0]), complex)
    num = den = 0.0
    # the basis of harmonic p is that of p = 0 times the unit-modulus e^{-i p Omega t}, so
    # every fit shares one Gram matrix (normal equations; the windowed quasi-periodic basis
    # is nearly orthogonal over many beats, cond(G) ~ 1)
    B = _basis(t, 0.0, nu, modes) * window[:, None]
    G = B.conj().T @ B
    for f in (0, 1):
        for p in range(P + 1):
            rhs = c[:, f, p] * window * np.exp(1j * p * omega * t)
            coef = np.linalg.solve(G, B.conj().T @ rhs)
            num += np.sum(np.abs(B @ coef - rhs) ** 2)
            den += np.sum(np.abs(rhs) ** 2)
            F[f, P + p] = coef if p == 0 else coef / 2
    # p = 0: c_0 is real, so its coefficients pair as F[0, m] = conj F[0, -m]; average them
    mirror = [int(np.flatnonzero(np.all(modes == -m, axis=1))[0]) for m in modes]
    for f in (0, 1):
        F[f, P] = 0.5 * (F[f, P] + np.conj(F[f, P, mirror]))
        for p in range(1, P + 1):
            F[f, P - p] = np.conj(F[f, P + p, mirror])
    return Torus(k, float(omega), np.asarray(nu, float), modes, F[0], F[1],
                 float(np.sqrt(num / max(den, 1e-300))), float(duration), tail)
