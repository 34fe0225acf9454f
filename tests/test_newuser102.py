"""An experimentalist's first afternoon with losses and physical units (newuser102).

- A shaker and a spectrum analyser read a frequency f in Hz; `coefficients` gave the carrier
  only as the angular omega (1/T, and with units "= 770.4 1/s"), which reads as Hz to an
  experimentalist and is 2 pi too high. With --physical (the paper chain) or --time-unit
  (a model) the table now also gives f = omega / (2 pi) in Hz.
- --amplitude of the paper chain's flags is the peak rotation in rad; "5" meant as degrees
  was refused as "--amplitude must be in (0, 1.5), got 5.0": no unit and no remedy. The
  refusal now names the unit and the value in rad.
"""

import json
import math

import pytest

from cli.app import main

#: the paper's blue material in SI: 1 g, J = 4e-9 kg m^2, a = 10 mm, k_l = 1000 N/m, so
#: alpha = a sqrt(m / 4J) = 2.5, K_s = k_s / k_l = 0.01851, K_theta = 4 k_theta / (k_l a^2)
#: = 0.01551, and 1 T = sqrt(m / k_l) = 1 ms
PHYSICAL = "1e-3,4e-9,0.01,1000,18.51,3.8775e-4"
ALPHA, K_S, K_THETA, SECONDS_PER_T = 2.5, 0.01851, 0.01551, 1e-3


def _omega_theta(k):
    """The rotational branch's linear frequency (1/T), from eq. `norm`'s quadratic energy:
    theta_tt / alpha^2 = K_s (theta_{n+1} - 2 theta_n + theta_{n-1})
    - K_theta (theta_{n+1} + 2 theta_n + theta_{n-1}) - 2 K_theta theta_n."""
    return ALPHA * math.sqrt(4 * K_S * math.sin(k / 2) ** 2
                             + 4 * K_THETA * math.cos(k / 2) ** 2 + 2 * K_THETA)


def test_physical_coefficients_give_the_carrier_frequency_in_hz(capsys):
    k = 0.81681
    assert main(["coefficients", "--physical", PHYSICAL, "--k", str(k), "--amplitude",
                 "0.028"]) == 0
    rows = [ln for ln in capsys.readouterr().out.splitlines() if ln.startswith("f = omega")]
    assert len(rows) == 1, rows
    semi_discrete = float(rows[0].split()[-1])  # the lattice's own (linear) frequency
    # 6 significant digits printed: rel 1e-5
    assert semi_discrete == pytest.approx(_omega_theta(k) / (2 * math.pi * SECONDS_PER_T),
                                          rel=1e-5)


def test_model_coefficients_give_omega_in_hz_with_a_time_unit(capsys):
    k, seconds = 2.5, 1e-3
    assert main(["coefficients", "--model", "fput", "--param", "alpha=1", "--param",
                 "beta=1.5", "--k", str(k), "--amplitude", "0.1", "--time-unit",
                 str(seconds)]) == 0
    row = next(ln for ln in capsys.readouterr().out.splitlines()
               if ln.startswith("omega (1/time)"))
    hz = float(row.split("(f = ")[1].split(" Hz")[0])
    # FPUT with unit masses and bond r^2/2: omega = 2 sin(k/2); 4 digits printed
    assert hz == pytest.approx(2 * math.sin(k / 2) / (2 * math.pi * seconds), rel=5e-4)


def test_model_coefficients_without_a_time_unit_print_no_hz(capsys):
    assert main(["coefficients", "--model", "fput", "--k", "2.5", "--amplitude", "0.1"]) == 0
    assert "Hz" not in capsys.readouterr().out


MATERIAL = ["--alpha", "2", "--K-s", "0.03", "--K-theta", "0.02"]


@pytest.mark.parametrize("command, extra, high", [
    ("coefficients", MATERIAL, 1.5),
    ("point", [*MATERIAL, "--case", "coupled"], 1.5),
    ("soliton", [*MATERIAL, "--case", "coupled"], 1.0),
    ("map", ["--alpha", "2", "--K-s", "0.03", "--delta", "-0.01:0.01:3", "--case",
             "coupled", "--theory-only", "--out", "unused"], 1.5),
])
def test_an_amplitude_in_degrees_is_refused_with_its_value_in_rad(capsys, tmp_path,
                                                                   monkeypatch, command,
                                                                   extra, high):
    monkeypatch.chdir(tmp_path)  # nothing is written: the refusal comes first
    argv = [command, *extra, "--k", "1.2", "--amplitude", "5"]
    assert main(argv) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1, err
    assert "rad" in err[0] and f"below {high:g} rad" in err[0]
    assert f"--amplitude {math.radians(5):.4g}" in err[0]  # 5 degrees = 0.08727 rad
    assert not any(tmp_path.iterdir())


def test_a_negative_amplitude_names_the_unit_but_no_degrees(capsys):
    argv = ["point", "--alpha", "2", "--K-s", "0.03", "--K-theta", "0.02", "--k", "1.2",
            "--case", "coupled", "--amplitude", "-1"]
    assert main(argv) == 2
    err = capsys.readouterr().err.strip()
    assert "peak rotation" in err and "degrees" not in err


def test_an_angle_past_a_quarter_turn_is_said_with_its_value_in_degrees(capsys):
    """flexmm-lossy at a = 3 (meant: 3 degrees) answered with the exact lattice's 4.6e266x
    amplification, "observable", and no word on the unit."""
    co = json.loads(_out(capsys, ["coefficients", "--model", "flexmm-lossy", "--k", "0.81681",
                                  "--amplitude", "3", "--json"]))
    notes = [w for w in co["warnings"] if "degrees" in w]
    assert len(notes) == 1, co["warnings"]
    # 3 rad = 171.9 degrees; 3 degrees = 0.05236 rad (math, not the code under test)
    assert f"{math.degrees(3):.4g} degrees" in notes[0]
    assert f"--amplitude {math.radians(3):.4g}" in notes[0]


@pytest.mark.parametrize("model, amplitude", [
    ("flexmm-lossy", 0.028),   # an angle, well inside a quarter turn
    ("flexmm-lossy", 1.5),     # just inside (pi/2 = 1.5708)
    ("fput", 3.0),             # a displacement: no cos/sin of u in its energy
])
def test_no_angle_note_inside_a_quarter_turn_or_for_a_displacement(capsys, model, amplitude):
    co = json.loads(_out(capsys, ["coefficients", "--model", model, "--k", "1",
                                  "--amplitude", str(amplitude), "--json"]))
    assert not [w for w in co["warnings"] if "degrees" in w]


def test_the_angle_note_reads_the_field_of_the_next_cell_too():
    """A field the energy reads only as cos(u_next) is an angle as well; a field whose name
    only begins another's (u in cos(uu)) is not."""
    from energy import load_model, parse_model
    from numerics.models import model_coefficients

    src = ('name = "t"\nfields = ["u", "uu"]\nbranch = "u"\n[parameters]\nC = 1.0\n'
           '[energy]\nkinetic = "u_t**2/2 + uu_t**2/2"\n'
           'bond = "C*(u_next - u)**2/2 + (1 - cos(u_next)) + (1 - cos(uu))"\n'
           'site = "u**2 + uu**2"\n')

    def said(text):
        warnings = model_coefficients(load_model(parse_model(text)), 1.0, 2.0)["warnings"]
        return [w for w in warnings if "degrees" in w]

    assert said(src)
    assert not said(src.replace("(1 - cos(u_next)) + ", ""))


def _out(capsys, argv) -> str:
    assert main(argv) == 0
    return capsys.readouterr().out
