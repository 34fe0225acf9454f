"""What a researcher meets in the first hour with a material of their own, beyond the
paper's two points: verdicts that do not exist are said so (never a finite "stable"),
starts that do not exist are refused before any work, every band is found whatever k,
and mistakes get the command's own error. Found by a randomized sweep of the CLI
(issue 23's review) at alpha 0.3-6, K_s and K_theta 0.001-1, amplitudes up to 0.5."""

import json
import math

import numpy as np
import pytest

from cli.app import main as cli
from numerics import Material, simulate
from numerics.maps import MapParameters
from numerics.theory import nls_summary, nls_undefined, soliton, theory_gain

#: delta < 0 and k^2 > 6 K_theta / |delta|: the continuum frequency is imaginary at k = 3.01
DEEP = Material(alpha=2.6206, K_s=0.005108, K_theta=0.1037)
K_DEEP = 3.0096


def test_an_nls_without_a_real_frequency_has_no_verdict():
    """g2 / g1 of the continuum NLS stays finite where omega^2 < 0 (its square roots
    cancel): it read "stable" there. Now NaN, with the reason; the semi-discrete NLS,
    whose omega is real at every k, keeps its verdict."""
    assert 6 * DEEP.K_theta + DEEP.delta * K_DEEP**2 < 0
    s = nls_summary(DEEP, "coupled", K_DEEP, amplitude=0.002)
    assert math.isnan(s["g"]) and not s["stable"] and "omega^2" in s["undefined"]
    assert np.all(np.isnan(theory_gain("paper NLS", DEEP, "coupled", K_DEEP, amplitude=0.002,
                                       offset=[0.1, 0.2])))
    assert nls_undefined("semi-discrete NLS", DEEP, "coupled", K_DEEP) is None
    lattice = nls_summary(DEEP, "coupled", K_DEEP, amplitude=0.002,
                          nls=__import__("generated.lattice_coefficients").lattice_coefficients)
    assert np.isfinite(lattice["g"]) and "undefined" not in lattice
    with pytest.raises(ValueError, match="no soliton at k = 3.0096: no real carrier"):
        soliton(DEEP, "coupled", K_DEEP, 0.002, theory="paper NLS")


def test_delta_zero_is_undefined_with_no_gain(capsys):
    """delta = 0 (g1 = 0): every verdict undefined and no peak gain shown (a 0 read as
    "stable" beside "undefined")."""
    assert cli(["coefficients", "--alpha", "2", "--K-s", "0.03", "--K-theta", "0.03",
                "--k", "1"]) == 0
    out = capsys.readouterr().out
    gains = next(ln for ln in out.splitlines() if ln.strip().startswith("peak gain"))
    assert gains.split()[-2:] == ["-", "-"]
    assert out.count("undefined: g1 = 0: delta = 0") == 4


def test_the_paper_start_where_it_does_not_exist_is_refused_before_any_work(tmp_path,
                                                                           capsys):
    """eq. IC takes theta_dot from the continuum omega: NaN there. simulate, point and map
    say why and what to use instead; no folder is left behind."""
    k = 2 * np.pi * 15 / 32
    with pytest.raises(ValueError, match="not real at k = 2.94524.*only k < 2.51214"):
        simulate(DEEP, "coupled", 32, k, amplitude=0.00126, t_end=10.0)
    simulate(DEEP, "coupled", 32, k, amplitude=0.00126, t_end=10.0, start="travelling")
    material = ["--alpha", "2.6206", "--K-s", "0.005108", "--case", "coupled",
                "--amplitude", "0.00126", "--N", "32"]
    out = tmp_path / "a" / "b"
    assert cli(["point", *material, "--K-theta", "0.1037", "--k", "3.0096",
                "--out", str(out)]) == 2
    cap = capsys.readouterr()
    assert cap.out == "" and cap.err.startswith("flexmm: error: --start paper: ")
    assert "'travelling'" in cap.err and not (tmp_path / "a").exists()
    assert cli(["map", *material, "--K-theta", "0.1037,0.01", "--k", "2.9452,1.0",
                "--theory-only", "--out", str(out)]) == 2
    cap = capsys.readouterr()
    assert "map" not in cap.out and "--start paper: at K_theta = 0.1037" in cap.err
    assert not (tmp_path / "a").exists()
    with pytest.raises(ValueError, match="start 'paper'"):
        MapParameters(case="coupled", material=DEEP, K_theta=(0.1037,), k=(2.9452,),
                      amplitude=0.00126, N=32)


