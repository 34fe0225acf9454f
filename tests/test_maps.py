"""MI maps: SPEC parsing, a 2 x 2 map on a LocalCluster of 2 workers, resume after an
interrupted map (only the missing cells run), bad input (one line, nothing written), and
the point command."""

import numpy as np
import pytest
import xarray as xr

from cli.app import main as cli
from common import paper
from numerics.maps import MapParameters, parse_spec
from numerics.maps import _store as maps  # blocks, _write_block, _run_tasks: internals under test

N = 100
K2 = tuple(2 * np.pi * np.array([13, 15]) / N)


def _params(**kw):
    args = dict(case="coupled", alpha=paper.ALPHA, K_s=paper.K_S, delta=(-0.003, 0.003),
                k=K2, amplitude=0.02, N=N, t_end=2000.0, block=1)
    args.update(kw)
    return MapParameters(**args)


@pytest.mark.parametrize("text, values", [
    ("0.1,0.3,0.2", [0.1, 0.2, 0.3]), ("0:1:3", [0.0, 0.5, 1.0]), ("-0.003", [-0.003]),
    ("1:1:1", [1.0])])
def test_spec_parsing(text, values):
    np.testing.assert_allclose(parse_spec(text, "--k"), values)


@pytest.mark.parametrize("text", ["", "a,b", "0:1", "0:1:0", "1:1:3", "0.1,nan", "0.1,0.1",
                                  "0:1:2:3"])
def test_bad_spec_is_a_clear_error(text):
    with pytest.raises(ValueError, match="--k"):
        parse_spec(text, "--k")


def test_two_by_two_map_on_two_workers(tmp_path):
    ds = maps.run_map(_params(), tmp_path, workers=2, progress=False, log=lambda *_: None)
    assert ds["done"].values.all() and ds.sizes == {"delta": 2, "k": 2}
    # what run_map returns (its values kept in memory, not read back) is the store
    xr.testing.assert_identical(ds, xr.open_zarr(tmp_path / "map.zarr", consolidated=False,
                                                 chunks=None).load())
    for name in ("verdict_simulated", "verdict_paper", "verdict_semidiscrete", "verdict_exact",
                 "verdict_exact_all"):
        # tri-state: 1 MI, 0 stable, -1 undetermined (none here: every theory evaluates)
        assert ds[name].dtype == np.int8 and set(np.unique(ds[name])) <= {0, 1}, name
    assert np.all(ds["growth"].values > 0) and set(np.unique(ds["growth_field"])) <= {0, 1}
    # every parameter is in the attributes; the store opens with plain xarray
    back = xr.open_zarr(tmp_path / "map.zarr", consolidated=False)
    for key in ("case", "alpha", "K_s", "amplitude", "N", "t_end", "seeds", "criterion"):
        assert key in back.attrs, key
    # the simulated verdict is the growth criterion, cell by cell, on the exponential
    # reading (probe 96; one seed: the cell's median is its run's)
    assert np.array_equal(ds["verdict_simulated"].values == 1,
                          ds["growth_exponential"].values > ds.attrs["growth_threshold"])
    assert np.all(ds["growth_exponential"].values <= ds["growth"].values)
    # the blue-point cell (delta = +0.003, k = 0.817) is unstable in every theory but the
    # semi-discrete NLS, as the scenes found at N = 500
    cell = ds.sel(delta=0.003, k=K2[0], method="nearest")
    assert int(cell["verdict_exact"]) == 1 and int(cell["verdict_simulated"]) == 1
    assert int(cell["verdict_semidiscrete"]) == 0
    # every cell predicted from its own initial state; where the run stays linear the
    # predicted growth over the simulated span is within 2x of the measured one (the
    # goal of issue 21; tests/test_response.py checks the linear response itself)
    assert ds["done_predicted"].values.all()
    linear = ds["predicted_status"].values == 0
    assert linear.any()
    assert np.all(np.abs(ds["growth_log_ratio"].values[linear]) < np.log10(2))
    ag = maps.agreement(ds)
    assert ag["predicted"] == 100.0 and ag["predicted_undetermined_cells"] == 0


