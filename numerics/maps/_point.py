"""MI at one point of a material: the theories' gain curves over the sideband offsets, the
growth factor predicted from the initial state, and (``simulate=True``) the measured sigma(q)
and verdict, with a map cell's step choice and seed-majority verdict.

``measure_point`` is ``flexmm point`` without the command line: the command prints and
writes what it returns (``point.json`` is :meth:`PointResult.as_dict`). It takes every kind
of point by its type (``POINT_KINDS``): a Material here, a lattice model's
``ModelPointSpec`` (``_model_point``, which registers itself).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field, fields

import numpy as np

from common import paper

from ..lattice import (
    GROWTH_THRESHOLD,
    LINEAR_STAGE_RULE,
    Material,
    band_summary,
    checks,
    grows_beyond_threshold,
    initial_condition,
    paper_start_undefined,
    run_length,
    shortest_run_error,
    simulated_verdict,
    snap_wavenumber,
)
from ..lattice import simulate as simulate_chain
from ..theory import (
    EXACT_LATTICE,
    MAX_AMPLITUDE,
    PAPER_START,
    THEORIES,
    NoPlaneWaveError,
    measure_gain,
    nls_coefficients,
    nls_undefined,
    predict_growth,
    theory_gain,
)
from ._cells import cell_step, growth_of
from ._point_exact import START_CURVE_POINTS, _start_grid, refine_band

#: sideband offsets Q = |q - k| searched for the theories' bands (lattice units): the
#: whole zone, as the map searches it (sidebands k + Q beyond pi fold back, k - Q below 0
#: too: a band at any offset is found, whatever k)
Q_GRID = np.linspace(0, math.pi, 3001)
#: a simulated point records its spectrum every SAVE_EVERY T (and predicts those records)
SAVE_EVERY = 5.0
#: the NLS theories' small parameter (their formulas take the paper's eps, A0)
EPS = paper.EPS
#: the most seeds a point simulates, and the longest run (T)
MAX_SEEDS = 1000
MAX_T_END = 1e7
#: the chain sizes simulate and predict_growth accept
N_RANGE = (8, 10**6)


@dataclass(frozen=True)
class PointResult:
    """What ``measure_point`` found at one point; ``as_dict()`` is ``point.json``.

    The fields with ``json`` metadata False stay out of the JSON (objects and arrays the
    command prints or plots from).

    Attributes
    ----------
    material : Material
    case : str                  "rotation" (case I) or "coupled" (case II)
    N, m : int                  the chain and the carrier's mode: k = 2 pi m / N
    k, k_requested : float      the carrier (snapped to the chain) and the k asked for
    amplitude : float           peak rotation of the plane wave (rad), 2 eps A0
    eps, A0 : float             the NLS theories' small parameter and envelope amplitude
    start : str                 "paper" (eq. `IC`) or "travelling"
    semidiscrete_nls : dict     omega, v_g, g1, g2, g of the semi-discrete NLS at k
    theories : dict             {theory: offset, q, curve (ndarray, shape (nQ,)), verdict,
                                peak_gain, peak_offset, band_edge[, reason][,
                                grows_beyond_threshold_within_t_end]}
    predicted : dict            the growth factor per seed from the linear response of
                                each seed's initial state, its verdict (or the reason none)
    simulated : dict or None    the measured verdict, band and sigma(q) (``simulate=True``)
    t_end : float               the run length the verdicts answer for (T)
    exact_theory : str          the exact theory's name for this start
    prediction : GrowthPrediction or None
    measured : dict or None     ``measure_gain``'s sigma(q), with sigma_by_offset
    growths : list of dict      each seed's growth factor, field and wavenumber
    length : RunLength          how T was chosen from the fastest predicted rate
    """

    material: Material
    case: str
    N: int
    m: int
    k: float
    k_requested: float
    amplitude: float
    eps: float
    A0: float
    start: str
    semidiscrete_nls: dict
    theories: dict
    predicted: dict
    simulated: dict | None = None
    t_end: float = field(default=math.nan, metadata={"json": False})
    exact_theory: str = field(default=EXACT_LATTICE.label, metadata={"json": False})
    prediction: object = field(default=None, metadata={"json": False})
    measured: dict | None = field(default=None, metadata={"json": False})
    growths: list | None = field(default=None, metadata={"json": False})
    length: object = field(default=None, metadata={"json": False})

    def to_xarray(self):
        """The gain curves as an ``xarray.Dataset``: ``gain_<theory>`` over its own
        ``offset_<theory>`` (each theory samples its offsets), ``gain_simulated`` (and its
        spread) over the ring's offsets when simulated; units and each theory's verdict and
        peak gain in the variables' attrs, the inputs (material, case, N, k, amplitude,
        start, T) and the simulated verdict in the dataset's. ``.to_netcdf(path)`` keeps it.

        Returns
        -------
        xarray.Dataset
        """
        return point_to_xarray(self)

    def as_dict(self, units: dict | None = None) -> dict:
        """The JSON fields in order (arrays as lists, ``simulated`` only when simulated),
        with ``units`` (what the numbers are in) after ``start``."""
        out = {}
        for f in fields(self):
            value = getattr(self, f.name)
            if f.metadata.get("json", True) is False or (f.name == "simulated" and value is None):
                continue
            if f.name == "material":
                value = {"alpha": value.alpha, "K_s": value.K_s, "K_theta": value.K_theta,
                         "delta": value.delta}
            elif f.name == "theories":
                value = {n: {key: (v.tolist() if isinstance(v, np.ndarray) else v)
                             for key, v in t.items()} for n, t in value.items()}
            out[f.name] = value
            if f.name == "start" and units is not None:
                out["units"] = units
        return out


def _theory_key(label: str) -> str:
    """A variable-name-safe key of a theory's label (its record's key, with the start)."""
    import re

    return re.sub(r"[^0-9a-zA-Z]+", "_", label).strip("_").lower()


def point_to_xarray(res: PointResult):
    """``PointResult.to_xarray``: see there."""
    import xarray as xr

    data, coords = {}, {}
    for label, t in res.theories.items():
        key = _theory_key(label)
        dim = f"offset_{key}"
        coords[dim] = (dim, np.asarray(t["offset"], float),
                       {"long_name": f"sideband offset from the carrier k ({label})",
                        "units": "rad per site"})
        data[f"gain_{key}"] = (dim, np.asarray(t["curve"], float), {
            "long_name": f"growth rate sigma(q): {label}", "units": "1/T (lattice time)",
            "theory": label, "verdict": t["verdict"],
            "peak_gain": float(t["peak_gain"]) if t["peak_gain"] is not None else math.nan})
    if res.measured is not None:
        coords["offset_simulated"] = ("offset_simulated",
                                      np.asarray(res.measured["offset"], float),
                                      {"long_name": "sideband offset from k (the ring's)",
                                       "units": "rad per site"})
        for name, values, what in (("gain_simulated", "sigma_by_offset", "measured sigma(q)"),
                                   ("gain_simulated_std", "std_by_offset",
                                    "its spread over the seeds and windows")):
            data[name] = ("offset_simulated", np.asarray(res.measured[values], float),
                          {"long_name": what, "units": "1/T (lattice time)"})
    m = res.material
    attrs = {"alpha": m.alpha, "K_s": m.K_s, "K_theta": m.K_theta, "delta": m.delta,
             "case": res.case, "N": res.N, "m": res.m, "k": res.k,
             "k_requested": res.k_requested, "amplitude": res.amplitude, "start": res.start,
             "t_end": res.t_end, "units": "lattice units: time T, wavenumbers rad per site"}
    if res.simulated is not None:
        attrs["verdict_simulated"] = res.simulated["verdict"]
        attrs["verdict_simulated_text"] = res.simulated.get("text", "")
    return xr.Dataset(data, coords=coords, attrs=attrs)


def fold(q):
    """Wavenumbers folded into [0, pi] (a real field's q and -q, q and q + 2 pi, are one)."""
    return np.abs((np.asarray(q, float) + math.pi) % (2 * math.pi) - math.pi)


def offset_curve(q, sigma, spread, k):
    """A measured sigma over the rfft bins q (0 .. pi) as a curve over the sideband offset
    Q = 1 .. N/2 bins: a pair grows only where both its sidebands do, so sigma(Q) is the
    smaller of sigma at its two bins, fold(k + Q) and |k - Q|. A bin is shared by two
    pairs (k + Q beyond pi folds back onto another pair's sideband); the minimum keeps
    each band at its own offset, whatever k. Returns Q, sigma(Q) and the ``spread`` (per
    bin) of the bin that gave the minimum."""
    q, sigma = np.asarray(q, float), np.asarray(sigma, float)
    dq, top = q[1] - q[0], q.size - 1
    m = int(round(k / dq))
    d = np.arange(1, top + 1)
    N = int(round(2 * math.pi / dq))
    upper = np.where(m + d <= top, m + d, N - (m + d))  # fold(k + Q) into [0, pi]
    lower = np.abs(m - d)
    pick = np.where(sigma[upper] <= sigma[lower], upper, lower)
    return d * dq, sigma[pick], np.asarray(spread, float)[pick]


def _undefined(Q, q, curve, reason) -> dict:
    return {"offset": Q, "q": q, "curve": curve, "verdict": "undefined", "reason": reason,
            "peak_gain": float("nan"), "peak_offset": float("nan"), "band_edge": float("nan")}


def theory_curves(material, case, k, amplitude, start="travelling", N=None) -> dict:
    """{theory: curve over Q_GRID, band summary, verdict}: the paper NLS, the semi-discrete
    NLS, and the exact lattice theory for ``start`` (the travelling wave; with "paper" the
    state eq. `IC` launches, on START_CURVE_POINTS offsets). The exact curve's peak and
    edge are resolved (:func:`refine_band`); given ``N``, its peak is the fastest pair a
    ring of N sites carries (where one grows; else the infinite chain's, and the point's
    note says no ring mode grows)."""
    A0 = amplitude / (2 * EPS)
    names = THEORIES if start == "travelling" else THEORIES[:2] + (PAPER_START,)
    out = {}
    for th in names:
        try:
            Q = Q_GRID if th != PAPER_START else _start_grid(material, case, k, amplitude)
            q = fold(k + Q)  # the upper sideband's wavenumber (k + Q beyond pi folds)
            with np.errstate(all="ignore"):
                curve = theory_gain(th, material, case, k, offset=Q, eps=EPS, A0=A0)
        except ArithmeticError as exc:  # no plane wave (a resonance), or a launched state
            # no linear theory applies to (``_torus``): say which, no verdict
            why = f"no plane wave: {exc}" if isinstance(exc, NoPlaneWaveError) else str(exc)
            out[th] = _undefined(Q, q, np.full(q.shape, np.nan), why)
            continue
        if not np.all(np.isfinite(curve)):  # no real omega, g1 = 0 or a resonance
            why = (nls_undefined(th, material, case, k) if th in THEORIES[:2] else None) \
                or "a singular gain curve"
            out[th] = _undefined(Q, q, curve, why)
            continue
        ring_peak = None
        if th not in THEORIES[:2]:  # the exact theories: a grid value is not the band's peak
            with np.errstate(all="ignore"):
                Q, curve, ring_peak = refine_band(
                    lambda x, th=th: theory_gain(th, material, case, k, offset=x, eps=EPS,
                                                 A0=A0), Q, curve, N)
            q = fold(k + Q)
        s = band_summary(k + Q, curve, k)  # over the offsets (band_summary: q - k)
        if ring_peak is not None and ring_peak[0] > 0:  # the fastest pair the ring carries
            s.update(peak_gain=ring_peak[0], peak_offset=ring_peak[1])
        out[th] = {"offset": Q, "q": q, "curve": curve,
                   "verdict": "MI" if s["peak_gain"] > 0 else "stable", **s}
    return out


def snap_carrier(k_requested: float, N: int, names=("k", "N")):
    """k on a periodic chain of N sites: the nearest 2 pi m / N, whatever k was typed;
    ``names`` are the ones an error message gives k and N (a command's options)."""
    k_requested = checks.real(names[0], k_requested, 0.0, math.pi)
    N = checks.integer(names[1], N, *N_RANGE)  # the bounds of simulate and predict_growth
    return snap_wavenumber(k_requested, N, return_index=True)


def point_step(material, case, N, k, amplitude, start, t_end) -> tuple[str, float]:
    """(method, dt) of a simulated point: ``cell_step``, a map cell's choice from the
    accuracy the growth factor needs over t_end (not the paper's RK4 at dt = 0.05, too
    coarse for stiff materials), the step then a whole fraction of the SAVE_EVERY T between
    records."""
    method, dt = cell_step(initial_condition(material, case, N, k, amplitude, 1e-3, 0, start),
                           material, case, t_end)
    return method, SAVE_EVERY / math.ceil(SAVE_EVERY / dt - 1e-9)


def _predicted(material, case, k, amplitude, start, N, t_end, seeds):
    """(GrowthPrediction or None, the JSON's "predicted"): the growth factor the simulation
    measures, predicted from each seed's initial state (records every SAVE_EVERY T, as a
    simulated point saves them)."""
    try:
        pred = predict_growth(material, case, k, amplitude, start=start, N=N, t_end=t_end,
                              seed=0, draws=seeds - 1,
                              records=max(2, min(4000, int(round(t_end / SAVE_EVERY)))))
    except ArithmeticError as exc:
        return None, {"growth": None, "verdict": "undefined",
                      "reason": str(exc).splitlines()[0]}
    predicted = [pred.growth, *pred.growth_draws.tolist()]
    # the verdict, as the runs': exponential growth only (the linear response of a stable
    # wave's beating modes can grow algebraically past 20x)
    return pred, {
        "growth": predicted, "verdict": simulated_verdict(pred.exponential, t_end).word,
        "growth_exponential": pred.exponential.tolist(),
        "t_end": t_end, "seeds": seeds, "rate": pred.rate,
        "linear": pred.linear, "approximate": pred.approximate,
        "method": "linear response of each seed's initial state (numerics.theory."
                  "predict_growth)"}


def _simulated(material, case, k, amplitude, start, N, t_end, seeds, on_estimate=None,
               figure=True):
    """(the JSON's "simulated", measure_gain's sigma(q) or None, each seed's growth): the
    seeds run with a map cell's step and judged by its seed majority; ``on_estimate``
    is called with their ``PointEstimate`` before they start."""
    runs = []

    def sim(**kw):
        run = simulate_chain(**kw)
        runs.append(run)
        return run

    method, dt = point_step(material, case, N, k, amplitude, start, t_end)
    if on_estimate is not None:
        from ._paper_point_estimate import estimate_paper_point

        on_estimate(estimate_paper_point(material, case, k, amplitude, N=N, start=start,
                                         t_end=t_end, seeds=seeds, method=method, dt=dt,
                                         save_every=SAVE_EVERY, figure=figure))
    meas = measure_gain(sim, range(seeds), material=material, case=case, N=N, k=k,
                        amplitude=amplitude, t_end=t_end, method=method, dt=dt,
                        save_every=SAVE_EVERY, start=start, progress=None,
                        energy_tolerance=1.0)
    growths = [growth_of(r.t, r.theta_hat, r.U_hat, r.m, r.N) for r in runs]
    # no seed with a linear stage (linear_stage's rule): no rate to fit, shown as "-",
    # not as a gain of 0
    if meas:  # sigma over the offset Q, once: the table, the JSON and the figure
        meas["offset"], meas["sigma_by_offset"], meas["std_by_offset"] = offset_curve(
            meas["q"], meas["sigma"], meas["sigma_std"], k)
    s = band_summary(k + meas["offset"], meas["sigma_by_offset"], k) if meas else \
        {"peak_gain": float("nan"), "peak_offset": float("nan"), "band_edge": float("nan"),
         "no_rate": f"no seed had a linear stage to fit a rate over ({LINEAR_STAGE_RULE})"}
    # the verdict counts exponential growth only (``exponential_bound``), as a model's
    # runs do: near delta = 0 a stable wave's run grew 35x within T = 40000, algebraically
    sv = simulated_verdict([g["growth_exponential"] for g in growths], t_end,
                           s["peak_gain"])
    algebraic = [g for g in growths
                 if g["growth"] > GROWTH_THRESHOLD >= g["growth_exponential"]]
    if algebraic:
        s["note"] = (
            f"{len(algebraic)} of {len(growths)} runs grew past {GROWTH_THRESHOLD:g}x "
            f"({_listed(g['growth'] for g in algebraic)}) but not exponentially: the "
            "log-slope over the second half of the linear stage accounts for "
            f"{_listed(g['growth_exponential'] for g in algebraic)} (algebraic, secular "
            "growth, no instability; numerics.lattice.exponential_bound)")
        if sv.word != "MI":  # the fitted sigma(q) is that growth's, no instability's
            s["peak_gain"] = float("nan")
    simulated = {**s, **sv.to_dict(), "t_end": t_end,
                 "growth_exponential": [g["growth_exponential"] for g in growths],
                 "seeds": seeds, "method": method, "dt": dt,
                 "growth": [g["growth"] for g in growths],
                 "growth_field": [g["growth_field"] for g in growths],
                 "criterion": f"MI when most seeds' largest non-carrier theta or U component "
                              f"grows more than {GROWTH_THRESHOLD:g}x within t_end; no growth "
                              f"within T below sqrt({GROWTH_THRESHOLD:g})x; undetermined "
                              "between",
                 "peak_gain": s["peak_gain"],
                 **({"q": meas["q"].tolist(), "sigma": meas["sigma"].tolist(),
                     "sigma_std": meas["sigma_std"].tolist(),
                     "offset": meas["offset"].tolist(),
                     "sigma_by_offset": meas["sigma_by_offset"].tolist()} if meas else {})}
    return simulated, meas, growths


def _listed(values) -> str:
    return ", ".join(f"{v:.3g}x" for v in values)


#: the kinds of point ``measure_point`` takes: {the point's type: its measure(point, ...)}
POINT_KINDS: dict = {}


def register_point_kind(kind: type, measure) -> None:
    """``measure_point(point, ...)`` of a ``kind`` is ``measure(point, ...)``: a kind of
    point answers the one entry point, as a map kind answers ``run_map``."""
    POINT_KINDS[kind] = measure


def measure_point(material, *args, **kwargs):
    """MI at one point: the theories, and (``simulate``) the runs that check them.

    ``material`` picks the kind of point (``POINT_KINDS``): a ``Material`` (the paper's
    chain; the parameters below) or a ``ModelPointSpec`` (any lattice model; the keywords
    ``on_estimate`` and ``estimate_figure`` only, see ``measure_model_point``: returns a
    ``ModelPoint``).

    Parameters
    ----------
    material : Material or ModelPointSpec
    case, k, amplitude, N, start, simulate, t_end, seeds, on_estimate, estimate_figure
        A Material's point: see ``_measure_material`` (below).

    Returns
    -------
    PointResult or ModelPoint
    """
    for kind, measure in POINT_KINDS.items():
        if isinstance(material, kind):
            return measure(material, *args, **kwargs)
    return _measure_material(material, *args, **kwargs)  # its check names what it takes


def _measure_material(material: Material, case: str, k: float,
                      amplitude: float = paper.AMPLITUDE, *, N: int = paper.N,
                      start: str = "paper", simulate: bool = False,
                      t_end: float | None = None, seeds: int = 4, on_estimate=None,
                      estimate_figure: bool = True) -> PointResult:
    """MI at one point: the three theories, the predicted growth and (``simulate``) the run.

    Parameters
    ----------
    material : Material
    case : {"rotation", "coupled"}
        Case I (U = 0) or case II (U and theta).
    k : float
        Carrier wavenumber (rad per site) in (0, pi), snapped to the nearest 2 pi m / N.
    amplitude : float
        Peak rotation of the plane wave (rad), the paper's 2 eps A0.
    N : int
        Sites of the periodic chain.
    start : {"paper", "travelling"}
        Eq. `IC` (U at rest) or the exact travelling wave.
    simulate : bool
        Also run ``seeds`` noisy chains (a map cell's method and step, ``point_step``) and
        measure sigma(q) and the growth factor; the verdict is the seeds' majority
        (``seed_majority``, as in a map cell).
    t_end : float, optional
        Run length (T); default ``run_length`` of the exact peak gain (enough e-foldings
        to decide, within a cap).
    seeds : int
        Noise seeds of the prediction and the simulation.
    on_estimate : callable, optional
        Called with the runs' ``PointEstimate`` before they start (``estimate_figure``:
        the figure counted), as a model point's.

    Returns
    -------
    PointResult
        With ``simulate``, each theory also carries
        ``grows_beyond_threshold_within_t_end`` (an observable, not its verdict); the
        simulated verdict is ``numerics.lattice.simulated_verdict``'s: MI, no growth
        within T, or undetermined. ``length`` says how T was chosen (``run_length``).
    """
    checks.instance("material", material, Material)
    amplitude = checks.real("amplitude", amplitude, 0.0, MAX_AMPLITUDE)
    k_requested = k
    k, m = snap_carrier(k, N)
    seeds = checks.integer("seeds", seeds, 1, MAX_SEEDS)
    if t_end is not None:
        checks.real("t_end", t_end, 0.0, MAX_T_END)
    if start == "paper" and (why := paper_start_undefined(material, k, ("travelling",))):
        raise ValueError(f"start='paper': {why}")
    co = nls_coefficients(material, k, amplitude)["semi-discrete"]
    th = theory_curves(material, case, k, amplitude, start, N)
    exact_name = EXACT_LATTICE.label if start == "travelling" else PAPER_START
    exact = th[exact_name]["peak_gain"]
    # T from the fastest predicted rate: enough e-foldings to decide, within a stated cap
    length = run_length(exact if math.isfinite(exact) else 0.0)
    t_end = t_end or length.t_end
    if short := shortest_run_error("--t-end", t_end, [(material, k)], case):
        raise ValueError(short)
    prediction, predicted = _predicted(material, case, k, amplitude, start, N, t_end, seeds)
    simulated = meas = growths = None
    if simulate:
        simulated, meas, growths = _simulated(material, case, k, amplitude, start, N, t_end,
                                              seeds, on_estimate, estimate_figure)
        # the theories keep their physical verdict; "grows 20x within T" is an observable
        for t in th.values():
            t["grows_beyond_threshold_within_t_end"] = (
                bool(grows_beyond_threshold(t["peak_gain"], t_end))
                if math.isfinite(t["peak_gain"]) else None)
    return PointResult(
        material=material, case=case, N=N, m=m, k=k, k_requested=k_requested,
        amplitude=amplitude, eps=EPS, A0=amplitude / (2 * EPS), start=start,
        semidiscrete_nls={"omega": co["omega"], "v_g": co["v_g"], "g1": co["g1"],
                          "g2": co[case]["g2"], "g": co[case]["g"]},
        theories=th, predicted=predicted, simulated=simulated, t_end=t_end,
        exact_theory=exact_name, prediction=prediction, measured=meas, growths=growths,
        length=length)


register_point_kind(Material, _measure_material)

__all__ = ["PointResult", "measure_point", "POINT_KINDS", "register_point_kind", "point_step", "theory_curves", "offset_curve", "fold",
           "snap_carrier", "MAX_SEEDS", "MAX_T_END", "Q_GRID", "SAVE_EVERY", "START_CURVE_POINTS"]
