"""A model's map over the carrier's amplitude (issue 40 item 2: any two axes among the
model's parameters, ``k`` and ``amplitude``): each cell's theories and runs at its own
amplitude, through the CLI and ``numerics.maps.run_map``."""

from __future__ import annotations

import json

import numpy as np
import pytest

from cli.app import main as cli


def _quiet(*_):
    pass


def test_a_theory_map_over_amplitude_and_k(tmp_path):
    """Each cell is the model's theory at its own amplitude: the semi-discrete NLS's peak
    gain is g2 a^2 (its own scaling: cells of one k at amplitudes a and 2a differ by 4
    exactly, to round-off), and the exact lattice theory is ``exact_gain`` at the cell's
    amplitude and k on the ring (the same deterministic computation: 1e-9)."""
    from energy import load_model
    from numerics.maps import ModelMapParameters, run_map
    from numerics.models import exact_gain

    amps, ks = [0.05, 0.1, 0.2], [1.0, 2.0]
    p = ModelMapParameters.from_model("fput", ("amplitude", amps), ("k", ks), None,
                                      params={"beta": 1.0}, theory_only=True, exact=True,
                                      N=32, block=1)
    ds = run_map(p, tmp_path, workers=1, progress=False, log=_quiet)
    assert ds["peak_gain_semidiscrete"].dims == ("amplitude", "k")
    assert ds.attrs["amplitude"] == "" and ds.attrs["axes"] == "amplitude k"
    nls = ds["peak_gain_semidiscrete"].values
    assert np.all(nls > 0)
    np.testing.assert_allclose(nls[1] / nls[0], 4.0, rtol=1e-12)
    np.testing.assert_allclose(nls[2] / nls[1], 4.0, rtol=1e-12)
    model = load_model("fput", beta=1.0)
    for i, a in enumerate(amps):
        for j, k in enumerate(ks):
            want = exact_gain(model, k, a, N=32).peak_gain
            assert ds["peak_gain_exact"].values[i, j] == pytest.approx(want, rel=1e-9, abs=1e-14)


def test_a_simulated_map_over_a_parameter_and_amplitude(tmp_path):
    """Runs at each cell's amplitude: every cell equals ``map_cells`` of that cell alone
    at that amplitude (the same seeded runs: 1e-12)."""
    from energy import load_model
    from numerics.maps import ModelMapParameters, run_map
    from numerics.models import map_cells

    p = ModelMapParameters.from_model("fput", ("beta", [0.5, 1.0]), ("amplitude", [0.1, 0.2]),
                                      None, k=2.4, N=16, t_end=20.0, block=2)
    ds = run_map(p, tmp_path, workers=1, progress=False, log=_quiet)
    assert ds["growth"].dims == ("beta", "amplitude") and ds["done"].values.all()
    model = load_model("fput")
    for i, beta in enumerate([0.5, 1.0]):
        for j, a in enumerate([0.1, 0.2]):
            row = map_cells(model, [({"beta": beta}, 2.4)], a, simulate=True, N=16,
                            t_end=20.0)[0]
            assert ds["growth"].values[i, j] == pytest.approx(row["growth"], rel=1e-12)
            assert ds["peak_gain_exact"].values[i, j] == pytest.approx(
                row["peak_gain_exact"], rel=1e-12, abs=1e-15)
    # the growth differs between the amplitudes (the runs did not all use one)
    assert not np.allclose(ds["growth"].values[:, 0], ds["growth"].values[:, 1])


def test_the_cli_sweeps_the_amplitude(tmp_path, capsys):
    code = cli(["map", "--model", "fput", "--param", "beta=0.5,1.5", "--k", "2.0",
                "--amplitude", "0.05:0.1:2", "--theory-only", "--json", "--out",
                str(tmp_path / "m")])
    out = json.loads(capsys.readouterr().out)
    assert code == 0
    assert out["amplitude"] is None and out["axes"] == {"amplitude": [0.05, 0.1],
                                                        "beta": [0.5, 1.5]}


@pytest.mark.parametrize("argv, match", [
    (["--param", "beta=0.5,1.5", "--k", "1.0,2.0", "--amplitude", "0.05,0.1"],
     "two axes among --k SPEC, --amplitude SPEC"),
    (["--k", "1.0,2.0", "--amplitude", "0.05,-0.1"], "--amplitude must be > 0"),
    (["--k", "1.0,2.0", "--amplitude", "0.05:0.1"], "--amplitude: cannot read SPEC"),
])
def test_bad_amplitude_axes_are_one_line(tmp_path, capsys, argv, match):
    code = cli(["map", "--model", "fput", *argv, "--theory-only", "--out",
                str(tmp_path / "m")])
    err = capsys.readouterr().err
    assert code == 2 and match in err and len(err.strip().splitlines()) == 1, err
    assert not (tmp_path / "m").exists()


def test_the_parameters_refuse_an_ambiguous_amplitude():
    from numerics.maps import ModelMapParameters

    with pytest.raises(ValueError, match="amplitude is a map axis"):
        ModelMapParameters.from_model("fput", ("amplitude", [0.1, 0.2]), ("k", [1.0]), 0.1)
    with pytest.raises(ValueError, match="amplitude must be > 0"):
        ModelMapParameters.from_model("fput", ("amplitude", [0.0, 0.2]), ("k", [1.0]), None)
    with pytest.raises(ValueError, match="give the carrier's amplitude"):
        ModelMapParameters.from_model("fput", ("beta", [1.0]), ("k", [1.0]), None)


def test_a_theory_map_takes_a_row_per_task_and_a_resumed_map_its_stores_block(tmp_path):
    """--block's default: a theory-only map a row per task (up to 64 cells; its cells are
    cheap, the client's writes per block are not), a simulated one 4, and a map resumed in
    a folder whose store has another block keeps the store's (its chunks)."""
    import zarr

    out = tmp_path / "m"
    base = ["map", "--model", "fput", "--param", "beta=0.5,1.0", "--k", "0.5:3.0:6",
            "--amplitude", "0.1", "--theory-only", "--workers", "1", "--out", str(out)]
    assert cli(base) == 0
    assert zarr.open_group(str(out / "map.zarr"), mode="r").attrs["block"] == 6
    other = tmp_path / "b"
    argv = [a if a != str(out) else str(other) for a in base]
    assert cli(argv + ["--block", "2"]) == 0
    assert cli(argv) == 0  # the same map again: resumed (nothing to do), not refused
    assert zarr.open_group(str(other / "map.zarr"), mode="r").attrs["block"] == 2
