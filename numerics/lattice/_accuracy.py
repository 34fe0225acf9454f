"""Accuracy you can ask for: the step for a requested error, and a warning when a run is off.

Error model of the fixed-step methods (``tol=``)
-------------------------------------------------
A method of order p integrating waves of dominant frequency w for a time T makes a
relative state error (max |x - x_exact| over max |theta|, theta and U)

    e(dt, T) ~= C_m (w dt)^p (w T),

the phase error of each step accumulated linearly. w is measured on the starting state as
the ratio rms(theta_dot) / rms(theta) (exact for a plane wave, the carrier frequency; the
larger of theta's and U's ratios in case II). The constants C_m were measured with
``bench/calibrate_accuracy.py`` (N = 500, T = 200) at five points: the paper's blue II and
green I, a 10x larger amplitude, and two other materials; ERROR_CONSTANTS keeps, per method,
the largest C_m found away from strong MI (so the error comes out at or below ``tol``,
measured 1-15x below). ``choose_step`` solves the model for dt for each method, keeps dt
below 80% of the method's stability limit, and takes the method with the fewest force
evaluations.

What the model cannot know: a modulationally unstable run amplifies every error by
e^{sigma T} once sigma T is not small (sigma the MI growth rate); no step size controls the
state after the instability has grown (the statistics, not the state, are then the
reproducible result). Ask for ``tol`` over times where sigma T < 1, or check the energy.

The energy check of fixed-dt runs
---------------------------------
The energy of eq. `norm` is conserved; a run whose relative energy error exceeds
``energy_tolerance`` ends with an :class:`AccuracyWarning` that names the error and a step
that meets the tolerance: the energy error of an order-p method scales as dt^p (symplectic
methods: bounded; RK4: a drift), so dt_new = dt (energy_tolerance / (2 error))^(1/p).
"""

from __future__ import annotations

import math
import warnings

import numpy as np

from . import checks
from ._integrators import get_method


class AccuracyWarning(UserWarning):
    """A run finished, but less accurately than asked (its energy error is too large)."""


#: C_m of the error model (module docstring), measured by bench/calibrate_accuracy.py.
ERROR_CONSTANTS = {"rk4": 0.061, "verlet": 0.11, "srkn6b": 8.9e-5, "srkn11b": 1.3e-6,
                   "kahanli8": 1.9e-4}
#: keep dt below this fraction of a method's linear stability limit
STABILITY_MARGIN = 0.8
#: tolerances outside this range are not what double precision and the model can deliver
TOL_RANGE = (1e-12, 1e-1)


#: a field counts for the dominant frequency only above this rms relative to theta's: U
#: below it is round-off (a travelling wave whose 2k harmonic sits at the zone boundary has
#: U ~ 1e-31, whose rms(U_dot) / rms(U) read 1e14 and asked for dt = 1e-16)
NEGLIGIBLE_FIELD = 1e-9


def dominant_frequency(state) -> float:
    """w = rms(theta_dot) / rms(theta) (and the same for U in case II where U is not
    negligible, NEGLIGIBLE_FIELD: the larger)."""
    def rms(x):
        return float(np.sqrt(np.mean(np.square(x))))

    def ratio(x, xdot):
        rx = rms(x)
        return rms(xdot) / rx if rx > 0 else 0.0

    w = ratio(state.theta, state.theta_dot)
    if state.U is not None and rms(state.U) > NEGLIGIBLE_FIELD * rms(state.theta):
        w = max(w, ratio(state.U, state.U_dot))
    return w


def check_tol(tol) -> float:
    """A relative state error in TOL_RANGE (closed)."""
    return checks.real("tol", tol, *TOL_RANGE, low_open=False, high_open=False)


def choose_step(state, material, case: str, t_end: float, tol: float,
                methods=None, constants=None) -> tuple[str, float]:
    """(method, dt) whose predicted relative state error at ``t_end`` is ``tol``.

    Parameters
    ----------
    state : LatticeState
        The starting state (its dominant frequency sets the error scale).
    material, case : the run's.
    t_end : float
        Duration of the run.
    tol : float
        Wanted relative state error, in TOL_RANGE.
    methods : iterable of str, optional
        Candidates (default: every fixed-step method with a measured constant).
    constants : dict, optional
        {method: C_m} of the error measured (default ERROR_CONSTANTS, the state's; the
        map cells pass the growth factor's, ``numerics.maps._cells``).

    Returns
    -------
    (str, float)
        The method with the fewest force evaluations, and its step.
    """
    tol = check_tol(tol)
    w = dominant_frequency(state)
    w_max = material.omega_max(case)
    if not w > 0:  # a state at rest: any step is exact; the stability limit decides
        w = w_max
    constants = ERROR_CONSTANTS if constants is None else constants
    best = None
    for name in methods or constants:
        m = get_method(name)
        if name not in constants:
            raise ValueError(f"no error constant for method {name!r}; choose from "
                             f"{', '.join(constants)}")
        dt = (tol / (constants[name] * w * t_end)) ** (1.0 / m.order) / w
        dt = min(dt, STABILITY_MARGIN * m.stability_limit() / w_max, t_end)
        cost = m.evaluations * math.ceil(t_end / dt)
        if best is None or cost < best[0]:
            best = (cost, name, dt)
    return best[1], best[2]


def energy_check(error: float, energy_tolerance: float, method: str, dt: float) -> None:
    """Warn (AccuracyWarning) when a run's relative energy error exceeds the tolerance."""
    if error <= energy_tolerance:
        return
    p = get_method(method).order
    better = dt * (energy_tolerance / (2.0 * error)) ** (1.0 / p) if math.isfinite(error) \
        else dt / 10
    warnings.warn(
        f"relative energy error {error:.3g} exceeds energy_tolerance = {energy_tolerance:g} "
        f"(method {method!r}, dt = {dt:g}): the run is not accurate; rerun with "
        f"dt <= {better:.3g}, or ask for accuracy with tol=...", AccuracyWarning,
        stacklevel=3)


def check_energy_tolerance(value) -> float:
    return checks.positive("energy_tolerance", value)
