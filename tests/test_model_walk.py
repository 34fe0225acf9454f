"""A new user's walk through the model path (README "Your own lattice", docs/models.md,
docs/maps.md): each test is a mistake or a surprise met on the way, fixed, and fails
without its fix."""

from __future__ import annotations

import pytest

from cli.app import main


@pytest.fixture
def no_run(monkeypatch):
    """The map engine replaced by a failure: a map that should be refused before its
    work fails at once, not after minutes of it. (cli.map binds run_map at its import:
    imported first, so that it keeps the real one for the tests after this one.)"""
    import cli.map  # noqa: F401
    import numerics.maps

    def ran(*a, **kw):
        raise RuntimeError("the map ran")

    monkeypatch.setattr(numerics.maps, "run_map", ran)


def _map(tmp_path, *extra):
    return ["map", "--model", "fput", "--amplitude", "0.1", "--workers", "1",
            "--out", str(tmp_path / "m"), *extra]


def test_a_model_map_of_too_many_cells_is_refused_before_any_work(tmp_path, capsys,
                                                                  no_run):
    """3000 x 3000 cells ran for minutes (theory-only) and 1e5 x 1e5 died on a 75 GiB
    allocation; the paper chain's map refuses more than 250 000 cells, and so does a
    model's, naming the options that asked for them."""
    assert main(_map(tmp_path, "--param", "beta=1:2:1000", "--k", "1:2:1000",
                     "--theory-only")) == 2
    err = capsys.readouterr().err
    assert "--param beta and --k ask for 1000000 cells; at most 250000" in err
    assert len(err.strip().splitlines()) == 1
    assert not (tmp_path / "m").exists()


def test_a_model_map_estimated_beyond_an_hour_asks_for_yes(tmp_path, capsys, no_run):
    """As the paper chain's map: an estimate above an hour is refused without --yes (a
    model map started hours of work unasked, and refused --yes). 400 stable cells (beta
    < 0: defocusing, no run stops early) of T = 1e9: each run's cost is measured here and
    scaled by T: ~1000 h on this 2-core machine (10 h at T = 1e7), beyond the gate's hour
    on any CPU."""
    argv = _map(tmp_path, "--param", "beta=-1:-0.5:20", "--k", "0.5:1.4:20", "--N", "64",
                "--t-end", "1e9")
    assert main(argv) == 2
    err = capsys.readouterr().err
    assert "add --yes to run it" in err and "> 60 min" in err
    assert not (tmp_path / "m" / "map.zarr").exists()
    with pytest.raises(RuntimeError, match="the map ran"):  # --yes passes the gate
        main(argv + ["--yes"])


def test_a_resumed_model_map_estimates_the_cells_left(tmp_path, capsys, interrupt_map):
    """A resumed map's estimate was of every cell (and its resume line gave another,
    rough, figure): it is of the cells left, and says so."""
    argv = _map(tmp_path, "--param", "beta=0.5,1", "--k", "1,2", "--theory-only")
    assert main(argv) == 0
    capsys.readouterr()
    interrupt_map(tmp_path / "m")  # one cell not computed
    assert main(argv) == 0
    out = capsys.readouterr().out
    assert "for 1 of its 4 cells (the other 3 are in the store)" in out
    assert "3 of 4 cells already done" in out
    # the estimate line and the resume line just below it count the same: the cells left,
    # the workers' start-up included (it comes after both lines); they said 18 s and 6 s
    import re

    said = re.search(r"estimate: about (.+?) for 1 of its 4 cells", out).group(1)
    assert f"1 to predict (about {said})" in out


