"""The lattice simulator: orders, conservation, symmetries, dispersion, errors."""

import math

import numpy as np
import pytest

from common import paper
from generated import coefficients as co
from numerics import (
    METHODS,
    BlowUpError,
    LatticeState,
    Material,
    SimulationInterrupted,
    discrete_omega_longitudinal,
    discrete_omega_rotation,
    energy,
    get_method,
    initial_condition,
    integrate,
    simulate,
)
from numerics.lattice import accel

BLUE, GREEN = Material.paper("blue"), Material.paper("green")
FIXED = [m for m in METHODS if get_method(m).fixed_step]


def random_state(N=32, amp=0.4, seed=0, coupled=True):
    rng = np.random.default_rng(seed)
    n = np.arange(N)
    th = amp * np.cos(2 * np.pi * 3 * n / N) + 0.05 * rng.normal(size=N)
    w = 0.3 * rng.normal(size=N)
    if coupled:
        return LatticeState(0.05 * rng.normal(size=N), 0.05 * rng.normal(size=N), th, w)
    return LatticeState(None, None, th, w)


@pytest.fixture(scope="module")
def reference():
    """Strongly nonlinear coupled run to T = 10, by the order-6 method at a tiny step.

    Its own error (against half that step) is ~3e-14, far below every error measured.
    """
    s0 = random_state()
    ref = integrate(s0, BLUE, "coupled", 10.0, 0.0025, "srkn11b")
    return s0, ref


DT = {"rk4": [0.4, 0.2, 0.1, 0.05], "verlet": [0.1, 0.05, 0.025, 0.0125],
      "srkn6b": [0.4, 0.2, 0.1, 0.05], "srkn11b": [0.4, 0.2, 0.1, 0.05],
      # order 8: errors 1e-5 .. 4e-9 over these steps, far above the reference's ~3e-14
      "kahanli8": [0.4, 0.3, 0.2, 0.15]}


@pytest.mark.filterwarnings("ignore::numerics.AccuracyWarning")  # coarse steps on purpose
@pytest.mark.parametrize("method", FIXED)
def test_convergence_order(method, reference):
    s0, ref = reference
    dts = DT[method]
    errs = []
    for dt in dts:
        s = integrate(s0, BLUE, "coupled", 10.0, dt, method)
        errs.append(max(np.abs(s.theta - ref.theta).max(), np.abs(s.U - ref.U).max()))
    slope = np.polyfit(np.log(dts), np.log(errs), 1)[0]
    assert abs(slope - get_method(method).order) < 0.3, (slope, errs)


@pytest.mark.parametrize("method", METHODS)
def test_all_methods_agree_with_dop853(method, reference):
    s0, ref = reference
    tight = integrate(s0, BLUE, "coupled", 10.0, 0.1, "dop853", rtol=1e-13, atol=1e-15)
    assert np.abs(tight.theta - ref.theta).max() < 1e-11  # the reference itself
    dt = {"verlet": 0.001, "rk4": 0.01}.get(method, 0.02)
    s = integrate(s0, BLUE, "coupled", 10.0, dt, method, rtol=1e-11, atol=1e-13)
    # Verlet at 1e-3: error ~ C dt^2 ~ 1e-6 (from the order test's constant); others < 1e-8
    tol = 5e-6 if method == "verlet" else 1e-7
    assert np.abs(s.theta - tight.theta).max() < tol
    assert np.abs(s.U - tight.U).max() < tol


def test_integrate_does_not_modify_input():
    s0 = random_state()
    copy = [a.copy() for a in (s0.U, s0.U_dot, s0.theta, s0.theta_dot)]
    integrate(s0, BLUE, "coupled", 1.0, 0.1)
    for a, b in zip(copy, (s0.U, s0.U_dot, s0.theta, s0.theta_dot)):
        assert np.array_equal(a, b)


@pytest.mark.parametrize("method", ["verlet", "srkn6b", "srkn11b", "kahanli8"])
def test_symplectic_methods_are_reversible(method):
    s0 = random_state()
    s1 = integrate(s0, BLUE, "coupled", 20.0, 0.05, method)
    back = integrate(LatticeState(s1.U, -s1.U_dot, s1.theta, -s1.theta_dot), BLUE, "coupled",
                     20.0, 0.05, method)
    # exact in exact arithmetic; rounding accumulates over 400 steps to ~1e-13
    assert np.abs(back.theta - s0.theta).max() < 1e-11
    assert np.abs(-back.theta_dot - s0.theta_dot).max() < 1e-11
    assert np.abs(back.U - s0.U).max() < 1e-11


