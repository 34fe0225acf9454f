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
