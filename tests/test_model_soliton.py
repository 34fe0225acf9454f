"""Any model's NLS soliton launched in its lattice and tracked (issue 44 item 6).

Physics against physics: the measured velocity against the group velocity, the width and
the frequency shift against the semi-discrete NLS, the kink of each acoustic field against
the mean-flow integral, the errors shrinking with the amplitude (the NLS is the a -> 0
limit), the run's energy conserved; `--model flexmm` against the paper chain's own launch;
the command's files and its one-line refusals.
"""

from __future__ import annotations

import json
import math

import pytest

from cli.app import main as cli
from energy import ModelError, load_model
from numerics.models import nls, ring_soliton, simulate_soliton

#: one field with a mean flow (alpha != 0: a kink of u); focusing at k = 1.6 (g = 6.2)
FPUT = {"alpha": 0.5}
#: two fields (masses 1 and 2), optical branch: an optical mean (v - u) and a kink of both
DIATOMIC = {"alpha": 0.5}


@pytest.fixture(scope="module")
def fput_runs():
    model = load_model("fput", **FPUT)
    return {a: simulate_soliton(model, 1.6, a, travel=5) for a in (0.1, 0.05)}


@pytest.fixture(scope="module")
def diatomic_runs():
    model = load_model("diatomic-fput", **DIATOMIC)
    return {a: simulate_soliton(model, 1.0, a, branch=1, travel=4) for a in (0.04, 0.02)}


def _errors(run):
    return run.errors()


@pytest.mark.parametrize("runs", ["fput_runs", "diatomic_runs"])
def test_the_soliton_moves_at_the_group_velocity_with_the_nls_width(runs, request):
    # The NLS is the leading order in the amplitude: its velocity and width are off by
    # O(a^2) relative terms it drops (nonlinear dispersion, the next order of the mean
    # flow). At the widths here (8-16 sites) those are a few 1e-3 (measured: 1e-4 - 3e-3);
    # 1% and 2% say "the soliton of the NLS", a wrong launch (carrier, frequency or mean
    # flow) shows as 5-20% here
    for a, run in request.getfixturevalue(runs).items():
        err = _errors(run)
        assert abs(err["velocity"]) < 0.01, (a, err)
        assert abs(err["width"]) < 0.02, (a, err)
        assert abs(err["amplitude"]) < 0.02, (a, err)
        assert run.measured()["travelled_widths"] > 3


@pytest.mark.parametrize("runs", ["fput_runs", "diatomic_runs"])
def test_the_errors_shrink_with_the_amplitude(runs, request):
    # halving the amplitude halves the NLS's small parameter: the dropped O(a^2) terms fall
    # about 4x; asserting "smaller" (not 4x) leaves room for the fit's own 1e-5 noise
    big, small = (request.getfixturevalue(runs)[a] for a in sorted(
        request.getfixturevalue(runs), reverse=True))
    eb, es = _errors(big), _errors(small)
    assert abs(es["width"]) < abs(eb["width"]), (eb, es)
    assert abs(es["velocity"]) < abs(eb["velocity"]), (eb, es)


@pytest.mark.parametrize("runs", ["fput_runs", "diatomic_runs"])
def test_the_nonlinear_frequency_shift_and_the_kinks_are_the_nls_ones(runs, request):
    # the carrier's frequency shift (soliton's own turn g2 a^2/8 plus the ring's
    # compensating strain through g2's mean-flow part) measured to 2% of itself: the shift
    # is O(a^2) of omega, so a relative test of the frequency alone would pass with no
    # shift at all. Kinks: the mean strain s |E|^2 summed, 3% (the O(a^2) shape change)
    for a, run in request.getfixturevalue(runs).items():
        p = run.predicted
        omega = p.nls.carrier.omega
        shift_pred, shift_meas = p.frequency - omega, run.frequency - omega
        assert abs(shift_meas / shift_pred - 1) < 0.02, (a, shift_pred, shift_meas)
        m, want = run.measured(), p.summary(run.model.fields)
        kinks = [key for key in want if key.startswith("kink_")]
        assert kinks, "these models have a mean flow"
        for key in kinks:
            assert abs(m[key] / want[key] - 1) < 0.03, (a, key, m[key], want[key])


