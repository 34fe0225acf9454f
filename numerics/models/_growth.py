"""The growth a model's run measures (``ModelRun.growth``, ``ModelRun.amplification``).

The deviation delta = u - U_exact(k n - omega t) from the exact wave is Fourier transformed
over the ring at each record. The sidebands are every ring mode but the carrier's harmonics
that stand above the noise (where the integrator's phase error and the noise's drift of the
centre of mass grow secularly; a harmonic far below the noise is kept, as on a small ring it
aliases onto a sideband); they are followed until their rms reaches a tenth of the amplitude
(``SATURATION``). The run is "unstable" when the sidebands grew ``GROWTH_FACTOR`` (20x) and
exponentially (the log-slope over the linear stage's second half, run over the whole stage,
bounds the factor: algebraic growth of a stable wave's near-carrier pairs does not pass),
with the rate the fastest Floquet exponent the linear stage shows (``settled_rate``: every
mode's log-slope over its settled stretch, read on the best measured copy of the fastest
mode; probe 95); otherwise "no growth within T", with the slowest rate the run could have
shown.
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
#: a mode's rate is read from where it passed this many times its start (the growing
#: Floquet mode then outweighs the neutral ones 10:1) ...
SETTLED = 10.0
#: ... over a stretch where it grew at least this much further (3 e-foldings)
SETTLED_SPAN = 20.0
#: ... and while it stands this far above the square of the largest mode (both over the
#: amplitude): the products of growing modes are below a tenth of it there
PRODUCTS = 10.0


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


def harmonic_drift(wave, N: int, k: float, exact_start: bool = True) -> np.ndarray:
    """Per ring mode j (shape (N,)): the most the carrier's own harmonics can put into the
    deviation from the wave there, 2 sum |c_h| over the harmonics h = 2..H (either sign)
    with h m = j (mod N) (a run launched on the exact wave that slips in phase or decays
    slowly, as a damped one does, follows the wave's family: it at most removes the
    content |c_h| and puts |c_h| elsewhere in phase); 0 on the other modes, inf on the mean
    and the carrier's own (never sideband growth). ``exact_start`` False (a linear start:
    not on the family, its combination tones reached 1000 |c_7| on the harmonic's mode,
    a stable KG ring of 32): inf on every harmonic's mode, |h| <= H."""
    m = int(round(k * N / (2 * math.pi)))
    H = wave.harmonics
    c = np.asarray(wave.coefficients)
    size = np.sqrt(np.sum(np.abs(c) ** 2, axis=0))  # (2H + 1,), the fields' norm
    drift = np.zeros(N)
    for h in range(2, H + 1):
        for s in (1, -1):
            drift[(s * h * m) % N] += 2 * size[H + s * h] if exact_start else np.inf
    drift[[0, m % N, (-m) % N]] = np.inf
    return drift


#: a harmonic's mode counts by what it holds beyond this many times its drift bound: a
#: carrier that decays faster than adiabatically leaves the family (an overdamped
#: Klein-Gordon carrier, gamma 3 at k 1 on 32 sites: 3.4x the bound on the 7th harmonic's
#: mode, read as a 395x amplification where the bound alone was subtracted)
OVER_DRIFT = 10.0


def amplitude_series(spectrum: np.ndarray, drift: np.ndarray) -> np.ndarray:
    """A(t): the largest of each record's modes (``spectrum`` (records, N), or one record
    (N,)) less ``OVER_DRIFT`` times its ``harmonic_drift``, where positive: the modes that
    are no carrier harmonic as they are, a harmonic's mode by what it holds beyond what
    the wave's own content can put there (continuous in t), the mean and the carrier's own
    never. On a small ring a high harmonic aliases onto the fastest
    sidebands (kg-cubic on 64 sites, k = 2 pi 23 / 64: h = -13 on mode 21, which grew e^14
    in a damped run while the modes no harmonic reached 2e3): leaving every harmonic's mode
    out read 1e-3 of the exact amplification."""
    S = np.asarray(spectrum)
    with np.errstate(invalid="ignore"):
        beyond = np.where(np.isfinite(drift), S - OVER_DRIFT * drift, 0.0)
    return np.max(np.maximum(beyond, 0.0), axis=-1)


