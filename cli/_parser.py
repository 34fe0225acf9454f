"""The parser of `flexmm`: its commands, their options, defaults and example epilogs
(``cli.app`` runs what it parses)."""

from __future__ import annotations

import argparse

from common import paper

from .models import add_model_args

#: the first example line of each command runs in the tests (tests/test_cli_help.py); a
#: command that takes --model shows one for any model first, then the paper chain's shorthand
EPILOG = {
    "models": "example:\n  flexmm models\n  flexmm models fput > mine.toml\n  "
              "flexmm coefficients --model fput --param alpha=1 "
              "--param beta=1 --k 1.57 --amplitude 0.1",
    "coefficients": "examples:\n  any model:\n  flexmm coefficients --model fput --param alpha=1 "
                    "--param beta=1 --k 1.57 --amplitude 0.1\n  the paper chain:\n  "
                    "flexmm coefficients --alpha 2.5 --K-s 0.01851 --K-theta 0.01551 "
                    "--k 0.81681",
    "table": "example:\n  flexmm table --A0 1.4",
    "scenes": "example:\n  flexmm scenes",
    "scene": "example:\n  flexmm scene fig2-dispersion --quick --out out",
    "run": "example:\n  flexmm run --quick --out out",
    "point": "examples:\n  any model:\n  flexmm point --model fput --param alpha=1 --param beta=1.5 "
             "--k 2.5 --amplitude 0.1 --N 64 --out out/point\n  flexmm point --model fput "
             "--param alpha=1 --param beta=1.5 --k 3.1 --amplitude 0.1 --N 64 --simulate "
             "--seeds 2 --out out/point\n  the paper chain:\n  flexmm point --alpha 2.5 "
             "--K-s 0.01851 --K-theta 0.01551 --k 0.81681 --case coupled\n  flexmm point "
             "--physical 0.01,2e-6,0.02,1e4,185,1 --k 1.0 --amplitude 0.1 --case rotation "
             "--simulate --seeds 2 --out out/point",
    "soliton": "examples:\n  any model:\n  flexmm soliton --model fput --param alpha=1 "
               "--param beta=1 --k 1.0 --amplitude 0.05\n  flexmm soliton --model fput "
               "--param alpha=0.5 --k 1.6 --amplitude 0.1 --simulate --travel 5 --out "
               "out/soliton\n  the paper chain:\n  "
               "flexmm soliton --alpha 2.5 --K-s 0.01851 --K-theta 0.02151 --k 0.92991 "
               "--amplitude 0.002 --case rotation\n  flexmm soliton --alpha 3 --K-s 0.05 "
               "--K-theta 0.03 --k 0.7 --amplitude 0.009 --kind dark --simulate --travel 5 "
               "--out out/soliton",
    "map": "examples:\n  any model (a parameter and k swept: --param NAME=start:stop:num):\n  "
           "flexmm map --model fput --param alpha=1 --param beta=0.5:1.5:3 --k 0.5:3:4 "
           "--amplitude 0.1 --theory-only --out out/fput-map\n  the paper chain:\n  "
           "flexmm map --alpha 2.5 --K-s 0.01851 --delta -0.01:0.01:5 --k 0.3:2.9:6 "
           "--case rotation --theory-only --out out/map",
}

#: --amplitude, the same for every command that takes --model
AMPLITUDE_HELP = ("amplitude a of the carrier's first harmonic in its field (any model: the "
                  "field is a cos(k n - omega t) + higher harmonics); for the paper chain's "
                  "flags (no --model) the peak rotation, rad (the paper's 2 eps A0; "
                  "equal to leading order)")
#: the title of the paper chain's group of options
PAPER_GROUP = "the paper chain's shorthand (without --model; there required: "


class _Help(argparse.ArgumentDefaultsHelpFormatter, argparse.RawDescriptionHelpFormatter):
    """Defaults shown after every option's help; the example epilog kept as written."""

    def _get_help_string(self, action):
        # ``is``, not ``in``: 0 == False, and a default of 0 (--seed) is one to show
        if action.default is None or action.default is False \
                or "default" in (action.help or ""):
            return action.help
        return super()._get_help_string(action)


class _Parser(argparse.ArgumentParser):
    """argparse's parser, whose errors about a value it could not convert (``--N 1.5``,
    ``--amplitude x``, ``--case foo``) are one line naming the option and the remedy (the
    project's rule for bad input; raised as ValueError, which ``cli.app.main`` prints as
    ``flexmm: error: ...`` with exit code 2) instead of the usage and "invalid float
    value". Its other errors (an unknown or missing option) keep argparse's usage."""

    def error(self, message):
        said = _value_error(self, message)
        if said is None:
            super().error(message)
        raise ValueError(said)


