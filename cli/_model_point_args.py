"""`flexmm point --model`: its command-line arguments checked and said as the API takes them
(its start, an input error named by its option), then the point measured
(``run_model_point``)."""

from __future__ import annotations

import contextlib
import math

from numerics.lattice import checks
from numerics.maps import MAX_SEEDS, MAX_T_END, measure_point

from ._slow import SLOW_MODEL_POINT, said_if_slow
from ._slow import to_stderr as _stderr

#: the shortest --t-end: below it the slowest rate a run can show, ln(20) / T, is past
#: float64 (probe 99: --t-end 5e-324 printed "a rate below inf /time cannot show")
MIN_T_END = 1e-300


def _model_start(args, model) -> str:
    """The run's start: "exact" (--start travelling, the default), "linear", or a start the
    model registers (``numerics.models.extra_starts``: "paper", eq. IC, for the paper
    chain's energy)."""
    from numerics.models import extra_starts

    start = getattr(args, "start", None)
    if start in (None, "travelling"):
        return "exact"
    if start == "linear" or start in extra_starts(model):
        return start
    raise ValueError(f"--start {start}: model {model.name} has no such start; it starts "
                     "from travelling (the exact wave, default) or linear (the linear plane "
                     "wave)" + ("; the paper's start (eq. IC) belongs to the paper chain's "
                                "energy, lossless (flexmm, flexmm-rotation)"
                                if start == "paper" else ""))


def _option_error(exc, args) -> ValueError:
    """A ``PointInputError`` said with the option's name (``--N: ...``), the start's as
    the command spells it (travelling for the API's "exact")."""
    if exc.field == "start":
        return ValueError(f"--start {args.start}: " + exc.reason.replace(
            "use start 'exact' or 'linear'", "use --start travelling or linear"))
    return ValueError(f"--{exc.field}: {exc.reason}")


def run_model_point(args) -> dict:
    """`flexmm point --model`: the options checked (each by its name, before any theory
    runs), ``measure_point`` of the ``ModelPointSpec``, then ``_model_point_text``."""
    import time

    from numerics.maps import ModelPointSpec, PointInputError

    from . import _model_point_text as text
    from .models import branch_of, check_amplitude, load
    from .units import model_units

    model = load(args)
    units = model_units(args)
    checks.real("--k", args.k, 0.0, math.pi, high_open=False)
    check_amplitude(args.amplitude)
    if args.t_end is not None and not args.simulate:
        raise ValueError("--t-end acts with --simulate only")
    if not args.simulate and ("--seeds" in getattr(args, "given", ()) or args.seeds != 4):
        # the paper chain's point predicts its growth per seed; a model's seeds are runs
        raise ValueError("--seeds: a model point's seeds are its runs'; add --simulate, "
                         "or leave --seeds out")
    if args.simulate:  # the runs' options, as the paper chain's point checks them: before
        checks.integer("--seeds", args.seeds, 1, MAX_SEEDS)  # any theory (--t-end 1e30
        if args.t_end is not None:  # hung in the estimate's probe)
            checks.real("--t-end", args.t_end, MIN_T_END, MAX_T_END, low_open=False)
    start = _model_start(args, model)
    try:  # the ring, the amplitude's resolution, a registered start's state
        spec = ModelPointSpec(model, args.k, args.amplitude, branch_of(args), N=args.N,
                              start=start, simulate=args.simulate, seeds=args.seeds,
                              t_end=args.t_end)
    except PointInputError as exc:
        raise _option_error(exc, args) from None
    if args.out:
        from common.output import check_output
        check_output(args.out, cache=False)
    if args.simulate:  # said before anything that takes time
        text.log_to(args)(f"point: the theories, then an estimate of the {args.seeds} "
                          "run(s) (a model's first run compiles its force for this "
                          "machine, once: seconds to tens of seconds)")
    said = []  # when the estimate was said: the runs' wall time is counted from there

    def on_estimate(est):
        text.say_estimate(args, est)
        said.append(time.perf_counter())

    # a point --simulate said what it does above; without runs, said only where slow
    slow = (contextlib.nullcontext() if args.simulate
            else said_if_slow(_stderr, SLOW_MODEL_POINT))
    try:
        with slow:
            point = measure_point(spec, on_estimate=on_estimate,
                                  estimate_figure=bool(args.out))
    except PointInputError as exc:  # --simulate where the model has no travelling wave
        raise _option_error(exc, args) from None
    return text.report(args, point, units, said[0] if said else None)