def test_an_interrupted_map_resumes_with_only_the_missing_cells(tmp_path, monkeypatch):
    params = _params(k=K2 + (2 * np.pi * 17 / N,))
    ds = maps.open_or_create(tmp_path / "map.zarr", params)
    todo = maps.blocks(params, ds["done"].values)
    # "interrupted" after two blocks: write them as the client would, then stop
    for i, js in todo[:2]:
        maps._write_block(tmp_path / "map.zarr", params, maps.simulate_block(params, i, js))
    seen = []
    original = maps._run_tasks

    def spy(params_, path, todo_, n_todo, *a, **k):
        seen.append((list(todo_), n_todo))
        return original(params_, path, todo_, n_todo, *a, **k)

    monkeypatch.setattr(maps, "_run_tasks", spy)
    messages = []
    ds = maps.run_map(params, tmp_path, workers=1, progress=False, log=messages.append)
    assert seen[0][1] == 6 - 2 and seen[0][0] == todo[2:]  # only the 4 missing cells ran
    assert any("2 of 6 cells already done" in m for m in messages)
    assert ds["done"].values.all()
    # resumed from the values its checksums were verified on, and still the store
    xr.testing.assert_identical(ds, xr.open_zarr(tmp_path / "map.zarr", consolidated=False,
                                                 chunks=None).load())


def test_a_damaged_store_is_repaired_and_what_run_map_returns_is_the_store(tmp_path):
    """A cell whose values no longer match their checksum is simulated again; run_map then
    returns the repaired store (the path that rewrites the store reads it afresh)."""
    import zarr

    params = _params(delta=(0.003,))
    first = maps.run_map(params, tmp_path, workers=1, progress=False, log=lambda *_: None)
    zarr.open_group(str(tmp_path / "map.zarr"), mode="r+")["growth"][0, 0] = 123.0
    messages = []
    ds = maps.run_map(params, tmp_path, workers=1, progress=False, log=messages.append)
    assert any("1 of 2 cells fail their checksum" in m for m in messages)
    xr.testing.assert_identical(ds, xr.open_zarr(tmp_path / "map.zarr", consolidated=False,
                                                 chunks=None).load())
    # the run is deterministic (seeded noise, fixed steps): the repaired cell is the
    # value it had before it was damaged, bit for bit
    assert ds["done"].values.all() and float(ds["growth"][0, 0]) != 123.0
    xr.testing.assert_identical(ds, first)


def _frame(flags, nbytes, blocksize, cbytes, rest):
    """A Blosc 1 frame: 16 header bytes (version 2, typesize 8) and ``rest``."""
    return (bytes((2, 1, flags, 8)) + b"".join(v.to_bytes(4, "little")
                                               for v in (nbytes, blocksize, cbytes)) + rest)


@pytest.mark.parametrize("garbage", [
    b"\x00garbage" * 3, b"", b"\x02\x01" + bytes(40),
    # headers that match the file (8 decoded bytes, the stored size its length) but whose
    # frame leads the decoder outside it: a block start past the end, a copied chunk
    # shorter than its data, a block size of 0
    _frame(0x01, 8, 8, 24, (99).to_bytes(4, "little") + bytes(4)),
    _frame(0x03, 8, 8, 20, bytes(4)),
    _frame(0x01, 8, 0, 24, bytes(8))])
def test_a_garbled_chunk_is_found_from_its_header_and_never_decoded(tmp_path, garbage):
    """Blosc reads past the end of a garbled buffer (numcodecs#228): what it raises, or
    returns, depends on the memory beside it (CI runs once got KeyError: 5, KeyError: 4).
    A chunk whose frame does not match its file is named damaged without being decoded."""
    from numerics.maps._integrity import read_raw, unsound_chunks

    store = tmp_path / "map.zarr"
    maps.open_or_create(store, _params(delta=(0.003, 0.004)))
    assert all(not unsound_chunks(store / n) for n in ("delta", "k", "done", "growth"))
    (store / "growth" / "1.0").write_bytes(garbage)
    assert unsound_chunks(store / "growth") == {"1.0"}
    raw, unreadable = read_raw(store, ["growth", "done"], (2, 2))
    assert unreadable.tolist() == [[False, False], [True, False]]


