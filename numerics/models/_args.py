"""The argument checks the model layer shares (a ring's size, a count, a truncation, a
carrier's k, wavenumbers): each a one-line ModelError naming the argument and its range."""

from __future__ import annotations

import math
import numbers

import numpy as np

from energy import ModelError

#: The largest ring (sites): a run keeps ``records`` spectra of N values each.
MAX_RING = 2**20


def check_ring(N) -> int:
    """A ring size: an integer in [8, MAX_RING] (not a bool)."""
    if isinstance(N, bool) or not isinstance(N, (int, np.integer)) or not 8 <= N <= MAX_RING:
        raise ModelError(f"N must be an integer in [8, {MAX_RING}], got {N!r}")
    return int(N)


def check_count(name: str, value, least: int = 1, most: int | None = None,
                why: str = "") -> int:
    """An integer option (records, samples, seed, ...) >= ``least`` (and <= ``most``,
    ``why`` saying what bounds it), not a bool."""
    if isinstance(value, bool) or not isinstance(value, (int, np.integer)) or value < least:
        raise ModelError(f"{name} must be an integer >= {least}, got {value!r}")
    if most is not None and value > most:
        raise ModelError(f"{name} must be an integer in [{least}, {most}]"
                         + (f" ({why})" if why else "") + f", got {value!r}")
    return int(value)


#: The most harmonics a truncation takes: 8x the travelling wave's own largest default (32);
#: 10**6 asked for 116 TiB (numpy's MemoryError, naming no argument)
MAX_HARMONICS = 256


def check_harmonics(harmonics, low: int, why: str, name: str = "harmonics") -> int | None:
    """A truncation: None (the default) or an integer (not a bool) in [``low``,
    MAX_HARMONICS]; ``why`` says what the lower bound is for, in the error."""
    if harmonics is None:
        return None
    if isinstance(harmonics, (bool, np.bool_)) or not isinstance(harmonics, numbers.Integral):
        raise ModelError(f"{name} must be an integer >= {low} or None (the default), got "
                         f"{type(harmonics).__name__} {harmonics!r}")
    if int(harmonics) < low:
        raise ModelError(f"{name} must be an integer >= {low} ({why}) or None (the "
                         f"default), got {int(harmonics)}")
    if int(harmonics) > MAX_HARMONICS:
        raise ModelError(f"{name} must be at most {MAX_HARMONICS} (a wave that needs more is "
                         f"not weakly nonlinear; None picks the truncation from the wave's "
                         f"decay), got {int(harmonics)}")
    return int(harmonics)


def scalar(value):
    """``value`` itself, or the number a 0-d real array holds (``np.array(2.5)``, what
    numpy's reductions and indexing hand back): the scalar checks below then take it as
    the number it is (probe 99: ``exact_gain(m, np.array(2.5), ...)`` was refused as "k
    must be in (0, pi], got array(2.5)", and ``t_end=np.array(10.0)`` as not > 0)."""
    if isinstance(value, np.ndarray) and value.ndim == 0 and value.dtype.kind in "fiu":
        return value.item()
    return value


def check_rate(name: str, rate) -> float:
    """A growth rate given to set a run's length: a finite real number >= 0 (probe 99: nan,
    -1 and inf were taken silently, as a rate of 0, the run then 5000 long)."""
    rate = scalar(rate)
    if isinstance(rate, (bool, np.bool_)) or not (
            isinstance(rate, numbers.Real) and math.isfinite(rate) and rate >= 0):
        raise ModelError(f"{name} must be a finite rate >= 0 (1/time) or None (the exact "
                         f"theory's), got {rate!r}")
    return float(rate)


def check_noise(noise) -> float:
    """A run's noise, relative to the amplitude: a real number in [0, 1), as the paper
    chain's (at 1 the start is noise, not a wave; probe 99: 1e300 blew up "by t = 0 ...
    lower the amplitude or dt", naming neither)."""
    noise = scalar(noise)
    if isinstance(noise, (bool, np.bool_)) or not (
            isinstance(noise, numbers.Real) and math.isfinite(noise) and 0 <= noise < 1):
        raise ModelError(f"noise must be a number in [0, 1) (of the amplitude), got "
                         f"{noise!r}")
    return float(noise)


def check_k(k) -> float:
    """A carrier wavenumber: a finite real number (not a bool) in (0, pi], the range nls,
    exact_gain and four_wave take (a Carrier that said k = -1 or 7 would be read
    downstream as a wave it is not: its v_g and e are those of k mod 2 pi)."""
    k = scalar(k)
    if isinstance(k, (bool, np.bool_)) or not isinstance(k, numbers.Real) \
            or not math.isfinite(k):
        raise ModelError(f"k must be a finite real number, got {type(k).__name__} {k!r}")
    if not 0 < k <= math.pi:
        raise ModelError(f"k must be in (0, pi] rad/site, got {k!r}: fold it into (0, pi] "
                         f"(k mod 2 pi, then 2 pi - k above pi)")
    return float(k)


def wavenumbers(kappa, name: str = "kappa") -> np.ndarray:
    """``kappa`` as a float array of finite real wavenumbers; ModelError naming ``name``
    otherwise (a bool, a string such as "1" that numpy would cast, a complex, NaN)."""
    try:
        raw = np.asarray(kappa)
        kap = raw.astype(float) if raw.dtype.kind in "fiu" else None
    except (TypeError, ValueError):
        kap = None
    if kap is None or not np.all(np.isfinite(kap)):
        raise ModelError(f"{name} must be finite real wavenumbers (rad/site), got "
                         f"{kappa!r}"[:300])
    return kap


def snap_ring(k: float, N: int) -> tuple[float, int]:
    """(2 pi m / N, m) nearest to k in (0, pi] on a ring of N sites (pi on an odd ring:
    m = (N - 1) / 2, not 2 pi (N + 1) / 2N > pi); k = pi (N even) also as 2 pi (N/2) / N
    a few ulps above it (probe 102: refused), returned as pi exactly."""
    N = check_ring(N)
    k = scalar(k)
    if isinstance(k, (bool, np.bool_)) or not (
            isinstance(k, numbers.Real) and math.isfinite(k)
            and 0 < k <= math.pi * (1 + 8 * np.finfo(float).eps)):
        raise ModelError(f"k must be in (0, pi], got {k!r}")
    m = min(int(round(k * N / (2 * math.pi))), N // 2)
    if 2 * m == N:
        return math.pi, m
    if m == 0:
        need = math.ceil(math.pi / k)
        raise ModelError(f"k = {k:g} snaps to 0 on a ring of N = {N} (no wave): " + (
            f"raise N above {need}" if need < MAX_RING else
            f"no ring carries it (N at most {MAX_RING}): k at least "
            f"{2 * math.pi / MAX_RING:.3g}"))
    return 2 * math.pi * m / N, m


def ring_offsets(N: int) -> np.ndarray:
    """The perturbation wavenumbers of a ring of N sites, q = 2 pi j / N, 0 < q <= pi."""
    N = check_ring(N)  # N = 0 or -4 was an empty array, 2.5 a wavenumber 2.51 > pi/2
    return 2 * np.pi * np.arange(1, N // 2 + 1) / N