def test_a_store_of_other_axes_is_refused_naming_the_axis(tmp_path, capsys):
    """A rerun with another grid said "with other parameters" and nothing more: the axis
    that differs is named, with the store's values and the asked ones."""
    base = _map(tmp_path, "--param", "beta=0.5,1", "--theory-only")
    assert main(base + ["--k", "1,2"]) == 0
    capsys.readouterr()
    assert main(base + ["--k", "1,1.5,2"]) == 2
    err = capsys.readouterr().err
    assert "its axes differ: k: 2 values 1 to 2 stored, 3 values 1 to 2 asked" in err
    assert main(base + ["--k", "1,2.5"]) == 2
    assert "k: 2 values 1 to 2 stored, 2 values 1 to 2.5 asked" in capsys.readouterr().err
    # one value moved: named by its place (another --out: an option given twice is refused)
    other = [str(tmp_path / "m2") if a == str(tmp_path / "m") else a for a in base]
    assert main(other + ["--k", "1,1.5,2"]) == 0
    capsys.readouterr()
    assert main(other + ["--k", "1,1.6,2"]) == 2
    assert "its axes differ: k: value 2 is 1.5 stored, 1.6 asked" in capsys.readouterr().err
    assert main(_map(tmp_path, "--param", "beta=0.5,0.75,1", "--theory-only", "--k",
                     "1,1.5,2")) == 2
    err = capsys.readouterr().err
    assert "beta: 2 values 0.5 to 1 stored, 3 values 0.5 to 1 asked; k: 2 values" in err
    assert len(err.strip().splitlines()) == 1


HERTZ = """name = "hertz"
description = "precompressed Hertz chain: the contact opens at strain d0"
fields = ["u"]
[parameters]
d0 = 1.0
[energy]
kinetic = "u_t**2/2"
bond = "(2/5)*(d0 - (u_next - u))**(5/2)"
"""


def test_theories_at_an_amplitude_the_model_cannot_carry_say_so(tmp_path, capsys):
    """A Hertz chain at k = 2, a = 0.8: its linear wave stretches a bond by 2 a sin(k/2) =
    1.35 > d0 = 1, where the energy is not real (the largest a is d0 / (2 sin 1) = 0.594).
    The exact theory said so; the four-wave theory rated the wave from the energy's Taylor
    coefficients at rest ("stable", and MI at a = 0.9 on a map) and coefficients printed
    the NLS's gain with no word. Now the four-wave theory is undefined with the reason, and
    coefficients notes that its numbers are of a wave that cannot exist."""
    import json
    import math

    model = tmp_path / "hertz.toml"
    model.write_text(HERTZ)
    assert 0.8 * 2 * math.sin(1.0) > 1.0 > 0.3 * 2 * math.sin(1.0)
    assert main(["coefficients", "--model", str(model), "--k", "2", "--amplitude", "0.8",
                 "--json"]) == 0
    co = json.loads(capsys.readouterr().out)
    assert co["four_wave"]["verdict"] == "undefined"
    assert "the energy is not real" in co["four_wave"]["reason"]
    # the reach is a bisection to 1e-4 of the amplitude: d0 / (2 sin 1) to 3 digits
    note = f"at most a = {1 / (2 * math.sin(1.0)):.3g} at k = 2"
    assert any(note in w and "cannot carry" in w for w in co["warnings"]), co["warnings"]
    assert main(["coefficients", "--model", str(model), "--k", "2", "--amplitude",
                 "0.3"]) == 0  # a wave the model carries: no such note, a four-wave verdict
    out = capsys.readouterr().out
    assert "cannot carry" not in out and "four-wave undefined" not in out
    argv = ["map", "--model", str(model), "--amplitude", "0.3,0.9", "--k", "2,2.5",
            "--theory-only", "--exact", "--N", "32", "--workers", "1",
            "--out", str(tmp_path / "m")]
    assert main(argv) == 0
    capsys.readouterr()
    import xarray as xr

    with xr.open_zarr(tmp_path / "m" / "map.zarr") as ds:
        beyond = ds["verdict_exact"].values[1] < 0  # a = 0.9: beyond d0 at both k
        assert beyond.all()
        assert (ds["verdict_fourwave"].values[1] == -1).all()
        assert (ds["verdict_fourwave"].values[0] >= 0).all()