def test_a_map_with_other_parameters_is_not_mixed_in(tmp_path):
    import zarr

    maps.open_or_create(tmp_path / "map.zarr", _params())
    zarr.open_group(str(tmp_path / "map.zarr"), mode="r+")["done"][0, 0] = True  # a finished cell
    with pytest.raises(ValueError, match="other parameters"):
        maps.open_or_create(tmp_path / "map.zarr", _params(t_end=3000.0))


def test_a_map_without_a_finished_cell_does_not_block_the_corrected_command(tmp_path):
    # every cell of the first command failed: its store holds nothing a rerun would lose
    maps.open_or_create(tmp_path / "map.zarr", _params())
    seen = []
    ds = maps.open_or_create(tmp_path / "map.zarr", _params(t_end=3000.0), log=seen.append)
    assert len(seen) == 1 and "no finished cell" in seen[0] and "replaced" in seen[0]
    assert ds.attrs["t_end"] == 3000.0


@pytest.mark.parametrize("extra, match", [
    (["--delta", "a:b:c"], "--delta"), (["--delta", "0.03"], "K_theta"),
    (["--delta", "0.001", "--k", "4"], "--k must be in (0, 3.14159)"),
    (["--delta", "0.001", "--seeds", "0"], "seeds"),
    (["--delta", "0.001", "--workers", "0"], "workers"),
    (["--delta", "0.001", "--amplitude", "3"], "amplitude"),
])
def test_map_bad_input_is_one_line_and_writes_nothing(extra, match, tmp_path, capsys):
    k = [] if "--k" in extra else ["--k", "0.8168"]  # an option given twice is refused
    args = ["map", "--case", "coupled", "--alpha", "2.5", "--K-s", "0.01851", *k,
            "--N", "100", "--out", str(tmp_path / "out")] + extra
    assert cli(args) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1 and match in err and "Traceback" not in err
    assert not (tmp_path / "out").exists()


def test_theory_only_map_never_starts_the_simulator(tmp_path, capsys):
    # a theory-only map predicts every cell's growth (tasks on the cluster) and simulates
    # none: no cell is done, none has a simulated time
    assert cli(["map", "--case", "rotation", "--alpha", "2.5", "--K-s", "0.01851",
                "--delta=-0.01:0.01:4", "--k", "0.2:3:5", "--theory-only",
                "--out", str(tmp_path), "--workers", "1"]) == 0
    # its summary: each theory's MI share, no "simulated" (there is none), no NaN
    share = [ln for ln in capsys.readouterr().out.splitlines() if ln.startswith("MI (grows")]
    assert len(share) == 1 and "paper " in share[0] and "exact " in share[0]
    assert "simulated" not in share[0] and "nan" not in share[0]
    ds = xr.open_zarr(tmp_path / "map.zarr", consolidated=False)
    assert ds.sizes == {"delta": 4, "k": 5} and not ds["done"].values.any()
    assert np.isnan(ds["t_simulated"].values).all()
    assert ds["done_predicted"].values.all()
    # every cell predicted: a verdict, or undetermined with its reason (near k = pi eq. IC
    # launches a backward wave as large as the carrier: no torus, no linear theory)
    v, status = ds["verdict_predicted"].values, ds["predicted_status"].values
    assert np.isin(v, (0, 1)).sum() >= 15
    assert np.all(np.isin(status[v < 0], (2, 3))) and np.all(np.isin(status[v >= 0], (0, 1)))
    # case I: the paper's NLS says MI exactly where delta < 0 (sign(g) = -sign(delta)),
    # given the finite-time question is decided by a nonzero gain
    gains = ds["peak_gain_paper"].values
    assert np.all((gains > 0) == (ds["delta"].values[:, None] < 0))


def test_point_prints_three_theories(capsys):
    blue = ["point", "--alpha", "2.5", "--K-s", "0.01851", "--K-theta", "0.01551",
            "--k", "0.81681", "--case", "coupled"]
    assert cli(blue + ["--start", "travelling"]) == 0
    out = capsys.readouterr().out
    for name in ("paper NLS", "semi-discrete NLS", "exact lattice"):
        assert name in out
    # the blue point, case II: the exact peak gain of gain-theories (0.00324)
    assert "0.00324" in out
    # the default start is eq. IC: its own exact theory (gain-theories' paper-start peak
    # 0.00307, measured to 0.1%), not the travelling wave's
    assert cli(blue) == 0
    out = capsys.readouterr().out
    row = next(ln for ln in out.splitlines() if ln.startswith("exact lattice, paper start"))
    assert abs(float(row.split()[5]) - 0.00307) < 0.5e-5  # the report's 3 digits
    assert "K_theta = 0.01551" in out and "amplitude 0.02 rad" in out  # inputs echoed


