"""`flexmm map --model`: a model's map over two axes, through the one map engine
(``numerics.maps.run_map``: cells as Dask tasks, the checksummed ``OUT/map.zarr``): the NLS
per cell, the exact and four-wave theories with --exact, runs of the ring per cell without
--theory-only."""

from __future__ import annotations

import math
from pathlib import Path

from ._map_guards import branch_jumps, cells_done, check_rest, option
from ._model_map_figure import OBSERVABLE, VERDICT_ORDER, _plot_map
from ._model_map_summary import (
    _differ_text,
    _no_wave_text,
    _overdamped_text,
    _print_observable,
    _summary,
)
from .models import _emit, branch_of, load, zero_damping_note
from .point import MIN_T_END


# ------------------------------------------------------------------ map
def run_map(args) -> int:
    import sys
    import time

    started = time.perf_counter()  # the estimate is of the command's wall time

    import numpy as np

    from common.output import check_output, prepare_output
    from energy import ModelError, check_value
    from numerics.maps import ModelMapParameters, model_text, parse_spec
    from numerics.maps import run_map as run_engine

    from .units import ModelUnits, model_units

    model, axes = load(args, axes_ok=True)
    units = model_units(args)
    k_axis = None
    k_fixed = None
    if args.k is not None:
        vals = parse_spec(args.k, "--k")
        if not np.all((vals > 0) & (vals <= math.pi)):  # named as the option, before work
            raise ValueError(f"--k must be in (0, pi], got {args.k!r}")
        if vals.size > 1 or ":" in args.k or "," in args.k:  # a SPEC, as --param's: an
            k_axis = vals  # axis even of one value (a 1 x 1 map: probe 97)
        else:
            k_fixed = float(vals[0])
    amp, amp_axis = args.amplitude, None
    if isinstance(amp, str):  # a SPEC (the parser keeps what is not one number)
        vals = parse_spec(amp, "--amplitude")
        if not np.all(np.isfinite(vals)) or vals.min() <= 0:
            raise ValueError(f"--amplitude must be > 0, got {amp!r}")
        for v in vals:
            check_value("--amplitude", float(v))
        amp, amp_axis = (None, vals) if vals.size > 1 or ":" in amp or "," in amp else (
            float(vals[0]), None)
    named = (list(axes.items()) + ([("k", k_axis)] if k_axis is not None else [])
             + ([("amplitude", amp_axis)] if amp_axis is not None else []))
    if len(named) != 2:
        raise ValueError(f"a model map sweeps two axes among --k SPEC, --amplitude SPEC and "
                         f"--param NAME=SPEC (SPEC v1,v2,... or start:stop:num); got "
                         f"{len(named)}: {', '.join(n for n, _ in named) or 'none'}")
    from .map import MAX_CELLS

    cells = len(named[0][1]) * len(named[1][1])
    if cells > MAX_CELLS:  # as the paper chain's map: before a grid fills memory
        raise ValueError(f"{' and '.join(option(n) for n, _ in named)} ask for {cells} "
                         f"cells; at most {MAX_CELLS} (split the map into several --out "
                         "folders)")
    check_rest(model, named)
    if amp_axis is not None and "amplitude" in model.params:
        raise ValueError("--amplitude SPEC: the model has a parameter named 'amplitude' too; "
                         "rename it in the model file to sweep the carrier's amplitude")
    if k_axis is None and k_fixed is None:
        raise ValueError("--k: give the carrier wavenumber (one value, or a SPEC to sweep)")
    simulated = not getattr(args, "theory_only", False)
    given = getattr(args, "given", ())
    start = _start_of(args, model, simulated) if "--start" in given else "exact"
    if not simulated and ("--seeds" in given or "--t-end" in given):
        given_run = " and ".join(o for o in ("--seeds", "--t-end") if o in given)
        raise ValueError(f"{given_run}: {'acts' if ' and ' not in given_run else 'act'} on "
                         "a simulated model map's runs; drop "
                         f"{'it' if ' and ' not in given_run else 'them'}, or drop "
                         "--theory-only to run the cells")
    if simulated and args.exact:
        raise ValueError("--exact: a simulated model map has the exact lattice theory "
                         "per cell already; drop --exact, or add --theory-only for the "
                         "theories without the runs")
    if amp is not None and check_value("--amplitude", amp) <= 0:
        raise ValueError(f"--amplitude must be > 0, got {amp!r}")
    ring = args.exact or simulated  # the ring the exact theory and the runs use
    from numerics.models import check_ring

    try:  # a theory-only map's too: it names the offsets a ring of N samples, and stores N
        check_ring(args.N)  # (--N 0 and 3 were stored as N, 1048577 too, without a word)
    except ValueError as exc:
        raise ValueError(f"--N: {exc}") from None
    seeds, t_end = args.seeds, None
    if simulated:
        if isinstance(seeds, bool) or not isinstance(seeds, int) or not 1 <= seeds <= 1000:
            raise ValueError(f"--seeds must be an integer in [1, 1000], got {seeds!r}")
        t_end = args.t_end if "--t-end" in given else None
        if t_end is not None and not (isinstance(t_end, (int, float))
                                      and MIN_T_END <= t_end < 1e12):
            raise ValueError(f"--t-end must be a finite time in [{MIN_T_END:g}, 1e12), got "
                             f"{t_end!r}")
    if args.workers is not None and args.scheduler:
        raise ValueError("give --scheduler or --workers, not both")
    if args.workers is not None and not (isinstance(args.workers, int)
                                         and 1 <= args.workers <= 10**4):
        raise ValueError(f"--workers must be an integer in [1, 10000], got {args.workers!r}")
    if not (isinstance(args.block, int) and 1 <= args.block <= 10**6):
        raise ValueError(f"--block must be an integer in [1, 1000000], got {args.block!r}")
    if not (args.timeout > 0 and np.isfinite(args.timeout)):
        raise ValueError(f"--timeout must be a finite time > 0, got {args.timeout!r}")
    # columns: k where k is an axis, else the amplitude, else the second parameter;
    # rows: the other axis
    x = next((a for a in named if a[0] == "k"), None) or next(
        (a for a in named if a[0] == "amplitude"), named[1])
    y = next(a for a in named if a is not x)
    from numerics.models import branch_index, snap_ring

    k0 = x[1][0] if x[0] == "k" else k_fixed
    branch_index(model, k0, branch_of(args))  # an impossible branch: the command's
    if ring:
        for kk in (x[1] if x[0] == "k" else [k_fixed]):
            try:
                snap_ring(float(kk), args.N)
            except ModelError as exc:
                raise ValueError(f"--k: {exc}") from None
    params = ModelMapParameters(
        model=args.model, text=model_text(args.model), parameters=tuple(model.params.items()),
        rows=y, cols=x, amplitude=None if amp is None else float(amp), k=k_fixed,
        branch=None if args.branch is None else str(args.branch), exact=bool(args.exact),
        theory_only=not simulated, N=args.N, seeds=seeds, t_end=t_end,
        block=args.block if "--block" in given else _default_block(
            None if args.overwrite else args.out, simulated, x),
        time_unit_s=units.seconds_per_T, length_unit_m=units.metres_per_site, start=start)
    check_output(args.out)
    log = (lambda *a: print(*a, file=sys.stderr)) if args.json else print
    from numerics.maps import resolve_device

    # before anything is written: a GPU asked where there is none is refused in one line
    asked = getattr(args, "device", "cpu")
    if start != "exact" and asked == "gpu":
        raise ValueError(f"--device gpu: the GPU launches the exact wave; a --start {start} "
                         "map runs on the CPU (--device cpu)")
    device = resolve_device("cpu" if start != "exact" else asked, params.theory_only, log,
                            args.scheduler)
    workers = args.workers
    if workers and workers > len(x[1]) * len(y[1]):  # idle workers only cost their start
        workers = len(x[1]) * len(y[1])
    n_workers = workers or (1 if args.scheduler else None)
    from numerics.maps import local_cores

    fixed = ", ".join(f"{p} = {v:g}" for p, v in model.params.items()
                      if p not in (x[0], y[0]))
    log(f"map of {model.name}" + (f" ({fixed})" if fixed else "")
        + f": {y[0]} x {x[0]} = {len(y[1])} x {len(x[1])} cells"
        + (f", k = {k_fixed:g}" if k_fixed is not None else "")
        + (f", amplitude {amp:g}" if amp is not None else "")
        + f"; {'theories ' + ', '.join(params.theory_columns())}"
        + (f" and {seeds} run(s) per cell (N = {args.N}, T = "
           + (f"{t_end:g}" if t_end is not None else "from each cell's "
              + ("exact" if start == "exact" else f"{start}-start theory's") + " rate"
              + (" and its peak time" if params.lossy else ""))
           + ("; with losses: noise on the carrier field, until A(t) halves, T a cap)"
              if params.lossy else ")")
           if simulated else "")
        + f" on {n_workers or local_cores()} worker(s)")
    log(f"units: {units.describe()} (the store's numbers in lattice units, the factors in "
        "its attributes time_unit_s and length_unit_m)")
    if not params.lossy and (note := zero_damping_note(model)):  # no damping axis either
        log(note.replace("so are these answers", "so is this map"))
    if ring:  # as the paper chain's map says it: k = pi on 33 sites is 3.046, not pi
        ks = [float(v) for v in (x[1] if x[0] == "k" else [k_fixed])]
        if moved := [(a, b) for a in ks if abs((b := snap_ring(a, args.N)[0]) - a) > 1e-9 * a]:
            log(f"note: {len(moved)} of {len(ks)} k values snapped to 2 pi m / N (N = "
                f"{args.N}), e.g. {moved[0][0]:g} -> {moved[0][1]:.6g}; every theory and run "
                "uses the snapped k (variable k_simulated)")
        if same := params.same_ring_k():
            log(f"note: {same}")
    if x[0] == "k" and (jump := branch_jumps(model, x[1], branch_of(args)
                                              or model.lattice.branch or None, y)):
        log(f"note: {jump}")
    if start != "exact":
        from numerics.models import extra_starts

        launched = extra_starts(model)[start]
        log(f"start: {launched.describe}, with its own noise"
            + (", the runs' T from its theory's rate" if t_end is None else "")
            + f"; its theory: {launched.column} (Hill's method about that state)")
    from numerics.maps import check_store

    # a store only --overwrite may replace: refused before the estimate's seconds
    check_store(Path(args.out) / "map.zarr", params, args.overwrite)
    # --overwrite discards the store: every cell is computed (and estimated)
    done, cells = (0, cells) if args.overwrite else cells_done(args.out, params)
    left = None  # the resume line's figure: the estimate's, where one is measured
    if done == cells:  # nothing to compute: no cell measured to estimate it
        log(f"estimate: none needed: {Path(args.out) / 'map.zarr'} holds every cell of this "
            "map (its checksums are verified, the summary and figure made again)")
        estimated = 0.0
    else:  # a resumed map: the cells left, not the whole map
        est = _estimate(params, n_workers or local_cores(), args.scheduler, log,
                        cells - done, cells)
        # the resume line comes before the workers start: its figure is this one, the
        # start-up included (it said 6 s below an estimate of 18 s for the same cells)
        left = est.seconds
        # the cells' line compares the command's wall time so far with this: the seconds
        # already spent (options, the cell measured) plus the estimate of what follows
        # (it said "the command so far 220.1 s, estimated 109 s" after a 94 s measurement
        # the 109 s did not include)
        estimated = time.perf_counter() - started + left
        from .map import CONFIRM_SECONDS

        if left > CONFIRM_SECONDS and not args.yes and device == "cpu":
            from common.text import duration

            raise ValueError(f"the map would take about {duration(left)} (> "
                             f"{duration(CONFIRM_SECONDS)}); add --yes to run it, or use "
                             "fewer cells" + (", seeds, a shorter --t-end or --theory-only"
                                              if simulated else " or a smaller --N"
                                              if params.ring else ""))
    out = prepare_output(args.out, cache=False)
    path = out / "map.zarr"
    existed = path.exists() and not args.overwrite  # --overwrite: the old one is gone
    import json

    from common.files import write_text
    from common.output import strict_json

    from .map import with_wall

    ds = run_engine(params, out, args.scheduler, workers,
                    log=with_wall(log, started, estimated), overwrite=args.overwrite,
                    timeout=args.timeout, device=device, estimate=left)
    # the figure's panel order, whatever order the store lists them in (newuser99: a
    # resumed map, its store reopened, printed its MI shares in another order)
    verdicts = sorted((v for v in ds.data_vars if v.startswith("verdict_")
                       and (simulated or v != "verdict_simulated")),
                      key=lambda v: (VERDICT_ORDER.index(v) if v in VERDICT_ORDER
                                     else len(VERDICT_ORDER), v))
    if all((ds[v].values < 0).all() for v in verdicts):
        if not existed:  # it holds nothing worth keeping, and would block the corrected map
            import shutil

            shutil.rmtree(path, ignore_errors=True)
        # the NLS alone has no verdict where its expansion fails (a flat branch's g1 = 0:
        # probe 95's v oscillator); the exact lattice and four-wave theories may have one
        more = ("" if simulated or params.exact else
                ", or add --exact (the exact lattice and four-wave theories on the ring)")
        raise ValueError(f"every cell of the map is undefined (first cell: "
                         f"{params.undefined_reason()}); change the axes, k, the amplitude "
                         f"or --branch{more}")
    png = out / "map.png"
    _plot_map(_as_words(ds, verdicts), png, model)
    from ._map_inputs import model_inputs

    summary = {"inputs": model_inputs(params, model, device),
               **_summary(ds, verdicts, simulated)}
    # mi_share: summary.json's mi_fraction by variable name (kept for older scripts)
    mi = {v: summary["mi_fraction"][v.removeprefix("verdict_")] for v in verdicts}
    write_text(out / "summary.json", json.dumps(strict_json(summary), indent=2) + "\n")
    files = [str(path), str(png), str(out / "summary.json")]
    critical = _critical_rows(ds)
    unsampled = _unsampled(ds)
    if args.json:
        # a swept parameter is an axis, not its default (beta = 1.0 of a beta axis read as
        # the map's beta); the amplitude is null where it is an axis, as here
        fixed = {n: v for n, v in model.params.items() if n not in (x[0], y[0])}
        res = {"model": model.name, "parameters": fixed, "amplitude": amp,
               "axes": {x[0]: list(map(float, x[1])), y[0]: list(map(float, y[1]))},
               "mi_fraction": summary["mi_fraction"], "mi_share": mi,
               "undetermined_cells": summary["undetermined_cells"], "files": files}
        if simulated:
            res["agreement_with_simulation_percent"] = summary[
                "agreement_with_simulation_percent"]
        for key in ("observable_fraction", "observable_unanswered_cells",
                    "observable_agreement_with_simulation_percent"):
            if key in summary:
                res[key] = summary[key]
        if critical:
            res["critical_damping"] = critical
        if unsampled is not None:
            res["nls_band_unsampled"] = unsampled
        if "slow_for_T_cells" in summary:
            res["slow_for_T_cells"] = summary["slow_for_T_cells"]
        if summary.get("blew_up_cells"):
            res["blew_up_cells"] = summary["blew_up_cells"]
        if summary.get("no_wave_cells"):
            res["no_wave_cells"] = summary["no_wave_cells"]
        u, _ = ModelUnits.json(units, {})
        if "k" in res["axes"]:  # the k axis, in rad/m too
            u["lattice"]["k"] = "rad/site"
            if units.metres_per_site:
                u["si"]["k"] = "rad/m"
                res["si"] = {"axes": {"k": [v / units.metres_per_site
                                            for v in res["axes"]["k"]]}}
        if k_fixed is not None:
            res["k"] = k_fixed
            u["lattice"]["k"] = "rad/site"
            if units.metres_per_site:
                u["si"]["k"] = "rad/m"
                res["si"] = {"k": k_fixed / units.metres_per_site}
        res["units"] = u
        _emit(res)
        return 0
    for v, share in mi.items():
        # the share among the cells a theory decides, as the paper chain's map gives it;
        # the cells it leaves undetermined (g1 = 0 for the NLS, no wave for the exact
        # theory) said beside it, so that 50% is read against the cells it decided
        n = summary["undetermined_cells"][v.removeprefix("verdict_")]
        print(f"MI share, {v.replace('verdict_', '')}: "
              + (f"{share:.0%}" if math.isfinite(share) else "no cell decided")
              + (f" ({n} of {ds[v].size} cells undetermined, left out)" if n else ""))
    ag = summary.get("agreement_with_simulation_percent") or {}
    # each theory's row (the runs' own undetermined cells are said with the MI shares)
    told = [n.removesuffix("_undetermined_cells") for n in ag
            if n.endswith("_undetermined_cells") and n != "simulated_undetermined_cells"]
    if told:  # the runs' verdict against each theory's (summary.json's numbers)
        print("agreement with the runs (cells the theory decides): " + ", ".join(
            (f"{n}: no cell it could evaluate" if not math.isfinite(ag[n]) else  # not nan%
             f"{n} {ag[n]:.0f}%"
             + (f" ({ag[n + '_decided']:.0f}% of {ag[n + '_decided_cells']} not marginal)"
                if n + "_decided" in ag and math.isfinite(ag[n + "_decided"]) else ""))
            + (f" ({ag[n + '_undetermined_cells']} undetermined, left out)"
               if ag[n + "_undetermined_cells"] else "") for n in told)
              + ("; with losses a theory's MI is its gain beating the damping at t = 0, "
                 "the runs' is 20x growth: the agreement on observable below compares "
                 "like with like" if "observable_fraction" in summary else ""))
    _print_observable(summary)
    if (differ := _differ_text(ds, params, str(args.model))) is not None:
        print(differ)
    if unsampled and unsampled["cells"]:
        print(_unsampled_text(unsampled, args.N))
    if summary.get("no_wave_cells"):
        print(_no_wave_text(ds, params, summary))
    if (over := _overdamped_text(ds, params)) is not None:
        print(over)
    if summary.get("blew_up_cells"):
        print(f"runs that blew up (the state left the lattice's range, growth inf): "
              f"{summary['blew_up_cells']} of {summary['cells']} cells, undetermined (a "
              "softening or escaping potential; their MI is not decided by these runs)")
    if summary.get("slow_for_T_cells"):  # runs too short for their cell's exact rate
        print(f"{ds.attrs['slow_for_T_note']}; a longer --t-end decides them")
    for name, c in critical.items():
        other = c["along"]
        print(f"{name} (amplification {OBSERVABLE:g}x): " + ", ".join(
            f"{other} {v:g}: " + ("-" if x is None else f"{x:.4g}")
            for v, x in zip(c[other], c["value"]))
              + ("" if all(x is not None for x in c["value"]) else f" ({c['reason']})"))
    print(f"wrote {path}, {png} and {out / 'summary.json'} (xarray: "
          f"xr.open_zarr({str(path)!r}))")
    return 0


