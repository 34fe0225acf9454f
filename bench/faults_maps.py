"""The fault catalogue's second half: the map, point, table and scene commands, and the map
stores (issue 24). ``bench/faults.py`` adds ``MAP_CATALOGUE`` to its ``CATALOGUE``; the
entries' form is described there."""

from __future__ import annotations

import math

import numpy as np

from bench._fault_helpers import BLUE, E, _sim, _smap
from common import paper
from numerics import LatticeState, mi_gain, plane_wave, stability_map

MAP_CATALOGUE = []

# --- the map, point, table and scene commands, stores (issue 24) ------------------------------

def _cli(*argv):
    """(exit code, stderr) of ``flexmm ARGV`` run in this process."""
    import contextlib
    import io

    from cli.app import main

    err, out = io.StringIO(), io.StringIO()
    with contextlib.redirect_stderr(err), contextlib.redirect_stdout(out):
        code = main(list(argv))
    return code, err.getvalue()


C = "cli"
MAP = ("map", "--case", "coupled", "--alpha", "2.5", "--K-s", "0.01851", "--out",
       "/nonexistent-flexmm/map")
MAP_GRID = ("--delta", "0.003", "--k", "0.8")
POINT = ("point", "--alpha", "2.5", "--K-s", "0.01851", "--K-theta", "0.01551", "--case",
         "coupled")


def _mp(**kw):
    from numerics.maps import MapParameters

    args = dict(case="coupled", alpha=2.5, K_s=paper.K_S, delta=(0.003,), k=(0.8,),
                amplitude=0.02, N=100, t_end=500.0)
    args.update(kw)
    return MapParameters(**args)


def _spec(text):
    from numerics.maps import parse_spec

    return parse_spec(text, "--k")


def _launched_from_noise():
    from numerics.theory import launched_state

    rng = np.random.default_rng(1)
    st = LatticeState(None, None, 1e-3 * rng.standard_normal(64), np.zeros(64))
    st.theta[:] += 1e-6 * np.cos(2 * np.pi * 8 * np.arange(64) / 64)
    return launched_state(BLUE, "rotation", 2 * np.pi * 8 / 64, initial=st)


def _tri_state():
    from numerics.maps import tri_state

    return tri_state(np.array([np.nan, 0.0, 1.0, 1e-5]), 5000.0)


def _agreement_leaves_out_undetermined():
    import xarray as xr

    from numerics.maps import agreement

    dims = ("delta", "k")
    ds = xr.Dataset({"done": (dims, np.ones((1, 3), bool)),
                     "verdict_simulated": (dims, np.array([[1, 0, 1]], np.int8)),
                     "verdict_exact": (dims, np.array([[1, 0, -1]], np.int8)),
                     "peak_gain_exact": (dims, np.array([[0.1, 0.0, np.nan]]))},
                    attrs={"t_end": 5000.0, "growth_threshold": 20.0})
    return agreement(ds)


def _store(tamper):
    """A theory-only 1 x 2 map store, tampered with, then opened again: the cells named."""
    import shutil
    import tempfile
    from pathlib import Path

    from numerics.maps import open_or_create

    d = Path(tempfile.mkdtemp())
    try:
        params = _mp(k=(0.8, 1.0), theory_only=True, block=1)
        open_or_create(d / "map.zarr", params, log=lambda *_: None)
        tamper(d / "map.zarr")
        seen = []
        ds = open_or_create(d / "map.zarr", params, log=seen.append)
        return seen, ds["done"].values.tolist()
    finally:
        shutil.rmtree(d, ignore_errors=True)


def _delete_chunk(path):
    (path / "peak_gain_exact" / "0.1").unlink()


def _garble_chunk(path):
    (path / "verdict_paper" / "0.0").write_bytes(b"not a chunk")


def _other_value(path):
    import zarr

    zarr.open_group(str(path), mode="r+")["peak_gain_paper"][0, 0] = 123.0


def _drop_variable(path):
    import shutil

    shutil.rmtree(path / "growth")


def _lock_held():
    import os
    import shutil
    import tempfile
    from pathlib import Path

    from numerics.maps import store_lock

    d = Path(tempfile.mkdtemp())
    try:
        with store_lock(d / "map.zarr", log=lambda *_: None):
            with store_lock(d / "map.zarr", log=lambda *_: None):
                return os.getpid()
    finally:
        shutil.rmtree(d, ignore_errors=True)


def _stale_lock():
    import json
    import shutil
    import socket
    import tempfile
    from pathlib import Path

    from numerics.maps import store_lock

    d = Path(tempfile.mkdtemp())
    try:
        # a pid no process has (above the kernel's pid_max)
        (d / "map.zarr.lock").write_text(json.dumps(
            {"host": socket.gethostname(), "pid": 2**22 + 7, "since": "earlier"}))
        seen = []
        with store_lock(d / "map.zarr", log=seen.append):
            pass
        return seen
    finally:
        shutil.rmtree(d, ignore_errors=True)


