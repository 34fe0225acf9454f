"""The state a run actually starts in: the exact travelling wave plus free linear waves.

An initial condition with a dominant carrier at wavenumber k (the paper's eq. `IC`, or any
user state) is not the lattice's travelling wave. Projected on the harmonics m k of the
carrier it splits into

- the travelling wave ``_plane_wave.plane_wave`` whose first harmonic matches the forward
  part of the initial rotation at k (amplitude and frequency fitted together: its frequency
  depends on its amplitude);
- free linear waves of both branches, forward and backward, at every harmonic m k: what is
  left of the initial fields and velocities at m k once the travelling wave is taken away.

For eq. `IC` (U = U_dot = 0) the free U waves at 2k, frequency omega_U(2k) (not 2 Omega),
cancel the forced second harmonic at T = 0; they beat against it. The U equation of
eq. `norm` is linear in U, so given the rotation the U field is this superposition exactly;
the rotation deviates from it by cross terms of the small free waves with the carrier
(relative order amplitude^2). ``_quasiperiodic`` computes the stability of the
superposition.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from generated import coefficients as continuum
from generated import lattice_model as model

from ..lattice import STARTS, LatticeState, Material, checks
from ._plane_wave import HARMONICS, PlaneWave, _check, plane_wave
from ._torus import PHASE_POINTS_TRIED, SPECTRAL_TAIL, Torus, torus

#: harmonics m k of the carrier searched for free waves (theta odd and U even beyond these
#: are below 1e-10 of the carrier at the amplitudes plane_wave allows)
FREE_HARMONICS = 8
#: amplitude fit of the carrier: fixed-point iterations on its first harmonic
FIT_ITERATIONS = 6
#: free waves get a torus phase of their own above this fraction of their field's scale
#: (LaunchedState.significant); smaller ones change the gain by < 1e-4 relative (their
#: effect is second order in their amplitude)
SIGNIFICANT = 1e-2


@dataclass(frozen=True)
class FreeWave:
    """A free linear wave of the lattice: ``field = amplitude cos(m k n - frequency T + phase)``.

    Attributes
    ----------
    field : {"theta", "U"}
        Branch: rotational (eq. `discrete2`) or longitudinal (eq. `discrete1`).
    harmonic : int
        m: the wave's wavenumber is m k (rad per site).
    wavenumber : float
        m k.
    frequency : float
        Signed: + omega_branch(m k) for a forward wave (moves with the carrier),
        - omega_branch(m k) for a backward one.
    amplitude, phase : float
        Peak value (rad for theta, units of the cell size for U) and phase at T = 0.
    """

    field: str
    harmonic: int
    wavenumber: float
    frequency: float
    amplitude: float
    phase: float

    @property
    def direction(self) -> str:
        return "forward" if self.frequency > 0 else "backward"

    def values(self, n, t=0.0):
        """The wave and its velocity at sites n, time t."""
        arg = self.wavenumber * np.asarray(n, float) - self.frequency * t + self.phase
        return self.amplitude * np.cos(arg), self.amplitude * self.frequency * np.sin(arg)


@dataclass(frozen=True)
class LaunchedState:
    """An initial state split into the exact travelling wave and free linear waves.

    Attributes
    ----------
    start : str
        "paper", "discrete", "travelling" or "initial" (a user's LatticeState).
    carrier : PlaneWave
        The travelling wave (its ``omega`` is the fitted, amplitude-dependent frequency).
    carrier_phase : float
        phi_0: the carrier is Theta(k n - Omega T + phi_0).
    free_waves : tuple of FreeWave
        Every free wave at the harmonics m k, m = 1 .. FREE_HARMONICS, largest first.
    unexplained : float
        Relative L2 norm of the initial rotation outside the harmonics of k (noise; 0 for
        the noise-free starts).
    torus : Torus or None
        The state as it evolves: carrier and the significant free waves with their
        measured (interaction-shifted) frequencies and Fourier coefficients
        (``_torus``); None for ``start="travelling"`` (the wave itself).
    """

    start: str
    carrier: PlaneWave
    carrier_phase: float
    free_waves: tuple
    unexplained: float = 0.0
    torus: Torus | None = None

    @property
    def case(self):
        return self.carrier.case

    @property
    def k(self):
        return self.carrier.k

    def fields(self, n, t=0.0):
        """theta, theta_dot, U, U_dot at sites n, time t: the linear superposition."""
        n = np.asarray(n, float)
        th, thd, U, Ud = self.carrier.fields(n + self.carrier_phase / self.k, t)
        for w in self.free_waves:
            x, xd = w.values(n, t)
            if w.field == "theta":
                th, thd = th + x, thd + xd
            else:
                U, Ud = U + x, Ud + xd
        return th, thd, U, Ud

    @property
    def frequencies(self) -> dict:
        """Lab frequencies as the state evolves: "carrier" Omega, and per significant free
        wave (field, harmonic, direction) its frequency, shifted by the interaction."""
        out = {"carrier": self.carrier.omega if self.torus is None else self.torus.omega}
        if self.torus is not None:
            for w, nu in zip(self.significant(), self.torus.nu):
                out[(w.field, w.harmonic, w.direction)] = float(nu + w.harmonic
                                                                * self.torus.omega)
        return out

    def mode(self, field: str, m: int, t):
        """Complex amplitude of ``field`` ("theta" or "U") at wavenumber m k (convention
        x = Re sum c e^{i m k n}) at times t: from the torus (interaction-shifted
        frequencies), else the linear superposition. For U at 2k: the forced harmonic
        beating the free waves, as the simulation shows it."""
        if self.torus is not None:
            return self.torus.harmonic(field, m, t)
        return self._linear_mode(field, m, t)

    def _linear_mode(self, field, m, t):
        """The linear superposition's amplitude at m k: the carrier's harmonic turning at
        m Omega, plus the free waves at their linear frequencies."""
        t = np.asarray(t, float)
        z = self.carrier.complex_harmonics(m)[field][m - 1]
        c = z * np.exp(1j * m * (self.carrier_phase - self.carrier.omega * t))
        for w in self.free_waves:
            if w.field == field and w.harmonic == m:
                c = c + w.amplitude * np.exp(1j * (w.phase - w.frequency * t))
        return c

    def significant(self, relative: float = SIGNIFICANT) -> tuple:
        """Free waves that matter for stability: rotational ones above ``relative`` of the
        carrier's first harmonic, longitudinal ones above ``relative`` of the carrier's
        second U harmonic (U waves drive the rotation through that coupling)."""
        a1 = abs(self.carrier.theta_harmonics[0])
        b2 = abs(self.carrier.U_harmonics[0]) if self.carrier.U_harmonics.size else 0.0
        return tuple(w for w in self.free_waves
                     if w.amplitude > relative * (a1 if w.field == "theta" else b2)
                     and w.amplitude > 0)


def _branch(field, material, wavenumber):
    if field == "theta":
        return float(model.omega_rotation(wavenumber, material.alpha, material.K_s,
                                          material.K_theta))
    return float(model.omega_longitudinal(wavenumber))


def _carrier_harmonics(wave: PlaneWave, phase: float, M: int):
    """Complex amplitudes (value, velocity) of the carrier's theta and U at m k, m = 1..M:
    the harmonic m of Theta(k n - W T + phi0) has velocity amplitude -i m W z."""
    m = np.arange(1, M + 1)
    out = {}
    for field, c in wave.complex_harmonics(M).items():
        z = c * np.exp(1j * m * phase)
        out[field] = np.stack([z, -1j * m * wave.omega * z])
    return out


def forward_backward(z, zd, w):
    """A linear wave's value z and velocity zd at one wavenumber, split into its forward
    part f e^{-i w T} and backward part b e^{+i w T}: z = f + b, zd = -i w f + i w b."""
    f = (w * z + 1j * zd) / (2 * w)
    return f, z - f


def _decompose(material, case, k, given, harmonics, start, unexplained=0.0):
    """Fit the carrier to the theta amplitude at k, then free waves from the residuals.

    ``given``: field -> (2, M) complex amplitudes of value and velocity at m k (convention
    x_n = Re sum_m c_m e^{i m k n}).
    """
    M = given["theta"].shape[1]
    A, B = given["theta"][:, 0]
    w_back = _branch("theta", material, k)
    peak, wave = abs(A), None
    for _ in range(FIT_ITERATIONS):
        wave = plane_wave(material, case, k, peak, harmonics)
        # forward part F (frequency Omega) and backward part (linear frequency) of the
        # rotation at k: A = F + beta, B = -i Omega F + i w beta
        F = (w_back * A + 1j * B) / (wave.omega + w_back)
        a1 = wave.theta_harmonics[0]
        if abs(abs(F) - a1) <= 1e-14 * abs(F):
            break
        peak = peak + abs(F) - a1
        if not 0 < peak:
            raise ValueError("the initial state has no forward carrier at k to fit")
    phase = float(np.angle(F))
    carrier = _carrier_harmonics(wave, phase, M)
    free = []
    for field in ("theta", "U") if case == "coupled" else ("theta",):
        R = given[field] - carrier[field]
        for m in range(1, M + 1):
            z, zd = R[:, m - 1]
            if z == 0 and zd == 0:
                continue
            kk = math.remainder(m * k, 2 * math.pi)
            w = _branch(field, material, kk)
            if w <= 0:
                continue  # a uniform mode (m k = 0 mod 2 pi): a rigid shift, not a wave
            f, b = forward_backward(z, zd, w)
            for amp, nu in ((f, w), (b, -w)):
                if abs(amp) > 0:
                    free.append(FreeWave(field, m, m * k, nu, float(abs(amp)),
                                         float(np.angle(amp))))
    free.sort(key=lambda w: -w.amplitude)
    state = LaunchedState(start, wave, phase, tuple(free), unexplained)
    free_phases = [(w.field, w.harmonic, w.frequency) for w in state.significant()]
    for points in PHASE_POINTS_TRIED:  # the fewest phase points that resolve the state
        x = 2 * np.pi * np.arange(points) / points
        e = np.exp(1j * np.outer(np.arange(1, M + 1), x))  # (M, points)
        fields0 = [(given[f][i] @ e).real for f in ("theta", "U") for i in (0, 1)]
        tor = torus(material, case, k, fields0, free_phases, wave.omega, M=points)
        if tor.tail < SPECTRAL_TAIL:
            break
    return LaunchedState(start, wave, phase, tuple(free), unexplained, tor)


def _paper_harmonics(material, k, amplitude, start, M):
    """Eq. `IC` without noise: theta = a cos(k n), theta_dot = a w sin(k n), U at rest."""
    if start == "paper":
        w = float(continuum.omega(k, material.alpha, material.K_s, material.K_theta))
    else:
        w = _branch("theta", material, k)
    given = {f: np.zeros((2, M), complex) for f in ("theta", "U")}
    given["theta"][:, 0] = amplitude, -1j * amplitude * w  # a w sin = Re[-i a w e^{ikn}]
    return given


def _state_harmonics(state: LatticeState, k, M):
    N = state.theta.size
    m0 = k * N / (2 * math.pi)
    if abs(m0 - round(m0)) > 1e-9 * max(1.0, m0):
        raise ValueError(f"k = {k} is not a wavenumber 2 pi m / N of the {N}-site chain the "
                         "initial state lives on; use numerics.snap_wavenumber(k, N)")
    m0 = int(round(m0))
    given = {}
    for f, (x, xd) in (("theta", (state.theta, state.theta_dot)),
                       ("U", (state.U, state.U_dot))):
        if x is None:
            given[f] = np.zeros((2, M), complex)
            continue
        X, Xd = np.fft.fft(x) * (2.0 / N), np.fft.fft(xd) * (2.0 / N)
        idx = [(m * m0) % N for m in range(1, M + 1)]
        # Nyquist and uniform bins carry cos only: halve the doubled amplitude
        factor = np.array([0.5 if i in (0, N // 2) and N % 2 == 0 or i == 0 else 1.0
                           for i in idx])
        given[f] = np.stack([X[idx] * factor, Xd[idx] * factor])
    th = state.theta
    total = np.sum(th**2)
    idx_all = {(m * m0) % N for m in range(1, M + 1)} | {(-m * m0) % N for m in range(1, M + 1)}
    T = np.fft.fft(th)
    rest = np.sum(np.abs(np.delete(T, sorted(idx_all)))**2) / N
    unexplained = float(np.sqrt(rest / total)) if total > 0 else 0.0
    return given, unexplained


#: largest rms share of an initial state's rotation outside k and its harmonics
MAX_UNEXPLAINED = 0.5


def launched_state(material: Material, case: str, k: float, amplitude: float | None = None,
                   start: str = "paper", initial: LatticeState | None = None,
                   harmonics: int = HARMONICS) -> LaunchedState:
    """The travelling wave and free linear waves an initial condition launches.

    Parameters
    ----------
    material : Material
    case : {"rotation", "coupled"}
    k : float
        Carrier wavenumber, rad per site, in (0, pi).
    amplitude : float
        Peak rotation of the initial cosine (2 eps A0 in eq. `IC`); for
        ``start="travelling"`` the travelling wave's peak rotation.
    start : {"paper", "discrete", "travelling"}
        "paper": eq. `IC`, theta = a cos(k n), theta_dot = a omega_c(k) sin(k n) with the
        continuum frequency (eq. `continuum2`), U = U_dot = 0; "discrete": the same with
        the lattice's linear frequency (eq. `discrete2`); "travelling": the exact
        travelling wave (no free waves). Ignored when ``initial`` is given.
    initial : LatticeState, optional
        Any state of a chain of N sites whose rotation is dominated by a carrier at
        k = 2 pi m / N (e.g. ``numerics.initial_condition(...)``); ``amplitude`` is then
        not used.
    harmonics : int
        Truncation of the travelling wave (as :func:`plane_wave`).

    Returns
    -------
    LaunchedState
        For eq. `IC` in case II: the carrier, free U waves at 2k (forward and backward,
        frequencies +- omega_U(2k)) cancelling its forced U harmonic at T = 0, and small
        free rotational waves (a backward wave at k: the initial velocity uses a frequency
        other than the carrier's; waves at 3k, 5k, .. replacing its odd harmonics).

    Examples
    --------
    >>> import numpy as np
    >>> s = launched_state(Material.paper("blue"), "coupled", 0.81681, 0.02)
    >>> u2 = s.mode("U", 2, np.linspace(0, 2000, 5))  # U at 2k: forced harmonic + free waves
    >>> forced = abs(s.carrier.U_harmonics[0])
    >>> bool(abs(u2[0]) < 0.01 * forced)  # eq. `IC` starts with U = 0: they cancel at T = 0
    True
    >>> bool(abs(u2).max() > forced)      # and beat later
    True
    """
    checks.instance("material", material, Material)
    M = FREE_HARMONICS
    if initial is not None:
        checks.instance("initial", initial, LatticeState)
        k = checks.real("k", k, 0.0, math.pi)
        if (initial.U is None) != (case == "rotation"):
            raise ValueError(f"initial state has {'no ' if initial.U is None else ''}U field "
                             f"but case is {case!r}")
        given, unexplained = _state_harmonics(initial, k, M)
        if abs(given["theta"][0, 0]) == 0:
            raise ValueError("the initial state has no rotation at wavenumber k")
        # the decomposition describes a carrier with small free waves; a state whose
        # rotation lies mostly elsewhere (noise, another wavenumber) would need a torus
        # with a free phase per component: no carrier, no launched state
        if unexplained > MAX_UNEXPLAINED:
            raise ValueError(f"initial: {100 * unexplained:.0f}% of its rotation (rms) lies "
                             f"outside k = {k:.6g} and its harmonics (at most "
                             f"{100 * MAX_UNEXPLAINED:.0f}%): it is not a carrier at k")
        return _decompose(material, case, k, given, harmonics, "initial", unexplained)
    if amplitude is None:
        raise TypeError("amplitude is required unless an initial state is given")
    k, amplitude = _check(material, case, k, amplitude)
    checks.choice("start", start, STARTS)
    if start == "travelling":
        return LaunchedState(start, plane_wave(material, case, k, amplitude, harmonics), 0.0, ())
    return _decompose(material, case, k, _paper_harmonics(material, k, amplitude, start, M),
                      harmonics, start)
