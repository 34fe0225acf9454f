"""Envelope solitons of the chain: prediction, lattice launch, and measurement of a run.

The closed forms are derived in ``derivation/_soliton.py`` and read from
``generated/soliton.py`` (bright and dark solitons of the NLS, eq. `NLS`, in lattice units,
with the kink of U in case II); the NLS coefficients come from ``generated.coefficients``
(theory ``"paper NLS"``) or ``generated.lattice_coefficients`` (``"semi-discrete NLS"``,
the default: it is the one the lattice follows, see docs/solitons.md).

Conventions: ``amplitude`` is the peak rotation (rad) of the carrier, 2|E| (the paper's
2 eps |B|); for a dark soliton that of the background. Widths in sites, |E| = a sech(xi/w)
(bright) or a tanh(xi/w) (black). Velocities in sites per T, frequencies in 1/T, the kink
height in lattice units of U.

A ring of N sites carries a bright soliton at k = 2 pi m / N, and a dark one only when the
carrier closes the envelope's phase jump: k N + (2 phi - pi) = 2 pi m (k = (2m + 1) pi / N
for a black soliton); :func:`ring_wavenumber` picks that k. Case II: U carries the mean
strain mu (|E|^2 - background) under the envelope (its integral is the kink) minus its ring
average (a periodic U has no net strain: the compensating uniform strain is kink / N), and
the second harmonic u2 = c E^2 e^{2 i sigma} + c.c.; U_dot = -v U' for the kink.
"""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass, field

import numpy as np

from generated import coefficients as continuum_nls
from generated import lattice_coefficients as lattice_nls
from generated import soliton as closed

from ..lattice import checks
from ..lattice._integrate import integrate
from ..lattice._model import LatticeState, Material, check_case

KINDS = ("bright", "dark")
#: the NLS theories a soliton can be predicted from (names as in ``THEORIES``)
SOLITON_THEORIES = {"semi-discrete NLS": lattice_nls, "paper NLS": continuum_nls}
#: below this width (sites) the envelope is too narrow for the weak-modulation ordering
#: (the convergence scene shows the error reaching tens of percent near 5 sites)
MIN_WIDTH = 8.0
#: longest run simulate_soliton picks by itself (about 2 min for a ring of 1000 sites)
MAX_T_END = 5e5


class SolitonWarning(UserWarning):
    """The soliton asked for is too narrow for the envelope theory."""


@dataclass(frozen=True)
class Soliton:
    """A predicted envelope soliton of one material, case, carrier and theory.

    Attributes
    ----------
    kind : {"bright", "dark"}
    theory : {"semi-discrete NLS", "paper NLS"}
    material, case, k, amplitude, phi
        The inputs (k in rad/site, amplitude = peak rotation in rad; phi the greyness angle
        of a dark soliton, 0 = black).
    omega, v_g, g1, g2 : float
        The NLS at k (linear carrier frequency, group velocity, eq. `g_i`).
    width : float
        Sites: |E| = a sech(xi/w) (bright), a^2 - |E|^2 = a^2 cos^2(phi) sech^2(xi/w) (dark).
    velocity : float
        Sites per T: v_g (bright, black), v_g + V (grey).
    frequency : float
        The soliton's carrier frequency (1/T): omega minus the nonlinear shift.
    mu : float
        Mean-flow coefficient (case II), U_{n+1} - U_n = mu (|E|^2 - background); 0 in case I.
    kink_height : float
        U(+inf) - U(-inf) across the soliton (lattice units); 0 in case I.
    """

    kind: str
    theory: str
    material: Material
    case: str
    k: float
    amplitude: float
    phi: float
    omega: float
    v_g: float
    g1: float
    g2: float
    width: float
    velocity: float
    frequency: float
    mu: float
    kink_height: float
    u2: complex = field(repr=False, default=0j)

    @property
    def g(self) -> float:
        return self.g2 / self.g1

    def envelope(self, xi, t=0.0):
        """E at sites ``xi`` from the centre (frame moving with v_g), time ``t``."""
        if self.kind == "bright":
            return closed.bright_envelope(xi, t, self.amplitude, self.g1, self.g2)
        return closed.dark_envelope(xi, t, self.amplitude, self.phi, self.g1, self.g2)

    def summary(self) -> dict:
        """The five numbers the CLI prints and ``soliton.json`` stores."""
        return {"velocity": self.velocity, "width": self.width, "amplitude": self.amplitude,
                "frequency": self.frequency, "kink_height": self.kink_height}


