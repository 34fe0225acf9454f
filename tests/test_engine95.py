"""The one map engine under stress (round 95): progress where no bar is drawn, the
estimate compared with the command's wall time, the split modules' single definitions.

Tests that start clusters or send signals here run serially (the Makefile's SERIAL_TESTS)."""

from __future__ import annotations

import os
import re
import signal
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import pytest

from cli.app import main as cli
from numerics.maps import _progress, _store


class _Clock:
    def __init__(self):
        self.now = 100.0

    def __call__(self):
        return self.now


def _lines(total=100, estimate=None):
    clock, said = _Clock(), []
    p = _progress.ProgressLines(total, "simulated", estimate, said.append, clock)
    return p, clock, said


def test_the_first_progress_line_comes_after_ten_seconds_then_every_thirty_at_most():
    p, clock, said = _lines()
    for t in np.arange(0.0, 9.99, 0.05):  # the polling loop's ticks
        clock.now = 100.0 + t
        p.tick()
    assert said == []
    clock.now = 110.0
    p.tick()
    assert len(said) == 1 and said[0].startswith("map: 0 of 100 cells simulated (0%) in 10 s")
    # no estimate and no cell back: no time left is claimed
    assert "left" not in said[0]
    times = []
    for t in np.arange(10.0, 200.0, 0.05):  # nothing finishes: still a line every 30 s
        clock.now = 100.0 + t
        n = len(said)
        p.tick()
        if len(said) > n:
            times.append(t)
    assert np.allclose(np.diff([10.0, *times]), 30.0, atol=0.06), times


def test_time_left_is_the_throughput_since_the_first_block_not_the_start_up():
    # workers start for 20 s, the first block of 4 cells is back at 20 s, then 4 cells
    # every 2 s: 96 cells left after the first block take 48 s, so at 30 s (20 cells
    # back) the 80 left take 40 s (by hand: 80 cells / (16 cells / 10 s))
    p, clock, said = _lines(estimate=60.0)
    clock.now = 105.0
    p.tick()
    assert said == []
    clock.now = 110.0
    p.tick()  # no cell back: the estimate less the time gone, said to be the estimate
    assert said[-1].endswith("about 50 s left (the estimate; no cell back yet)")
    clock.now = 120.0
    p.update(4)  # the first block: 20 s each for 4 cells, start-up included: 96 * 5 s
    assert p.left(120.0) == pytest.approx(96 * 20.0 / 4)
    for n in range(4):
        clock.now = 122.0 + 2 * n
        p.update(4)
    clock.now = 130.0
    assert p.left(clock.now) == pytest.approx(80 * 10.0 / 16)
    p.tick()  # 20 s after the first line: not due yet
    assert len(said) == 1
    clock.now = 140.0
    p.tick()
    assert p.left(140.0) == pytest.approx(80 * 20.0 / 16)  # 100 s: "2 min" in words
    assert said[-1] == ("map: 20 of 100 cells simulated (20%) in 40 s; about 2 min left at "
                        "the pace so far")


def test_a_finished_map_prints_no_progress_line():
    p, clock, said = _lines(total=4)
    clock.now = 200.0
    p.update(4)
    p.tick()
    assert said == []


def test_progress_lines_only_where_no_bar_is_drawn(monkeypatch):
    import io
    import sys

    class Tty(io.StringIO):
        def isatty(self):
            return True

    monkeypatch.setattr(sys, "stderr", Tty())
    assert _progress.progress_lines(None, 4, "simulated") is None  # tqdm draws its bar
    monkeypatch.setattr(sys, "stderr", io.StringIO())
    assert isinstance(_progress.progress_lines(None, 4, "simulated"), _progress.ProgressLines)
    for given in (False, True, print):  # off, a forced bar, the caller's callable
        assert _progress.progress_lines(given, 4, "simulated") is None


