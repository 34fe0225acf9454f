"""The exponential reading of a run's growth, as plain scalar loops: one source for the host
(``_analysis.exponential_bound``, a point's and a map cell's run on the CPU) and the GPU
(``_cuda``, compiled for the device from this same function: the cell's running bound and
its early stop are reduced on the chip).
"""

from __future__ import annotations

import math


def bound_of_records(t, top, lo, hi, stage_end):
    """exp(s L) of the records lo .. hi - 1 of ``top`` at times ``t`` (see
    ``exponential_bound``): s the least-squares log-slope over the second half of the
    linear stage (up to the first record above ``stage_end``, else the last), L the stage's
    length; 1 where s <= 0; inf (nothing to bound with) where fewer than two records, one
    not finite or not positive, or fewer than three in the second half.

    The slope is the centred two-pass least-squares fit (numpy's polyfit agrees to
    round-off: 1e-13 relative on the slopes tested)."""
    if hi - lo < 2:
        return math.inf
    end = -1
    for i in range(lo, hi):
        y = top[i]
        if math.isnan(y) or math.isinf(y) or not y > 0.0:
            return math.inf
        if end < 0 and y > stage_end:
            end = i
    if end < 0:
        end = hi - 1
    if end < lo + 1:
        end = lo + 1
    length = t[end] - t[lo]
    mid = t[lo] + length / 2
    count = 0
    sx = 0.0
    sy = 0.0
    for i in range(lo, end + 1):
        if t[i] >= mid:
            count += 1
            sx += t[i]
            sy += math.log(top[i])
    if count < 3:
        return math.inf
    mx = sx / count
    my = sy / count
    sxy = 0.0
    sxx = 0.0
    for i in range(lo, end + 1):
        if t[i] >= mid:
            dx = t[i] - mx
            sxy += dx * (math.log(top[i]) - my)
            sxx += dx * dx
    if not sxx > 0.0:  # the second half's records at one time: no slope (1, as numpy's
        return 1.0     # nan slope read before the host's copy was compiled)
    slope = sxy / sxx
    # no min/max builtins: numba-cuda 0.30 does not type them in a device function
    e = slope * length if slope > 0.0 else 0.0
    return math.exp(e if e < 700.0 else 700.0)