#: a value of each type for a remedy, where the option has no default to show
_EXAMPLE = {"float": "1.2", "int": "64"}
_WHAT = {"float": "a number", "int": "a whole number"}


def _value_error(parser, message: str) -> str | None:
    """The one-line error for argparse's ``message`` about a value it could not convert,
    or None for its other errors. Every option's type and choices go through here, so no
    option needs its own converter."""
    import re

    typed = re.fullmatch(r"argument (--[\w-]+)(?:/\S+)?: invalid (float|int) value: (.*)",
                         message)
    if typed:
        option, kind, value = typed.groups()
        action = parser._option_string_actions.get(option)  # argparse's own table
        default = getattr(action, "default", None)
        example = (f"{default:g} (the default)" if isinstance(default, (int, float))
                   and not isinstance(default, bool) else _EXAMPLE[kind])
        return f"{option}: {value} is not {_WHAT[kind]}; give one such as {example}"
    chosen = re.fullmatch(r"argument (--[\w-]+)(?:/\S+)?: invalid choice: (.*) \(choose "
                          r"from (.*)\)", message)
    if chosen:
        option, value, choices = chosen.groups()
        return f"{option}: {value} is not one of {choices}; give one of them"
    return None


def _sub(sub, name, help_):
    return sub.add_parser(name, help=help_, description=help_[0].upper() + help_[1:] + ".",
                          epilog=EPILOG[name], formatter_class=_Help)


def build_parser(model_mode: bool = False):
    """The parser; ``model_mode`` (a --model on the line): the paper chain's required
    --case is not required (the model's commands refuse it)."""
    p = _Parser(  # each command's parser is one too (argparse makes them of this class)
        prog="flexmm", description="Modulation instability in flexible mechanical "
        "metamaterials: coefficients, MI verdicts, simulations, maps and the paper's figures.",
        epilog="run `flexmm COMMAND --help` for a command's options and an example")
    from importlib.metadata import version

    p.add_argument("--version", action="version",
                   version=f"%(prog)s {version('flexmm-mi')} (flexmm-mi)")
    sub = p.add_subparsers(dest="cmd", required=True, metavar="COMMAND")
    p.commands = sub.choices  # {name: its parser}, for the errors of _parse
    co = _sub(sub, "coefficients", "NLS coefficients and MI band of any model or material "
              "at any k")
    co.add_argument("--k", type=float, required=True,
                    help="(required) carrier wavenumber, rad per site, in (0, pi) (with --model "
                         "(0, pi]: the zone boundary too)")
    co.add_argument("--amplitude", type=float, default=paper.AMPLITUDE, help=AMPLITUDE_HELP)
    add_model_args(co)
    _material_args(co, map_=False)
    tab = _sub(sub, "table", "NLS coefficients at the paper's two test points")
    tab.add_argument("--A0", type=float, default=1.0, help="the paper's envelope amplitude "
                     "A0 (peak rotation 2 eps A0 with eps = 0.01)")
    _sub(sub, "scenes", "list the scenes with a description and run time")
    one = _sub(sub, "scene", "run one scene (one figure of the paper)")
    from scenes import SCENE_NAMES

    one.add_argument("name", metavar="NAME",
                     help="one of: " + ", ".join(sorted(SCENE_NAMES)))
    one.add_argument("--replot", action="store_true",
                     help="redraw the figure from OUT/NAME/data.h5 without computing")
    for sp_ in (one, _sub(sub, "run", "run every scene and write OUT/report.md")):
        sp_.add_argument("--quick", action="store_true",
                         help="reduced N / t_end / grids: seconds per scene")
        sp_.add_argument("--out", default="out", help="output folder")
        sp_.add_argument("--seed", type=int, default=0, help="noise seed")
        sp_.add_argument("--force", action="store_true", help="recompute cached simulations")
    _point_parser(sub, model_mode)
    _map_parser(sub, model_mode)
    _soliton_parser(sub, model_mode)
    ms = _sub(sub, "models", "list the built-in lattice models: their fields, parameters and "
              "what each describes")
    ms.add_argument("name", nargs="?", help="a built-in model: print its model file (a "
                    "template for your own: flexmm models fput > mine.toml)")
    ms.add_argument("--json", action="store_true", help="one JSON object on stdout")
    return p


