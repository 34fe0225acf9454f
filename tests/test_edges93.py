"""Edges (issue 93, a new user's walk): an option given twice is refused, not silently
replaced by its last value; a model's point says which k was asked when the ring snapped
it; the one-line errors about a model's rest state, masses and reserved names name the
cause and the remedy."""

import numpy as np
import pytest

from cli.app import main


def _one_line_error(capsys, argv):
    code = main(argv)
    err = capsys.readouterr().err.strip().splitlines()
    assert code == 2 and len(err) == 1, err
    return err[0]


@pytest.mark.parametrize("argv, option", [
    # argparse keeps the last value: a user who typed the axis twice got the second grid,
    # the paper chain's material with the second alpha, without a word
    (["map", "--model", "fput", "--param", "beta=0.5:1.5:2", "--k", "0.5:2:2",
      "--k", "1:2:2", "--theory-only", "--out", "unused"], "--k"),
    (["point", "--alpha", "2.5", "--K-s", "0.01851", "--K-theta", "0.01551", "--k", "0.8",
      "--case", "coupled", "--alpha", "3"], "--alpha"),
    (["coefficients", "--model", "fput", "--k", "1", "--amplitude=0.1", "--amplitude",
      "0.2"], "--amplitude"),
    (["point", "--model", "fput", "--k", "1", "--N", "64", "--N=128"], "--N"),
])
def test_an_option_given_twice_is_refused_in_one_line(argv, option, capsys, tmp_path,
                                                      monkeypatch):
    monkeypatch.chdir(tmp_path)
    err = _one_line_error(capsys, argv)
    assert f"{option} given twice" in err and "give it once" in err
    assert not (tmp_path / "unused").exists()


def test_flags_and_repeatable_options_may_repeat(capsys):
    assert main(["coefficients", "--model", "fput", "--param", "alpha=1", "--param",
                 "beta=1", "--k", "1", "--json", "--json"]) == 0


def test_a_models_point_says_which_k_was_asked_when_the_ring_snapped_it(capsys):
    # 2 pi / 9 = 0.698 is the nearest k a ring of 9 sites carries to 1: a 30% change the
    # user must see, as the paper chain's point says it
    assert main(["point", "--model", "fput", "--k", "1", "--N", "9",
                 "--amplitude", "0.1"]) == 0
    carrier = next(l for l in capsys.readouterr().out.splitlines()
                   if l.startswith("carrier:"))
    assert "k = 0.698132" in carrier and "asked 1" in carrier


def test_a_models_point_on_the_ring_says_no_asked_k(capsys):
    assert main(["point", "--model", "fput", "--k", "1.5707963267948966", "--N", "64",
                 "--amplitude", "0.1"]) == 0
    assert "asked" not in capsys.readouterr().out


def test_an_energy_divided_by_a_zero_parameter_names_the_division(toda, capsys, tmp_path):
    # the Toda chain's a/b (...) at b = 0 is 0/0 at rest: the message guessed a square root
    (tmp_path / "toda.toml").write_text(toda)
    err = _one_line_error(capsys, ["coefficients", "--model", str(tmp_path / "toda.toml"),
                                   "--param", "b=0", "--k", "1"])
    assert "division by zero" in err
    err = _one_line_error(capsys, ["map", "--model", str(tmp_path / "toda.toml"),
                                   "--param", "b=0:1:2", "--k", "0.5:2:2", "--theory-only",
                                   "--out", str(tmp_path / "m")])
    assert "division by zero" in err and "--param b=0" in err


def test_a_negative_mass_names_the_parameters_to_change(toda, capsys, tmp_path):
    (tmp_path / "m.toml").write_text(toda.replace('name = "toda"', 'name = "heavy"')
                                     .replace("a = 1.0", "a = 1.0\nm = -1.0")
                                     .replace('"u_t**2/2"', '"m*u_t**2/2"'))
    err = _one_line_error(capsys, ["coefficients", "--model", str(tmp_path / "m.toml"),
                                   "--k", "1"])
    assert "mass of u is not > 0" in err and "m*u_t**2/2" in err and "--param m" in err


