"""Units for any model (issue 44 item 4): --time-unit SECONDS and --length-unit METRES give
rates in 1/s, wavenumbers in rad/m, times in s beside the lattice numbers; a units line in
every table, a "units" object in every JSON, the factors in a model map's store attributes."""

from __future__ import annotations

import json
import math

import pytest

from cli.app import main as cli

T, L = 2.5e-3, 0.04  # seconds per unit of lattice time, metres per site
UNITS = ["--time-unit", str(T), "--length-unit", str(L)]
FPUT = ["--model", "fput", "--param", "alpha=1", "--param", "beta=1.5"]


def _json(argv, capsys) -> dict:
    assert cli(argv) == 0
    return json.loads(capsys.readouterr().out)


def test_coefficients_json_carries_units_and_the_scaled_numbers(capsys):
    co = _json(["coefficients", *FPUT, "--k", "2.5", "--amplitude", "0.1", "--json", *UNITS],
               capsys)
    u, si = co["units"], co["si"]
    assert u["time_unit_s"] == T and u["length_unit_m"] == L
    assert u["lattice"]["peak_gain"] == "1/time" and u["si"]["peak_gain"] == "1/s"
    assert u["lattice"]["k"] == "rad/site" and u["si"]["k"] == "rad/m"
    assert u["si"]["e_folding_time"] == "s" and u["si"]["group_velocity"] == "m/s"
    assert co["peak_gain"] > 0
    assert si["peak_gain"] == pytest.approx(co["peak_gain"] / T, rel=1e-12)
    assert si["omega"] == pytest.approx(co["omega"] / T, rel=1e-12)
    assert si["e_folding_time"] == pytest.approx(co["e_folding_time"] * T, rel=1e-12)
    assert si["k"] == pytest.approx(co["k"] / L, rel=1e-12)
    assert si["band_edge"] == pytest.approx(co["band_edge"] / L, rel=1e-12)
    assert si["group_velocity"] == pytest.approx(co["group_velocity"] * L / T, rel=1e-12)
    assert si["four_wave"]["peak_gain"] == pytest.approx(co["four_wave"]["peak_gain"] / T)


def test_lattice_units_without_the_options(capsys):
    """Without the options the JSON still says what its numbers are in, and has no "si"."""
    co = _json(["coefficients", *FPUT, "--k", "2.5", "--json"], capsys)
    assert co["units"]["time_unit_s"] is None and co["units"]["length_unit_m"] is None
    assert co["units"]["lattice"]["peak_gain"] == "1/time" and co["units"]["si"] == {}
    assert "si" not in co
    assert cli(["coefficients", *FPUT, "--k", "2.5"]) == 0
    assert ("units:    lattice units: time as in the model file, wavenumber rad/site\n"
            in capsys.readouterr().out)


def test_one_unit_alone_scales_its_own_numbers_only(capsys):
    co = _json(["coefficients", *FPUT, "--k", "2.5", "--json", "--time-unit", str(T)], capsys)
    assert co["si"]["peak_gain"] == pytest.approx(co["peak_gain"] / T)
    assert "k" not in co["si"] and "group_velocity" not in co["si"]


def test_coefficients_table_shows_the_units_line_and_si(capsys):
    assert cli(["coefficients", *FPUT, "--k", "2.5", "--amplitude", "0.1", *UNITS]) == 0
    out = capsys.readouterr().out
    assert "units:    lattice units: time as in the model file, wavenumber rad/site; SI: " \
           f"1 time unit = {T:.4g} s (--time-unit), 1 site = {L:.4g} m (--length-unit)" in out
    assert f"k = 2.5 rad/site = {2.5 / L:.4g} rad/m" in out
    line = next(s for s in out.splitlines() if s.startswith("peak gain (1/time)"))
    assert line.endswith(" 1/s") and "=" in line


def test_soliton_json_and_table_carry_units(capsys):
    argv = ["soliton", *FPUT, "--k", "1.0", "--amplitude", "0.05", *UNITS]
    s = _json(argv + ["--json"], capsys)
    assert s["si"]["width"] == pytest.approx(s["width"] * L)
    assert s["si"]["velocity"] == pytest.approx(s["velocity"] * L / T)
    assert s["si"]["frequency"] == pytest.approx(s["frequency"] / T)
    assert cli(argv) == 0
    assert "units:    lattice units" in capsys.readouterr().out