def _kind_that_exists(g):
    return "bright" if g > 0 else "dark"


def soliton(material: Material, case: str, k: float, amplitude: float, kind: str | None = None,
            *, theory: str = "semi-discrete NLS", phi: float = 0.0,
            N: int | None = None) -> Soliton:
    """The envelope soliton the NLS predicts at carrier ``k`` and peak rotation ``amplitude``.

    Parameters
    ----------
    material : Material
    case : {"rotation", "coupled"}
    k : float
        Carrier wavenumber, rad/site, in (0, pi).
    amplitude : float
        Peak rotation (rad): of the soliton (bright) or of its background (dark).
    kind : {"bright", "dark"}, optional
        Default: the one that exists (bright where g = g2/g1 > 0, dark where g < 0).
    theory : {"semi-discrete NLS", "paper NLS"}
    phi : float
        Greyness angle of a dark soliton, |phi| < pi/2 (0: black); 0 for bright ones.
    N : int, optional
        On a ring of N sites (case II, semi-discrete NLS): a periodic U has no net strain,
        so the mean strain under the soliton is compensated by a uniform one over the ring,
        which the carrier feels through the mean-flow part of g2 (a frequency shift of
        order width / N). Default: an infinite chain with no strain far away.

    Returns
    -------
    Soliton

    Raises
    ------
    ValueError
        A kind that does not exist here (the message names the one that does), or bad input.

    Warns
    -----
    SolitonWarning
        When the width is below ``MIN_WIDTH`` sites (the envelope theory does not hold).

    Examples
    --------
    >>> from numerics import Material
    >>> from numerics.theory import soliton
    >>> s = soliton(Material.paper("green"), "rotation", 0.92991, 0.002)
    >>> print(s.kind, f"{s.width:.1f} sites, v = {s.velocity:.5f}")
    bright 28.0 sites, v = -0.01689
    """
    checks.instance("material", material, Material)
    check_case(case)
    k = checks.real("k", k, 0.0, math.pi)
    amplitude = checks.positive("amplitude", amplitude)
    if amplitude >= 1.0:
        raise ValueError(f"amplitude must be a small peak rotation (< 1 rad), got {amplitude}")
    try:
        nls = SOLITON_THEORIES[theory]
    except (KeyError, TypeError):
        raise ValueError(f"theory must be one of {tuple(SOLITON_THEORIES)}, got "
                         f"{theory!r}") from None
    phi = checks.real("phi", phi, -math.pi / 2, math.pi / 2)
    p = (k, material.alpha, material.K_s, material.K_theta)
    omega, v_g, g1 = (float(f(*p)) for f in (nls.omega, nls.group_velocity, nls.g1))
    g2 = float(getattr(nls, f"g2_{case}")(*p))
    if not (math.isfinite(g1) and math.isfinite(g2)) or g1 == 0 or g2 == 0:
        raise ValueError(f"the {theory} has g1 = {g1:.4g}, g2 = {g2:.4g} at k = {k:g}: no "
                         "soliton (delta = 0 or a resonance)")
    g = g2 / g1
    exists = _kind_that_exists(g)
    if kind is None:
        kind = exists
    if kind not in KINDS:
        raise ValueError(f"kind must be one of {KINDS}, got {kind!r}")
    if kind != exists:
        nature = "focusing" if g > 0 else "defocusing"
        raise ValueError(f"kind={kind!r}: the {theory} is {nature} here (g = g2/g1 = {g:.4g}, "
                         f"case {case}, k = {k:g}), so a {exists} soliton exists, not a {kind} "
                         "one")
    if kind == "bright" and phi != 0:
        raise ValueError(f"phi (greyness) applies to dark solitons only, got phi = {phi}")
    coupled = case == "coupled"
    mu = 0.0
    if coupled:
        mu = float(lattice_nls.mean_flow_coefficient(*p) if nls is lattice_nls
                   else closed.continuum_mean_flow_coefficient(*p))
    if N is not None:
        N = checks.integer("N", N, 3)
    # the mean-flow term of the semi-discrete NLS is g2_mf (F_X / mu) E with F_X = mu |E|^2
    # + c; a uniform strain c (no strain far away; on a ring, minus the soliton's mean)
    # turns E at g2_mf c / mu: the frequency moves by -g2_mf c / mu
    g2_mf = float(closed.lattice_g2_mean_flow(*p)) if coupled and nls is lattice_nls else 0.0
    if kind == "bright":
        width = float(closed.bright_width(amplitude, g1, g2))
        velocity = v_g
        c_over_mu = 0.0 if N is None else -2 * (amplitude / 2) ** 2 * width / N
        frequency = (omega - float(closed.bright_frequency_shift(amplitude, g1, g2))
                     - g2_mf * c_over_mu)
        kink = float(closed.bright_kink(amplitude, g1, g2, mu))
    else:
        width = float(closed.dark_width(amplitude, phi, g1, g2))
        velocity = v_g + float(closed.dark_velocity(amplitude, phi, g1, g2))
        dip = 0.0 if N is None else 2 * width * math.cos(phi) ** 2 / N
        c_over_mu = -(amplitude / 2) ** 2 * (1 - dip)
        frequency = (omega - float(closed.dark_frequency_shift(amplitude, g2))
                     - g2_mf * c_over_mu)
        kink = float(closed.dark_kink(amplitude, phi, g1, g2, mu))
    if width < MIN_WIDTH:
        warnings.warn(f"the {kind} soliton is {width:.3g} sites wide (< {MIN_WIDTH:g}): the "
                      "envelope theory does not hold at this amplitude; lower the amplitude",
                      SolitonWarning, stacklevel=2)
    u2 = complex(nls.u2_coefficient(*p)) if coupled else 0j
    return Soliton(kind=kind, theory=theory, material=material, case=case, k=k,
                   amplitude=amplitude, phi=phi, omega=omega, v_g=v_g, g1=g1, g2=g2,
                   width=width, velocity=velocity, frequency=frequency, mu=mu,
                   kink_height=kink if coupled else 0.0, u2=u2)