@pytest.mark.parametrize("runs", ["fput_runs", "diatomic_runs"])
def test_the_launched_state_is_a_soliton_not_a_packet_that_sheds(runs, request):
    # at the smaller amplitude (16 sites) the width stays within 2e-3 over the run and
    # nothing is shed (radiation < 1e-5 of the soliton's intensity): measured 5e-4 and
    # 2e-7 (fput), 5e-5 and 2e-7 (diatomic). A two-field launch without the packet's
    # polarisation gradient (e', e'') ripples by 1.2% and sheds 2e-4 (checked)
    runs = request.getfixturevalue(runs)
    run = runs[min(runs)]
    width = run.series("width")
    assert (width.max() - width.min()) / run.predicted.width < 2e-3
    assert run.series("radiation").max() < 1e-5


@pytest.mark.parametrize("runs", ["fput_runs", "diatomic_runs"])
def test_the_run_conserves_energy(runs, request):
    # srkn11b (order 6) at a fifth of its stability limit: round-off level, 1e-9 leaves
    # four orders of magnitude above the measured 1e-13 - 1e-15
    for run in request.getfixturevalue(runs).values():
        assert run.energy_drift < 1e-9


@pytest.mark.parametrize("name, params, k, branch, amplitude", [
    ("fput", FPUT, 0.8, None, 0.1),  # g = -0.97, one field
    ("diatomic-fput", DIATOMIC, 1.0, 0, 0.05),  # g = -5.8, acoustic branch, two fields
])
def test_a_dark_soliton_where_the_nls_defocuses(name, params, k, branch, amplitude):
    # a black soliton (the carrier closes the ring with the phase jump: k = (2m + 1) pi / N);
    # the goals above. Its frequency is the background's: within 5% of the NLS's shift,
    # which the exact plane wave itself misses by 2.75% at fput's a = 0.1 (the O(a^2)
    # correction beyond the NLS; measured 2.6%)
    run = simulate_soliton(load_model(name, **params), k, amplitude, branch=branch,
                           travel=5)
    p = run.predicted
    assert p.kind == "dark"
    assert round(p.k * run.N / math.pi) % 2 == 1
    err = run.errors()
    assert abs(err["velocity"]) < 0.01 and abs(err["width"]) < 0.02, err
    assert all(abs(err[key]) < 0.03 for key in err if key.startswith("kink_")), err
    omega = p.nls.carrier.omega
    assert abs((run.frequency - omega) / (p.frequency - omega) - 1) < 0.05
    assert run.energy_drift < 1e-9


def test_model_flexmm_equals_the_paper_chains_run():
    # the same lattice, the same NLS (semi-discrete), launched by two codes: the paper
    # chain's (numerics.theory, fused kernel, dt 0.25) and any model's (generated force,
    # dt a fifth of the stability limit). Both measure the same soliton: 2e-3 is the
    # size of their difference allowed by the fits (the errors against the NLS are 1e-3)
    from numerics import Material
    from numerics.theory import simulate_soliton as paper_soliton

    alpha, K_s, K_theta, k, a = 2.0, 0.03, 0.02, 1.0, 0.005
    paper = paper_soliton(Material(alpha=alpha, K_s=K_s, K_theta=K_theta), "coupled", k, a,
                          travel=2)
    model = simulate_soliton(load_model("flexmm", alpha=alpha, K_s=K_s, K_theta=K_theta), k,
                             a, N=paper.N, travel=2)
    assert model.predicted.k == pytest.approx(paper.predicted.k, rel=1e-12)
    assert model.predicted.width == pytest.approx(paper.predicted.width, rel=1e-9)
    assert model.predicted.frequency == pytest.approx(paper.predicted.frequency, rel=1e-9)
    assert model.predicted.soliton.kink[1] == pytest.approx(paper.predicted.kink_height,
                                                            rel=1e-9)
    pm, mm = paper.measured(), model.measured()
    for key in ("velocity", "width", "amplitude"):
        assert mm[key] == pytest.approx(pm[key], rel=2e-3), key
    assert mm["kink_U"] == pytest.approx(pm["kink_height"], rel=2e-3)


