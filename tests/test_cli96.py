"""Probe 96: the command line and the Python entry points at inputs nobody tried
(bench/probe_cli96.py). Each test names what the old tree did."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

import energy
import numerics.models as nm
from energy import ModelError
from generated import soliton as closed


@pytest.mark.parametrize("k", [-1.0, 0.0, 4.0, 7.0, math.pi + 1e-12, -math.pi])
def test_carrier_takes_the_range_nls_takes(k):
    # before: carrier(fput, -1.0) returned a Carrier with k = -1 (omega 0.9589, v_g of the
    # wave at +1) and carrier(fput, 7.0) one with k = 7, where nls, exact_gain and
    # four_wave refuse k outside (0, pi]; carrier(fput, 0.0) talked of float64 resolution
    m = energy.load_model("fput", alpha=1, beta=1)
    with pytest.raises(ModelError, match=r"k must be in \(0, pi\].*got"):
        nm.carrier(m, k)
    with pytest.raises(ModelError, match=r"k must be in \(0, pi\]"):
        nm.nls(m, k)


def test_carrier_keeps_the_zone_boundary():
    # FPUT by hand: omega = 2 sin(k/2) = 2 at pi, v_g = cos(k/2) = 0, g1 = -sin(k/2)/2
    c = nm.carrier(energy.load_model("fput"), math.pi)
    assert c.omega == pytest.approx(2.0, rel=1e-14)
    assert c.group_velocity == 0.0
    assert c.g1 == pytest.approx(-0.5, rel=1e-10)  # lambda'' - 2 v_g^2: a few ulps of 1


G1, G2 = 0.02, 40.0  # bright: g = 2000; dark: g2 -> -G2


@pytest.mark.parametrize("a", [0.002, 0.01])
def test_soliton_forms_take_the_amplitude_by_its_size(a):
    # before: bright_width(-0.002, 0.02, 40) = -22.4 sites, dark_width and both kinks
    # negative too: a width is a length. The amplitude is the peak rotation 2|E| and
    # E -> -E solves the NLS when E does, so -a is the soliton of |a| (docs/solitons.md).
    # By hand, with a/2 = |E|: w = 1/((a/2) sqrt(g)), kink 2 mu (a/2)^2 w
    g, mu, phi = G2 / G1, -1.3, 0.4
    w_bright = 1 / (a / 2 * math.sqrt(g))
    w_dark = 1 / (a / 2 * math.cos(phi) * math.sqrt(g))
    for amp in (a, -a):
        assert closed.bright_width(amp, G1, G2) == pytest.approx(w_bright, rel=1e-14)
        assert closed.dark_width(amp, phi, G1, -G2) == pytest.approx(w_dark, rel=1e-14)
        assert closed.bright_kink(amp, G1, G2, mu) == pytest.approx(
            2 * mu * (a / 2) ** 2 * w_bright, rel=1e-14)
        assert closed.dark_kink(amp, phi, G1, -G2, mu) == pytest.approx(
            -2 * mu * (a / 2) ** 2 * math.cos(phi) ** 2 * w_dark, rel=1e-14)
        # V = g1 (a/2) sin(phi) sqrt(-g): the grey soliton of |a|, not the mirror one
        assert closed.dark_velocity(amp, phi, G1, -G2) == pytest.approx(
            G1 * a / 2 * math.sin(phi) * math.sqrt(g), rel=1e-14)
    xi, t = np.linspace(-3 * w_bright, 3 * w_bright, 41), 7.0
    np.testing.assert_array_equal(closed.bright_envelope(xi, t, -a, G1, G2),
                                  closed.bright_envelope(xi, t, a, G1, G2))
    np.testing.assert_array_equal(closed.dark_envelope(xi, t, -a, phi, G1, -G2),
                                  closed.dark_envelope(xi, t, a, phi, G1, -G2))


# ------------------------------------------------------------------ the command line

def _fails(capsys, argv) -> str:
    """The one stderr line of a refused command (exit 2, no traceback)."""
    from cli.app import main

    assert main(argv) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "Traceback" not in err[0], err
    return err[0]


@pytest.mark.parametrize("value", ["0", "-1", "nan", "1e200"])
def test_table_names_its_option(capsys, value):
    # before: "A0 must be in (0, 75], got 0.0": no option of that name
    assert _fails(capsys, ["table", "--A0", value]).startswith(
        "flexmm: error: --A0 must be in (0, 75]")


@pytest.mark.parametrize("argv", [
    ["point", "--alpha", "2.5", "--K-s", "0.01851", "--K-theta", "0.01551", "--k", "0.81681",
     "--case", "coupled"],
    ["soliton", "--model", "fput", "--k", "1.0", "--amplitude", "0.05"],
    ["map", "--model", "fput", "--param", "beta=1:2:2", "--k", "0.5:1:2", "--theory-only"],
    ["scene", "fig2-dispersion", "--quick"],
    ["run", "--quick"],
])
@pytest.mark.parametrize("under", [False, True])
def test_an_out_that_is_a_file_is_named_as_the_option(capsys, tmp_path, argv, under):
    # before: "/tmp/.../afile is a file, not a folder" (or "cannot create ...: ... is a
    # file"), naming no option; now --out, the remedy, and nothing written beside it
    f = tmp_path / "afile"
    f.write_text("x")
    out = f / "sub" if under else f
    err = _fails(capsys, argv + ["--out", str(out)])
    assert err.startswith(f"flexmm: error: --out {out}") and "give a folder" in err
    assert sorted(p.name for p in tmp_path.iterdir()) == ["afile"] and f.read_text() == "x"


def test_replot_without_data_names_the_option_and_the_command(capsys, tmp_path):
    # before: ".../data.h5 does not exist: run `flexmm scene fig2-dispersion` first": that
    # command writes to out/, not to the --out the replot read
    out = tmp_path / "figs"
    err = _fails(capsys, ["scene", "fig2-dispersion", "--replot", "--out", str(out)])
    assert err.startswith("flexmm: error: --replot: ")
    assert f"flexmm scene fig2-dispersion --out {out}" in err and not out.exists()


def test_a_model_soliton_refuses_the_paper_theory_when_it_only_prints(capsys):
    # before: `soliton --model fput ... --theory paper` printed the semi-discrete NLS's
    # soliton (exit 0) as if the paper's continuum NLS had been asked and used; with
    # --simulate or --out the same request was refused
    err = _fails(capsys, ["soliton", "--model", "fput", "--k", "1.0", "--amplitude", "0.05",
                          "--theory", "paper"])
    assert err.startswith("flexmm: error: --theory paper:") and "no --model" in err


@pytest.mark.skipif(not Path("/proc/self").is_dir(), reason="needs Linux's /proc")
def test_an_out_nobody_can_create_is_named_as_the_option(capsys):
    # before: "cannot write to /proc/96/m: No such file or directory (/proc)"
    err = _fails(capsys, ["point", "--model", "fput", "--k", "2", "--amplitude", "0.1",
                          "--out", "/proc/96/m"])
    assert err.startswith("flexmm: error: cannot write to /proc/96/m")
    assert err.endswith("give an --out you can write to")


# ------------------------------------------------------------------ the Python entry points

def test_wavenumber_arguments_are_checked_by_name():
    lossy = energy.load_model("flexmm-lossy")
    # before: numpy's LinAlgError "Array must not contain infs or NaNs" (no argument named)
    with pytest.raises(ModelError, match="kappa must be finite real wavenumbers"):
        nm.damping_rates(lossy, float("nan"))
    # before: the string "1" was cast by numpy and answered omega(1)
    with pytest.raises(ModelError, match="kappa must be finite real wavenumbers"):
        nm.branches(energy.load_model("fput"), "1")
    # before: carrier_damping(flexmm-lossy, 7.0) = 0.003125, where carrier refuses k = 7
    with pytest.raises(ModelError, match=r"k must be in \(0, pi\]"):
        nm.carrier_damping(lossy, 7.0)
    # the lossless answer at a k it takes: FPUT omega = 2 sin(k/2), no damping
    fput = energy.load_model("fput")
    assert nm.branches(fput, [1.0])[0, 0] == pytest.approx(2 * math.sin(0.5), rel=1e-14)
    assert nm.carrier_damping(fput, 1.0) == 0.0


def test_sizes_that_only_exhaust_memory_are_refused_by_name():
    m = energy.load_model("fput", alpha=1, beta=1)
    # before: numpy's MemoryError 'Unable to allocate 116. TiB' (harmonics = 10**6) and
    # 'Allocation failed' (samples = 10**8), naming no argument
    with pytest.raises(ModelError, match=r"harmonics must be at most 256"):
        nm.travelling_wave(m, 1.0, 0.1, harmonics=10**6)
    with pytest.raises(ModelError, match=r"samples must be an integer in \[8, 524288\]"):
        nm.exact_gain(m, 2.5, 0.1, samples=10**8)


@pytest.mark.parametrize("N", [0, -4, 2.5, True])
def test_ring_offsets_takes_a_ring(N):
    # before: N = 0 and -4 gave an empty array and N = 2.5 the offset [2.51]
    with pytest.raises(ModelError, match=r"N must be an integer in \[8, "):
        nm.ring_offsets(N)


def test_ring_offsets_of_eight_sites():
    # by hand: q = 2 pi j / 8, j = 1..4
    np.testing.assert_allclose(nm.ring_offsets(8), [math.pi / 4, math.pi / 2,
                                                    3 * math.pi / 4, math.pi], rtol=1e-15)


def test_compile_model_names_a_path_it_cannot_write(tmp_path):
    import derivation

    lat = energy.builtin("fput")
    # before: IsADirectoryError "'/.../.tmp.x.tmp' -> '/...'" after writing a temporary file
    # beside the folder; None was os.fspath's "expected str, bytes or os.PathLike object"
    with pytest.raises(ValueError, match="is a folder: give the module file"):
        derivation.compile_model(lat, tmp_path)
    with pytest.raises(TypeError, match="path must be the module file to write"):
        derivation.compile_model(lat, None)
    assert list(tmp_path.iterdir()) == []


@pytest.mark.parametrize("argv, names", [
    (["point", "--model", "fput", "--k", "2.5", "--amplitude", "0.1", "--N", "64"],
     ["point.json", "point.png"]),
    (["soliton", "--model", "fput", "--k", "1.0", "--amplitude", "0.05"],
     ["soliton.json", "soliton.png"]),
])
def test_json_with_out_names_the_files_it_wrote(capsys, tmp_path, argv, names):
    # before: with --json the "wrote ..." line is left out (stdout holds one JSON object)
    # and the object did not say what was written where; a map's --json has "files"
    import json

    from cli.app import main

    out = tmp_path / "o"
    assert main(argv + ["--json", "--out", str(out)]) == 0
    printed = json.loads(capsys.readouterr().out)
    assert printed["files"] == [str(out / n) for n in names]
    assert all((out / n).stat().st_size > 0 for n in names)
    assert "files" not in json.loads((out / names[0]).read_text())


@pytest.mark.parametrize("N", ["0", "3", "1048577"])
def test_a_theory_only_model_map_checks_its_ring(capsys, tmp_path, N):
    # before: --N 0, 3 and 1048577 wrote a map whose store said N = 0 (3, 1048577), where
    # point refuses them; the ring's size bounds the same [8, 2**20] everywhere
    out = tmp_path / "m"
    err = _fails(capsys, ["map", "--model", "fput", "--param", "beta=1:2:2", "--k", "1:2:2",
                          "--theory-only", "--N", N, "--workers", "1", "--out", str(out)])
    assert err.startswith("flexmm: error: --N: N must be an integer in [8, 1048576]")
    assert not out.exists()


PAPER_FLAGS = ["--alpha", "2.5", "--K-s", "0.01851", "--K-theta", "0.01551", "--k", "1"]


@pytest.mark.parametrize("argv", [
    ["coefficients", *PAPER_FLAGS], ["point", *PAPER_FLAGS, "--case", "coupled"],
    ["soliton", *PAPER_FLAGS, "--case", "coupled"]])
@pytest.mark.parametrize("amplitude", ["1e-320", "1e-9"])
def test_the_paper_flags_refuse_an_amplitude_float64_cannot_resolve(capsys, argv, amplitude):
    # before (1e-320): coefficients said case II "MI" with peak gain 0, point called the
    # focusing case II (g = 992) "stable" with gain 0, soliton printed width inf after a
    # RuntimeWarning; a --model command refuses such an amplitude (ModelNLS.check_resolved).
    # By hand: |g2| a^2 / 4 against eps omega, with the semi-discrete omega ~ 0.774 and
    # |g2| ~ 18 (case I, the larger) at this point: a >= 2 sqrt(eps omega / |g2|) ~ 6e-9
    err = _fails(capsys, argv + ["--amplitude", amplitude])
    assert err.startswith(f"flexmm: error: --amplitude {float(amplitude):.3g} is below what "
                          "float64 resolves")
    least = float(err.rsplit(">= ", 1)[1])
    assert 2 * math.sqrt(2.2e-16 * 0.77 / 18.4) == pytest.approx(least, rel=0.01)


def test_damping_parameters_names_what_it_takes():
    """A name (not a lattice) was an AttributeError about 'lossy'; a Model is read by its
    lattice (the same answer as Model.lattice)."""
    from numerics.maps import damping_parameters

    with pytest.raises(TypeError, match="energy.Lattice or Model"):
        damping_parameters("x")
    lossy = energy.load_model("flexmm-lossy")
    assert damping_parameters(lossy) == damping_parameters(lossy.lattice) != ()


def test_four_wave_caps_its_samples_as_exact_gain():
    """samples=10**8 ran past 60 s (exact_gain refuses it by the largest ring)."""
    from numerics.models import four_wave

    with pytest.raises(ModelError, match="samples must be an integer in"):
        four_wave(energy.load_model("fput"), 2.5, 0.1, samples=10**8)


def test_model_map_parameters_check_their_ring_without_one():
    """from_model(..., N=3, theory_only=True) was accepted and run (the CLI refuses it)."""
    from numerics.maps import ModelMapParameters

    with pytest.raises(ValueError, match="N"):
        ModelMapParameters.from_model("fput", ("beta", [0.8, 1.6]), ("k", [2.6, 2.8]), 0.1,
                                      params={"alpha": 1.0}, theory_only=True, N=3)
