"""`flexmm`'s entry point: parse the command line (its parser in `_parser.py`), dispatch each
subcommand (the NLS table, point, map, soliton, coefficients, models, the scenes), and turn
bad input, interruptions and a closed stdout into one-line messages and exit codes."""

from __future__ import annotations

import argparse
import math
import sys
import time
from pathlib import Path

from common.options import unused_without

from ._parser import EPILOG, build_parser

#: EPILOG (each command's examples) and build_parser: read by the tests (test_cli_help.py)
__all__ = ["EPILOG", "build_parser", "main"]

#: what float() reads after a minus sign and argparse takes for an option (``--t-end -inf``)
_NON_FINITE = ("inf", "infinity", "nan")


def _join_negative_values(argv: list) -> list:
    """``--delta -0.01:0.01:5`` as ``--delta=-0.01:0.01:5``: argparse would read a value that
    starts with '-' and holds ':' or ',' (or is -inf, -nan) as an option, so the check that
    names the option never saw it."""
    out, i = [], 0
    while i < len(argv):
        a = argv[i]
        if (a.startswith("--") and "=" not in a and i + 1 < len(argv)
                and argv[i + 1][:1] == "-" and (argv[i + 1][1:2] in "0123456789."
                                                and argv[i + 1][1:2] != ""
                                                or argv[i + 1][1:].lower() in _NON_FINITE)):
            out.append(f"{a}={argv[i + 1]}")
            i += 2
            continue
        out.append(a)
        i += 1
    return out


def _print_checks(summary):
    for c in summary.get("checks", []):
        print(f"[{c['outcome']}] {c['check']}: theory {c['theory']}; numerics {c['numerics']}")


def _quiet_stdout() -> None:
    """stdout pointed at the null device: its reader is gone, and the interpreter's last
    flush would otherwise print 'Exception ignored ... BrokenPipeError' at exit."""
    import os

    try:
        devnull = os.open(os.devnull, os.O_WRONLY)
        os.dup2(devnull, sys.stdout.fileno())
    except (OSError, ValueError, AttributeError):  # no real stdout (captured): nothing to do
        pass


def main(argv=None) -> int:
    """Run the CLI; returns the exit code (0 ok, 2 bad input or file system, 130 SIGINT,
    143 SIGTERM: both handled alike, one line saying what was kept where; 141, silent,
    where the reader of its output left, as ``| head`` does)."""
    from common.signals import exit_code, interrupts, received

    created = []  # the --out folders this command would create (removed if left empty)
    with interrupts():
        try:
            args = _parse(_join_negative_values(sys.argv[1:] if argv is None
                                                else list(argv)))
            if getattr(args, "out", None) is not None:
                args.out = args.out or "."  # --out '' is the current folder, and says so
                _check_out(args.out)
                created = _missing_folders(args.out)
            code = _run(args)
            if (interrupt := received()) is not None:
                # an interrupt that a library swallowed (raised in a __del__ or a weakref
                # callback, Python prints "Exception ignored" and goes on; probe 99: a
                # SIGTERM during soliton.png's drawing, exit 0): still the interrupt's
                raise interrupt
            return code
        except KeyboardInterrupt as exc:  # SIGINT or SIGTERM, at any moment
            _remove_if_empty(created)
            try:
                print(f"flexmm: {_interrupted(locals().get('args'), exc)}", file=sys.stderr)
            except KeyboardInterrupt:
                pass
            return exit_code(exc)
        except BrokenPipeError:  # `flexmm ... | head`: the reader has what it wanted
            _quiet_stdout()
            return 141  # as a shell reports a writer ended by SIGPIPE (128 + 13)
        except (ValueError, TypeError, FloatingPointError, MemoryError, OSError) as exc:
            _remove_if_empty(created)
            if (interrupt := received()) is not None:  # an interrupt, in another form
                print(f"flexmm: {_interrupted(locals().get('args'), interrupt)}",
                      file=sys.stderr)
                return exit_code(interrupt)
            if isinstance(exc, OSError):
                where = f" {exc.filename}:" if exc.filename else (  # else the --out it wrote
                    f" under {args.out}:" if getattr(locals().get("args"), "out", None) else "")
                print(f"flexmm: error:{where} {exc.strerror or exc}", file=sys.stderr)
            else:
                text = str(exc).splitlines()[0] if str(exc) else type(exc).__name__
                print(f"flexmm: error: {text}", file=sys.stderr)
            return 2