def _small_simulated_map(**kw):
    from numerics.maps import ModelMapParameters

    return ModelMapParameters.from_model("fput", ("beta", [0.8, 1.6]), ("k", [2.4, 2.8]), 0.1,
                                         params={"alpha": 1.0}, N=32, t_end=200.0, **kw)


def test_a_map_stopped_after_its_last_cell_ends_as_an_undisturbed_one(tmp_path, monkeypatch):
    """Ctrl-C between the last cell written and the store's closing attributes (seen with
    SIGINT right after "simulated 100 cells in ..."): the rerun had no cell to simulate and
    the store lacked device and device_name for good; now it ends equal to an
    undisturbed run's, attributes included. Fails on the old tree (device missing)."""
    import xarray as xr

    from numerics.maps import _devices, run_map

    params = _small_simulated_map()
    quiet = {"workers": 1, "progress": False, "log": lambda *_: None}
    whole = run_map(params, tmp_path / "whole", **quiet)
    real = _devices.device_attrs

    def stopped(*a, **k):
        raise KeyboardInterrupt

    monkeypatch.setattr(_devices, "device_attrs", stopped)
    with pytest.raises(KeyboardInterrupt):
        run_map(params, tmp_path / "cut", **quiet)
    monkeypatch.setattr(_devices, "device_attrs", real)
    said = []
    again = run_map(params, tmp_path / "cut", workers=1, progress=False, log=said.append)
    assert any("4 of 4 cells already done" in s for s in said), said  # nothing recomputed
    assert not any(re.match(r"simulated \d+ cell", s) for s in said), said
    for ds in (again, xr.open_zarr(tmp_path / "cut" / "map.zarr", chunks=None)):
        assert ds.attrs == whole.attrs
        for name in whole.variables:
            np.testing.assert_array_equal(ds[name].values, whole[name].values)
            assert ds[name].attrs == whole[name].attrs, name


def test_a_model_maps_estimate_counts_the_time_it_took_to_measure(tmp_path, capsys,
                                                                  monkeypatch):
    """The cells' line compares the command's wall time with the estimate: the seconds
    spent measuring a cell belong to the estimate too (a cold kernel cache: 94 s of
    measuring, then "the command so far 220.1 s, estimated 109 s", the 109 s counting
    from after the measurement); and a slow measurement is said while it runs. Both fail
    on the old tree."""
    import cli.model_map as model_map
    import numerics.maps as maps

    probe, estimate, seen = maps.probe_model_cell, maps.estimate_model_map, []

    def slow_probe(params):
        time.sleep(1.5)  # as a first compile would, in small
        return probe(params)

    def kept(*a, **k):
        seen.append(estimate(*a, **k))
        return seen[-1]

    monkeypatch.setattr(maps, "probe_model_cell", slow_probe)
    monkeypatch.setattr(maps, "estimate_model_map", kept)
    monkeypatch.setattr(model_map, "PROBE_NOTE_S", 0.3)
    assert cli(["map", "--model", "fput", "--param", "alpha=1", "--param", "beta=0.8,1.6",
                "--k", "2.6,2.8", "--amplitude", "0.1", "--theory-only", "--workers", "1",
                "--out", str(tmp_path / "m")]) == 0
    out = capsys.readouterr().out.splitlines()
    note = [i for i, s in enumerate(out) if s.startswith("estimate: measuring one cell here")]
    about = [i for i, s in enumerate(out) if s.startswith("estimate: about ")]
    assert len(note) == 1 and len(about) == 1 and note[0] < about[0], out
    said = float(re.search(r"; the command so far [\d.]+ s, estimated (\d+) s",
                           "\n".join(out)).group(1))
    # the 1.5 s slept before the estimate, and the estimate after it (the line rounds to
    # a second: 0.5 s either way)
    assert said >= seen[0].seconds + 1.5 - 0.5, (said, seen[0].seconds)


