"""Edges (issue 94, five rough edges of the CLI): a model map's cell where the model
carries no wave of the amplitude gets no NLS verdict; summary.json's mi_fraction means the
same for every map; argparse's own value errors are one line with a remedy; "1 cell", and
a model's soliton at an amplitude it cannot have is refused; --overwrite starts afresh."""

import json

import numpy as np
import pytest
import xarray as xr

from cli.app import main

FPUT_MAP = ["map", "--model", "fput", "--param", "alpha=1", "--param", "beta=0.8,1.6",
            "--k", "2.6,2.8", "--amplitude", "0.1", "--theory-only", "--workers", "1"]


def _one_line_error(capsys, argv):
    code = main(argv)
    err = capsys.readouterr().err.strip().splitlines()
    assert code == 2 and len(err) == 1, err
    return err[0]


# ------------------------------------------------------------ 1: no wave, no verdict
def test_a_model_map_gives_no_verdict_where_the_model_carries_no_wave(toda, capsys, tmp_path):
    """Toda's exp(-r) overflows past r = 710: at a = 2000 the linear wave's largest strain
    |u_next - u| = 2 a sin(k / 2) is about 990 at k = 0.5, and the map gave the NLS's
    'stable' there, while `point` notes that the wave cannot exist. The cell is
    undetermined by every theory now, counted (no_wave_cells) and said; a = 1 keeps its
    verdicts."""
    import math

    (tmp_path / "toda.toml").write_text(toda)
    argv = ["map", "--model", str(tmp_path / "toda.toml"), "--k", "0.5,1", "--amplitude",
            "1,2000", "--theory-only", "--workers", "1", "--out", str(tmp_path / "m")]
    assert main(argv) == 0
    out = capsys.readouterr().out
    # the strain 2 a sin(k / 2) of the linear wave against ln(max float) = 709.8: at
    # a = 2000 both k overflow, at a = 1 neither (an independent count of the cells)
    overflow = [[2 * a * math.sin(k / 2) > 709.8 for k in (0.5, 1)] for a in (1, 2000)]
    assert overflow == [[False, False], [True, True]]
    with xr.open_zarr(tmp_path / "m" / "map.zarr") as ds:
        no_wave, verdict = ds["no_wave"].values, ds["verdict_semidiscrete"].values
        assert ds["no_wave"].dims == ("amplitude", "k")
    assert (no_wave == 1).tolist() == overflow
    assert (verdict[no_wave == 1] == -1).all() and (verdict[no_wave == 0] >= 0).all()
    summary = json.loads((tmp_path / "m" / "summary.json").read_text())
    assert summary["no_wave_cells"] == 2 and summary["undetermined_cells"]["semidiscrete"] == 2
    line = next(ln for ln in out.splitlines() if ln.startswith("no wave of the amplitude"))
    assert "2 of 4 cells" in line and "largest amplitude the model allows" in line
    assert main([*argv[:-2], "--out", str(tmp_path / "j"), "--json"]) == 0
    assert json.loads(capsys.readouterr().out)["no_wave_cells"] == 2


def test_a_simulated_map_runs_no_cell_without_a_wave(toda, capsys, tmp_path):
    (tmp_path / "toda.toml").write_text(toda)
    assert main(["map", "--model", str(tmp_path / "toda.toml"), "--k", "0.5,1",
                 "--amplitude", "1,2000", "--N", "32", "--t-end", "200", "--workers", "1",
                 "--out", str(tmp_path)]) == 0
    with xr.open_zarr(tmp_path / "map.zarr") as ds:
        gone = ds["no_wave"].values == 1
        assert gone.sum() == 2 and ds["done"].values.all()
        for v in ("semidiscrete", "exact", "fourwave", "simulated"):
            assert (ds[f"verdict_{v}"].values[gone] == -1).all(), v
        assert np.isnan(ds["growth"].values[gone]).all()  # no run made there
    assert json.loads((tmp_path / "summary.json").read_text())["no_wave_cells"] == 2


GPU_MAP = """
import json, sys, tempfile
from numerics.maps import ModelMapParameters, run_map
path = sys.argv[1]
p = ModelMapParameters(model=path, text=open(path).read(), parameters=(("a", 1.0), ("b", 1.0)),
                       rows=("amplitude", [1.0, 2000.0]), cols=("k", [0.5, 1.0]),
                       amplitude=None, N=16, t_end=6.0, block=1)
ds = run_map(p, tempfile.mkdtemp(), progress=False, log=lambda *a: None, device="gpu")
print(json.dumps({n: ds[n].values.tolist() for n in ("no_wave", "verdict_simulated",
                                                     "t_simulated", "done")}))
"""