def _material_args(p, map_=False, case=False, model_mode=False):
    """The paper chain's options, apart: its material (and --case where ``case``)."""
    g = p.add_argument_group(PAPER_GROUP + "--alpha, --K-s and "
                             + ("--K-theta or --delta" if map_ else "--K-theta, or --physical")
                             + ("; --case" if case else "") + ")")
    g.add_argument("--alpha", type=float, help="inertia parameter alpha = a sqrt(m / (4 J))")
    g.add_argument("--K-s", dest="K_s", type=float, help="shear stiffness K_s = k_s / k_l")
    if map_:
        g.add_argument("--K-theta", dest="K_theta", help="SPEC of the bending stiffness "
                       "K_theta = 4 k_theta / (k_l a^2): v1,v2,... or start:stop:num")
        g.add_argument("--delta", help="SPEC of delta = K_s - K_theta instead of --K-theta")
    else:
        g.add_argument("--K-theta", dest="K_theta", type=float,
                       help="bending stiffness K_theta = 4 k_theta / (k_l a^2)")
        g.add_argument("--physical", metavar="m,J,a,k_l,k_s,k_theta",
                       help="physical units instead: mass (kg), moment of inertia (kg m^2), "
                            "cell length (m), and the three spring stiffnesses (N/m, N/m, "
                            "N m/rad); answers then also in seconds and metres")
    if case:  # required without --model; the help says so in the group's title
        g.add_argument("--case", required=not model_mode, choices=("rotation", "coupled"),
                       help="rotation: case I, U = 0; coupled: case II, U and theta")
    return g


def _experiment_args(p):
    p.add_argument("--amplitude", type=float, default=paper.AMPLITUDE, help=AMPLITUDE_HELP)
    p.add_argument("--start", choices=("paper", "travelling", "linear"), default=None,
                   help="initial state: paper (default for the paper chain): eq. IC of the "
                        "paper (U at rest; with --model, points of the paper chain's models "
                        "flexmm and flexmm-rotation); travelling (default with --model): the "
                        "exact travelling wave; linear (--model only): the linear plane wave")
    p.add_argument("--N", type=int, default=500, help="sites of the periodic chain; k is "
                   "snapped to the nearest 2 pi m / N")


def _point_parser(sub, model_mode=False):
    p = _sub(sub, "point", "MI at one point of any model or material: the theories' "
             "verdicts and gain curves (and a simulation that checks them, with --simulate)")
    p.add_argument("--k", type=float, required=True,
                   help="(required) carrier wavenumber, rad per site, in (0, pi) (with --model "
                         "(0, pi]: the zone boundary too)")
    _experiment_args(p)
    p.add_argument("--simulate", action="store_true",
                   help="also run the ring of --N sites from noise (--seeds runs) and measure "
                        "the growth rate sigma(q) and the verdict, the theories' check")
    p.add_argument("--t-end", dest="t_end", type=float,
                   help="run length in T (default: 9 e-foldings of the exact peak gain, "
                        "within [1000, 100000]; 5000 where nothing grows; with --model "
                        "those bounds times 10/omega_max where the lowest branch's top "
                        "frequency omega_max is above 10, 0.1/omega_max below 0.1; the "
                        "output says when the cap stops a run short of the 4 e-foldings "
                        "that decide). "
                        "A run's verdict: MI, 'no growth within T' or undetermined")
    p.add_argument("--seeds", type=int, default=4, help="noise seeds of the runs (--simulate) and of the paper "
                   "chain's predicted growth factor (no runs needed); a model's point: "
                   "with --simulate only")
    p.add_argument("--out", help="folder for point.json and point.png (default: none, "
                   "print only)")
    add_model_args(p)
    _material_args(p, case=True, model_mode=model_mode)


def _soliton_parser(sub, model_mode=False):
    p = _sub(sub, "soliton", "the envelope soliton (bright or dark) a material carries at one "
             "k: width, velocity, frequency and kink of U, and with --simulate the same "
             "measured in the lattice")
    p.add_argument("--k", type=float, required=True,
                   help="(required) carrier wavenumber, rad per site, in (0, pi) (with --model "
                         "(0, pi]: the zone boundary too)")
    p.add_argument("--amplitude", type=float, default=0.002,
                   help="peak amplitude of the soliton (bright) or of its background (dark): "
                        "a of the carrier's first harmonic in its field (the paper chain: "
                        "the peak rotation, rad, the paper's 2 eps A0); the width is about "
                        "2 / (amplitude sqrt|g|) sites")
    p.add_argument("--kind", choices=("bright", "dark"),
                   help="the soliton asked for (default: the one that exists here; asking "
                        "for the other is an error that names it)")
    # the records' CLI names (numerics.theory: SEMIDISCRETE_NLS.cli, PAPER_NLS.cli; a test
    # checks them), typed here so that `--help` imports no numerics
    p.add_argument("--theory", choices=("semi-discrete", "paper"), default="semi-discrete",
                   help="the NLS that predicts it: the semi-discrete one (derived on the "
                        "lattice) or the paper's continuum one")
    p.add_argument("--simulate", action="store_true",
                   help="launch it in the lattice (srkn11b; dt = 0.25 for the paper chain, a "
                        "fifth of the stability limit for --model) and measure it")
    p.add_argument("--travel", type=float, default=20.0,
                   help="with --simulate: run until it has moved this many widths "
                        "(0.1 to 1000; shorter, the measured velocity is round-off)")
    p.add_argument("--N", type=int, help="with --simulate: ring size (default: 20 widths, at "
                   "least 256 sites); k moves to the nearest wavenumber the ring carries")
    p.add_argument("--out", help="folder for soliton.json and soliton.png (default: none, "
                   "print only)")
    add_model_args(p)
    g = _material_args(p)
    g.add_argument("--case", choices=("rotation", "coupled"),
                   default=None if model_mode else "coupled",
                   help="rotation: case I, U = 0; coupled: case II, with the kink of U")


