"""The steppers behind simulate and integrate: one class per method family, picked by
``Method.kind`` from a registry, each bit for bit the computation of the single class they
replaced (kept below as the reference); simulate's record grid and its stepping loop."""

import numpy as np
import pytest

from numerics import METHODS, get_method, initial_condition, simulate
from numerics.lattice import LatticeState, _integrate
from numerics.lattice import _kernels as kernels
from numerics.lattice._integrate import STEPPERS, Stepper
from numerics.lattice._run import record_grid as _record_grid


class _Reference:
    """The stepper as one class switching on ``method.kind`` (numerics/lattice/_integrate.py
    before the stepper families), the same operations in the same order."""

    def __init__(self, state, material, case, method, dt, rtol=1e-10, atol=1e-12):
        self.coupled = case == "coupled"
        self.method, self.dt, self.rtol, self.atol = method, dt, rtol, atol
        n = state.N
        self.th, self.w = state.theta.copy(), state.theta_dot.copy()
        self.U = state.U.copy() if self.coupled else kernels.empty_u()
        self.V = state.U_dot.copy() if self.coupled else kernels.empty_u()
        self.s, self.c, self.v = np.empty(n), np.empty(n), np.empty(n)
        self.ath, self.aU = np.empty(n), np.empty(n if self.coupled else 0)
        self.params = (material.alpha**2, material.K_s, material.K_theta)
        self.evaluations = 0
        nU = n if self.coupled else 0
        if method.kind == "srkn":
            self.acoef, self.bcoef = np.array(method.a), np.array(method.b)
            self.work, self.work_U = np.empty((8, n)), np.empty((2, nU))
            kernels.accel(self.th, self.U, self.coupled, *self.params, self.s, self.c,
                          self.v, self.ath, self.aU)
            self.evaluations += 1
        elif method.kind == "rk4":
            self.work, self.work_U = np.empty((11, n)), np.empty((5, nU))

    def advance(self, nsteps):
        if self.method.kind == "scipy":
            return self._scipy(nsteps * self.dt)
        args = (self.th, self.w, self.U, self.V)
        if self.method.kind == "srkn":
            done = kernels.srkn_steps(*args, self.ath, self.aU, self.coupled, *self.params,
                                      self.acoef, self.bcoef, self.dt, nsteps, self.work,
                                      self.work_U)
            if done < nsteps:
                done += kernels.srkn_steps_libm(*args, self.ath, self.aU, self.coupled,
                                                *self.params, self.acoef, self.bcoef,
                                                self.dt, nsteps - done, self.s, self.c,
                                                self.v)
        else:
            done = kernels.rk4_steps(*args, self.coupled, *self.params, self.dt, nsteps,
                                     self.work, self.work_U)
            if done < nsteps:
                done += kernels.rk4_steps_libm(*args, self.coupled, *self.params, self.dt,
                                               nsteps - done, self.s, self.c, self.v,
                                               np.empty((10, self.th.size)))
        self.evaluations += done * self.method.evaluations
        return done

    def _scipy(self, span):
        from scipy.integrate import solve_ivp

        n, coupled = self.th.size, self.coupled
        nf = 4 * n if coupled else 2 * n
        y0 = (np.concatenate([self.th, self.w, self.U, self.V]) if coupled
              else np.concatenate([self.th, self.w]))

        def rhs(_t, y):
            U = y[2 * n:3 * n] if coupled else kernels.empty_u()
            kernels.accel(np.ascontiguousarray(y[:n]), np.ascontiguousarray(U), coupled,
                          *self.params, self.s, self.c, self.v, self.ath, self.aU)
            out = np.empty(nf)
            out[:n], out[n:2 * n] = y[n:2 * n], self.ath
            if coupled:
                out[2 * n:3 * n], out[3 * n:] = y[3 * n:], self.aU
            return out

        sol = solve_ivp(rhs, (0.0, span), y0, method=self.method.name.upper(),
                        rtol=self.rtol, atol=self.atol)
        self.evaluations += sol.nfev
        if not sol.success or not np.all(np.isfinite(sol.y[:, -1])):
            return 0
        y = sol.y[:, -1]
        self.th[:], self.w[:] = y[:n], y[n:2 * n]
        if coupled:
            self.U[:], self.V[:] = y[2 * n:3 * n], y[3 * n:]
        return int(round(span / self.dt))


