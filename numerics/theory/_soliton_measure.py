"""What a lattice state and a run show of a soliton: the fitted profile (centre, amplitude,
width, depth, radiation), the kink of U, the carrier frequency, and the report that sets
them beside the prediction. Conventions as in ``_soliton``.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from ..lattice import (
    RADIATION_WINDOW,
    LatticeState,
    fit_soliton_profile,
    kink_window,
    ring_distance,
)
from ._soliton import Soliton


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


def _kink(state, sol, centre, width):
    """U across the soliton: the low-passed strain (|q| < k/2 drops the second harmonic)
    summed over +-8 widths (``kink_window``: less on a short ring), minus the background
    strain times the window."""
    N = state.N
    strain = np.roll(state.U, -1) - state.U
    s_hat = np.fft.rfft(strain)
    q = 2 * np.pi * np.fft.rfftfreq(N)
    s_hat[q > sol.k / 2] = 0
    strain = np.fft.irfft(s_hat, N)
    d = ring_distance(np.arange(N) + 0.5, centre, N)
    win = np.abs(d) < kink_window(width, N)
    bg = np.median(strain[~win]) if (~win).any() else 0.0
    return float(np.sum(strain[win] - bg))


def measure_state(state: LatticeState, sol: Soliton, t: float, centre_guess: float) -> Snapshot:
    """Fit the soliton in one state (intensity |2E|^2 = theta^2 + (theta_dot/omega_s)^2)."""
    amp2 = state.theta**2 + (state.theta_dot / sol.frequency) ** 2
    fit = fit_soliton_profile(amp2, sol.kind, centre_guess, sol.width)
    # unwrap: the ring distance keeps the centre continuous across the seam
    kink = _kink(state, sol, fit.centre, fit.width) if sol.case == "coupled" else 0.0
    return Snapshot(t=t, centre=fit.centre, amplitude=fit.amplitude, width=fit.width,
                    depth=fit.depth, kink_height=kink, radiation=fit.radiation,
                    shape_misfit=fit.shape_misfit)


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


def carrier_phasor(state, sol, centre, t):
    """z_n = theta + i theta_dot / omega_s = 2 E e^{i(k n - omega_s t)}, demodulated by the
    predicted carrier e^{-i(k n - omega_s t)}: its phase moves at omega_s - omega_measured."""
    z = state.theta + 1j * state.theta_dot / sol.frequency
    n = np.arange(state.N)
    r = z * np.exp(-1j * (sol.k * n - sol.frequency * t))
    if sol.kind == "bright":
        return r
    # dark: keep the background, far from the dip (the phase jumps across it)
    far = np.abs(ring_distance(n, centre, state.N)) > 6 * sol.width
    return np.where(far, r, 0)


def measured_frequency(times, phases, sol):
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


__all__ = ["Snapshot", "measure_state", "SolitonRun", "soliton_report", "RADIATION_WINDOW"]
