"""Every registered scene runs in quick mode and writes its files; the cache works."""

import json

import h5py
import pytest

from numerics import _cache, scenes
from numerics.cli import main as cli

SIM_SCENES = ["fig5-blue-rotation", "fig6-blue-coupled", "fig7-green-rotation",
              "fig8-green-coupled"]


@pytest.fixture(scope="module")
def out(tmp_path_factory):
    return tmp_path_factory.mktemp("out")


@pytest.mark.parametrize("name", list(scenes.REGISTRY))
def test_scene_runs_quick_and_writes_its_files(name, out):
    summary = scenes.run_scene(name, out, quick=True)
    folder = out / name
    for f in ("figure.png", "figure.pdf", "data.h5", "summary.json"):
        assert (folder / f).stat().st_size > 0, f
    assert json.loads((folder / "summary.json").read_text())["scene"] == name
    with h5py.File(folder / "data.h5") as h:
        assert h.attrs["package_version"] and h.attrs["quick"]
    assert summary["checks"], "every scene asserts something"


@pytest.mark.parametrize("name", SIM_SCENES)
def test_quick_simulation_verdicts_match_the_theory(name, out):
    s = json.loads((out / name / "summary.json").read_text())
    for key in ("scene", "case", "alpha", "K_s", "K_theta", "k", "N", "eps", "A0", "seed",
                "t_end", "dt", "method"):
        assert key in s, key
    assert set(s["theory"]) >= {"g", "stable"}
    assert set(s["numerics"]) >= {"stable", "sideband_to_carrier_start",
                                  "sideband_to_carrier_end"}
    assert s["numerics"]["stable"] == s["theory"]["stable"]


def test_theory_only_scenes_never_start_the_simulator(tmp_path):
    before = _cache.STATS["simulations"]
    for name, sc in scenes.REGISTRY.items():
        if not sc.simulates:
            scenes.run_scene(name, tmp_path, quick=True)
    assert _cache.STATS["simulations"] == before


def test_cache_hits_do_not_resimulate(tmp_path):
    scenes.run_scene("fig5-blue-rotation", tmp_path, quick=True)
    n = _cache.STATS["simulations"]
    scenes.run_scene("fig5-blue-rotation", tmp_path, quick=True)
    assert _cache.STATS["simulations"] == n
    scenes.run_scene("fig5-blue-rotation", tmp_path, quick=True, force=True)
    assert _cache.STATS["simulations"] == n + 1
    scenes.run_scene("fig5-blue-rotation", tmp_path, quick=True, seed=1)  # new key
    assert _cache.STATS["simulations"] == n + 2


def test_rotation_runs_store_no_U(out):
    with h5py.File(out / "fig5-blue-rotation" / "data.h5") as h:
        assert "U" not in h and "theta" in h


def test_bad_scene_name_and_parameters(tmp_path, capsys):
    with pytest.raises(ValueError, match="unknown scene"):
        scenes.run_scene("fig99", tmp_path)
    assert cli(["scene", "fig99", "--out", str(tmp_path)]) == 2
    err = capsys.readouterr().err
    assert err.startswith("flexmm: error: unknown scene") and "Traceback" not in err
    assert cli(["scene", "fig2-dispersion", "--seed", "-1", "--out", str(tmp_path)]) == 2


def test_cli_lists_every_scene(capsys):
    assert cli(["scenes"]) == 0
    listing = capsys.readouterr().out
    for name in scenes.REGISTRY:
        assert name in listing


def test_report_states_disagreements(tmp_path):
    summaries = {"x": {"checks": [{"check": "c1", "theory": "1", "numerics": "2",
                                   "pass": False}]}}
    text = scenes.write_report(summaries, tmp_path, quick=True).read_text()
    assert "**FAIL**" in text and "disagree" in text
