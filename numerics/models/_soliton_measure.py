"""What a state of any model's lattice shows of its NLS soliton (``_soliton_run``): the
carrier field's analytic signal z = u + i u_dot / Omega band-passed at |q - k| < k/2
(2 E e^{i theta}: the mean at q = 0 and the second harmonic at 2k outside), |z|^2 fitted
by a^2 sech^2 (bright) or a^2 (1 - D sech^2) (dark) for centre, amplitude, width and D
(``numerics.lattice.fit_soliton_profile``, the paper chain's fit too); its
demodulated phase for the frequency; each acoustic field's strain low-passed at |q| < k/2
and summed over +-8 widths for its kink. As the paper chain's ``_soliton_measure``.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from ..lattice import RADIATION_WINDOW, fit_soliton_profile, kink_window, ring_distance

if TYPE_CHECKING:  # the prediction's type only
    from ._soliton_ring import RingSoliton


@dataclass(frozen=True)
class ModelSnapshot:
    """What one state shows of the soliton: fitted centre (unwrapped), amplitude (the
    carrier's first harmonic at the peak, or of the background), width, depth (dark),
    kink per field (0 where none), radiation and shape misfit as the paper chain's
    ``Snapshot``."""

    t: float
    centre: float
    amplitude: float
    width: float
    depth: float
    kink: np.ndarray
    radiation: float
    shape_misfit: float


def analytic_carrier(u, v, pred: RingSoliton) -> np.ndarray:
    """z = u + i v / Omega of the carrier field, band-passed at |q - k| < k/2:
    2 E e^{i theta}."""
    f = pred.nls.carrier.field
    N = u.shape[1]
    z = np.fft.fft(u[f] + 1j * v[f] / pred.frequency)
    q = 2 * np.pi * np.fft.fftfreq(N)
    near = np.abs((q - pred.k + np.pi) % (2 * np.pi) - np.pi) < pred.k / 2
    return np.fft.ifft(np.where(near, z, 0))


def _kinks(u, pred: RingSoliton, centre, width):
    """Each kink field's step: its strain low-passed at |q| < k/2 (the harmonics out),
    summed over +-8 widths (``kink_window``: less on a short ring), minus the background strain over the window."""
    d, N = u.shape
    out = np.zeros(d)
    q = 2 * np.pi * np.fft.rfftfreq(N)
    dist = ring_distance(np.arange(N) + 0.5, centre, N)
    win = np.abs(dist) < kink_window(width, N)
    for i in pred.kink_fields():
        s_hat = np.fft.rfft(np.roll(u[i], -1) - u[i])
        s_hat[q > pred.k / 2] = 0
        strain = np.fft.irfft(s_hat, N)
        bg = np.median(strain[~win]) if (~win).any() else 0.0
        out[i] = float(np.sum(strain[win] - bg))
    return out


def measure_snapshot(u, v, pred: RingSoliton, t: float,
                     centre_guess: float) -> ModelSnapshot:
    """Fit the soliton in the state (u, v) (each shape (d, N))."""
    z = analytic_carrier(u, v, pred)
    fit = fit_soliton_profile(np.abs(z) ** 2, pred.kind, centre_guess, pred.width)
    return ModelSnapshot(t=float(t), centre=fit.centre, amplitude=fit.amplitude,
                         width=fit.width, depth=fit.dip,
                         kink=_kinks(u, pred, fit.centre, fit.width),
                         radiation=fit.radiation, shape_misfit=fit.shape_misfit)


def phasor(u, v, pred, centre, t):
    """z demodulated by the predicted carrier e^{-i(k n - Omega t)}; dark: the background
    far from the dip only (the phase jumps across it)."""
    N = u.shape[1]
    n = np.arange(N)
    r = analytic_carrier(u, v, pred) * np.exp(-1j * (pred.k * n - pred.frequency * t))
    if pred.kind == "bright":
        return r
    far = np.abs(ring_distance(n, centre, N)) > 6 * pred.width
    return np.where(far, r, 0)


def frequency_of(times, phases, pred):
    """Omega - d(phase)/dt of the demodulated field (unwrapped between records): for a
    bright soliton the phase of its sum (its mode at k), for a dark one the site-by-site
    phase change of the background."""
    if pred.kind == "bright":
        steps = [np.angle(np.sum(b) * np.conj(np.sum(a)))
                 for a, b in zip(phases[:-1], phases[1:])]
    else:
        steps = [np.angle(np.sum(b * np.conj(a))) for a, b in zip(phases[:-1], phases[1:])]
    phase = np.concatenate([[0.0], np.cumsum(steps)])
    return float(pred.frequency - np.polyfit(times, phase, 1)[0])


__all__ = ["ModelSnapshot", "analytic_carrier", "measure_snapshot", "phasor", "frequency_of",
           "RADIATION_WINDOW"]
