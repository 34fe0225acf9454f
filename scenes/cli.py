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
    _point_parser(sub)
    _map_parser(sub)
    return p


def _material_args(p):
    p.add_argument("--alpha", type=float, help="inertia parameter alpha")
    p.add_argument("--K-s", dest="K_s", type=float, help="shear stiffness K_s = k_s / k_l")
    p.add_argument("--case", required=True, choices=("rotation", "coupled"))
    p.add_argument("--amplitude", type=float, default=0.02,
                   help="peak rotation of the plane wave, rad (2 eps A0; default 0.02)")
    p.add_argument("--start", choices=("paper", "travelling"), default="paper",
                   help="eq. IC (U at rest) or the exact travelling wave (default paper)")
    p.add_argument("--N", type=int, default=500, help="sites of the periodic chain (500)")


def _point_parser(sub):
    p = sub.add_parser("point", help="the three theories of MI at one point (and a "
                       "simulation with --simulate)")
    _material_args(p)
    p.add_argument("--K-theta", dest="K_theta", type=float,
                   help="bending stiffness K_theta = 4 k_theta / (k_l a^2)")
    p.add_argument("--physical", metavar="m,J,a,k_l,k_s,k_theta",
                   help="physical units instead: mass, moment of inertia, cell length and "
                        "the three spring stiffnesses (Material.from_physical)")
    p.add_argument("--k", type=float, required=True, help="carrier wavenumber, rad per site")
    p.add_argument("--simulate", action="store_true", help="measure sigma(q) too")
    p.add_argument("--t-end", dest="t_end", type=float,
                   help="run length (default: 9 e-foldings of the exact peak gain)")
    p.add_argument("--seeds", type=int, default=4, help="noise seeds (default 4)")
    p.add_argument("--out", help="folder for point.json (and point.png with --simulate)")


def _map_parser(sub):
    p = sub.add_parser("map", help="an MI map over (delta, k), simulated on Dask")
    _material_args(p)
    g = p.add_mutually_exclusive_group(required=True)
    g.add_argument("--delta", help="SPEC of delta = K_s - K_theta: v1,v2,... or start:stop:num")
    g.add_argument("--K-theta", dest="K_theta", help="SPEC of K_theta instead of delta")
    p.add_argument("--k", required=True, help="SPEC of k (rad per site); each k is snapped "
                   "to 2 pi m / N for the simulation (k_simulated in the dataset)")
    p.add_argument("--t-end", dest="t_end", type=float, default=5000.0, help="run length")
    p.add_argument("--seeds", type=int, default=1, help="noise seeds per cell (default 1)")
    p.add_argument("--out", default="out/map", help="folder of map.zarr (default out/map)")
    p.add_argument("--scheduler", help="address of a running Dask scheduler "
                   "(tcp://host:8786); default: a LocalCluster on this machine")
    p.add_argument("--workers", type=int, help="LocalCluster workers (default: the cores)")
    p.add_argument("--theory-only", action="store_true",
                   help="the theories' verdicts only: no simulation")
    p.add_argument("--block", type=int, default=4, help="cells per task (default 4)")


def _print_checks(summary):
    for c in summary.get("checks", []):
        print(f"[{c['outcome']}] {c['check']}: theory {c['theory']}; numerics {c['numerics']}")


def main(argv=None) -> int:
    """Run the CLI; returns the exit code (0 ok, 2 bad input or file system, 130 Ctrl-C)."""
    args = _parser().parse_args(argv)
    if getattr(args, "out", None) is not None:
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
    if args.cmd == "point":
        from .point import run_point

        run_point(args)
        return 0
    if args.cmd == "map":
        from ._map_command import run_map_command

        run_map_command(args)
        return 0
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
