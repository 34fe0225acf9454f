"""The four-wave theory in model maps (issue 43, item 1): its columns where the map computes
the exact theory, equal to ``four_wave`` at the cells, its panel in the figure, and a store
made before the columns existed refused, saying so."""

from __future__ import annotations

import json
import math

import matplotlib.figure
import numpy as np
import xarray as xr

from cli.app import main
from energy import load_model
from numerics.maps import MODE_KIND_CODES, VERDICT_CODES
from numerics.models import four_wave

ARGV = ["map", "--model", "fput", "--param", "alpha=1", "--param", "beta=0.8,1.6",
        "--k", "2.6,2.8", "--amplitude", "0.1", "--N", "32", "--theory-only", "--exact",
        "--workers", "1"]


def test_the_four_wave_columns_are_four_wave_at_the_cells(tmp_path, capsys, monkeypatch):
    titles = []
    monkeypatch.setattr(matplotlib.figure.Figure, "savefig",
                        lambda fig, *a, **kw: titles.extend(ax.get_title() for ax in fig.axes))
    assert main([*ARGV, "--out", str(tmp_path), "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert "verdict_fourwave" in out["mi_share"]
    assert any("four-wave" in t for t in titles) and len(titles) == 3
    with xr.open_zarr(tmp_path / "map.zarr") as ds:
        assert ds.attrs["theories"] == "semidiscrete exact fourwave"
        assert ds["verdict_fourwave"].dtype == "int8"
        assert ds["mode_kind_fourwave"].dtype == "int8"
        assert "flag_meanings" in ds["mode_kind_fourwave"].attrs
        for i, beta in enumerate(ds["beta"].values):
            for j, k in enumerate(ds["k"].values):
                fw = four_wave(load_model("fput", alpha=1.0, beta=float(beta)), float(k), 0.1,
                               N=32)
                assert ds["verdict_fourwave"].values[i, j] == VERDICT_CODES[fw.verdict]
                assert ds["mode_kind_fourwave"].values[i, j] == MODE_KIND_CODES[fw.mode_kind]
                got = float(ds["peak_gain_fourwave"].values[i, j])
                assert math.isclose(got, fw.gain, rel_tol=1e-12, abs_tol=0.0)
        # either side of this chain's critical beta, as the exact theory
        assert ds["verdict_fourwave"].values.tolist() == [[0, 0], [1, 1]]
        assert (ds["mode_kind_fourwave"].values[1] > 0).all()


def test_a_store_without_the_four_wave_columns_is_refused(tmp_path, capsys):
    import zarr

    assert main([*ARGV, "--out", str(tmp_path)]) == 0
    capsys.readouterr()
    # a store made before the four-wave columns existed: its theories are the two
    group = zarr.open_group(str(tmp_path / "map.zarr"), mode="r+")
    group.attrs["theories"] = "semidiscrete exact"
    zarr.consolidate_metadata(str(tmp_path / "map.zarr"))
    assert main([*ARGV, "--out", str(tmp_path)]) == 2
    err = capsys.readouterr().err
    assert "of other theories" in err and "four-wave" in err and "--overwrite" in err
    assert main([*ARGV, "--out", str(tmp_path), "--overwrite"]) == 0
    with xr.open_zarr(tmp_path / "map.zarr") as ds:
        assert np.isfinite(ds["peak_gain_fourwave"].values).all()


def test_a_lossy_map_stores_each_theory_s_amplification(tmp_path, capsys, monkeypatch,
                                                       fput_lossy):
    """Issue 42 item 5: a map over a damping parameter and k of a lossy model stores
    amplification_<theory> per cell, and the figure marks the observable cells (>= 20x)."""
    from numerics.models import (
        exact_amplification,
        four_wave_amplification,
        nls_amplification,
        snap_ring,
    )

    path = tmp_path / "chain.toml"
    path.write_text(fput_lossy)
    marks = []

    def savefig(fig, *a, **kw):
        # what the panels share is said once above them (the figure's suptitle)
        shared = fig.get_suptitle()
        for ax in fig.axes:
            title = shared + " | " + ax.get_title()
            n = sum(len(c.get_offsets()) for c in ax.collections[1:])
            marks.append((title, n))

    monkeypatch.setattr(matplotlib.figure.Figure, "savefig", savefig)
    argv = ["map", "--model", str(path), "--param", "gamma=0.002,0.02", "--k", "2.6,2.8",
            "--amplitude", "0.1", "--N", "32", "--theory-only", "--exact", "--workers", "1",
            "--out", str(tmp_path / "m")]
    assert main(argv) == 0
    capsys.readouterr()
    with xr.open_zarr(tmp_path / "m" / "map.zarr") as ds:
        assert ds.attrs["amplification"] == "semidiscrete exact fourwave"
        for i, gamma in enumerate(ds["gamma"].values):
            for j, k in enumerate(ds["k"].values):
                m = load_model(str(path), gamma=float(gamma))
                # the ring's k for every theory (the NLS's too, as point's)
                k_ring = snap_ring(float(k), 32)[0]
                want = {"semidiscrete": nls_amplification(m, k_ring, 0.1),
                        "exact": exact_amplification(m, float(k), 0.1, N=32),
                        "fourwave": four_wave_amplification(m, float(k), 0.1, N=32)}
                for theory, a in want.items():
                    got = float(ds[f"amplification_{theory}"].values[i, j])
                    assert math.isclose(got, a.amplification, rel_tol=1e-9), theory
        # weak damping: the sidebands grow past 20x; ten times more: they do not
        for theory in ("semidiscrete", "exact", "fourwave"):
            obs = ds[f"amplification_{theory}"].values >= 20
            assert obs.tolist() == [[True, True], [False, False]]
    assert len(marks) == 3 and all("observable" in t and n == 2 for t, n in marks)
    # the store of a lossy model names its amplification columns: one without is refused
    import zarr

    group = zarr.open_group(str(tmp_path / "m" / "map.zarr"), mode="r+")
    del group.attrs["amplification"]
    zarr.consolidate_metadata(str(tmp_path / "m" / "map.zarr"))
    assert main(argv) == 2
    assert "amplification columns" in capsys.readouterr().err
