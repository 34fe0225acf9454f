"""Every registered scene runs in quick mode, writes complete files, redraws from its data,
and its checks come out as recorded in tests/golden/quick_outcomes.json."""

import dataclasses
import json
import os
from pathlib import Path

import h5py
import numpy as np
import pytest

import scenes
from cli.app import main as cli
from numerics.lattice import _cache

GOLDEN = Path(__file__).with_name("golden") / "quick_outcomes.json"
SIM_SCENES = ["fig5-blue-rotation", "fig6-blue-coupled", "fig7-green-rotation",
              "fig8-green-coupled"]


@pytest.mark.parametrize("name", list(scenes.REGISTRY))
def test_scene_runs_quick_and_writes_its_files(name, quick_scenes):
    out, summaries = quick_scenes
    folder = out / name
    for f in ("figure.png", "figure.pdf", "data.h5", "summary.json"):
        path = folder / f
        assert path.stat().st_size > 0, f
        assert oct(path.stat().st_mode & 0o777) == oct(0o666 & ~_umask()), f"{f} permissions"
    assert not list(folder.glob("*.tmp")), "temporary files left behind"
    summary = json.loads((folder / "summary.json").read_text())  # strict JSON: no NaN
    assert summary["scene"] == name
    with h5py.File(folder / "data.h5") as h:
        assert h.attrs["package_version"] and h.attrs["quick"]
    assert summaries[name]["checks"], "every scene checks something"


def _umask():
    mask = os.umask(0)
    os.umask(mask)
    return mask


def test_check_outcomes_match_the_golden_record(quick_scenes, request):
    """Each check's outcome (agrees / paper disagrees (...) / FAIL) is what was recorded;
    ``pytest --update-golden`` rewrites the record after a deliberate change."""
    _, summaries = quick_scenes
    got = {name: {c["check"]: c["outcome"] for c in s["checks"]} for name, s in summaries.items()}
    if request.config.getoption("--update-golden"):
        GOLDEN.write_text(json.dumps(got, indent=2, sort_keys=True) + "\n")
        pytest.skip(f"rewrote {GOLDEN}")
    want = json.loads(GOLDEN.read_text())
    assert got == want, ("check outcomes changed; if deliberate, run "
                         "`.venv/bin/python -m pytest tests/test_scenes.py --update-golden`")
    fails = [c for s in summaries.values() for c in s["checks"] if c["outcome"].startswith("FAIL")]
    assert not fails, fails


@pytest.mark.parametrize("name", SIM_SCENES)
def test_quick_simulation_verdicts_match_the_theory(name, quick_scenes):
    s = json.loads((quick_scenes[0] / name / "summary.json").read_text())
    for key in ("scene", "case", "alpha", "K_s", "K_theta", "k", "N", "eps", "A0", "seed",
                "t_end", "dt", "method"):
        assert key in s, key
    assert s["numerics"]["stable"] == s["theory"]["stable"]
    # the verdict is the growth factor against the stated threshold, both reported
    assert (s["numerics"]["growth_factor"] < s["numerics"]["threshold"]) == s["numerics"]["stable"]


@pytest.mark.parametrize("name", ["fig2-dispersion", "fig6-blue-coupled", "gain-theories"])
def test_replot_redraws_from_data_alone(name, quick_scenes, tmp_path, monkeypatch):
    out = tmp_path / "copy"
    (out / name).mkdir(parents=True)
    (out / name / "data.h5").write_bytes((quick_scenes[0] / name / "data.h5").read_bytes())
    # nothing may compute: the scene's compute and the simulator raise if called
    sc = scenes.get_scene(name)
    monkeypatch.setitem(scenes.REGISTRY, name, dataclasses.replace(sc, compute=_forbidden))
    monkeypatch.setattr(_cache, "simulate", _forbidden)
    assert cli(["scene", name, "--replot", "--out", str(out)]) == 0
    assert (out / name / "figure.png").stat().st_size > 0
    assert (out / name / "figure.pdf").stat().st_size > 0


def _forbidden(*_, **__):
    raise AssertionError("replot computed")


