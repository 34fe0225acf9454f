"""Review 102 of the lossy exact theory's damping (``_losses_hill.mode_damping``), refereed
by the damped ring's time-domain monodromy (``bench._floquet102_ref``: the energy file
parsed and differentiated there, the whole ring's fundamental matrix integrated along the
held carrier), which shares nothing with the theory but the energy file."""

from __future__ import annotations

import math

import numpy as np
import pytest

from bench._floquet102_ref import RingReferee, monodromy, wave_state
from bench.probe_floquet102 import model_text
from energy import load_model
from numerics.models import exact_amplification, exact_gain, simulate_seeds

#: issue 41's bar, as test_floquet102: the damped Hill pencil and the damped ring's
#: monodromy are the same linear equations (the referee's own error ~1e-10 relative)
RTOL = 1e-6


def _net_and_damped(tmp_path, params, m, N, a):
    """(initial_gain, the damped ring's fastest monodromy rate) of flexmm-lossy."""
    path = tmp_path / "flexmm-lossy.toml"
    path.write_text(model_text("flexmm-lossy"))
    model = load_model(str(path), **params)
    k = 2 * math.pi * m / N
    spec = exact_gain(model, k, a, 0, N=N)
    ref = RingReferee(model_text("flexmm-lossy"), params, N)
    mu, _, T, _ = monodromy(ref, wave_state(spec.wave, N), spec.wave.omega)
    net = exact_amplification(model, k, a, 0, N=N, first=spec).initial_gain
    return spec, net, float((np.log(np.abs(mu)) / T).max())


def test_a_slower_mode_of_the_undamped_field_outgrows_the_damped_fastest(tmp_path):
    """Theta damped strongly, U not at all (k 2 pi 5/13, a 0.474, 13 sites): the fastest
    lossless mode at each offset (theta, 0.121-0.126) is damped to 0.01, but a slower
    growing mode at the same offsets holds less theta and nets 0.0547. Only the fastest
    was continued: initial_gain 0.0056 where the damped ring grows at 0.0547."""
    spec, net, damped = _net_and_damped(
        tmp_path, {"gamma_theta": 0.0387, "gamma_U": 0.0}, 5, 13, 0.474)
    assert spec.peak_gain > 0.1 and damped > 0.05  # the point's physics: both grow
    assert net == pytest.approx(damped, rel=RTOL)


@pytest.mark.xfail(strict=True, reason="review 102, not fixed: a lossless-neutral mode "
                   "of negative energy grows with the damping (dissipation-induced); "
                   "mode_damping continues only modes that grow without losses")
def test_a_neutral_mode_the_damping_destabilises(tmp_path):
    """Theta damped strongly, U not at all (k 2 pi 7/16, a 0.169, 16 sites): every
    lossless growing mode is damped below 0 (initial_gain -0.096, 'stable (damped)'), but
    a theta mode neutral without losses (lambda 1.2453i at q = pi/2) grows at a rate
    proportional to the damping (the dense damped pencil: 0.0022, 0.0042, 0.0077, 0.0128,
    0.0186 at 1/16, 1/8, 1/4, 1/2, 1 of it): the damped ring grows at 0.0178."""
    spec, net, damped = _net_and_damped(
        tmp_path, {"gamma_theta": 0.0431, "gamma_U": 0.0}, 7, 16, 0.169)
    assert damped > 0.01
    assert net == pytest.approx(damped, rel=RTOL)


def _theory_and_runs(gamma, a, **launch):
    """flexmm-lossy at k 1 on 64 sites: the exact theory's answer and 3 seeded runs."""
    model = load_model("flexmm-lossy", gamma_theta=gamma, gamma_U=gamma)
    spec = exact_gain(model, 1.0, a, 0, N=64)
    th = exact_amplification(model, 1.0, a, 0, N=64, first=spec)
    sim = simulate_seeds(model, 1.0, a, spec, branch=0, N=64, seeds=3,
                         t_end=2.5 * th.amplification_time, noise_on="carrier", **launch)
    logs = np.log([r.amplification().amplification for r in sim.runs])
    return th, logs


@pytest.mark.xfail(strict=True, reason="review 102, not fixed: the carrier decays at the "
                   "linear branch's Gamma in every theory; the nonlinear carrier, holding "
                   "U, decays slower")
