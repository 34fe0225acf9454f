"""Probe 97 of the map engine (bench/probe_maps97.py): what it found, kept as tests.

A map store whose metadata an xarray reader cannot use is damaged, found on resume and
rebuilt keeping its verified cells, never resumed as sound: a variable's ``.zattrs`` lost
(the resume raised xarray's KeyError, a traceback), and a flipped byte in the consolidated
``.zmetadata`` (the resume said every checksum held while ``xr.open_zarr``, the way the
docs open a store, failed on it). A map's progress lines: no "about 0 s left" once the
estimate has passed with no cell back, and their clock starts before the cluster's."""

from __future__ import annotations

import json
import shutil

import numpy as np
import pytest
import xarray as xr

from numerics.maps import ModelMapParameters, open_or_create, run_map

#: the store's tests share a finished map (a LocalCluster started once): the file takes
#: 6 s on the 2-core VM (21 s while other sessions loaded it to 7), so none is slow-marked


def _fput_map(**options):
    return ModelMapParameters.from_model("fput", ("beta", [0.8, 1.6]), ("k", [2.6, 2.8]),
                                         0.1, params={"alpha": 1.0}, **options)


@pytest.fixture(scope="module")
def _finished(tmp_path_factory):
    """A finished theory-only map of 2 x 2 cells, made once (a LocalCluster's start)."""
    out = tmp_path_factory.mktemp("finished")
    params = _fput_map(N=16, theory_only=True, exact=True)
    ds = run_map(params, out, workers=1, progress=False, log=lambda *a: None)
    return params, out, ds.load()


@pytest.fixture
def theory_store(_finished, tmp_path):
    """A copy of the finished map's store, to damage, and its values."""
    params, out, ds = _finished
    shutil.copytree(out / "map.zarr", tmp_path / "map.zarr")
    return params, tmp_path, ds


def _resume(params, out):
    """The store opened as a resumed map opens it (its checks, repair and verification;
    nothing is left to compute, so no cluster is needed)."""
    said = []
    ds = open_or_create(out / "map.zarr", params, log=said.append)
    return ds.load(), said


def _same_cells(a, b):
    """The cells' values of ``b`` equal ``a``'s, bit for bit (a store rebuilt before its
    map's end lacks the summary's derived variables: those are written at the end)."""
    assert b["done_predicted"].values.all()
    for name in b.data_vars:
        np.testing.assert_array_equal(a[name].values, b[name].values, err_msg=name)


@pytest.mark.parametrize("variable", ["verdict_semidiscrete", "k_simulated", "beta"])
def test_a_variable_whose_zattrs_is_lost_is_damaged_and_rebuilt(theory_store, variable):
    params, out, first = theory_store
    (out / "map.zarr" / variable / ".zattrs").unlink()
    ds, said = _resume(params, out)  # before: KeyError (_ARRAY_DIMENSIONS), a traceback
    assert any("damaged" in line and variable in line for line in said), said
    _same_cells(first, ds)  # every cell kept: their data and checksums survive
    _same_cells(first, xr.open_zarr(out / "map.zarr").load())  # as the docs open it


def test_a_flipped_byte_in_the_consolidated_metadata_is_found(theory_store):
    params, out, first = theory_store
    meta = out / "map.zarr" / ".zmetadata"
    text = meta.read_text()
    at = text.index('"<f8"', text.index('"peak_gain_exact/.zarray"'))
    meta.write_text(text[:at] + '"<f4"' + text[at + 5:])  # one byte: 8 -> 4
    with pytest.raises(ValueError):  # what the user met: the store unreadable to xarray
        xr.open_zarr(out / "map.zarr")["peak_gain_exact"].load()
    ds, said = _resume(params, out)  # before: "checksums verified", the store left as it was
    assert any("damaged" in line and ".zmetadata" in line for line in said), said
    back = xr.open_zarr(out / "map.zarr").load()
    _same_cells(first, back)
    # the consolidated copy is the files again, entry for entry
    entries = json.loads(meta.read_text())["metadata"]
    for key, value in entries.items():
        assert json.loads((out / "map.zarr" / key).read_text()) == value, key


def test_an_intact_store_is_not_called_damaged(theory_store):
    """The check must not cry wolf: a finished store resumes without a rebuild."""
    params, out, first = theory_store
    ds, said = _resume(params, out)
    assert not any("damaged" in line for line in said), said
    _same_cells(first, ds)


class _Clock:
    def __init__(self):
        self.now = 100.0

    def __call__(self):
        return self.now


def test_past_the_estimate_with_no_cell_back_no_time_left_is_claimed():
    """A paper map on a busy machine estimated 31 s; at 40 s, no cell back yet, its line
    said 'about 0 s left' and the map took 72 s more."""
    from numerics.maps import _progress

    clock, said = _Clock(), []
    p = _progress.ProgressLines(6, "simulated", 31.0, said.append, clock)
    clock.now = 110.0
    p.tick()
    assert said[-1].endswith("about 21 s left (the estimate; no cell back yet)")
    clock.now = 140.0
    p.tick()
    assert "0 s left" not in said[-1] and "past the estimate (31 s)" in said[-1], said


