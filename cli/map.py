"""`flexmm map`: read the command line, check all of it (nothing is written on bad
input), run the map (``numerics.maps.run_map``), write its figure and summary."""

from __future__ import annotations

import json
import math
from pathlib import Path

from common.output import check_output, prepare_output, strict_json
from common.text import duration as _duration
from common.text import plural
from numerics.lattice import GROWTH_THRESHOLD, checks
from numerics.maps import (
    AGREEMENT_MARGIN,
    MapParameters,
    agreement,
    local_cores,
    parse_spec,
    run_map,
)
from numerics.theory import MAP_COLUMNS

from ._map_shares import mi_fraction as _mi_fraction

#: a map of more cells than this is refused (its theory columns alone fill memory)
MAX_CELLS = 250_000
#: a simulated map estimated to take longer than this needs --yes
CONFIRM_SECONDS = 3600.0




#: MapParameters' field names -> the map command's options, for its error messages
_OPTIONS = {"N": "--N", "t_end": "--t-end", "seeds": "--seeds", "amplitude": "--amplitude",
            "block": "--block", "k": "--k", "delta": "--delta", "case": "--case",
            "start": "--start", "alpha": "--alpha", "K_s": "--K-s", "K_theta": "--K-theta"}


def _as_option(message: str) -> str:
    """A MapParameters message with its leading field name as the option's."""
    import re

    m = re.match(r"([A-Za-z_]+)(\[\d+\])?", message)
    if m and m.group(1) in _OPTIONS:
        return _OPTIONS[m.group(1)] + message[len(m.group(1)):]
    return message




def with_wall(log, started: float, estimate: float):
    """``log``, whose "simulated/predicted N cells in X s" line (the cells' phase) also says
    the command's wall time so far (since ``started``, perf_counter) and ``estimate`` (s,
    what the estimate line said): the two numbers a user compares."""
    import re
    import time

    def out(msg="", *a, **kw):
        if re.match(r"(simulated|predicted) \d+ cells? (in|on) ", str(msg)):
            msg = (f"{msg}; the command so far {time.perf_counter() - started:.1f} s, "
                   f"estimated {estimate:.0f} s")
        return log(msg, *a, **kw)

    return out


def plot_map(ds, ax=None):
    """Simulated verdict (white: MI) with the theories' boundaries drawn over it, each cell
    centred on its value (``scenes.map_figure``; any grid shape)."""
    from scenes import map_figure

    return map_figure(ds, ax)


def _agreement_text(name: str, ag: dict) -> str:
    """One theory's agreement with the simulation, in words (no NaN where it could
    evaluate no cell, or none is far from the threshold)."""
    und = ag[name + "_undetermined_cells"]
    left = f"{und} undetermined, left out" if und else ""
    if not math.isfinite(ag[name]):
        return f"{name}: no cell it could evaluate ({left or 'none simulated'})"
    decided = ag[name + "_decided_cells"]
    parts = [f"{ag[name + '_decided']:.0f}% of the {decided} not marginal" if decided
             else "every cell marginal"] + ([left] if left else [])
    return f"{name} {ag[name]:.0f}% of cells ({'; '.join(parts)})"


def _map_parameters(args):
    """(MapParameters, the k values, the cell count) from the options, every one checked
    and named in its error (nothing is written on bad input)."""
    if args.alpha is None or args.K_s is None:
        raise ValueError("--alpha and --K-s are required (the material's inertia and shear "
                         "stiffness)")
    for name, v in (("--alpha", args.alpha), ("--K-s", args.K_s)):
        checks.positive(name, v)
    k = parse_spec(args.k, "--k")
    # the rows as given: --delta, or --K-theta (its values reach the cells and the theories
    # unchanged; largest first, so that delta = K_s - K_theta ascends)
    if args.delta is not None and args.K_theta is not None:
        raise ValueError("give --K-theta SPEC or --delta SPEC (delta = K_s - K_theta), not both")
    if args.delta is not None:
        rows = {"delta": tuple(float(d) for d in parse_spec(args.delta, "--delta"))}
    elif args.K_theta is not None:
        rows = {"K_theta": tuple(float(x) for x in parse_spec(args.K_theta, "--K-theta")[::-1])}
    else:
        raise ValueError("give --K-theta SPEC or --delta SPEC (the map's second axis)")
    if args.workers is not None and args.scheduler:
        raise ValueError("give --scheduler or --workers, not both")
    if args.workers is not None:
        checks.integer("--workers", args.workers, 1, 10**4)
    cells = len(k) * len(next(iter(rows.values())))
    if cells > MAX_CELLS:
        raise ValueError(f"--k and --delta ask for {cells} cells; at most {MAX_CELLS} "
                         "(split the map into several --out folders)")
    checks.positive("--timeout", args.timeout)
    if isinstance(args.amplitude, (int, float)):  # its unit, and degrees (newuser 102)
        from numerics.theory import MAX_AMPLITUDE

        from ._resolved import check_peak_rotation

        check_peak_rotation(args.amplitude, MAX_AMPLITUDE)
    try:
        params = MapParameters(case=args.case, alpha=args.alpha, K_s=args.K_s, **rows,
                               k=tuple(float(x) for x in k), amplitude=args.amplitude,
                               N=args.N, t_end=args.t_end, seeds=args.seeds,
                               start=args.start, theory_only=args.theory_only,
                               block=args.block)
    except (ValueError, TypeError) as exc:  # name the option, not the field
        raise type(exc)(_as_option(str(exc))) from None
    return params, k, cells