def test_a_map_whose_stderr_is_no_terminal_prints_progress_lines(tmp_path, capsys,
                                                                  monkeypatch):
    """stderr a log file or a pipe: tqdm draws no bar, and a 100-cell map said nothing
    between its estimate and its end (minutes); now plain lines (here due at once). Fails
    on the old tree (no line)."""
    monkeypatch.setattr(_progress, "FIRST_LINE_S", 0.0)
    assert cli(["map", "--model", "fput", "--param", "alpha=1", "--param", "beta=0.8,1.6",
                "--k", "2.6,2.8", "--amplitude", "0.1", "--theory-only", "--workers", "1",
                "--out", str(tmp_path / "m")]) == 0
    err = capsys.readouterr().err.splitlines()
    lines = [s for s in err if re.match(r"map: \d of 4 cells predicted \(\d+%\) in \d+ s", s)]
    assert lines, err


def test_a_tampered_cell_is_estimated_and_computed_again_not_called_none_needed(
        tmp_path, capsys):
    """A finished store with one cell's value changed behind its checksum (a valid chunk,
    other numbers): the engine recomputes that cell, and the estimate before it now says
    so; it said "estimate: none needed: ... holds every cell (its checksums are verified)"
    and 0 s, then ran the cell (13.7 s). Fails on the old tree."""
    import zarr

    cmd = ["map", "--model", "fput", "--param", "alpha=1", "--param", "beta=0.8,1.6",
           "--k", "2.4,2.8", "--amplitude", "0.1", "--N", "32", "--t-end", "200",
           "--workers", "1", "--out", str(tmp_path / "m")]
    assert cli(cmd) == 0
    capsys.readouterr()
    group = zarr.open_group(str(tmp_path / "m" / "map.zarr"), mode="r+",
                            use_consolidated=False)
    group["growth"][1, 0] = group["growth"][1, 0] * 2 + 1  # decodes fine, digest differs
    assert cli(cmd) == 0
    out = capsys.readouterr().out
    assert "estimate: none needed" not in out, out
    assert "estimate: about " in out and "for 1 of its 4 cells" in out, out
    assert "1 of 4 cells fail their checksum" in out and "1 to simulate" in out, out


def test_a_finished_map_resumed_claims_no_time_for_nothing(tmp_path):
    """Resuming a store that holds every cell: '24 of 24 cells already done ..., 0 to
    simulate (about 12 s)' gave the caller's start-up estimate for no work. Fails on the
    old tree."""
    from numerics.maps import run_map

    params = _small_simulated_map()
    run_map(params, tmp_path, workers=1, progress=False, log=lambda *_: None)
    said = []
    run_map(params, tmp_path, workers=1, progress=False, log=said.append, estimate=12.0)
    line = next(s for s in said if s.startswith("resuming "))
    assert "4 of 4 cells already done" in line and "0 to simulate" in line
    assert "about" not in line, line


def test_every_coordinate_of_a_paper_map_store_says_its_unit():
    """xr.open_zarr of the paper chain's store: delta and K_theta had a long_name and no
    units (k, k_simulated had theirs; a model map's axes all have one). The stiffnesses
    are ratios to k_l (K_s = k_s / k_l, common.paper): dimensionless. Fails on the old
    tree."""
    from numerics import Material
    from numerics.maps import MapParameters

    params = MapParameters(case="coupled", material=Material.paper("blue"),
                           delta=(-0.003, 0.003), k=(0.6, 0.8), amplitude=0.02,
                           theory_only=True)
    ds = params.new_dataset()
    assert set(ds.coords) == {"delta", "K_theta", "k", "k_simulated"}
    for name in ds.coords:
        assert ds[name].attrs.get("units"), name
    assert ds["delta"].attrs["units"].startswith("1 ")  # dimensionless


class _Costs:
    """A map's parameters as the order reads them: each block's cost from a table."""

    def __init__(self, costs):
        self.costs = costs

    def block_cost(self, i, js, arrays=None):
        return self.costs[i]


