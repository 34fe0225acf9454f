"""The paper chain's smallest amplitude float64 resolves, for the paper flags' point,
soliton and coefficients: the rule of ``common.resolution``, which a model's commands apply
too (``numerics.models.ModelNLS.smallest_amplitude``)."""

from __future__ import annotations

import math

from common.resolution import EPS, smallest_resolved_amplitude


def check_paper_amplitude(mat, k: float, amplitude: float) -> float:
    """``amplitude``, or a ValueError naming --amplitude where the semi-discrete NLS's
    frequency shift |g2| a^2 / 4 (the larger case's |g2|) is below omega's rounding error
    eps omega: there every theory's rate is rounding or an underflow (at 1e-320 `point`
    called the focusing case II "stable", its gain 0; `soliton` printed a width of inf)."""
    import numpy as np

    from generated import lattice_coefficients as lc

    at = (k, mat.alpha, mat.K_s, mat.K_theta)
    with np.errstate(all="ignore"):
        omega = float(lc.omega(*at))
        g2 = [abs(float(f(*at))) for f in (lc.g2_rotation, lc.g2_coupled)]
    g2 = max((g for g in g2 if math.isfinite(g)), default=0.0)
    least = smallest_resolved_amplitude(omega, g2)  # 0: no NLS here, the theories say why
    if amplitude < least:
        raise ValueError(
            f"--amplitude {amplitude:.3g} is below what float64 resolves at k = {k:.6g}: "
            f"the NLS's frequency shift |g2| a^2 / 4 = {g2 / 4 * amplitude * amplitude:.3g} "
            f"is under omega's rounding error eps omega = {EPS * omega:.3g}, so every "
            f"theory's growth rate there is rounding, not a verdict; give --amplitude >= "
            f"{least:.3g}")
    return amplitude


def check_peak_rotation(value, high: float) -> float:
    """--amplitude of the paper chain's flags: the peak rotation in rad, in (0, ``high``),
    or a ValueError naming it and its unit, and, past ``high``, what the value would be
    had it been meant in degrees (newuser 102: an experimentalist's "5 degrees" read
    "--amplitude must be in (0, 1.5), got 5.0", no unit and no remedy)."""
    from numerics.lattice import checks

    try:
        return checks.real("--amplitude", value, 0.0, high)
    except ValueError as exc:
        v = float(value)
        hint = (f"; if {v:g} was meant in degrees: --amplitude {math.radians(v):.4g}"
                if math.isfinite(v) and v >= high else "")
        raise ValueError(f"{exc} (rad: the peak rotation, below {high:g} rad where the "
                         f"theories hold){hint}") from None
