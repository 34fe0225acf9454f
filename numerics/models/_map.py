"""MI maps of any model over two of its parameters, or one parameter and the carrier k."""

from __future__ import annotations

import math

import numpy as np

from energy import Model, ModelError

from ._map_cells import _map_cell, lossy_runs

AXIS_K = "k"


def _axis(model: Model, name: str, values) -> np.ndarray:
    if name != AXIS_K and name not in model.lattice.parameters:
        raise ModelError(f"map axis {name!r} is neither 'k' nor a parameter of model "
                         f"{model.name!r} ({', '.join(model.lattice.parameters)})")
    if isinstance(values, (str, bytes)) or any(
            isinstance(x, (bool, np.bool_, str, bytes)) for x in np.ravel(
                np.asarray(values, dtype=object))):
        raise ModelError(f"map axis {name} needs real numbers, got {values!r}")
    try:
        v = np.asarray(values, dtype=float)
    except (TypeError, ValueError):
        raise ModelError(f"map axis {name} needs real numbers, got {values!r}") from None
    if v.ndim != 1:  # before: "needs finite values" for a finite 2-D list
        raise ModelError(f"map axis {name} needs a 1-D list of values, got an array of "
                         f"shape {v.shape}")
    if v.size == 0 or not np.all(np.isfinite(v)):
        raise ModelError(f"map axis {name} needs finite values, got {values!r}")
    if name == AXIS_K and (v.min() <= 0 or v.max() > math.pi):
        raise ModelError(f"k must be in (0, pi], got {v.min():g}..{v.max():g}")
    return v


def model_map(model: Model, x: tuple, y: tuple, amplitude: float, k: float | None = None,
              branch=None, exact=None, cell=None, done=None, on_cell=None,
              progress: bool | None = False):
    """Theory MI map of ``model`` over two axes.

    Parameters
    ----------
    model : energy.Model
    x, y : (str, array)
        Axis name (``"k"`` or a parameter of the model) and its values.
    amplitude : float
        Carrier amplitude a (first harmonic of its field).
    k : float, optional
        The carrier wavenumber when neither axis is ``"k"``.
    branch : int or str, optional
    exact : callable, optional
        ``exact(model, k, amplitude, branch) -> (verdict, peak_gain)``: adds the exact
        lattice columns.
    cell : callable, optional
        ``cell(model, k, amplitude, branch) -> dict``: more columns per cell (a simulation:
        :func:`simulated_cell`); its keys name them.
    done, on_cell : optional
        ``done[(i, j)]``: a cell's ``cell`` columns computed before (a resumed map), not
        computed again; ``on_cell(i, j, columns)`` after each cell computed (a journal).
    progress : bool or None
        A progress bar over the cells (None: where stderr is a terminal).

    Returns
    -------
    xarray.Dataset
        ``verdict_semidiscrete`` ("MI", "stable", "undefined"), ``peak_gain_semidiscrete``
        (1/time), ``g1``, ``g2``, ``reason`` (why undefined), and the exact columns when
        asked; dims (y, x) named after the axes; model, parameters and amplitude in attrs.
        A lossy model's NLS verdict is physical ("stable" where no sideband outgrows its
        damping at t = 0, as ``map_cells``'); its peak gain the lossless rate.
    """
    import xarray as xr

    from energy import check_value

    amplitude = check_value("amplitude", amplitude)
    if amplitude <= 0:
        raise ModelError(f"amplitude must be > 0, got {amplitude!r}")
    if k is not None:
        k = float(_axis(model, AXIS_K, [k])[0])
    for axis in (x, y):  # (name, values): a bare name once failed inside _axis's call
        if not (isinstance(axis, tuple) and len(axis) == 2 and isinstance(axis[0], str)):
            raise ModelError(f"a map axis is a (name, values) pair such as ('k', [1.0, 2.0]), "
                             f"got {axis!r}")
    if AXIS_K in (x[0], y[0]) and AXIS_K in model.params:  # the carrier's or the parameter's?
        raise ModelError("map axis 'k' is ambiguous: the model has a parameter named 'k' "
                         "(the carrier's wavenumber is the axis 'k'); rename it in the model "
                         "file to sweep one of them")
    xn, xv = x[0], _axis(model, *x)
    yn, yv = y[0], _axis(model, *y)
    if xn == yn:
        raise ModelError(f"the two map axes must differ, got {xn!r} twice")
    if AXIS_K not in (xn, yn) and k is None:
        raise ModelError("give k (the carrier) when neither map axis is 'k'")
    if AXIS_K in (xn, yn) and k is not None:  # before: k = 1.0 dropped without a word
        raise ModelError(f"k = {k:g} given and 'k' is a map axis: give one of them")
    from ._linear import branch_index

    k0 = xv[0] if xn == AXIS_K else (yv[0] if yn == AXIS_K else k)
    branch_index(model, k0, branch)  # an impossible branch is the caller's, not each cell's
    shape = (yv.size, xv.size)
    verdict = np.empty(shape, dtype=object)
    reason = np.empty(shape, dtype=object)
    peak, g1, g2 = (np.full(shape, np.nan) for _ in range(3))
    ex_verdict = np.empty(shape, dtype=object)
    ex_peak = np.full(shape, np.nan)
    extra: dict = {}
    done = done or {}
    from common.progress import progress_class
    tqdm = progress_class()

    bar = tqdm(total=verdict.size, unit="cell", desc="model map",
               disable=None if progress is None else not progress)
    for i, yy in enumerate(yv):
        for j, xx in enumerate(xv):
            bar.update(1)
            vals = {n: v for n, v in ((xn, xx), (yn, yy)) if n != AXIS_K}
            kk = {xn: xx, yn: yy}.get(AXIS_K, k)
            m = model.with_params(**vals)
            if cell is not None:
                cols = done.get((i, j))
                if cols is None:
                    cols = cell(m, kk, amplitude, branch)
                    if on_cell is not None:
                        on_cell(i, j, cols)
                for name, v in cols.items():
                    if name not in extra:
                        extra[name] = np.full(shape, np.nan) if isinstance(
                            v, (int, float)) or v is None else np.full(shape, "", dtype=object)
                    extra[name][i, j] = np.nan if v is None else v
            # the NLS columns as a map task computes them (map_cells)
            row = _map_cell(m, kk, amplitude, branch)
            verdict[i, j], reason[i, j] = row["verdict_semidiscrete"], row["reason"]
            if not row["carrier"]:  # no carrier on this branch at these values
                ex_verdict[i, j] = "undefined"
                continue
            peak[i, j], g1[i, j], g2[i, j] = (row["peak_gain_semidiscrete"], row["g1"],
                                              row["g2"])
            if exact is not None:
                ex_verdict[i, j], ex_peak[i, j] = exact(m, kk, amplitude, branch)
    bar.close()
    undefined = {"undefined", "undetermined", "", "nan", "None"}
    if all(str(v) in undefined for v in verdict.flat) and (exact is None or all(
            str(v) in undefined for v in ex_verdict.flat)) and all(
            str(v) in undefined for name, arr in extra.items()
            if name.startswith("verdict_") for v in arr.flat):
        why = next((str(r) for r in reason.flat if r), "no theory has a verdict")
        raise ModelError(f"every cell of the map is undefined (first cell: {why}); "
                         "change the axes, k, the amplitude or --branch")
    dims = (yn, xn)
    data = {
        "verdict_semidiscrete": (dims, verdict.astype(str),
                                 {"long_name": "semi-discrete NLS verdict"}),
        "peak_gain_semidiscrete": (dims, peak, {"units": "1/time (lattice units)"}),
        "g1": (dims, g1, {"long_name": "d^2 omega/dk^2"}),
        "g2": (dims, g2, {"long_name": "NLS nonlinear coefficient (mean flow included)"}),
        "reason": (dims, reason.astype(str), {"long_name": "why a verdict is undefined"}),
    }
    if exact is not None:
        data["verdict_exact"] = (dims, ex_verdict.astype(str),
                                 {"long_name": "exact lattice verdict"})
        data["peak_gain_exact"] = (dims, ex_peak, {"units": "1/time (lattice units)"})
    for name, arr in extra.items():
        data[name] = (dims, arr.astype(str) if arr.dtype == object else arr,
                      {"units": "1/time (lattice units)"} if "gain" in name else {})
    attrs = {"model": model.name, "model_hash": model.lattice.content_hash,
             "amplitude": float(amplitude), "branch": "" if branch is None else str(branch)}
    attrs.update({f"param_{p}": v for p, v in model.params.items() if p not in (xn, yn)})
    if k is not None and AXIS_K not in (xn, yn):
        attrs["k"] = float(k)
    coords = {xn: (xn, xv, {"units": "rad/site"} if xn == AXIS_K else {}),
              yn: (yn, yv, {"units": "rad/site"} if yn == AXIS_K else {})}
    return xr.Dataset(data, coords=coords, attrs=attrs)


