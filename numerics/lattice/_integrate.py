"""Advancing a lattice state: ``integrate`` (state -> state) and the stepper behind it.

``Stepper`` holds the work arrays of one run and advances it by whole chunks of steps: one
class per method family (``Method.kind``), registered in :data:`STEPPERS` (as ``METHODS``
registers the integrators): compiled loops (``_kernels``, RK4 and the symplectic RKN
methods, handing over to the libm loops), or scipy's ``solve_ivp`` for the adaptive ones.
"""

from __future__ import annotations

import math

import numpy as np

from . import _kernels as kernels
from . import checks
from ._accuracy import check_energy_tolerance, choose_step, energy_check
from ._integrators import Method, get_method
from ._model import LatticeState, Material, check_case, energy

#: the paper's RK4 step, the default when neither dt nor tol is given
DEFAULT_DT = 0.05


class BlowUpError(FloatingPointError):
    """The solution stopped being finite; ``run`` holds what was saved before."""

    def __init__(self, message, run=None, time=None):
        super().__init__(message)
        self.run = run
        self.time = time


class SimulationInterrupted(KeyboardInterrupt):
    """Ctrl-C during a run; ``run`` holds the saved part, ``state`` the state at ``time``
    (exactly), ``remaining`` the time left to t_end."""

    def __init__(self, message, run=None, state=None, time=None, remaining=None, dt=None,
                 record_phase=0, signum=2):
        super().__init__(message)
        self.signum = signum  # SIGINT (2) or SIGTERM (15): the exit code is 128 + signum
        self.run = run
        self.state = state
        self.time = time
        self.remaining = remaining
        self.dt = dt
        self.record_phase = record_phase


def check_tolerances(rtol, atol):
    """rtol in [1e-15, 1), atol in (0, 1): scipy's solve_ivp hangs on 0, NaN or inf."""
    return (checks.real("rtol", rtol, 1e-15, 1.0, low_open=False),
            checks.real("atol", atol, 0.0, 1.0))


def check_time(t_end, dt):
    t_end = checks.positive("t_end", t_end)
    dt = checks.positive("dt", dt)
    if dt > t_end:
        raise ValueError(f"dt = {dt} is larger than t_end = {t_end}")
    nsteps = math.ceil(t_end / dt - 1e-9)
    if nsteps > 10**10:
        raise ValueError(f"t_end/dt = {nsteps:.3g} steps is absurd; use a larger dt")
    return nsteps, t_end / nsteps


#: the stepper class of each ``Method.kind`` (:func:`register_stepper`), as METHODS holds the
#: integrators: ``Stepper(state, material, case, method, dt)`` builds the one of method.kind
STEPPERS: dict[str, type] = {}


def register_stepper(kind: str):
    """Class decorator: the stepper of every method of this ``Method.kind``."""
    def add(cls):
        if kind in STEPPERS:
            raise ValueError(f"a stepper for methods of kind {kind!r} registered twice")
        STEPPERS[kind] = cls
        return cls
    return add


class Stepper:
    """Holds the work arrays of one run and advances it by whole chunks of steps.

    ``Stepper(state, material, case, method, dt, rtol, atol)`` returns the stepper
    registered for ``method.kind`` (:data:`STEPPERS`); each family implements ``_advance``.
    ``advance`` is defined here only, so that wrapping ``Stepper.advance`` (the tests'
    interrupts) wraps every family.
    """

    def __new__(cls, state: LatticeState, material: Material, case: str, method: Method,
                dt: float, rtol: float = 1e-10, atol: float = 1e-12):
        if cls is Stepper:
            try:
                cls = STEPPERS[method.kind]
            except KeyError:
                raise ValueError(f"no stepper for methods of kind {method.kind!r}; "
                                 f"registered: {', '.join(STEPPERS)}") from None
        return super().__new__(cls)

    def __init__(self, state: LatticeState, material: Material, case: str, method: Method,
                 dt: float, rtol: float = 1e-10, atol: float = 1e-12):
        self.case = case
        self.coupled = case == "coupled"
        self.material = material
        self.method = method
        self.dt = dt
        self.rtol, self.atol = rtol, atol
        n = state.N
        self.th = state.theta.copy()
        self.w = state.theta_dot.copy()
        self.U = state.U.copy() if self.coupled else kernels.empty_u()
        self.V = state.U_dot.copy() if self.coupled else kernels.empty_u()
        self.s, self.c, self.v = np.empty(n), np.empty(n), np.empty(n)
        self.ath = np.empty(n)
        self.aU = np.empty(n if self.coupled else 0)
        self.params = (material.alpha**2, material.K_s, material.K_theta)
        self.evaluations = 0

    def state(self) -> LatticeState:
        """A copy of the current state."""
        if self.coupled:
            return LatticeState(self.U.copy(), self.V.copy(), self.th.copy(), self.w.copy())
        return LatticeState(None, None, self.th.copy(), self.w.copy())

    def advance(self, nsteps: int) -> int:
        """Advance ``nsteps`` steps; returns the number completed while finite."""
        return self._advance(nsteps)

    def _advance(self, nsteps: int) -> int:
        """The family's advance (see :meth:`advance`)."""
        raise NotImplementedError


