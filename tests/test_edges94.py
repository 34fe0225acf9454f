"""Edges (issue 94, a second new user's walk, losses first): with losses growth is
transient, so every output of a lossy model says how much the sidebands are amplified,
when, and whether that passes 20x -- a rate or a "MI" share alone misleads."""

import json
import math

import numpy as np
import pytest
import xarray as xr

from cli.app import main

#: the lossy FPUT point of README's losses section: k on the ring of 64 sites, a = 0.2
N = 64
K = 2 * math.pi * 25 / N
AMPLITUDE = 0.2


def test_a_lossy_map_cells_growth_is_what_its_runs_showed(tmp_path, fput_lossy):
    """The map stored growth 1.0 in every cell of a lossy map, also where the run grew 167x
    and its verdict said MI: the rate rule's log-slope bound read the fall after the peak
    (a lossy run goes on until A(t) halves) as no growth."""
    from energy import load_model
    from numerics.models import map_cells

    path = tmp_path / "fput-lossy.toml"
    path.write_text(fput_lossy)
    weak, strong = map_cells(load_model(str(path)), [({"gamma": 0.01}, K),
                                                     ({"gamma": 0.03}, K)],
                             AMPLITUDE, N=N, simulate=True)
    assert weak["verdict_simulated"] == "MI"
    # one seed: its growth factor is the run's own max_t A(t) / A(0), the amplification
    # the verdict read (the verdict's "grew more than 20x" must show in the column)
    assert weak["growth"] >= 20 and weak["growth"] == weak["amplification_simulated"]
    assert strong["growth"] < 20 and strong["growth"] == strong["amplification_simulated"]


def _lossy_map(tmp_path, fput_lossy, *extra):
    path = tmp_path / "fput-lossy.toml"
    path.write_text(fput_lossy)
    out = tmp_path / "m"
    argv = ["map", "--model", str(path), "--param", "gamma=0.01,0.03", "--k", f"2.3,{K}",
            "--amplitude", str(AMPLITUDE), "--N", str(N), "--workers", "1", "--out",
            str(out), *extra]
    return argv, out


def test_a_lossy_map_says_which_cells_are_observable_and_how_the_runs_agree(
        tmp_path, fput_lossy, capsys):
    """It printed "MI share, exact: 100%" (the gain beats the damping at t = 0 everywhere)
    and "agreement with the runs: exact 25%" (that rate verdict against the runs' 20x),
    never which cells grow 20x before the losses win, the question a lossy sample asks."""
    argv, out = _lossy_map(tmp_path, fput_lossy)
    assert main(argv) == 0
    lines = capsys.readouterr().out.splitlines()
    ds = xr.open_zarr(out / "map.zarr").load()
    seen = {n: ds[f"amplification_{n}"].values >= 20
            for n in ("exact", "fourwave", "semidiscrete")}
    runs = ds["observable_simulated"].values
    seen["simulated"] = runs == 1
    assert (runs >= 0).all()  # every cell ran
    # the weak damping's cells grow past 20x in every theory, the strong one's in none:
    # the shares below are not all 0% or all 100%, so a wrong column would show
    assert seen["exact"][0].all() and not seen["exact"][1].any()
    share = next(ln for ln in lines if ln.startswith("observable (amplified 20x"))
    for name, s in seen.items():
        assert f"{name} {100 * s.mean():.0f}%" in share
    rates = next(ln for ln in lines if ln.startswith("agreement with the runs (cells"))
    assert "gain beating the damping at t = 0" in rates  # what that agreement compares
    agree = next(ln for ln in lines if ln.startswith("agreement with the runs on observable"))
    for name in ("exact", "fourwave", "semidiscrete"):
        assert f"{name} {100 * np.mean(seen[name] == seen['simulated']):.0f}%" in agree
    summary = json.loads((out / "summary.json").read_text())
    assert summary["observable_fraction"] == {n: float(s.mean()) for n, s in seen.items()}
    assert summary["observable_agreement_with_simulation_percent"]["exact"] == \
        pytest.approx(100 * np.mean(seen["exact"] == seen["simulated"]))


def test_a_lossy_theory_only_map_says_which_cells_are_observable(tmp_path, fput_lossy,
                                                                  capsys):
    argv, out = _lossy_map(tmp_path, fput_lossy, "--theory-only", "--json")
    assert main(argv) == 0
    res = json.loads(capsys.readouterr().out)
    ds = xr.open_zarr(out / "map.zarr").load()
    assert res["observable_fraction"] == {
        "semidiscrete": float(np.mean(ds["amplification_semidiscrete"].values >= 20))}
    assert "observable_agreement_with_simulation_percent" not in res


