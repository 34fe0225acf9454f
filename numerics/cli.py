"""`flexmm`: list and run the scenes (figures of the paper and checks beyond it)."""

from __future__ import annotations

import argparse
import sys
import time


def _parser():
    p = argparse.ArgumentParser(prog="flexmm", description=__doc__)
    sub = p.add_subparsers(dest="cmd", required=True)
    sub.add_parser("scenes", help="list the scenes with a description and run time")
    one = sub.add_parser("scene", help="run one scene")
    one.add_argument("name")
    for sp_ in (one, sub.add_parser("run", help="run every scene and write out/report.md")):
        sp_.add_argument("--quick", action="store_true",
                         help="reduced N / t_end / grids: seconds per scene")
        sp_.add_argument("--out", default="out", help="output folder (default: out)")
        sp_.add_argument("--seed", type=int, default=0, help="noise seed (default 0)")
        sp_.add_argument("--force", action="store_true", help="recompute cached simulations")
    return p


def main(argv=None) -> int:
    args = _parser().parse_args(argv)
    from . import scenes

    try:
        if args.cmd == "scenes":
            width = max(len(n) for n in scenes.REGISTRY)
            for sc in scenes.REGISTRY.values():
                print(f"{sc.name:<{width}}  {sc.runtime:<18}  {sc.description}")
            return 0
        if args.seed < 0:
            raise ValueError(f"--seed must be >= 0, got {args.seed}")
        t0 = time.perf_counter()
        if args.cmd == "scene":
            s = scenes.run_scene(args.name, args.out, args.quick, args.seed, args.force)
            for c in s.get("checks", []):
                print(f"[{'pass' if c['pass'] else 'FAIL'}] {c['check']}: theory "
                      f"{c['theory']}; numerics {c['numerics']}")
            print(f"{args.name}: wrote {args.out}/{args.name}/ in "
                  f"{time.perf_counter() - t0:.1f} s")
        else:
            report = scenes.run_all(args.out, args.quick, args.seed, args.force)
            print(report.read_text())
            print(f"wrote {report} and {len(scenes.REGISTRY)} scene folders in "
                  f"{time.perf_counter() - t0:.1f} s")
        return 0
    except (ValueError, FloatingPointError) as exc:
        print(f"flexmm: error: {exc}", file=sys.stderr)
        return 2


if __name__ == "__main__":
    sys.exit(main())
