"""A map cell's run stops where its linear stage has saturated (``until_saturated``): no
work the cell does not need, and the growth it measures is the whole run's, bit for bit.
The paper chain's cells stop early the same way (``numerics.maps.simulate_cell``)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from energy import load_model
from numerics.models import (
    exact_gain,
    map_cells,
    saturation_record,
    saturation_time,
    simulate_model,
)

#: (model, params, k, amplitude): MI points of a one- and a two-field model, and a stable
#: one (FPUT with alpha only: no MI anywhere), on rings of 64
POINTS = [("fput", dict(alpha=0.5, beta=1.0), 2 * np.pi * 20 / 64, 0.15),
          ("flexmm", dict(K_theta=0.016), 2 * np.pi * 9 / 64, 0.1),
          ("fput", dict(alpha=1.0, beta=0.0), 2 * np.pi * 20 / 64, 0.1)]


@pytest.mark.parametrize("name,params,k,a", POINTS)
def test_a_run_stopped_at_saturation_measures_the_whole_runs_growth(name, params, k, a):
    model = load_model(name, **params)
    spec = exact_gain(model, k, a, N=64)
    T = 1500.0
    whole = simulate_model(model, k, a, N=64, t_end=T, seed=3, wave=spec.wave)
    short = simulate_model(model, k, a, N=64, t_end=T, seed=3, wave=spec.wave,
                           until_saturated=True)
    s = saturation_record(whole.spectrum, 64, whole.k, whole.wave.harmonics, a)
    if spec.peak_gain > 0:
        # grown from 1e-8 of the amplitude to a tenth (~16 e-foldings) inside T here
        assert s is not None and short.t_end == whole.t[s] < T
        assert len(short.t) == s + 1
        # the same steps up to the stop: the records are the whole run's first ones
        np.testing.assert_array_equal(short.spectrum, whole.spectrum[:s + 1])
    else:
        assert s is None and short.t_end == T and len(short.t) == len(whole.t)
    g_whole, g_short = whole.growth(), short.growth()
    assert g_short == g_whole  # every field, bit for bit (the dataclass compares them)
    if spec.peak_gain > 0:
        assert g_whole.verdict == "unstable"
        # the measured rate is the exact one (a linear stage of ~16 e-foldings: 2%)
        assert g_whole.rate == pytest.approx(spec.peak_gain, rel=0.02)


def test_saturation_time_is_when_the_noise_reaches_saturation():
    assert saturation_time(0.01, noise=1e-8) == pytest.approx(math.log(0.1 / 1e-8) / 0.01)
    assert saturation_time(0.0) == math.inf and saturation_time(math.nan) == math.inf


def test_a_map_cell_reports_the_time_it_ran_and_the_same_verdict():
    """An MI cell's ``t_simulated`` is where its run stopped (< T), a cell whose run went
    the whole T says T; its rate is the point's (``simulate_model`` to T)."""
    model = load_model("fput", alpha=0.5, beta=1.0)
    ks = [2 * np.pi * 20 / 64, 2 * np.pi * 4 / 64]
    rows = map_cells(model, [({}, k) for k in ks], 0.15, exact=True, simulate=True, N=64,
                     t_end=1500.0)
    for k, row in zip(ks, rows):
        spec = exact_gain(model, k, 0.15, N=64)
        whole = simulate_model(model, k, 0.15, N=64, t_end=1500.0, seed=0, wave=spec.wave,
                               energy=False)
        g = whole.growth()
        if g.verdict == "unstable":
            assert row["verdict_simulated"] == "MI" and row["t_simulated"] < 1500.0
            assert row["peak_gain_simulated"] == g.rate
        else:
            assert row["t_simulated"] == 1500.0
        assert row["growth"] == g.factor