def ring_wavenumber(k: float, N: int, kind: str = "bright", phi: float = 0.0) -> float:
    """The wavenumber nearest ``k`` on which a ring of ``N`` sites carries the soliton.

    Bright: 2 pi m / N. Dark: the envelope's phase jumps by 2 phi - pi across the soliton,
    so the carrier must close the ring with the opposite phase: k N + 2 phi - pi = 2 pi m.
    """
    N = checks.integer("N", N, 3)
    k = checks.real("k", k, 0.0, math.pi)
    if kind not in KINDS:
        raise ValueError(f"kind must be one of {KINDS}, got {kind!r}")
    offset = 0.0 if kind == "bright" else math.pi - 2 * phi
    m = round((k * N - offset) / (2 * math.pi))
    out = (2 * math.pi * m + offset) / N
    if not 0 < out < math.pi:
        raise ValueError(f"no ring wavenumber near k = {k:g} for N = {N}")
    return out


def soliton_state(sol: Soliton, N: int, centre: float | None = None) -> LatticeState:
    """theta, theta_dot (and U, U_dot in case II) of ``sol`` centred at site ``centre``.

    theta_n = E e^{i k n} + c.c. and theta_dot from the envelope's motion at v_g and its
    frequency; in case II, U from the mean strain (ring average removed) and the second
    harmonic, U_dot from their motion. ``sol.k`` must fit the ring (:func:`ring_wavenumber`).
    """
    N = checks.integer("N", N, 16)
    fit = ring_wavenumber(sol.k, N, sol.kind, sol.phi)
    if abs(fit - sol.k) > 1e-9 * sol.k:
        raise ValueError(f"k = {sol.k:.6g} does not fit a ring of N = {N} sites for a {sol.kind}"
                         f" soliton; use k = ring_wavenumber(k, N, kind) = {fit:.6g}")
    if sol.width * 12 > N:
        raise ValueError(f"N = {N} is too short for a soliton {sol.width:.3g} sites wide "
                         f"(need N >= 12 widths = {math.ceil(12 * sol.width)})")
    c = N / 2 if centre is None else float(centre)
    n = np.arange(N, dtype=float)
    xi = n - c
    carrier = np.exp(1j * sol.k * n)
    h, ht = 1e-3, 1e-2  # central differences: (h / w)^2 < 1e-8
    E = sol.envelope(xi)
    E_xi = (sol.envelope(xi + h) - sol.envelope(xi - h)) / (2 * h)
    E_t = (sol.envelope(xi, ht) - sol.envelope(xi, -ht)) / (2 * ht)
    # d/dt of E(n - v_g t, t) e^{i(k n - w t)}; the NLS frame moves with v_g. E turns at
    # its own shift s (e^{i s t}), so w = frequency + s: omega, except in case II where a
    # uniform strain (a ring's, a dark soliton's background) moves it (see soliton())
    s_E = (closed.bright_frequency_shift(sol.amplitude, sol.g1, sol.g2) if sol.kind == "bright"
           else closed.dark_frequency_shift(sol.amplitude, sol.g2))
    dE = E_t - sol.v_g * E_xi - 1j * (sol.frequency + float(s_E)) * E
    theta = 2 * np.real(E * carrier)
    theta_dot = 2 * np.real(dE * carrier)
    if sol.case == "rotation":
        return LatticeState(None, None, theta, theta_dot)
    bg = 0.0 if sol.kind == "bright" else (sol.amplitude / 2) ** 2
    mid = sol.envelope(xi + 0.5)  # the strain U_{n+1} - U_n sits between the sites
    strain = sol.mu * (np.abs(mid) ** 2 - bg)
    strain -= strain.mean()  # periodic U: the ring absorbs the kink as a uniform strain
    U = np.concatenate([[0.0], np.cumsum(strain)[:-1]])
    U -= U.mean()
    U_dot = -sol.velocity * (strain + np.roll(strain, 1)) / 2
    second = sol.u2 * E**2 * carrier**2
    U = U + 2 * np.real(second)
    U_dot = U_dot + 2 * np.real(-2j * sol.frequency * second)
    return LatticeState(U, U_dot, theta, theta_dot)


