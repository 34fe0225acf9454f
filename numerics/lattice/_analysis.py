"""Spectral diagnostics of lattice runs: stability verdicts, sideband growth rates, harmonics.

Every verdict here comes from the simulated fields alone, never from the theory.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

from ._bound import bound_of_records  # the GPU kernel compiles the same function

# the host's copy compiled too: in Python its 2 x 201-record loops took ~100 us a call, and
# the GPU path reads every chain's bound on the host (4096 chains: 0.8 s of a 2.6 s launch
# on an H200, bench.gpu's kernel row 21.5 -> 33.7 ps per site-evaluation, probe 96)
_bound_host = njit(cache=True, nogil=True)(bound_of_records)

#: A run is "unstable" when the largest non-carrier component of the theta spectrum,
#: relative to the carrier, grows by more than this factor over the run. Measured at the
#: paper's four points (N = 500, T = 5000): stable runs grow by 5-7x (bounded four-wave
#: mixing of the noise), unstable ones by 660-4000x.
GROWTH_THRESHOLD = 20.0


def spectrum(fields: np.ndarray) -> np.ndarray:
    """|rfft| * 2/N along the last axis: a plane wave of amplitude a peaks at a."""
    fields = np.asarray(fields, dtype=float)
    return np.abs(np.fft.rfft(fields, axis=-1)) * (2.0 / fields.shape[-1])


def mode(fields: np.ndarray, j: int) -> np.ndarray:
    """Complex amplitude of wavenumber bin j per record, normalised 2/N (one DFT bin).

    a cos(2 pi j n / N - phi) gives a e^{i phi}. Shape (nt,) for fields (nt, N).
    """
    fields = np.asarray(fields, dtype=float)
    N = fields.shape[-1]
    return fields @ np.exp(-2j * np.pi * (j % N) * np.arange(N) / N) * (2.0 / N)


def harmonic_bins(m: int, N: int, hmax: int = 9) -> list[int]:
    """rfft bins of the odd harmonics h*k (h = 1, 3, .., hmax) of the carrier bin m.

    Cubic nonlinearity drives odd harmonics of the carrier without any instability;
    they are excluded from the sideband measure. Aliasing folds them into [0, N/2].
    """
    out = set()
    for h in range(1, hmax + 1, 2):
        j = (h * m) % N
        out.add(min(j, N - j))
    return sorted(out)


def non_carrier_bins(m: int, N: int, field: str = "theta") -> np.ndarray:
    """Boolean mask over the rfft bins [0, N/2]: True where a component counts as growth.

    Excluded: the mean (bin 0) and, for theta, the carrier and its odd harmonics (driven by
    the cubic nonlinearity without any instability); for U also the even harmonics 2k, 4k,
    6k, 8k (forced by the carrier through the coupling, eq. `u2`). The one definition the
    simulated verdicts, the measured gains and the maps use.
    """
    if field not in ("theta", "U"):
        raise ValueError(f"field must be 'theta' or 'U', got {field!r}")
    mask = np.ones(N // 2 + 1, dtype=bool)
    mask[harmonic_bins(m, N)] = False
    if field == "U":
        for h in range(2, 10, 2):
            j = (h * m) % N
            mask[min(j, N - j)] = False
    mask[0] = False
    return mask


#: U's growth is measured from its level at this fraction of the run (U starts at rest in
#: the paper's initial condition, so its level at T = 0 is no reference)
U_REFERENCE = 0.05


#: U's reference record must lie this many carrier periods into the run: before it, U is
#: still building up from rest and its "growth" is that build-up. Measured (coupled, alpha
#: 2.5, K_s 0.01851, delta 0.003, k = 2 pi 64/500, N = 500; exact theory: < 1.1x within
#: T <= 10): U's reading gives 20.7x at T = 1e-7 and 20.3x at T = 1 (reference well inside
#: the first period: false MI), 11.9x at 0.6 periods, 5.3x at 1.2, 3.7x at 2.5, 1.9x at 5;
#: from one period on it stays below the 20x threshold by a factor of about 3
U_SETTLE_PERIODS = 1.0


def shortest_run(material, case: str, k) -> float:
    """The shortest t_end whose growth reading can tell MI (0 in case rotation, where U
    is not read): U's reference record, U_REFERENCE t_end, at least U_SETTLE_PERIODS
    periods 2 pi / omega of the slowest carrier among ``k`` (rotational branch, eq.
    `discrete2`) into the run. A shorter run reads U's build-up from rest as growth."""
    from ._model import check_case, discrete_omega_rotation

    if check_case(case) == "rotation":
        return 0.0
    omega = float(np.min(discrete_omega_rotation(np.atleast_1d(np.asarray(k, float)),
                                                 material)))
    if not (omega > 0 and math.isfinite(omega)):  # under- or overflowed
        return math.inf
    return U_SETTLE_PERIODS * 2 * np.pi / omega / U_REFERENCE


