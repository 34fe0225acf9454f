"""`flexmm point --model ... --out`: point.png and the sigma(q) curves, as the paper
chain's point writes them (issue 44, item 3)."""

from __future__ import annotations

import json
import subprocess
import sys


def _point(tmp_path, *argv):
    out = tmp_path / "p"
    proc = subprocess.run([sys.executable, "-m", "cli", "point", *argv, "--out", str(out)],
                          capture_output=True, text=True)
    assert proc.returncode == 0, proc.stderr
    return out, json.loads((out / "point.json").read_text())


def test_model_point_writes_the_figure_and_every_theorys_curve(tmp_path):
    out, data = _point(tmp_path, "--model", "fput", "--param", "alpha=1", "--param",
                       "beta=1.5", "--k", "2.5", "--amplitude", "0.1", "--N", "64")
    assert (out / "point.png").stat().st_size > 10_000
    curves = data["curves"]
    assert {"semi-discrete NLS", "exact lattice", "four-wave"} <= set(curves)
    for name in ("semi-discrete NLS", "exact lattice", "four-wave"):
        c = curves[name]
        assert len(c["offset"]) == len(c["curve"]) > 10
    # the exact curve's peak is the exact row's peak gain (the ring's offsets)
    exact = [g for g in curves["exact lattice"]["curve"] if g is not None]
    assert max(exact) == data["exact lattice"]["peak_gain"]


def test_model_point_simulated_sigma_of_q_matches_the_exact_rate(tmp_path):
    out, data = _point(tmp_path, "--model", "fput", "--param", "alpha=1", "--param",
                       "beta=1.5", "--k", "3.1", "--amplitude", "0.1", "--N", "64",
                       "--simulate", "--seeds", "2")
    assert (out / "point.png").is_file()
    sim = data["curves"]["simulated"]
    assert len(sim["q"]) == len(sim["sigma"]) == 33
    peak = data["exact lattice"]["peak_gain"]
    assert abs(max(sim["sigma_by_offset"]) / peak - 1) < 0.1