# --------------------------------------------------------------------------- measurement

@dataclass(frozen=True)
class Snapshot:
    """What one state shows of a soliton: fitted centre (site, unwrapped), peak rotation
    (bright) or background peak rotation (dark), width, depth (dark: min/background),
    kink height (case II); radiation: the intensity off the fitted profile farther than
    RADIATION_WINDOW widths from the centre, scaled to the whole ring (the window hides
    its share of radiation spread evenly), relative to the soliton's own intensity;
    shape_misfit: the same inside the window (how far the profile is from sech^2)."""

    t: float
    centre: float
    amplitude: float
    width: float
    depth: float
    kink_height: float
    radiation: float
    shape_misfit: float


#: half-width (in soliton widths) of the window that counts as the soliton
RADIATION_WINDOW = 6.0


def _ring_distance(n, c, N):
    return (n - c + N / 2) % N - N / 2


def _fit_profile(amp2, kind, c0, w0, N):
    """Least-squares fit of the intensity |2E|^2 near c0: (centre, amplitude, width, depth)."""
    from scipy.optimize import least_squares

    n = np.arange(N, dtype=float)
    d = _ring_distance(n, c0, N)
    win = np.abs(d) < (6 if kind == "bright" else 8) * w0
    scale = float(np.max(amp2))  # fit O(1) numbers: least_squares' tolerances are absolute
    x, y = d[win], amp2[win] / scale
    if kind == "bright":
        def model(p):
            return p[1] ** 2 / np.cosh((x - p[0]) / p[2]) ** 2
        p0 = [x[np.argmax(y)], math.sqrt(y.max()), w0]
    else:
        def model(p):
            return p[1] ** 2 * (1 - p[3] / np.cosh((x - p[0]) / p[2]) ** 2)
        far = np.abs(d) > 8 * w0
        bg = math.sqrt(np.median(amp2[far] / scale)) if far.any() else 1.0
        p0 = [x[np.argmin(y)], bg, w0, 1.0 - y.min() / bg**2]
    res = least_squares(lambda p: model(p) - y, p0, xtol=1e-12, ftol=1e-12, gtol=1e-12)
    p = res.x
    p[1] *= math.sqrt(scale)
    centre = c0 + p[0]
    fit_full = np.zeros(N)
    dd = _ring_distance(n, centre, N)
    if kind == "bright":
        fit_full = p[1] ** 2 / np.cosh(dd / p[2]) ** 2
        soliton_part = fit_full
    else:
        fit_full = p[1] ** 2 * (1 - p[3] / np.cosh(dd / p[2]) ** 2)
        soliton_part = p[1] ** 2 - fit_full
    off = np.abs(amp2 - fit_full)
    core = np.abs(dd) <= RADIATION_WINDOW * abs(p[2])
    content = np.sum(np.abs(soliton_part))
    share = max(1 - core.mean(), 1e-12)  # the part of the ring outside the window
    radiation = float(np.sum(off[~core]) / content / share) if (~core).any() else float("nan")
    misfit = float(np.sum(off[core]) / content)
    depth = 0.0 if kind == "bright" else float(1 - p[3])
    return centre, abs(float(p[1])), abs(float(p[2])), depth, radiation, misfit