def shortest_run_error(name: str, t_end: float, cells, case: str) -> str | None:
    """The one-line refusal of a ``t_end`` too short to measure growth at any of ``cells``
    ((material, k values) pairs), naming ``name``; None when it is long enough."""
    with np.errstate(all="ignore"):
        need = max((shortest_run(mat, case, k) for mat, k in cells), default=0.0)
    if not math.isfinite(need):  # omega under- or overflowed: no period to wait for
        return (f"{name}: no run length can measure growth here: the carrier's frequency is "
                f"not a positive float64 number for this material (an underflow or overflow,"
                " not a resonance); rescale the material")
    if t_end >= need:
        return None
    return (f"{name} = {t_end:g} is too short to measure growth: U starts at rest and its "
            f"growth counts from {U_REFERENCE:g} t_end, which must lie a carrier period in "
            f"(U is still building up before that, and would read as MI); give at least "
            f"{math.ceil(need):g}")


#: the linear stage of a paper chain's run ends where its largest non-carrier component
#: reaches this share of the carrier (the models' ``SATURATION``: nonlinear beyond)
STAGE_END = 0.1


def exponential_bound(t: np.ndarray, top: np.ndarray) -> float:
    """The growth factor an exponential growth of ``top`` (a run's largest component over
    the carrier, per record from its reference record ``t[0]``) can claim: exp(s L),
    s the least-squares log-slope over the second half of the linear stage (up to the
    first record above ``STAGE_END``, else the last), L the stage's length; 1 where s <= 0.

    An exponential growth keeps its rate to the stage's end, so s L is at least its
    e-foldings; an algebraic one, t^p, has s L = p ln 4 at most there (``4^p``): near
    delta = 0 of the paper chain (alpha 2.2, K_s 0.02, delta -1e-5, k = 2 pi 41/256,
    rotation) the exact lattice is stable and a run of T = 40000 grew 35x, nearly
    linearly in t (a near-degenerate pair's secular exchange, probe 95); this reads 1.7x.
    The model runs' rule (``numerics.models._growth``), for the paper chain; a point's run,
    a map cell's on the CPU and on the GPU (``_bound.bound_of_records``, one source)."""
    t = np.ascontiguousarray(t, float)
    top = np.ascontiguousarray(top, float)
    if t.shape != top.shape or t.ndim != 1:
        raise ValueError(f"t and top must be 1-d of one length, got {t.shape} and {top.shape}")
    return float(_bound_host(t, top, 0, t.size, STAGE_END))


def spectrum_growth(t, ratios: dict, bins: dict, N: int, t_end: float | None = None,
                    exponential: bool = False):
    """The simulated verdicts' reading of a run: the largest growth factor of the largest
    non-carrier, non-harmonic component relative to the carrier, and where it sits.

    Parameters
    ----------
    t : ndarray, shape (nt,)
        Record times.
    ratios : dict field -> ndarray, shape (draws, nt, nbins)
        Per field ("theta", "U"): the components on ``bins[field]`` (rfft bins, the mask
        :func:`non_carrier_bins`) over the carrier's amplitude, per record.
    bins : dict field -> ndarray of int, shape (nbins,)
    t_end : float, optional
        The run's planned length (default: the last record's time): U's reference record
        sits at U_REFERENCE t_end, also in a run stopped early.
    exponential : bool
        Count exponential growth only: each field's factor is at most
        :func:`exponential_bound` of its records (algebraic growth, a secular exchange of
        a stable wave's near-degenerate modes, does not pass the threshold: a point's and a
        map cell's run verdict, probe 96). False (default): the factor as read, max over
        records (the stored ``growth``).

    Returns
    -------
    growth : ndarray, shape (draws,)
        max over records of the largest ratio, over its value at the reference record
        (theta: T = 0; U: U_REFERENCE t_end), the larger of the fields (``exponential``:
        each at most its exponential bound).
    field : ndarray of str, shape (draws,)
    q : ndarray, shape (draws,)
        Wavenumber (rad per site) of the largest component at the record of the peak
        (NaN where nothing was measured).
    """
    if not ratios:  # every ring mode is a harmonic of the carrier (a small or odd ring)
        raise ValueError(_no_sideband(N))
    draws = next(iter(ratios.values())).shape[0]
    growth = np.zeros(draws)
    field = np.full(draws, "theta", dtype=object)
    q = np.full(draws, np.nan)
    for name, r in ratios.items():
        i0 = 0 if name == "theta" else int(np.searchsorted(
            t, U_REFERENCE * (t[-1] if t_end is None else t_end)))
        if i0 >= len(t) - 1 or r.shape[2] == 0:  # no record after the reference, no bin
            continue
        top = r[:, i0:].max(axis=2)  # (draws, nt)
        ref = top[:, 0]
        with np.errstate(divide="ignore", invalid="ignore"):
            g = np.where(ref > 0, top.max(axis=1) / np.where(ref > 0, ref, 1.0), 0.0)
        if exponential:
            g = np.minimum(g, [exponential_bound(t[i0:], row) for row in top])
        better = g > growth
        i = i0 + np.argmax(top, axis=1)
        j = np.asarray(bins[name])[np.argmax(r[np.arange(draws), i], axis=1)]
        growth = np.where(better, g, growth)
        field = np.where(better, name, field)
        q = np.where(better, 2 * np.pi * j / N, q)
    return growth, field.astype(str), q