def test_blocks_of_equal_cost_go_spread_over_the_grid_costlier_first():
    """A fresh model map's blocks all tie (its theories are the tasks'): in grid order its
    first blocks were its first rows (a 100-cell fput map's low amplitudes, all of T
    each) and the pace the progress lines read was 4x too slow. Now ties go in the
    bit-reversed order of their ranks, so any first few sample the whole grid; a
    costlier block still goes first. Fails on the old tree (grid order)."""
    todo = [(i, [0, 1]) for i in range(16)]
    order = _store._longest_first(_Costs([(0, 2)] * 16), todo)
    assert sorted(order) == sorted(todo)
    assert [i for i, _ in order[:4]] == [0, 8, 4, 12]  # by hand: 0, 1/2, 1/4, 3/4 of 16
    rows = [i for i, _ in order[:8]]
    assert min(rows) < 4 and max(rows) >= 12  # both ends of the grid among the first half
    costs = [(0, 2)] * 16
    costs[5] = (2, 2)  # two stable cells: runs all of T
    costs[9] = (1, 2)
    order = _store._longest_first(_Costs(costs), todo)
    assert [i for i, _ in order[:3]] == [5, 9, 0]


ROOT = Path(__file__).resolve().parents[1]
#: a model map whose cells take seconds each (N = 128, T = 40000: its stable cells run all
#: of T), one worker, a cell a task: a signal lands between finished cells
SLOW_MAP = ["map", "--model", "fput", "--k", "0.4,1.2,2.0,2.8", "--amplitude", "0.03,0.3",
            "--N", "128", "--t-end", "40000", "--block", "1", "--workers", "1"]


def _flexmm(args, **kw):
    return subprocess.Popen([sys.executable, "-m", "cli", *args], cwd=ROOT, text=True,
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, **kw)


@pytest.fixture(scope="module")
def undisturbed(tmp_path_factory):
    out = tmp_path_factory.mktemp("whole")
    p = _flexmm(SLOW_MAP + ["--out", str(out)])
    _, err = p.communicate(timeout=600)
    assert p.returncode == 0, err
    import xarray as xr

    return xr.open_zarr(out / "map.zarr", chunks=None).load()


@pytest.mark.parametrize("signum, code", [(signal.SIGTERM, 143), (signal.SIGKILL, -9)])
def test_a_model_map_killed_mid_map_resumes_to_the_undisturbed_store(signum, code, tmp_path,
                                                                      undisturbed):
    """SIGTERM (one line, exit 143, the lock released) or kill -9 (a stale lock, taken
    over) after some cells: the same command resumes with every finished cell kept and
    none computed again, and ends with the undisturbed store, bit for bit (seeded runs)."""
    from numerics.maps import cells_done

    out = tmp_path / "m"
    p = _flexmm(SLOW_MAP + ["--out", str(out)], start_new_session=True)
    try:
        end = time.monotonic() + 300
        while time.monotonic() < end and p.poll() is None:
            got = cells_done(out / "map.zarr")
            if got and 1 <= got[0] < got[1]:
                break
            time.sleep(0.05)
        assert p.poll() is None, "the map ended before the signal"
        os.kill(p.pid, signum)  # the command only: its workers see their client go
        _, err = p.communicate(timeout=120)
    finally:
        if p.poll() is None:
            os.killpg(p.pid, signal.SIGKILL)
            p.communicate()
    assert p.returncode == code, err
    kept = cells_done(out / "map.zarr")[0]
    assert kept >= 1
    if signum != signal.SIGKILL:
        # the progress lines a busy machine's map prints first (stderr a pipe) aside
        lines = [t for t in err.strip().splitlines() if not re.match(r"map: \d+ of \d+ cells ", t)]
        assert len(lines) == 1 and "Traceback" not in err, err
        assert f"{kept} of 8 cells are kept" in lines[0], lines
        assert not (out / "map.zarr.lock").exists()
    again = _flexmm(SLOW_MAP + ["--out", str(out)])
    said, err = again.communicate(timeout=600)
    assert again.returncode == 0, err
    line = re.search(rf"resuming {re.escape(str(out / 'map.zarr'))}: (\d) of 8 cells "
                     "already done", said)
    if line:
        resumed = int(line.group(1))
    else:
        # kill -9 inside the write of the only kept cell: no cell is left done, so no
        # "resuming" line; the damaged cell is said instead (checked below)
        assert signum == signal.SIGKILL and kept == 1, said + err
        resumed = 0
    # kill -9 may land inside a block's write (a cell a block here): that cell fails its
    # checksum and is computed again, said; every other finished cell is kept
    lost = kept - resumed
    assert lost == 0 or (signum == signal.SIGKILL and lost == 1
                         and "1 of 8 cells fail their checksum" in said), said
    assert re.search(rf"simulated {8 - resumed} cells? in ", said), said  # none again
    import xarray as xr

    ds = xr.open_zarr(out / "map.zarr", chunks=None).load()
    assert ds.attrs == undisturbed.attrs
    for name in undisturbed.variables:
        np.testing.assert_array_equal(ds[name].values, undisturbed[name].values, err_msg=name)