def test_the_progress_clock_starts_before_the_cluster(monkeypatch, tmp_path):
    """The lines count from before the cluster's start, as the estimate they quote does:
    the first came 10 s after a start-up of 13-50 s on a busy machine, its time left the
    estimate less only the tasks' time."""
    from numerics.maps import _cluster, _progress, _store

    order = []
    real = _progress.progress_lines

    def lines(*a, **k):
        order.append("lines")
        return real(*a, **k)

    class Stop(Exception):
        pass

    def connect(*a, **k):
        order.append("connect")
        raise Stop

    monkeypatch.setattr(_progress, "progress_lines", lines)
    monkeypatch.setattr(_cluster, "connect", connect)
    with pytest.raises(Stop):
        _store._run_tasks(_fput_map(N=16, theory_only=True), tmp_path / "map.zarr", [], 4,
                          None, 1, None, lambda *a: None)
    assert order == ["lines", "connect"]


def test_a_lock_created_a_moment_ago_without_its_record_yet_is_held(tmp_path):
    """A writer creates the lock (O_EXCL), then writes its record: a second map in between
    read an empty file as 'no flexmm lock record', took it over, and both wrote the store."""
    from numerics.maps._integrity import StoreLocked, store_lock

    store = tmp_path / "map.zarr"
    lock = tmp_path / "map.zarr.lock"
    lock.write_bytes(b"")  # the first writer, between its O_EXCL create and its record
    with pytest.raises(StoreLocked, match="holds no record yet"):
        with store_lock(store, log=lambda *a: None):
            pass
    assert lock.read_bytes() == b""  # left to its writer
    # an old record-less file (a writer that died mid-way) is still taken over, said
    import os
    import time
    old = time.time() - 60
    os.utime(lock, (old, old))
    said = []
    with store_lock(store, log=said.append):
        assert b'"pid"' in lock.read_bytes()
    assert any("no flexmm lock record" in line for line in said) and not lock.exists()


@pytest.mark.parametrize("axes", [
    ["--param", "beta=1:1:1", "--k", "2.6:2.6:1"],  # a 1 x 1 map
    ["--param", "beta=1", "--k", "2.6:2.6:1", "--amplitude", "0.1:0.1:1"],
])
def test_a_one_value_spec_of_k_or_amplitude_is_an_axis_as_a_params_is(axes, monkeypatch,
                                                                      tmp_path):
    """--param beta=1:1:1 made an axis of one value while --k 2.6:2.6:1 and --amplitude
    0.1:0.1:1 were fixed values, so no map of one cell could be asked ('got 1: beta')."""
    import numerics.maps
    from cli.app import main as cli

    class Asked(BaseException):
        pass

    def check_store(path, params, overwrite=False):  # the map as resolved, before work
        raise Asked(params)

    monkeypatch.setattr(numerics.maps, "check_store", check_store)
    args = ["map", "--model", "fput", "--param", "alpha=1", *axes, "--N", "64",
            "--theory-only", "--out", str(tmp_path)]
    if "--amplitude" not in axes:
        args += ["--amplitude", "0.1"]
    with pytest.raises(Asked) as asked:
        cli(args)
    params = asked.value.args[0]
    assert params.grid_shape == (1, 1), params.dims


def test_a_store_set_aside_by_a_stopped_rewrite_is_restored(tmp_path):
    """A rewrite (a damaged store rebuilt) renames the store aside, then its successor into
    place: a kill -9 between the two left no map.zarr, and the next run deleted the store
    set aside with every finished cell in it."""
    import zarr

    params = _fput_map(N=16, theory_only=True)
    store = tmp_path / "map.zarr"
    open_or_create(store, params, log=lambda *a: None)
    from numerics.maps._integrity import CHECKSUM, cell_checksums

    group = zarr.open_group(str(store), mode="r+")
    group["g1"][0, 0] = 4.25  # a finished cell (flagged, its checksum right) to find again
    group["done_predicted"][0, 0] = True
    names = [n for n in group.array_keys() if n not in (CHECKSUM, *params.store_coords())]
    group[CHECKSUM][...] = cell_checksums({n: group[n][...] for n in names})
    store.rename(tmp_path / ".map.zarr.old")
    said = []
    ds = open_or_create(store, params, log=said.append)
    assert any("restored" in line for line in said), said
    assert float(ds["g1"][0, 0]) == 4.25


def test_an_interrupt_after_the_last_cell_says_every_cell_is_done(_finished, tmp_path):
    """Ctrl-C after a map's last cell said 'the cells that were running were not kept: run
    the same command again to continue', of a map with no cell left; and a theory-only
    map's interrupt counted its cells by the simulations' flag: '0 of 4 cells are kept'."""
    import argparse
    import signal

    from cli.app import _interrupted

    _, out, _ = _finished
    args = argparse.Namespace(cmd="map", out=str(out), theory_only=True)
    said = _interrupted(args, KeyboardInterrupt(signal.SIGINT))
    assert "4 of 4 cells are kept" in said and "every cell is done" in said, said
    assert "were not kept" not in said
