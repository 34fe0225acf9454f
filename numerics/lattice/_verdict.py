"""One meaning of a simulation's verdict, and a run long enough to reach it.

A theory's verdict is physical: MI when its peak gain is > 0, however slow. A run of length
T can only show growth fast enough to pass GROWTH_THRESHOLD within T, so its verdict is one
of three words (``VERDICT_WORDS``), never a bare "stable" that a longer run would overturn:

- ``"MI"``: the run grew more than GROWTH_THRESHOLD-fold (with its measured rate);
- ``"no growth within T"``: it stayed below sqrt(GROWTH_THRESHOLD) (noise and beating
  level): a rate below ln(GROWTH_THRESHOLD) / T cannot show in it;
- ``"undetermined"``: it grew, but not to the threshold (a longer run decides), or no run
  gave a growth factor.

:func:`run_length` chooses T from the fastest predicted rate: enough e-foldings to measure
the rate, within a stated cap, and says when the cap stops the run short of deciding.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ._analysis import GROWTH_THRESHOLD

#: the three words a simulation's verdict uses
VERDICT_WORDS = ("MI", "no growth within T", "undetermined")
#: e-foldings of the predicted rate a run needs to decide: ln(20) = 3.0, plus one for the
#: noise's projection on the growing mode (measured at alpha 1.3, K_s 0.05, K_theta 0.045:
#: 4 seeds grew 0.6x-1.1x exp(rate T))
DECIDE_E_FOLDINGS = 4.0
#: e-foldings a run is given to measure the rate (linear stage over, the fit settled)
MEASURE_E_FOLDINGS = 9.0
#: bounds of the chosen T (lattice units): at least T_MIN, at most T_CAP (~1 min for 4
#: seeds of 500 sites on one core), DEFAULT_T where nothing is predicted to grow
T_MIN, T_CAP, DEFAULT_T = 1000.0, 100_000.0, 5000.0


def slowest_visible_rate(t_end: float, threshold: float = GROWTH_THRESHOLD) -> float:
    """The smallest rate (1/T) that grows ``threshold``-fold within ``t_end``."""
    return math.log(threshold) / t_end


@dataclass(frozen=True)
class RunLength:
    """T chosen for a run: ``t_end``; the ``rate`` it was chosen from; ``capped``: the cap
    stopped it before DECIDE_E_FOLDINGS e-foldings; ``decides_at``: the T that would decide
    (NaN where nothing is predicted to grow)."""

    t_end: float
    rate: float
    capped: bool
    decides_at: float
    cap: float

    def note(self) -> str | None:
        """A sentence when the cap stops the run short of deciding, else None."""
        if not self.capped:
            return None
        return (f"T = {self.t_end:g} (the cap) holds {self.rate * self.t_end:.2g} e-foldings "
                f"of the fastest predicted rate {self.rate:.4g} /T; {DECIDE_E_FOLDINGS:g} "
                f"decide: --t-end {self.decides_at:g} would")


def run_length(rate: float, cap: float | None = None, *, time_scale: float = 1.0) -> RunLength:
    """T for a run whose fastest predicted rate is ``rate`` (1/T): MEASURE_E_FOLDINGS
    e-foldings rounded up to 100 T, within [T_MIN, cap]; DEFAULT_T where nothing grows.

    ``time_scale``: the bounds (T_MIN, the cap, DEFAULT_T, the rounding) are in units of
    it (``numerics.models.time_scale``: 1 for a chain whose lowest branch tops out at 0.1
    to 10, as the paper's; a stiff chain's 10/omega_max: before probe 97, a model of
    stiffness 1e6 and mass 1e-3 (omega ~ 6e4) ran at least T = 1000, 6e7 radians, an
    estimated 88 min on 64 sites, where 9 e-foldings took T = 1; a cap of None is T_CAP
    in those units).

    Returns
    -------
    RunLength
    """
    from . import checks

    tau = checks.positive("time_scale", time_scale)
    cap = tau * T_CAP if cap is None else checks.positive("cap", cap)  # before: cap = -1
    if not (isinstance(rate, (int, float, np.floating)) and rate > 0 and math.isfinite(rate)):
        return RunLength(tau * DEFAULT_T, float("nan"), False, float("nan"), cap)
    rate = float(rate)
    step = 100 * tau
    t = min(max(math.ceil(MEASURE_E_FOLDINGS / rate / step) * step, tau * T_MIN), cap)
    decides = math.ceil(DECIDE_E_FOLDINGS / rate / step) * step
    return RunLength(float(t), rate, rate * t < DECIDE_E_FOLDINGS, float(decides), cap)


@dataclass(frozen=True)
class Verdict:
    """A simulation's verdict: ``word`` (one of VERDICT_WORDS), the run's ``t_end``, the
    measured peak ``rate`` (NaN: none fitted), the ``growth`` factors (one per seed), the
    ``slowest_visible`` rate ln(threshold) / T and, when undetermined, the ``reason``."""

    word: str
    t_end: float
    rate: float
    growth: tuple
    slowest_visible: float
    reason: str = ""
    #: the lattice time's name in the text: "T" (the paper chain's), "time" for a model,
    #: whose file sets its time unit
    time_name: str = "T"

    def __str__(self) -> str:
        per = f"/{self.time_name}"
        if self.word == "MI":
            return "MI" + (f" (measured rate {self.rate:.4g} {per})" if math.isfinite(self.rate)
                           else f" (grew {_factors(self.growth)} within T = {self.t_end:g})")
        if self.word == "no growth within T":
            return (f"no growth within T = {self.t_end:g} (a rate below "
                    f"{self.slowest_visible:.2g} {per} cannot show)")
        return f"undetermined ({self.reason})"

    @property
    def map_rate(self) -> float:
        """The rate a map cell stores for these runs (``peak_gain_simulated``): the measured
        rate where MI; where there was no growth within T, the bound ln(threshold) / T
        below which the rate lies (a faster one would have grown past the threshold); NaN
        where undetermined (it grew, but less than the threshold)."""
        if self.word == "MI":
            return float(self.rate)
        if self.word == "no growth within T":
            return float(self.slowest_visible)
        return math.nan

    def to_dict(self) -> dict:
        return {"verdict": self.word, "text": str(self), "t_end": self.t_end,
                "rate": self.rate, "growth": list(self.growth),
                "slowest_visible_rate": self.slowest_visible, "reason": self.reason}


def _factors(g) -> str:
    g = [x for x in g if math.isfinite(x)]
    if not g:
        return "?"
    lo, hi = min(g), max(g)
    return f"{lo:.3g}x" if lo == hi else f"{lo:.3g}x-{hi:.3g}x"


def simulated_verdict(growth, t_end: float, rate: float = float("nan"),
                      threshold: float = GROWTH_THRESHOLD, time_name: str = "T") -> Verdict:
    """The verdict of a simulation from its measured growth factors.

    Parameters
    ----------
    growth : sequence of float
        Growth factor of each seed's run (the largest non-carrier component over the
        carrier, end over start: ``numerics.maps.growth_of``).
    t_end : float
        The runs' length T.
    rate : float, optional
        The measured peak rate (1/T), NaN where no linear stage gave one.
    threshold : float
        Growth that counts as MI (GROWTH_THRESHOLD, 20).
    time_name : str
        The lattice time's name in the verdict's text ("T"; "time" for a model).

    Returns
    -------
    Verdict
        "MI" when most seeds grew more than ``threshold``-fold; "no growth within T" when
        their median stayed below sqrt(threshold); "undetermined" between (it grew, a longer
        run decides) or without a finite growth factor.
    """
    # before: t_end = -1 gave "MI (grew 100x within T = -1)", threshold 0 "math domain
    # error", a bare number "'float' object is not iterable", a factor -5 "no growth"
    from . import checks

    t_end = checks.positive("t_end", t_end)
    threshold = checks.real("threshold", threshold, 1.0, None)
    if isinstance(growth, (str, bytes)) or not hasattr(growth, "__iter__"):
        raise TypeError(f"growth must be a sequence of growth factors (one per seed), got "
                        f"{type(growth).__name__} {growth!r}")
    g = tuple(checks.real("growth", x, finite=False) if not (
        isinstance(x, float) and math.isnan(x)) else x for x in growth)
    if any(x < 0 for x in g):
        raise ValueError(f"growth factors are amplitude ratios (end over start), >= 0, "
                         f"got {min(g):g}")
    low = slowest_visible_rate(t_end, threshold)
    if not g or not all(math.isfinite(x) for x in g):
        return Verdict("undetermined", t_end, rate, g, low, "no growth factor from the run",
                       time_name)
    if sum(x > threshold for x in g) * 2 > len(g):
        return Verdict("MI", t_end, rate, g, low, time_name=time_name)
    med = float(np.median(g))
    if med <= math.sqrt(threshold):
        return Verdict("no growth within T", t_end, rate, g, low, time_name=time_name)
    return Verdict("undetermined", t_end, rate, g, low,
                   f"grew {_factors(g)} within T = {t_end:g}: more than noise, less than the "
                   f"{threshold:g}x that decides; a longer --t-end decides", time_name)


__all__ = ["VERDICT_WORDS", "DECIDE_E_FOLDINGS", "MEASURE_E_FOLDINGS", "T_MIN", "T_CAP",
           "RunLength", "run_length", "Verdict", "simulated_verdict", "slowest_visible_rate"]
