"""Input checks with one rule: a wrong type raises TypeError naming the parameter, a wrong
value raises ValueError naming the parameter and its valid range. Nothing is cast
silently (a complex number is not a real one, True is not an integer)."""

from __future__ import annotations

import math
import numbers

import numpy as np

#: seeds are stored as signed 64-bit integers (HDF5, JSON): the valid range
SEED_RANGE = (0, 2**63)


def real(name: str, value, low: float | None = None, high: float | None = None, *,
         low_open: bool = True, high_open: bool = True, finite: bool = True) -> float:
    """A finite real number, optionally in (low, high) (closed ends when *_open=False).
    ``finite=False`` admits an infinite value within the bounds (a tolerance "no limit");
    NaN never passes."""
    if isinstance(value, (bool, np.bool_)) or not isinstance(value, numbers.Real):
        raise TypeError(f"{name} must be a real number, got {type(value).__name__} "
                        f"{value!r}")
    v = float(value)
    lo = "-inf" if low is None else f"{'(' if low_open else '['}{low:g}"
    hi = "inf)" if high is None else f"{high:g}{')' if high_open else ']'}"
    ok = math.isfinite(v) or (not finite and math.isinf(v))
    if ok and low is not None:
        ok = v > low if low_open else v >= low
    if ok and high is not None:
        ok = v < high if high_open else v <= high
    if not ok:
        where = f"in {lo}, {hi}" if (low is not None or high is not None) else "finite"
        raise ValueError(f"{name} must be {where}, got {value!r}")
    return v


def positive(name: str, value) -> float:
    """A finite real number > 0."""
    if isinstance(value, numbers.Real) and not isinstance(value, (bool, np.bool_)):
        v = float(value)
        if not (math.isfinite(v) and v > 0):
            raise ValueError(f"{name} must be finite and > 0, got {value!r}")
        return v
    raise TypeError(f"{name} must be a real number, got {type(value).__name__} {value!r}")


def integer(name: str, value, low: int | None = None, high: int | None = None) -> int:
    """An integer (Python or NumPy, not bool) in [low, high)."""
    if isinstance(value, (bool, np.bool_)) or not isinstance(value, numbers.Integral):
        raise TypeError(f"{name} must be an integer, got {type(value).__name__} {value!r}")
    v = int(value)
    if (low is not None and v < low) or (high is not None and v >= high):
        lo = "-inf" if low is None else str(low)
        hi = "inf" if high is None else str(high)
        raise ValueError(f"{name} must be an integer in [{lo}, {hi}), got {v}")
    return v


def seed(value, name: str = "seed") -> int:
    """A noise seed: an integer in [0, 2^63)."""
    if isinstance(value, (bool, np.bool_)) or not isinstance(value, numbers.Integral):
        raise TypeError(f"{name} must be an integer, got {type(value).__name__} {value!r}")
    if not SEED_RANGE[0] <= int(value) < SEED_RANGE[1]:
        raise ValueError(f"{name} must be an integer in [0, 2^63), got {value}")
    return int(value)


def instance(name: str, value, cls):
    """``value`` itself if it is a ``cls``, else TypeError naming the parameter."""
    if not isinstance(value, cls):
        raise TypeError(f"{name} must be a {cls.__name__}, got {type(value).__name__}")
    return value


def choice(name: str, value, choices) -> str:
    if not isinstance(value, str) or value not in choices:
        raise ValueError(f"{name} must be one of {', '.join(map(repr, choices))}, "
                         f"got {value!r}")
    return value


def real_array(name: str, value) -> np.ndarray:
    """A float array of real values (complex, object or non-numeric input: TypeError)."""
    arr = np.asarray(value)
    if arr.dtype.kind not in "fiu" or arr.dtype == bool:
        raise TypeError(f"{name} must hold real numbers, got dtype {arr.dtype}")
    return arr.astype(float)


def finite_array(name: str, value) -> np.ndarray:
    """:func:`real_array`, every value finite (a NaN or an infinity names ``name``)."""
    arr = real_array(name, value)
    if not np.all(np.isfinite(arr)):
        bad = arr[~np.isfinite(arr)].ravel()[0]
        raise ValueError(f"{name} must hold finite values, got {float(bad)!r}")
    return arr


def real_values(name: str, values) -> tuple:
    """A non-empty sequence of finite real numbers (each checked as :func:`real`: a bool or a
    complex number is refused, not cast)."""
    if isinstance(values, (str, bytes)) or not hasattr(values, "__len__"):
        raise TypeError(f"{name} must be a sequence of real numbers, got "
                        f"{type(values).__name__} {values!r}")
    if len(values) == 0:
        raise ValueError(f"{name} must hold at least one value, got none")
    return tuple(real(f"{name}[{i}]", v) for i, v in enumerate(values))


def available_memory() -> int:
    """Bytes this process can still allocate: MemAvailable of /proc/meminfo, else the
    physical memory (the limit a request is checked against before it allocates)."""
    try:
        with open("/proc/meminfo") as f:
            for line in f:
                if line.startswith("MemAvailable:"):
                    return int(line.split()[1]) * 1024
    except OSError:
        pass
    try:
        import os

        return os.sysconf("SC_PAGE_SIZE") * os.sysconf("SC_PHYS_PAGES")
    except (ValueError, OSError, AttributeError):
        return 8 * 2**30


def memory(name: str, nbytes: float, what: str) -> None:
    """ValueError naming ``name`` when ``what`` needs more than half the available memory
    (half: the request's temporaries and the rest of the process need the other half)."""
    limit = available_memory() / 2
    if nbytes > limit:
        raise ValueError(f"{name}: {what} would need {nbytes / 2**30:.3g} GiB, more than half "
                         f"of the {2 * limit / 2**30:.3g} GiB this machine has available; "
                         "ask for less")
