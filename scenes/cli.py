"""`flexmm`: the NLS table at the test points; list, run and redraw the scenes."""

from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path


def _parser():
    p = argparse.ArgumentParser(prog="flexmm", description=__doc__)
    sub = p.add_subparsers(dest="cmd", required=True)
    tab = sub.add_parser("table", help="NLS coefficients at the paper's two test points")
    tab.add_argument("--A0", type=float, default=1.0, help="envelope amplitude (default 1)")
    sub.add_parser("scenes", help="list the scenes with a description and run time")
    one = sub.add_parser("scene", help="run one scene")
    one.add_argument("name")
    one.add_argument("--replot", action="store_true",
                     help="redraw the figure from OUT/NAME/data.h5 without computing")
    for sp_ in (one, sub.add_parser("run", help="run every scene and write out/report.md")):
        sp_.add_argument("--quick", action="store_true",
                         help="reduced N / t_end / grids: seconds per scene")
        sp_.add_argument("--out", default="out", help="output folder (default: out)")
        sp_.add_argument("--seed", type=int, default=0, help="noise seed (default 0)")
        sp_.add_argument("--force", action="store_true", help="recompute cached simulations")
    return p


def _print_checks(summary):
    for c in summary.get("checks", []):
        print(f"[{c['outcome']}] {c['check']}: theory {c['theory']}; numerics {c['numerics']}")


def main(argv=None) -> int:
    """Run the CLI; returns the exit code (0 ok, 2 bad input or file system, 130 Ctrl-C)."""
    args = _parser().parse_args(argv)
    if hasattr(args, "out"):
        args.out = args.out or "."  # --out '' is the current folder, and says so
    try:
        return _run(args)
    except KeyboardInterrupt:
        cache = f"{args.out}/.cache" if hasattr(args, "out") else "the cache"
        print(f"flexmm: interrupted; finished simulations are kept in {cache} and the one "
              "running was checkpointed there: run the same command again to continue",
              file=sys.stderr)
        return 130
    except (ValueError, TypeError, FloatingPointError) as exc:
        print(f"flexmm: error: {exc}", file=sys.stderr)
        return 2
    except OSError as exc:
        where = f" {exc.filename}" if exc.filename else ""
        print(f"flexmm: error: cannot write{where}: {exc.strerror or exc}", file=sys.stderr)
        return 2


def _run(args) -> int:
    import warnings

    import scenes
    from numerics import AccuracyWarning

    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always", AccuracyWarning)
        code = _dispatch(args, scenes)
    for w in caught:
        if issubclass(w.category, AccuracyWarning):
            print(f"flexmm: warning: {w.message}", file=sys.stderr)
        else:
            warnings.showwarning(w.message, w.category, w.filename, w.lineno)
    return code


def _dispatch(args, scenes) -> int:
    if args.cmd == "table":
        from .table import format_table

        print(format_table(args.A0))
        return 0
    if args.cmd == "scenes":
        width = max(len(n) for n in scenes.REGISTRY)
        for sc in scenes.REGISTRY.values():
            print(f"{sc.name:<{width}}  {sc.runtime:<18}  {sc.description}")
        return 0
    t0 = time.perf_counter()
    if args.cmd == "scene" and args.replot:
        folder = scenes.replot_scene(args.name, args.out)
        print(f"{args.name}: redrew {folder}/figure.png and figure.pdf from data.h5 in "
              f"{time.perf_counter() - t0:.1f} s")
    elif args.cmd == "scene":
        _print_checks(scenes.run_scene(args.name, args.out, args.quick, args.seed,
                                       args.force))
        print(f"{args.name}: wrote {Path(args.out) / args.name}/ in "
              f"{time.perf_counter() - t0:.1f} s")
    else:
        report = scenes.run_all(args.out, args.quick, args.seed, args.force)
        print(report.read_text())
        print(f"wrote {report} and {len(scenes.REGISTRY)} scene folders in "
              f"{time.perf_counter() - t0:.1f} s")
    return 0


if __name__ == "__main__":
    sys.exit(main())
