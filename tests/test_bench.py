"""Fast parts of `make stress` as assertions, and a smoke run of `make bench-quick`."""

import json
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "bench"))

import stress  # noqa: E402


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


def test_bench_quick_smoke(tmp_path):
    # make bench-quick's work-precision part (< 1 min): it runs and writes its json
    subprocess.run([sys.executable, str(ROOT / "bench" / "work_precision.py"), "--quick"],
                   check=True, cwd=ROOT, capture_output=True, timeout=120)
    res = json.loads((ROOT / "bench" / "results_quick.json").read_text())
    rows = res["work_precision"]["blue-II"]["rows"]
    assert {r["method"] for r in rows} >= {"rk4", "srkn11b", "dop853", "numpy-rk4"}
    assert res["work_precision"]["blue-II"]["reference_difference"] < 1e-8