def test_the_gpu_path_launches_no_cell_without_a_wave(toda, tmp_path):
    """run_map(device="gpu") under numba's CUDA simulator (no GPU needed): the cells
    without a wave are not launched, as on the CPU (their runs undetermined, no growth)."""
    import os
    import subprocess
    import sys

    (tmp_path / "toda.toml").write_text(toda)
    env = dict(os.environ, NUMBA_ENABLE_CUDASIM="1", OMP_NUM_THREADS="1")
    res = subprocess.run([sys.executable, "-c", GPU_MAP, str(tmp_path / "toda.toml")],
                         env=env, capture_output=True, text=True, timeout=600)
    assert res.returncode == 0, res.stderr[-3000:]
    got = json.loads(res.stdout.splitlines()[-1])
    assert got["no_wave"] == [[0, 0], [1, 1]] and got["done"] == [[True, True]] * 2
    assert got["verdict_simulated"][1] == [-1, -1]
    # a run's length is NaN only where none was made (T = 6 is too short for a verdict at
    # a = 1, whose runs are made and undetermined too, on the CPU as here)
    ran, none = got["t_simulated"]
    assert ran == [6.0, 6.0] and all(t != t for t in none)


def test_a_model_map_whose_waves_all_exist_says_nothing_of_them(capsys, tmp_path):
    assert main([*FPUT_MAP, "--out", str(tmp_path)]) == 0
    assert "no wave" not in capsys.readouterr().out
    with xr.open_zarr(tmp_path / "map.zarr") as ds:
        assert (ds["no_wave"].values == 0).all()
    assert json.loads((tmp_path / "summary.json").read_text())["no_wave_cells"] == 0


# ------------------------------------------------------------ 2: one mi_fraction
def test_a_model_maps_mi_fraction_is_the_share_among_decided_cells(capsys, tmp_path):
    """Klein-Gordon's NLS has g1 = 0 at cos k = (3 - sqrt 5) / 2: that column of the map
    is undetermined. The model map counted it as not MI (50%), the paper map leaves such
    cells out; one definition now, the paper map's, with the count beside it."""
    import math

    k0 = math.acos((3 - math.sqrt(5)) / 2)
    code = main(["map", "--model", "klein-gordon", "--param", "beta=1,2", "--k",
                 f"2,{k0!r}", "--amplitude", "0.1", "--theory-only", "--workers", "1",
                 "--out", str(tmp_path), "--json"])
    out = json.loads(capsys.readouterr().out)
    summary = json.loads((tmp_path / "summary.json").read_text())
    with xr.open_zarr(tmp_path / "map.zarr") as ds:
        v = ds["verdict_semidiscrete"].values
    decided = v >= 0
    assert code == 0 and decided.sum() == 2  # the k0 column undetermined
    # the share the paper map's definition gives, from the store's own verdicts
    want = float((v[decided] == 1).mean())
    assert summary["mi_fraction"]["semidiscrete"] == want
    assert out["mi_fraction"]["semidiscrete"] == want
    assert out["mi_share"]["verdict_semidiscrete"] == want
    assert summary["undetermined_cells"]["semidiscrete"] == 2


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


# ------------------------------------------------------------ 4: wording, the soliton
def test_one_cell_is_one_cell(capsys, tmp_path):
    assert main(["map", "--alpha", "2.5", "--K-s", "0.01851", "--delta", "0.01", "--k", "1",
                 "--case", "rotation", "--theory-only", "--N", "32", "--workers", "1",
                 "--out", str(tmp_path)]) == 0
    out = capsys.readouterr().out
    assert "1 cells" not in out, out
    assert "map (theory only): 1 cell, " in out and "predicted 1 cell in " in out


def test_a_models_soliton_narrower_than_a_site_is_refused(capsys, tmp_path):
    # fput at a = 1e3: the NLS's width 0.0005 sites and a frequency 1e6 times omega were
    # printed as a dark soliton, with a note (and written, with --out); the width goes as
    # 1 / a, so the remedy's amplitude for 8 sites is a * width / 8
    argv = ["soliton", "--model", "fput", "--param", "alpha=1", "--param", "beta=1",
            "--k", "1", "--amplitude", "1e3"]
    for extra in ([], ["--out", str(tmp_path / "s")]):
        err = _one_line_error(capsys, argv + extra)
        assert "narrower than one site" in err and "lower --amplitude" in err
    assert not (tmp_path / "s").exists()
    assert main(["soliton", "--model", "fput", "--param", "alpha=1", "--param", "beta=1",
                 "--k", "1", "--amplitude", "0.0664", "--json"]) == 0
    width = json.loads(capsys.readouterr().out)["width"]
    assert width == pytest.approx(8, rel=2e-3)  # the remedy's 3 digits of the amplitude


def test_a_soliton_of_a_wave_the_model_cannot_carry_is_refused(toda, capsys, tmp_path):
    # Toda at a = 1000, k = 1: the linear wave's strain reaches 954, beyond 710 where
    # exp(-r) overflows; a soliton of it was printed (width 0.001 sites)
    (tmp_path / "toda.toml").write_text(toda)
    err = _one_line_error(capsys, ["soliton", "--model", str(tmp_path / "toda.toml"),
                                   "--k", "1", "--amplitude", "1e3"])
    assert "energy is not real" in err and "lower --amplitude" in err
    # within its reach, the soliton stands
    assert main(["soliton", "--model", str(tmp_path / "toda.toml"), "--k", "1",
                 "--amplitude", "0.05"]) == 0
    assert "soliton, amplitude 0.05" in capsys.readouterr().out