def test_a_model_file_whose_energy_ends_too_soon_says_where(tmp_path, capsys):
    """A trailing '+' (a line cut while editing) was 'syntax error ... at column 0': the
    error says it is at the expression's end; an error inside keeps its column."""
    text = HERTZ.replace('bond = "(2/5)*(d0 - (u_next - u))**(5/2)"',
                         'bond = "(2/5)*(d0 - (u_next - u))**(5/2) +"')
    (tmp_path / "cut.toml").write_text(text)
    assert main(["coefficients", "--model", str(tmp_path / "cut.toml"), "--k", "1"]) == 2
    err = capsys.readouterr().err
    assert "energy.bond: syntax error in" in err and "at its end" in err
    assert "column 0" not in err and len(err.strip().splitlines()) == 1
    (tmp_path / "inside.toml").write_text(text.replace("**(5/2) +", "** * (5/2)"))
    assert main(["coefficients", "--model", str(tmp_path / "inside.toml"), "--k", "1"]) == 2
    # the lone "*" after "** " is character 29 (1-based, as Python counts)
    assert "at column 29: invalid syntax" in capsys.readouterr().err


def test_output_piped_into_a_reader_that_stops_is_not_an_error():
    """`flexmm coefficients ... | head -2` printed 'flexmm: error: Broken pipe': a reader
    that has what it wanted is no error (silent, exit 141 as for SIGPIPE)."""
    import subprocess
    import sys

    p = subprocess.Popen([sys.executable, "-m", "cli", "coefficients", "--model", "fput",
                          "--k", "1", "--amplitude", "0.1"], stdout=subprocess.PIPE,
                         stderr=subprocess.PIPE)
    p.stdout.close()  # the reader leaves before the first line (the imports take ~1 s)
    err = p.stderr.read().decode()
    assert p.wait(timeout=120) == 141, err
    assert err == "", err


ROTOR = """name = "rotor-chain"
description = "a sliding field u and a rotation phi per cell, coupled through cos(phi)"
fields = ["u", "phi"]
[parameters]
k_l = 1.0
k_r = 0.1
J = 0.5
a = 1.0
[energy]
kinetic = "u_t**2/2 + J*phi_t**2/2"
bond = "k_l*(u_next - u + a*(cos(phi_next) - cos(phi)))**2/2 + k_r*(phi_next + phi)**2/2"
site = "k_r*phi**2/2"
"""


def test_a_point_where_the_nls_grows_and_the_lattice_does_not_says_so(tmp_path, capsys):
    """A two-field rotor chain (a user's first model) at k = 1, a = 0.05 on 64 sites: the
    semi-discrete NLS says MI at ~0.006 /time, the exact lattice nothing, and a run of
    T = 5000 (where 0.006 /time would grow e^30) shows no growth. The table showed the two
    rows side by side with no word on which to trust (only the opposite case, exact well
    above the NLS, had a note)."""
    model = tmp_path / "rotor.toml"
    model.write_text(ROTOR)
    assert main(["point", "--model", str(model), "--k", "1", "--amplitude", "0.05",
                 "--N", "64", "--simulate", "--seeds", "1"]) == 0
    out = capsys.readouterr().out
    rows = {ln.split()[0]: ln.split() for ln in out.splitlines()
            if ln.startswith(("semi-discrete", "exact", "simulated "))}
    assert rows["semi-discrete"][2] == "MI" and float(rows["semi-discrete"][3]) > 1e-3
    assert rows["exact"][2] == "stable"
    assert "simulated: no growth within T" in out  # the lattice itself sides with exact
    assert "note: the semi-discrete NLS's sidebands grow on this ring" in out
    assert "nothing grows there in the exact lattice theory" in out
    # where the two agree (FPUT, alpha 0, k 2: both MI, 0.0177 and 0.017) no such note
    assert main(["point", "--model", "fput", "--k", "2", "--amplitude", "0.1",
                 "--N", "64"]) == 0
    assert "nothing grows there in the exact" not in capsys.readouterr().out


