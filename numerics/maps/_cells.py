"""One cell of an MI map, simulated: the verdict, the growth and where it sits.

A cell is a material, a case, a carrier k and the plane wave's amplitude (eq. `IC`,
its peak rotation ``amplitude``). :func:`simulate_cell` runs the paper's experiment and applies the scenes'
criterion: MI when the largest non-carrier, non-harmonic component grows more than
GROWTH_THRESHOLD (20x) over the run (the theories' verdicts on the same question are in
``scenes.maps.theory_columns``).

Accuracy (what the verdict needs): the run's method and step come from the accuracy of the
quantity measured, the growth factor, not from the paper's RK4 step: :func:`cell_step`
solves the error model of ``numerics.lattice._accuracy`` with the growth factor's own
constants (GROWTH_ERROR_CONSTANTS, measured by ``bench/calibrate_growth.py``) for a
relative growth error GROWTH_TOL (1%); a map takes one step for all its cells
(:func:`map_step`, at its fastest carrier) and records it in the store's attrs.

Verdict (probe 96): MI when the growth factor that exponential growth accounts for,
``growth_exponential`` (the factor, at most ``numerics.lattice.exponential_bound`` of the
records: exp(s L), s the log-slope over the linear stage's second half), exceeds the
threshold: a point's run verdict, on the same records. Algebraic (secular) growth, a
stable wave's near-degenerate pair exchanging amplitude near delta = 0, does not count:
before, a cell of such a run that grew past 20x read MI where ``flexmm point`` said "no
growth within T".

Early stop (the rule): the spectrum is recorded RECORDS times over the run; the run stops
at the first record where the factor so far exceeds the threshold and so does the
exponential bound of the records so far (the bound alone can fall later where growth
decelerates, but an exponential growth keeps its rate to the linear stage's end, after
which the bound is fixed). A verdict other than MI needs the whole run. The run is one
stepper advanced record by record (no re-built state between checks).
"""

from __future__ import annotations

import math

import numpy as np

from ..lattice import (
    GROWTH_THRESHOLD,
    RUN_REL_TOL,
    U_REFERENCE,
    BlowUpError,
    Material,
    Stepper,
    blowup_message,
    choose_step,
    dominant_frequency,
    exponential_bound,
    get_method,
    growth_rates,
    initial_condition,
    linear_stage,
    non_carrier_bins,
    snap_wavenumber,
    spectrum,
    spectrum_growth,
)

#: spectrum records over a run (every t_end / RECORDS): the growth factor's time resolution
RECORDS = 200
#: relative accuracy of the growth factor a map cell asks for (see GROWTH_ERROR_CONSTANTS)
GROWTH_TOL = 0.01
#: C_m of the growth factor's error model, e = C_m (w dt)^p (w T) as in ``_accuracy``
#: (w the starting state's dominant frequency; e the largest relative error of the growth
#: factor over the records), per method: the largest constant measured by
#: ``bench/calibrate_growth.py`` on 32 cells between those of the fig3-simulated grid (both
#: cases, N = 500, T = 5000; spread 2e-9 .. 1.6e-6 for srkn11b, the largest at near-resonant
#: case II cells). The largest are about the state's (``ERROR_CONSTANTS``), most cells' far
#: below (the spectrum's magnitudes do not see the carrier's phase error, which dominates
#: the state error); the big step comes from asking 1% of the growth factor.
GROWTH_ERROR_CONSTANTS = {"srkn11b": 1.6e-6, "srkn6b": 6.4e-5, "kahanli8": 8.9e-5}


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


def growth_of(t, theta_hat, U_hat, m, N, t_end: float | None = None) -> dict:
    """Largest growth factor over the records, which field and wavenumber carries it
    (the reading :func:`numerics.lattice.spectrum_growth` defines), and
    ``growth_exponential``: the factor exponential growth accounts for (at most
    ``exponential_bound``: algebraic growth does not count; a point's run verdict reads
    it). U's growth counts from its level at U_REFERENCE t_end (default t_end: the last
    record's time; a run stopped early passes its planned t_end, so the reference does not
    move)."""
    ratios, bins = _ratios(theta_hat, U_hat, m, N)
    stack = {f: r[None] for f, r in ratios.items()}
    growth, field, q = spectrum_growth(np.asarray(t), stack, bins, N, t_end)
    expo, _, _ = spectrum_growth(np.asarray(t), stack, bins, N, t_end, exponential=True)
    return {"growth": float(growth[0]), "growth_field": str(field[0]),
            "growth_q": float(q[0]), "growth_exponential": float(expo[0])}


