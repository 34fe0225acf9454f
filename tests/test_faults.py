"""The fault suite: every bad input of bench/faults.py has its exact outcome, and the faults
that need signals, files or the CLI (resume after Ctrl-C, checkpoints, tampered cache
entries, partial files, file-system errors) end as they must."""

import json
import math
import os
import signal
import sys
import threading
from pathlib import Path

import h5py
import numpy as np
import pytest

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "bench"))

import faults

import scenes
from cli.app import main as cli
from common import paper
from numerics import BlowUpError, SimulationInterrupted, resume, simulate
from numerics.lattice import _cache

# these tests send themselves SIGINT: the handler they rely on, also in a background job
pytestmark = pytest.mark.usefixtures("sigint_raises")


@pytest.mark.parametrize("name, action, expected", faults.CATALOGUE,
                         ids=[c[0] for c in faults.CATALOGUE])
def test_catalogue(name, action, expected):
    outcome, detail = faults.run_one(action, expected)
    assert outcome != "problem", detail


def _sigint_after(seconds):
    timer = threading.Timer(seconds, lambda: os.kill(os.getpid(), signal.SIGINT))
    timer.start()
    return timer


# --- 1. resume after a real Ctrl-C --------------------------------------------------------

def test_real_sigint_stops_on_a_consistent_state_and_resume_is_exact(blue):
    # the case, shorter: N = 2000, energy records every 50; Ctrl-C mid-run
    kw = dict(material=blue, case="coupled", N=2000, k=2 * np.pi * 260 / 2000, t_end=3000.0,
              dt=0.05, store="energy", save_every=50.0)
    full = simulate(**kw)
    _sigint_after(0.4)
    with pytest.raises(SimulationInterrupted) as info:
        simulate(**kw)
    exc = info.value
    assert 0 < exc.time < kw["t_end"] and exc.time + exc.remaining == pytest.approx(3000.0)
    assert exc.run.t[-1] <= exc.time  # the message's T is the state's time
    whole = resume(exc, **kw)
    assert whole.completed and len(whole.t) == len(full.t)
    np.testing.assert_allclose(whole.t, full.t, rtol=0, atol=1e-9)
    np.testing.assert_allclose(whole.energy, full.energy, rtol=1e-14)
    np.testing.assert_allclose(whole.final_state.theta, full.final_state.theta, rtol=0,
                               atol=1e-14)


def test_interrupt_between_records_keeps_the_record_grid(blue, monkeypatch):
    # interrupt inside a record interval (sub-chunks of 1 step): resume fills the grid
    from numerics.lattice import _runcontrol, _simulate

    monkeypatch.setattr(_runcontrol, "_WORK_PER_CALL", 1.0)  # one step per compiled call
    kw = dict(material=blue, case="rotation", N=64, k=2 * np.pi * 8 / 64, t_end=20.0,
              dt=0.05, save_every=1.0)
    full = simulate(**kw)
    calls = {"n": 0}
    original = _simulate.Stepper.advance

    def counting(self, n):
        calls["n"] += 1
        if calls["n"] == 137:  # 6.85 T: between the records at 6 and 7
            os.kill(os.getpid(), signal.SIGINT)
        return original(self, n)

    monkeypatch.setattr(_simulate.Stepper, "advance", counting)
    with pytest.raises(SimulationInterrupted) as info:
        simulate(**kw)
    monkeypatch.setattr(_simulate.Stepper, "advance", original)
    exc = info.value
    assert exc.run.t[-1] == pytest.approx(6.0) and exc.time == pytest.approx(6.85)
    whole = resume(exc, **kw)
    np.testing.assert_allclose(whole.t, full.t, atol=1e-12)
    np.testing.assert_allclose(whole.theta, full.theta, rtol=0, atol=1e-14)


# --- 2. the blow-up advice works -------------------------------------------------------------

def test_blow_up_advice_is_a_step_that_works(blue):
    # the case: blue II, N = 200, t_end = 2000, dt = 0.707 blew up and advised
    # dt <= 0.707; the energy check fired, theta was finite
    kw = dict(material=blue, case="coupled", N=200, k=paper.k("blue"), t_end=2000.0,
              store="energy")
    with pytest.raises(BlowUpError, match="energy drifted") as info:
        simulate(dt=0.707, **kw)
    msg = str(info.value)
    assert "below the linear stability limit" in msg
    advised = float(msg.split("Try dt <= ")[1])
    assert advised < 0.707
    run = simulate(dt=advised, energy_tolerance=1.0, **kw)
    assert run.completed and run.energy_error < 0.5


def test_blow_up_above_the_linear_limit_says_so(blue):
    with pytest.raises(BlowUpError, match="above the linear stability limit") as info:
        simulate(blue, "coupled", 64, 2 * np.pi * 8 / 64, t_end=2000.0, dt=1.7, save_every=10.0)
    assert info.value.run is not None and not info.value.run.completed
    advised = float(str(info.value).split("Try dt <= ")[1])
    run = simulate(blue, "coupled", 64, 2 * np.pi * 8 / 64, t_end=2000.0, dt=advised,
                   save_every=10.0, energy_tolerance=1.0)
    assert run.completed