def test_a_lossless_map_says_nothing_of_observable(tmp_path, capsys):
    assert main(["map", "--model", "fput", "--param", "beta=0.5,1", "--k", "2.5,2.8",
                 "--amplitude", "0.1", "--theory-only", "--workers", "1", "--out",
                 str(tmp_path / "m")]) == 0
    assert "observable" not in capsys.readouterr().out
    assert "observable_fraction" not in json.loads((tmp_path / "m" / "summary.json")
                                                   .read_text())


def test_coefficients_of_a_lossy_model_say_the_amplification_not_a_rate_alone(
        tmp_path, fput_lossy, capsys):
    """`coefficients` printed the lossless peak gain and e-folding time of a lossy chain
    (and the carrier's damping), never that its sidebands grow only 5.5x: README's
    lossy FPUT point, whose NLS amplification `point` prints as 5.489 at t = 51.27."""
    path = tmp_path / "fput-lossy.toml"
    path.write_text(fput_lossy)
    argv = ["coefficients", "--model", str(path), "--param", "gamma=0.03", "--k", str(K),
            "--amplitude", str(AMPLITUDE)]
    assert main(argv) == 0
    line = next(ln for ln in capsys.readouterr().out.splitlines()
                if ln.startswith("with losses"))
    assert "5.489x" in line and "t = 51.27" in line and "not observable (< 20x)" in line
    assert main([*argv, "--json"]) == 0
    co = json.loads(capsys.readouterr().out)
    assert co["amplification"] == pytest.approx(5.489, abs=5e-4)
    assert co["amplification_time"] == pytest.approx(51.27, abs=5e-3)
    assert co["observable"] is False and co["units"]["lattice"]["amplification_time"] == "time"
    # weakly damped, 146-217x (README): observable
    assert main([*argv[:4], "gamma=0.012", *argv[5:]]) == 0
    assert "observable (>= 20x)" in capsys.readouterr().out


def test_coefficients_of_a_lossless_model_print_no_losses_line(capsys):
    assert main(["coefficients", "--model", "fput", "--k", "2.5", "--amplitude", "0.2"]) == 0
    assert "with losses" not in capsys.readouterr().out


@pytest.mark.parametrize("model, remedy", [
    ("fput-lossy.toml", "--param gamma=0"),
    ("flexmm-lossy", "--param gamma_U=0 --param gamma_theta=0")])
