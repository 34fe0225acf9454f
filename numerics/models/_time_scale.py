"""A model's own time scale, for the bounds of a run's length.

A run's T is chosen in the model's time (``numerics.lattice.run_length``): at least T_MIN =
1000, at most T_CAP = 1e5, 5000 where nothing grows. Those bounds were set on chains whose
frequencies are of order 1 (the paper's, FPUT, Klein-Gordon). A model file sets its own
time unit: a chain of stiffness 1e6 and mass 1e-3 (omega up to 6e4) or of stiffness 1e-6
(omega up to 2e-3) is the same chain in another unit, and its runs must cost the same and
decide the same. Probe 97: before, the stiff chain's point ran at least T = 1000, 6e7
radians (an estimated 88 min for one run of 64 sites, where 9 e-foldings took T = 1); the
soft chain's run was capped at 200 radians of its fastest wave and could not decide.
"""

from __future__ import annotations

import math

import numpy as np

from energy import Model

#: the lowest branch's top frequencies (1/time) for which the bounds stand as they are:
#: every built-in model's and the paper chain's lie inside
OMEGA_LOW, OMEGA_HIGH = 0.1, 10.0

_SCALES: dict = {}


def time_scale(model: Model) -> float:
    """The unit of a run's length bounds for ``model``: 1 where its lowest branch's top
    frequency omega_max (over k in [0, pi]) is within [OMEGA_LOW,
    OMEGA_HIGH], else OMEGA_HIGH / omega_max above and OMEGA_LOW / omega_max below (the
    bounds then hold as many radians of the fastest wave as at the band's edge; continuous
    in omega_max). A chain whose every stiffness is scaled by s^2 has its runs' T scaled by
    1/s outside the band, as its rates are scaled by s."""
    from ._linear import branches

    key = (model.code, np.asarray(model.p, float).tobytes())
    if key not in _SCALES:
        if len(_SCALES) > 256:
            _SCALES.clear()
        w = branches(model, np.linspace(0.0, math.pi, 65))  # (k, branch), ascending
        # the lowest branch's top: the whole band where one branch, the scale of every
        # branch where all are scaled alike; not a far optical branch's (diatomic-fput at
        # m = 1e-300: 1.4e150, which made an acoustic carrier's run 1e-147 long, nothing
        # measured, where its run is refused as too stiff to step, test_probe5)
        low = w[:, 0] if w.ndim == 2 else w
        wmax = float(np.nanmax(low)) if np.any(np.isfinite(low)) else math.nan
        if not (math.isfinite(wmax) and wmax > 0):
            scale = 1.0
        elif wmax > OMEGA_HIGH:
            scale = OMEGA_HIGH / wmax
        elif wmax < OMEGA_LOW:
            scale = OMEGA_LOW / wmax
        else:
            scale = 1.0
        _SCALES[key] = scale
    return _SCALES[key]
