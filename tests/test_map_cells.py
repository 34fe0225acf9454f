"""Map cells as accurate as their verdict needs: the step chosen for the growth factor's
accuracy, recorded in the store's attributes; the growth factor at that step against a
tight reference; the error model's order; the early stop."""

import numpy as np
import pytest

from common import paper
from numerics import Material, get_method
from numerics.lattice import GROWTH_THRESHOLD
from numerics.maps import (
    GROWTH_ERROR_CONSTANTS,
    GROWTH_TOL,
    MapParameters,
    cell_records,
    growth_of,
    simulate_cell,
)

N, T = 100, 2000.0
# cells of the fig3 plane (alpha = 2.5) at N = 100: the blue point's k, one stable, one MI
MI_CELL = ("coupled", 0.003, 2 * np.pi * 13 / N)
STABLE_CELL = ("rotation", 0.003, 2 * np.pi * 13 / N)


def _mat(delta):
    return Material(paper.ALPHA, paper.K_S, paper.K_S - delta)


def _curve(rec, n):
    U = rec["U_hat"]
    return np.array([growth_of(rec["t"][:j + 1], rec["theta_hat"][:j + 1],
                               None if U is None else U[:j + 1], rec["m"], N, T)["growth"]
                     for j in range(1, n)])


def test_the_map_step_is_chosen_for_the_growth_accuracy_and_recorded():
    params = MapParameters(case="coupled", alpha=paper.ALPHA, K_s=paper.K_S,
                           delta=(-0.003, 0.003), k=(0.8, 1.2), amplitude=0.02)
    attrs = params.attrs()
    # the cheapest method for 1% on the growth factor is the order-6 SRKN, at a step far
    # above the paper's RK4 dt = 0.05 (the carrier's phase error does not enter |theta_hat|)
    assert attrs["method"] == "srkn11b" and attrs["dt"] > 0.5
    assert attrs["growth_tol"] == GROWTH_TOL and "chosen" in attrs["step"]
    # ... and below the method's stability limit at the lattice's highest frequency
    mat = Material(paper.ALPHA, paper.K_S, paper.K_S + 0.003)
    assert attrs["dt"] < get_method("srkn11b").stability_limit() / mat.omega_max("coupled")
    given = MapParameters(case="coupled", alpha=paper.ALPHA, K_s=paper.K_S, delta=(0.003,),
                          k=(0.8,), amplitude=0.02, method="rk4", dt=0.05).attrs()
    assert (given["method"], given["dt"], given["step"]) == ("rk4", 0.05, "given")
    with pytest.raises(ValueError, match="method"):
        MapParameters(case="coupled", alpha=paper.ALPHA, K_s=paper.K_S, delta=(0.003,),
                      k=(0.8,), amplitude=0.02, method="dop853")


@pytest.mark.parametrize("cell", [MI_CELL, STABLE_CELL], ids=["MI", "stable"])
def test_growth_at_the_chosen_step_is_the_tight_reference_s(cell):
    """The default step against srkn11b at dt = 0.1 (its own growth error ~1e-9): the
    verdict is the same and the growth factor, at every record up to the reference's
    early stop, within GROWTH_TOL (calibrated at N = 500, T = 5000: this is N = 100,
    T = 2000, another setting)."""
    case, delta, k = cell
    ref = cell_records(_mat(delta), case, k, N, T, dt=0.1, method="srkn11b")
    rec = cell_records(_mat(delta), case, k, N, T, early_stop=False, stop_at=len(ref["t"]) - 1)
    # an SRKN at 7x the reference's step or more (srkn6b here: srkn11b's step is capped by
    # its stability limit at omega_max = 2 of case II, which makes it the dearer of the two)
    assert rec["method"] in GROWTH_ERROR_CONSTANTS and rec["dt"] > 0.7
    g_ref, g = _curve(ref, len(ref["t"])), _curve(rec, len(ref["t"]))
    assert np.max(np.abs(g - g_ref) / g_ref) < GROWTH_TOL
    assert (g_ref.max() > GROWTH_THRESHOLD) == (g.max() > GROWTH_THRESHOLD) == (case == "coupled")


def test_growth_error_falls_with_the_method_s_order():
    """The error model's form, e ~ dt^p: the growth curve error of srkn11b at two steps
    1.6x apart falls by 1.6^6 = 17 (accepted 8-35: the error is a maximum over records,
    not a smooth function of dt)."""
    case, delta, k = MI_CELL
    ref = cell_records(_mat(delta), case, k, N, T, dt=0.1, method="srkn11b")
    n = len(ref["t"])
    g_ref = _curve(ref, n)
    errs = []
    for dt in (2.0, 1.25):
        rec = cell_records(_mat(delta), case, k, N, T, dt=dt, method="srkn11b",
                           early_stop=False, stop_at=n - 1)
        errs.append(np.max(np.abs(_curve(rec, n) - g_ref) / g_ref))
    assert 8 < errs[0] / errs[1] < 35, errs


def test_early_stop_keeps_the_verdict_and_stops_at_the_crossing():
    case, delta, k = MI_CELL
    early = simulate_cell(_mat(delta), case, k, N, T)
    full = simulate_cell(_mat(delta), case, k, N, T, early_stop=False)
    assert early["verdict_simulated"] and full["verdict_simulated"] and early["stopped_early"]
    assert not full["stopped_early"] and early["t_simulated"] < full["t_simulated"] == T
    # stopped at the first record whose growth exceeds the threshold: one record earlier
    # it did not
    rec = cell_records(_mat(delta), case, k, N, T)
    n = len(rec["t"])
    g = _curve(rec, n)
    assert g[-1] > GROWTH_THRESHOLD and g[-2] <= GROWTH_THRESHOLD
    assert early["growth"] == pytest.approx(g[-1], rel=1e-12)
    assert (early["method"], early["dt"]) == (rec["method"], rec["dt"])


def test_linear_stage_needs_one_e_folding_of_growth():
    """A rate is fitted only over a window in which the largest sideband grows e-fold: a run
    that passes 5x its start in its last samples gets no linear stage (its slope there is
    noise), a clean exponential gets the window from 5x to 1% of the carrier."""
    from numerics.lattice import growth_rates, linear_stage

    N, m = 64, 8
    t = np.arange(0.0, 2000.0, 5.0)
    spec = np.full((t.size, N // 2 + 1), 1e-6)
    spec[:, m] = 1.0
    spec[:, m + 3] = 1e-4 * np.exp(2e-3 * t)  # 5x at T = 805, 1% of the carrier at 2303
    win = linear_stage(spec, m, N)
    assert win is not None and t[win[0]] == pytest.approx(805.0, abs=5.0)
    np.testing.assert_allclose(growth_rates(t, spec, win)[m + 3], 2e-3, rtol=1e-9)
    # the same growth stopped at 5.9x: 5x is passed, e-fold after it never is
    late = spec.copy()
    late[:, m + 3] = 1e-4 * np.minimum(np.exp(2e-3 * t), 5.9)
    assert linear_stage(late, m, N) is None
    # a high noise floor (1e-3 of the carrier): 5x to the 1% ceiling is only 2x, but the
    # window ends at the ceiling, so it is a linear stage
    loud = spec.copy()
    loud[:, m + 3] = 1e-3 * np.exp(2e-3 * t)
    win = linear_stage(loud, m, N)
    assert win is not None
    np.testing.assert_allclose(growth_rates(t, loud, win)[m + 3], 2e-3, rtol=1e-9)