def _map_parser(sub, model_mode=False):
    p = _sub(sub, "map", "an MI map over a model's parameter and k, two parameters, or the "
             "paper chain's (delta, k): the theories' verdicts and, unless --theory-only, "
             "simulations")
    p.add_argument("--k", required=True, help="(required) SPEC of k (rad per site): "
                   "v1,v2,... or start:stop:num (with --model one value where two "
                   "parameters are swept); each k is snapped to 2 pi m / N "
                   "(k_simulated in the dataset; the theories use it too) where the map "
                   "uses the ring: the paper chain's maps, a simulated map, --exact; a "
                   "--model --theory-only map without --exact takes k as given (the NLS "
                   "of the infinite chain; --N unused)")
    _experiment_args(p)
    p.add_argument("--exact", action="store_true",
                   help="with --model: add the exact lattice theory per cell (harmonic "
                        "balance and Hill spectrum on the ring of --N sites; measured at "
                        "N = 256: 10-30 ms CPU a cell for fput, klein-gordon, sine-gordon, "
                        "diatomic-fput, flexmm-rotation, ~0.2 s for flexmm, whose coupled "
                        "harmonics take a pencil of the central ones: bench/README.md); the "
                        "paper chain's maps have it already")
    p.add_argument("--t-end", dest="t_end", type=float, default=5000.0,
                   help="run length, T (paper chain: 5000 by default; with --model, "
                        "given: every cell's T, else each cell's from its exact rate as "
                        "`point` chooses)")
    p.add_argument("--seeds", type=int, default=1, help="noise seeds per cell")
    p.add_argument("--out", default="out/map", help="folder of map.zarr")
    p.add_argument("--overwrite", action="store_true",
                   help="discard the map.zarr in OUT (its finished cells too, whichever map "
                        "it holds) and compute the map afresh; without it the same command "
                        "resumes its map, and a store of another map is refused")
    p.add_argument("--yes", action="store_true",
                   help="run even when the estimated run time exceeds one hour")
    p.add_argument("--scheduler", help="address of a running Dask scheduler "
                   "(tcp://host:8786); default: a LocalCluster on this machine")
    p.add_argument("--workers", type=int, help="LocalCluster workers (default: the cores)")
    p.add_argument("--timeout", type=float, default=20.0,
                   help="seconds to reach --scheduler and see it answer as a Dask scheduler")
    p.add_argument("--theory-only", action="store_true",
                   help="the theories' verdicts only: no simulation")
    p.add_argument("--block", type=int, default=4,
                   help="cells per task (with --model: default 4 for a simulated map, a row "
                        "up to 64 cells for --theory-only, a store's own when resuming)")
    p.add_argument("--device", choices=("cpu", "gpu", "auto"), default="cpu",
                   help="where the cells' simulations run: cpu (a Dask cluster, default), "
                        "gpu (this machine's CUDA GPU, batches of cells in one launch; needs "
                        "the gpu extra: pip install -e '.[gpu]'), auto (the GPU where one is "
                        "usable); the theories run on the CPU")
    add_model_args(p, "print one JSON object on stdout (MI shares, files written)")
    param = next(a for a in p._actions if a.dest == "param")
    param.metavar = "NAME=VALUE|NAME=start:stop:num"
    param.help = ("with --model: a parameter of the model (repeatable): a value, or an axis swept "
                  "--param NAME=start:stop:num (or NAME=v1,v2,...); a map sweeps two axes: "
                  "one parameter and --k SPEC, or two parameters at one --k; the others "
                  "keep their defaults")
    _material_args(p, map_=True, case=True, model_mode=model_mode)
    if model_mode:  # a model's map may sweep the carrier's amplitude
        amp = next(a for a in p._actions if a.dest == "amplitude")
        amp.type = _number_or_spec
        amp.metavar = "AMPLITUDE|SPEC"
        amp.help = (AMPLITUDE_HELP + "; with --model a SPEC (v1,v2,... or start:stop:num) "
                    "makes it a map axis (with --k or one --param NAME=SPEC)")


def _number_or_spec(text: str):
    """--amplitude of a model's map: a number, or the SPEC of an axis (read by the map)."""
    try:
        return float(text)
    except ValueError:
        return text