def _replot(content):
    import shutil
    import tempfile
    from pathlib import Path

    d = Path(tempfile.mkdtemp())
    try:
        (d / "fig2-dispersion").mkdir()
        if content is not None:
            content(d / "fig2-dispersion" / "data.h5")
        return _cli("scene", "fig2-dispersion", "--replot", "--out", str(d))
    finally:
        shutil.rmtree(d, ignore_errors=True)


def _h5_without_datasets(path):
    import h5py

    with h5py.File(path, "w") as f:
        f.attrs["quick"] = True


MAP_VALUES = [  # MapParameters field, bad value, exception, message
    ("N", 3, ValueError, r"N must be an integer in \[8, "), ("N", 2, ValueError, "N"), ("N", 10**7, ValueError, "N"),
    ("N", 100.0, TypeError, "N"), ("N", True, TypeError, "N"),
    ("t_end", 1e12, ValueError, "t_end"), 
    ("t_end", -1.0, ValueError, "t_end"), ("t_end", math.nan, ValueError, "t_end"),
    ("t_end", True, TypeError, "t_end"), ("seeds", 0, ValueError, "seeds"),
    ("seeds", True, TypeError, "seeds"), ("seeds", 2.0, TypeError, "seeds"),
    ("amplitude", 2.0, ValueError, "amplitude"), ("amplitude", -0.1, ValueError, "amplitude"),
    ("amplitude", True, TypeError, "amplitude"), ("amplitude", 0.02j, TypeError, "amplitude"),
    ("k", (True,), TypeError, r"k\[0\]"), ("k", (0.8, 1 + 0j), TypeError, r"k\[1\]"),
    ("k", (), ValueError, "k must hold"), ("k", (4.0,), ValueError, r"k must be in \(0, 3.14159\)"),
    ("k", "0.8", TypeError, "k must be a sequence"),
    ("delta", (True,), TypeError, r"delta\[0\]"), ("delta", (0.05,), ValueError, "delta must be < K_s"),
    ("delta", (math.nan,), ValueError, r"delta\[0\]"),
    ("alpha", True, TypeError, "alpha"), ("alpha", -1.0, ValueError, "alpha"),
    ("K_s", 0.0, ValueError, "K_s"), ("eps", True, TypeError, "eps"),
    ("dt", 0.0, ValueError, "dt"), ("dt", True, TypeError, "dt"),
    ("noise", 2.0, ValueError, "noise"), ("noise", True, TypeError, "noise"),
    ("method", "euler", ValueError, "method"), ("case", "both", ValueError, "case"),
    ("start", "discrete", ValueError, "start"), ("block", 0, ValueError, "block"),
    ("block", True, TypeError, "block"), ("theory_only", "yes", TypeError, "theory_only"),
]
MAP_CATALOGUE += [(f"MapParameters: {f} = {v!r}", (lambda f=f, v=v: _mp(**{f: v})),
               (E, exc, rx)) for f, v, exc, rx in MAP_VALUES]
# a given step larger than the records' spacing (t_end / 200)
MAP_CATALOGUE += [("MapParameters: t_end = 0.5 with dt = 0.05",
               lambda: _mp(t_end=0.5, dt=0.05, method="rk4"), (E, ValueError, "dt"))]

