"""The fault catalogue's fourth round (issue 39): model files, the model cache, model maps
and the model API, each class tried with values of its own (none from the issue's report),
with its exact outcome. ``bench/faults_maps.py`` adds ``ROUND4`` to ``MAP_CATALOGUE``; the
entries' form is described in ``bench/faults.py``."""

from __future__ import annotations

import math
import os
import tempfile
from pathlib import Path

from bench._fault_helpers import E

C = "cli"


def _cli(*argv):
    from bench.faults_maps import _cli as cli

    return cli(*argv)


def _text(bond="C*(u_next - u)**2/2 + (u_next - u)**4/4", params="C = 1.0",
          description='"probe"', fields='["u"]', kinetic="u_t**2/2"):
    return (f'name = "probe4"\ndescription = {description}\nfields = {fields}\n'
            f'[parameters]\n{params}\n[energy]\nkinetic = "{kinetic}"\nbond = "{bond}"\n')


def _file(text) -> str:
    d = tempfile.mkdtemp(prefix="flexmm-faults4-")
    path = Path(d) / "m.toml"
    path.write_text(text)
    return str(path)


def _parse(**kw):
    from energy import parse_model

    return parse_model(_text(**kw))


def _injected():
    """A description that closes the docstring and writes a file when imported: the
    model derives and runs (in a cache of its own), and the file is never written."""
    out = Path(tempfile.mkdtemp(prefix="flexmm-faults4-")) / "ran"
    payload = (f"'''z\"\"\"\nopen({str(out)!r}, 'w').write('x')\n"
               "\"\"\"'''")
    old = os.environ.get("FLEXMM_CACHE")
    os.environ["FLEXMM_CACHE"] = tempfile.mkdtemp(prefix="flexmm-faults4-cache-")
    try:
        from energy import load_model
        from numerics.models import nls

        m = load_model(_parse(description=payload, params="C = 0.77"))
        return nls(m, 0.9).verdict, out.exists()
    finally:
        if old is None:
            os.environ.pop("FLEXMM_CACHE", None)
        else:
            os.environ["FLEXMM_CACHE"] = old


def _with_cache(fn):
    def run():
        old = os.environ.get("FLEXMM_CACHE")
        os.environ["FLEXMM_CACHE"] = tempfile.mkdtemp(prefix="flexmm-faults4-cache-")
        try:
            return fn()
        finally:
            if old is None:
                os.environ.pop("FLEXMM_CACHE", None)
            else:
                os.environ["FLEXMM_CACHE"] = old
    return run


def _load(**kw):
    from energy import load_model

    return load_model(_parse(**kw))


def _fput():
    from energy import load_model

    return load_model("fput", alpha=0.4)


def _exact(**kw):
    from numerics.models import exact_gain

    return exact_gain(_fput(), 1.2, 0.1, **kw)


def _run(**kw):
    from numerics.models import simulate_model

    return simulate_model(_fput(), 1.2, 0.1, N=16, t_end=5.0, **kw)


def _model_map(x=("k", [1.0, 2.0]), y=("beta", [1.0, 1.5]), amplitude=0.1):
    from numerics.models import model_map

    return model_map(_fput(), x, y, amplitude)


def _refused_map_then_corrected():
    """A refused model map leaves nothing under OUT; the corrected command then runs."""
    out = Path(tempfile.mkdtemp(prefix="flexmm-faults4-")) / "out"
    base = ["map", "--model", "fput", "--param", "beta=0.8,1.6", "--k", "2.5,2.8",
            "--amplitude", "0.1", "--N", "16", "--out", str(out)]
    bad = _cli(*base, "--t-end", "nan")
    left = out.exists()
    good = _cli(*base, "--t-end", "30")
    return bad[0], left, good[0]