# --- 3. files complete or absent -------------------------------------------------------------

def test_a_failure_while_saving_leaves_the_previous_scene_folder_whole(tmp_path, monkeypatch):
    scenes.run_scene("fig2-dispersion", tmp_path, quick=True, seed=0)
    before = {p.name: p.read_bytes() for p in (tmp_path / "fig2-dispersion").iterdir()}
    from scenes import _runner

    def broken(*_a, **_k):
        raise OSError(28, "No space left on device")

    monkeypatch.setattr(_runner, "_save_figure", broken)
    with pytest.raises(OSError):
        scenes.run_scene("fig2-dispersion", tmp_path, quick=True, seed=5)
    after = {p.name: p.read_bytes() for p in (tmp_path / "fig2-dispersion").iterdir()}
    assert after == before  # all four files of the seed-0 run, none of seed 5
    assert not [p for p in tmp_path.iterdir() if p.name.startswith(".fig2")]


# --- 4. file-system errors in the CLI: one line, exit != 0, nothing written -----------------

def _file_as_out(d):
    (d / "out").write_text("x")
    return d / "out"


def _file_as_cache(d):
    (d / "out").mkdir()
    (d / "out" / ".cache").write_text("x")
    return d / "out"


def _file_as_scene_folder(d):
    (d / "out").mkdir()
    (d / "out" / "fig2-dispersion").write_text("x")
    return d / "out"


@pytest.mark.parametrize("setup, match", [
    (_file_as_out, "is a file"), (_file_as_cache, r"\.cache is a file"),
    (_file_as_scene_folder, "fig2-dispersion is a file"),
    (lambda d: Path("/proc/flexmm-test"), "cannot write"),
])
def test_cli_file_system_errors(setup, match, tmp_path, capsys):
    out = setup(tmp_path)
    assert cli(["scene", "fig2-dispersion", "--quick", "--out", str(out)]) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1 and "Traceback" not in err
    assert err.startswith("flexmm: error:") and __import__("re").search(match, err)


@pytest.mark.parametrize("command", [
    ["point", "--case", "coupled", "--alpha", "2.5", "--K-s", "0.01851", "--K-theta", "0.02",
     "--k", "0.9", "--simulate"],
    ["soliton", "--alpha", "2.5", "--K-s", "0.01851", "--K-theta", "0.02", "--k", "0.9",
     "--simulate"]])
def test_point_and_soliton_check_their_output_before_simulating(command, tmp_path, capsys,
                                                                monkeypatch):
    """--out under a file fails at once (no simulation runs first), in one line."""
    from cli import point as point_command
    from cli import soliton as soliton_command

    def never(*_a, **_k):
        raise AssertionError("simulated before checking --out")

    monkeypatch.setattr(point_command, "measure_point", never)
    monkeypatch.setattr(soliton_command, "simulate_soliton", never)
    out = _file_as_out(tmp_path) / "x"
    assert cli(command + ["--out", str(out)]) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1 and "Traceback" not in err
    assert err.startswith("flexmm: error:") and str(out) in err


@pytest.mark.skipif(not Path("/proc/self").is_dir(), reason="needs Linux's /proc")
@pytest.mark.parametrize("out", ["/proc/flexmm-test", "/proc/flexmm-test/deeper"])
def test_map_refuses_an_unwritable_out_before_announcing_its_work(out, capsys, monkeypatch):
    """An --out that cannot be created (here under /proc, which takes no new folders, also
    for root, who ignores permission bits) is one line and exit 2, before the map says
    what it will compute and before any theory runs."""
    import cli.map as map_command

    def never(*_a, **_k):
        raise AssertionError("the map started before checking --out")

    monkeypatch.setattr(map_command, "run_map", never, raising=False)
    code = cli(["map", "--case", "coupled", "--alpha", "2.5", "--K-s", "0.01851",
                "--delta=-0.003,0.003", "--k", "0.5:1.2:4", "--out", out])
    captured = capsys.readouterr()
    assert code == 2
    err = captured.err.strip()
    assert len(err.splitlines()) == 1 and "Traceback" not in err
    assert err.startswith("flexmm: error: cannot write to") and out in err
    assert "map:" not in captured.out + captured.err


# --- 5. Ctrl-C in the CLI: one line, 130, checkpoint, the rerun continues -----------------

def test_cli_ctrl_c_is_one_line_and_exit_130(tmp_path, capsys, monkeypatch):
    def interrupted(*_a, **_k):
        raise KeyboardInterrupt

    monkeypatch.setattr(scenes, "run_scene", interrupted)
    assert cli(["scene", "fig6-blue-coupled", "--out", str(tmp_path)]) == 130
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1 and "run the same command again" in err