def test_any_k_is_snapped_and_carried(tmp_path, capsys):
    """k = 1.0 is no 2 pi m / 500: point and map snap it and say so, and both k's are kept."""
    import json

    assert cli(["point", "--alpha", "2.5", "--K-s", "0.01851", "--K-theta", "0.02151",
                "--k", "1.0", "--case", "rotation", "--out", str(tmp_path / "p")]) == 0
    res = json.loads((tmp_path / "p" / "point.json").read_text())
    assert res["k_requested"] == 1.0 and res["m"] == 80
    assert abs(res["k"] - 2 * np.pi * 80 / 500) < 1e-15
    assert (tmp_path / "p" / "point.png").stat().st_size > 0  # always drawn
    assert len(res["theories"]["paper NLS"]["curve"]) == len(res["theories"]["paper NLS"]["q"])
    assert cli(["map", "--alpha", "2.5", "--K-s", "0.01851", "--delta", "-0.003,0.003",
                "--k", "0.25:2.9:10", "--case", "rotation", "--theory-only",
                "--out", str(tmp_path / "m")]) == 0
    import xarray as xr

    ds = xr.open_zarr(tmp_path / "m" / "map.zarr")
    m = np.round(ds["k_simulated"].values * 500 / (2 * np.pi))
    np.testing.assert_allclose(ds["k_simulated"].values, 2 * np.pi * m / 500, rtol=1e-15)
    np.testing.assert_allclose(ds["k"].values, np.linspace(0.25, 2.9, 10))
    # two k's on one lattice wavenumber are refused before anything is written
    assert cli(["map", "--alpha", "2.5", "--K-s", "0.01851", "--delta", "0.003",
                "--k", "0.25,0.2501", "--case", "rotation", "--out", str(tmp_path / "d")]) == 2
    assert "both snap" in capsys.readouterr().err and not (tmp_path / "d").exists()


def test_map_refuses_a_long_run_without_yes_and_names_overwrite(tmp_path, capsys):
    base = ["map", "--alpha", "2.5", "--K-s", "0.01851", "--delta", "0.003",
            "--k", "0.5,1.0", "--case", "rotation", "--out", str(tmp_path)]
    assert cli(base + ["--t-end", "1e8"]) == 2  # estimated at ~10 h: refused without --yes
    assert "--yes" in capsys.readouterr().err
    assert not (tmp_path / "map.zarr").exists()
    assert cli(base + ["--theory-only"]) == 0
    assert cli(base + ["--theory-only", "--amplitude", "0.03"]) == 2
    assert "--overwrite" in capsys.readouterr().err
    assert cli(base + ["--theory-only", "--amplitude", "0.03", "--overwrite"]) == 0


def test_a_simulated_maps_last_line_says_what_was_written_where(tmp_path, capsys):
    """The agreement lines come before it: what was written, and where, is the last line."""
    assert cli(["map", "--alpha", "2.5", "--K-s", "0.01851", "--delta", "0.003", "--k",
                "0.5,1.0", "--case", "rotation", "--N", "64", "--t-end", "1000",
                "--workers", "1", "--out", str(tmp_path)]) == 0
    lines = capsys.readouterr().out.strip().splitlines()
    assert any(ln.startswith("theory verdicts that agree") for ln in lines)
    assert lines[-1] == (f"wrote {tmp_path / 'map.zarr'}, {tmp_path / 'map.png'}, "
                         f"{tmp_path / 'summary.json'}")