def _energy_errors(method, dt, t_end=2000.0):
    # these tests measure the energy error itself, at steps chosen large: no warning
    run = simulate(BLUE, "coupled", 64, 2 * np.pi * 8 / 64, eps=0.05, t_end=t_end, dt=dt,
                   method=method, save_every=10.0, store="energy", energy_tolerance=1.0)
    return run.t, run.relative_energy_error


def test_symplectic_energy_error_is_bounded_and_rk4_drifts():
    t, e_v = _energy_errors("verlet", 0.1)
    half = len(t) // 2
    # bounded oscillation: the second half is no worse than the first (no secular drift)
    assert e_v[half:].max() < 1.5 * e_v[:half].max()
    t, e_r = _energy_errors("rk4", 0.4)
    # RK4 is dissipative: its error grows roughly linearly in time
    slope = np.polyfit(t[1:], e_r[1:], 1)[0]
    assert slope > 0
    assert e_r[-1] > 1.5 * e_r[len(t) // 4]


def test_rk4_energy_drift_scales_as_dt_to_the_fifth():
    # RK4 damps an oscillator by (omega h)^6/72 per step, i.e. ~h^5 per unit time: halving
    # dt must divide the drift by 2^5 = 32 (measured 32.0; +-25% allows for noise modes).
    _, e1 = _energy_errors("rk4", 0.1, t_end=1000.0)
    _, e2 = _energy_errors("rk4", 0.05, t_end=1000.0)
    assert 24 < e1[-1] / e2[-1] < 40
    # the bound from the fastest mode (omega_max = 2, the U branch) holds
    assert e2[-1] < (2 * 0.05) ** 6 / 72 / 0.05 * 1000


@pytest.mark.parametrize("mat", [BLUE, GREEN], ids=["delta>0", "delta<0"])
def test_small_amplitude_wave_follows_discrete2(mat):
    N, m, a = 64, 13, 1e-7
    q = 2 * np.pi * m / N
    w = float(discrete_omega_rotation(q, mat))
    n = np.arange(N)
    s0 = LatticeState(None, None, a * np.cos(q * n), a * w * np.sin(q * n))
    T = 200.0
    s = integrate(s0, mat, "rotation", T, 0.01, "srkn11b")
    exact = a * np.cos(q * n - w * T)
    # nonlinear frequency shift ~ a^2 = 1e-14 relative; integration error < 1e-10
    assert np.abs(s.theta - exact).max() < 1e-6 * a
    # and it is not the continuum frequency: that one is off by ~1e-2
    wc = float(co.omega(q, mat.alpha, mat.K_s, mat.K_theta))
    assert np.abs(a * np.cos(q * n - wc * T) - s.theta).max() > 1e-2 * a


def test_longitudinal_wave_follows_discrete1():
    N, m, a = 64, 21, 1e-3
    q = 2 * np.pi * m / N
    w = float(discrete_omega_longitudinal(q))
    n = np.arange(N)
    zero = np.zeros(N)
    s0 = LatticeState(a * np.cos(q * n), a * w * np.sin(q * n), zero, zero)
    T = 100.0
    s = integrate(s0, BLUE, "coupled", T, 0.01, "srkn11b")
    assert np.all(s.theta == 0)  # theta = 0 is invariant: U alone is linear
    assert np.abs(s.U - a * np.cos(q * n - w * T)).max() < 1e-9 * a / 1e-3


def test_translation_invariance():
    s0 = random_state(seed=5)
    s1 = integrate(s0, BLUE, "coupled", 5.0, 0.05, "rk4")
    r0 = LatticeState(*(np.roll(x, 3) for x in (s0.U, s0.U_dot, s0.theta, s0.theta_dot)))
    r1 = integrate(r0, BLUE, "coupled", 5.0, 0.05, "rk4")
    assert np.abs(r1.theta - np.roll(s1.theta, 3)).max() < 1e-13
    assert np.abs(r1.U - np.roll(s1.U, 3)).max() < 1e-13


def test_rotation_equals_coupled_with_U_pinned():
    # (a) forces: eq. `norm` at U = 0 gives the rotation-case theta acceleration exactly
    rng = np.random.default_rng(7)
    N = 16
    th = rng.normal(0, 0.5, N)
    out = [np.empty(N) for _ in range(5)]
    accel(th, np.zeros(N), True, 6.25, 0.02, 0.01, *out[:3], out[3], out[4])
    rot = np.empty(N)
    accel(th, np.zeros(0), False, 6.25, 0.02, 0.01, *out[:3], rot, np.zeros(0))
    assert np.array_equal(out[3], rot)
    # (b) dynamics: theta_n = (-1)^n f(t) keeps cos(theta_{n+1}) = cos(theta_{n-1}), so
    # the force on U vanishes, U stays exactly 0 and both cases give the same theta(t).
    sign = (-1.0) ** np.arange(N)
    th0, w0 = 0.3 * sign, 0.1 * sign
    c = integrate(LatticeState(np.zeros(N), np.zeros(N), th0, w0), BLUE, "coupled", 50.0,
                  0.05)
    r = integrate(LatticeState(None, None, th0, w0), BLUE, "rotation", 50.0, 0.05)
    assert np.all(c.U == 0) and np.all(c.U_dot == 0)
    assert np.array_equal(c.theta, r.theta)


def test_energy_is_conserved_by_dop853_on_a_strongly_nonlinear_state():
    s0 = random_state(amp=1.0)
    e0 = energy(s0, BLUE, "coupled")
    s = integrate(s0, BLUE, "coupled", 20.0, 1.0, "dop853", rtol=1e-12, atol=1e-14)
    assert abs(energy(s, BLUE, "coupled") - e0) < 1e-10 * abs(e0)


# --- simulate ------------------------------------------------------------------------

def test_simulate_paper_initial_condition_and_snapping():
    run = simulate(BLUE, "coupled", paper.N, paper.k("blue"), t_end=1.0, dt=0.05, save_every=0.5)
    assert run.m == 65 and run.k == pytest.approx(2 * np.pi * 65 / 500)
    assert run.theta.shape == (3, 500) and run.U.shape == (3, 500)
    assert np.array_equal(run.t, [0.0, 0.5, 1.0])
    n = np.arange(500)
    b0 = np.random.default_rng(0).uniform(-1e-3, 1e-3, 500)
    np.testing.assert_allclose(run.theta[0], 0.02 * (1 + b0) * np.cos(run.k * n), rtol=1e-15)
    assert np.all(run.U[0] == 0)
    assert run.relative_energy_error.max() < 1e-8  # RK4 drift ~1e-9 per unit time here


def test_simulate_rotation_has_no_U_and_spectrum_storage():
    run = simulate(GREEN, "rotation", paper.N, paper.k("green"), t_end=2.0, dt=0.05, store="spectrum")
    assert run.U is None and run.U_hat is None and run.theta is None
    assert run.theta_hat.shape[1] == 251
    # the carrier dominates the spectrum, with amplitude 2 eps A0
    j = np.argmax(run.theta_hat[0])
    assert j == run.m and run.theta_hat[0, j] == pytest.approx(0.02, rel=2e-3)


def test_simulate_discrete_omega_option():
    k = 2 * np.pi * 13 / 100
    a = initial_condition(BLUE, "rotation", 100, k)
    b = initial_condition(BLUE, "rotation", 100, k, start="discrete")
    assert np.array_equal(b.theta, a.theta)  # same positions, same noise...
    wd = discrete_omega_rotation(k, BLUE)
    wc = co.omega(k, BLUE.alpha, BLUE.K_s, BLUE.K_theta)
    assert abs(wd / wc - 1) > 1e-4  # (the two models differ here, else the test is void)
    # ...velocities theta_dot = amp omega sin(k n): their ratio is exactly wd / wc
    moving = np.abs(a.theta_dot) > 1e-6
    np.testing.assert_allclose(b.theta_dot[moving] / a.theta_dot[moving], wd / wc, rtol=1e-12)
    # and simulate passes the option through: the first records differ the same way
    ra = simulate(BLUE, "rotation", 100, k, t_end=0.1, dt=0.05, save_every=0.05)
    rb = simulate(BLUE, "rotation", 100, k, t_end=0.1, dt=0.05, save_every=0.05,
                  start="discrete")
    assert np.array_equal(ra.theta[0], rb.theta[0]) and not np.allclose(ra.theta[1], rb.theta[1],
                                                                         rtol=1e-9, atol=0)


@pytest.mark.parametrize("kwargs, match", [
    (dict(N=2), "N"),
    (dict(k=0.8), "commensurate"),
    (dict(dt=0.0), "dt"),
    (dict(dt=-1.0), "dt"),
    (dict(t_end=float("nan")), "t_end"),
    (dict(method="euler"), "unknown method"),
    (dict(case="both"), "case"),
    (dict(store="all"), "store"),
    (dict(eps=-0.1), "eps"),
])
def test_simulate_bad_inputs(kwargs, match):
    args = dict(material=BLUE, case="coupled", N=100, k=2 * np.pi * 13 / 100, t_end=1.0,
                dt=0.05)
    args.update(kwargs)
    with pytest.raises(ValueError, match=match):
        simulate(**args)


def test_bad_states_and_materials():
    with pytest.raises(ValueError, match="not finite"):
        LatticeState(None, None, [0.0, np.nan, 0.0], [0.0, 0.0, 0.0])
    with pytest.raises(ValueError, match="N >= 3"):
        LatticeState(None, None, [0.0, 0.1], [0.0, 0.0])
    with pytest.raises(ValueError, match="sites"):
        LatticeState(None, None, [0.0, 0.1, 0.2], [0.0, 0.0])
    with pytest.raises(ValueError, match="K_theta must be finite and > 0"):
        Material(2.5, 0.01, -0.1)
    with pytest.raises(ValueError, match="alpha"):
        Material(float("inf"), 0.01, 0.01)
    with pytest.raises(ValueError, match="needs U"):
        integrate(LatticeState(None, None, np.zeros(5), np.zeros(5)), BLUE, "coupled", 1, 0.1)


def test_material_delta_and_from_physical():
    assert BLUE.delta == pytest.approx(0.003)
    # m = 1, J = 1/4 -> alpha = a sqrt(m/(4J)) = a; k_theta = k_l a^2 / 4 -> K_theta = 1
    m = Material.from_physical(m=1.0, J=0.25, a=2.0, k_l=3.0, k_s=0.3, k_theta=3.0)
    assert (m.alpha, m.K_s, m.K_theta) == pytest.approx((2.0, 0.1, 1.0))
    with pytest.raises(ValueError, match="J"):
        Material.from_physical(m=1.0, J=0.0, a=2.0, k_l=3.0, k_s=0.3, k_theta=3.0)


def test_blow_up_is_reported_with_time_and_safe_dt():
    limit = get_method("rk4").stability_limit() / BLUE.omega_max("coupled")
    with pytest.raises(BlowUpError, match=r"T = .* Try dt <= ") as info:
        simulate(BLUE, "coupled", 64, 2 * np.pi * 8 / 64, t_end=2000.0, dt=1.2 * limit,
                 save_every=10.0)
    err = info.value
    assert err.run is not None and len(err.run.t) >= 1 and not err.run.completed
    assert np.all(np.isfinite(err.run.energy))


def test_stability_limits_from_coefficients():
    assert get_method("rk4").stability_limit() == pytest.approx(2 * math.sqrt(2), rel=1e-9)
    assert get_method("verlet").stability_limit() == pytest.approx(2.0, rel=1e-9)


@pytest.mark.parametrize("name", FIXED)
def test_the_stability_limit_scan_is_the_one_step_walk(name):
    """The limit is found from the one-step matrices of the whole grid at once (the walk,
    one matrix at a time, cost every process ~0.3 s): the same number, to the last bit,
    as the walk to the grid's first unstable step and the bisection after it."""
    m = get_method(name)

    def stable(h):
        return np.max(np.abs(np.linalg.eigvals(m._oscillator_matrix(h)))) <= 1 + 1e-9

    hs = np.linspace(1e-3, 8.0, 8000)
    bad = next(i for i, h in enumerate(hs) if not stable(h))
    lo, hi = hs[bad - 1], hs[bad]
    for _ in range(50):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if stable(mid) else (lo, mid)
    assert m._stability_limit() == float(lo)


def test_interrupted_run_keeps_data_and_resumes(monkeypatch):
    from numerics.lattice import _integrate as _simulate

    full = simulate(BLUE, "coupled", 64, 2 * np.pi * 8 / 64, t_end=10.0, dt=0.05,
                    save_every=1.0)
    calls = {"n": 0}
    original = _simulate.Stepper.advance

    def flaky(self, nsteps):
        calls["n"] += 1
        if calls["n"] == 4:
            raise KeyboardInterrupt
        return original(self, nsteps)

    monkeypatch.setattr(_simulate.Stepper, "advance", flaky)
    with pytest.raises(SimulationInterrupted, match="Resume") as info:
        simulate(BLUE, "coupled", 64, 2 * np.pi * 8 / 64, t_end=10.0, dt=0.05, save_every=1.0)
    monkeypatch.setattr(_simulate.Stepper, "advance", original)
    part = info.value.run
    assert len(part.t) == 4 and not part.completed
    np.testing.assert_array_equal(part.theta, full.theta[:4])
    rest = simulate(BLUE, "coupled", 64, 2 * np.pi * 8 / 64, t_end=7.0, dt=0.05,
                    save_every=1.0, initial=info.value.state)
    np.testing.assert_allclose(rest.theta[-1], full.theta[-1], rtol=0, atol=1e-14)
