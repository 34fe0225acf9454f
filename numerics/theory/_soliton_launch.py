"""A predicted soliton in the lattice: its state on a ring, and a run that tracks it.

Case II: U carries the mean strain mu (|E|^2 - background) under the envelope (its integral
is the kink) minus its ring average (a periodic U has no net strain: the compensating
uniform strain is kink / N), and the second harmonic u2 = c E^2 e^{2 i sigma} + c.c.;
U_dot = -v U' for the kink. Conventions as in ``_soliton``.
"""

from __future__ import annotations

import math
import warnings

import numpy as np

from generated import soliton as closed

from ..lattice import LatticeState, Material, checks, integrate
from ._soliton import Soliton, SolitonWarning, ring_wavenumber, soliton
from ._soliton_measure import SolitonRun, carrier_phasor, measure_state, measured_frequency

#: longest run simulate_soliton picks by itself (about 2 min for a ring of 1000 sites)
MAX_T_END = 5e5


class RunTooLong(ValueError):
    """The asked travel takes longer than MAX_T_END; :meth:`advice` says it with the
    caller's names of the parameters that shorten it."""

    def __init__(self, velocity, travel, t_end, amplitude):
        self.velocity, self.travel, self.t_end, self.amplitude = velocity, travel, t_end, \
            amplitude
        super().__init__(self.advice("travel", "amplitude", "t_end"))

    def advice(self, travel: str, amplitude: str, t_end: str | None = None) -> str:
        """The refusal, its remedies named ``travel``, ``amplitude`` (and ``t_end``)."""
        shorter = MAX_T_END / self.t_end  # T is travel x width / |v|, and width ~ 1/amplitude
        return (f"the soliton moves at {self.velocity:.3g} sites/T: {self.travel:g} widths "
                f"take T = {self.t_end:.3g} (> {MAX_T_END:g}); give {travel} <= "
                f"{self.travel * shorter:.3g}, or {amplitude} >= "
                f"{self.amplitude / shorter:.3g} (its width shrinks as 1 / amplitude)"
                + (f", or {t_end}" if t_end else ""))


def shortest_ring(width_at, N: int, errors) -> int | None:
    """A ring (from ``N`` up, the shortest where the width varies smoothly with k) that
    holds 12 widths of the soliton at that ring's own k (``width_at(ring)``): k moves as
    the ring changes, and the width with it (12 widths at a 16-site ring's k advised 4409
    sites for FPUT at k = 1, whose k there needs 5109). A ring whose k has no such soliton
    (``errors`` raised) is stepped over; None where no ring up to 2^20 sites holds one."""
    ring = N
    for _ in range(80):  # each step lengthens the ring; k moves by < pi / ring
        try:
            need = math.ceil(12 * width_at(ring))
        except errors:  # no such soliton at this ring's k: a longer ring, nearer k
            need = max(ring + 1, math.ceil(1.1 * ring))
        else:
            if need <= ring:
                return ring
        ring = max(need, ring + 1)
        if ring > 2**20:
            break
    return None


def ring_too_short(N: int, width: float, k: float, fits: int | None) -> str:
    """The refusal of a ring of N sites for a soliton ``width`` sites wide at the ring's
    ``k``, with the shortest ring ``fits`` that holds one (:func:`shortest_ring`)."""
    return (f"N = {N} is too short for a soliton {width:.3g} sites wide at the ring's k = "
            f"{k:.6g} (12 widths = {math.ceil(12 * width)} sites)"
            + (f"; k moves with N: N = {fits} holds 12 widths at its own k" if fits else ""))


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

    def at(ring: int, kn: float) -> Soliton:
        with warnings.catch_warnings():  # said once, for the k asked
            warnings.simplefilter("ignore", SolitonWarning)
            return soliton(material, case, kn, amplitude, sol0.kind, theory=theory, phi=phi,
                           N=ring)

    def width_at(ring: int) -> float:
        return at(ring, ring_wavenumber(k, ring, sol0.kind, phi)).width

    try:
        sol = at(N, kr)
    except ValueError as exc:  # the ring's k has the other kind: g changes sign between
        if "kind=" not in str(exc):
            raise
        fits = shortest_ring(width_at, N + 1, ValueError)
        raise ValueError(f"N = {N} moves k to {kr:.6g}, where the {theory} has no "
                         f"{sol0.kind} soliton (g changes sign between it and k = {k:.6g}); "
                         + (f"N = {fits} holds one of 12 widths at its own k" if fits else
                            "a longer ring keeps k nearer")) from None
    if 12 * sol.width > N:  # before the run's set-up: with the ring that holds one
        raise ValueError(ring_too_short(N, sol.width, kr, shortest_ring(width_at, N,
                                                                         ValueError)))
    snapshots = checks.integer("snapshots", snapshots, 2)
    if t_end is None:
        travel = checks.positive("travel", travel)
        t_end = travel * sol.width / max(abs(sol.velocity), 1e-12)
        if t_end > MAX_T_END:
            raise RunTooLong(sol.velocity, travel, t_end, amplitude)
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
        phases.append(carrier_phasor(state, sol, snap.centre, float(ti)))
    frequency = measured_frequency(times, phases, sol)
    return SolitonRun(predicted=sol, k_asked=float(k), N=N, t_end=float(t_end), dt=dt,
                      method=method, snapshots=tuple(snaps), frequency=frequency,
                      theta=np.array(thetas), U=np.array(Us) if case == "coupled" else None)


__all__ = ["soliton_state", "simulate_soliton", "default_ring", "MAX_T_END", "RunTooLong",
           "shortest_ring", "ring_too_short"]