def test_a_k_that_snaps_to_pi_is_said_so(capsys):
    assert cli(["point", "--alpha", "0.5325", "--K-s", "0.002879", "--K-theta", "0.005264",
                "--k", "3.1", "--case", "coupled", "--N", "16"]) == 2
    err = capsys.readouterr().err
    assert "k = 3.1 snaps to pi on N = 16" in err and "N >= 76" in err
    assert cli(["point", "--alpha", "0.5325", "--K-s", "0.002879", "--K-theta", "0.005264",
                "--k", "3.1", "--case", "coupled", "--N", "76"]) == 0  # the remedy works


def test_point_finds_a_band_at_any_offset(tmp_path):
    """Offsets q - k up to pi, as the map searches them: at k = pi / 2 the semi-discrete
    band peaks at offset 2.87, beyond pi - k (point's q in [0, pi] read the grid's edge)."""
    material = Material(alpha=5.2407, K_s=0.04644, K_theta=0.07905)
    assert cli(["point", "--alpha", "5.2407", "--K-s", "0.04644", "--K-theta", "0.07905",
                "--k", "1.5708", "--case", "rotation", "--amplitude", "0.15", "--start",
                "travelling", "--N", "128", "--out", str(tmp_path)]) == 0
    res = json.loads((tmp_path / "point.json").read_text())
    got = res["theories"]["semi-discrete NLS"]
    Q = np.linspace(0, np.pi, 20001)[1:]
    ref = theory_gain("semi-discrete NLS", material, "rotation", res["k"], 0.15, Q)
    assert got["peak_offset"] > np.pi - res["k"]
    # the point's 3001-offset grid reaches the peak of a 20 000-offset one to 1e-4
    assert abs(got["peak_gain"] / ref.max() - 1) < 1e-4
    assert abs(got["peak_offset"] - Q[ref.argmax()]) < 2 * np.pi / 3000


def test_point_simulates_with_the_step_a_map_cell_takes(tmp_path):
    """RK4 at the paper's dt = 0.05 blows up on a stiff material (alpha 5.84, K_theta 0.81:
    energy drift 0.5 by T = 40) that a map cell simulates; point takes the map cell's step,
    and its run conserves energy and measures the exact theory's band."""
    from numerics import BlowUpError, snap_wavenumber

    mat = Material(alpha=5.8406, K_s=0.3968, K_theta=0.8075)
    k = snap_wavenumber(0.55926, 200)
    with pytest.raises(BlowUpError):
        simulate(mat, "coupled", 200, k, amplitude=0.0347, t_end=100.0, start="travelling")
    args = ["point", "--alpha", "5.8406", "--K-s", "0.3968", "--K-theta", "0.8075", "--k",
            "0.55926", "--amplitude", "0.0347", "--case", "coupled", "--start", "travelling",
            "--N", "200", "--simulate", "--t-end", "300", "--seeds", "1",
            "--out", str(tmp_path)]
    assert cli(args) == 0
    sim = json.loads((tmp_path / "point.json").read_text())["simulated"]
    assert sim["method"] != "rk4" and (5.0 / sim["dt"]) % 1 < 1e-9  # records fall on steps
    assert sim["verdict"] == "MI"


def test_point_measures_a_band_beyond_pi_minus_k(tmp_path):
    """At k = 2.9 the band peaks at offset 0.46 > pi - k = 0.24: its upper sideband folds
    back onto another pair's bin. The measured offset must still be the band's (it read
    0.025 when only bins above k were read), within a few bins of the exact theory's."""
    assert cli(["point", "--alpha", "2", "--K-s", "0.03", "--K-theta", "0.02", "--k", "2.9",
                "--amplitude", "0.04", "--case", "rotation", "--start", "travelling",
                "--simulate", "--seeds", "2", "--out", str(tmp_path)]) == 0
    res = json.loads((tmp_path / "point.json").read_text())
    exact, sim = res["theories"]["exact lattice"], res["simulated"]
    assert exact["peak_offset"] > math.pi - res["k"]
    # 4 bins of 2 pi / 500: the measured curve's peak is flat over a few bins at T = 1700
    assert abs(sim["peak_offset"] - exact["peak_offset"]) < 4 * 2 * math.pi / 500
    assert abs(sim["peak_gain"] / exact["peak_gain"] - 1) < 0.05


