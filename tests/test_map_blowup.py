"""A map cell whose run blows up (a softening bond r^2/2 - r^4 driven past its barrier:
the state leaves the lattice's range) is one undetermined cell of the map, not the end of
the map: before, the run's FloatingPointError ended `flexmm map --model` with one line
after the cells done so far, however many cells were left."""

from __future__ import annotations

import json
import math

import pytest

SOFT = """
name = "soft"
description = "a softening chain: its bond potential has a barrier at strain 1/2"
fields = ["u"]
[parameters]
c = 1.0
[energy]
kinetic = "u_t**2/2"
bond = "c*(u_next - u)**2/2 - (u_next - u)**4"
"""


@pytest.fixture
def soft(tmp_path):
    from energy import load_model

    path = tmp_path / "soft.toml"
    path.write_text(SOFT)
    return load_model(str(path))


def test_a_run_that_blows_up_raises_blowuperror_with_its_time(soft):
    from numerics import BlowUpError
    from numerics.models import simulate_model

    with pytest.raises(BlowUpError, match="the run blew up by t = ") as info:
        simulate_model(soft, 2.0, 0.3, N=32, t_end=200.0, seed=0, energy=False)
    assert 0 < info.value.time < 200.0  # when the stepper saw the non-finite state


def test_a_map_cell_whose_run_blows_up_is_undetermined_with_growth_inf(soft):
    from numerics.models import map_cells, simulated_cell

    (row,) = map_cells(soft, [({"c": 1.0}, 2.0)], 0.3, simulate=True, N=32, t_end=200.0)
    assert row["verdict_simulated"] == "undetermined"
    assert math.isinf(row["growth"]) and row["growth"] > 0
    assert 0 < row["t_simulated"] < 200.0
    assert math.isnan(row["peak_gain_simulated"])
    assert row["verdict_exact"] in ("MI", "stable")  # the theories still stand
    one = simulated_cell(soft, 2.0, 0.3, N=32, t_end=200.0)
    assert one["verdict_simulated"] == "undetermined" and one["peak_gain_simulated"] is None


def test_a_model_map_with_a_blown_up_cell_finishes_and_counts_it(soft, tmp_path, capsys):
    from cli import main

    out = tmp_path / "m"
    rc = main(["map", "--model", str(tmp_path / "soft.toml"), "--amplitude", "0.3:0.6:2",
               "--k", "1:2:2", "--N", "32", "--t-end", "200", "--workers", "1", "--out",
               str(out)])
    text = capsys.readouterr().out
    assert rc == 0
    summary = json.loads((out / "summary.json").read_text())
    assert summary["blew_up_cells"] == 1  # amplitude 0.3, k 2 (0.6 at k 2 has no wave)
    assert "runs that blew up (the state left the lattice's range, growth inf): 1 of 4" \
        in text
    assert text.rstrip().splitlines()[-1].startswith("wrote ")


def test_the_device_paths_cpu_runs_say_the_same_of_a_blown_up_cell(tmp_path):
    """The map's device path runs a lossy model's cells on the CPU (its damped steppers
    are the CPU's; no GPU needed: nothing is launched): the soft chain's escape is the
    same undetermined cell with growth inf as map_cells' (here the damped run's records
    overflow before its stepper sees a non-finite state; the next test takes the
    stepper's BlowUpError)."""
    from energy import load_model
    from numerics.maps import simulate_model_cells_gpu

    path = tmp_path / "soft-lossy.toml"
    path.write_text(SOFT.replace("c = 1.0\n", "c = 1.0\ngamma = 1e-4\n")
                    + '[dissipation]\nsite = "gamma*u_t**2/2"\n')
    lines = []
    (row,) = simulate_model_cells_gpu(load_model(str(path)), [({}, 2.0)], 0.3, N=32,
                                      seeds=1, t_end=200.0, log=lines.append)
    assert row["verdict_simulated"] == "undetermined" and row["device"] == "cpu"
    assert math.isinf(row["growth"]) and 0 < row["t_simulated"] < 200.0


def test_a_blow_up_in_the_device_paths_cpu_runs_is_an_undetermined_cell(monkeypatch):
    """Where the device path's CPU runs raise the blow-up (as the soft chain's ring of 32
    does in map_cells), the cell is map_cells' undetermined one, the block goes on: the
    runs stood in for by one that blows up at t = 5 (no GPU needed: a lossy model's cells
    run on the CPU)."""
    from energy import load_model
    from numerics import BlowUpError
    from numerics.maps import simulate_model_cells_gpu

    def blows_up(*_a, **_k):
        raise BlowUpError("the run blew up by t = 5", time=5.0)

    monkeypatch.setattr("numerics.models.simulate_seeds", blows_up)
    (row,) = simulate_model_cells_gpu(load_model("flexmm-lossy"), [({}, 0.8)], 0.05, N=64,
                                      seeds=1, t_end=100.0, log=lambda *_: None)
    assert row["verdict_simulated"] == "undetermined" and math.isinf(row["growth"])
    assert row["t_simulated"] == 5.0 and row["device"] == "cpu"