def test_the_paper_chains_soliton_narrower_than_a_site_is_refused_too(capsys):
    # its amplitude is bounded by 1 rad (1e3 refused), but 0.9 printed a table of a
    # soliton 0.06 sites wide, with a warning
    paper = ["soliton", "--alpha", "2.5", "--K-s", "0.01851", "--K-theta", "0.02151",
             "--k", "0.92991", "--case", "rotation", "--amplitude"]
    err = _one_line_error(capsys, [*paper, "0.9"])
    assert "narrower than one site" in err and "lower --amplitude" in err
    assert main([*paper, "0.002"]) == 0  # the epilog's example stands


def test_a_soliton_of_a_few_sites_keeps_its_note(capsys):
    assert main(["soliton", "--model", "fput", "--param", "alpha=1", "--param", "beta=1",
                 "--k", "1", "--amplitude", "0.3"]) == 0
    assert "too narrow for the envelope theory" in capsys.readouterr().out


# ------------------------------------------------------------ 5: --overwrite starts afresh
def test_overwrite_of_the_same_map_discards_its_cells(capsys, tmp_path):
    out = ["--out", str(tmp_path)]
    assert main([*FPUT_MAP, *out]) == 0
    # a mark that only a recomputation removes: a cell's verdict edited with its checksum
    # left as it was would be recomputed on resume too, so the store's attrs carry it
    import zarr

    zarr.open_group(str(tmp_path / "map.zarr"), mode="r+").attrs["left_by"] = "the old run"
    capsys.readouterr()
    assert main([*FPUT_MAP, *out]) == 0  # without --overwrite: resumed, nothing computed
    said = capsys.readouterr().out
    assert "resuming" in said and "predicted" not in said
    assert main([*FPUT_MAP, *out, "--overwrite"]) == 0
    said = capsys.readouterr().out
    assert "discarded (4 finished cells of its map)" in said and "resuming" not in said
    assert "predicted 4 cells in " in said and "estimate: about" in said
    group = zarr.open_group(str(tmp_path / "map.zarr"), mode="r")
    assert "left_by" not in group.attrs and np.asarray(group["done_predicted"]).all()


@pytest.mark.parametrize("make", ["files", "link", "nested"])
def test_overwrite_never_removes_a_folder_that_is_no_map_store(make, capsys, tmp_path):
    store = tmp_path / "out" / "map.zarr"
    mine = tmp_path / "mine"
    mine.mkdir()
    (mine / "notes.txt").write_text("keep me")
    if make == "files":  # a folder of the user's own, named map.zarr
        store.parent.mkdir()
        mine.rename(store)
        mine = store
    elif make == "link":  # a link to it
        store.parent.mkdir()
        store.symlink_to(mine, target_is_directory=True)
    else:  # a Zarr group's marker, and a folder no map variable holds
        store.mkdir(parents=True)
        (store / ".zgroup").write_text('{"zarr_format": 2}')
        (store / "done").mkdir()
        (store / "done" / "sub").mkdir()
        (store / "done" / "sub" / "data").write_text("keep me")
    err = _one_line_error(capsys, [*FPUT_MAP, "--out", str(tmp_path / "out"), "--overwrite"])
    assert "is not a map store" in err and "--overwrite removes only a map store" in err
    if make == "nested":
        assert (store / "done" / "sub" / "data").read_text() == "keep me"
    else:
        assert (mine / "notes.txt").read_text() == "keep me"
        assert store.exists() or store.is_symlink()


def test_point_and_coefficients_give_no_nls_verdict_where_the_model_carries_no_wave(
        toda, capsys, tmp_path):
    """The map's cell and the point's table say the same where the wave cannot exist:
    Toda at a = 2000, k = 1 (strain 2 a sin(1/2) ~ 1900 > ln(max float) ~ 710) read
    'stable' in the point's and the coefficients' NLS row. g1 and g2 stay (they do not
    depend on a); a = 1 keeps its verdict."""
    import math

    from energy import load_model
    from numerics.models import model_coefficients

    (tmp_path / "toda.toml").write_text(toda)
    model = load_model(str(tmp_path / "toda.toml"))
    assert 2 * 2000 * math.sin(0.5) > 709.8 > 2 * 1 * math.sin(0.5)
    far = model_coefficients(model, 1.0, 2000.0)
    assert far["verdict"] == "undefined" and "energy is not real" in far["reason"]
    assert far["peak_gain"] is None and far["band_edge"] is None
    assert far["g1"] is not None and math.isfinite(far["g2"])
    near = model_coefficients(model, 1.0, 1.0)
    assert near["verdict"] in ("MI", "stable") and not near["reason"]
    assert main(["point", "--model", str(tmp_path / "toda.toml"), "--k", "1", "--amplitude",
                 "2000", "--N", "64"]) == 0
    out = capsys.readouterr().out
    row = next(line for line in out.splitlines() if line.startswith("semi-discrete NLS"))
    assert row.split()[2] == "undefined", row
    assert "exact lattice undefined: as the semi-discrete NLS" in out