#: a theory-only map's cells per task unless --block: a row of the map, up to this many
#: (its cells take ~1-30 ms, so 4 a task made the client's writes, ~20 ms a block, and
#: the scheduler the bottleneck: a 64 x 64 fput --exact map 70 s wall, ~35 s of it writes)
THEORY_BLOCK = 64


def _default_block(out, simulated: bool, cols) -> int:
    """--block's default: the block of a map store already in ``out`` (a resumed map keeps
    its chunks; ``out`` None: a store discarded by --overwrite), else 4 cells a task for a
    simulated map (each cell runs the ring), else a row of the map up to THEORY_BLOCK
    cells."""
    import zarr

    stored = None
    try:
        if out is not None:
            stored = zarr.open_group(str(Path(out) / "map.zarr"), mode="r").attrs.get("block")
    except Exception:  # no store there, or none readable: the map's own default
        stored = None
    if isinstance(stored, int) and stored >= 1:
        return stored
    return 4 if simulated else min(len(cols[1]), THEORY_BLOCK)


def _start_of(args, model, simulated: bool) -> str:
    """--start of a model map: travelling (the exact wave, "exact"), or a start the model
    registers (``numerics.models.extra_starts``: paper, eq. IC, for the paper chain's
    models), for a simulated map or --exact (its theory and runs use the ring)."""
    from numerics.models import extra_starts

    start = args.start
    if start in (None, "travelling"):
        return "exact"
    if start not in extra_starts(model):
        raise ValueError(f"--start {start}: a map of model {model.name} starts from the exact "
                         "wave (--start travelling, the default)" + (
                             "; the paper's start (eq. IC) belongs to the paper chain's "
                             "energy, lossless (flexmm, flexmm-rotation)"
                             if start == "paper" else ""))
    if not (simulated or args.exact):
        raise ValueError(f"--start {start}: its theory and runs use the ring: a simulated "
                         "map, or --theory-only --exact")
    return start