def test_point_says_when_the_ring_samples_none_of_the_band(capsys):
    """k = 1, case I of the --physical example: the exact band (offsets < 0.037) lies below
    the smallest offset 2 pi / 128 = 0.049 of a ring of 128 sites, which therefore cannot
    grow (a run: 'no growth within T' beside three MI theories); 180 sites sample it. The
    note names a ring that keeps k = 2 pi 20/128 (a multiple of 128/gcd(20, 128) = 32):
    160's smallest offset, 0.0393, lies above the band, 192's, 0.0327, inside."""
    base = ["point", "--physical", "0.01,2e-6,0.02,1e4,185,1", "--k", "1.0", "--case",
            "rotation"]
    assert cli(base + ["--N", "128"]) == 0
    note = [ln for ln in capsys.readouterr().out.splitlines() if "holds no offset" in ln]
    assert len(note) == 1 and "N = 128" in note[0]
    assert "N = 192 with --k 0.981747704 samples it" in note[0]
    assert cli(base + ["--N", "180"]) == 0
    assert "holds no offset" not in capsys.readouterr().out


def test_point_physical_units_and_bad_input(capsys):
    assert cli(["point", "--physical", "1,0.1,1,1,0.03,0.005", "--k", "0.9",
                "--case", "coupled"]) == 0
    assert cli(["point", "--physical", "1,2,3", "--k", "0.9", "--case", "coupled"]) == 2
    assert "six numbers" in capsys.readouterr().err
    assert cli(["point", "--alpha", "2.5", "--k", "0.9", "--case", "coupled"]) == 2


def test_point_physical_table_gives_rates_in_per_second(capsys):
    """--physical promises rates in 1/s and k in rad/m: the table carries them beside the
    lattice units (1 T = sqrt(m/k_l) = 1 ms, a = 2 cm: 1/s = 1000 x 1/T)."""
    assert cli(["point", "--physical", "0.01,2e-6,0.02,1e4,185,1", "--k", "1.0", "--case",
                "rotation", "--N", "128"]) == 0
    lines = capsys.readouterr().out.splitlines()
    assert any(ln.startswith("growth factor within T = 100000 (= 100 s)") for ln in lines)
    head = next(i for i, line in enumerate(lines) if line.startswith("theory "))
    cols = [c.strip() for c in lines[head].split("  ") if c.strip()]
    assert cols[-3:] == ["peak gain (1/s)", "e-folding (s)", "at q - k (rad/m)"]
    row = lines[head + 2].split()  # the paper NLS: "paper NLS MI gain efold offset ..."
    gain_T, efold_T, offset, gain_s, efold_s, offset_m = (
        float(row[i]) for i in (3, 4, 5, 7, 8, 9))
    assert gain_s == pytest.approx(gain_T * 1000, rel=1e-3)
    assert efold_s == pytest.approx(efold_T / 1000, rel=1e-3)
    assert offset_m == pytest.approx(offset / 0.02, rel=1e-3)


def test_map_parameters_take_a_material_and_carry_K_theta_unchanged(tmp_path):
    # material= and K_theta= as given: each row's cells and theories use the typed K_theta
    # (0.003 is one whose K_s - (K_s - K_theta) round trip is off by an ulp); the stored
    # attributes are those of the (alpha, K_s, delta) form, and positional arguments work
    from numerics import Material

    blue = Material.paper("blue")
    rows = (0.02151, 0.003)
    assert paper.K_S - (paper.K_S - 0.003) != 0.003
    p = MapParameters(case="coupled", material=blue, K_theta=rows, k=K2, amplitude=0.02,
                      N=N, t_end=2000.0)
    assert (p.alpha, p.K_s) == (blue.alpha, blue.K_s) and p.K_theta == rows
    assert [p.material_at(i).K_theta for i in range(2)] == list(rows)
    assert p.delta == tuple(paper.K_S - x for x in rows)
    q = MapParameters("coupled", paper.ALPHA, paper.K_S, p.delta, K2, 0.02, N=N, t_end=2000.0)
    assert q.attrs() == p.attrs() and q.delta == p.delta
    assert q.K_theta == tuple(paper.K_S - d for d in p.delta)
    import dataclasses

    assert dataclasses.replace(p, seeds=2).K_theta == rows  # both given, consistent
    with pytest.raises(ValueError, match="not both"):
        MapParameters(case="coupled", alpha=2.5, K_s=paper.K_S, delta=(0.0,), K_theta=(0.01,),
                      k=K2, amplitude=0.02)
    with pytest.raises(TypeError, match="not both"):
        MapParameters(case="coupled", material=blue, alpha=2.5, delta=(0.0,), k=K2,
                      amplitude=0.02)
    with pytest.raises(TypeError, match="delta= or K_theta="):
        MapParameters(case="coupled", material=blue, k=K2, amplitude=0.02)
    with pytest.raises(ValueError, match="K_theta must be finite and > 0"):
        MapParameters(case="coupled", material=blue, K_theta=(-0.01,), k=K2, amplitude=0.02)
    # the store holds K_theta as a coordinate of its rows; the theories are evaluated there
    ds = maps.open_or_create(tmp_path / "map.zarr", p)
    assert tuple(ds["K_theta"].values) == rows
    from numerics.maps import theory_columns

    for name, v in theory_columns(p).items():
        np.testing.assert_array_equal(ds[name].values, v)


