"""What probe 99 of the edges found (bench/probe_edges99.py runs all its tries):

- the Python API refused a 0-d array (``np.array(2.5)``, what numpy's reductions hand
  back) where it takes the number, some with a message naming a valid value as invalid
  ("k must be in (0, pi], got array(2.5)", "t_end must be a finite time > 0, got
  array(10.)", "travel must be a number of widths > 0, got np.float32(1.0)");
- ``simulate_model(initial=...)`` holding nan or inf blew up "by t = 0 ... lower the
  amplitude or dt"; ``expected_gain`` and ``simulate_seeds``' ``gain`` took nan, -1 and
  inf silently (as a rate of 0: a run of T = 5000);
- ``--time-unit 5e-324`` printed "omega = inf 1/s" and "peak gain 0 = nan 1/s";
- ``point --simulate --t-end 5e-324`` was refused as "t_end ... got 0.0" (the estimate's
  probe run of T / 1e4 underflowed), naming neither the option nor its value;
- ``soliton --simulate --travel 1e-100`` measured a velocity of -5e87 sites/time (the
  position's round-off over a step of 1e-100 widths) and printed it as the lattice's; the
  paper chain's said "dt = 0.25 is larger than t_end = 8e-99";
- ``map --workers 1000`` on a 4-cell map started 1000 worker processes on 2 cores (no
  answer within 60 s).
"""

from __future__ import annotations

import json
import math
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

import numerics.models as nm
from cli.app import main as cli
from energy import ModelError, load_model

FPUT = ["--model", "fput", "--param", "alpha=1", "--param", "beta=1"]


@pytest.fixture(scope="module")
def fput():
    return load_model("fput", alpha=1, beta=1)


def test_a_0d_array_is_the_number_it_holds(fput):
    """Each entry point gives the same answer for 2.5 and np.array(2.5) (before: refused)."""
    a, b = (nm.model_coefficients(fput, k, amp) for k, amp in
            ((1.0, 0.1), (np.array(1.0), np.array(0.1))))
    assert a["g2"] == b["g2"] and a["omega"] == b["omega"]
    ring = [nm.exact_gain(fput, k, 0.1, N=64).gain for k in (2.5, np.array(2.5))]
    assert np.array_equal(*ring)
    chain = [nm.four_wave(fput, k, amp).gain for k, amp in ((2.5, 0.1),
                                                            (np.array(2.5), np.array(0.1)))]
    assert chain[0] == chain[1]
    assert load_model("fput", beta=np.array(2.0)).params["beta"] == 2.0
    run = nm.simulate_model(fput, 2.5, 0.1, N=16, t_end=np.array(10.0), records=2)
    assert run.t[-1] == 10.0
    pred = nm.ring_soliton(fput, 1.0, 0.05)
    assert nm.travel_time(pred, np.float32(1.0)) == nm.travel_time(pred, 1.0)


@pytest.mark.parametrize("bad", [(np.nan, 0.0), (0.0, np.inf)])
def test_an_initial_state_with_nan_or_inf_is_refused_by_name(fput, bad):
    u = np.full((1, 16), bad[0])
    v = np.full((1, 16), bad[1])
    with pytest.raises(ModelError, match="^initial must be finite") as exc:
        nm.simulate_model(fput, 2.5, 0.1, N=16, t_end=10.0, initial=(u, v))
    assert "\n" not in str(exc.value)


@pytest.mark.parametrize("rate", [math.nan, -1.0, math.inf])
def test_a_given_rate_must_be_a_rate(fput, rate):
    with pytest.raises(ModelError, match="^expected_gain must be a finite rate >= 0"):
        nm.simulate_model(fput, 2.5, 0.1, N=16, expected_gain=rate)
    spec = nm.exact_gain(fput, 2.5, 0.1, N=32)
    with pytest.raises(ModelError, match="^gain must be a finite rate >= 0"):
        nm.simulate_seeds(fput, 2.5, 0.1, spec, N=32, gain=rate)