def measure_amplification(run: ModelRun) -> Amplification:
    A = amplitude_series(run.spectrum, harmonic_drift(run.wave, run.N, run.k,
                                                      run.start == "exact"))
    i = int(np.argmax(A))
    amp = float(A[i] / max(A[0], 1e-300))
    peaked = bool(np.any(A[i:] <= A[i] / 2)) if run.peaked is None else bool(run.peaked)
    return Amplification(amp, float(run.t[i]), amp >= GROWTH_FACTOR, peaked, A)


def _fit(t: np.ndarray, y: np.ndarray, level: float) -> float:
    """Least-squares slope of the log amplitude ``y`` over its stretch above ``level``
    (the last 4 records where it is shorter)."""
    above = np.nonzero(y > level)[0]
    first = int(above[0]) if above.size else 0
    first = min(first, max(0, len(y) - 4))
    return float(np.polyfit(t[first:], y[first:], 1)[0])


def settled_rate(t: np.ndarray, S: np.ndarray, start: np.ndarray, amplitude: float,
                 modes: np.ndarray | None = None, m: int = 0,
                 N: int = 0) -> tuple[float, int]:
    """The fastest Floquet exponent a run's linear stage shows, and the mode (column of
    ``S``) that shows it.

    In the linear stage each ring mode j grows at the exact rate of its own offset once
    the fastest Floquet mode there outweighs the neutral ones: its log amplitude's
    least-squares slope over that stretch is that rate. The largest mode at the stage's
    end need not be the fastest (probe 95: fput alpha 0.5, beta 1, k 1.52, a 0.2 on 128
    sites: the mode at 0.98, rate 0.0261, started higher and stayed ahead of the fastest,
    0.93 at 0.0289, through the whole stage: the run read 10% low at any T). So every
    mode is read over its own stretch: from the last record where it was below
    ``SETTLED`` x the neutral modes' level (their lower quartile at that record: the
    noise's launch transient moves it), while it stays above ``PRODUCTS`` x r_max^2 (r: a
    mode over the amplitude; the products of two growing modes, ~ r_a r_b, grow at
    s_a + s_b and are below a tenth of it there, and a product mode itself is never
    above); it counts when it grew ``SETTLED_SPAN`` x over that stretch (3 e-foldings: a
    shorter stretch's slope is the beat of its neutral components). A Floquet mode shows
    on several ring modes (its copies +-j + l m, |l| <= 2), each read on the copy that
    grew most, the best measured; the run's rate is the fastest such reading. Where no
    mode counts (a short stage) the largest mode
    at the stage's end is read over its stretch above 10x its start (the rule before
    probe 95).

    Parameters
    ----------
    t : ndarray, shape (nt,)
    S : ndarray, shape (nt, modes)
        |mode| over the linear stage.
    start : ndarray, shape (modes,)
        Each mode's start level (the fallback's reference).
    amplitude : float
        The wave's amplitude (the products' scale).
    modes, m, N : optional
        The ring mode j of each column, the carrier's mode and the ring: the fastest
        mode's copies +-j + l m (|l| <= 2) are one Floquet mode, read on the one that grew
        most (None: the fastest column itself).

    Returns
    -------
    (rate, column)
    """
    y = np.log(np.maximum(S, 1e-300))
    r = S / amplitude
    # the products of two growing modes, ~ r_a r_b <= r_max^2 (r: a mode over the
    # amplitude), land on other modes and grow at s_a + s_b: a mode is read only while it
    # is above PRODUCTS x r_max^2, where they are a tenth of it at most (and a mode that
    # is a product is never above)
    # a run that blew up ends on a record holding inf: no mode is read there, and the
    # floor below takes it as the largest float (inf - inf in the quantile's lerp is nan)
    finite = np.isfinite(S)
    clean = finite & (r >= PRODUCTS * np.max(r, axis=1, keepdims=True) ** 2)
    # the neutral modes' level at each record (their lower quartile: robust while fewer
    # than 3/4 of the modes grow); it moves: the noise's launch transient raised every
    # mode ~30x within the first ~100 time units (probe 95, a Hertz-like bond at k 1.52,
    # a 0.15), so a mode's own start is no reference
    floor = np.quantile(np.where(finite, S, np.finfo(float).max), 0.25, axis=1)
    best, col = -math.inf, -1
    rates = {}
    for i in range(S.shape[1]):
        out = np.nonzero(~clean[:, i])[0]
        stop = int(out[0]) if out.size else S.shape[0]
        low = np.nonzero(S[:stop, i] <= SETTLED * floor[:stop])[0]
        first = int(low[-1]) + 1 if low.size else 0
        if stop - first < 4 or S[stop - 1, i] < SETTLED_SPAN * S[first, i]:
            continue
        rates[i] = (float(np.polyfit(t[first:stop], y[first:stop, i], 1)[0]),
                    float(y[stop - 1, i] - y[first, i]))
        if rates[i][0] > best:
            best, col = rates[i][0], i
    if col >= 0:
        if modes is None:
            return best, col
        # a Floquet mode shows on its pair and first copies (j -> +-j + l m, |l| <= 2:
        # kappa, 2 k - kappa, kappa +- k; one exponent), and is read on the one that grew
        # most over its stretch, the best measured: a weak copy's short stretch read 13%
        # above the exact rate (fput at k = pi / 2 on 64 sites, probe 95), its family's
        # best 1%. Farther copies, weighted by the wave's higher harmonics, would take in
        # other offsets' modes on a ring.
        index = {int(modes[i]): i for i in rates}

        def reading(i):
            j = int(modes[i])
            kin = [index[f] for f in {min(f, N - f) for f in (
                (s * j + h * m) % N for s in (1, -1) for h in range(-2, 3))} if f in index]
            top = max(kin, key=lambda c: rates[c][1])
            return rates[top][0], top

        return max((reading(i) for i in rates), key=lambda x: x[0])
    # the largest mode at the end of the linear stage: products of growing modes (rates
    # 2 sigma, 3 sigma) rise late from below it, so their slopes are not read
    i = int(np.argmax(S[-1]))
    return _fit(t, y[:, i], math.log(SETTLED * start[i])), i