def test_map_command_passes_K_theta_through_unchanged(tmp_path, monkeypatch):
    # `flexmm map --K-theta`: the MapParameters it builds hold the typed values (largest
    # first, so that delta ascends), no K_s - delta conversion on the way
    from cli import map as _map_command

    seen = []

    def stop(params, *a, **k):
        seen.append(params)
        raise KeyboardInterrupt

    monkeypatch.setattr(_map_command, "run_map", stop)
    assert cli(["map", "--case", "rotation", "--alpha", "2.5", "--K-s", "0.01851",
                "--K-theta", "0.003,0.0155,0.2", "--k", "0.8168", "--theory-only",
                "--out", str(tmp_path)]) != 0
    p = seen[0]
    assert p.K_theta == (0.2, 0.0155, 0.003)
    assert list(p.delta) == sorted(p.delta)
    assert p.material_at(2).K_theta == 0.003


@pytest.mark.skipif(__import__("platform").libc_ver()[0] != "glibc", reason="glibc's mallopt")
def test_map_tasks_reuse_freed_memory_under_dasks_malloc_setting():
    """Under Dask's worker setting MALLOC_TRIM_THRESHOLD_=65536 every large array is a fresh
    mmap whose pages fault in; after ``keep_freed_memory`` (every map task calls it) freed
    arrays are reused: the page faults of 50 allocations of 8 MB drop > 10x."""
    import subprocess
    import sys

    code = (
        "import resource, numpy as np\n"
        "from numerics.maps._blocks import keep_freed_memory\n"
        "def faults():\n"
        "    r0 = resource.getrusage(resource.RUSAGE_SELF).ru_minflt\n"
        "    for _ in range(50):\n"
        "        a = np.ones(1 << 20)\n"
        "        del a\n"
        "    return resource.getrusage(resource.RUSAGE_SELF).ru_minflt - r0\n"
        "before = faults()\n"
        "assert keep_freed_memory()\n"
        "faults()\n"
        "print(before, faults())\n")
    env = dict(__import__("os").environ, MALLOC_TRIM_THRESHOLD_="65536")
    out = subprocess.run([sys.executable, "-c", code], env=env, capture_output=True,
                         text=True, check=True).stdout.split()
    before, after = int(out[0]), int(out[1])
    assert before > 5000 and after * 10 < before, (before, after)


def test_overwrite_discards_this_maps_store_and_replaces_another(tmp_path):
    import zarr

    maps.open_or_create(tmp_path / "map.zarr", _params())
    zarr.open_group(str(tmp_path / "map.zarr"), mode="r+")["done"][0, 0] = True
    # the same map with --overwrite: computed afresh, its finished cell discarded and said
    # (it resumed before: a user who says --overwrite expects the old cells gone)
    seen = []
    ds = maps.open_or_create(tmp_path / "map.zarr", _params(), overwrite=True,
                             log=seen.append)
    assert len(seen) == 1 and "discarded (1 finished cell of its map)" in seen[0]
    assert not ds["done"].values.any()
    ds = maps.open_or_create(tmp_path / "map.zarr", _params(t_end=3000.0), overwrite=True)
    assert ds.attrs["t_end"] == 3000.0