def grows_beyond_threshold(peak_gain, t_end: float):
    """A theory's verdict on the simulation's question: does a mode growing at
    ``peak_gain`` (1/T) grow more than GROWTH_THRESHOLD-fold within ``t_end``?
    (peak_gain t_end > ln GROWTH_THRESHOLD; works on arrays.)"""
    return np.asarray(peak_gain) * t_end > np.log(GROWTH_THRESHOLD)


def sideband_to_carrier(spec: np.ndarray, m: int, N: int) -> np.ndarray:
    """Largest non-carrier, non-harmonic theta component over the carrier, per record.

    Parameters
    ----------
    spec : ndarray, shape (nt, N//2 + 1)
    m : int, the carrier bin; N : int, number of sites.

    Returns
    -------
    ndarray, shape (nt,)
    """
    mask = non_carrier_bins(m, N)
    if not mask.any():
        raise ValueError(_no_sideband(N))
    return spec[:, mask].max(axis=1) / spec[:, m]


def _no_sideband(N: int) -> str:
    return (f"no sideband to measure on a ring of N = {N} sites: every ring mode there is "
            "a harmonic of the carrier; choose another N (a larger one, or an even one)")


def stability_verdict(spec: np.ndarray, m: int, N: int) -> dict:
    """Numerical stability of a noisy plane wave from its spectrum over time."""
    r = sideband_to_carrier(spec, m, N)
    growth = float(r.max() / r[0])
    if not np.isfinite(growth):  # a NaN must not read as "MI" (nor as "stable")
        raise ValueError(f"no stability verdict: the sideband-to-carrier ratio is not finite "
                         f"(growth factor {growth}); the spectrum holds NaN/inf or a zero "
                         "carrier")
    return {"stable": bool(growth < GROWTH_THRESHOLD),
            "sideband_to_carrier_start": float(r[0]),
            "sideband_to_carrier_end": float(r[-1]),
            "sideband_to_carrier_max": float(r.max()),
            "growth_factor": growth, "threshold": GROWTH_THRESHOLD}


#: linear_stage's defaults: the stage starts when the largest sideband has grown RISE-fold,
#: ends at CEILING of the carrier, and a window that ends with the run must span SPAN-fold
LINEAR_STAGE_RISE, LINEAR_STAGE_CEILING, LINEAR_STAGE_SPAN = 5.0, 0.01, np.e
#: the same, in words (for messages that say why a run gave no rate)
LINEAR_STAGE_RULE = (f"its largest sideband must pass {LINEAR_STAGE_RISE:g}x its start, then, "
                     "over at least 5 records, reach "
                     f"{LINEAR_STAGE_CEILING:.0%} of the carrier or grow e-fold more before "
                     "the run ends")


