"""One cell of an MI map, simulated: the verdict, the growth and where it sits.

A cell is a material, a case, a carrier k and the plane wave's amplitude (eq. `IC`,
its peak rotation ``amplitude``). :func:`simulate_cell` runs the paper's experiment and applies the scenes'
criterion: MI when the largest non-carrier, non-harmonic component grows more than
GROWTH_THRESHOLD (20x) over the run (the theories' verdicts on the same question are in
``scenes.maps.theory_columns``).

Early stop (the rule): the run goes in segments; as soon as the growth factor exceeds the
threshold the verdict "MI" is certain (the factor is a running maximum and can only grow),
so the run stops there. A stable verdict needs the whole run.
"""

from __future__ import annotations

import math

import numpy as np

from ..lattice._analysis import GROWTH_THRESHOLD, growth_rates, linear_stage, non_carrier_bins
from ..lattice._model import Material
from ..lattice._simulate import simulate

#: a run is cut into this many segments for the early-stop check
SEGMENTS = 20
#: U's growth is measured from its level at this fraction of the run (U starts at rest in
#: the paper's initial condition, so its level at T = 0 is no reference)
U_REFERENCE = 0.05


def _ratios(theta_hat, U_hat, m, N):
    """Largest non-carrier, non-harmonic component over the carrier, per record and
    field, and where it sits."""
    carrier = theta_hat[:, m]
    mask = non_carrier_bins(m, N, "theta")
    out = {"theta": theta_hat[:, mask] / carrier[:, None]}
    if U_hat is not None:
        mask_U = non_carrier_bins(m, N, "U")
        out["U"] = U_hat[:, mask_U] / carrier[:, None]
        return out, {"theta": np.flatnonzero(mask), "U": np.flatnonzero(mask_U)}
    return out, {"theta": np.flatnonzero(mask)}


def growth_of(t, theta_hat, U_hat, m, N) -> dict:
    """Largest growth factor over the records, which field and wavenumber carries it."""
    ratios, bins = _ratios(theta_hat, U_hat, m, N)
    best = {"growth": 0.0, "growth_field": "theta", "growth_q": float("nan")}
    for field, r in ratios.items():
        i0 = 0 if field == "theta" else int(np.searchsorted(t, U_REFERENCE * t[-1]))
        if i0 >= len(t) - 1:
            continue
        top = r[i0:].max(axis=1)
        ref = top[0]
        if not ref > 0:
            continue
        g = float(top.max() / ref)
        if g > best["growth"]:
            i = i0 + int(np.argmax(top))
            j = bins[field][int(np.argmax(r[i]))]
            best = {"growth": g, "growth_field": field, "growth_q": 2 * math.pi * j / N}
    return best


def simulate_cell(material: Material, case: str, k: float, N: int, t_end: float,
                  amplitude: float = 0.02, noise: float = 1e-3, seed: int = 0,
                  start: str = "paper", dt: float = 0.05, method: str = "rk4",
                  early_stop: bool = True) -> dict:
    """The simulated verdict at one cell (the scenes' criterion), with early stop.

    Returns the verdict (True = MI), the largest growth factor and the field ("theta" or
    "U") and wavenumber carrying it, the time simulated and whether it stopped early.
    """
    seg = t_end / SEGMENTS
    kw = dict(material=material, case=case, N=N, amplitude=amplitude, noise=noise, seed=seed,
              dt=dt, method=method, store="spectrum", start=start, progress=False,
              energy_tolerance=1.0)
    ts, th, U = [], [], []
    state, t0, k_used, m = None, 0.0, k, None
    for _ in range(SEGMENTS):
        run = simulate(k=k_used, t_end=seg, save_every=seg / 10, initial=state, **kw)
        k_used, m = run.k, run.m
        first = 0 if state is None else 1
        ts.append(run.t[first:] + t0)
        th.append(run.theta_hat[first:])
        if run.U_hat is not None:
            U.append(run.U_hat[first:])
        state, t0 = run.final_state, t0 + seg
        g = growth_of(np.concatenate(ts), np.concatenate(th),
                      np.concatenate(U) if U else None, m, run.N)
        if early_stop and g["growth"] > GROWTH_THRESHOLD:
            break
    t, theta_hat = np.concatenate(ts), np.concatenate(th)
    mi = bool(g["growth"] > GROWTH_THRESHOLD)
    return {"verdict_simulated": mi, **g, "growth_q": float(g["growth_q"]),
            "peak_gain": measured_peak_gain(t, theta_hat, m, run.N) if mi else float("nan"),
            "t_simulated": t0, "stopped_early": bool(t0 < t_end - 1e-9), "k": k_used}


def measured_peak_gain(t, theta_hat, m, N) -> float:
    """Largest sideband growth rate from a linear-stage fit (NaN without a linear stage)."""
    win = linear_stage(theta_hat, m, N)
    if win is None:
        return float("nan")
    rates = growth_rates(t, theta_hat, win)
    return float(rates[non_carrier_bins(m, N)].max())


__all__ = ["simulate_cell", "growth_of", "measured_peak_gain"]
