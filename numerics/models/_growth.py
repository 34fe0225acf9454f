"""The growth a model's run measures (``ModelRun.growth``, ``ModelRun.amplification``).

The deviation delta = u - U_exact(k n - omega t) from the exact wave is Fourier transformed
over the ring at each record. The sidebands are every ring mode but the carrier's harmonics
that stand above the noise (where the integrator's phase error and the noise's drift of the
centre of mass grow secularly; a harmonic far below the noise is kept, as on a small ring it
aliases onto a sideband); they are followed until their rms reaches a tenth of the amplitude
(``SATURATION``). The run is "unstable" when the sidebands grew ``GROWTH_FACTOR`` (20x) and
exponentially (the log-slope over the linear stage's second half, run over the whole stage,
bounds the factor: algebraic growth of a stable wave's near-carrier pairs does not pass),
with the rate the least-squares slope of the largest mode's log amplitude over its stretch
above ten times its start; otherwise "no growth within T", with the slowest rate the run
could have shown.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

if TYPE_CHECKING:
    from ._simulate import ModelRun

#: deviation (rms over sites, relative to the amplitude) where the linear growth ends
SATURATION = 0.1
#: growth of a mode that makes a run "unstable" (the verdict's threshold, as for maps)
GROWTH_FACTOR = 20.0


@dataclass(frozen=True)
class Growth:
    """The growth a run measured.

    Attributes
    ----------
    verdict : 'unstable', 'no growth within T' or 'undetermined'
        (undetermined: every mode of the ring is a harmonic of the carrier, nothing to
        measure; factor nan)
    rate : float
        The fastest mode's rate (1/time) where unstable, else nan.
    wavenumber : float
        That mode's ring wavenumber (rad/site) in (-pi, pi], else nan.
    factor : float
        The sidebands' growth: their largest rms in the linear stage over their start.
    detectable : float
        The slowest rate that would have grown GROWTH_FACTOR within the run's linear stage.
    t_linear : float
        Where the linear stage ended (the deviation reached SATURATION, or T).
    """

    verdict: str
    rate: float
    wavenumber: float
    factor: float
    detectable: float
    t_linear: float

    @property
    def label(self) -> str:
        if self.verdict == "unstable":
            return f"unstable (measured rate {self.rate:.4g})"
        if self.verdict == "undetermined":
            return ("undetermined (every mode of the ring is a harmonic of the carrier: a "
                    "growth cannot be told from the wave's own; a larger N)")
        return (f"no growth within T (a rate below {self.detectable:.2g} cannot show by "
                f"t = {self.t_linear:.4g})")


@dataclass(frozen=True)
class Amplification:
    """A run's amplification: ``amplification`` = max_t A(t) / A(0), at
    ``amplification_time``; ``observable`` = amplification >= GROWTH_FACTOR; ``peaked``:
    A(t) fell to half its maximum before the run's end (else the run's cap ended it)."""

    amplification: float
    amplification_time: float
    observable: bool
    peaked: bool
    A: np.ndarray

    def row(self) -> dict:
        return {"amplification": self.amplification,
                "amplification_time": self.amplification_time,
                "observable": self.observable, "peaked": self.peaked}


def _sideband_modes(N: int, m: int, H: int) -> np.ndarray:
    """Ring modes that are not harmonics of the carrier mode m: h m mod N, |h| <= H (the
    exact wave's harmonics), and the mean (h = 0)."""
    harm = {(h * m) % N for h in range(-H, H + 1)}
    return np.array([j not in harm for j in range(N)])


def _lower_keep(N: int, m: int, H: int) -> np.ndarray:
    """The modes 0 < j <= N/2 that are no harmonic of the carrier (|h| <= H): a subset of
    the modes ``measure_growth`` sums (it leaves out only the harmonics that drift)."""
    return _sideband_modes(N, m, H) & (np.arange(N) <= N // 2) & (np.arange(N) > 0)


def saturation_record(spectrum: np.ndarray, N: int, k: float, H: int,
                      amplitude: float) -> int | None:
    """The first record whose sidebands, every carrier harmonic (up to the H-th) left out,
    have an rms above ``SATURATION`` x ``amplitude``; None where none has.

    ``measure_growth`` sums these modes and perhaps some harmonics, so its linear stage has
    ended by this record: a run stopped here (``simulate_model(until_saturated=True)``, a
    map cell's run) measures the same growth, bit for bit, as the whole run."""
    m = int(round(k * N / (2 * math.pi)))
    keep = _lower_keep(N, m, H)
    spec = np.asarray(spectrum)
    rms = np.sqrt(2 * np.sum(spec[:, keep] ** 2, axis=1))
    over = np.nonzero(rms > SATURATION * amplitude)[0]
    return int(over[0]) if over.size else None


def sideband_amplitude(spectrum: np.ndarray, N: int, k: float, H: int) -> np.ndarray:
    """A(t): the largest |FFT| / N over the ring modes that are not carrier harmonics
    (up to the H-th)."""
    m = int(round(k * N / (2 * math.pi)))
    return np.max(np.asarray(spectrum)[..., _sideband_modes(N, m, H)], axis=-1)


def measure_amplification(run: ModelRun) -> Amplification:
    A = sideband_amplitude(run.spectrum, run.N, run.k, run.wave.harmonics)
    i = int(np.argmax(A))
    amp = float(A[i] / max(A[0], 1e-300))
    peaked = bool(np.any(A[i:] <= A[i] / 2)) if run.peaked is None else bool(run.peaked)
    return Amplification(amp, float(run.t[i]), amp >= GROWTH_FACTOR, peaked, A)


def measure_growth(run: ModelRun) -> Growth:
    N = run.N
    m = int(round(run.k * N / (2 * math.pi)))
    # the carrier's harmonics whose phase drift could show: the wave's phase error phi
    # (integrator, noise) makes harmonic h deviate by ~ h phi |c_h| (secular); phi is read
    # off the carrier's own mode. A harmonic whose drift stays below a tenth of the noise is
    # kept: on a small ring a high harmonic aliases onto a sideband (h k = k + q mod 2 pi;
    # measured: FPUT on 64 sites, the 5th harmonic on the fastest sideband)
    H = run.wave.harmonics
    size = np.max(np.abs(run.wave.coefficients), axis=0)[H:]  # |c_h|, h = 0..H
    others = np.array([j not in (0, m % N, (-m) % N) for j in range(N)])
    floor = float(np.median(run.spectrum[0, others]))
    # read up to the saturation (``saturation_record``): after it the carrier's own mode is
    # no phase drift, and a run stopped there reads the same records
    stop = saturation_record(run.spectrum, N, run.k, H, run.amplitude)
    last = len(run.t) if stop is None else stop + 1
    phase = float(np.max(run.spectrum[:last, m % N])) / max(size[1], 1e-300)
    harmonics = {0, m % N, (-m) % N} | {
        (s * h * m) % N for h in range(2, H + 1) for s in (1, -1)
        if h * phase * size[h] > 0.1 * floor}
    keep = np.array([j not in harmonics and 0 < j <= N // 2 for j in range(N)])
    if not keep.any():  # every mode of the ring is the carrier's (N = 9, k = 8 pi / 9: its
        # sidebands k +- 2 pi / 9 are -k and 3k): a growth cannot be told from the wave's
        # own drift, so none is claimed (a run that grew 1e8x once read "no growth")
        T = float(run.t[-1])
        return Growth("undetermined", math.nan, math.nan, math.nan,
                      math.log(GROWTH_FACTOR) / T if T > 0 else math.inf, T)
    # the sidebands' rms (the carrier's harmonics left out: a linear start slips in phase)
    sidebands = np.sqrt(2 * np.sum(run.spectrum[:, keep] ** 2, axis=1))
    sat = np.nonzero(sidebands > SATURATION * run.amplitude)[0]
    end = int(sat[0]) if sat.size else len(run.t) - 1
    end = max(end, 1)
    S = run.spectrum[:end + 1, keep]
    start = np.maximum(np.median(run.spectrum[:3, keep], axis=0), 1e-300)
    factor = np.max(S, axis=0) / start
    # the verdict reads the sidebands' rms: one mode's share of the noise can swing
    # between its stable eigenmodes (measured: 20x on stable FPUT and flexmm rings), their
    # sum cannot
    total = float(np.max(sidebands[:end + 1]) / max(np.median(sidebands[:3]), 1e-300))
    t_lin = float(run.t[end])
    # ... and an exponential one: the log-slope over the linear stage's second half, run
    # over the whole stage, bounds the factor. Algebraic growth near the carrier (the
    # near-degenerate Bogoliubov pairs of a stable wave exchange amplitude, measured 5x on
    # flexmm-rotation at k = 1, a = 0.1) has a slope of at most ln 2 / (T / 2) there: 4x
    half = run.t[:end + 1] >= t_lin / 2
    if half.sum() >= 3:
        slope = np.polyfit(run.t[:end + 1][half], np.log(np.maximum(
            sidebands[:end + 1][half], 1e-300)), 1)[0]
        total = min(total, float(math.exp(min(max(slope, 0.0) * t_lin, 700.0))))
    detectable = math.log(GROWTH_FACTOR) / t_lin if t_lin > 0 else math.inf
    if not factor.size or total < GROWTH_FACTOR:
        return Growth("no growth within T", math.nan, math.nan, total, detectable, t_lin)
    # the largest mode at the end of the linear stage is the fastest: products of growing
    # modes (rates 2 sigma, 3 sigma) rise late from below it, so their slopes are not read
    i = int(np.argmax(S[-1]))
    y = np.log(np.maximum(S[:, i], 1e-300))
    above = np.nonzero(y > math.log(10 * start[i]))[0]
    first = int(above[0]) if above.size else 0
    if S.shape[0] - first < 4:
        first = max(0, S.shape[0] - 4)
    rate = float(np.polyfit(run.t[first:end + 1], y[first:], 1)[0])
    j = np.nonzero(keep)[0][i]
    kap = 2 * math.pi * j / N
    return Growth("unstable", rate, float((kap + math.pi) % (2 * math.pi) - math.pi),
                  total, detectable, t_lin)
