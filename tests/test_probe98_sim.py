"""What probe 98 of the model simulator found (bench/probe_sim98.py runs all its checks;
the model texts and their energies by hand in bench/_sim98_models.py):

- a ``dt`` past the method's stability limit ran silently: a cosine-bond chain (top
  frequency 2.39) at dt = 5 with srkn11b grew its energy 520x, at dt = 1e6 7e27x, and the
  run returned as sound;
- the default step followed the linear branches only: a start state far stiffer than the
  chain at rest (a Morse bond compressed to r = -2, local frequency ~84 where the branches
  end at 3) ran at omega dt ~ 8 and lost 4.7% of its energy without a word.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from bench import _sim98_models as H
from energy import ModelError, load_model, parse_model


def _model(name):
    return load_model(parse_model(H.FILES[name], f"{name}.toml"))


@pytest.mark.parametrize("dt", [5.0, 1e6])
def test_a_step_past_the_stability_limit_is_refused(dt):
    """pend's top frequency is sqrt(w0^2 + 4 K) = sqrt(0.49 + 5.2) = 2.385 (by hand);
    srkn11b's limit omega dt = 3.14: any dt above 3.14 / 2.385 = 1.32 is unstable.
    Before: the run returned, energy 520x (dt 5) or 7e27x (dt 1e6) its start."""
    from numerics.models import simulate_model

    with pytest.raises(ModelError) as exc:
        simulate_model(_model("pend"), 1.0, 0.3, N=16, t_end=50.0, dt=dt, records=1)
    msg = str(exc.value)
    assert "\n" not in msg and msg.startswith(f"dt = {dt:g} is past the stability limit")
    top = math.sqrt(0.49 + 4 * 1.3)
    limit = float(msg.split("give dt below ")[1].split(",")[0])
    # the advice is the limit over the top frequency to its 3 printed digits
    assert limit == pytest.approx(3.1414310877528093 / top, rel=5e-3)


def test_a_step_below_the_limit_still_runs():
    """dt = 1.3, just below pend's 1.32: stable, energy conserved by the symplectic method
    to 1e-6 (measured 2.4e-9 at omega dt = 3.1, near the limit where the error is large)."""
    from numerics.models import simulate_model

    r = simulate_model(_model("pend"), 1.0, 0.3, N=16, t_end=50.0, dt=1.3, records=1)
    u, v = r.state
    assert abs(H.energy("pend", u, v) - r.energy[0]) / r.energy[0] < 1e-6


def test_the_default_step_follows_a_stiff_start_state():
    """A Morse chain (D 0.5, b 1.5) started from u_n = (-1)^n, at rest: every other bond
    sits at r = -2, stiffness V'' = 2 D b^2 (2 e^{-2 b r} - e^{-b r}) = 2.25 (2 e^6 - e^3)
    = 1770 (by hand), the others at r = 2 (V'' = -0.11): the pair across a stiff bond
    moving apart has the local frequency sqrt(2 V'') = 59.5, where the branches end at
    3.01; the step must be 0.2 of srkn11b's limit over 1.1 times it. The hand
    energy (bench._sim98_models) must be conserved to 1e-7 (srkn11b at a fifth of its
    limit: measured 3.5e-9 now). Before: dt 0.097 (omega dt ~ 8, past the limit), energy
    off by 4.7e-2."""
    from numerics.models import simulate_model

    N = 16
    x = np.where(np.arange(N) % 2 == 0, 1.0, -1.0)[None, :]
    r = simulate_model(_model("morse"), math.pi, 0.1, N=N, t_end=50.0, noise=0.0,
                       initial=(x, np.zeros((1, N))), records=1)
    Vpp = 2.25 * (2 * math.exp(6) - math.exp(3))
    # 2%: the soft bond's and the site's -0.11 + 0.09 + 1.5 u^2 beside 2 V'' = 3540 move
    # the frequency by 0.02%; the power iteration reaches the top from below (measured 0.3%)
    assert r.dt == pytest.approx(0.2 * 3.1414310877528093 / (1.1 * math.sqrt(2 * Vpp)),
                                 rel=2e-2)
    u, v = r.state
    E0 = H.energy("morse", x, np.zeros((1, N)))
    assert abs(H.energy("morse", u, v) - E0) / E0 < 1e-7


def test_the_default_step_is_unchanged_near_rest():
    """Near rest the local frequency is the branches' top: the step stays the old rule's
    0.2 limit / (1.1 omega_top + omega) (by hand for pend: omega_top 2.385, the carrier
    omega ~ 1.37 at k 1, a 0.3), to 1e-12 (a float's round-off over the snapping)."""
    from numerics.models import simulate_model, travelling_wave

    m = _model("pend")
    r = simulate_model(m, 1.0, 0.3, N=16, t_end=20.0, records=1)
    w = travelling_wave(m, r.k, 0.3).omega
    want = 0.2 * 3.1414310877528093 / (1.1 * math.sqrt(5.69) + w)
    assert r.dt == pytest.approx(20.0 / math.ceil(20.0 / want), rel=1e-12)


def _damped_reference(gamma, u0, v0, T):
    """The damped98 chain's equations written by hand (bond force r + alpha r^2 + beta
    r^3, site w0^2 u, damping gamma v and eta's discrete Laplacian of v), integrated by
    scipy's Radau (implicit, for the stiff damping) at rtol 1e-11."""
    from scipy.integrate import solve_ivp

    N = u0.shape[1]

    def rhs(t, y):
        u, v = y[:N], y[N:]
        r = np.roll(u, -1) - u
        f = r + 0.4 * r**2 + r**3
        return np.concatenate([v, f - np.roll(f, 1) - 0.25 * u - gamma * v
                               + 0.002 * (np.roll(v, -1) - 2 * v + np.roll(v, 1))])

    y = solve_ivp(rhs, (0, T), np.concatenate([u0[0], v0[0]]), method="Radau", rtol=1e-11,
                  atol=1e-14).y[:, -1]
    return y[None, :N], y[None, N:]


@pytest.mark.parametrize("method, bar", [("rk4", 1e-8), ("srkn11b", 5e-2)])
def test_the_default_step_follows_a_strong_damping(method, bar):
    """damped98 with site damping gamma = 100 (100x its top frequency 2.06): overdamped.
    The run's energy at T = 20 against the hand equations' (Radau): rk4 (order 4, at
    c dt = 0.57 of the damping's rate: measured 2.5e-12, bar 1e-8), the SRKN Strang
    splitting (order 2 in c dt = 0.63: measured 2.0e-2, bar 5e-2). Before: the step
    followed the oscillation only (dt 0.16-0.18): rk4 blew up by t = 0.48, srkn11b ended
    at E = 1.1e-3 where the chain keeps 0.131."""
    from numerics.models import simulate_model

    m = _model("damped").with_params(gamma=100.0)
    N = 16
    rng = np.random.default_rng(98)
    x = 0.2 * np.cos(2 * math.pi * 3 * np.arange(N) / N)[None, :]
    u0, v0 = x + 0.002 * rng.standard_normal((1, N)), 0.01 * rng.standard_normal((1, N))
    r = simulate_model(m, 2 * math.pi * 3 / N, 0.2, N=N, t_end=20.0, initial=(u0, v0),
                       noise=0.0, method=method, records=1)
    E = H.energy("damped", *r.state)
    E_ref = H.energy("damped", *_damped_reference(100.0, u0, v0, 20.0))
    assert abs(E - E_ref) / E_ref < bar


def test_a_damping_flow_that_underflows_runs():
    """gamma = 1e4 at a given dt = 0.2: the damping's exact flow over dt/2, exp(-1000),
    underflows to 0 at every wavenumber; the velocities are gone after each half step.
    Before: numpy's 'zero-size array to reduction operation maximum' from the flow's
    kernel. Now the run ends, its hand energy below the start's (the damping only takes)."""
    from numerics.models import simulate_model

    m = _model("damped").with_params(gamma=1e4)
    r = simulate_model(m, 1.0, 0.2, N=16, t_end=2.0, dt=0.2, records=1)
    u, v = r.state
    assert np.all(np.isfinite(u)) and H.energy("damped", u, v) < r.energy[0]


def test_a_shifted_start_runs_the_shifted_run():
    """The default step now reads the start state (its local frequency); a start shifted
    by one site must still give the shifted end, bit for bit (the same arithmetic on
    shifted data: every probe model measured 0.0). A Morse chain at a = 0.3, where the
    start state sets the step: a random power-iteration start made the two steps differ
    and the ends by 4.4e-9 (a guard of this change; the old step read no state)."""
    from numerics.models import simulate_model

    m = _model("morse")
    r0 = simulate_model(m, 1.0, 0.3, N=32, t_end=0.01, noise=1e-2, records=1)
    u0, v0 = r0.state
    a = simulate_model(m, 1.0, 0.3, N=32, t_end=20.0, noise=0.0, initial=(u0, v0), records=1)
    b = simulate_model(m, 1.0, 0.3, N=32, t_end=20.0, noise=0.0, records=1,
                       initial=(np.roll(u0, 1, axis=1), np.roll(v0, 1, axis=1)))
    assert a.dt == b.dt
    assert np.array_equal(np.roll(a.state[0], 1, axis=1), b.state[0])


def test_a_wave_past_its_range_is_refused_promptly():
    """Probe 98: a Morse wave at a 2, k pi (past the branch's range) took 120-340 s CPU to be
    refused: the least-squares fallback ran 200 (n + 1) evaluations with a finite-difference
    Jacobian (16 184 Jacobians of 64 residuals each). It now uses the exact Jacobian, at most
    100 + 4 n evaluations: ~0.7 s. The bar, 30 s CPU, is a hang guard (40x the time now,
    4x below the old one on an idle machine), not a benchmark."""
    import time

    from numerics.models import travelling_wave

    model = load_model(parse_model(H.FILES["morse"]))
    t0 = time.process_time()
    with pytest.raises(ModelError, match="no travelling wave of amplitude 2"):
        travelling_wave(model, math.pi, 2.0)
    assert time.process_time() - t0 < 30