def _kink(state, sol, centre, width):
    """U across the soliton: the low-passed strain (|q| < k/2 drops the second harmonic)
    summed over +-8 widths, minus the background strain times the window."""
    N = state.N
    strain = np.roll(state.U, -1) - state.U
    s_hat = np.fft.rfft(strain)
    q = 2 * np.pi * np.fft.rfftfreq(N)
    s_hat[q > sol.k / 2] = 0
    strain = np.fft.irfft(s_hat, N)
    d = _ring_distance(np.arange(N) + 0.5, centre, N)
    win = np.abs(d) < 8 * width
    bg = np.median(strain[~win]) if (~win).any() else 0.0
    return float(np.sum(strain[win] - bg))


def measure_state(state: LatticeState, sol: Soliton, t: float, centre_guess: float) -> Snapshot:
    """Fit the soliton in one state (intensity |2E|^2 = theta^2 + (theta_dot/omega_s)^2)."""
    amp2 = state.theta**2 + (state.theta_dot / sol.frequency) ** 2
    c, a, w, depth, rad, misfit = _fit_profile(amp2, sol.kind, centre_guess, sol.width,
                                               state.N)
    # unwrap: the ring distance keeps the centre continuous across the seam
    kink = _kink(state, sol, c, w) if sol.case == "coupled" else 0.0
    return Snapshot(t=t, centre=c, amplitude=a, width=w, depth=depth, kink_height=kink,
                    radiation=rad, shape_misfit=misfit)