def linear_stage(spec: np.ndarray, m: int, N: int, rise: float = LINEAR_STAGE_RISE,
                 ceiling: float = LINEAR_STAGE_CEILING, span: float = LINEAR_STAGE_SPAN):
    """Index window (i0, i1) of the linear stage of MI.

    Starts when the largest sideband has grown ``rise``-fold over its initial level (the
    unstable modes dominate the noise) and ends when it reaches ``ceiling`` of the carrier
    (before pump depletion and cascades). Products of two unstable sidebands grow at
    sigma_1 + sigma_2 from a level ~ r^2, so they stay below the noise floor r0 while
    r < sqrt(r0): the default 1% keeps them out of the fit at the paper's noise (r0 ~ 1e-4),
    where 3% let them fake "growth" outside the band (the green band edge came out 1.5x
    too wide against the exact lattice gain; at 1% it agrees to 0.3%). A window that ends
    with the run, not at the ceiling, must see the largest sideband grow at least
    ``span``-fold (one e-folding): a run that only just passes ``rise`` before it ends
    leaves a few samples over which a slope is noise (a slowly unstable point gave 9.3e-4
    at an offset of 1.6 over its last 20 T, where it grew at 1.5e-4). Returns None when the
    run never gets there.
    """
    r = sideband_to_carrier(spec, m, N)
    above = np.flatnonzero(r > rise * r[0])
    if above.size == 0:
        return None
    i0 = int(above[0])
    top = np.flatnonzero(r[i0:] > ceiling)
    i1 = i0 + int(top[0]) if top.size else len(r) - 1
    if i1 - i0 < 4 or (not top.size and not r[i0:i1 + 1].max() >= span * r[i0]):
        return None
    return i0, i1


def growth_rates(t: np.ndarray, spec: np.ndarray, window) -> np.ndarray:
    """Least-squares slope of log|theta_hat(q, t)| over ``window``, for every q."""
    i0, i1 = window
    tt = t[i0:i1 + 1]
    y = np.log(np.maximum(spec[i0:i1 + 1], 1e-300))
    tc = tt - tt.mean()
    return (tc @ (y - y.mean(axis=0))) / (tc @ tc)


def band_summary(q: np.ndarray, sigma: np.ndarray, k: float, frac: float = 0.5) -> dict:
    """Peak gain, its offset from the carrier, and the band edge of a gain curve.

    Uses the upper side q > k. The edge is where sigma falls to ``frac`` of its peak,
    interpolated linearly, outward of the peak. Half the peak is a level both a measured
    curve (error bars ~1e-5 in the band, larger outside it) and a theory reach cleanly.
    """
    up = q > k
    qq, ss = q[up] - k, sigma[up]
    if qq.size == 0 or not np.any(ss > 0):
        return {"peak_gain": 0.0, "peak_offset": float("nan"), "band_edge": float("nan")}
    j = int(np.argmax(ss))
    peak = float(ss[j])
    level = frac * peak
    edge = float("nan")
    for i in range(j, len(ss) - 1):
        if ss[i] >= level > ss[i + 1]:
            edge = float(qq[i] + (ss[i] - level) / (ss[i] - ss[i + 1]) * (qq[i + 1] - qq[i]))
            break
    return {"peak_gain": peak, "peak_offset": float(qq[j]), "band_edge": edge}


def forced_second_harmonic(t: np.ndarray, U: np.ndarray, k_bin: int, omega_carrier: float,
                           omega_free: float) -> dict:
    """Split U at 2k into the part locked to the carrier (2 omega) and free waves.

    Fits U_hat(2k, t) (complex, normalised 2/N) by A e^{-2 i omega t} + B e^{-i W t}
    + C e^{+i W t}, W = ``omega_free`` (the lattice U branch at 2k). |A| is the forced
    second harmonic that eq. `u1` predicts (2 eps^2 |u2 coefficient| A0^2).
    """
    c = mode(U, 2 * k_bin)
    freqs = (2 * omega_carrier, omega_free, -omega_free)
    M = np.exp(-1j * np.outer(t, freqs))
    coef, *_ = np.linalg.lstsq(M, c, rcond=None)
    resid = np.linalg.norm(M @ coef - c) / max(np.linalg.norm(c), 1e-300)
    return {"forced": float(abs(coef[0])), "free_plus": float(abs(coef[1])),
            "free_minus": float(abs(coef[2])), "fit_residual": float(resid)}


def carrier_amplitude(theta: np.ndarray, m: int) -> float:
    """Mean amplitude a of the carrier a cos(k n - omega t) over the records."""
    return float(np.mean(np.abs(mode(theta, m))))


def carrier_frequency(t: np.ndarray, theta: np.ndarray, m: int) -> float:
    """Frequency of the carrier from the phase of theta_hat(k, t) (unwrapped, fitted)."""
    phase = np.unwrap(np.angle(mode(theta, m)))
    slope = np.polyfit(t, phase, 1)[0]
    return float(-slope)