def test_a_field_named_pi_is_told_to_rename(toda, capsys, tmp_path):
    (tmp_path / "pi.toml").write_text(toda.replace('["u"]', '["pi"]'))
    err = _one_line_error(capsys, ["coefficients", "--model", str(tmp_path / "pi.toml"),
                                   "--k", "1"])
    assert "'pi'" in err and "rename it" in err


def test_a_map_estimate_probing_a_cell_with_no_wave_neither_fails_nor_warns(toda, tmp_path):
    """The estimate runs one cell; at Toda's amplitude 2000 exp overflows along the wave, so
    scipy's solver refused its start ('Residuals are not finite in the initial point'):
    the whole map ended in that line, though its cells say 'undetermined' there."""
    import warnings

    from numerics.maps import ModelMapParameters
    from numerics.maps._estimate import probe_model_cell

    (tmp_path / "toda.toml").write_text(toda)
    params = ModelMapParameters.from_model(str(tmp_path / "toda.toml"),
                                           ("amplitude", [1.0, 2000.0]), ("k", [1.0, 2.0]),
                                           None, N=64, t_end=200.0)
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        cost = probe_model_cell(params)
    # the middle cell (amplitude 2000) has no wave to run: a corner's run is timed instead
    # (it counted the runs as 0 s, an estimate too low by every cell's run)
    assert cost.theory > 0 and cost.run > 0.0 and cost.t_end == 200.0
    assert not [w for w in caught if issubclass(w.category, RuntimeWarning)], caught


def test_models_given_a_file_says_where_a_file_goes(toda, capsys, tmp_path):
    # a newcomer's `flexmm models mine.toml` (to see their model) named only the built-ins
    (tmp_path / "toda.toml").write_text(toda)
    err = _one_line_error(capsys, ["models", str(tmp_path / "toda.toml")])
    assert f"--model {tmp_path / 'toda.toml'}" in err and "flexmm coefficients" in err


def test_a_simulated_paper_map_says_what_its_runs_found(tmp_path, capsys):
    """It printed the theories' agreement with the runs, never the runs' own share of MI
    (a model map prints 'MI share, simulated'); the share is read back from the store."""
    import xarray as xr

    out = tmp_path / "m"
    assert main(["map", "--alpha", "2.5", "--K-s", "0.01851", "--delta", "0.003", "--k",
                 "0.8,1.0", "--case", "coupled", "--N", "64", "--t-end", "200",
                 "--workers", "1", "--out", str(out)]) == 0
    lines = capsys.readouterr().out.strip().splitlines()
    runs = xr.open_zarr(out / "map.zarr")["verdict_simulated"].values.ravel()
    assert (runs >= 0).all()
    share = f"{100 * (runs == 1).mean():.0f}%"
    line = next(ln for ln in lines if ln.startswith("MI (grows more than 20x within T = 200)"))
    assert f"in: simulated {share} of cells;" in line
    assert lines[-1].startswith("wrote ")


@pytest.mark.parametrize("values, name", [("0.01,2e-6,0.02,1e4,185,0", "k_theta"),
                                          ("0.01,2e-6,0.02,0,185,1", "k_l")])
def test_a_bad_physical_value_names_the_option(values, name, capsys):
    # 'k_theta must be finite and > 0' named no option: --physical's sixth value it is
    err = _one_line_error(capsys, ["coefficients", "--physical", values, "--k", "1"])
    assert err.startswith("flexmm: error: --physical m,J,a,k_l,k_s,k_theta: ")
    assert f"{name} must be finite and > 0" in err


def test_a_run_that_blows_up_says_so_without_numpys_overflow_warnings(toda, tmp_path):
    """A softening chain (bond r^2/2 - r^4) launched at a = 0.3, k = 5 pi/8 escapes to
    infinity: the run's records squared a state past 1e154 before the stepper saw a
    non-finite one, and a map's workers printed numpy's 'overflow encountered in square'
    after the cell's verdict. The run says it blew up (a point's); a map cell's run stops
    at the record that left the range (its saturation stop), as before, in silence."""
    import warnings

    from energy import load_model
    from numerics.models import simulate_model

    (tmp_path / "soft.toml").write_text(toda.replace('name = "toda"', 'name = "soft"')
                                        .replace("a/b*(exp(-b*(u_next - u)) - 1 + b*(u_next"
                                                 " - u))", "(u_next - u)**2/2 - "
                                                 "(u_next - u)**4"))
    model = load_model(str(tmp_path / "soft.toml"))
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        with pytest.raises(FloatingPointError, match="the run blew up by t = "):
            simulate_model(model, 5 * np.pi / 8, 0.3, N=32, t_end=300.0, seed=0)
        run = simulate_model(model, 5 * np.pi / 8, 0.3, N=32, t_end=300.0, seed=0,
                             until_saturated=True, energy=False)
    assert not [w for w in caught if issubclass(w.category, RuntimeWarning)], caught
    assert run.t[-1] < 300.0 and not np.isfinite(run.deviation[-1])  # left the range