def test_cli_writes_the_table_json_and_figure(tmp_path, capsys):
    out = tmp_path / "sol"
    assert cli(["soliton", "--model", "fput", "--param", "alpha=0.5", "--k", "1.6",
                "--amplitude", "0.1", "--simulate", "--travel", "3", "--out", str(out)]) == 0
    text = capsys.readouterr().out
    assert "kind: bright" in text and "kink of u" in text and "measured" in text
    assert text.strip().splitlines()[-1].startswith("wrote ")
    data = json.loads((out / "soliton.json").read_text())
    assert data["kind"] == "bright" and data["model"] == "fput"
    assert set(data["predicted"]) == {"velocity", "width", "amplitude", "frequency", "kink_u"}
    assert abs(data["errors"]["velocity"]) < 0.01
    assert data["run"]["N"] >= 12 * data["predicted"]["width"]
    assert "units" in data
    assert (out / "soliton.png").read_bytes()[:4] == b"\x89PNG"


def test_cli_json_scales_the_numbers_to_si_but_not_the_errors(capsys):
    # 1 ms per time unit, 1 cm per site: a velocity in sites/time is x10 in m/s, a width
    # x0.01 in m; the errors and drifts are ratios and stay as they are
    assert cli(["soliton", "--model", "fput", "--param", "alpha=0.5", "--k", "1.6",
                "--amplitude", "0.1", "--simulate", "--travel", "2", "--json",
                "--time-unit", "0.001", "--length-unit", "0.01"]) == 0
    data = json.loads(capsys.readouterr().out)
    p, m, si = data["predicted"], data["measured"], data["si"]
    assert si["predicted"]["velocity"] == pytest.approx(10 * p["velocity"], rel=1e-12)
    assert si["measured"]["width"] == pytest.approx(0.01 * m["width"], rel=1e-12)
    assert data["errors"]["velocity"] == pytest.approx(m["velocity"] / p["velocity"] - 1,
                                                       rel=1e-12)
    assert "errors" not in si and "drift" not in si["measured"]
    assert data["units"]["si"]["velocity"] == "m/s"


@pytest.mark.parametrize("argv, message", [
    (["--k", "0.8", "--amplitude", "0.1", "--kind", "bright"], "only dark solitons"),
    (["--k", "1.6", "--amplitude", "3"], "no envelope; --amplitude <="),
    (["--k", "1.6", "--amplitude", "0.05", "--N", "100"], "too short"),
    (["--k", "0.001", "--amplitude", "0.05"], "k x width"),
    (["--k", "1.6", "--amplitude", "0.05", "--theory", "paper"], "--theory paper"),
])
def test_bad_input_is_one_line_and_exit_2(argv, message, capsys):
    code = cli(["soliton", "--model", "fput", "--param", "alpha=0.5", *argv, "--simulate"])
    out, err = capsys.readouterr()
    err = err.strip()
    assert code == 2
    assert len(err.splitlines()) == 1 and message in err, err
    assert "estimate" not in out  # a refused launch is not estimated first


def test_a_lossy_model_is_refused_and_its_lossless_limit_runs(capsys):
    # the NLS is lossless: a damped soliton decays, so it is refused in one line; the same
    # file with its damping at 0 is the lossless lattice and runs
    base = ["soliton", "--model", "flexmm-lossy", "--k", "1.0", "--param", "alpha=2",
            "--param", "K_s=0.03", "--param", "K_theta=0.02", "--amplitude", "0.01",
            "--simulate", "--travel", "1"]
    assert cli(base) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1 and "[dissipation]" in err, err
    assert cli(base + ["--param", "gamma_theta=0", "--param", "gamma_U=0"]) == 0
    assert "energy drift" in capsys.readouterr().out


def test_no_bright_soliton_where_g_is_negative():
    # fput alpha = 0.5 at k = 0.8: g2/g1 < 0 (defocusing) -> a bright one is refused
    model = load_model("fput", **FPUT)
    assert nls(model, 0.8).g < 0
    with pytest.raises(ModelError, match="only dark solitons"):
        ring_soliton(model, 0.8, 0.1, kind="bright")