@pytest.mark.parametrize("energy, param", [
    ('site = "sqrt(u - 1)"', []),  # sqrt(-1) at rest for any c: said 'not an equilibrium:
    # the force on u there is I/2'
    ('site = "u**2/2 + log(u**2 - 1)"', []),  # log(-1): 'not a minimum: omega^2 = -1'
    ('site = "u**2/2 + sqrt(u**2 - c)"', []),  # sqrt(-1) at rest
    ('site = "u**2/2 + log(u**2 + 1 - c)"', ["--param", "c=2"]),  # log(-1) at c = 2
    (None, ["--param", "d0=-1"]),  # a Hertz contact open at rest: (d0 - r)**(5/2) at d0 < 0
])
def test_an_energy_not_real_at_rest_is_refused_in_one_line(tmp_path, capsys, energy, param):
    """An energy that is complex at rest for the parameters' values (the derivation's
    symbolic checks hold for every value, so they pass it): coefficients printed omega =
    nan, g2 '-' and RuntimeWarnings naming the cache's generated file, or refused it as 'not
    a minimum: omega^2 = -1'. Now one line: the energy is not real at the rest state."""
    text = HERTZ if energy is None else (
        'name = "bad"\nfields = ["u"]\n[parameters]\nc = 1.0\n[energy]\n'
        f'kinetic = "u_t**2/2"\nbond = "(u_next - u)**2/2"\n{energy}\n')
    (tmp_path / "m.toml").write_text(text)
    assert main(["coefficients", "--model", str(tmp_path / "m.toml"), "--k", "1",
                 "--amplitude", "0.1", *param]) == 2
    err = capsys.readouterr().err
    assert "the energy is not real at the rest state (every field 0)" in err, err
    assert len(err.strip().splitlines()) == 1, err


def test_a_map_axis_through_values_without_a_rest_state_is_refused(tmp_path, capsys):
    """A Hertz map over d0 = -1, 1: at d0 < 0 the contact is open at rest and the energy
    complex. The map ran, printed a dozen RuntimeWarnings naming the cache's generated
    file and left those cells undefined with no reason; now refused before any work,
    naming the value."""
    (tmp_path / "hertz.toml").write_text(HERTZ)
    assert main(["map", "--model", str(tmp_path / "hertz.toml"), "--param", "d0=-1,1",
                 "--k", "1,2", "--amplitude", "0.1", "--theory-only", "--workers", "1",
                 "--out", str(tmp_path / "m")]) == 2
    err = capsys.readouterr().err
    assert err.startswith("flexmm: error: --param d0=-1: the energy of hertz is not real "
                          "at the rest state"), err
    assert len(err.strip().splitlines()) == 1 and not (tmp_path / "m").exists()


def test_physical_with_a_model_names_the_model_units_options(capsys):
    """--physical (the paper chain's SI material) with --model pointed to --param only; a
    user after SI answers needs --time-unit and --length-unit (docs/models.md, Units)."""
    assert main(["coefficients", "--model", "fput", "--k", "1", "--physical",
                 "0.01,2e-6,0.02,1e4,185,1"]) == 2
    err = capsys.readouterr().err
    assert "--physical: the paper chain's flags" in err
    assert "--time-unit SECONDS and --length-unit METRES" in err
    assert main(["coefficients", "--model", "fput", "--k", "1", "--time-unit", "0.001",
                 "--length-unit", "0.01"]) == 0  # the options it names work as named
    assert "1 time unit = 0.001 s (--time-unit)" in capsys.readouterr().out


def test_a_simulated_model_map_prints_its_agreement_with_the_runs(tmp_path, capsys):
    """A simulated model map printed each theory's MI share but not how often it agreed
    with the runs (only summary.json had it, the paper map prints it): the line is there,
    with the shares the store's verdicts give."""
    import json

    import numpy as np
    import xarray as xr

    assert main(_map(tmp_path, "--param", "alpha=1", "--param", "beta=0.8,1.6", "--k",
                     "2.0,2.8", "--N", "64")) == 0
    out = capsys.readouterr().out
    line = next(ln for ln in out.splitlines() if ln.startswith("agreement with the runs"))
    with xr.open_zarr(tmp_path / "m" / "map.zarr") as ds:
        sim = ds["verdict_simulated"].values
        for name in ("semidiscrete", "fourwave", "exact"):
            v = ds[f"verdict_{name}"].values
            decided = v >= 0
            share = 100 * np.mean(v[decided] == sim[decided])
            assert f"{name} {share:.0f}%" in line, line
    summary = json.loads((tmp_path / "m" / "summary.json").read_text())
    assert f"exact {summary['agreement_with_simulation_percent']['exact']:.0f}%" in line


