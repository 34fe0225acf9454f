"""The one stepper of any lattice with a compiled force (``numerics.lattice.ForceStepper``):
every fixed-step method of the registry at its order, the damped RK4 and the Strang
splitting against exact solutions of a linear chain, and a blow-up reported as such."""

from __future__ import annotations

import math
import os
import re
import subprocess
import sys

import numpy as np
import pytest
from numba import njit

from numerics.lattice import METHODS, ForceStepper, get_method, local_flow

N = 16
MODE = 3
K = 2 * math.pi * MODE / N
OMEGA = 2 * math.sin(K / 2)  # u'' = u_{n+1} - 2 u_n + u_{n-1}: omega(k) = 2 sin(k / 2)
FIXED = [m for m in METHODS if get_method(m).fixed_step]


@njit
def chain_force(u, p, out, S):
    """p[0] (u_{n+1} - 2 u_n + u_{n-1}), one field."""
    n_ = u.shape[1]
    for n in range(n_):
        out[0, n] = p[0] * (u[0, (n + 1) % n_] - 2 * u[0, n] + u[0, n - 1])


@njit
def blowing_force(u, p, out, S):
    """A force that overflows once |u| passes 1: u'' = u^3 grows without bound."""
    for n in range(u.shape[1]):
        out[0, n] = u[0, n] ** 3 * 1e300


def _mode(t, gamma=0.0):
    """The travelling mode cos(k n - w t) of the chain, damped at rate gamma where the
    chain is (u'' = Lu - 2 gamma u': each mode decays as exp(-gamma t))."""
    n = np.arange(N)
    w = math.sqrt(OMEGA**2 - gamma**2)
    ph = K * n - w * t
    e = math.exp(-gamma * t)
    u = e * np.cos(ph)
    v = e * (w * np.sin(ph) - gamma * np.cos(ph))
    return u[None, :].copy(), v[None, :].copy()


def _error(method, dt, t_end=20.0, damping=None, flow=None, gamma=0.0):
    u, v = _mode(0.0, gamma)
    nsteps = round(t_end / dt)
    st = ForceStepper(chain_force, np.array([1.0]), 0, u, v, get_method(method),
                      t_end / nsteps, damping=damping, flow=flow)
    assert st.advance(nsteps) == nsteps
    return float(np.max(np.abs(u - _mode(t_end, gamma)[0])))


@pytest.mark.parametrize("method", FIXED)
def test_every_fixed_step_method_converges_at_its_order(method):
    m = get_method(method)
    # steps from a fifth of the stability limit down, where the error is above round-off
    # (1e-10 at the smallest step for the order 8 method) and in its asymptotic regime
    h0 = 0.2 * m.stability_limit() / OMEGA
    dts = [h0, h0 / 2, h0 / 4]
    errs = [_error(method, dt) for dt in dts]
    slope = np.polyfit(np.log(dts), np.log(errs), 1)[0]
    # the fitted slope of log(error) against log(dt) is the order to within 0.3 (the
    # pre-asymptotic higher-order terms at the largest step shift it by less)
    assert abs(slope - m.order) < 0.3, (method, errs, slope)


def test_rk4_with_a_velocity_force_is_the_same_loop():
    """Zero damping through the damped path gives the lossless path's numbers bit for bit;
    a damping gamma gives the exact damped mode at order 4."""
    d0 = (np.zeros((1, 1)), np.zeros((2, 2)), np.ones(1))
    u1, v1 = _mode(0.0)
    u2, v2 = _mode(0.0)
    rk4 = get_method("rk4")
    ForceStepper(chain_force, np.array([1.0]), 0, u1, v1, rk4, 0.1).advance(100)
    ForceStepper(chain_force, np.array([1.0]), 0, u2, v2, rk4, 0.1, damping=d0).advance(100)
    np.testing.assert_array_equal(u1, u2)
    gamma = 0.05
    damp = (np.array([[2 * gamma]]), np.zeros((2, 2)), np.ones(1))  # R = gamma v^2
    dts = [0.2, 0.1, 0.05]
    errs = [_error("rk4", dt, damping=damp, gamma=gamma) for dt in dts]
    slope = np.polyfit(np.log(dts), np.log(errs), 1)[0]
    assert abs(slope - 4) < 0.3, (errs, slope)