def _parse(argv):
    """The parsed command line. An unknown option is the command's error (its usage, not
    flexmm's), with the nearest option it has: ``--K-thetaa`` -> did you mean --K-theta?"""
    import difflib
    import re

    # --help: the usage line shows --case optional (the help's group title says where it
    # is required), as it is with --model
    p = build_parser(any(a == "--model" or a.startswith("--model=") or a in ("-h", "--help")
                         for a in argv))
    args, extra = p.parse_known_args(argv)
    sub = next(a for a in p._actions
               if isinstance(a, argparse._SubParsersAction)).choices[args.cmd]
    if extra:
        sub = p.commands[args.cmd]
        # the command's options, as its help lists them (argparse's public output)
        known = sorted(set(re.findall(r"(?<![\w-])--[A-Za-z][\w-]*", sub.format_help())))
        close = [c for e in extra if e.startswith("-")
                 for c in difflib.get_close_matches(e.split("=")[0], known, n=1)]
        sub.error(f"unrecognized arguments: {' '.join(extra)}"
                  + (f" (did you mean {close[0]}?)" if close else ""))
    _refuse_repeated(sub, argv)
    unused_without(sub, args, argv)  # an option that acts only with another, given alone
    # the options the user typed (a default that differs by command, e.g. a model map's
    # T chosen from the exact rate unless --t-end is given)
    args.given = frozenset(a.split("=", 1)[0] for a in argv if a.startswith("--"))
    return args


def _refuse_repeated(sub, argv) -> None:
    """An option of one value given twice is refused: argparse keeps the last value without
    a word, so ``--k 0.5:2:2 ... --k 1:2:2`` mapped the second grid and ``--alpha 2.5 ...
    --alpha 3`` another material. Flags and ``--param`` (one per parameter) may repeat."""
    actions = sub._option_string_actions  # argparse's own table of the command's options
    seen = {}
    for i, token in enumerate(argv):
        if not token.startswith("--"):
            continue
        name = token.split("=", 1)[0]
        matches = ([name] if name in actions  # else an abbreviation argparse accepted
                   else [o for o in actions if o.startswith(name)])
        if len(matches) != 1:
            continue
        action = actions[matches[0]]
        if action.nargs == 0 or isinstance(action, argparse._AppendAction):
            continue
        value = (token.split("=", 1)[1] if "=" in token
                 else argv[i + 1] if i + 1 < len(argv) else "")
        if action.dest in seen:
            option, before = seen[action.dest]
            raise ValueError(f"{option} given twice ({before} and {value}): give it once")
        seen[action.dest] = (action.option_strings[-1], value)


def _check_out(out) -> None:
    """--out named in the error where it is a file or lies under one, before any work (the
    commands' own checks said "X is a file, not a folder", naming no option)."""
    path = Path(out).absolute()
    base = path
    while not base.exists() and base != base.parent:
        base = base.parent
    if base.exists() and not base.is_dir():
        where = "" if base == path else f" cannot be created: {base}"
        raise ValueError(f"--out {out}{where} is a file, not a folder: give a folder (it is "
                         "created if missing)")
    from common.output import check_output

    try:  # a dangling link, a folder that takes no new entries (read-only, /proc)
        check_output(out, cache=False)
    except ValueError as exc:
        raise ValueError(f"{exc}" + ("" if "--out" in str(exc) else
                                     ": give an --out you can write to")) from None