M = "--model"
ROUND4 = [
    # 1. nothing of a model file runs: a description that breaks out of a docstring
    ("model: description closing the docstring with code after it", _injected,
     ("ok", lambda r: r == ("MI", False) or (r[1] is False and r[0] in ("MI", "stable")))),
    # 2. names the generated module cannot hold: keywords, built-ins, generator names
    ("model: parameter named 'def'", lambda: _parse(params="def = 1.0"),
     (E, ValueError, r"'def' is reserved \(a Python keyword\)")),
    ("model: parameter named 'len'", lambda: _parse(params="len = 1.0"),
     (E, ValueError, r"'len' is reserved \(a Python built-in\)")),
    ("model: parameter named 'cell_energy'", lambda: _parse(params="cell_energy = 1.0"),
     (E, ValueError, r"'cell_energy' is reserved \(a name the generated code uses\)")),
    ("model: field named 'pi'", lambda: _parse(fields='["pi"]', kinetic="pi_t**2/2",
                                               bond="(pi_next - pi)**2"),
     (E, ValueError, r"'pi' is a function or constant")),
    # 3. the generator's suffixes
    ("model: parameter 'z_prev'", lambda: _parse(params="z_prev = 1.0"),
     (E, ValueError, r"ends in '_prev'")),
    # 4. a name check that backtracked: 45 characters and a '-'
    ("model: a 45-character name ending in '-'", lambda: _parse(
        params=f'"{"b" * 44}-" = 1.0'), (E, ValueError, r"is not valid")),
    # 5, 6. bounds said before SymPy
    ("model: 3**4**5 as a factor", lambda: _parse(bond="3**4**5*(u_next - u)**2"),
     (E, ValueError, r"exponent .* \|exponent\| <= 64")),
    ("model: tanh nested 5 deep", lambda: _parse(bond="tanh(" * 5 + "u_next - u" + ")" * 5),
     (E, ValueError, r"nested more than 4 deep")),
    ("model: 11 fields", lambda: _parse(
        fields=str([f"a{i}" for i in range(11)]).replace("'", '"'),
        kinetic=" + ".join(f"a{i}_t**2/2" for i in range(11)), bond="0"),
     (E, ValueError, r"11 fields: at most 8")),
    ("model: a constant of 25 digits", lambda: _parse(bond="(u_next - u)**2*" + "7" * 25),
     (E, ValueError, r"larger than 1e\+15")),
    ("model: /dev/zero as a model file", lambda: _cli("coefficients", M, "/dev/zero",
                                                       "--k", "1"),
     (C, 2, r"/dev/zero: (not a regular file|the model file is larger)")),
    # 7. allowed energies derive; what cannot be derived says why
    ("model: Abs(r)**3 in the bond", _with_cache(
        lambda: _load(bond="C*(u_next - u)**2/2 + Abs(u_next - u)**3")),
     ("ok", lambda m: m.code.NAME == "probe4")),
    ("model: a mass of 0", _with_cache(lambda: _load(kinetic="0*u_t**2/2")),
     (E, ValueError, r"the mass of u is 0")),
    ("model: sqrt(u) on site", _with_cache(lambda: _load(
        bond="(u_next - u)**2 + sqrt(u**2 + 3*u)")),
     (E, ValueError, r"not differentiable at the rest state")),
    # 9. no verdict where the coefficients overflow: a parameter beyond energy.MAX_VALUE
    # is refused where it is given (probe 5), an overflow below it is undefined
    ("model_coefficients: fput alpha=1e250 is refused where it is given", lambda: __import__(
        "energy").load_model("fput", alpha=1e250),
     (E, ValueError, r"parameter alpha must be at most 1e\+15")),
    # 10, 12. model maps: refused input leaves nothing; the command's bad options
    ("map --model: --t-end nan leaves nothing; the corrected map runs",
     _refused_map_then_corrected, ("ok", lambda r: r == (2, False, 0))),
    ("map --model --exact --N 6", lambda: _cli(
        "map", M, "fput", "--param", "beta=1,2", "--k", "1,2", "--amplitude", "0.1",
        "--theory-only", "--exact", "--N", "6", "--out", "/nonexistent-flexmm/m4"),
     (C, 2, r"--N: N must be an integer in \[8, ")),
    ("map --model --branch 4 (one field)", lambda: _cli(
        "map", M, "fput", "--param", "beta=1,2", "--k", "1,2", "--amplitude", "0.1",
        "--theory-only", "--branch", "4", "--out", "/nonexistent-flexmm/m4"),
     (C, 2, r"--branch 4: give an index 0\.\.0")),
    # 15. a ring with no sideband bin
    ("point --simulate --N 11 (odd ring, every theta bin a harmonic)", lambda: _cli(
        "point", "--alpha", "2.4", "--K-s", "0.03", "--K-theta", "0.02", "--case", "coupled",
        "--k", "0.8", "--N", "11", "--simulate", "--seeds", "1"),
     (C, 2, r"no sideband to measure on a ring of N = 11")),
    # 16. the API
    ("nls: k = False", lambda: __import__("numerics.models", fromlist=["nls"]).nls(
        _fput(), False), (E, ValueError, r"k must be a real number")),
    ("exact_gain: N = 0 is not the infinite chain", lambda: _exact(N=0),
     (E, ValueError, r"N must be an integer in \[8, ")),
    ("exact_gain: samples = 3", lambda: _exact(samples=3),
     (E, ValueError, r"samples must be an integer >= 8")),
    ("exact_gain: N = 2**31", lambda: _exact(N=2**31),
     (E, ValueError, r"N must be an integer in \[8, 1048576\]")),
    ("simulate_model: records = 0", lambda: _run(records=0),
     (E, ValueError, r"records must be an integer >= 1")),
    ("simulate_model: seed = -3", lambda: _run(seed=-3),
     (E, ValueError, r"seed must be an integer >= 0")),
    ("model_map: amplitude -0.2", lambda: _model_map(amplitude=-0.2),
     (E, ValueError, r"amplitude must be > 0")),
    ("model_map: amplitude inf", lambda: _model_map(amplitude=math.inf),
     (E, ValueError, r"amplitude must be finite")),
    ("model_map: an axis holding False", lambda: _model_map(y=("beta", [1.0, False])),
     (E, ValueError, r"map axis beta needs real numbers")),
    ("Lattice: references = 3.5", lambda: __import__("energy").Lattice(
        name="x", fields=("u",), parameters={}, kinetic="u_t**2/2", bond="(u_next-u)**2",
        references=3.5), (E, ValueError, r"references must be a string")),
]
