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


def test_model_point_exact_curve_shows_each_mode_once(tmp_path):
    """An FPUT chain at k near 2.5 (issue 44 walkthrough): the Hill spectrum on the ring
    repeats the sideband mode at +-q + l k (a band at Q = 1.47 - 2.36 of the same rate);
    the curve keeps the mode at its own offset, lists the copies, and keeps the row's
    peak gain and fastest offset."""
    import math

    _, data = _point(tmp_path, "--model", "fput", "--param", "alpha=0", "--param", "beta=1",
                     "--k", "2.5", "--amplitude", "0.2", "--N", "64")
    k, row = data["k"], data["exact lattice"]
    c = data["curves"]["exact lattice"]
    unstable = [(q, g) for q, g in zip(c["offset"], c["curve"]) if g is not None and g > 0]
    assert max(g for _, g in unstable) == row["peak_gain"]
    assert any(abs(q - row["fastest_offset"]) < 1e-9 for q, g in unstable
               if g == row["peak_gain"])
    # the copies are left out: every unstable offset kept lies in one band near the
    # carrier (the NLS's band is below 1 rad/site here), none past 1.4
    assert max(q for q, _ in unstable) < 1.0
    assert c["copy_of"] and "copies" in c["note"]

    def wrap(x):
        return (x + math.pi) % (2 * math.pi) - math.pi

    kept = {round(q, 12) for q, _ in unstable}
    for copy, orig in c["copy_of"]:
        assert round(orig, 12) in kept and round(copy, 12) not in kept
        # a copy is +-orig + l k on the ring (k and the offsets are multiples of 2 pi / N)
        assert min(abs(wrap(copy - s * orig - ell * k)) for s in (1, -1)
                   for ell in range(-3, 4)) < 1e-9
    # the copy the walkthrough saw: Q = k - 0.589 at the same rate
    assert any(abs(cp - (k - row["fastest_offset"])) < 1e-9 for cp, _ in c["copy_of"])
