"""The paper's start (eq. IC) and its theory as the flexmm models' own (issue 40 item 4):
registered by the paper chain's energy (``numerics.models.extra_starts``), the same state
and the same steps as the paper engine's, the rate its theory predicts, and
``point --model flexmm --start paper``."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest

import energy
from energy import ModelError, load_model
from numerics import Material, simulate
from numerics.models import extra_starts, simulate_model
from numerics.theory import PAPER_START


def test_the_paper_chain_models_have_the_paper_start_and_no_other_does(tmp_path):
    text = (Path(energy.__file__).parent / "models" / "flexmm.toml").read_text()
    renamed = tmp_path / "my-chain.toml"
    renamed.write_text(text.replace('name = "flexmm"', 'name = "my-chain"', 1))
    for model in (load_model("flexmm"), load_model("flexmm-rotation"),
                  load_model(str(renamed))):
        assert list(extra_starts(model)) == ["paper"]
    for name in ("flexmm-lossy", "flexmm-stiff-hinge", "fput", "klein-gordon"):
        assert extra_starts(load_model(name)) == {}, name
        with pytest.raises(ModelError, match="start must be one of exact, linear"):
            simulate_model(load_model(name), 1.0, 0.05, N=32, t_end=1.0, start="paper")


@pytest.mark.parametrize("name,case", [("flexmm", "coupled"), ("flexmm-rotation", "rotation")])
def test_the_paper_start_is_the_paper_engines_state_and_run(name, case):
    """From eq. IC with the same seed, method and step, the model path (the registered
    fused force in ForceStepper) and the paper engine (``numerics.simulate``) end in the
    same state to the last bit (tests/test_fast_forces.py: one computation for an SRKN
    method), on parameters away from the defaults."""
    params = dict(alpha=2.1, K_s=0.03, K_theta=0.012)
    model = load_model(name, **params)
    k, a = 2 * np.pi * 7 / 64, 0.05
    run = simulate_model(model, k, a, N=64, start="paper", seed=3, t_end=200.0, dt=0.05,
                         records=4)
    ref = simulate(Material(**params), case, 64, k, a, seed=3, start="paper", t_end=200.0,
                   dt=0.05, method="srkn11b").final_state
    u, v = run.state
    assert np.array_equal(u[0], ref.theta) and np.array_equal(v[0], ref.theta_dot)
    if case == "coupled":
        assert np.array_equal(u[1], ref.U) and np.array_equal(v[1], ref.U_dot)
    assert run.start == "paper" and run.noise == 1e-3  # the paper's b0 law, its default
    assert np.max(np.abs(u[0] - a * np.cos(k * np.arange(64)))) > 1e-3  # it moved


def test_a_run_from_the_paper_start_grows_at_its_theorys_rate():
    """Case II, delta = +0.0025, k = 2 pi 8/64, a = 0.03: the theory of the state eq. IC
    launches (Hill about it, ``theory_gain``'s "exact lattice, paper start") against
    the model's run from it. Tolerance 5%: from the paper's noise (1e-3) to saturation the
    linear stage holds ~5.5 e-foldings, and the fit over it reads the fastest ring mode
    to ~2% (measured 1.5%); the offset is the theory's fastest, exactly (a ring mode)."""
    model = load_model("flexmm", K_theta=0.016)
    k, a = 2 * np.pi * 8 / 64, 0.03
    th = extra_starts(model)["paper"].theory(model, k, a, 64)
    assert th["label"] == PAPER_START and th["verdict"] == "MI"
    g = simulate_model(model, k, a, N=64, start="paper", seed=1).growth()
    assert g.verdict == "unstable"
    assert g.rate == pytest.approx(th["peak_gain"], rel=0.05)
    assert abs(abs(g.wavenumber - k) - th["fastest_offset"]) < 1e-9


def test_where_eq_ic_has_no_state_the_start_says_why():
    # delta = K_s - K_theta = -0.019 < 0: the continuum frequency alpha sqrt(6 K_theta +
    # delta k^2) is not real above k_max = 2.51
    model = load_model("flexmm", K_s=0.001, K_theta=0.02)
    with pytest.raises(ModelError, match="not real"):
        simulate_model(model, 2.8, 0.02, N=64, start="paper", t_end=10.0)


def test_point_from_the_paper_start(capsys):
    from cli.app import main

    code = main(["point", "--model", "flexmm", "--param", "K_theta=0.016", "--k", "0.7854",
                 "--N", "64", "--amplitude", "0.03", "--start", "paper", "--simulate",
                 "--seeds", "1", "--json"])
    out = json.loads(capsys.readouterr().out)
    assert code == 0
    row = out[PAPER_START]
    assert row["verdict"] == "MI" and out["simulated"]["start"] == "paper"
    assert out["simulated"]["peak_gain"] == pytest.approx(row["peak_gain"], rel=0.05)
    assert PAPER_START in out["curves"]
    # the run's length follows this start's theory (9 e-foldings of its rate), not the
    # exact wave's
    assert out["simulated"]["t_end"] == pytest.approx(round(9 / row["peak_gain"], -2))


@pytest.mark.parametrize("argv,words", [
    (["--model", "fput", "--k", "1"], "belongs to the paper chain's energy"),
    (["--model", "flexmm-lossy", "--k", "1"], "no such start"),
    (["--model", "flexmm", "--param", "K_s=0.001", "--param", "K_theta=0.02", "--k", "2.8"],
     "not real"),
])
def test_the_paper_start_refused_in_one_line(argv, words, capsys):
    from cli.app import main

    code = main(["point", *argv, "--start", "paper", "--N", "64"])
    err = capsys.readouterr().err
    assert code == 2 and words in err and len(err.strip().splitlines()) == 1, err