def seed_majority(growths) -> bool:
    """The verdict of several seeds at one point (a map cell, ``measure_point``): MI when
    more than half of the seeds' growth factors exceed GROWTH_THRESHOLD (a tie is stable)."""
    return sum(g > GROWTH_THRESHOLD for g in growths) * 2 > len(growths)


def cell_verdict(growths, t_end: float) -> int:
    """A map cell's stored verdict (int8 code) from its seeds' exponential readings: the
    point's rule (``numerics.lattice.simulated_verdict``, ``measure_point``), so a map and
    a point never name one run differently. 1: MI (most seeds grew more than
    GROWTH_THRESHOLD); 0: no growth within T (the median stayed below its square root);
    -1: undetermined (it grew, less than the threshold: a longer run decides; or no
    finite growth factor). Before probe 97 the band between was stored 0, "stable"."""
    from ..lattice import simulated_verdict

    # t_end names the span in the verdict's text only: a run stopped at its first record
    # (t 0) or a NaN time must not make a cell an error
    t_end = float(t_end) if t_end > 0 and math.isfinite(t_end) else 1.0
    word = simulated_verdict(list(growths), t_end).word
    return {"MI": 1, "no growth within T": 0}.get(word, -1)


def cell_step(state, material: Material, case: str, t_end: float,
              growth_tol: float = GROWTH_TOL, methods=None) -> tuple[str, float]:
    """(method, dt) whose predicted relative error of the growth factor over ``t_end`` is
    ``growth_tol`` (the error model of ``_accuracy`` with GROWTH_ERROR_CONSTANTS), the
    cheapest of ``methods`` (default: every method with a constant)."""
    return choose_step(state, material, case, t_end, growth_tol, methods,
                       constants=GROWTH_ERROR_CONSTANTS)


def map_step(material_of, case: str, ks, N: int, t_end: float, amplitude: float,
             start: str = "paper", growth_tol: float = GROWTH_TOL,
             methods=None) -> tuple[str, float]:
    """One (method, dt) for every cell of a map: :func:`cell_step` at the grid's largest
    dominant frequency (the smallest step any of its cells needs). ``material_of`` is the
    list of the map's materials (one per delta), ``ks`` its carriers (snapped)."""
    best = None
    for mat in material_of:
        for k in ks:
            state = initial_condition(mat, case, N, k, amplitude, 0.0, 0, start)
            w = dominant_frequency(state)
            if best is None or w > best[0]:
                best = (w, mat, state)
    return cell_step(best[2], best[1], case, t_end, growth_tol, methods)


def simulate_cell(material: Material, case: str, k: float, N: int, t_end: float,
                  amplitude: float = 0.02, noise: float = 1e-3, seed: int = 0,
                  start: str = "paper", dt: float | None = None, method: str | None = None,
                  early_stop: bool = True, growth_tol: float = GROWTH_TOL) -> dict:
    """The simulated verdict at one cell (the scenes' criterion), with early stop.

    ``method`` and ``dt`` default to :func:`cell_step`'s choice for ``growth_tol``; the
    step used is t_end / (RECORDS n) for a whole n, so that records fall on steps.

    Returns the verdict (True = MI: ``growth_exponential`` above the threshold), the
    largest growth factor, its exponential reading and the field ("theta" or "U") and
    wavenumber carrying it, the time simulated, whether it stopped early, and the method
    and step used.
    """
    rec = cell_records(material, case, k, N, t_end, amplitude, noise, seed, start, dt,
                       method, early_stop, growth_tol)
    t, th_hat, U_hat, m = rec["t"], rec["theta_hat"], rec["U_hat"], rec["m"]
    g = growth_of(t, th_hat, U_hat, m, N, t_end)
    mi = bool(g["growth_exponential"] > GROWTH_THRESHOLD)  # a point's run verdict
    t_sim = float(t[-1])
    return {"verdict_simulated": mi, **g, "growth_q": float(g["growth_q"]),
            "peak_gain": measured_peak_gain(t, th_hat, m, N) if mi else float("nan"),
            "t_simulated": t_sim, "stopped_early": bool(t_sim < t_end * (1 - 1e-9)),
            "k": rec["k"], "method": rec["method"], "dt": rec["dt"]}