#: the rules ``measure_growth`` reads a rate by: "settled" (probe 95, the default) and
#: "largest" (the rule before it, kept for bench/probe_runs95's comparison)
RATE_RULES = ("settled", "largest")


def read_modes(run: ModelRun) -> np.ndarray:
    """The ring modes a run's growth reads (boolean, shape (N,)): 0 < j <= N/2, the
    carrier and the harmonics whose phase drift could show left out."""
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
    return np.array([j not in harmonics and 0 < j <= N // 2 for j in range(N)])


def measure_growth(run: ModelRun, rule: str = "settled") -> Growth:
    """What ``run`` shows (the module's rule); ``rule``: how its rate is read, one of
    ``RATE_RULES`` ("settled", the default; "largest", the rule before probe 95)."""
    N = run.N
    m = int(round(run.k * N / (2 * math.pi)))
    keep = read_modes(run)
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
    if rule not in RATE_RULES:
        raise ValueError(f"rule must be one of {', '.join(RATE_RULES)}, got {rule!r}")
    if rule == "settled":
        rate, i = settled_rate(run.t[:end + 1], S, start, run.amplitude,
                               np.nonzero(keep)[0], m % N, N)
    else:
        i = int(np.argmax(S[-1]))
        rate = _fit(run.t[:end + 1], np.log(np.maximum(S[:, i], 1e-300)),
                    math.log(SETTLED * start[i]))
    j = np.nonzero(keep)[0][i]
    kap = 2 * math.pi * j / N
    return Growth("unstable", rate, float((kap + math.pi) % (2 * math.pi) - math.pi),
                  total, detectable, t_lin)