def test_run_options_on_a_theory_only_map_name_the_right_remedy(tmp_path, capsys):
    """--seeds on a --theory-only map said 'drop them, or --theory-only' to a user who had
    given --theory-only: the remedy is to drop --theory-only (or the option given)."""
    assert main(_map(tmp_path, "--param", "beta=1,2", "--k", "1,2", "--theory-only",
                     "--seeds", "3")) == 2
    err = capsys.readouterr().err
    assert "--seeds: acts on a simulated model map's runs" in err
    assert "drop it, or drop --theory-only" in err and "--t-end" not in err


def test_a_resumed_map_given_another_block_says_to_omit_it(tmp_path, capsys):
    """A map resumed with another --block (the cells a task takes; the store keeps its
    own) was refused with only '--overwrite, or another --out', which would throw its
    finished cells away; without --block it continues."""
    base = _map(tmp_path, "--param", "beta=1,2", "--k", "1,2", "--theory-only")
    assert main(base + ["--block", "1"]) == 0
    capsys.readouterr()
    assert main(base + ["--block", "2"]) == 2
    assert "(block 1 stored, 2 asked: omit --block to continue with the store's)" in (
        capsys.readouterr().err)
    assert main(base) == 0  # as the error says
    assert "4 of 4 cells already done" in capsys.readouterr().out


@pytest.mark.parametrize("given, said", [
    ("betta=1", "--param betta: model 'fput' has no parameter 'betta'; did you mean 'beta'?"),
    ("Alpha=1", "--param Alpha: model 'fput' has no parameter 'Alpha'; did you mean 'alpha'?"),
    ("zzz=1", "--param zzz: model 'fput' has no parameter 'zzz' (it has: alpha, beta)"),
])
def test_a_parameter_typo_names_the_option_and_the_likely_name(tmp_path, capsys, given,
                                                              said):
    """'model 'fput' has no parameter 'betta'' named neither the option nor the name
    meant; a map's axis ('betta=1,2') is refused in the same words."""
    assert main(["coefficients", "--model", "fput", "--param", given, "--k", "1"]) == 2
    err = capsys.readouterr().err
    assert said in err and len(err.strip().splitlines()) == 1, err
    axis = given.replace("=1", "=1,2")
    assert main(["map", "--model", "fput", "--param", axis, "--k", "1,2", "--theory-only",
                 "--out", str(tmp_path / "m")]) == 2
    assert said in capsys.readouterr().err


def test_a_typo_in_a_model_file_names_the_likely_symbol(tmp_path, capsys):
    """'unknown symbol 'betta'' in a model file: the declared name it likely meant is said
    (case too); a symbol close to none ('I', the imaginary unit) gets no guess."""
    for typo, said in (("betta", " (did you mean 'beta'?)"), ("Beta", " (did you mean "
                                                                      "'beta'?)"),
                       ("I", "")):
        text = HERTZ.replace("[parameters]\nd0 = 1.0", "[parameters]\nd0 = 1.0\nbeta = 1.0")
        text = text.replace('(5/2)"', f'(5/2) + {typo}*(u_next - u)**4"')
        (tmp_path / "m.toml").write_text(text)
        assert main(["coefficients", "--model", str(tmp_path / "m.toml"), "--k", "1"]) == 2
        err = capsys.readouterr().err
        assert f"energy.bond: unknown symbol {typo!r}{said}; allowed here: beta, d0, u" in err


