"""A model point's command-line arguments said as the API takes them (``point --model``):
its start, and an input error named by its option."""

from __future__ import annotations


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