def test_units_past_float64_are_refused_and_no_nan_is_printed(capsys):
    assert cli(["coefficients", *FPUT, "--k", "1", "--amplitude", "0.1",
                "--time-unit", "5e-324"]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "--time-unit" in err and "Traceback" not in err
    # 1e300 s per unit: every rate 1e-300 /s, finite; omega = 2 sin(1/2) by hand
    assert cli(["coefficients", *FPUT, "--k", "1", "--amplitude", "0.1",
                "--time-unit", "1e300"]) == 0
    out = capsys.readouterr().out
    assert " nan " not in out and " inf " not in out
    line = next(ln for ln in out.splitlines() if ln.startswith("omega"))
    assert float(line.split("=")[1].split()[0]) == pytest.approx(2 * math.sin(0.5) * 1e-300,
                                                                 rel=1e-3)  # 4 digits shown


def test_a_subnormal_t_end_is_refused_by_its_option(capsys):
    assert cli(["point", *FPUT, "--k", "2.5", "--amplitude", "0.1", "--N", "64",
                "--simulate", "--t-end", "5e-324"]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert err[-1].startswith("flexmm: error: --t-end must be in [1e-300")


@pytest.mark.parametrize("travel", ["1e-100", "1e-10"])
def test_a_travel_too_short_to_measure_is_refused(travel, capsys):
    assert cli(["soliton", *FPUT, "--k", "1", "--amplitude", "0.05", "--simulate",
                "--travel", travel]) == 2
    assert "--travel must be in [0.1, 1000)" in capsys.readouterr().err
    assert cli(["soliton", "--alpha", "2.5", "--K-s", "0.01851", "--K-theta", "0.02151",
                "--k", "0.92991", "--amplitude", "0.002", "--case", "rotation", "--simulate",
                "--travel", travel]) == 2
    assert "--travel must be in [0.1, 1000)" in capsys.readouterr().err


def test_the_shortest_travel_still_measures_the_group_velocity(capsys):
    """FPUT (alpha 1, beta 1): omega = 2 sin(k/2), v_g = cos(k/2) = 0.8776 at k = 1 (by
    hand); at a = 0.05 the soliton moves at 0.8815 (its O(a^2) shift, the same at travel
    1 and 20): 1% holds both."""
    assert cli(["soliton", *FPUT, "--k", "1", "--amplitude", "0.05", "--simulate",
                "--travel", "0.1", "--json"]) == 0
    measured = json.loads(capsys.readouterr().out)
    v = measured["measured"]["velocity"]
    assert v == pytest.approx(math.cos(0.5), rel=1e-2)


@pytest.mark.slow
def test_more_workers_than_cells_start_one_a_cell(tmp_path):
    """Before: 1000 worker processes for 4 cells, no answer within 60 s on 2 cores."""
    argv = [sys.executable, "-m", "cli", "map", "--model", "fput", "--param", "alpha=1",
            "--param", "beta=0.5:1.5:2", "--k", "2:3:2", "--amplitude", "0.1",
            "--theory-only", "--workers", "1000", "--out", str(tmp_path / "m")]
    p = subprocess.run(argv, capture_output=True, text=True, timeout=150,
                       cwd=Path(__file__).resolve().parents[1])
    said = p.stdout + p.stderr
    assert p.returncode == 0, said[-300:]
    assert "on 4 worker(s)" in said and "Traceback" not in said


@pytest.mark.parametrize("noise", [1.0, 1e300])
def test_noise_is_a_share_of_the_amplitude_below_1(fput, noise):
    """As the paper chain's (``numerics.lattice``): before, 1e300 blew up "by t = 0 ...
    lower the amplitude or dt", naming neither."""
    with pytest.raises(ModelError, match=r"^noise must be a number in \[0, 1\)"):
        nm.simulate_model(fput, 2.5, 0.1, N=16, t_end=10.0, noise=noise)
    assert nm.simulate_model(fput, 2.5, 0.1, N=16, t_end=10.0, noise=0.5,
                             records=2).t[-1] == 10.0


def test_a_zero_branch_names_the_branch_that_carries_a_wave():
    """v is in the kinetic energy only: a zero branch, the lowest, the default. Before: "no
    carrier wave there", no remedy. u is FPUT's: omega = 2 sin(k/2) by hand."""
    from energy import Lattice

    lat = Lattice(name="nodep", fields=("u", "v"), parameters={"beta": 1.0},
                  kinetic="u_t**2/2 + v_t**2/2",
                  bond="(u_next - u)**2/2 + beta*(u_next - u)**4/4")
    model = load_model(lat)
    with pytest.raises(ModelError, match=r"no carrier wave there; branch 1 carries one: give "
                                         r"branch \(--branch\) 1$"):
        nm.model_coefficients(model, 2.5, 0.1)
    assert nm.model_coefficients(model, 2.5, 0.1, 1)["omega"] == pytest.approx(
        2 * math.sin(1.25), rel=1e-12)


SOLITON = ["soliton", *FPUT, "--k", "1", "--amplitude", "0.05"]


def test_an_interrupt_while_the_figure_is_drawn_leaves_nothing(tmp_path, monkeypatch, capsys):
    """Before: soliton.json was written, then SIGTERM came while soliton.png was drawn:
    soliton.json alone, and the command said "nothing was written"."""
    import signal

    import cli.model_soliton as ms
    from common.signals import Interrupted

    def drawing(*args, **kw):
        raise Interrupted(signal.SIGTERM)  # what the handler raises mid-drawing

    monkeypatch.setattr(ms, "_figure", drawing)
    assert cli([*SOLITON, "--out", str(tmp_path / "s")]) == 143
    assert "nothing was written" in capsys.readouterr().err
    assert not (tmp_path / "s").exists() or not any((tmp_path / "s").iterdir())


def test_an_interrupt_while_the_files_are_written_waits_for_both(tmp_path, monkeypatch,
                                                                  capsys):
    """A SIGTERM sent while the first file is written is held until the second is: both are
    whole, and the message names them."""
    import os
    import signal

    import common.files as files

    real = files.atomic_write
    sent = []

    def first_write_signalled(path, mode="w"):
        if not sent and Path(path).name.startswith("soliton."):
            sent.append(path)
            os.kill(os.getpid(), signal.SIGTERM)
        return real(path, mode)

    monkeypatch.setattr(files, "atomic_write", first_write_signalled)
    out = tmp_path / "s"
    assert cli([*SOLITON, "--out", str(out)]) == 143
    assert sent, "the writer was not reached"
    err = capsys.readouterr().err
    assert "after writing" in err and "soliton.json" in err and "soliton.png" in err
    assert json.loads((out / "soliton.json").read_text())["kind"] == "dark"
    assert (out / "soliton.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


def test_an_interrupt_a_library_swallowed_is_still_the_exit(tmp_path, monkeypatch, capsys):
    """The handler's Interrupted raised inside a __del__ (or any code that catches it) was
    lost: the command went on and exited 0 (probe 99, once, a SIGTERM while soliton.png was
    drawn: a traceback printed and exit 0). It is the exit code all the same."""
    import signal

    import cli.model_soliton as ms
    from common.signals import raise_interrupted

    def drawing(*args, **kw):
        try:
            raise_interrupted(signal.SIGTERM, None)  # the handler, mid-drawing
        except KeyboardInterrupt:
            pass  # as Python does with an exception raised in a __del__
        return b"\x89PNG\r\n\x1a\n"

    monkeypatch.setattr(ms, "_figure", drawing)
    assert cli([*SOLITON, "--out", str(tmp_path / "s")]) == 143
    assert "interrupted (SIGTERM)" in capsys.readouterr().err