def test_interrupted_cached_run_is_checkpointed_and_resumed(tmp_path, blue):
    kw = dict(material=blue, case="coupled", N=2000, k=2 * np.pi * 260 / 2000, t_end=3000.0,
              dt=0.05, store="energy", save_every=50.0, progress=False)
    _sigint_after(0.4)
    before = dict(_cache.STATS)
    with pytest.raises(SimulationInterrupted):
        _cache.cached_simulate(tmp_path, **kw)
    assert _cache.STATS["checkpoints"] == before["checkpoints"] + 1
    assert len(list(tmp_path.glob("*.partial.h5"))) == 1
    run = _cache.cached_simulate(tmp_path, **kw)  # resumes from the checkpoint
    assert run.completed and not list(tmp_path.glob("*.partial.h5"))
    full = simulate(**kw)
    np.testing.assert_allclose(run.energy, full.energy, rtol=1e-14)
    assert run.t.shape == full.t.shape


# --- 6. strict JSON ------------------------------------------------------------------------

def test_summary_json_has_no_bare_nan(tmp_path):
    from common.output import strict_json as _strict

    text = json.dumps(_strict({"a": math.nan, "b": [1.0, math.inf], "c": np.float64("nan")}),
                      allow_nan=False)
    assert json.loads(text) == {"a": None, "b": [1.0, None], "c": None}


# --- 7. seeds are checked before any work ------------------------------------------------

def test_cli_rejects_a_huge_seed_before_simulating(tmp_path, capsys):
    before = _cache.STATS["simulations"]
    assert cli(["scene", "fig5-blue-rotation", "--seed", str(2**64), "--out",
                str(tmp_path)]) == 2
    assert "seed" in capsys.readouterr().err and _cache.STATS["simulations"] == before
    assert not (tmp_path / "fig5-blue-rotation").exists()


# --- 10. tampered cache entries are recomputed ---------------------------------------------

@pytest.mark.parametrize("tamper", ["nan", "cut"])
def test_tampered_cache_entries_are_recomputed(tamper, tmp_path, blue):
    kw = dict(material=blue, case="rotation", N=64, k=2 * np.pi * 8 / 64, t_end=20.0,
              dt=0.05, save_every=1.0, progress=False)
    good = _cache.cached_simulate(tmp_path, **kw)
    (entry,) = tmp_path.glob("*.h5")
    with h5py.File(entry, "r+") as f:
        theta = f["theta"][()]
        del f["theta"]
        if tamper == "nan":
            theta[3, 5] = np.nan
            f.create_dataset("theta", data=theta)
        else:
            f.create_dataset("theta", data=theta[:10])
    n = _cache.STATS["simulations"]
    again = _cache.cached_simulate(tmp_path, **kw)
    assert _cache.STATS["simulations"] == n + 1  # not used as is
    np.testing.assert_array_equal(again.theta, good.theta)


# --- 14. --out '' and the cost of a cached rerun ------------------------------------------

def test_empty_out_is_the_current_folder(tmp_path, capsys, monkeypatch):
    monkeypatch.chdir(tmp_path)
    assert cli(["scene", "fig2-dispersion", "--quick", "--out", ""]) == 0
    assert "wrote fig2-dispersion/" in capsys.readouterr().out
    assert (tmp_path / "fig2-dispersion" / "figure.png").exists()


def test_cached_rerun_of_gain_theories_redoes_no_theory(tmp_path, monkeypatch):
    from scenes import gain_theories

    calls = {"n": 0}
    original = gain_theories.theory_gain

    def counted(*a, **k):
        calls["n"] += 1
        return original(*a, **k)

    monkeypatch.setattr(gain_theories, "theory_gain", counted)
    monkeypatch.setattr(gain_theories, "POINTS", gain_theories.POINTS[-1:])  # one point
    scenes.run_scene("gain-theories", tmp_path, quick=True)
    first = calls["n"]
    scenes.run_scene("gain-theories", tmp_path, quick=True)
    assert first > 0 and calls["n"] == first


def test_a_wavenumber_below_the_longest_wave_names_the_limit():
    from numerics import snap_wavenumber

    with pytest.raises(ValueError, match=r"2 pi / N = 0\.01257: choose k >= 0\.01257, or "
                                         r"more sites \(N >= 1257\)"):
        snap_wavenumber(0.005, 500)


def test_a_full_disk_while_a_map_writes_names_the_store_and_keeps_its_cells(tmp_path,
                                                                            monkeypatch, capsys):
    # the disk fills after the first block: one line naming the store, the block kept
    from numerics.maps import _store

    written = []
    real = _store._CellWriter.write

    def write(self, region, cells, arrays=None):
        if written:
            raise OSError(28, "No space left on device")
        written.append(cells)
        return real(self, region, cells, arrays)

    monkeypatch.setattr(_store._CellWriter, "write", write)
    args = ["map", "--case", "rotation", "--alpha", "3.1", "--K-s", "0.024", "--delta",
            "0.0035", "--k", "0.9,1.3", "--N", "64", "--t-end", "300", "--block", "1",
            "--workers", "1", "--out", str(tmp_path / "m")]
    assert cli(args) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and f"{tmp_path / 'm' / 'map.zarr'}: No space left on device" in err[0]
    assert "cells finished before are kept" in err[0]
    monkeypatch.undo()
    assert cli(args) == 0
    assert "1 of 2 cells already done" in capsys.readouterr().out
