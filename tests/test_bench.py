"""Fast parts of `make stress` as assertions, and a smoke run of `make bench-quick`.

bench/ is a package (imported from the repository root, pyproject's pytest pythonpath);
its scripts run as ``python -m bench.<script>``."""

import json
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from bench import simulator, stress

ROOT = Path(__file__).resolve().parents[1]


@pytest.mark.parametrize("case,mat", [("coupled", stress.BLUE), ("rotation", stress.GREEN)])
def test_rk4_stability_limit_is_the_predicted_one(case, mat):
    # bisection of the largest bounded dt on a random lattice state vs 2 sqrt 2 / omega_max;
    # 5% is the tolerance (measured: 0.1%)
    dt, pred = stress.largest_stable_dt("rk4", mat, case, t_end=1000.0)
    assert dt == pytest.approx(pred, rel=0.05)


def test_verlet_stability_limit_is_the_predicted_one():
    dt, pred = stress.largest_stable_dt("verlet", stress.GREEN, "rotation", t_end=1000.0)
    assert dt == pytest.approx(pred, rel=0.05)


def test_blow_up_and_bad_input_are_reported():
    checks = stress.bad_input_checks()
    assert all(c["pass"] for c in checks), [c for c in checks if not c["pass"]]


def test_bench_writes_outside_the_git_tree_unless_asked(tmp_path):
    # default: out/bench/ (gitignored); the committed bench/ only with --update
    assert simulator.output_dir() == ROOT / "out" / "bench"
    assert simulator.output_dir(update=True) == ROOT / "bench"
    assert simulator.output_dir(out=tmp_path) == tmp_path
    assert simulator.arguments(argv=["--quick"]) == (True, ROOT / "out" / "bench")
    assert simulator.arguments(argv=["--update"]) == (False, ROOT / "bench")
    with pytest.raises(SystemExit):
        simulator.arguments(argv=["--update", "--out", str(tmp_path)])


def test_results_sections_are_merged(tmp_path):
    simulator.write_section("a", {"x": 1}, True, tmp_path)
    simulator.write_sections({"b": 2, "c": 3}, True, tmp_path)
    simulator.write_section("a", {"x": 4}, True, tmp_path)
    assert json.loads((tmp_path / "results_quick.json").read_text()) == {
        "a": {"x": 4}, "b": 2, "c": 3}


def test_bench_quick_smoke(tmp_path):
    # make bench-quick's work-precision part (< 1 min), as `make` runs it, into tmp_path
    subprocess.run([sys.executable, "-m", "bench.work_precision", "--quick", "--out",
                    str(tmp_path)], check=True, cwd=ROOT, capture_output=True, timeout=120)
    res = json.loads((tmp_path / "results_quick.json").read_text())
    rows = res["work_precision"]["blue-II"]["rows"]
    assert {r["method"] for r in rows} >= {"rk4", "srkn11b", "dop853", "numpy-rk4"}
    assert res["work_precision"]["blue-II"]["reference_difference"] < 1e-8


def test_error_budget_quick(tmp_path):
    # bench/error_budget.py (make bench's evaluation counts to 1e-6) at T = 50, into tmp_path
    subprocess.run([sys.executable, "-m", "bench.error_budget", "--quick", "--out",
                    str(tmp_path)], check=True, cwd=ROOT, capture_output=True, timeout=300)
    res = json.loads((tmp_path / "results_quick.json").read_text())["error_budget"]
    ev = res["evaluations_to_target"]
    # the dt interpolated from the sweep lands on the target (within 30%: the sweep's
    # log-log line is fitted over a factor 4 in dt, where the order-6 slope holds)
    for name in ("srkn6b", "srkn11b", "kahanli8"):
        assert abs(np.log(ev[name]["error"] / res["target"])) < np.log(1.3), name
    # order 6 needs fewer evaluations than order 4 at 1e-6 on this problem
    assert ev["srkn11b"]["evaluations"] < ev["srkn6b"]["evaluations"]
    for b in res["budget"].values():
        assert 0 <= b["share_at_theta_carrier"] + b["share_at_U_2k"] <= 1 + 1e-12
    assert res["bound"] is None  # no speed section in tmp_path to bound against