def test_a_stale_consolidated_metadata_is_rebuilt_by_the_next_run(tmp_path):
    # .zmetadata that is valid JSON but lacks a variable: xr.open_zarr fails on it until
    # the next run of the same map (which has nothing left to do) rebuilds it
    import json

    import xarray as xr

    params = _params(theory_only=True)
    maps.run_map(params, tmp_path, workers=1, log=lambda *_: None, progress=False)
    meta_file = tmp_path / "map.zarr" / ".zmetadata"
    meta = json.loads(meta_file.read_text())
    del meta["metadata"]["growth_predicted/.zarray"]
    meta_file.write_text(json.dumps(meta))
    with pytest.raises(Exception):  # noqa: B017 - whatever zarr raises, the store is unread
        xr.open_zarr(tmp_path / "map.zarr")["growth_predicted"].values  # noqa: B018
    maps.run_map(params, tmp_path, workers=1, log=lambda *_: None, progress=False)
    with xr.open_zarr(tmp_path / "map.zarr") as ds:
        assert ds["done_predicted"].values.all() and ds["growth_predicted"].notnull().all()


def _chunk_files(array_dir) -> dict:
    """{chunk key: file bytes} of a zarr v2 array (its metadata files left out)."""
    return {f.name: f.read_bytes() for f in array_dir.iterdir() if not f.name.startswith(".")}


def _random_values(rng, like):
    """Values of ``like``'s dtype and shape, the fill value among them for small dtypes."""
    if like.dtype == bool:
        return rng.random(like.shape) > 0.5
    if like.dtype.kind == "i":
        return rng.integers(-1, 2, like.shape).astype(like.dtype)
    if like.dtype.kind == "u":
        return rng.integers(0, 2**62, like.shape).astype(like.dtype)
    return rng.random(like.shape)


def test_the_client_writes_the_chunks_zarr_would_write(tmp_path):
    """The client writes its blocks' chunks itself (zarr v2: the codec's encoding of the
    chunk's C-order bytes): the files equal, byte for byte, those zarr writes for the same
    values - a whole chunk, the last chunk of a row partly outside the grid (3 columns in
    chunks of 2: its padding is the fill value in both), a single cell of a chunk (a map's
    last blocks go a cell at a time), a write across a whole and an edge chunk, and a chunk
    set back to the fill value alone, which neither stores (zarr's write_empty_chunks
    False) - and zarr reads them back."""
    import zarr

    params = _params(k=tuple(2 * np.pi * np.array([11, 13, 15]) / N), block=2)
    ours, theirs = tmp_path / "ours" / "map.zarr", tmp_path / "theirs" / "map.zarr"
    for path in (ours, theirs):
        maps.open_or_create(path, params)
    with xr.open_zarr(ours, consolidated=False, chunks=None) as ds:
        arrays = {n: ds[n].values.copy() for n in ds.data_vars}
    names = ("growth", "done", "verdict_simulated", "checksum")
    # the store's fill values (growth NaN; the others none given, which zarr reads as 0)
    fill = {"growth": np.nan, "done": False, "verdict_simulated": 0, "checksum": 0}
    writer = maps._CellWriter(ours)
    assert set(names) <= set(writer.direct)
    rng = np.random.default_rng(7)
    for cells, values in [((slice(0, 1), slice(0, 2)), "random"),  # chunk 0.0, whole
                          ((slice(1, 2), slice(2, 3)), "random"),  # 1.1: the edge chunk
                          ((slice(0, 1), slice(2, 3)), "random"),  # 0.1: the edge chunk
                          ((slice(1, 2), slice(0, 1)), "random"),  # a cell of 1.0
                          ((slice(1, 2), slice(1, 3)), "random"),  # across 1.0 and 1.1
                          ((slice(0, 1), slice(0, 2)), "fill")]:  # 0.0 back to the fill
        region = {}
        for name in names:
            a = arrays[name]
            a[cells] = (_random_values(rng, a[cells]) if values == "random" else fill[name])
            region[name] = a[cells]
        writer.write(region, cells, arrays)
        group = zarr.open_group(str(theirs), mode="r+")
        for name, values in region.items():
            group[name][cells] = values
    for name in names:
        mine, zarrs = _chunk_files(ours / name), _chunk_files(theirs / name)
        assert sorted(mine) == sorted(zarrs), name
        assert "0.0" not in mine, name  # the fill value alone: not stored (and removed)
        assert "1.1" in mine or name == "done", name  # done's 1.1 may hold False alone
        for key in mine:
            assert mine[key] == zarrs[key], (name, key)
        back = zarr.open_group(str(ours), mode="r")[name][...]
        np.testing.assert_array_equal(back, arrays[name])
        np.testing.assert_array_equal(back, zarr.open_group(str(theirs), mode="r")[name][...])