def _state(case, theta0, rng, N=32):
    """theta about theta0 moving at ~50 rad/T (theta0 = 9999.9 crosses the polynomial's
    range, TRIG_LIMIT = 1e4, within the run: the fast loop hands over to the libm one)."""
    th = theta0 + 0.01 * rng.standard_normal(N)
    w = 50.0 + 0.1 * rng.standard_normal(N)
    if case == "rotation":
        return LatticeState(None, None, th, w)
    return LatticeState(0.01 * rng.standard_normal(N), 0.01 * rng.standard_normal(N), th, w)


def test_every_method_kind_has_a_stepper_and_unknown_kinds_are_refused(blue, rng):
    state = _state("coupled", 0.0, rng)
    for name in METHODS:
        m = get_method(name)
        st = Stepper(state, blue, "coupled", m, 0.05)
        assert type(st) is STEPPERS[m.kind] and isinstance(st, Stepper)
    with pytest.raises(ValueError, match="registered twice"):
        _integrate.register_stepper("rk4")(type("Again", (Stepper,), {}))
    odd = get_method("rk4").__class__("odd", 2, 1, "odd-kind", False, "not registered")
    with pytest.raises(ValueError, match="no stepper for methods of kind 'odd-kind'"):
        Stepper(state, blue, "coupled", odd, 0.05)


#: (method, theta0): every method near 0 (the fast loops); the fixed-step ones also across
#: the polynomial's range (handover to the libm loops) and beyond it (libm from the start)
STARTS = [(m, 0.5) for m in METHODS] + [(m, t) for m in METHODS if get_method(m).fixed_step
                                        for t in (9999.9, 2e4)]


@pytest.mark.parametrize("case", ["rotation", "coupled"])
@pytest.mark.parametrize("method, theta0", STARTS)
def test_each_stepper_family_repeats_the_single_class_bit_for_bit(method, case, theta0, blue,
                                                                   rng):
    m = get_method(method)
    state = _state(case, theta0, rng)
    dt = 0.01 if m.fixed_step else 0.25
    new, ref = Stepper(state, blue, case, m, dt, 1e-9, 1e-11), \
        _Reference(state, blue, case, m, dt, 1e-9, 1e-11)
    for n in (7, 1, 30) if m.fixed_step else (2, 1):  # chunks: the state carries over
        assert new.advance(n) == ref.advance(n) == n
        assert new.evaluations == ref.evaluations
        got = new.state()
        for field, want in (("theta", ref.th), ("theta_dot", ref.w)) + (
                (("U", ref.U), ("U_dot", ref.V)) if case == "coupled" else ()):
            assert getattr(got, field).tobytes() == want.tobytes(), field
    if m.fixed_step and theta0 > 1:  # the fast loop stops within the first chunk
        assert Stepper(state, blue, case, m, dt)._fast(7) < 7


@pytest.mark.parametrize("save_every, phase", [(None, 0), (0.7, 0), (0.7, 3), (1.0, 14),
                                                (50.0, 0)])
def test_simulate_records_fall_on_the_record_grid(save_every, phase, blue):
    # the records sit at step 0, grid.first, every per_save steps after it and at the end,
    # each the state a plain stepper reaches there
    k = 2 * np.pi * 8 / 64
    run = simulate(blue, "coupled", 64, k, t_end=7.3, dt=0.05, save_every=save_every,
                   record_phase=phase, progress=False)
    grid = _record_grid(146, run.dt, save_every, phase)
    steps = [0] + [grid.step_of(j) for j in range(1, grid.count)]
    assert len(run.t) == grid.count and steps[-1] == 146 and steps[-2] < 146
    np.testing.assert_array_equal(run.t, np.array(steps) * run.dt)
    ref = _Reference(initial_condition(blue, "coupled", 64, k), blue, "coupled",
                     get_method("rk4"), run.dt)
    for j in range(1, len(steps)):
        ref.advance(steps[j] - steps[j - 1])
        assert run.theta[j].tobytes() == ref.th.tobytes()
        assert run.U[j].tobytes() == ref.U.tobytes()
    assert run.force_evaluations == ref.evaluations == 146 * 4


def test_the_record_grid_checks_its_inputs():
    with pytest.raises(ValueError, match="save_every"):
        _record_grid(100, 0.05, -1.0, 0)
    with pytest.raises(ValueError, match="record_phase"):
        _record_grid(100, 0.05, 1.0, 21)  # more steps than a record interval holds
    grid = _record_grid(100, 0.05, 1.0, 5)
    assert (grid.per_save, grid.first, grid.count) == (20, 15, 2 + 5)
    assert grid.since_record(40, 3) == 40 - 35 and grid.since_record(3, 1) == 3 + 5