def run_map_command(args, log=print):
    """`flexmm map`: parse, check everything (nothing is written on bad input), run."""
    import time

    from common.files import write_text
    from numerics.maps import resolve_device

    started = time.perf_counter()  # the estimate is of the command's wall time
    params, k, cells = _map_parameters(args)
    check_output(args.out)  # a bad --out fails before the map is announced
    # a GPU asked where there is none fails here, in one line, before the work is announced
    device = resolve_device(getattr(args, "device", "cpu"), params.theory_only, log,
                            args.scheduler)
    moved = [(a, b) for a, b in zip(params.k, params.k_simulated) if abs(a - b) > 1e-9 * a]
    if moved:
        log(f"note: {len(moved)} of {len(k)} k values snapped to 2 pi m / N (N = {params.N}),"
            f" e.g. {moved[0][0]:g} -> {moved[0][1]:.6g}; simulation and theories use the "
            "snapped k (coordinate k_simulated)")
    n_workers = args.workers or (1 if args.scheduler else local_cores())
    from numerics.maps import check_store, estimate_map

    # a store only --overwrite may replace: refused before the estimate
    check_store(Path(args.out) / "map.zarr", params, args.overwrite)

    from ._map_guards import cells_done

    # a resumed map: the estimate of the cells left (--overwrite computes every cell)
    done = 0 if args.overwrite else cells_done(args.out, params)[0]
    # this machine's speed
    estimate = estimate_map(params, n_workers, args.scheduler, cells=cells - done)
    est = estimate.seconds
    left = f" for the {cells - done} left ({done} in the store)" if done else ""
    if params.theory_only:
        log(f"map (theory only): {plural(cells, 'cell')}, N = {params.N}, T = {params.t_end:g}: "
            f"predictions about {_duration(est)}{left} ({estimate.describe()}) on "
            f"{n_workers} worker(s)")
    else:
        log(f"map: {plural(cells, 'cell')} x {params.seeds} seed(s), N = {params.N}, T = "
            f"{params.t_end:g}: about {_duration(est)}{left} ({estimate.describe()}) on "
            f"{n_workers} worker(s) (less where MI stops a run early)")
    if device == "gpu":
        log("device gpu: the cells' simulations run on the GPU in batches (the estimate "
            "above is this CPU's; bench/gpu.py measures the GPU)")
    if est > CONFIRM_SECONDS and not args.yes and device == "cpu":
        raise ValueError(f"the map would take about {_duration(est)} (> "
                         f"{_duration(CONFIRM_SECONDS)}); add --yes to run it, or use "
                         "fewer cells, seeds, a shorter --t-end or --theory-only")
    out = prepare_output(args.out)
    ds = run_map(params, out, args.scheduler, args.workers, log=with_wall(log, started, est),
                 overwrite=args.overwrite, timeout=args.timeout, device=device,
                 # the resume line comes before the workers start: the figure above (and
                 # the progress lines' time left until a cell is back)
                 estimate=est)
    verdicts = [n for n in ds.data_vars if n.startswith("verdict_")]
    from ._map_inputs import paper_inputs

    summary = {"inputs": paper_inputs(args, params, device),
               "cells": int(ds["done"].size), "simulated": int(ds["done"].values.sum()),
               "agreement_with_simulation_percent": agreement(ds),
               "mi_fraction": {n.removeprefix("verdict_"): _mi_fraction(ds[n].values)
                               for n in verdicts},
               "undetermined_cells": {n.removeprefix("verdict_"): int((ds[n].values < 0).sum())
                                      for n in verdicts}}
    write_text(out / "summary.json", json.dumps(strict_json(summary), indent=2) + "\n")
    fig = plot_map(ds)
    from common.files import atomic_write
    from scenes import plt

    with atomic_write(out / "map.png", mode=None) as tmp:
        fig.savefig(tmp, format="png", dpi=110)
    plt.close(fig)
    # what the runs found leads, where they ran: a simulated map printed only the theories'
    # agreement with them, never the runs' own share of MI
    und, share = summary["undetermined_cells"], summary["mi_fraction"]
    log(f"MI (grows more than {GROWTH_THRESHOLD:g}x within T = {params.t_end:g}) in: "
        + "; ".join(f"{n} {100 * share[n]:.0f}% of cells"
                    + (f" ({und[n]} undetermined, left out)" if und[n] else "")
                    for n in ("simulated", *MAP_COLUMNS)
                    if n in share and (n != "simulated" or summary["simulated"])))
    if summary["simulated"]:
        ag = summary["agreement_with_simulation_percent"]
        log(f"theory verdicts that agree with the simulation (marginal: the theory's growth "
            f"within {AGREEMENT_MARGIN:g}x of {GROWTH_THRESHOLD:g}x): " + "; ".join(
            _agreement_text(n, ag) for n in MAP_COLUMNS))
        if ag["predicted_growth_cells"]:
            log(f"predicted growth within 2x of the measured one in "
                f"{ag['predicted_growth_within_2x']:.0f}% of the "
                f"{plural(ag['predicted_growth_cells'], 'cell')} that grew 2x to 1000x")
    log(f"wrote {out / 'map.zarr'}, {out / 'map.png'}, {out / 'summary.json'}")  # last
    return ds

