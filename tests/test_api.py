"""The public API reads like SciPy's: plain values back, options as keywords, one name per
concept (issue 36 item 4)."""

from __future__ import annotations

import math
import time

import pytest

from numerics import snap_wavenumber


def test_snap_wavenumber_snaps_and_returns_a_float():
    k = snap_wavenumber(0.8, 500)
    assert isinstance(k, float) and k == pytest.approx(2 * math.pi * 64 / 500, rel=1e-15)
    assert snap_wavenumber(0.8, 500, return_index=True) == (k, 64)


def test_snap_wavenumber_strictness_is_an_option():
    assert snap_wavenumber(0.8, 500, rel_tol=1e-2) == snap_wavenumber(0.8, 500)
    with pytest.raises(ValueError, match="not commensurate.*0.804248"):
        snap_wavenumber(0.8, 500, rel_tol=1e-3)


@pytest.mark.parametrize("N, error", [(0, ValueError), (-100, ValueError), (True, TypeError),
                                      (8.0, TypeError)])
def test_snap_wavenumber_checks_N(N, error):
    with pytest.raises(error, match="N must"):
        snap_wavenumber(0.8, N)


def test_snap_wavenumber_refuses_a_nan_tolerance():
    with pytest.raises(ValueError, match="rel_tol"):
        snap_wavenumber(0.8, 500, rel_tol=float("nan"))


def test_a_runs_verdict_is_never_a_bare_stable():
    """issue 36 item 1: MI (measured rate), no growth within T (with the slowest rate that
    could show), or undetermined (grew, not to the threshold), from growth factors."""
    from numerics.lattice import VERDICT_WORDS, simulated_verdict

    mi = simulated_verdict([50.0, 60.0, 3.0], 20000.0, 4.9e-4)
    assert mi.word == "MI" and "4.9e-04" in f"{mi.rate:.1e}" and "measured rate" in str(mi)
    none = simulated_verdict([1.2, 1.5], 20000.0)
    assert none.word == "no growth within T"
    assert none.slowest_visible == pytest.approx(math.log(20) / 20000)
    assert "a rate below 0.00015 /T cannot show" in str(none)
    # a model's time is its file's: its runs' words say /time, as its tables say 1/time
    assert "a rate below 0.00015 /time cannot show" in str(
        simulated_verdict([1.2, 1.5], 20000.0, time_name="time"))
    assert "(measured rate 0.00049 /time)" in str(
        simulated_verdict([50.0, 60.0, 3.0], 20000.0, 4.9e-4, time_name="time"))
    grew = simulated_verdict([6.77, 10.2, 6.06, 10.7], 20000.0)  # issue 36's material
    assert grew.word == "undetermined" and "longer --t-end" in str(grew)
    assert simulated_verdict([], 100.0).word == "undetermined"
    assert {mi.word, none.word, grew.word} == set(VERDICT_WORDS)


def test_run_length_decides_within_its_cap_and_says_when_it_cannot():
    from numerics.lattice import T_CAP, run_length
    from numerics.lattice._verdict import DECIDE_E_FOLDINGS

    r = run_length(1.123e-4)  # issue 36: capped at 20 000 before, ~2 e-foldings
    assert not r.capped and r.rate * r.t_end >= DECIDE_E_FOLDINGS and r.t_end <= T_CAP
    slow = run_length(2e-5)
    assert slow.capped and slow.t_end == T_CAP
    assert f"--t-end {slow.decides_at:g} would" in slow.note()
    assert slow.decides_at * 2e-5 >= DECIDE_E_FOLDINGS
    assert run_length(0.0).t_end == 5000.0 and not run_length(float("nan")).capped


def test_the_machine_speed_leaves_the_first_calls_compile_out(monkeypatch):
    """The reference cell is timed warm: a first call that compiles (a machine with an
    empty numba cache: 2-4 s against 0.06 s) made a fresh machine's estimates 12-20x too
    long (a 64 x 64 map that took 4.5 min was said to take 63 min), and was cached so."""
    from numerics.maps import _estimate as e

    def slow_first(seconds):
        calls = []

        def fake(*args, **kwargs):
            if not calls:  # the compile: CPU time, as numba's
                t0 = time.process_time()
                while time.process_time() - t0 < seconds:
                    pass
            calls.append(1)
        return fake

    # where measure_speed imports them from
    monkeypatch.setattr("numerics.maps._cells.simulate_cell", slow_first(0.3))
    monkeypatch.setattr("numerics.maps._cells.predict_cell", slow_first(0.3))
    speed = e.measure_speed()
    # what is left is the fakes' own call: microseconds, floored at 1 ms
    assert speed["predict"] < 0.05 and speed["simulate"] < 0.05