def _missing_folders(out) -> list:
    """The folders of ``out`` that do not exist yet, deepest first."""
    path, missing = Path(out).absolute(), []
    while not path.exists() and path != path.parent:
        missing.append(path)
        path = path.parent
    return missing


def _remove_if_empty(folders) -> None:
    """A command that failed leaves no empty --out behind: each folder it created is
    removed if it holds nothing (or only an empty ``.cache``); anything written stays."""
    for folder in folders:
        try:
            if (folder / ".cache").is_dir():
                (folder / ".cache").rmdir()
            folder.rmdir()
        except OSError:  # not empty (results, a map store), or already gone
            return


def _interrupted(args, exc) -> str:
    """What an interrupt kept, and where (one line)."""
    import signal as _signal

    from common.signals import signal_number

    name = _signal.Signals(signal_number(exc)).name
    cmd = getattr(args, "cmd", None)
    if cmd in ("scene", "run"):
        where = Path(args.out) / ".cache"
        running = getattr(exc, "checkpoint", None)
        if not where.exists():  # nothing had been computed (the empty folder is gone)
            return (f"interrupted ({name}); no simulation had finished, nothing was "
                    "written: run the same command again to start")
        return (f"interrupted ({name}); finished simulations are kept in {where}"
                + (f", the running one was checkpointed in {running}" if running else
                   ", no simulation was running")
                + ": run the same command again to continue")
    if cmd == "map":  # any model's map: the one store
        store = Path(args.out) / "map.zarr"
        from numerics.maps import cells_done

        # a theory-only map's cells are predicted, not simulated: its own flag counts them
        # (probe 97: an interrupted --theory-only map said '0 of 4 cells are kept')
        done = cells_done(store, "done_predicted" if getattr(args, "theory_only", False)
                          else "done")
        if not done:  # the store is made before any cell runs: none had started
            return (f"interrupted ({name}); nothing was written to {store}, no cell had "
                    "started: run the same command again to start")
        kept = f"{done[0]} of {done[1]} cells are kept in {store} (checksummed)"
        if done[0] == done[1]:  # stopped after its last cell (probe 97: it said that
            # running cells were lost, of a map that had none left)
            return (f"interrupted ({name}); {kept}: every cell is done; run the same "
                    "command again for its summary and figure")
        return (f"interrupted ({name}); {kept}; the cells that were running were not kept: "
                "run the same command again to continue")
    if cmd in ("point", "soliton"):  # each writes its files at its end, together, or nothing
        out = getattr(args, "out", None)
        files = [Path(out) / f"{cmd}.{ext}" for ext in ("json", "png")] if out else []
        # an interrupt held back while the files were written arrives after them (probe
        # 99: the command said "nothing was written" beside a soliton.json it had written)
        from common.files import results_written

        written = {f.resolve() for f in results_written()}
        if files and all(f.resolve() in written for f in files):
            return (f"interrupted ({name}) after writing {files[0]} and {files[1]} (whole; "
                    "what came after them, the last lines, was not printed)")
        return (f"interrupted ({name}); nothing was written"
                + (f" to {args.out}" if out else ""))
    return f"interrupted ({name})"


def _run(args) -> int:
    import warnings

    import scenes
    from energy import ModelCacheWarning
    from numerics import AccuracyWarning

    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always", AccuracyWarning)
        warnings.simplefilter("always", ModelCacheWarning)
        code = _dispatch(args, scenes)
    for w in caught:
        if issubclass(w.category, (AccuracyWarning, ModelCacheWarning)):
            print(f"flexmm: warning: {w.message}", file=sys.stderr)
        else:
            warnings.showwarning(w.message, w.category, w.filename, w.lineno)
    return code