MAP_CATALOGUE += [
    # SPECs
    ("parse_spec: empty", lambda: _spec(""), (E, ValueError, "--k")),
    ("parse_spec: 1e9 values", lambda: _spec("0.1:3:1000000000"), (E, ValueError, "--k.*at most")),
    ("parse_spec: words", lambda: _spec("a,b"), (E, ValueError, "--k")),
    ("parse_spec: inf", lambda: _spec("0.1,inf"), (E, ValueError, "--k.*non-finite")),
    ("parse_spec: repeated value", lambda: _spec("0.1,0.1"), (E, ValueError, "--k.*repeats")),
    # bools, complex and sizes in the theories and the simulator
    ("simulate: k True", lambda: _sim(k=True), (E, TypeError, "k must be a real")),
    ("simulate: save_every True", lambda: _sim(save_every=True), (E, TypeError, "save_every")),
    ("simulate: save_every 0", lambda: _sim(save_every=0.0), (E, ValueError, "save_every")),
    ("mi_gain: offset True", lambda: mi_gain(BLUE, "coupled", 0.8, 0.02, True),
     (E, TypeError, "offset")),
    ("mi_gain: complex offset", lambda: mi_gain(BLUE, "coupled", 0.8, 0.02, [0.1 + 1j]),
     (E, TypeError, "offset")),
    ("mi_gain: harmonics True", lambda: mi_gain(BLUE, "coupled", 0.8, 0.02, [0.1],
                                                harmonics=True), (E, TypeError, "harmonics")),
    ("plane_wave: harmonics 1000", lambda: plane_wave(BLUE, "coupled", 0.8, 0.02, 1000),
     (E, ValueError, "harmonics")),
    ("stability_map: offset = []", lambda: _smap(offset=[]), (E, ValueError, "offset must hold")),
    ("stability_map: no plane wave is NaN, not stable", lambda: stability_map(
        np.array([0.565487]), np.array([0.012]), "coupled", 2.5, paper.K_S, 0.2),
     ("ok", lambda g: bool(np.isnan(g).all()))),
    ("resonance_map: grid 2^40", lambda: __import__("numerics.maps", fromlist=["x"])
     .resonance_map(0.8, 0.003, "coupled", 2.5, paper.K_S, 0.02, grid=2**40),
     (E, ValueError, "grid")),
    ("gain_spectrum: free_order 10^6", lambda: __import__("numerics.theory", fromlist=["x"])
     .gain_spectrum(BLUE, "coupled", 0.8, 0.02, [0.1], start="paper", free_order=10**6),
     (E, ValueError, "free_order")),
    ("launched_state: a state with no carrier", _launched_from_noise,
     (E, ValueError, "initial.*not a carrier")),
    ("nls_summary: A0 = -1", lambda: __import__("numerics").nls_summary(
        BLUE, "coupled", 0.8, 0.01, -1.0), (E, ValueError, "A0")),
    ("nls_summary: A0 True", lambda: __import__("numerics").nls_summary(
        BLUE, "coupled", 0.8, 0.01, True), (E, TypeError, "A0")),
    ("nls_summary: eps NaN", lambda: __import__("numerics").nls_summary(
        BLUE, "coupled", 0.8, math.nan), (E, ValueError, "eps")),
    # tri-state verdicts and agreement
    ("tri_state: NaN gain is undetermined (-1)", _tri_state,
     ("ok", lambda v: v.tolist() == [-1, 0, 1, 0] and v.dtype == np.int8)),
    ("agreement leaves undetermined cells out and counts them",
     _agreement_leaves_out_undetermined,
     ("ok", lambda a: a["exact"] == 100.0 and a["exact_undetermined_cells"] == 1)),
    # stores: every damage found, named, repaired; one writer
    ("store: a deleted chunk is found and named", lambda: _store(_delete_chunk),
     ("ok", lambda r: len(r[0]) == 1 and "1 of 2 cells" in r[0][0] and "k = 1" in r[0][0])),
    ("store: a garbled chunk is found", lambda: _store(_garble_chunk),
     ("ok", lambda r: len(r[0]) == 1 and "k = 0.8" in r[0][0])),
    ("store: a value overwritten is found", lambda: _store(_other_value),
     ("ok", lambda r: len(r[0]) == 1 and "1 of 2 cells" in r[0][0])),
    ("store: a missing variable is found", lambda: _store(_drop_variable),
     ("ok", lambda r: len(r[0]) == 2 and "damaged: growth;" in r[0][0]
      and "2 of 2 cells" in r[0][1])),
    ("store: an intact store is opened as is", lambda: _store(lambda p: None),
     ("ok", lambda r: r[0] == [])),
    ("store lock: a second writer is refused, naming the holder", _lock_held,
     (E, ValueError, r"being written by pid \d+ on .* since")),
    ("store lock: a stale lock is taken over, with a note", _stale_lock,
     ("ok", lambda seen: len(seen) == 1 and "stale lock" in seen[0])),
    # the CLI: one line, exit 2, the option named, before any work
    ("map: --N 3", lambda: _cli(*MAP, *MAP_GRID, "--N", "3"), (C, 2, r"--N must be an integer in \[8, ")),
    ("map: --t-end 1e12", lambda: _cli(*MAP, *MAP_GRID, "--t-end", "1e12"), (C, 2, "--t-end")),
    ("map: --t-end nan", lambda: _cli(*MAP, *MAP_GRID, "--t-end", "nan"), (C, 2, "--t-end")),
    ("map: --seeds 0", lambda: _cli(*MAP, *MAP_GRID, "--seeds", "0"), (C, 2, "--seeds")),
    ("map: --amplitude 3", lambda: _cli(*MAP, *MAP_GRID, "--amplitude", "3"),
     (C, 2, "--amplitude")),
    ("map: --block 0", lambda: _cli(*MAP, *MAP_GRID, "--block", "0"), (C, 2, "--block")),
    ("map: --k 4", lambda: _cli(*MAP, "--delta", "0.003", "--k", "4"),
     (C, 2, r"--k must be in \(0, 3.14159\)")),
    ("map: --k 1e9 values", lambda: _cli(*MAP, "--delta", "0.003", "--k", "0.1:3:1000000000"),
     (C, 2, "--k")),
    ("map: 90 000 cells need --yes", lambda: _cli(*MAP, "--delta=-0.01:0.01:300", "--k",
                                                  "0.1:3:300", "--N", "20000"),
     (C, 2, "--yes")),
    ("map: --delta beyond K_s", lambda: _cli(*MAP, "--delta", "0.05", "--k", "0.8"),
     (C, 2, "--delta must be < K_s")),
    ("map: no second axis", lambda: _cli(*MAP, "--k", "0.8"), (C, 2, "--K-theta SPEC")),
    ("map: --workers 0", lambda: _cli(*MAP, *MAP_GRID, "--workers", "0"), (C, 2, "--workers")),
    ("map: --workers and --scheduler", lambda: _cli(*MAP, *MAP_GRID, "--workers", "2",
                                                    "--scheduler", "tcp://x:1"),
     (C, 2, "not both")),
    ("map: --timeout 0", lambda: _cli(*MAP, *MAP_GRID, "--timeout", "0"), (C, 2, "--timeout")),
    ("map: --alpha -1", lambda: _cli("map", "--case", "coupled", "--alpha=-1", "--K-s",
                                     "0.01851", *MAP_GRID), (C, 2, "--alpha")),
    ("point: --seeds 0 with --simulate", lambda: _cli(*POINT, "--k", "0.8", "--simulate",
                                                      "--seeds", "0"), (C, 2, "--seeds")),
    ("point: --k 4", lambda: _cli(*POINT, "--k", "4"), (C, 2, "--k")),
    ("point: --k nan", lambda: _cli(*POINT, "--k", "nan"), (C, 2, "--k")),
    ("point: --N 2", lambda: _cli(*POINT, "--k", "0.8", "--N", "2"), (C, 2, "--N")),
    ("point: --amplitude 5", lambda: _cli(*POINT, "--k", "0.8", "--amplitude", "5"),
     (C, 2, "--amplitude")),
    ("point: --t-end 1e9", lambda: _cli(*POINT, "--k", "0.8", "--simulate", "--t-end", "1e9"),
     (C, 2, "--t-end")),
    ("point: --K-theta -1", lambda: _cli("point", "--alpha", "2.5", "--K-s", "0.01851",
                                         "--K-theta=-1", "--case", "coupled", "--k", "0.8"),
     (C, 2, "--K-theta")),
    ("point: --physical of five numbers", lambda: _cli("point", "--physical", "1,2,3,4,5",
                                                       "--case", "coupled", "--k", "0.8"),
     (C, 2, "--physical")),
    ("table: --A0 -1", lambda: _cli("table", "--A0=-1"), (C, 2, "A0")),
    ("table: --A0 nan", lambda: _cli("table", "--A0", "nan"), (C, 2, "A0")),
    ("table: --A0 1e200", lambda: _cli("table", "--A0", "1e200"), (C, 2, "A0")),
    ("table: --A0 0", lambda: _cli("table", "--A0", "0"), (C, 2, "A0")),
    ("coefficients: --k 0", lambda: _cli("coefficients", "--alpha", "2.5", "--K-s", "0.01851",
                                         "--K-theta", "0.01551", "--k", "0"), (C, 2, "k")),
    ("replot: no data.h5", lambda: _replot(None), (C, 2, "does not exist")),
    ("replot: data.h5 is not HDF5", lambda: _replot(lambda p: p.write_bytes(b"junk" * 100)),
     (C, 2, "data.h5 cannot be read")),
    ("replot: data.h5 lacks a dataset", lambda: _replot(_h5_without_datasets),
     (C, 2, "lacks the dataset")),
    ("scene: unknown name", lambda: _cli("scene", "no-such-scene", "--replot"),
     (C, 2, "no-such-scene")),
    ("map --scheduler: a closed port", lambda: _cli(*MAP, *MAP_GRID, "--t-end", "500",
                                                    "--N", "100", "--scheduler",
                                                    "tcp://127.0.0.1:1", "--timeout", "5"),
     (C, 2, "tcp://127.0.0.1:1: cannot connect")),
]

from bench.faults_round3 import ROUND3  # noqa: E402 - the third round (issue 35)

MAP_CATALOGUE += ROUND3

from bench.faults_round4 import ROUND4  # noqa: E402 - the fourth round (issue 39)

MAP_CATALOGUE += ROUND4
