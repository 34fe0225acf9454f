"""Probe 100's leftovers (bench/probe_leftovers100.py): what a demanding user still hit.

- ``flexmm point --simulate`` with the paper chain's flags said no run time before its
  runs, where ``--model`` points do: it now measures one short run of the ring with the
  runs' method and step and says ``estimate: about ...`` (and ``took ... after the
  estimate``), as a model point.
- A ring that misses a band of the infinite chain printed the band's peak rate read from
  the Hill offsets that found it (a Lennard-Jones chain: 10% low); now the band's maximum.
- A lossy model file at zero damping printed the loss lines (carrier damping 0, an
  unbounded amplification): ``Model.lossy`` is now whether anything is damped at the
  model's values, and the commands say the damping is zero and answer as the lossless
  chain.
"""

import json
import math
import time

import numpy as np
import pytest

from bench.probe_newuser99 import LJ  # the probe's copy of the file
from cli.app import main
from energy import load_model, parse_model

PAPER = ["--alpha", "2", "--K-s", "0.03", "--K-theta", "0.02", "--k", "1.2",
         "--amplitude", "0.04", "--case", "coupled"]


def test_a_paper_point_says_its_runs_estimate_before_them(capsys):
    assert main(["point", *PAPER, "--N", "64", "--simulate", "--seeds", "2",
                 "--t-end", "400"]) == 0
    out = capsys.readouterr().out.splitlines()
    est = [n for n, line in enumerate(out) if line.startswith("estimate: about ")]
    table = next(n for n, line in enumerate(out) if line.startswith("theory "))
    assert len(est) == 1 and est[0] < table, out
    assert "2 run(s) of T = 400 on N = 64 sites" in out[est[0]]
    assert any(line.startswith("took ") and "after the estimate" in line for line in out)


def test_the_paper_points_estimate_is_within_2x_of_its_runs_cpu():
    from numerics import Material
    from numerics.lattice import simulate
    from numerics.maps import estimate_paper_point, point_step, snap_carrier

    mat = Material(2.0, 0.03, 0.02)
    k = snap_carrier(1.2, 256)[0]
    t_end = 3000.0
    method, dt = point_step(mat, "coupled", 256, k, 0.04, "paper", t_end)
    est = estimate_paper_point(mat, "coupled", k, 0.04, N=256, start="paper", t_end=t_end,
                               seeds=1, method=method, dt=dt, save_every=5.0, figure=False)
    t0 = time.process_time()
    simulate(mat, "coupled", 256, k, amplitude=0.04, seed=1, t_end=t_end, dt=dt,
             method=method, save_every=5.0, start="paper", store="spectrum",
             energy_tolerance=1.0)
    cpu = time.process_time() - t0
    # the estimate is a measured 4000 of the run's steps scaled to all of them: CPU time
    # (not wall) on both sides, so only the probe's own noise (a time slice, caches) is
    # left: the 2x the user is promised
    assert 0.5 < est.run / cpu < 2.0, (est.run, cpu)




def test_a_missed_bands_peak_is_the_bands_maximum():
    from numerics.models import exact_gain, hill_spectrum, ring_misses, snap_ring

    model = load_model(parse_model(LJ))
    k = snap_ring(1.0, 128)[0]
    chain = exact_gain(model, k, 0.01)
    misses = ring_misses(model, 1.0, 0.01, N=128, chain=chain)
    assert misses  # two narrow bands (newuser99)
    for b in misses:
        lo, hi = b["band"]
        # the band's own maximum on a grid 1/4000 of its width: the peak's curvature
        # leaves (1/4000)^2 relative, far below the 1e-6 asked (the old reading: 10% low)
        q = np.linspace(lo, hi, 4001)
        top = float(np.max(hill_spectrum(chain.wave, q).gain))
        assert b["peak_gain"] == pytest.approx(top, rel=1e-6), (b, top)


ZERO = ["--model", "flexmm-lossy", "--param", "gamma_theta=0", "--param", "gamma_U=0"]