def test_point_json_carries_the_tables_notes(tmp_path, capsys):
    """The table's notes (the NLS against the exact theory, a band the ring misses) were
    printed only: --json and point.json had no word of them. Now a "notes" list."""
    import json

    model = tmp_path / "rotor.toml"
    model.write_text(ROTOR)
    argv = ["point", "--model", str(model), "--k", "1", "--amplitude", "0.05", "--N", "64"]
    assert main(argv) == 0
    printed = [ln.removeprefix("note: ") for ln in capsys.readouterr().out.splitlines()
               if ln.startswith("note: the semi-discrete NLS's sidebands")]
    assert main(argv + ["--json", "--out", str(tmp_path / "p")]) == 0
    notes = json.loads(capsys.readouterr().out)["notes"]
    assert printed and printed[0] in notes
    assert json.loads((tmp_path / "p" / "point.json").read_text())["notes"] == notes


def test_a_resumed_paper_map_estimates_the_cells_left(tmp_path, capsys, interrupt_map):
    """The paper chain's map as a model's: its estimate (and the --yes gate on it) was of
    every cell of a resumed map; it is of the cells left, and says so."""
    argv = ["map", "--alpha", "2.5", "--K-s", "0.01851", "--delta=-0.003,0.003", "--k",
            "0.5,1", "--case", "coupled", "--theory-only", "--N", "64", "--workers", "1",
            "--out", str(tmp_path / "m")]
    assert main(argv) == 0
    assert " left (" not in capsys.readouterr().out
    interrupt_map(tmp_path / "m")
    assert main(argv) == 0
    out = capsys.readouterr().out
    assert "for the 1 left (3 in the store)" in out
    assert "3 of 4 cells already done" in out


def test_exact_on_a_simulated_map_gives_the_remedy(tmp_path, capsys):
    """'--exact: a simulated model map has the exact lattice theory per cell already' said
    what, not what to do: a user who wanted the theories alone needs --theory-only."""
    assert main(_map(tmp_path, "--param", "beta=1,2", "--k", "1,2", "--exact")) == 2
    err = capsys.readouterr().err
    assert "drop --exact, or add --theory-only" in err
    assert main(_map(tmp_path, "--param", "beta=1,2", "--k", "1,2", "--exact", "--N", "32",
                     "--theory-only")) == 0  # the remedy runs


def test_the_map_help_examples_run_one_after_the_other(tmp_path, capsys, monkeypatch):
    """`flexmm map --help` gave both examples --out out/map: the second, run after the
    first as a reader would, was refused as 'a map with other parameters (or of an older
    format)' while the store held a model's map. Each example has its own folder, and a
    paper map meeting a model's store says whose it is."""
    import shlex

    from cli.app import EPILOG

    monkeypatch.chdir(tmp_path)
    lines = [ln.strip() for ln in EPILOG["map"].splitlines()
             if ln.strip().startswith("flexmm map")]
    assert len(lines) == 2
    for line in lines:
        assert main(shlex.split(line)[1:]) == 0, capsys.readouterr().err
    capsys.readouterr()
    model_out = shlex.split(lines[0])[shlex.split(lines[0]).index("--out") + 1]
    paper = shlex.split(lines[1])[1:]
    paper[paper.index("--out") + 1] = model_out  # the paper map into the model's folder
    assert main(paper) == 2
    assert "holds a map of model 'fput' (flexmm map --model)" in capsys.readouterr().err


def test_models_name_prints_a_template_that_loads(tmp_path, capsys):
    """A user writing a model file had the format in docs/models.md but no file to start
    from: `flexmm models NAME` prints a built-in's file; saved under another name it is a
    model of its own that loads and answers as the built-in does."""
    import json

    assert main(["models", "diatomic-fput"]) == 0
    text = capsys.readouterr().out
    mine = tmp_path / "mine.toml"
    mine.write_text(text.replace('name = "diatomic-fput"', 'name = "mine"'))
    argv = ["coefficients", "--k", "1", "--amplitude", "0.05", "--json", "--model"]
    assert main(argv + ["diatomic-fput"]) == 0
    builtin = json.loads(capsys.readouterr().out)
    assert main(argv + [str(mine)]) == 0
    own = json.loads(capsys.readouterr().out)
    assert own["model"] == "mine" and own["g2"] == builtin["g2"]
    assert main(["models", "fpu"]) == 2
    assert "no built-in model 'fpu'; built-in: diatomic-fput" in capsys.readouterr().err