def test_an_unknown_option_is_the_commands_error_with_the_nearest(capsys):
    with pytest.raises(SystemExit) as exc:
        cli(["coefficients", "--alpha", "1.8", "--K-s", "0.05", "--K-thetaa", "0.03",
             "--k", "1.2"])
    assert exc.value.code == 2
    err = capsys.readouterr().err
    assert "usage: flexmm coefficients" in err and "did you mean --K-theta?" in err


def test_map_refuses_two_row_axes(tmp_path, capsys):
    assert cli(["map", "--alpha", "1.8", "--K-s", "0.05", "--K-theta", "0.03", "--delta",
                "0.01", "--k", "1", "--case", "coupled", "--theory-only",
                "--out", str(tmp_path / "m")]) == 2
    assert "not both" in capsys.readouterr().err and not (tmp_path / "m").exists()


def test_soliton_warns_where_the_kink_is_not_separable(capsys):
    """k x width = 1.8: the kink's spectrum reaches the low-pass at k/2 (measured -69% to
    +13% by ring size); the README's soliton (k x width = 31) gets no warning."""
    base = ["soliton", "--case", "coupled", "--simulate", "--travel", "2"]
    assert cli(base + ["--alpha", "3.8019", "--K-s", "0.002685", "--K-theta", "0.01722",
                       "--k", "0.14296", "--amplitude", "0.02"]) == 0
    assert "the kink height is not separable" in capsys.readouterr().out


def test_growth_without_an_unstable_mode_is_predicted_and_said_so(tmp_path, capsys):
    """alpha 5.24, amplitude 0.15, k = pi/2: no Hill mode grows (fastest ~1e-13 /T), yet
    the runs' spectra grow ~25x within T = 5000: the linear response itself. The
    prediction says so and matches the runs (measured here: 24.9 / 26.2x predicted, 25.3 /
    26.1x simulated; 10% is the spread between seeds)."""
    assert cli(["point", "--alpha", "5.2407", "--K-s", "0.04644", "--K-theta", "0.07905",
                "--k", "1.5708", "--case", "rotation", "--amplitude", "0.15", "--start",
                "travelling", "--N", "128", "--simulate", "--seeds", "2", "--t-end", "5000",
                "--out", str(tmp_path)]) == 0
    assert "not an exponential instability" in capsys.readouterr().out
    res = json.loads((tmp_path / "point.json").read_text())
    assert res["predicted"]["rate"] < 1e-6
    np.testing.assert_allclose(res["predicted"]["growth"], res["simulated"]["growth"],
                               rtol=0.1)
    assert min(res["simulated"]["growth"]) > 20


def test_a_prediction_past_the_linear_stage_says_a_run_measures_less(capsys):
    """The predicted growth factor is linear response: where its sidebands reach a few % of
    the carrier by T, a run grows slower (the README's point: 1.5e3x measured, 3.3e3x
    predicted); the point says so there, and only there."""
    blue = ["point", "--alpha", "2.5", "--K-s", "0.01851", "--K-theta", "0.01551", "--k",
            "0.81681", "--case", "coupled", "--start", "travelling", "--N", "128"]
    assert cli(blue) == 0  # T = 2300 (9 e-foldings): ~3500x, the sidebands at 0.6 of it
    out = capsys.readouterr().out
    assert "the predicted sidebands reach 0.6" in out and "a run measures less" in out
    assert cli(blue + ["--t-end", "1000"]) == 0  # ~20x: the sidebands at 0.3% of it
    assert "a run measures less" not in capsys.readouterr().out