def test_a_lossy_file_at_zero_damping_is_the_lossless_chain():
    zero = load_model("flexmm-lossy", gamma_theta=0.0, gamma_U=0.0)
    assert zero.lattice.lossy and not zero.lossy
    assert zero.with_params(gamma_U=1e-6).lossy
    assert load_model("flexmm-lossy").lossy


def test_coefficients_and_point_at_zero_damping_answer_as_the_lossless_chain(capsys):
    assert main(["coefficients", *ZERO, "--k", "1", "--json"]) == 0
    zero = json.loads(capsys.readouterr().out)
    assert main(["coefficients", "--model", "flexmm", "--k", "1", "--json"]) == 0
    lossless = json.loads(capsys.readouterr().out)
    assert "carrier_damping" not in zero and "amplification" not in json.dumps(zero)
    for key in ("omega", "g1", "g2", "g"):
        assert zero[key] == lossless[key]
    assert main(["coefficients", *ZERO, "--k", "1"]) == 0
    text = capsys.readouterr().out
    assert "damping:  zero at these values (gamma_U = 0, gamma_theta = 0)" in text
    assert "carrier damping" not in text and "with losses" not in text
    assert main(["point", *ZERO, "--k", "1", "--N", "64"]) == 0
    text = capsys.readouterr().out
    assert "damping:  zero at these values" in text and "with losses" not in text
    assert "continuum NLS" in text  # the lossless chain's own extra theory


def test_a_map_of_zero_damping_is_lossless_and_a_damping_axis_from_zero_lossy():
    from numerics.maps import ModelMapParameters

    flat = ModelMapParameters.from_model("flexmm-lossy", ("K_theta", [0.01, 0.02]),
                                         ("k", [0.8, 1.2]), amplitude=0.02,
                                         params={"gamma_theta": 0.0, "gamma_U": 0.0},
                                         theory_only=True)
    assert not flat.lossy and flat.amplified() == ()
    axis = ModelMapParameters.from_model("flexmm-lossy", ("gamma_theta", [0.0, 0.01]),
                                         ("k", [0.8, 1.2]), amplitude=0.02,
                                         params={"gamma_U": 0.0}, theory_only=True,
                                         exact=True)
    assert axis.lossy and "exact" in axis.amplified()
    assert "paper" not in axis.theory_columns()  # damped cells have no continuum NLS


def _no_plane_wave_line(capsys, case, k):
    assert main(["point", "--alpha", "2.5", "--K-s", "0.01851", "--K-theta", "0.01551",
                 "--k", str(k), "--case", case, "--start", "paper", "--N", "200",
                 "--amplitude", "0.05"]) == 0
    # the paper start's row: its state is no torus (said without 'no plane wave' since
    # the travelling wave exists: that label is a NoPlaneWaveError's)
    return next(line for line in capsys.readouterr().out.splitlines()
                if line.startswith("exact lattice, paper start: ") and "not quasi-periodic"
                in line)


def test_eq_ic_not_quasi_periodic_in_case_i_names_its_counter_wave_not_u(capsys):
    import re

    line = _no_plane_wave_line(capsys, "rotation", 3.0)  # k snaps to 2 pi 95/200
    assert "omega_U" not in line  # case I freezes U (the old text named 2 Omega = omega_U(2k))
    m = re.search(r"\(([\d.]+) of its amplitude: theta_dot set by the frequency ([\d.]+), "
                  r"not the lattice's omega\(k\) = ([\d.]+)", line)
    assert m, line
    share, w_start, w = map(float, m.groups())
    k, mat = 2 * math.pi * 95 / 200, (2.5, 0.01851, 0.01551)
    assert w == pytest.approx(_omega_theta(k), rel=1e-3)
    # eq. `continuum2` by hand: eq. IC's theta_dot frequency alpha sqrt(6 K_theta + delta k^2)
    alpha, K_s, K_theta = mat
    assert w_start == pytest.approx(alpha * math.sqrt(6 * K_theta + (K_s - K_theta) * k**2),
                                    rel=1e-3)  # printed to 4 digits
    # theta = a cos(k n), theta_dot = a w_start sin(k n) is a wave at +k of (1 + w_start/w)/2
    # and one at -k of (1 - w_start/w)/2: their ratio, from the printed (4-digit) numbers
    assert share == pytest.approx(abs(w_start - w) / (w_start + w), rel=2e-2)


