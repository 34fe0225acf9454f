"""The one map engine under stress (round 95): interrupted maps that end as undisturbed
ones.

Tests that start clusters or send signals here run serially (the Makefile's SERIAL_TESTS)."""

from __future__ import annotations

import re

import numpy as np
import pytest


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
