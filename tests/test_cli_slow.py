"""A point that computes for long says so (a new user's fresh clone: `flexmm point --model
fput-lossy.toml ...` printed nothing for 93 s while its kernels compiled once, the paper
chain's `point --physical ... --simulate` nothing for 94 s)."""

from __future__ import annotations

import time

import pytest

import cli._model_point_args
import cli._slow
import cli.point
from cli._slow import said_if_slow
from cli.app import main

PAPER = ["point", "--alpha", "2.5", "--K-s", "0.01851", "--K-theta", "0.01551",
         "--k", "0.81681", "--case", "coupled"]
MODEL = ["point", "--model", "fput", "--k", "2", "--amplitude", "0.1", "--N", "16"]


@pytest.fixture
def slow_points(monkeypatch):
    """measure_point 0.5 s slower than it is, and a note after 0.05 s: 10x apart, so the
    timer fires whatever the machine's load (a thread's start is milliseconds)."""
    real = cli.point.measure_point

    def slow(*args, **kwargs):
        time.sleep(0.5)
        return real(*args, **kwargs)

    monkeypatch.setattr(cli.point, "measure_point", slow)  # the paper chain's point
    monkeypatch.setattr(cli._model_point_args, "measure_point", slow)  # --model's
    monkeypatch.setattr(cli._slow, "SLOW_NOTE_S", 0.05)


@pytest.mark.parametrize("argv, note", [
    (MODEL, cli._slow.SLOW_MODEL_POINT),
    ([*PAPER, "--N", "100", "--seeds", "1"], cli._slow.SLOW_PAPER_POINT)])
def test_a_slow_point_says_what_it_computes(slow_points, capsys, argv, note):
    assert main(argv) == 0
    out, err = capsys.readouterr()
    assert err.count(note) == 1 and note not in out  # stdout's text is the machine's own
    assert "theory" in out


def test_a_model_points_note_goes_to_stderr_with_json(slow_points, capsys):
    import json

    assert main([*MODEL, "--json"]) == 0
    out, err = capsys.readouterr()
    json.loads(out)  # stdout stays one JSON object
    assert cli._slow.SLOW_MODEL_POINT in err


class _Stop(Exception):
    pass


def test_a_paper_point_says_its_runs_before_them(monkeypatch, capsys):
    """--simulate: the runs' line comes before any computation (seconds to minutes)."""
    def stop(*args, **kwargs):
        raise _Stop

    monkeypatch.setattr(cli.point, "measure_point", stop)
    with pytest.raises(_Stop):
        main([*PAPER, "--simulate", "--seeds", "2", "--N", "100"])
    out = capsys.readouterr().out
    assert "point: the theories and each seed's predicted growth, then 2 run(s) of the " \
           "ring of N = 100 sites, T = 9 e-foldings of the exact rate" in out


def test_nothing_is_said_where_the_step_ends_first():
    said = []
    with said_if_slow(said.append, "slow", after=5.0):
        pass
    time.sleep(0.1)  # a cancelled timer never fires
    assert said == []
    with pytest.raises(ZeroDivisionError), said_if_slow(said.append, "slow", after=0.2):
        raise ZeroDivisionError
    time.sleep(0.4)
    assert said == []


def test_a_paper_point_with_runs_says_its_slow_theories(slow_points, capsys):
    """--simulate: the theories before the runs' estimate said nothing (a fresh clone: 32 s
    while the kernels compiled, newuser101); now the slow note, once, on stderr, as
    without runs."""
    assert main([*PAPER, "--N", "64", "--seeds", "1", "--simulate", "--t-end", "200"]) == 0
    out, err = capsys.readouterr()
    assert err.count(cli._slow.SLOW_PAPER_POINT) == 1 and cli._slow.SLOW_PAPER_POINT not in out