class _CompiledStepper(Stepper):
    """Fixed-step methods: compiled fast loops (``_kernels``), continued by the libm loops
    (``_kernels_libm``) where |theta| leaves the polynomial's range or the state blows up."""

    def _advance(self, nsteps):
        """Fast loops, then libm loops for the rest; counts the force evaluations."""
        done = self._fast(nsteps)
        if done < nsteps:
            # |theta| beyond the polynomial's range, or not finite: the libm loops go on
            # (and stop at once on a non-finite state, reporting the blow-up)
            done += self._libm(nsteps - done)
        self.evaluations += done * self.method.evaluations
        return done

    def _fast(self, nsteps):
        """Up to ``nsteps`` steps in the fast loop; returns the steps done."""
        raise NotImplementedError

    def _libm(self, nsteps):
        """Up to ``nsteps`` steps in the libm loop; returns the steps done."""
        raise NotImplementedError


@register_stepper("rk4")
class _RK4Stepper(_CompiledStepper):
    """Classical RK4 on (q, q'), four fused passes per step."""

    def __init__(self, state, material, case, method, dt, rtol=1e-10, atol=1e-12):
        super().__init__(state, material, case, method, dt, rtol, atol)
        n = state.N
        nU = n if self.coupled else 0  # case "rotation" allocates nothing for U
        self.work, self.work_U = np.empty((11, n)), np.empty((5, nU))

    def _fast(self, nsteps):
        """``kernels.rk4_steps``."""
        return kernels.rk4_steps(self.th, self.w, self.U, self.V, self.coupled, *self.params,
                                 self.dt, nsteps, self.work, self.work_U)

    def _libm(self, nsteps):
        """``kernels.rk4_steps_libm``."""
        return kernels.rk4_steps_libm(self.th, self.w, self.U, self.V, self.coupled,
                                      *self.params, self.dt, nsteps, self.s, self.c, self.v,
                                      np.empty((10, self.th.size)))


@register_stepper("srkn")
class _SRKNStepper(_CompiledStepper):
    """Symplectic RKN (BAB, coefficients ``method.a``, ``method.b``): the acceleration of
    the current state is kept between calls (one force evaluation on construction)."""

    def __init__(self, state, material, case, method, dt, rtol=1e-10, atol=1e-12):
        super().__init__(state, material, case, method, dt, rtol, atol)
        n = state.N
        nU = n if self.coupled else 0  # case "rotation" allocates nothing for U
        self.acoef = np.array(method.a)
        self.bcoef = np.array(method.b)
        self.work, self.work_U = np.empty((8, n)), np.empty((2, nU))
        self._accel()

    def _accel(self):
        """The acceleration of the current state into ``ath``, ``aU``."""
        kernels.accel(self.th, self.U, self.coupled, *self.params, self.s, self.c, self.v,
                      self.ath, self.aU)
        self.evaluations += 1

    def _fast(self, nsteps):
        """``kernels.srkn_steps``."""
        return kernels.srkn_steps(self.th, self.w, self.U, self.V, self.ath, self.aU,
                                  self.coupled, *self.params, self.acoef, self.bcoef,
                                  self.dt, nsteps, self.work, self.work_U)

    def _libm(self, nsteps):
        """``kernels.srkn_steps_libm``."""
        return kernels.srkn_steps_libm(self.th, self.w, self.U, self.V, self.ath, self.aU,
                                       self.coupled, *self.params, self.acoef,
                                       self.bcoef, self.dt, nsteps, self.s, self.c, self.v)


@register_stepper("scipy")
class _ScipyStepper(Stepper):
    """Adaptive reference methods: one scipy ``solve_ivp`` over each chunk's span (rtol,
    atol), the state landing on its end."""

    def _advance(self, nsteps):
        """One solve_ivp over ``nsteps * dt``; all the steps, or 0 when it failed."""
        return self._solve(nsteps * self.dt)

    def _solve(self, span):
        """Integrate over ``span``; returns its steps of dt (0: failed or not finite)."""
        from scipy.integrate import solve_ivp

        n = self.th.size
        nf = 4 * n if self.coupled else 2 * n
        y0 = (np.concatenate([self.th, self.w, self.U, self.V]) if self.coupled
              else np.concatenate([self.th, self.w]))
        ath, aU = self.ath, self.aU
        coupled = self.coupled

        def rhs(_t, y):
            th = y[:n]
            U = y[2 * n:3 * n] if coupled else kernels.empty_u()
            kernels.accel(np.ascontiguousarray(th), np.ascontiguousarray(U), coupled,
                          *self.params, self.s, self.c, self.v, ath, aU)
            out = np.empty(nf)
            out[:n] = y[n:2 * n]
            out[n:2 * n] = ath
            if coupled:
                out[2 * n:3 * n] = y[3 * n:]
                out[3 * n:] = aU
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