def test_a_lossy_soliton_names_the_damping_parameters_to_zero(model, remedy, tmp_path,
                                                              fput_lossy, capsys,
                                                              monkeypatch):
    """The refusal said '--param NAME=0' and the note '--param its damping = 0': the user
    had to find which parameters damp; the remedy now reads as options to type."""
    monkeypatch.chdir(tmp_path)
    (tmp_path / "fput-lossy.toml").write_text(fput_lossy)
    k, a = ("2.5", "0.05") if model.endswith(".toml") else ("0.92991", "0.002")
    argv = ["soliton", "--model", model, "--k", k, "--amplitude", a]
    assert main(argv) == 0
    note = capsys.readouterr().out.strip().splitlines()[-1]
    assert note.startswith("note: ") and f"{remedy} for the lossless chain" in note
    assert main([*argv, "--simulate"]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and f"add {remedy} to launch the lossless one" in err[0]


def test_a_lossy_solitons_remedy_runs_as_written(tmp_path, fput_lossy, capsys):
    (tmp_path / "fput-lossy.toml").write_text(fput_lossy)
    assert main(["soliton", "--model", str(tmp_path / "fput-lossy.toml"), "--k", "2.5",
                 "--amplitude", "0.05", "--simulate", "--travel", "2",
                 "--param", "gamma=0"]) == 0
    assert "simulated: N = " in capsys.readouterr().out


def test_every_scenes_run_time_says_which_is_the_quick_one():
    """`flexmm scenes` listed four-wave-pairs as '~7 s (~5 s)': which was quick was left to
    guess, where every other scene says '(quick ~5 s)'."""
    import re

    import scenes

    time = r"(<1 s|~\d+ (s|min))"
    for scene in scenes.REGISTRY.values():
        assert re.fullmatch(fr"{time}( \(quick {time}\))?", scene.runtime), scene.name


def test_coefficients_lossy_line_gives_the_peak_time_in_seconds_too(tmp_path, fput_lossy,
                                                                    capsys):
    # every other time of the command is also in s with --time-unit (1 time unit = 1 ms)
    (tmp_path / "fput-lossy.toml").write_text(fput_lossy)
    assert main(["coefficients", "--model", str(tmp_path / "fput-lossy.toml"), "--param",
                 "gamma=0.03", "--k", str(K), "--amplitude", str(AMPLITUDE), "--time-unit",
                 "0.001"]) == 0
    line = next(ln for ln in capsys.readouterr().out.splitlines()
                if ln.startswith("with losses"))
    assert "t = 51.27 = 0.05127 s" in line


def test_a_lossy_maps_store_says_when_each_theorys_amplification_peaks(tmp_path,
                                                                      fput_lossy, capsys):
    """The store held each theory's amplification but not when it peaks (only the runs'
    amplification_time_simulated): half of a transient answer; `point` prints both."""
    import zarr

    argv, out = _lossy_map(tmp_path, fput_lossy, "--theory-only", "--exact")
    assert main(argv) == 0
    ds = xr.open_zarr(out / "map.zarr").load()
    capsys.readouterr()
    assert main(["point", "--model", str(tmp_path / "fput-lossy.toml"), "--param",
                 "gamma=0.03", "--k", str(K), "--amplitude", str(AMPLITUDE), "--N", str(N),
                 "--json"]) == 0
    point = json.loads(capsys.readouterr().out)
    cell = ds.sel(gamma=0.03, k=K)
    for theory, row in (("semidiscrete", "semi-discrete NLS"), ("exact", "exact lattice"),
                        ("fourwave", "four-wave")):
        t = float(cell[f"amplification_time_{theory}"])
        assert ds[f"amplification_time_{theory}"].attrs["units"] == "T (lattice time)"
        # README's lossy FPUT point peaks at t = 50-51 in every theory, as the point's
        assert 45 < t < 55 and t == pytest.approx(point[row]["amplification_time"],
                                                  rel=1e-9), theory
    # a lossy store made before these columns is refused, saying so (not a KeyError)
    group = zarr.open_group(str(out / "map.zarr"), mode="r+")
    del group.attrs["amplification_time"]
    zarr.consolidate_metadata(str(out / "map.zarr"))
    assert main(argv) == 2
    assert "amplification_time_<theory>" in capsys.readouterr().err


def test_a_point_whose_losses_win_from_the_start_is_stable(tmp_path, fput_lossy, capsys):
    """Every theory said MI at gamma = 0.3 (the carrier and every sideband damped at
    gamma / 2 = 0.15, above the lossless gains 0.087-0.10): docs/models.md promises a
    physical verdict, MI where the gain beats the damping at t = 0."""
    (tmp_path / "fput-lossy.toml").write_text(fput_lossy)
    argv = ["point", "--model", str(tmp_path / "fput-lossy.toml"), "--k", str(K),
            "--amplitude", str(AMPLITUDE), "--N", str(N)]
    assert main([*argv, "--param", "gamma=0.3", "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    for name in ("semi-discrete NLS", "four-wave", "exact lattice"):
        row = out[name]
        assert row["verdict"] == "stable" and row["lossless_verdict"] == "MI"
        # R = gamma u_t^2 / 2 damps every wave at gamma / 2; the NLS's best net rate is
        # on its grid of 200 offsets, within 1e-4 of its peak (a smooth maximum). The
        # exact row's is the damped Hill pencil's, the damped ring's own rate: with
        # C = gamma M the damping also softens the stiffness by gamma^2 M / 4
        # (u = e^{-gamma t / 2} y), second order: 2.0e-4 above peak - 0.15 here (the
        # damped ring's monodromy -0.0631321 too, probe 102)
        bar = 5e-4 if name == "exact lattice" else 1e-4
        assert row["net_gain"] == pytest.approx(row["peak_gain"] - 0.15, abs=bar), name
        assert row["amplification"] == 1.0
    assert out["units"]["lattice"]["net_gain"] == "1/time"
    assert main([*argv, "--param", "gamma=0.3"]) == 0
    text = capsys.readouterr().out
    assert "stable with these losses" in text and "the lossless chain's, which is MI" in text
    # weaker damping, a gain that beats it at t = 0 (README: 4.6x-5.5x): MI, no such note
    assert main([*argv, "--param", "gamma=0.03", "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert all(out[n]["verdict"] == "MI" and "lossless_verdict" not in out[n]
               for n in ("semi-discrete NLS", "four-wave", "exact lattice"))


def test_a_map_cell_whose_losses_win_from_the_start_is_stable(tmp_path, fput_lossy):
    from energy import load_model
    from numerics.models import map_cells

    (tmp_path / "fput-lossy.toml").write_text(fput_lossy)
    model = load_model(str(tmp_path / "fput-lossy.toml"))
    weak, strong = map_cells(model, [({"gamma": 0.03}, K), ({"gamma": 0.3}, K)], AMPLITUDE,
                             N=N, exact=True)
    for theory in ("semidiscrete", "exact", "fourwave"):
        assert weak[f"verdict_{theory}"] == "MI" and strong[f"verdict_{theory}"] == "stable"
        # the rate column stays the lossless chain's (the same at both dampings)
        assert strong[f"peak_gain_{theory}"] == weak[f"peak_gain_{theory}"] > 0.08


def test_coefficients_whose_losses_win_from_the_start_say_stable(tmp_path, fput_lossy,
                                                                 capsys):
    # as point's: the NLS's gain 0.103 at k = 2.5 is below every wave's damping 0.15
    (tmp_path / "fput-lossy.toml").write_text(fput_lossy)
    argv = ["coefficients", "--model", str(tmp_path / "fput-lossy.toml"), "--param",
            "gamma=0.3", "--k", "2.5", "--amplitude", str(AMPLITUDE)]
    assert main([*argv, "--json"]) == 0
    co = json.loads(capsys.readouterr().out)
    assert co["verdict"] == "stable" and co["lossless_verdict"] == "MI"
    assert co["net_gain"] == pytest.approx(co["peak_gain"] - 0.15, abs=1e-4)
    assert co["four_wave"]["verdict"] == "stable"
    assert main(argv) == 0
    text = capsys.readouterr().out
    assert "stable (damped)" in text and "the losses win from t = 0" in text


def test_a_lossy_run_capped_before_its_peak_is_not_called_unobservable(tmp_path, fput_lossy,
                                                                       capsys):
    """--t-end 50 stops the runs while A(t) still rises (the theories peak near t = 140,
    146x at gamma 0.012): the table said 'no' in the observable column, an answer the
    runs did not give."""
    (tmp_path / "fput-lossy.toml").write_text(fput_lossy)
    assert main(["point", "--model", str(tmp_path / "fput-lossy.toml"), "--param",
                 "gamma=0.012", "--k", str(K), "--amplitude", str(AMPLITUDE), "--N", str(N),
                 "--simulate", "--seeds", "1", "--t-end", "50"]) == 0
    lines = capsys.readouterr().out.splitlines()
    table = lines[next(i for i, ln in enumerate(lines) if ln.startswith("with losses")):]
    row = next(ln for ln in table if ln.startswith("simulated "))
    assert row.rstrip().endswith("not by cap"), row


def test_a_lossy_maps_runs_capped_before_the_peak_are_said_undecided(tmp_path, fput_lossy,
                                                                     capsys):
    """--t-end 50: the weakly damped cells' theories peak past 20x near t = 160-260, so
    their runs (7-17x by t = 50) cannot answer; the map counted them not observable and
    said the runs' critical gamma lies below the axis, without a word on T (a lossless
    map says 'a longer --t-end decides them' for runs too short for their rate)."""
    argv, out = _lossy_map(tmp_path, fput_lossy, "--t-end", "50")
    assert main(argv) == 0
    text = capsys.readouterr().out
    assert "2 of 4 cells:" in text and "peaks after the run's end" in text
    assert "a longer --t-end decides them" in text
    ds = xr.open_zarr(out / "map.zarr").load()
    # gamma 0.01 (first row): 236x and 468x, at t > 150; gamma 0.03: below 5x, decided
    assert ds["slow_for_T"].values.tolist() == [[1, 1], [0, 0]]


@pytest.mark.parametrize("cmd", [["scene", "fig2-dispersion"], ["run"]])
def test_a_bad_scene_seed_names_the_option(cmd, tmp_path, capsys):
    # 'seed must be an integer in [0, 2^63)' named no option of the command
    code = main([*cmd, "--seed", "-1", "--out", str(tmp_path / "o")])
    err = capsys.readouterr().err.strip().splitlines()
    assert code == 2 and len(err) == 1 and "--seed must be an integer" in err[0], err
    assert not (tmp_path / "o").exists()


def test_the_exact_and_four_wave_rows_name_one_pair_in_one_order(capsys):
    """flexmm at k 0.785 on 64 sites: the note said 'branch 1 (theta) at 0.2945 and branch
    0 (theta) at 1.276', the four-wave line the same pair the other way round. (Both waves
    are theta waves on the carrier's sheet, across the theta-U crossing: since probe 95
    the pair is 'sidebands', not 'parametric', and the exact row's note says so without
    naming the waves; its JSON names them in the same order.)"""
    assert main(["point", "--model", "flexmm", "--k", "0.8", "--amplitude", "0.02", "--N",
                 "64", "--json"]) == 0
    rows = json.loads(capsys.readouterr().out)
    ex, fw = rows["exact lattice"], rows["four-wave"]
    assert ex["mode_kind"] == fw["mode_kind"] == "sidebands"
    assert [w["field"] for w in ex["mode_waves"]] == ["theta", "theta"]
    order = [round(w["wavenumber"], 3) for w in fw["mode_waves"]]
    assert [round(w["wavenumber"], 3) for w in ex["mode_waves"]] in (order, order[::-1])
    assert main(["point", "--model", "flexmm", "--k", "0.8", "--amplitude", "0.02", "--N",
                 "64"]) == 0
    line = next(ln for ln in capsys.readouterr().out.splitlines()
                if ln.startswith("four-wave: the fastest pair"))
    assert "sidebands (branch 0 (theta) at 1.276 and branch 1 (theta) at 0.2945)" in line


def test_coefficients_of_an_undamped_lossy_model_is_strict_json(tmp_path, fput_lossy,
                                                                  capsys):
    # gamma = 0: the lossless chain (probe 100; it said "unbounded", null and words, where
    # the lossless answer is the whole story): strict JSON, no amplification
    (tmp_path / "fput-lossy.toml").write_text(fput_lossy)
    assert main(["coefficients", "--model", str(tmp_path / "fput-lossy.toml"), "--param",
                 "gamma=0", "--k", "2.5", "--amplitude", str(AMPLITUDE), "--json"]) == 0

    def refuse(constant):
        raise ValueError(f"not strict JSON: {constant}")

    co = json.loads(capsys.readouterr().out, parse_constant=refuse)
    for row in (co, co["four_wave"]):
        assert "amplification" not in row and "carrier_damping" not in row


def test_a_lossy_maps_runs_capped_before_the_peak_have_no_observable_answer(
        tmp_path, fput_lossy, capsys):
    """--t-end 50: the runs of the weakly damped row stop at 7-17x while their theories
    peak past 20x later (slow_for_T); point says 'not by cap' for such runs, but the map
    counted their observable 0 as 'not observable' in the runs' share and in each
    theory's agreement with them. They have no answer: left out, as mi_fraction leaves
    out the cells a theory does not decide."""
    argv, out = _lossy_map(tmp_path, fput_lossy, "--t-end", "50")
    assert main(argv) == 0
    text = capsys.readouterr().out
    ds = xr.open_zarr(out / "map.zarr").load()
    runs, slow = ds["observable_simulated"].values, ds["slow_for_T"].values == 1
    assert slow.any() and (runs[slow] == 0).any()  # the case this test is about
    answered = (runs >= 0) & ~(slow & (runs == 0))
    summary = json.loads((out / "summary.json").read_text())
    assert summary["observable_unanswered_cells"]["simulated"] == int((~answered).sum())
    assert summary["observable_fraction"]["simulated"] == pytest.approx(
        float(np.mean(runs[answered] == 1)))
    exact = ds["amplification_exact"].values >= 20
    both = answered & ~np.isnan(ds["amplification_exact"].values)
    assert summary["observable_agreement_with_simulation_percent"]["exact"] == \
        pytest.approx(100 * np.mean(exact[both] == (runs[both] == 1)))
    assert "slow_for_T" in ds["observable_simulated"].attrs["comment"]  # the store says it
    share = next(ln for ln in text.splitlines() if ln.startswith("observable (amplified"))
    assert f"simulated {np.mean(runs[answered] == 1):.0%} ({int((~answered).sum())} " \
        "without an answer, left out)" in share


def test_coefficients_name_a_pair_in_points_order(capsys):
    """point names a pair's waves larger wavenumber first (fa19315); coefficients' four-wave
    line printed them as the theory holds them (k + q first, wrapped): flexmm at k 2.6,
    a 0.02, 'branch 1 (U) at -1.41 and branch 0 (U) at 0.3268', the other way round."""
    import re

    assert main(["coefficients", "--model", "flexmm", "--k", "2.6", "--amplitude",
                 "0.02"]) == 0
    line = next(ln for ln in capsys.readouterr().out.splitlines()
                if ln.startswith("four-wave") and " at " in ln)
    at = [float(x) for x in re.findall(r" at (-?[\d.]+)", line)]
    assert len(at) == 2 and at[0] > at[1], line
