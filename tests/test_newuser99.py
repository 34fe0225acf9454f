"""A new user's first two hours (newuser99): what the walk found and fixed.

- ``--param`` and ``--branch`` act only on a lattice model. Given to the paper chain's
  flags (no ``--model``) they were dropped without a word: ``coefficients --alpha 2
  --K-s 0.03 --K-theta 0.02 --k 1 --param K_s=0.5`` answered for K_s = 0.03 with exit 0,
  and the same in point, soliton and map (``--time-unit`` alone was refused already).
"""

import pytest

from cli.app import main

PAPER = ["--alpha", "2", "--K-s", "0.03", "--K-theta", "0.02", "--k", "1"]


def _one_line_error(capsys, argv):
    code = main(argv)
    err = capsys.readouterr().err.strip().splitlines()
    assert code == 2 and len(err) == 1, err
    return err[0]


@pytest.mark.parametrize("command, extra", [
    ("coefficients", []),
    ("point", ["--case", "coupled"]),
    ("soliton", ["--case", "coupled", "--amplitude", "0.005"]),
    ("map", ["--case", "coupled", "--theory-only", "--out", "unused"]),
])
@pytest.mark.parametrize("option", [["--param", "K_s=0.5"], ["--branch", "1"],
                                    ["--param=K_s=0.5"]])
def test_model_options_given_to_the_paper_flags_are_refused(command, extra, option, capsys,
                                                            tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    err = _one_line_error(capsys, [command, *PAPER, *extra, *option])
    name = option[0].split("=", 1)[0]
    assert f"{name} does nothing without --model" in err, err
    assert not (tmp_path / "unused").exists()  # refused before any work


def test_model_options_still_act_with_a_model(capsys):
    assert main(["coefficients", "--model", "diatomic-fput", "--param", "m=3",
                 "--branch", "v", "--k", "1", "--amplitude", "0.05"]) == 0
    assert "m = 3" in capsys.readouterr().out
