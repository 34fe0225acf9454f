"""Issue 44 item 1: every model command says how long it will take before the work (from one
cell measured on this machine) and reports its progress during it. Whether the estimate is
within 2x of the wall time is a benchmark (``python -m bench.maps --estimates``), not a timed
test: the machine is shared."""

from __future__ import annotations

import math
import time

import pytest

from cli.app import main as cli


def _lines(text: str) -> list[str]:
    return [ln for ln in text.splitlines() if ln.strip()]


def test_a_model_map_prints_its_estimate_before_the_work_and_its_wall_after(tmp_path, capsys):
    assert cli(["map", "--model", "fput", "--param", "alpha=1", "--param", "beta=0.8,1.6",
                "--k", "2.6,2.8", "--amplitude", "0.1", "--theory-only", "--workers", "1",
                "--out", str(tmp_path / "m")]) == 0
    out = _lines(capsys.readouterr().out)
    est = [i for i, ln in enumerate(out) if ln.startswith("estimate: about ")]
    done = [i for i, ln in enumerate(out) if ln.startswith("predicted 4 cells in ")]
    assert len(est) == 1 and len(done) == 1 and est[0] < done[0], out
    assert "one cell measured here: theories" in out[est[0]]
    # the cells' line says the command's wall time beside the estimate, to compare them
    assert "; the command so far " in out[done[0]] and ", estimated " in out[done[0]]


def test_a_simulated_model_point_prints_its_estimate_and_wall(tmp_path, capsys):
    assert cli(["point", "--model", "fput", "--param", "alpha=1", "--param", "beta=1.5",
                "--k", "2.5", "--amplitude", "0.1", "--N", "32", "--simulate", "--seeds", "2",
                "--t-end", "300"]) == 0
    out = _lines(capsys.readouterr().out)
    # the first line before any work (the theories, a first compile), then the estimate
    assert out[0].startswith("point: the theories, then an estimate of the 2 run(s)")
    assert out[1].startswith("estimate: about ") and "2 run(s) of T = 300 on N = 32" in out[1]
    assert out[2].startswith("took ") and "after the estimate (estimated " in out[2]
    assert out[3].startswith("model:")


def test_a_model_map_reports_progress_for_every_cell(tmp_path):
    """run_map's progress callable is told each finished block's cells: they add up to the
    map's cells, each block counted once."""
    from numerics.maps import ModelMapParameters, run_map

    params = ModelMapParameters.from_model("fput", ("beta", [0.8, 1.6]),
                                           ("k", [2.4, 2.6, 2.8]), 0.1,
                                           params={"alpha": 1.0}, theory_only=True, block=2)
    seen = []
    ds = run_map(params, tmp_path, workers=1, progress=seen.append, log=lambda *_: None)
    assert sum(seen) == 6 and sorted(seen) == [1, 1, 2, 2]  # blocks of up to 2 k per row
    assert ds["done_predicted"].values.all()


def test_a_run_reports_progress_for_every_step():
    """simulate_model's on_steps hears of every step, in stretches, ending at the run's
    step count."""
    from energy import load_model
    from numerics.models import simulate_model

    told = []
    run = simulate_model(load_model("fput", alpha=1.0, beta=1.5), 2.5, 0.1, N=32, t_end=50.0,
                         records=10, on_steps=lambda n, total: told.append((n, total)))
    nsteps = told[0][1]
    assert {t for _, t in told} == {nsteps} and sum(n for n, _ in told) == nsteps
    assert nsteps == math.ceil(50.0 / run.dt - 1e-9)
    assert len(told) >= 10  # a stretch per record: the bar moves as the run does