def test_map_estimate_counts_start_up_cells_and_load(tmp_path, monkeypatch):
    """issue 36 item 2: the estimate is the command's wall time: start-up (cluster, imports,
    store) plus the cells at this machine's measured speed (cached once), slowed by the
    load average."""
    import dataclasses

    from numerics.maps import MapParameters
    from numerics.maps import _estimate as e

    monkeypatch.setenv("XDG_CACHE_HOME", str(tmp_path))
    calls = []
    monkeypatch.setattr(e, "measure_speed",
                        lambda: calls.append(1) or {"simulate": 0.02, "predict": 0.1})
    assert e.machine_speed() == e.machine_speed() == {"simulate": 0.02, "predict": 0.1}
    assert calls == [1] and (tmp_path / "flexmm-mi" / "speed.json").exists()
    monkeypatch.setattr(e, "load_slowdown", lambda workers: (1.0, 0.0, 2))
    p = MapParameters(case="coupled", alpha=2.5, K_s=0.01851, delta=(-0.003, 0.003),
                      k=(0.5, 0.8, 1.1, 1.4), amplitude=0.02, N=500, t_end=1000.0, seeds=1,
                      start="paper")
    est = e.estimate_map(p, 2)
    start = e.STARTUP_SECONDS["local"] + e.WORKER_WARMUP_SECONDS
    # issue 44 item 2: the client's theory columns are start-up too, and grow with the cells
    assert est.startup > start
    wider = e.estimate_map(dataclasses.replace(p, k=(0.5, 0.6, 0.8, 0.9, 1.1, 1.4)), 2)
    assert wider.startup > est.startup
    # a cell's prediction costs the reference cell's (0.1 s here) times a map cell's typical
    # share, more at larger k N (its Bloch families): the grid's k straddle the reference's
    # 0.73, so within 2x of it
    cell = 0.1 * e.PREDICT_CELL_OVER_REFERENCE
    assert 8 * cell / 2 < est.predict < 8 * cell * 2
    far = e.estimate_map(dataclasses.replace(p, k=(2.0, 2.2, 2.4, 2.6)), 2)
    assert far.predict > est.predict
    assert est.simulate > 0 and est.seconds == pytest.approx(est.startup
                                                             + (est.predict + est.simulate) / 2)

    theory = e.estimate_map(dataclasses.replace(p, theory_only=True), 2)
    assert theory.simulate == 0 and theory.seconds < est.seconds
    monkeypatch.setattr(e, "load_slowdown", lambda workers: (2.0, 3.0, 2))
    assert e.estimate_map(p, 2).seconds == pytest.approx(2 * est.seconds)


def test_runs_and_gain_spectra_convert_to_xarray_with_units_and_inputs(tmp_path):
    import numpy as np

    from numerics import Material, gain_spectrum, simulate

    mat = Material(2.0, 0.03, 0.02)
    k = snap_wavenumber(1.2, 64)
    run = simulate(mat, "coupled", 64, k, amplitude=0.04, t_end=5.0, store="spectrum")
    ds = run.to_xarray()
    assert set(ds.data_vars) >= {"theta_hat", "U_hat", "energy"}
    assert ds["theta_hat"].dims == ("t", "wavenumber")
    assert ds["wavenumber"].attrs["units"] == "rad per site"
    assert ds.attrs["K_theta"] == 0.02 and ds.attrs["start"] == "paper" and ds.attrs["k"] == k
    ds.to_zarr(tmp_path / "run.zarr", consolidated=False)
    spec = gain_spectrum(mat, "coupled", k, 0.04, np.linspace(0.05, 0.6, 5), start="travelling")
    g = spec.to_xarray(material=mat, case="coupled", k=k, amplitude=0.04)
    assert g["sigma"].dims == ("offset",) and g["sigma"].attrs["units"].startswith("1/T")
    assert g.attrs["alpha"] == 2.0 and g.attrs["amplitude"] == 0.04
    np.testing.assert_array_equal(g["sigma"].values, spec.sigma)