@pytest.mark.parametrize("dtype, fill", [("<f8", "NaN"), ("<f8", 0.25), ("|i1", -1),
                                         ("<u8", None), ("|b1", None)])
def test_the_client_writes_edge_chunks_in_both_dimensions_as_zarr_does(tmp_path, dtype, fill):
    """A zarr v2 array of 5 x 7 in chunks of 2 x 3 (the map store's chunks are one row,
    so only this array has edge chunks across rows): the client's chunk files equal zarr's
    byte for byte after writes of a whole chunk, the corner chunk (one cell inside the
    grid), a region across whole, partly written, edge and corner chunks, and a stored
    chunk set back to the fill value (removed by both); the chunks never written are
    absent in both."""
    import zarr

    shape = (5, 7)
    fill_value = {"NaN": np.nan, None: 0}.get(fill, fill)  # what a read of it gives
    ours, theirs = tmp_path / "ours", tmp_path / "theirs"
    for path in (ours, theirs):
        zarr.open_group(str(path), mode="w", zarr_format=2).create_array(
            "x", shape=shape, chunks=(2, 3), dtype=dtype,
            fill_value=np.nan if fill == "NaN" else fill)
    writer = maps._CellWriter(ours)
    assert "x" in writer.direct
    x = np.full(shape, fill_value, dtype)
    rng = np.random.default_rng(3)
    for cells, values in [((slice(0, 2), slice(0, 3)), "random"),  # chunk 0.0, whole
                          ((slice(4, 5), slice(6, 7)), "random"),  # 2.2: one cell in the grid
                          ((slice(2, 5), slice(2, 7)), "random"),  # 1.0 to 2.2: 5 partial
                          ((slice(2, 4), slice(3, 6)), "fill")]:  # 1.1 back to the fill
        x[cells] = _random_values(rng, x[cells]) if values == "random" else fill_value
        if values == "random" and dtype == "|b1":
            x[cells][0, 0] = True  # a value other than the fill in every write
        writer.write({"x": x[cells]}, cells, {"x": x})
        zarr.open_group(str(theirs), mode="r+")["x"][cells] = x[cells]
    mine, zarrs = _chunk_files(ours / "x"), _chunk_files(theirs / "x")
    assert sorted(mine) == sorted(zarrs)
    # 1.1 set back to the fill; rows 0-1 of columns 3-6 (0.1, 0.2) never written
    assert sorted(mine) == ["0.0", "1.0", "1.2", "2.0", "2.1", "2.2"]
    for key in mine:
        assert mine[key] == zarrs[key], key
    np.testing.assert_array_equal(zarr.open_group(str(ours), mode="r")["x"][...], x)


def test_an_array_with_nested_chunk_keys_is_written_by_zarr(tmp_path):
    """A zarr v2 array whose chunk keys are nested ("i/j", dimension_separator "/") is not
    written by the client itself (its chunk files would need folders it does not make):
    zarr writes it, and it reads back."""
    import zarr

    zarr.open_group(str(tmp_path), mode="w", zarr_format=2).create_array(
        "x", shape=(5, 7), chunks=(2, 3), dtype="<f8", fill_value=np.nan,
        chunk_key_encoding={"name": "v2", "separator": "/"})
    writer = maps._CellWriter(tmp_path)
    assert "x" not in writer.direct
    x = np.full((5, 7), np.nan)
    cells = (slice(1, 5), slice(2, 7))
    x[cells] = np.arange(20.0).reshape(4, 5)
    writer.write({"x": x[cells]}, cells, {"x": x})
    assert (tmp_path / "x" / "2" / "2").is_file()
    np.testing.assert_array_equal(zarr.open_group(str(tmp_path), mode="r")["x"][...], x)