def simulated_cell(model: Model, k: float, amplitude: float, branch=None, *, N: int = 256,
                   seeds: int = 1, t_end: float | None = None) -> dict:
    """One simulated map cell: the exact lattice theory on the ring of N sites and seeded
    runs from its exact wave, as ``point --model --simulate`` does (``run_length`` of the
    exact rate unless ``t_end``): verdict_exact, peak_gain_exact, verdict_simulated (MI,
    "no growth within T", "undetermined"; "undefined" without a travelling wave) and
    peak_gain_simulated (the seeds' median rate where MI; with no growth within T, the
    bound ln(threshold) / T the rate lies below); for a lossy model also the runs'
    amplification columns (``lossy_runs``). A run that blew up (the state left the
    lattice's range) leaves verdict_simulated "undetermined"."""
    from numerics.lattice import BlowUpError

    from ._reach import exact_gain_checked
    from ._seeds import simulate_seeds

    try:  # the energy not real along the wave: undefined, as without a travelling wave
        spec = exact_gain_checked(model, k, amplitude, branch, N=N)
    except ModelError:  # no travelling wave here: nothing to launch or measure from
        return {"verdict_exact": "undefined", "peak_gain_exact": None,
                "verdict_simulated": "undefined", "peak_gain_simulated": None}
    if model.lossy:  # issue 42: the runs' amplification, launched as a point's
        from ._losses import exact_amplification

        try:
            peak = exact_amplification(model, k, amplitude, branch, N=N,
                                       first=spec).amplification_time
        except ModelError:  # no peak time: the cap from the exact rate alone
            peak = None
        sim, amp = lossy_runs(model, k, amplitude, spec, branch=branch, N=N, seeds=seeds,
                              t_end=t_end, peak_time=peak)
    else:
        try:
            sim, amp = simulate_seeds(model, k, amplitude, spec, branch=branch, N=N,
                                      seeds=seeds, t_end=t_end, until_saturated=True), {}
        except BlowUpError:  # the state left the lattice's range: no MI verdict from it
            return {"verdict_exact": spec.verdict, "peak_gain_exact": spec.peak_gain,
                    "verdict_simulated": "undetermined", "peak_gain_simulated": None}
    rate = sim.verdict.map_rate
    return {"verdict_exact": spec.verdict, "peak_gain_exact": spec.peak_gain,
            "verdict_simulated": sim.verdict.word,
            "peak_gain_simulated": rate if math.isfinite(rate) else None, **amp}