def test_the_nls_warns_beyond_weak_nonlinearity(capsys):
    """The NLS's own frequency shift -eps^2 g2 A0^2 is the exact plane wave's (case I,
    semi-discrete: to 0.1% at amplitude 0.005, where O(a^4) is 1e-3 of it); past 10% of
    omega the commands say the expansion no longer holds (amplitude 0.5: 89%)."""
    from generated import lattice_coefficients
    from numerics.theory import plane_wave

    mat = Material(alpha=2.0, K_s=0.03, K_theta=0.02)
    s = nls_summary(mat, "rotation", 1.2, amplitude=0.005, nls=lattice_coefficients)
    exact = plane_wave(mat, "rotation", 1.2, 0.005).omega - s["omega"]
    assert exact == pytest.approx(s["frequency_shift"], rel=1e-3)  # Omega - omega (probe 100)
    base = ["coefficients", "--alpha", "1.8", "--K-s", "0.05", "--K-theta", "0.03",
            "--k", "1.234"]
    assert cli(base + ["--amplitude", "0.5"]) == 0
    assert "beyond the weakly nonlinear expansion" in capsys.readouterr().out
    assert cli(base + ["--amplitude", "0.02"]) == 0
    assert "weakly nonlinear" not in capsys.readouterr().out


def test_a_round_off_field_does_not_set_the_step():
    """A travelling wave whose 2k sits at the zone boundary (k = pi/2, N = 32) carries
    U ~ 1e-31: its rms(U_dot) / rms(U) read 1e14 and asked for dt = 1e-16 (t_end / dt =
    7.5e18 steps, refused). The step comes from theta there, within the stability limit."""
    from numerics import initial_condition, snap_wavenumber
    from numerics.lattice import dominant_frequency
    from numerics.maps import cell_step

    mat = Material(alpha=0.3468, K_s=0.4775, K_theta=0.001388)
    k = snap_wavenumber(1.571, 32)
    state = initial_condition(mat, "coupled", 32, k, 0.1602, 1e-3, 0, "travelling")
    assert np.sqrt(np.mean(state.U**2)) < 1e-20
    assert dominant_frequency(state) <= mat.omega_max("coupled")
    assert cell_step(state, mat, "coupled", 1000.0)[1] > 0.1


def test_the_map_summary_has_no_nan_where_a_theory_evaluated_nothing():
    from cli.map import _agreement_text

    none = {"p": float("nan"), "p_decided": float("nan"), "p_decided_cells": 0,
            "p_undetermined_cells": 4}
    assert _agreement_text("p", none) == "p: no cell it could evaluate (4 undetermined, left out)"
    some = {"p": 50.0, "p_decided": float("nan"), "p_decided_cells": 0,
            "p_undetermined_cells": 0}
    assert "nan" not in _agreement_text("p", some)


def test_a_gain_that_vanishes_with_the_amplitude_is_explained(capsys):
    """Issue 36's material: at amplitude 0.04 the exact theory has no growing sideband
    where the NLS has one; point says the band closes, found at a quarter amplitude."""
    from cli.app import main

    code = main(["point", "--alpha", "1.3", "--K-s", "0.05", "--K-theta", "0.045", "--k", "1",
                 "--case", "coupled", "--amplitude", "0.04"])
    out = capsys.readouterr().out
    assert code == 0
    assert "has no growing sideband at amplitude 0.04 but has one at 0.01" in out


def test_progress_bars_need_no_widgets(monkeypatch):
    """Without ipywidgets (the docs build's kernel) the bar is tqdm's terminal one, so a
    notebook shows no 'IProgress not found' warning naming the build machine's path;
    with it, tqdm.auto's choice."""
    import builtins

    import tqdm.std

    from common.progress import progress_class

    real = builtins.__import__

    def no_widgets(name, *args, **kwargs):
        if name == "ipywidgets":
            raise ImportError(name)
        return real(name, *args, **kwargs)

    monkeypatch.setattr(builtins, "__import__", no_widgets)
    assert progress_class() is tqdm.std.tqdm


@pytest.mark.parametrize("cmd, extra, writes", [
    ("coefficients", [], None), ("point", ["--case", "coupled"], "point.json"),
    ("soliton", ["--case", "coupled"], "soliton.json")])
def test_json_without_a_model_names_the_command_and_what_it_writes(cmd, extra, writes,
                                                                    capsys):
    """--json acts on --model commands: the refusal names this command's own way (not
    `point`'s for every command)."""
    assert cli([cmd, "--alpha", "2.0", "--K-s", "0.03", "--K-theta", "0.02", "--k", "1.2",
                *extra, "--json"]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and f"try {cmd} --model flexmm" in err
    assert (f"writes {writes} with --out" in err) if writes else "writes" not in err