@dataclass(frozen=True)
class SolitonRun:
    """A soliton launched in the lattice and tracked.

    Attributes
    ----------
    predicted : Soliton
        At the ring's k (``predicted.k``; ``k_asked`` is what was asked).
    N, t_end, dt, method : the run.
    snapshots : tuple of Snapshot, one per recorded time (the first at t = 0).
    frequency : float
        Measured carrier frequency (1/T), from the phase of the demodulated field.
    theta, U : ndarray, shape (n_snapshots, N)
        The recorded fields (U None in case I), for the figures.
    """

    predicted: Soliton
    k_asked: float
    N: int
    t_end: float
    dt: float
    method: str
    snapshots: tuple
    frequency: float
    theta: np.ndarray = field(repr=False)
    U: np.ndarray | None = field(repr=False)

    @property
    def t(self) -> np.ndarray:
        return np.array([s.t for s in self.snapshots])

    def series(self, name: str) -> np.ndarray:
        return np.array([getattr(s, name) for s in self.snapshots])

    @property
    def velocity(self) -> float:
        """Least-squares slope of the unwrapped centre against time (sites per T)."""
        return float(np.polyfit(self.t, self.series("centre"), 1)[0])

    def measured(self) -> dict:
        """The measured counterparts of :meth:`Soliton.summary` (at the end of the run),
        plus the drifts (end / start - 1; velocity: second half of the run / first half
        - 1; radiation and shape misfit: end - start), the radiation and the shape misfit
        at the end (see :class:`Snapshot`) and the distance travelled in widths."""
        first, last = self.snapshots[0], self.snapshots[-1]
        rel = (lambda a, b: (b / a - 1) if a else float("nan"))
        t, c = self.t, self.series("centre")
        half = len(t) // 2
        v_early, v_late = ((float(np.polyfit(t[:half + 1], c[:half + 1], 1)[0]),
                            float(np.polyfit(t[half:], c[half:], 1)[0])) if len(t) >= 4
                           else (self.velocity, self.velocity))
        out = {"velocity": self.velocity, "width": last.width, "amplitude": last.amplitude,
               "frequency": self.frequency,
               "kink_height": last.kink_height if self.predicted.case == "coupled" else 0.0,
               "radiation": last.radiation, "shape_misfit": last.shape_misfit,
               "travelled_widths": abs(last.centre - first.centre) / self.predicted.width,
               "drift": {"velocity": rel(v_early, v_late),
                         "width": rel(first.width, last.width),
                         "amplitude": rel(first.amplitude, last.amplitude),
                         "kink_height": rel(first.kink_height, last.kink_height)
                         if self.predicted.case == "coupled" else 0.0,
                         "radiation": last.radiation - first.radiation,
                         "shape_misfit": last.shape_misfit - first.shape_misfit}}
        if self.predicted.kind == "dark":
            out["depth"] = last.depth
        return out

    def errors(self) -> dict:
        """measured / predicted - 1 of velocity, width, amplitude, frequency, kink height."""
        m, p = self.measured(), self.predicted.summary()
        return {key: (m[key] / p[key] - 1) if p[key] else float("nan") for key in p}


def default_ring(width: float) -> int:
    """A ring of at least 20 widths (and 256 sites): the tails (e^{-20}) never meet."""
    return int(max(256, 2 * math.ceil(10 * width)))


def simulate_soliton(material: Material, case: str, k: float, amplitude: float,
                     kind: str | None = None, *, theory: str = "semi-discrete NLS",
                     phi: float = 0.0, N: int | None = None, travel: float = 20.0,
                     t_end: float | None = None, snapshots: int = 21,
                     method: str = "srkn11b", dt: float = 0.25) -> SolitonRun:
    """Launch the predicted soliton in the lattice, integrate and track it.

    Parameters
    ----------
    material, case, k, amplitude, kind, theory, phi
        As :func:`soliton`; k is moved to the nearest :func:`ring_wavenumber`.
    N : int, optional
        Ring size; default :func:`default_ring` (20 widths).
    travel : float
        Run until the soliton has moved this many widths at the predicted velocity
        (ignored when ``t_end`` is given).
    snapshots : int
        Recorded states, t = 0 included.
    method, dt
        Integrator: the symplectic order-6 SRKN11b at dt = 0.25 by default (energy error
        ~1e-9 at these amplitudes; 11 force evaluations per step, the fastest per accuracy).

    Returns
    -------
    SolitonRun
    """
    sol0 = soliton(material, case, k, amplitude, kind, theory=theory, phi=phi)
    N = default_ring(sol0.width) if N is None else checks.integer("N", N, 16)
    kr = ring_wavenumber(k, N, sol0.kind, phi)
    with warnings.catch_warnings():  # said once, for the k asked
        warnings.simplefilter("ignore", SolitonWarning)
        sol = soliton(material, case, kr, amplitude, sol0.kind, theory=theory, phi=phi, N=N)
    snapshots = checks.integer("snapshots", snapshots, 2)
    if t_end is None:
        travel = checks.positive("travel", travel)
        t_end = travel * sol.width / max(abs(sol.velocity), 1e-12)
        if t_end > MAX_T_END:
            raise ValueError(f"the soliton moves at {sol.velocity:.3g} sites/T: {travel:g} "
                             f"widths take T = {t_end:.3g} (> {MAX_T_END:g}); give t_end")
    t_end = checks.positive("t_end", t_end)
    state = soliton_state(sol, N)
    times = np.linspace(0.0, t_end, snapshots)
    snaps, thetas, Us, phases = [], [], [], []
    centre = N / 2
    for i, ti in enumerate(times):
        if i:
            state = integrate(state, material, case, ti - times[i - 1], dt, method)
        # the fit keeps the centre continuous: guess = previous centre + predicted motion
        guess = centre + (sol.velocity * (ti - times[i - 1]) if i else 0.0)
        snap = measure_state(state, sol, float(ti), guess)
        centre = snap.centre
        snaps.append(snap)
        thetas.append(state.theta)
        Us.append(state.U if case == "coupled" else None)
        phases.append(_phasor(state, sol, snap.centre, float(ti)))
    frequency = _frequency(times, phases, sol)
    return SolitonRun(predicted=sol, k_asked=float(k), N=N, t_end=float(t_end), dt=dt,
                      method=method, snapshots=tuple(snaps), frequency=frequency,
                      theta=np.array(thetas), U=np.array(Us) if case == "coupled" else None)