def test_the_model_estimate_counts_cells_seeds_workers_and_load(monkeypatch):
    """The estimate's parts: the cells' theories and runs at the measured cost of one
    (given here), the seeds' runs, shared by the workers, the start-up alone, all slowed
    by the measured share of the cores."""
    import dataclasses

    from numerics.maps import ModelCellCost, ModelMapParameters, estimate_model_map
    from numerics.maps import _estimate as e

    monkeypatch.setattr(e, "load_slowdown", lambda workers: (1.0, 0.0, 2))
    p = ModelMapParameters.from_model("fput", ("beta", [0.8, 1.2, 1.6]), ("k", [2.6, 2.8]),
                                      0.1, params={"alpha": 1.0}, N=64, seeds=1)
    cost = ModelCellCost(theory=0.5, run=2.0, t_end=1000.0, warmup=1.0, probe=0.1)
    one = estimate_model_map(p, 1, cost=cost)
    assert one.predict == pytest.approx(6 * 0.5) and one.simulate == pytest.approx(6 * 2.0)
    assert one.startup > cost.warmup  # the cluster's start besides the kernels
    seeds = estimate_model_map(dataclasses.replace(p, seeds=3), 1, cost=cost)
    assert seeds.simulate == pytest.approx(3 * one.simulate)
    two = estimate_model_map(p, 2, cost=cost)
    assert two.seconds - two.startup == pytest.approx((one.seconds - one.startup) / 2)
    theory = estimate_model_map(dataclasses.replace(p, theory_only=True), 1, cost=cost)
    assert theory.simulate == 0 and theory.seconds < one.seconds
    monkeypatch.setattr(e, "load_slowdown", lambda workers: (3.0, 7.0, 2))
    assert estimate_model_map(p, 1, cost=cost).seconds == pytest.approx(3 * one.seconds)


def test_the_share_of_a_core_is_measured():
    from numerics.maps._estimate import cpu_share

    share = cpu_share(0.05)
    assert 0 < share <= 1


def test_one_cell_of_a_model_map_is_measured_here():
    """probe_model_cell: its theories and a run's cost are positive CPU times, the run's T
    the map's."""
    from numerics.maps import ModelMapParameters, probe_model_cell

    p = ModelMapParameters.from_model("fput", ("beta", [0.8, 1.6]), ("k", [2.6, 2.8]), 0.1,
                                      params={"alpha": 1.0}, N=32, t_end=200.0)
    cost = probe_model_cell(p)
    assert cost.theory > 0 and cost.run > 0 and cost.t_end == 200.0 and cost.warmup >= 0
    theory_only = probe_model_cell(ModelMapParameters.from_model(
        "fput", ("beta", [0.8, 1.6]), ("k", [2.6, 2.8]), 0.1, params={"alpha": 1.0},
        theory_only=True))
    assert theory_only.run == 0 and theory_only.t_end == 0


def test_a_run_without_its_energy_records_the_same_run():
    """A map cell's runs skip the energy (its kernel compiles in every worker and no column
    uses it): the records the cell's columns come from are the same to the last bit, the
    energy NaN."""
    from energy import load_model
    from numerics.models import simulate_model

    model = load_model("fput", alpha=1.0, beta=1.5)
    with_e, without = (simulate_model(model, 2.5, 0.1, N=32, t_end=50.0, records=20,
                                      energy=e) for e in (True, False))
    assert (with_e.spectrum == without.spectrum).all()
    assert (with_e.deviation == without.deviation).all() and (with_e.t == without.t).all()
    assert with_e.growth() == without.growth()
    assert math.isfinite(with_e.energy_drift) and math.isnan(without.energy_drift)


def test_the_model_probe_leaves_the_theories_compile_out(monkeypatch):
    """A machine whose numba cache is empty compiles the ring's theories in the probe's
    first cell (33 s on a fresh H200 host against 0.5 s a cell): the probe pays that in
    its warm-up, not as every cell's cost (a 1024-cell map was said to take ~35 min where
    its cells take ~1 min). Here a first ring call that burns 0.3 s of CPU stands for the
    compile, with the probe's threshold for slow cells lowered to 0.2 s."""
    from numerics.maps import ModelMapParameters, probe_model_cell
    from numerics.maps import _estimate as e

    compiled = []

    def fake_map_cells(model, cells, amplitude, branch=None, *, exact=False, **kw):
        if exact and not compiled:  # the compile: CPU time, as numba's
            compiled.append(1)
            t0 = time.process_time()
            while time.process_time() - t0 < 0.3:
                pass
        return [{"peak_gain_exact": float("nan")} for _ in cells]

    monkeypatch.setattr("numerics.models.map_cells", fake_map_cells)
    monkeypatch.setattr(e, "PROBE_MORE_BELOW", 0.2)
    p = ModelMapParameters.from_model("fput", ("beta", [0.8, 1.6]), ("k", [2.6, 2.8]), 0.1,
                                      params={"alpha": 1.0}, N=64, theory_only=True,
                                      exact=True)
    cost = probe_model_cell(p)
    assert compiled and cost.warmup >= 0.3 and cost.theory < 0.1, cost