def _omega_theta(k, alpha=2.5, K_s=0.01851, K_theta=0.01551):
    """eq. `discrete2` by hand from the energy linearised at U = 0: omega^2 / alpha^2 =
    4 K_s sin^2(k/2) + 4 K_theta cos^2(k/2) + 2 K_theta."""
    return alpha * math.sqrt(4 * K_s * math.sin(k / 2)**2 + 4 * K_theta * math.cos(k / 2)**2
                             + 2 * K_theta)


def test_eq_ic_near_u_resonance_in_case_ii_names_it(capsys):
    line = _no_plane_wave_line(capsys, "coupled", 0.97)
    assert "2 Omega = omega_U(2k)" in line and "the wave at -k" not in line, line
    # by hand at k = 2 pi 31/200: omega_U(q) = 2 sin(q/2) (mass 4, bond 2 (dU)^2), the
    # detuning |2 omega - omega_U(2k)| / (2 omega), printed to 0.1%
    k = 2 * math.pi * 31 / 200
    w = _omega_theta(k)
    off = float(line.split("omega_U(2k), ")[1].split("%")[0]) / 100
    assert off == pytest.approx(abs(2 * w - 2 * math.sin(k)) / (2 * w), abs=1e-3)


@pytest.mark.parametrize("case", ["rotation", "coupled"])
@pytest.mark.parametrize("k", [0.5, 1.0, 2.0])
def test_the_paper_engines_frequency_shift_is_the_exact_waves(case, k):
    """nls_summary's frequency_shift is Omega - omega of the exact plane wave, as the model
    engine's: in case II at k 1 it had the other sign and 4.2x the size (the mean flow,
    which a uniform wave does not feel, counted)."""
    from generated import lattice_coefficients
    from numerics import Material
    from numerics.theory import nls_summary, plane_wave

    mat = Material(2.5, 0.01851, 0.01551)
    w0 = plane_wave(mat, case, k, 1e-6).omega
    d1, d2 = ((plane_wave(mat, case, k, a).omega - w0) / a**2 for a in (0.01, 0.02))
    c = (4 * d1 - d2) / 3  # the a^2 coefficient, the O(a^4) term cancelled
    s = nls_summary(mat, case, k, amplitude=1.0, nls=lattice_coefficients)
    # the fit's O(a^6) left: ~1e-4 relative measured (d1, d2 differ by 1e-2 .. 2e-1)
    assert s["frequency_shift"] == pytest.approx(c, rel=1e-3)


def test_a_model_maps_estimate_counts_its_end_after_the_cells():
    """The estimate is the command's wall time: after its cells a map writes its summary
    and figure and closes its cluster (2.4 s wall at load 5 on the 2-core VM, probe 100),
    which it did not count: with free cells on a given scheduler (no load read) the
    estimate is the start-up, the workers' warm-up and that end."""
    from numerics.maps import ModelCellCost, ModelMapParameters, estimate_model_map
    from numerics.maps._estimate import (
        MODEL_WORKER_WARMUP_SECONDS,
        STARTUP_SECONDS,
    )

    params = ModelMapParameters.from_model("fput", ("beta", [0.5, 1.0]), ("k", [1.0, 2.0]),
                                           0.1, theory_only=True)
    free = ModelCellCost(theory=0.0, run=0.0, t_end=0.0, warmup=0.0, probe=0.0)
    est = estimate_model_map(params, 2, "tcp://127.0.0.1:1", free)
    start = STARTUP_SECONDS["scheduler"] + MODEL_WORKER_WARMUP_SECONDS
    assert est.seconds >= start + 0.5  # the end: ~1 s of a core