def cell_records(material: Material, case: str, k: float, N: int, t_end: float,
                 amplitude: float = 0.02, noise: float = 1e-3, seed: int = 0,
                 start: str = "paper", dt: float | None = None, method: str | None = None,
                 early_stop: bool = True, growth_tol: float = GROWTH_TOL,
                 stop_at: int | None = None) -> dict:
    """The spectrum records of a cell's run (what :func:`simulate_cell` measures): t,
    theta_hat, U_hat (None in case "rotation") up to the early stop (or record
    ``stop_at``), the carrier bin m and k, the method and step used."""
    ks, m = snap_wavenumber(k, N, rel_tol=RUN_REL_TOL, return_index=True)
    state = initial_condition(material, case, N, ks, amplitude, noise, seed, start)
    if dt is None:
        method, dt = cell_step(state, material, case, t_end, growth_tol,
                               None if method is None else [method])
    elif method is None:
        raise ValueError("give method with dt (or neither: both are chosen for growth_tol)")
    meth = get_method(method)
    record = t_end / RECORDS
    per_record = max(1, math.ceil(record / dt - 1e-9))
    dt_eff = record / per_record
    st = Stepper(state, material, case, meth, dt_eff)
    coupled = case == "coupled"
    nq = N // 2 + 1
    t = np.arange(RECORDS + 1) * record
    th_hat = np.empty((RECORDS + 1, nq))
    U_hat = np.empty((RECORDS + 1, nq)) if coupled else None
    mask = non_carrier_bins(m, N, "theta")
    mask_U = non_carrier_bins(m, N, "U")
    i0_U = int(np.searchsorted(t, U_REFERENCE * t_end))  # growth_of's reference record

    def take(j):
        th_hat[j] = spectrum(st.th)
        if coupled:
            U_hat[j] = spectrum(st.U)

    # the largest non-carrier component over the carrier per record (growth_of's top), and
    # its running maximum: the early stop's reading
    top_th = np.zeros(RECORDS + 1)
    top_U = np.zeros(RECORDS + 1)
    peak = [0.0, 0.0]  # theta's from record 0, U's from i0_U

    def passed(top, f, i0, j):
        """growth_of's exponential reading of records i0 .. j above the threshold (the
        bound, O(j), only once the factor has passed)."""
        return (top[i0] > 0 and peak[f] > GROWTH_THRESHOLD * top[i0]
                and exponential_bound(t[i0:j + 1], top[i0:j + 1]) > GROWTH_THRESHOLD)

    take(0)
    last = RECORDS if stop_at is None else min(stop_at, RECORDS)
    j = 0
    while j < last:
        done = st.advance(per_record)
        if done < per_record:
            time = j * record + done * dt_eff
            raise BlowUpError(blowup_message(time, dt_eff, material, case, meth),
                              time=time)
        j += 1
        take(j)
        if not early_stop:
            continue
        # the exponential reading so far (growth_of's, on the records so far): MI as soon
        # as it exceeds the threshold (the module's rule)
        for i in (0, j) if j == 1 else (j,):
            top_th[i] = th_hat[i, mask].max() / th_hat[i, m]
            peak[0] = max(peak[0], top_th[i])
            if coupled:
                top_U[i] = U_hat[i, mask_U].max() / th_hat[i, m]
                if i >= i0_U:
                    peak[1] = max(peak[1], top_U[i])
        if passed(top_th, 0, 0, j) or coupled and j > i0_U and passed(top_U, 1, i0_U, j):
            break
    n = j + 1
    return {"t": t[:n], "theta_hat": th_hat[:n], "U_hat": U_hat[:n] if coupled else None,
            "m": m, "k": ks, "method": meth.name, "dt": dt_eff}


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
    from ..theory import NoPlaneWaveError, predict_growth

    try:
        p = predict_growth(material, case, k, amplitude, start=start, N=N, t_end=t_end,
                           seed=0, noise=noise, draws=seeds - 1)
    except NoPlaneWaveError:
        status, p = "no plane wave", None
    except ArithmeticError:  # the launched state is not a torus: no linear theory
        status, p = "not quasi-periodic", None
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


__all__ = ["simulate_cell", "cell_records", "cell_step", "map_step", "growth_of", "seed_majority",
           "cell_verdict",
           "measured_peak_gain", "predict_cell", "PREDICTED_STATUS"]