def test_data_h5_round_trip(tmp_path):
    from scenes._runner import read_data, write_data

    data = {"a": np.arange(3.0), "g/b": np.ones((2, 2)), "x": 1.5, "n": 3, "s": "text",
            "flag": True, "lst": [1.0, 2.0], "d": {"k": [1, 2]}, "none": None}
    write_data(tmp_path / "d.h5", data)
    back = read_data(tmp_path / "d.h5")
    assert np.array_equal(back["a"], data["a"]) and np.array_equal(back["g/b"], data["g/b"])
    assert back["x"] == 1.5 and back["n"] == 3 and back["s"] == "text" and back["flag"]
    assert back["lst"] == [1.0, 2.0] and back["d"] == {"k": [1, 2]} and "none" not in back


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


def test_rotation_runs_store_no_U(quick_scenes):
    with h5py.File(quick_scenes[0] / "fig5-blue-rotation" / "data.h5") as h:
        assert "U" not in h and "theta" in h


def test_bad_scene_name_and_parameters(tmp_path, capsys):
    with pytest.raises(ValueError, match="unknown scene"):
        scenes.run_scene("fig99", tmp_path)
    assert cli(["scene", "fig99", "--out", str(tmp_path)]) == 2
    err = capsys.readouterr().err
    assert err.startswith("flexmm: error: unknown scene") and "Traceback" not in err
    assert cli(["scene", "fig2-dispersion", "--seed", "-1", "--out", str(tmp_path)]) == 2
    assert cli(["scene", "fig2-dispersion", "--replot", "--out", str(tmp_path / "none")]) == 2


def test_cli_lists_every_scene_and_prints_the_table(capsys):
    assert cli(["scenes"]) == 0
    listing = capsys.readouterr().out
    for name in scenes.REGISTRY:
        assert name in listing
    assert cli(["table"]) == 0
    table = capsys.readouterr().out
    assert "2088.6" in table and "-2820.5" in table  # g at blue II, green II (README table)


def test_report_separates_findings_from_failures(tmp_path):
    c = scenes.check
    summaries = {"x": {"checks": [
        c("expected agreement", "1", "1", True),
        c("known finding", "1", "2", False, scenes.known("erratum 6")),
        c("unexpected", "1", "2", False),
        c("finding that vanished", "1", "1", True, scenes.known("finding: X"))]}}
    text = scenes.write_report(summaries, tmp_path, quick=True).read_text()
    assert "| agrees |" in text and "| paper disagrees (erratum 6) |" in text
    assert "| **FAIL** |" in text and "**FAIL (expected: paper disagrees (finding: X))**" in text
    assert "## Unexpected results" in text and "unexpected" in text.split("## Unexpected")[1]
    assert "known finding" not in text.split("## Unexpected")[1]


def test_numerics_does_not_import_matplotlib():
    # the simulator layer never draws: figures live in scenes/
    import subprocess
    import sys

    code = ("import sys, numerics, numerics.maps._cells, numerics.theory._gain; "
            "assert 'matplotlib' not in sys.modules, 'matplotlib imported'")
    subprocess.run([sys.executable, "-c", code], check=True)


def test_paper_start_unstable_where_the_travelling_wave_is_not(quick_scenes):
    """The issue's quick-mode point: at delta = -0.0051, k = 2 pi 90/500 (case II) eq. `IC`
    grows and the travelling wave does not, as their theories predict; what grows is a
    theta pair pumped by the free U waves (wavenumbers summing to 2k)."""
    _, summaries = quick_scenes
    starts = {st["start"]: st for st in summaries["gain-theories"]["starts"]
              if st["point"] == "II d=-0.0051 k=1.131"}
    assert starts["paper"]["predicted"] == starts["paper"]["simulated"] == "MI"
    assert starts["travelling"]["predicted"] == starts["travelling"]["simulated"] == "stable"
    assert starts["paper"]["field"] == "theta"
    k = 2 * np.pi * 90 / 500
    w1, w2 = starts["paper"]["wavenumbers"]
    # the pair: k + q and k - q, i.e. wavenumbers summing to 2k (mod 2 pi, folded)
    assert min(abs(w1 + w2 - 2 * k), abs(w2 - w1 - 2 * k), abs(2 * np.pi - w1 - w2 - 2 * k),
               abs(w1 - w2 - 2 * k)) < 1e-3
    assert abs(starts["paper"]["measured_peak"] / starts["paper"]["predicted_peak"] - 1) < 0.05


def test_the_static_scene_list_is_the_registry():
    """`flexmm scene --help` names the scenes without importing them (SCENE_NAMES): the
    list is the registry's, in its order."""
    from scenes import SCENE_NAMES

    assert tuple(scenes.REGISTRY) == SCENE_NAMES