def test_the_exact_amplification_follows_the_runs_carrier():
    """gamma 0.001 each, a 0.15: the theory's 339x at t 485 (a(t) = a0 e^{-Gamma t},
    Gamma 0.003125 = gamma_theta alpha^2 / 2, theta's linear branch); the runs (noise 1e-4
    on theta's positions) 2800-4000x at t 510-580. The runs' carrier's first harmonic
    decays at 0.0013 over t 0-100 (0.0028 at a 0.05, 0.0031 at a 0.02: the linear rate
    in the limit): at a 0.15 the wave holds U (its second harmonic near U's branch),
    damped 25x less than theta. Bar: the seeds' spread in ln plus ln 3 (a run starts from
    noise, of which the growing mode holds a share; the theory from the mode itself)."""
    th, logs = _theory_and_runs(0.001, 0.15, noise=1e-4)
    assert th.amplification > 100  # observable either way: a point where it is measured
    assert abs(math.log(th.amplification) - np.median(logs)) <= np.ptp(logs) + math.log(3)


@pytest.mark.xfail(strict=True, reason="review 102, not fixed: a damped run's default "
                   "launch noise lies below the damped carrier's departure from the "
                   "lossless wave family in a harmonic's mode (past OVER_DRIFT's bound)")
def test_a_damped_runs_amplification_is_its_sidebands():
    """gamma 0.003 each, a 0.15 (the exact theory 4.1x; the runs with noise 1e-4 1.6-3.0x):
    launched with the default noise (A(0) 3.5e-10) A(t) reaches ~7e-8 by t 20 in mode 16
    (harmonic 8 of m = 10, 45x its content |c_8|, past OVER_DRIFT's 10x) whatever the noise
    (1e-3: A stays ~3e-5), rising at ~0.3 per unit time where the ring's fastest mode
    grows at 0.04 (the monodromy): the runs read 170-180x, observable. The sidebands' own
    amplification is below the runs' 20x."""
    th, logs = _theory_and_runs(0.003, 0.15)
    assert th.amplification < 20
    assert np.median(logs) < math.log(20)


@pytest.mark.parametrize("N, a", [(18, 0.3733), (24, 0.2)])
def test_the_paper_chain_grows_where_exact_gain_said_stable(tmp_path, N, a):
    """flexmm (lossless, the file's parameters) at k 2 pi/N: exact_gain's peak was 0 at
    P 10 (the central pencil finds modes growing at 0.566 (N 18, a 0.3733) and 0.253
    (N 24, a 0.2) and the kept-mode rule dropped them, their weight reaching the outer
    harmonics; the dense pencil at P 10 has none) where the dense Hill pencil at P 12-20
    and the ring's monodromy grow (0.56638 at N 18: a rate past omega 0.347, no narrow
    band). 9 of 27 (k, a) of the paper chain at k <= 0.35, a >= 0.1 on 256 sites; now the
    whole spectrum again at P + 4 where such a mode was dropped and nothing kept."""
    path = tmp_path / "flexmm.toml"
    path.write_text(model_text("flexmm"))
    model = load_model(str(path))
    spec = exact_gain(model, 2 * math.pi / N, a, 0, N=N)
    ref = RingReferee(model_text("flexmm"), {}, N)
    mu, _, T, back = monodromy(ref, wave_state(spec.wave, N), spec.wave.omega)
    assert back < 1e-6  # the project's wave is a solution of the referee's ring
    assert spec.peak_gain == pytest.approx(float((np.log(np.abs(mu)) / T).max()), rel=RTOL)


def test_the_paper_chains_infinite_chain_grows_at_least_as_its_ring(tmp_path):
    """The infinite chain holds every offset of a ring of its k, so its peak is at least
    the ring's fastest monodromy rate (k 2 pi/24, a 0.2: 0.2535 on 24 sites); exact_gain
    on the chain read 0 there (the same dropped modes as the ring's, its samples never
    re-checked at P + 4)."""
    path = tmp_path / "flexmm.toml"
    path.write_text(model_text("flexmm"))
    model = load_model(str(path))
    ring = exact_gain(model, 2 * math.pi / 24, 0.2, 0, N=24)
    ref = RingReferee(model_text("flexmm"), {}, 24)
    mu, _, T, _ = monodromy(ref, wave_state(ring.wave, 24), ring.wave.omega)
    rate = float((np.log(np.abs(mu)) / T).max())
    chain = exact_gain(model, 2 * math.pi / 24, 0.2, 0)
    assert rate > 0.2 and chain.peak_gain >= rate * (1 - RTOL)
