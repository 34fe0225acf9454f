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
from numba import njit

from generated import lattice_model as model

from ..lattice import FASTMATH, checks, get_method, sincos_vers, site_acceleration

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
#: the fit of the torus (normal equations: ~8 samples x modes^2 flops for the Gram matrix,
#: modes = (2 order + 1)^free waves) is refused above this: a state with 5 or more
#: significant free waves (3125 modes, ~1e12 flops: minutes in one uninterruptible BLAS
#: call; the paper chain at amplitude 1 rad launches 6: 15625 modes, more than its samples)
#: is no carrier with small sidebands, the linear response's premise; 4 (625 modes, ~4e10
#: flops, ~10 s) are fitted
TORUS_FIT_FLOPS = 1e11
#: the reduced chain is integrated by SRKN11b (order 6) with omega_max dt below this: its
#: error model (``_accuracy.ERROR_CONSTANTS``) gives ~6e-6 relative over 20 000 T (the
#: tori last ~2000 T); halving it changes predicted growth factors by < 3e-6 (60 fig3 cells)
OMEGA_DT = 0.8
#: frequency analysis: coarse grid points over +- 3 resolution bins (10 per bin: the peak's
#: main lobe spans 4), Newton steps, and the tolerance relative to the grid's half-width
PEAK_GRID, PEAK_NEWTON, PEAK_TOL = 61, 8, 1e-9


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
        d = self.nu.size
        shape = (phi.size,) + (psi.size,) * d
        if not d:
            return out.sum(axis=1).real.reshape(shape)
        grids = np.stack([g.ravel() for g in np.meshgrid(*([psi] * d), indexing="ij")])
        # every mode's free phase factor on the grid at once: (nm, Mq^d)
        return (out @ np.exp(1j * (self.modes @ grids))).real.reshape(shape)


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