def safe_step(dt, material, case, method):
    """A step that cures a blow-up at ``dt``: below half the linear stability limit, and a
    quarter of ``dt`` (a blow-up below the limit is nonlinear: the energy error grew; for
    order p it falls 4^p-fold). Tested: the advised step completes the failed run."""
    limit = method.stability_limit() / material.omega_max(case)
    return min(0.5 * limit, dt / 4)


def blowup_message(t, dt, material, case, method, reason="non-finite", drift=None,
                    max_drift=None):
    limit = method.stability_limit() / material.omega_max(case)
    what = ("theta stopped being finite" if reason == "non-finite" else
            f"the energy drifted by {drift:.3g} of its initial value (more than "
            f"max_energy_error = {max_drift:g})")
    cause = (f"dt is above the linear stability limit dt < {limit:.4g} of {method.name!r} "
             "here" if dt >= limit else
             f"dt is below the linear stability limit ({limit:.4g}): the step is too "
             "coarse for the nonlinear dynamics")
    return (f"solution blew up near T = {t:.6g} with dt = {dt:g} and method "
            f"{method.name!r}: {what}; {cause}. Try dt <= "
            f"{safe_step(dt, material, case, method):.3g}")


def resolve_step(state, material, case, t_end, dt, method, tol):
    """(method name, dt) of a run: as given, or chosen for ``tol`` (``_accuracy``)."""
    if tol is None:
        return (method or "rk4"), (DEFAULT_DT if dt is None else dt)
    if dt is not None:
        raise ValueError("give dt or tol, not both (tol chooses the step)")
    if method is not None and not get_method(method).fixed_step:
        raise ValueError(f"tol chooses a fixed-step method; {method!r} is adaptive: "
                         "use rtol/atol for it")
    t_end = checks.positive("t_end", t_end)
    return choose_step(state, material, case, t_end, tol, None if method is None else [method])


def integrate(state: LatticeState, material: Material, case: str, t_end: float,
              dt: float | None = None, method: str | None = None, *, tol: float | None = None,
              rtol: float = 1e-10, atol: float = 1e-12, energy_tolerance: float = 1e-3
              ) -> LatticeState:
    """Integrate eq. `norm` from ``state`` to ``t_end``; the input is not modified.

    Parameters
    ----------
    state : LatticeState
        Initial condition (U, U_dot None for case "rotation").
    material : Material
    case : {"rotation", "coupled"}
    t_end, dt : float
        Final time and step (default 0.05); the step used is t_end / ceil(t_end / dt)
        <= dt so that the run lands exactly on t_end.
    method : str, optional
        One of ``numerics.METHODS`` (default "rk4"); rtol/atol apply to the scipy methods.
    tol : float, optional
        Ask for a relative state error instead of a step: method (unless given) and dt
        are chosen by the error model of ``numerics._accuracy`` (no dt then).
    energy_tolerance : float
        A fixed-step run whose relative energy error at t_end exceeds this ends with an
        :class:`AccuracyWarning` naming a step that meets it.

    Returns
    -------
    LatticeState at t_end.

    Raises
    ------
    BlowUpError
        When the solution stops being finite (the message names the time and a safe dt).
    """
    checks.instance("state", state, LatticeState)
    checks.instance("material", material, Material)
    check_case(case)
    state = state.for_case(case)
    energy_tolerance = check_energy_tolerance(energy_tolerance)
    rtol, atol = check_tolerances(rtol, atol)
    method, dt = resolve_step(state, material, case, t_end, dt, method, tol)
    m = get_method(method)
    nsteps, dt_eff = check_time(t_end, dt)
    st = Stepper(state, material, case, m, dt_eff, rtol, atol)
    done = st.advance(nsteps)
    if done < nsteps:
        raise BlowUpError(blowup_message(done * dt_eff, dt_eff, material, case, m),
                          time=done * dt_eff)
    final = st.state()
    if m.fixed_step:
        with np.errstate(over="ignore", invalid="ignore"):  # a huge state: error inf
            e0 = energy(state, material, case)
            error = abs(energy(final, material, case) - e0) / abs(e0) if e0 else 0.0
        energy_check(error, energy_tolerance, m.name, dt_eff)
    return final
