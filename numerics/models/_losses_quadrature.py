"""The tables of ``_losses._integrate`` (issue 42's quadrature along the decaying carrier),
compiled: which samples' segment holds each time's s = (a / a0)^2, its weight, the steps,
and where each column stops (``_losses._calm``). numpy built them in ~15 array passes over
the 4001 times and the columns, ~0.1 ms a call, three calls a damped point; here one loop
does the same arithmetic (elementwise IEEE operations in the same order: the same bits,
tests/test_dissipation.py compares ``_integrate`` with its array form to the last bit).
"""

from __future__ import annotations

import numpy as np
from numba import njit


@njit(cache=True, nogil=True, error_model="numpy", boundscheck=False)
def quadrature_tables(s_arr, g2, s_t, t, G):
    """(lo, j, lo_j, w, dt, cold, s_hot, ok) of ``_losses._integrate``: per column its
    lowest positive sample (the last where none is), per time the segment
    [s_arr[j - 1], s_arr[j]] of ``np.searchsorted(s_arr, s_t)`` clipped to 1..n - 1 and
    the weight of s_t in it, the steps t[i + 1] - t[i], and ``_losses._calm``'s cold
    level, hottest sample and line test per column. s_arr ascending (n,), g2 (n, cols)."""
    n, m = g2.shape
    nt = s_t.size
    lo = np.empty(m, np.int64)
    for c in range(m):
        lo[c] = n - 1
        for i in range(n):
            if g2[i, c] > 0:
                lo[c] = i
                break
    j = np.zeros(nt, np.int64)
    lo_j = np.zeros(nt, np.int64)
    w = np.empty(nt)
    for i in range(nt):
        jj = 0
        if n > 1:
            k = 0  # searchsorted, side left: the samples below s_t[i]
            while k < n and s_arr[k] < s_t[i]:
                k += 1
            jj = min(max(k, 1), n - 1)
        lj = max(jj - 1, 0)
        j[i], lo_j[i] = jj, lj
        w[i] = (s_t[i] - s_arr[lj]) / (s_arr[jj] - s_arr[lj] if jj != lj else 1.0)
    dt = np.empty(max(t.size - 1, 0))
    for i in range(dt.size):
        dt[i] = t[i + 1] - t[i]
    cold = np.empty(m)
    s_hot = np.empty(m)
    ok = np.zeros(m, np.bool_)
    for c in range(m):
        top = 0.0
        for i in range(n):
            if g2[i, c] > top:
                top = g2[i, c]
        gg = G[c] * G[c]
        cold[c] = gg - 1e-12 * max(gg, top)
        s_hot[c] = np.inf
        for i in range(n):
            if g2[i, c] > cold[c] and s_arr[i] < s_hot[c]:
                s_hot[c] = s_arr[i]
        b = min(lo[c] + 1, n - 1)
        a = max(lo[c] - 1, 0) if b == lo[c] else lo[c]
        ds = s_arr[b] - s_arr[a]
        slope = (g2[b, c] - g2[a, c]) / ds if ds != 0 else 0.0
        ok[c] = (g2[b, c] - slope * s_arr[b] <= cold[c]) and G[c] > 0
    return lo, j, lo_j, w, dt, cold, s_hot, ok