@njit(cache=True, fastmath=FASTMATH, boundscheck=False)
def _reduced_accel(th, U, SpT, SmT, coupled, a2, Ks, Kt, X, XU, s, c, v, ath, aU):
    """Accelerations of the reduced chain: neighbours by the shift matrices (stored
    transposed, so the inner loop runs over contiguous rows and vectorises while every
    sum keeps its order), the site formula of the lattice kernel (``numerics.lattice.site_acceleration``) on
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
        s[i], c[i], v[i] = sincos_vers(X[i])
    for i in range(M):
        ath[i], aU[i] = site_acceleration(M + i, i, 2 * M + i, X, XU, s, c, v, coupled, a2, Ks, Kt)


@njit(cache=True, fastmath=FASTMATH, boundscheck=False)
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
    """Frequency near ``guess`` maximising |S(nu)| = |sum w c e^{i nu t}| (a NAFF step): a
    coarse grid finds the peak, Newton steps on |S|^2 refine it to PEAK_TOL of the span.

    The grid's values come from one exponential and a running product (t is uniform:
    e^{i (nu + h) t} = e^{i nu t} e^{i h t}); Newton uses S' and S'' in closed form. Where
    Newton does not settle inside the grid cell, a bounded scalar search does it."""
    wc = window * c
    grid = guess + np.linspace(-span, span, PEAK_GRID)
    step = grid[1] - grid[0]
    term = np.exp(1j * grid[0] * t) * wc
    turn = np.exp(1j * step * t)
    power = np.empty(PEAK_GRID)
    for i in range(PEAK_GRID):
        power[i] = abs(term.sum())
        term *= turn
    best = float(grid[np.argmax(power)])
    lo, hi = best - step, best + step
    twc, t2wc = t * wc, t * t * wc
    nu = best
    for _ in range(PEAK_NEWTON):
        e = np.exp(1j * nu * t)
        S, S1, S2 = e @ wc, e @ twc, e @ t2wc
        # f = |S|^2: f' = 2 Re(conj(S) i S1), f'' = 2 (|S1|^2 - Re(conj(S) S2))
        d1 = -2.0 * (np.conj(S) * S1).imag
        d2 = 2.0 * (abs(S1) ** 2 - (np.conj(S) * S2).real)
        if not d2 < 0.0:  # not concave here: no Newton step
            break
        move = -d1 / d2
        nu += move
        if not lo <= nu <= hi:
            break
        if abs(move) < PEAK_TOL * span:
            return float(nu)
    from scipy.optimize import minimize_scalar

    neg = lambda x: -abs(np.exp(1j * x * t) @ wc)
    res = minimize_scalar(neg, bounds=(lo, hi), method="bounded",
                          options={"xatol": PEAK_TOL * span})
    return float(res.x) if -res.fun >= -neg(best) else best


def uniform_phases(t, w):
    """e^{i w t} for t (nt,) and w (nw,) -> (nt, nw), the same as np.exp(1j * np.outer(t,
    w)) to a few eps. On a uniform t (t_j = t_0 + j h) as the product of two tables,
    e^{i w (t_0 + B a h)} e^{i w b h} with j = B a + b: ~2 sqrt(nt) exponentials per w
    instead of nt (the trajectories' sample grids and the records are uniform)."""
    t, w = np.asarray(t, float), np.asarray(w, float)
    nt = t.size
    h = (t[-1] - t[0]) / (nt - 1) if nt > 1 else 0.0
    if nt < 64 or not np.allclose(t, t[0] + h * np.arange(nt), rtol=0.0,
                                  atol=1e-12 * max(abs(t[-1]), abs(t[0]), 1.0)):
        return np.exp(1j * np.outer(t, w))
    B = int(np.ceil(np.sqrt(nt)))
    coarse = np.exp(1j * np.outer(t[0] + B * h * np.arange(-(-nt // B)), w))  # (na, nw)
    fine = np.exp(1j * np.outer(h * np.arange(B), w))  # (B, nw)
    return (coarse[:, None, :] * fine[None, :, :]).reshape(-1, w.size)[:nt]


def _basis(t, base, nu, modes):
    return uniform_phases(t, -(base + modes @ nu))


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
    # the fit's basis: samples x (2 order + 1)^d complex values, twice (B and its adjoint),
    # and its Gram matrix (a state with many free waves, e.g. no carrier, would ask for
    # terabytes)
    nm = (2 * order + 1) ** d
    if nm > samples / 2 or 8.0 * samples * nm**2 > TORUS_FIT_FLOPS:
        # no linear theory of its sidebands (as a state that is no torus): ArithmeticError,
        # the theory's row undefined with this reason, a map cell's "not quasi-periodic"
        raise ArithmeticError(
            f"start 'paper': the state eq. `IC` launches holds {d} significant free waves "
            f"besides the carrier ({nm} quasi-periodic modes to fit to {samples} samples, "
            f"~{8.0 * samples * nm**2:.1e} flops): no carrier with small sidebands, the "
            "linear response's premise (an amplitude far beyond the NLS's range); lower "
            "--amplitude, or use --start travelling (the exact travelling wave)")
    checks.memory("start 'paper'", 16.0 * (2 * samples * nm + nm * nm),
                  f"the torus of the state eq. `IC` launches, with {d} free waves ({samples} "
                  "samples; a smaller amplitude launches fewer, the travelling start none)")
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
    # the basis of harmonic p is that of p = 0 times the unit-modulus e^{-i p Omega t}, so
    # every fit shares one Gram matrix (normal equations; the windowed quasi-periodic basis
    # is nearly orthogonal over many beats, cond(G) ~ 1)
    B = _basis(t, 0.0, nu, modes) * window[:, None]
    Bh = np.ascontiguousarray(B.conj().T)
    G = Bh @ B
    # every (field, p) at once: the demodulated harmonics are the right-hand sides
    demod = uniform_phases(t, omega * np.arange(P + 1))  # (nt, P + 1)
    rhs = (c * (window[:, None] * demod)[:, None, :]).reshape(t.size, 2 * (P + 1))
    coef = np.linalg.solve(G, Bh @ rhs)  # (nm, 2 (P + 1))
    num = np.sum(np.abs(B @ coef - rhs) ** 2)
    den = np.sum(np.abs(rhs) ** 2)
    coef = coef.T.reshape(2, P + 1, -1)
    F[:, P] = coef[:, 0]
    F[:, P + 1:] = coef[:, 1:] / 2
    # p = 0: c_0 is real, so its coefficients pair as F[0, m] = conj F[0, -m]; average them
    mirror = [int(np.flatnonzero(np.all(modes == -m, axis=1))[0]) for m in modes]
    for f in (0, 1):
        F[f, P] = 0.5 * (F[f, P] + np.conj(F[f, P, mirror]))
        for p in range(1, P + 1):
            F[f, P - p] = np.conj(F[f, P + p, mirror])
    return Torus(k, float(omega), np.asarray(nu, float), modes, F[0], F[1],
                 float(np.sqrt(num / max(den, 1e-300))), float(duration), tail)
