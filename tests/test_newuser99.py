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


LJ = """name = "lj-chain"
description = "unit masses, Lennard-Jones bonds of unit stiffness at rest"
fields = ["u"]
[parameters]
eps = 0.013888888888888888
[energy]
kinetic = "u_t**2/2"
bond = "eps*((1 + u_next - u)**(-12) - 2*(1 + u_next - u)**(-6) + 1)"
"""


def _exact_row_and_misses(capsys, argv):
    assert main(argv) == 0
    lines = capsys.readouterr().out.splitlines()
    exact = next(l for l in lines if l.startswith("exact lattice "))
    return exact, [l for l in lines if "which no offset 2 pi j / N" in l]


def test_the_n_a_missed_band_note_advises_samples_that_band(capsys, tmp_path):
    """The LJ chain at k = 1, a = 0.01 on 128 sites: the exact theory finds narrow
    resonance bands (1e-3 wide near offset 1.14) that no ring offset samples, and the note
    named an N that 'does'. On that ring k snapped elsewhere (N = 132: k 0.9817 ->
    0.9996), where the chain's bands lie elsewhere: the point was stable again, with a
    new N advised (145, 151). A user who follows the note must see the band grow."""
    model = tmp_path / "lj.toml"
    model.write_text(LJ)
    base = ["point", "--model", str(model), "--amplitude", "0.01"]
    exact, notes = _exact_row_and_misses(capsys, [*base, "--k", "1", "--N", "128"])
    assert exact.split()[2] == "stable" and notes, (exact, notes)
    import re

    for note in notes:
        m = re.search(r"samples: N = (\d+)(?: with --k (\S+))?", note)
        assert m, note
        k = m.group(2) or "1"  # the old text named no k: the user's own
        exact, _ = _exact_row_and_misses(capsys, [*base, "--k", k, "--N", m.group(1)])
        assert exact.split()[2] == "MI", (note, exact)


def test_a_narrow_missed_band_is_printed_with_distinct_edges():
    from cli._model_point_text import _miss_text

    text = _miss_text({"band": (1.14183, 1.14241), "peak_gain": 2e-4, "N": 352,
                       "same_k": True}, 128, 0.98174770424681)
    assert "offsets 1.1418 to 1.1424 rad/site" in text
    assert "N = 352 with --k 0.981747704" in text