#: seconds of measuring one cell after which the estimate says why it takes long
PROBE_NOTE_S = 5.0


def _estimate(params, workers: int, scheduler, log, left: int, cells: int):
    """The map's wall time (a MapEstimate) for the ``left`` of its ``cells`` still to
    compute, estimated from one cell measured here (its theories and, for a simulated map,
    a short run of its ring) and said before the work."""
    import threading

    from common.text import duration
    from numerics.maps import estimate_model_map, probe_model_cell

    # a fresh install compiles the cell's kernels here first (fput: 94 s said nothing
    # between the options' notes and the estimate): said where the measurement is slow
    slow = threading.Timer(PROBE_NOTE_S, lambda: log(
        f"estimate: measuring one cell here (over {PROBE_NOTE_S:g} s: a busy machine, or "
        "its kernels compiling once after an install or upgrade, a minute or two)"))
    slow.daemon = True
    slow.start()
    try:
        cost = probe_model_cell(params)
    finally:
        slow.cancel()
    est = estimate_model_map(params, workers, scheduler, cost, cells=left)
    measured = f"theories {cost.theory:.2g} s" + (
        f", a run of T = {cost.t_end:g} {cost.run:.2g} s" if not params.theory_only else "")
    log(f"estimate: about {duration(est.seconds)}"
        + (f" for {left} of its {cells} cells (the other {cells - left} "
           f"{'is' if cells - left == 1 else 'are'} in the store)"
           if left < cells else "")
        + f" ({est.describe()}; one cell measured here: "
        f"{measured} of CPU) on {workers} worker(s)")
    return est


