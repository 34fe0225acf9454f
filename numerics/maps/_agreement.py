"""How often each theory's verdict agrees with the simulated one over a map's cells."""

from __future__ import annotations

import math

import numpy as np

from ._columns import UNDETERMINED

#: a theory's verdict is "marginal" at a cell when its predicted growth exp(sigma t_end) is
#: within this factor of the threshold: the noise's share in the unstable mode and the time
#: the linear stage takes to set in change the measured factor by about that much
MARGIN = 3.0


def agreement(ds, margin: float = MARGIN) -> dict:
    """Percent of the simulated cells where each theory's verdict equals the simulation's
    (over the cells the runs decide: ``simulated_undetermined_cells`` counts the others):
    over the cells where the theory is determined (``<name>_undetermined_cells`` says how
    many simulated cells it could not evaluate), and over those where it is not marginal
    either (its predicted growth over t_end not within ``margin`` of the threshold; left
    out where the store has no one t_end: a model map whose runs are as long as each
    cell's own rate needs).

    "predicted" (the growth factor predicted from each cell's own initial state) is
    marginal where ``growth_predicted`` is within ``margin`` of the threshold.
    ``predicted_growth_within_2x``: percent of the cells whose measured growth lies in
    [2, 1000] where the predicted one is within 2x of it (over the same span:
    ``growth_log_ratio``), out of ``predicted_growth_cells``."""
    sim = ds["verdict_simulated"].values.astype(np.int8)
    # a cell whose runs cannot decide (grew, less than the threshold) is no evidence for or
    # against a theory: left out as a theory's undetermined cells are, and counted
    simulated = ds["done"].values
    done = simulated & (sim != UNDETERMINED)
    thr = float(ds.attrs["growth_threshold"])
    try:  # a model map's runs may take their length from each cell's rate: no one T
        t_end = float(ds.attrs["t_end"])
    except (TypeError, ValueError):
        t_end = None
    names = [n.removeprefix("verdict_") for n in ds.data_vars
             if n.startswith("verdict_") and n != "verdict_simulated"
             and f"peak_gain_{n.removeprefix('verdict_')}" in ds.data_vars]
    out = {"simulated_undetermined_cells": int((simulated & (sim == UNDETERMINED)).sum())}

    def pct(v, m):
        return float(100 * np.mean(v[m] == sim[m])) if m.any() else float("nan")

    for name in names:
        v = ds[f"verdict_{name}"].values.astype(np.int8)
        gain = ds[f"peak_gain_{name}"].values
        determined = done & (v != UNDETERMINED)
        with np.errstate(invalid="ignore"):
            decided = determined & (np.abs(gain * (t_end or 0.0) - math.log(thr))
                                    > math.log(margin))
        out[name] = pct(v, determined)
        out[f"{name}_undetermined_cells"] = int((simulated & (v == UNDETERMINED)).sum())
        if t_end is None:  # each run as long as its cell's own rate needs: none marginal
            continue
        out[f"{name}_decided"] = pct(v, decided)
        out[f"{name}_decided_cells"] = int(decided.sum())
    if "verdict_predicted" in ds:
        v = ds["verdict_predicted"].values.astype(np.int8)
        growth = ds["growth_predicted"].values
        determined = done & (v != UNDETERMINED)
        with np.errstate(invalid="ignore", divide="ignore"):
            decided = determined & (np.abs(np.log(growth) - math.log(thr)) > math.log(margin))
        out["predicted"] = pct(v, determined)
        out["predicted_undetermined_cells"] = int((simulated & (v == UNDETERMINED)).sum())
        out["predicted_decided"] = pct(v, decided)
        out["predicted_decided_cells"] = int(decided.sum())
        measured, ratio = ds["growth"].values, ds["growth_log_ratio"].values
        with np.errstate(invalid="ignore"):  # growth factors: every simulated cell
            mid = simulated & (v != UNDETERMINED) & (measured >= 2) & (measured <= 1000) & np.isfinite(ratio)
        out["predicted_growth_cells"] = int(mid.sum())
        out["predicted_growth_within_2x"] = (
            float(100 * np.mean(np.abs(ratio[mid]) <= math.log10(2))) if mid.any()
            else float("nan"))
    return out


__all__ = ["agreement", "MARGIN"]
