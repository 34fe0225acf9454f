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


import numpy as np

from ..lattice._analysis import (GROWTH_THRESHOLD, growth_rates, linear_stage, non_carrier_bins,
                                 spectrum_growth)
from ..lattice._model import Material
from ..lattice._simulate import simulate

#: a run is cut into this many segments for the early-stop check
SEGMENTS = 20


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
    """Largest growth factor over the records, which field and wavenumber carries it
    (the reading :func:`numerics.lattice.spectrum_growth` defines)."""
    ratios, bins = _ratios(theta_hat, U_hat, m, N)
    growth, field, q = spectrum_growth(np.asarray(t), {f: r[None] for f, r in ratios.items()},
                                       bins, N)
    return {"growth": float(growth[0]), "growth_field": str(field[0]),
            "growth_q": float(q[0])}


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


#: why a cell's prediction is what it is (the store's ``predicted_status`` flag)
PREDICTED_STATUS = {"linear": 0, "saturates": 1, "no plane wave": 2, "not quasi-periodic": 3,
                    "approximate torus": 4}


def predict_cell(material: Material, case: str, k: float, N: int, t_end: float,
                 amplitude: float = 0.02, noise: float = 1e-3, seeds: int = 1,
                 start: str = "paper"):
    """The growth factor the simulation of this cell will measure, predicted
    (:func:`numerics.theory.predict_growth`), as the map stores it.

    The map's seeds are 0 .. seeds - 1; with several, the median growth factor over them
    (as the simulated column). Returns (row, prediction): ``row`` holds
    ``growth_predicted`` (NaN where no linear theory applies), ``verdict_predicted``
    (1 MI, 0 stable, -1 undetermined),
    ``rate_predicted`` and ``predicted_status`` (PREDICTED_STATUS); ``prediction`` is the
    GrowthPrediction, or None.
    """
    from ..theory import predict_growth

    try:
        p = predict_growth(material, case, k, amplitude, start=start, N=N, t_end=t_end,
                           seed=0, noise=noise, draws=seeds - 1)
    except ArithmeticError as exc:  # the state has no linear theory (said in the status)
        status = "no plane wave" if "harmonic balance" in str(exc) else "not quasi-periodic"
        p = None
    if p is None:
        return {"growth_predicted": float("nan"), "verdict_predicted": -1,
                "rate_predicted": float("nan"),
                "predicted_status": PREDICTED_STATUS[status]}, None
    growth = float(np.median(np.concatenate([[p.growth], p.growth_draws])))
    return {"growth_predicted": growth,
            "verdict_predicted": int(growth > GROWTH_THRESHOLD),
            "rate_predicted": p.rate,
            "predicted_status": PREDICTED_STATUS[
                "saturates" if not p.linear else "approximate torus"
                if p.approximate else "linear"]}, p


__all__ = ["simulate_cell", "growth_of", "measured_peak_gain", "predict_cell",
           "PREDICTED_STATUS"]
