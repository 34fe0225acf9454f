"""A model's run under the lattice's run control: Ctrl-C stops it between two compiled
calls, on a state whose time is known, keeping its records (SimulationInterrupted), as the
paper chain's runs do (tests/test_faults.py)."""

from __future__ import annotations

import os
import signal

import numpy as np
import pytest

from energy import load_model
from numerics.lattice import ForceStepper, SimulationInterrupted, _runcontrol
from numerics.models import ModelRun, simulate_model


@pytest.mark.parametrize("name,method", [("fput", "srkn11b"), ("flexmm-lossy", "rk4")])
def test_ctrl_c_keeps_a_model_runs_records_and_its_state(name, method, sigint_raises,
                                                         monkeypatch):
    monkeypatch.setattr(_runcontrol, "_WORK_PER_CALL", 1.0)  # one step per compiled call
    model = load_model(name)
    kw = dict(N=32, t_end=20.0, dt=0.1, records=10, seed=2, method=method)
    full = simulate_model(model, 1.0, 0.1, **kw)
    original = ForceStepper.advance
    calls = {"n": 0}

    def counting(self, n):
        calls["n"] += 1
        if calls["n"] == 57:  # the Ctrl-C comes during step 57: between records at 4 and 6
            os.kill(os.getpid(), signal.SIGINT)
        return original(self, n)

    monkeypatch.setattr(ForceStepper, "advance", counting)
    with pytest.raises(SimulationInterrupted) as info:
        simulate_model(model, 1.0, 0.1, **kw)
    monkeypatch.setattr(ForceStepper, "advance", original)
    exc = info.value
    assert exc.signum == signal.SIGINT and len(str(exc).splitlines()) == 1
    assert exc.time == pytest.approx(5.7) and exc.time + exc.remaining == pytest.approx(20.0)
    run = exc.run
    assert isinstance(run, ModelRun) and run.force == full.force
    np.testing.assert_array_equal(run.t, full.t[:3])  # records every 2.0: 0, 2, 4
    np.testing.assert_array_equal(run.spectrum, full.spectrum[:3])
    np.testing.assert_array_equal(run.energy, full.energy[:3])
    # the state is the one at exc.time: a run of 57 steps of the same dt from the same start
    part = simulate_model(model, 1.0, 0.1, N=32, t_end=57 * 0.1, dt=0.1, records=1, seed=2,
                          method=method)
    for a, b in zip(exc.state, part.state):
        # the same steps; dt = 5.7 / 57 may differ from 0.1 in its last bit (1e-16 of
        # each step's update): 1e-12 of the amplitude bounds the difference 100-fold
        np.testing.assert_allclose(a, b, rtol=0, atol=1e-13)
