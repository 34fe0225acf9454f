"""The smallest carrier amplitude float64 resolves: one rule for the paper chain's flags
(``cli._resolved``) and any model (``numerics.models.ModelNLS.smallest_amplitude``).

Below it the NLS's frequency shift |g2| a^2 / 4 (the nonlinear terms' share of the wave's
frequency) is under omega's rounding error eps omega: the wave is linear to the last bit of
omega and every theory's rate (~ the shift) is rounding or an underflow, no verdict.
"""

from __future__ import annotations

import math
import sys

#: float64's machine epsilon (numpy's finfo(float).eps; no numpy import for one number)
EPS = sys.float_info.epsilon


def smallest_resolved_amplitude(omega: float, g2: float) -> float:
    """2 sqrt(eps omega / |g2|): the amplitude a whose shift |g2| a^2 / 4 is eps omega;
    0 where the NLS gives no shift (g2 zero or not finite, omega not a positive number)."""
    g2 = abs(g2)
    if not (math.isfinite(omega) and omega > 0 and math.isfinite(g2) and g2 > 0):
        return 0.0
    # the product eps * omega / g2 first: a^2 itself may underflow
    return 2 * math.sqrt(EPS * omega / g2)


__all__ = ["EPS", "smallest_resolved_amplitude"]