def test_point_table_and_json_carry_units(tmp_path, capsys):
    argv = ["point", *FPUT, "--k", "2.5", "--amplitude", "0.1", "--N", "32", *UNITS,
            "--out", str(tmp_path)]
    assert cli(argv) == 0
    out = capsys.readouterr().out
    assert "units:    lattice units: time as in the model file, wavenumber rad/site; SI:" in out
    assert "peak gain (1/s)" in out and "e-folding (s)" in out and "offset (rad/m)" in out
    p = json.loads((tmp_path / "point.json").read_text())
    assert p["units"]["time_unit_s"] == T and p["units"]["length_unit_m"] == L
    assert p["si"]["k"] == pytest.approx(p["k"] / L)
    assert p["si"]["k_requested"] == pytest.approx(2.5 / L)
    for theory in ("semi-discrete NLS", "exact lattice", "four-wave"):
        gain = p[theory]["peak_gain"]
        assert p["si"][theory]["peak_gain"] == pytest.approx(gain / T, rel=1e-12)
    off = p["exact lattice"]["fastest_offset"]
    assert p["si"]["exact lattice"]["fastest_offset"] == pytest.approx(off / L)
    assert "curves" not in p["si"]  # curves stay in lattice units, said in their description


def test_model_map_json_and_store_attrs_carry_units(tmp_path, capsys):
    import xarray as xr

    out = tmp_path / "map"
    argv = ["map", *FPUT[:4], "--param", "beta=0.5:1.5:2", "--k", "0.5:3:2",
            "--amplitude", "0.1", "--theory-only", "--workers", "1", "--out", str(out),
            "--json", *UNITS]
    m = _json(argv, capsys)
    assert m["units"]["time_unit_s"] == T and m["units"]["length_unit_m"] == L
    assert m["si"]["axes"]["k"] == pytest.approx([0.5 / L, 3.0 / L])
    ds = xr.open_zarr(out / "map.zarr")
    assert ds.attrs["time_unit_s"] == T and ds.attrs["length_unit_m"] == L
    # the same map in other units is another map's store: refused in one line
    assert cli(argv[:-4] + ["--time-unit", str(2 * T)]) == 2
    err = capsys.readouterr().err  # the progress log (stderr with --json), then the error
    last = err.splitlines()[-1]
    assert last.startswith("flexmm: error:") and err.count("flexmm: error") == 1
    assert "time_unit_s" in last and "--overwrite" in last and "Traceback" not in err


@pytest.mark.parametrize("value", ["0", "-1", "inf", "nan", "-inf"])
@pytest.mark.parametrize("option", ["--time-unit", "--length-unit"])
def test_bad_units_are_refused_in_one_line(option, value, capsys):
    assert cli(["coefficients", *FPUT, "--k", "2.5", option, value]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and option in err and "Traceback" not in err
    assert "finite and > 0" in err


def test_units_options_need_a_model(capsys):
    """The paper chain's units come from --physical, which keeps working unchanged."""
    assert cli(["coefficients", "--alpha", "2.5", "--K-s", "0.01851", "--K-theta", "0.01551",
                "--k", "0.81681", "--time-unit", "1e-3"]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "--time-unit" in err and "--model" in err
    assert cli(["coefficients", "--physical", "0.01,2e-6,0.02,1e4,185,1", "--k", "1.0"]) == 0
    out = capsys.readouterr().out
    assert "SI from --physical: 1 T = sqrt(m/k_l) = " in out
    assert math.isfinite(float(out.split("1 T = sqrt(m/k_l) = ")[1].split()[0]))


def test_nls_coefficients_carry_their_units(capsys):
    """g1 = d^2 omega/dk^2 is in site^2/time (m^2/s: L^2 / T); g2 multiplies |a|^2 in
    1/time, a in the carrier field's own unit, which no option converts (1/s: 1 / T)."""
    co = _json(["coefficients", *FPUT, "--k", "2.5", "--amplitude", "0.1", "--json", *UNITS],
               capsys)
    u, si = co["units"], co["si"]
    assert u["lattice"]["g1"] == "site^2/time" and u["si"]["g1"] == "m^2/s"
    assert u["lattice"]["g2"] == "1/(time amplitude^2)"
    assert si["g1"] == pytest.approx(co["g1"] * L**2 / T, rel=1e-12)
    assert si["g2"] == pytest.approx(co["g2"] / T, rel=1e-12)
    assert cli(["coefficients", *FPUT, "--k", "2.5", "--amplitude", "0.1", *UNITS]) == 0
    lines = capsys.readouterr().out.splitlines()
    g1 = next(s for s in lines if s.startswith("g1 = d^2 omega/dk^2 (site^2/time)"))
    assert g1.endswith(" m^2/s")
    assert any(s.startswith("g2 (1/(time amplitude^2))") and s.endswith("1/(s amplitude^2)")
               for s in lines)