def _critical_rows(ds) -> dict:
    """{critical_<damping>_<theory>: {"along": the other axis, its values, "value" (None
    where none inside the axis), "reason"}} of a map over a damping axis (issue 42)."""

    out = {}
    for name in sorted(n for n in ds.data_vars if n.startswith("critical_")):
        var = ds[name]
        other = var.dims[0]
        out[name] = {"along": other, other: [float(v) for v in ds[other].values],
                     "value": [float(v) if math.isfinite(v) else None for v in var.values],
                     "reason": str(var.attrs.get("reason", ""))}
    return out


def _unsampled(ds) -> dict | None:
    """The cells where the semi-discrete NLS (the infinite chain) finds MI in a band of
    offsets 0 < |q| < a sqrt(g2/g1) narrower than the ring's smallest offset 2 pi / N: no
    ring offset samples it, so the ring's theories (exact, four-wave on the ring) and runs
    cannot show that MI -- ``flexmm point`` lists the same as ``ring_misses``. Read from
    the store's ``nls_band_unsampled`` (``ModelMapParameters.unsampled_band``); None where
    the map has no ring theory."""
    if "nls_band_unsampled" not in ds.data_vars:
        return None
    a = ds["nls_band_unsampled"].attrs
    edge = a.get("widest_band_edge")
    return {"cells": int(a["cells"]), "of": int(a["of"]),
            "ring_smallest_offset": float(a["ring_smallest_offset"]),
            "widest_band_edge": float(edge) if isinstance(edge, (int, float)) else None,
            "ring_not_MI": {n.removeprefix("ring_not_MI_"): int(v) for n, v in a.items()
                            if n.startswith("ring_not_MI_")}}


def _unsampled_text(u: dict, N: int) -> str:
    return (f"{u['cells']} of {u['of']} cells: the semi-discrete NLS band (edge a "
            f"sqrt(g2/g1) <= {u['widest_band_edge']:.3g} rad/site) lies below the ring's "
            f"smallest offset 2 pi / N = {u['ring_smallest_offset']:.4g} (N = {N}): no ring "
            "offset samples it (cells there the ring calls not MI: "
            + ", ".join(f"{name} {n}" for name, n in u["ring_not_MI"].items())
            + "); a larger --N samples it; the store's nls_band_unsampled marks them")


def _as_words(ds, verdicts):
    """The store's int8 verdicts as words (what the figure reads)."""
    import numpy as np

    words = np.array(["undefined", "stable", "MI"])
    unused = [v for v in ds.data_vars if v.startswith("verdict_") and v not in verdicts]
    return ds.drop_vars(unused).assign(  # a theory-only map has no simulated panel
        {v: (ds[v].dims, words[ds[v].values.astype(int) + 1]) for v in verdicts})