@pytest.mark.parametrize("method", ["verlet", "srkn11b"])
def test_strang_splitting_of_a_site_damping_is_second_order(method):
    gamma = 0.05
    damp = (np.array([[2 * gamma]]), np.zeros((2, 2)), np.ones(1))
    dts = [0.2, 0.1, 0.05]
    errs = []
    for dt in dts:
        h = (20.0 / round(20.0 / dt)) / 2
        flow = (local_flow, (np.array([[math.exp(-2 * gamma * h)]]),))
        errs.append(_error(method, dt, damping=damp, flow=flow, gamma=gamma))
    slope = np.polyfit(np.log(dts), np.log(errs), 1)[0]
    assert abs(slope - 2) < 0.3, (method, errs, slope)


def test_a_damped_srkn_run_needs_its_flow_and_a_blow_up_stops_the_loop():
    u, v = _mode(0.0)
    damp = (np.eye(1), np.zeros((2, 2)), np.ones(1))
    with pytest.raises(ValueError, match="flow"):
        ForceStepper(chain_force, np.array([1.0]), 0, u, v, get_method("srkn11b"), 0.1,
                     damping=damp)
    with pytest.raises(ValueError, match="fixed-step"):
        ForceStepper(chain_force, np.array([1.0]), 0, u, v, get_method("dop853"), 0.1)
    for method in ("rk4", "verlet"):
        u, v = _mode(0.0)
        st = ForceStepper(blowing_force, np.array([1.0]), 0, 3 * u, v, get_method(method),
                          0.1)
        assert st.advance(1000) < 1000


@njit
def identity_flow(v, args):
    """A flow that leaves v as it is: ForceStepper then takes its generic SRKN loop."""


@pytest.mark.parametrize("case", ["coupled", "rotation"])
@pytest.mark.parametrize("method", ["srkn11b", "verlet"])
def test_the_fused_forces_cached_srkn_loop_is_the_generic_one_bit_for_bit(case, method):
    """The paper chain's fused forces step in an SRKN loop of their own, cached on disk
    (the generic loop takes its force as an argument and is compiled in every process):
    the same states, to the last bit, as the generic loop (identity flow), over a run
    long enough (2000 steps) for any difference in an operation's rounding to show."""
    from numerics.lattice import flexmm_force, flexmm_rotation_force

    force, d = (flexmm_force, 2) if case == "coupled" else (flexmm_rotation_force, 1)
    rng = np.random.default_rng(7)
    u0 = 0.3 * rng.standard_normal((d, 64))
    v0 = 0.05 * rng.standard_normal((d, 64))
    p = np.array([2.5 ** 2, 0.01851, 0.016])  # (alpha^2, K_s, K_theta), the paper's case II
    runs = []
    for flow in (None, (identity_flow, ())):
        st = ForceStepper(force, p, 3, u0.copy(), v0.copy(), get_method(method), 0.05,
                          flow=flow)
        assert st.advance(2000) == 2000
        runs.append((st.u, st.v, st.evaluations))
    (u1, v1, e1), (u2, v2, e2) = runs
    assert np.array_equal(u1, u2) and np.array_equal(v1, v2) and e1 == e2
    assert np.max(np.abs(u1 - u0)) > 1e-3  # the state moved: the comparison means something


def test_the_fused_forces_srkn_loops_load_from_numbas_disk_cache(tmp_path):
    """Why those loops exist: a second process loads them from Numba's disk cache instead
    of compiling them (a loop built as a closure over its force, or called with the force
    as a value, compiles anew in every process). Two fresh processes on an empty cache
    folder; Numba's cache log (NUMBA_DEBUG_CACHE) says what each saved and loaded."""
    script = (
        "import numpy as np\n"
        "from numerics.lattice import (ForceStepper, flexmm_force, flexmm_rotation_force,\n"
        "                              get_method)\n"
        "p = np.array([6.25, 0.01851, 0.016])\n"
        "for f, d in ((flexmm_force, 2), (flexmm_rotation_force, 1)):\n"
        "    u, v = 0.1 * np.ones((d, 16)), np.zeros((d, 16))\n"
        "    ForceStepper(f, p, 3, u, v, get_method('verlet'), 0.05).advance(3)\n")
    env = dict(os.environ, NUMBA_DEBUG_CACHE="1", NUMBA_CACHE_DIR=str(tmp_path))
    logs = []
    for _ in range(2):
        out = subprocess.run([sys.executable, "-c", script], env=env, capture_output=True,
                             text=True, timeout=300, check=True)
        logs.append(out.stdout + out.stderr)
    for loop in ("_srkn_flexmm_steps", "_srkn_flexmm_rotation_steps"):
        saved = re.compile(rf"data saved to .*\.{loop}-")
        loaded = re.compile(rf"data loaded from .*\.{loop}-")
        assert saved.search(logs[0]), (loop, logs[0][-2000:])
        assert loaded.search(logs[1]) and not saved.search(logs[1]), (loop, logs[1][-2000:])