@pytest.mark.parametrize("flags", [
    ["--model", "fput", "--param", "beta=0.8,1.6", "--k", "2.4,2.8", "--amplitude", "0.1",
     "--N", "32", "--t-end", "200"],
    ["--alpha", "2.5", "--K-s", "0.01851", "--delta=-0.003,0.003", "--k", "0.8,1.2",
     "--case", "coupled", "--t-end", "1000"]], ids=["model", "paper"])
def test_a_second_map_on_a_store_being_written_is_refused_before_its_estimate(
        flags, tmp_path, capsys):
    """Two maps on one OUT: the second measured a cell and estimated its map (seconds)
    before the store's lock refused it; now refused before the estimate, in one line, exit
    2, the store untouched. Fails on the old tree (an estimate line first)."""
    from numerics.maps import store_lock

    out = tmp_path / "m"
    out.mkdir()
    with store_lock(out / "map.zarr", log=lambda *_: None):  # a live writer: this process
        assert cli(["map", *flags, "--workers", "1", "--out", str(out)]) == 2
        printed = capsys.readouterr()
    assert "estimate" not in printed.out + printed.err and " cells x " not in printed.out
    assert printed.err.strip().count("\n") == 0 and "is being written by pid " \
        f"{os.getpid()}" in printed.err, printed.err
    assert not (out / "map.zarr").exists()


def test_ctrl_c_while_a_block_is_written_keeps_the_block(tmp_path, monkeypatch, sigint_raises):
    """A signal between a block's done flags and its checksums (seen: SIGTERM to `flexmm
    map --model`, the rerun found '1 of 8 cells fail their checksum' and ran all 8 again):
    the finished block was flagged done and failed its checksum, a finished cell lost. Now
    the signal waits until the block is written whole: every flagged cell verifies. Fails
    on the old tree (flagged 1, verified 0)."""
    from numerics.maps import cells_done, run_map

    params = _small_simulated_map(block=1)
    original, sent = _store._write_chunks, []

    def interrupted(array_dir, *a, **k):
        if array_dir.name == "checksum" and not sent:  # the block's last variable
            sent.append(True)
            os.kill(os.getpid(), signal.SIGINT)
        return original(array_dir, *a, **k)

    monkeypatch.setattr(_store, "_write_chunks", interrupted)
    with pytest.raises(KeyboardInterrupt):
        run_map(params, tmp_path, workers=1, progress=False, log=lambda *_: None)
    store = tmp_path / "map.zarr"
    flagged, verified = cells_done(store)[0], cells_done(store, params=params)[0]
    assert sent and flagged >= 1 and verified == flagged, (flagged, verified)
