"""What issue 94's hidden check of the paper chain found wrong (seeded random materials,
not the paper's two points, probed against independent finite differences of eq. `norm`
linearised, simulations and edge inputs), each reproduced on its input."""

from __future__ import annotations

import pytest

from cli.app import main
from numerics import Material


def _one_line_error(capsys, argv):
    code = main(argv)
    err = capsys.readouterr().err.strip().splitlines()
    assert code == 2 and len(err) == 1, err
    return err[0]


@pytest.mark.parametrize("values", [
    # k_l a^2 = 1e-300 * 1e-600 underflows to 0: a ZeroDivisionError traceback
    "1e-300,1e-300,1e-300,1e-300,1e-300,1e-300",
    # m / (4 J) overflows: alpha = inf
    "1e300,1e-300,1,1,1,1",
    # k_l a^2 overflows: K_theta = 0, refused as 'K_theta must be > 0' without naming why
    "1,1,1e200,1,1,1",
    # the material is fine (alpha 0.5, K_s 1, K_theta 4) but sqrt(m / k_l) = inf: 'inf s'
    "1e300,1e300,1,1e-300,1e-300,1e-300",
])
def test_physical_values_outside_float64_are_one_line_errors(values, capsys):
    err = _one_line_error(capsys, ["coefficients", "--physical", values, "--k", "1"])
    assert err.startswith("flexmm: error: --physical m,J,a,k_l,k_s,k_theta: ")
    assert "float64" in err and "units" in err  # the cause and the remedy


def test_from_physical_outside_float64_is_a_value_error():
    with pytest.raises(ValueError, match="float64"):
        Material.from_physical(1e-300, 1e-300, 1e-300, 1e-300, 1e-300, 1e-300)
    # an ordinary material still converts (alpha = a sqrt(m / 4J) = 0.02 sqrt(0.01/4e-6))
    mat = Material.from_physical(0.01, 1e-6, 0.02, 1000.0, 20.0, 0.02)
    assert mat.alpha == pytest.approx(0.02 * 50.0, rel=1e-14)
    assert mat.K_s == pytest.approx(0.02, rel=1e-14)
    assert mat.K_theta == pytest.approx(4 * 0.02 / (1000.0 * 0.02**2), rel=1e-14)
