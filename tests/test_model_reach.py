"""A Hertz chain whose contact opens: the solver's "Residuals are not finite" becomes the
model's words, the strain it reaches and the largest amplitude allowed (issue 44, item 7)."""

from __future__ import annotations

import math
import subprocess
import sys

import pytest

from energy import Lattice, ModelError, load_model
from numerics.models import amplitude_reach, energy_not_real, exact_gain_checked

#: V = (2/5)(d0 - r)^(5/2), its linear term removed: real only while r = u_next - u <= d0
HERTZ = Lattice(name="hertz", fields=("u",), parameters={"d0": 0.5}, kinetic="u_t**2/2",
                bond="2*(d0 - (u_next - u))**(5/2)/5 + d0**(3/2)*(u_next - u)")


def test_the_largest_amplitude_is_where_the_linear_strain_reaches_d0():
    model = load_model(HERTZ)
    k = 2.0
    a_max = amplitude_reach(model, k, 0.4)
    # the linear wave's strain 2 a sin(k / 2) reaches d0 (the ring of 512 sites samples
    # the phases: within a few 1e-4)
    assert a_max == pytest.approx(0.5 / (2 * math.sin(k / 2)), rel=2e-3)
    assert amplitude_reach(model, k, 0.2) == 0.2
    assert energy_not_real(model, k, 0.2) is None
    why = energy_not_real(model, k, 0.4)
    assert "not real" in why and "0.673" in why and "d0 = 0.5" in why and "0.297" in why


def test_exact_gain_says_why_instead_of_the_solvers_words():
    with pytest.raises(ModelError, match="energy is not real") as exc:
        exact_gain_checked(load_model(HERTZ), 2.0, 0.4, N=64)
    assert "Residuals" not in str(exc.value)


def test_point_names_the_strain_and_the_largest_amplitude(tmp_path):
    f = tmp_path / "hertz.toml"
    f.write_text('name = "hertz"\nfields = ["u"]\n[parameters]\nd0 = 1.0\n[energy]\n'
                 'kinetic = "u_t**2/2"\n'
                 'bond = "2*(d0 - (u_next - u))**(5/2)/5 + d0**(3/2)*(u_next - u)"\n')
    proc = subprocess.run([sys.executable, "-m", "cli", "point", "--model", str(f),
                           "--param", "d0=0.5", "--k", "2.0", "--amplitude", "0.4", "--N",
                           "64", "--simulate"], capture_output=True, text=True)
    assert proc.returncode == 2
    assert "Residuals" not in proc.stderr and "Traceback" not in proc.stderr
    assert "energy is not real" in proc.stderr and "d0 = 0.5" in proc.stderr
    assert "largest amplitude the model allows" in proc.stderr


def test_a_site_limit_is_named_by_the_displacement_not_a_strain():
    """A site term real only for u > -d (a one-sided substrate) limits the displacement
    |u| = a, whatever the strain: the sentence names the displacement and d (it named the
    strain |u_next - u| = 2 a sin(k/2), a quantity that has no limit here)."""
    model = load_model(Lattice(
        name="substrate", fields=("u",), parameters={"d": 0.5}, kinetic="u_t**2/2",
        bond="(u_next - u)**2/2",
        site="(2/3)*(d + u)**(3/2) - sqrt(d)*u - (2/3)*d**(3/2) + u**2/2"))
    why = energy_not_real(model, 1.0, 0.8)
    assert "displacement |u|" in why and "strain" not in why and "d = 0.5" in why
    # the linear wave's largest |u| is a (512 sites sample the phases to ~1e-4)
    assert amplitude_reach(model, 1.0, 0.8) == pytest.approx(0.5, rel=2e-3)