def _phasor(state, sol, centre, t):
    """z_n = theta + i theta_dot / omega_s = 2 E e^{i(k n - omega_s t)}, demodulated by the
    predicted carrier e^{-i(k n - omega_s t)}: its phase moves at omega_s - omega_measured."""
    z = state.theta + 1j * state.theta_dot / sol.frequency
    n = np.arange(state.N)
    r = z * np.exp(-1j * (sol.k * n - sol.frequency * t))
    if sol.kind == "bright":
        return r
    # dark: keep the background, far from the dip (the phase jumps across it)
    far = np.abs(_ring_distance(n, centre, state.N)) > 6 * sol.width
    return np.where(far, r, 0)


def _frequency(times, phases, sol):
    """omega_s - d(phase)/dt of the demodulated field: for bright solitons the phase of its
    sum, for dark ones the site-by-site phase change of the background, each unwrapped
    between consecutive records (their spacing keeps the residual phase step < pi when
    the prediction is within pi / spacing)."""
    steps = []
    for a, b in zip(phases[:-1], phases[1:]):
        if sol.kind == "bright":
            steps.append(np.angle(np.sum(b) * np.conj(np.sum(a))))
        else:
            both = (a != 0) & (b != 0)
            steps.append(np.angle(np.sum(b[both] * np.conj(a[both]))))
    phase = np.concatenate([[0.0], np.cumsum(steps)])
    return float(sol.frequency - np.polyfit(times, phase, 1)[0])


def soliton_report(sol: Soliton, run: SolitonRun | None = None) -> dict:
    """The JSON of ``flexmm soliton``: kind, predicted, measured (None without a run),
    inputs."""
    m = sol.material
    out = {"kind": sol.kind, "predicted": sol.summary(),
           "measured": None if run is None else run.measured(),
           "inputs": {"alpha": m.alpha, "K_s": m.K_s, "K_theta": m.K_theta, "k": sol.k,
                      "amplitude": sol.amplitude, "case": sol.case, "theory": sol.theory,
                      "phi": sol.phi}}
    if run is not None:
        out["run"] = {"N": run.N, "k_ring": run.predicted.k, "t_end": run.t_end,
                      "dt": run.dt, "method": run.method}
        out["predicted_on_ring"] = run.predicted.summary()
    return out


__all__ = ["KINDS", "SOLITON_THEORIES", "MIN_WIDTH", "SolitonWarning", "Soliton", "soliton",
           "ring_wavenumber", "soliton_state", "Snapshot", "measure_state", "SolitonRun",
           "simulate_soliton", "default_ring", "soliton_report"]