def test_an_interrupted_soliton_says_what_it_wrote(tmp_path, capsys, monkeypatch):
    # a point said 'nothing was written to OUT'; a soliton, which writes at its end too,
    # said only 'interrupted (SIGINT)'
    from cli import soliton as soliton_command

    def interrupted(*_a, **_k):
        raise KeyboardInterrupt

    monkeypatch.setattr(soliton_command, "simulate_soliton", interrupted)
    out = tmp_path / "s"
    code = main(["soliton", "--alpha", "2.5", "--K-s", "0.01851", "--K-theta", "0.02151",
                 "--k", "0.92991", "--amplitude", "0.002", "--case", "rotation",
                 "--simulate", "--travel", "1", "--out", str(out)])
    err = capsys.readouterr().err.strip().splitlines()
    assert code == 130 and err == [f"flexmm: interrupted (SIGINT); nothing was written to "
                                   f"{out}"]
    assert not out.exists()


def test_a_map_k_no_ring_carries_is_not_told_a_larger_n(capsys, tmp_path):
    # k = 3.14159 is 2.7e-6 from pi: a ring carrying it needs N ~ 2.4e6 > 10^6, the bound;
    # the map said 'give a larger N', the point says to choose k <= 3.129
    err = _one_line_error(capsys, ["map", "--alpha", "2.5", "--K-s", "0.01851", "--case",
                                   "rotation", "--theory-only", "--delta", "0.003", "--k",
                                   "3.1,3.14159", "--out", str(tmp_path / "m")])
    assert "snaps to pi" in err and "choose k <= 3.129" in err
    assert "no chain of up to 10^6 sites" in err and "larger N" not in err


TWO_FIELDS = """
name = "two-field"
fields = ["u", "v"]
[parameters]
c = 0.3
[energy]
kinetic = "u_t**2/2 + 2*v_t**2/2"
bond = "(u_next - u)**2/2 + (v_next - v)**2/2 + (u_next - u)**4/4"
site = "c*(u - v)**2/2"
"""


def test_a_map_axis_through_an_unstable_rest_state_is_refused(capsys, tmp_path):
    """c < 0 pushes u and v apart: omega^2 = 2c (1 + 1/2) < 0 at k = 0 (-0.15 at c = -0.1),
    which a point refuses; the map called those cells MI at the NLS's rate."""
    (tmp_path / "two.toml").write_text(TWO_FIELDS)
    err = _one_line_error(capsys, ["map", "--model", str(tmp_path / "two.toml"), "--param",
                                   "c=-0.1,0.3", "--k", "1,2", "--amplitude", "0.1",
                                   "--theory-only", "--out", str(tmp_path / "m")])
    assert err.startswith("flexmm: error: --param c=-0.1: the rest state is not a minimum")
    assert "omega^2 = -0.15 < 0 at k = 0" in err and "leave such values out" in err
    assert not (tmp_path / "m").exists()


def test_a_rest_state_that_is_no_equilibrium_gets_a_remedy(toda, capsys, tmp_path):
    # site f u is a constant force: the error named the force only
    (tmp_path / "lin.toml").write_text(toda.replace('name = "toda"', 'name = "lin"')
                                       .replace("a/b*(exp(-b*(u_next - u)) - 1 + b*(u_next"
                                                " - u))", "(u_next - u)**2/2")
                                       + 'site = "u**2/2 + a*u"\n')
    err = _one_line_error(capsys, ["coefficients", "--model", str(tmp_path / "lin.toml"),
                                   "--k", "1"])
    assert "is not an equilibrium: the force on u there is -a" in err
    assert "remove the energy's terms linear in the fields" in err
