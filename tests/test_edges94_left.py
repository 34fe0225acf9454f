"""Edges (issue 94, five rough edges of the CLI): a model map's cell where the model
carries no wave of the amplitude gets no NLS verdict; summary.json's mi_fraction means the
same for every map; argparse's own value errors are one line with a remedy; "1 cell", and
a model's soliton at an amplitude it cannot have is refused; --overwrite starts afresh."""


import pytest

from cli.app import main

TODA = """
name = "toda"
fields = ["u"]
[parameters]
a = 1.0
b = 1.0
[energy]
kinetic = "u_t**2/2"
bond = "a/b*(exp(-b*(u_next - u)) - 1 + b*(u_next - u))"
"""


def _one_line_error(capsys, argv):
    code = main(argv)
    err = capsys.readouterr().err.strip().splitlines()
    assert code == 2 and len(err) == 1, err
    return err[0]


# ------------------------------------------------------------ 3: argparse's value errors
@pytest.mark.parametrize("argv, said", [
    (["point", "--model", "fput", "--k", "1", "--N", "1.5"],
     "--N: '1.5' is not a whole number; give one such as 500"),
    (["point", "--model", "fput", "--k", "1", "--amplitude", "x"],
     "--amplitude: 'x' is not a number; give one such as 0.02"),
    (["coefficients", "--model", "fput", "--k", "abc"],
     "--k: 'abc' is not a number; give one such as 1.2"),
    (["table", "--A0", "zz"], "--A0: 'zz' is not a number; give one such as 1"),
    (["map", "--model", "fput", "--param", "beta=1:2:2", "--k", "1", "--device", "tpu"],
     "--device: 'tpu' is not one of 'cpu', 'gpu', 'auto'"),
])
def test_a_value_argparse_cannot_read_is_one_line_with_a_remedy(argv, said, capsys):
    err = _one_line_error(capsys, argv)
    assert err.startswith("flexmm: error: " + said), err


def test_an_unknown_option_keeps_its_usage_and_nearest_name(capsys):
    # the other errors of argparse stay its own (the usage, and the nearest option)
    with pytest.raises(SystemExit) as exc:
        main(["coefficients", "--model", "fput", "--k", "1", "--amplitudee", "0.1"])
    assert exc.value.code == 2
    assert "did you mean --amplitude?" in capsys.readouterr().err