def _dispatch(args, scenes) -> int:
    if args.cmd == "models":
        from .models import run_models

        return run_models(args)
    if getattr(args, "json", False) and getattr(args, "model", None) is None:
        # what the paper chain's own command writes instead (with --out), if anything
        writes = {"point": "point.json", "soliton": "soliton.json",
                  "map": "summary.json"}.get(args.cmd)
        raise ValueError("--json: for --model commands (" + (
            f"the paper chain's {args.cmd} writes {writes} with --out; " if writes else "")
            + f"try {args.cmd} --model flexmm --param alpha=...)")
    if getattr(args, "model", None) is None:
        if getattr(args, "exact", False):
            raise ValueError("--exact: for --model maps (the paper chain's maps hold the "
                             "exact lattice theory already)")
        if hasattr(args, "start"):  # the paper chain's starts: eq. IC (default), travelling
            if args.start == "linear":
                raise ValueError("--start linear: for --model runs (the paper chain starts "
                                 "from eq. IC, 'paper', or the exact wave, 'travelling')")
            args.start = args.start or "paper"
    if args.cmd == "point":  # one point path: every model's, the paper flags' too
        from .point import run_point

        run_point(args)
        return 0
    if getattr(args, "model", None) is not None:
        from . import model_map, models

        run = {"coefficients": models.run_coefficients, "map": model_map.run_map,
               "soliton": models.run_soliton}[args.cmd]
        return run(args)
    if args.cmd == "soliton":
        from .soliton import run_soliton

        run_soliton(args)
        return 0
    if args.cmd == "map":
        from .map import run_map_command

        run_map_command(args)
        return 0
    if args.cmd == "table":
        from common import paper
        from numerics.lattice import checks
        from numerics.theory import MAX_AMPLITUDE

        from .table import format_table

        # named as the option (was 'A0 must be in (0, 75]'), the bound nls_summary's
        checks.real("--A0", args.A0, 0.0, MAX_AMPLITUDE / (2 * paper.EPS), high_open=False)
        print(format_table(args.A0))
        return 0
    if args.cmd == "coefficients":
        from .coefficients import format_coefficients
        from .point import material_from

        mat, units = material_from(args)
        from numerics.lattice import checks
        from numerics.theory import MAX_AMPLITUDE

        checks.real("--k", args.k, 0.0, math.pi)  # the option's name, as in point
        from ._resolved import check_paper_amplitude, check_peak_rotation

        check_peak_rotation(args.amplitude, MAX_AMPLITUDE)

        check_paper_amplitude(mat, args.k, args.amplitude)
        print(format_coefficients(mat, args.k, args.amplitude, units))
        return 0
    if args.cmd == "scenes":
        width = max(len(n) for n in scenes.REGISTRY)
        for sc in scenes.REGISTRY.values():
            print(f"{sc.name:<{width}}  {sc.runtime:<18}  {sc.description}")
        return 0
    t0 = time.perf_counter()
    if args.cmd in ("scene", "run"):  # named as the option ('seed must be ...' named none)
        from numerics.lattice import checks

        checks.seed(args.seed, "--seed")
    if args.cmd == "scene" and args.replot:
        if not (Path(args.out) / args.name / "data.h5").is_file():
            raise ValueError(f"--replot: {Path(args.out) / args.name / 'data.h5'} does not "
                             f"exist: run `flexmm scene {args.name} --out {args.out}` (without "
                             "--replot) first")
        folder = scenes.replot_scene(args.name, args.out)
        print(f"{args.name}: redrew {folder}/figure.png and figure.pdf from data.h5 in "
              f"{time.perf_counter() - t0:.1f} s")
    elif args.cmd == "scene":
        _print_checks(scenes.run_scene(args.name, args.out, args.quick, args.seed,
                                       args.force))
        print(f"{args.name}: wrote {Path(args.out) / args.name}/ in "
              f"{time.perf_counter() - t0:.1f} s")
    else:
        report = scenes.run_all(args.out, args.quick, args.seed, args.force,
                                log=lambda line: print(line, flush=True))
        print(report.read_text())
        print(f"wrote {report} and {len(scenes.REGISTRY)} scene folders in "
              f"{time.perf_counter() - t0:.1f} s")
    return 0


if __name__ == "__main__":
    sys.exit(main())
