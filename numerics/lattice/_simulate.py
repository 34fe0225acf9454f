"""The paper's numerical experiment: ``simulate`` a noisy plane wave on a periodic chain.

Builds the initial condition (eq. `IC`, or the exact travelling wave), snaps k to the
chain, advances it with ``_integrate._Stepper`` record by record, keeps only what is asked
for, and stops with ``BlowUpError`` or ``SimulationInterrupted`` keeping what was computed.
"""

from __future__ import annotations

import dataclasses
import math
import numbers
from dataclasses import dataclass

import numpy as np

from common.paper import A0 as PAPER_A0
from common.paper import EPS as PAPER_EPS

from ._analysis import spectrum
from . import checks
from ._accuracy import check_energy_tolerance, energy_check
from ._integrate import (BlowUpError, SimulationInterrupted, _blowup_message, _check_time,
                         _Stepper, check_tolerances, resolve_step)
from ._integrators import get_method
from ._starts import LEGACY_OMEGA_MODELS, build_start, check_start
from common.signals import signal_number

from ._runcontrol import _deferred_interrupt, _Interrupt, _progress, _steps_per_call
from ._model import LatticeState, Material, check_case, energy


STORE_CHOICES = ("snapshots", "spectrum", "energy")


def _check_sites(N):
    """N: an integer in [3, 1e8] (more sites than that does not fit a 24 GiB machine)."""
    return checks.integer("N", N, 3, 10**8 + 1)


@dataclass
class Run:
    """Output of :func:`simulate`.

    Attributes
    ----------
    t : ndarray, shape (nt,)
    theta, U : ndarray, shape (nt, N), or None (U for case "rotation"; both when
        ``store`` is not "snapshots")
    theta_hat, U_hat : ndarray, shape (nt, N//2 + 1), or None
        |rfft| * 2/N of theta and U (a plane wave of amplitude a shows as a peak a);
        stored when ``store == "spectrum"``.
    energy : ndarray, shape (nt,)
    """

    t: np.ndarray
    theta: np.ndarray | None
    U: np.ndarray | None
    energy: np.ndarray
    material: Material
    case: str
    N: int
    k: float  # snapped carrier wavenumber 2 pi m / N
    m: int
    k_requested: float
    amplitude: float  # peak rotation of the carrier at T = 0 (the paper's 2 eps A0)
    noise: float
    seed: int
    method: str
    dt: float
    t_end: float
    save_every: float
    store: str
    start: str
    theta_hat: np.ndarray | None = None
    U_hat: np.ndarray | None = None
    final_state: LatticeState | None = None
    force_evaluations: int = 0
    completed: bool = True

    def __repr__(self) -> str:
        m = self.material
        return (f"Run(case={self.case!r}, alpha={m.alpha:g}, K_s={m.K_s:g}, "
                f"K_theta={m.K_theta:g}, N={self.N}, k={self.k:.6g}, "
                f"amplitude={self.amplitude:g}, start={self.start!r}, seed={self.seed}, "
                f"method={self.method!r}, dt={self.dt:g}, t=[0, {self.t[-1]:g}] in "
                f"{len(self.t)} records, store={self.store!r}, "
                f"energy_error={self.energy_error:.1e}"
                f"{'' if self.completed else ', completed=False'})")

    @property
    def wavenumbers(self) -> np.ndarray:
        """q of the spectrum columns, rad per site."""
        return 2 * np.pi * np.arange(self.N // 2 + 1) / self.N

    @property
    def relative_energy_error(self) -> np.ndarray:
        """|E(t) - E(0)| / |E(0)| at every record."""
        return np.abs(self.energy - self.energy[0]) / abs(self.energy[0])

    @property
    def energy_error(self) -> float:
        """The largest relative energy error over the records (the run's accuracy check)."""
        return float(self.relative_energy_error.max())


def snap_wavenumber(k: float, N: int, rel_tol: float = 1e-3):
    """Nearest periodic wavenumber 2 pi m / N to k; ValueError if further than rel_tol."""
    if isinstance(k, (bool, np.bool_)) or not isinstance(k, numbers.Real):
        raise TypeError(f"k must be a real number, got {type(k).__name__} {k!r}")
    k = float(k)
    if not math.isfinite(k) or k <= 0 or k >= math.pi:
        raise ValueError(f"k must be in (0, pi), got {k!r}")
    m = int(round(k * N / (2 * math.pi)))
    ks = 2 * math.pi * m / N
    if m == 0 or abs(ks - k) > rel_tol * k:
        raise ValueError(
            f"k = {k} is not commensurate with N = {N} periodic sites: the nearest "
            f"2 pi m / N is {ks:.6g} (m = {m}), {abs(ks - k) / k:.2e} away (> {rel_tol:g} "
            f"relative); choose k = 2 pi m / N")
    return ks, m


def _amplitude(amplitude, eps, A0) -> float:
    """The peak rotation: ``amplitude``, or the paper's 2 eps A0 when given as (eps, A0)."""
    if amplitude is not None:
        if eps is not None or A0 is not None:
            raise TypeError("give the amplitude either as amplitude= (peak rotation) or as "
                            "the paper's eps= and A0= (amplitude = 2 eps A0), not both")
        return checks.positive("amplitude", amplitude)
    eps = checks.positive("eps", PAPER_EPS if eps is None else eps)
    A0 = checks.positive("A0", PAPER_A0 if A0 is None else A0)
    return 2 * eps * A0


def _start(start, omega_model) -> str:
    if omega_model is not None:  # the earlier name of the same choice
        checks.choice("omega_model", omega_model, tuple(LEGACY_OMEGA_MODELS))
        if start not in (None, LEGACY_OMEGA_MODELS[omega_model]):
            raise TypeError(f"start={start!r} and omega_model={omega_model!r} disagree; "
                            "give start= only")
        return LEGACY_OMEGA_MODELS[omega_model]
    return check_start("paper" if start is None else start)


def initial_condition(material: Material, case: str, N: int, k: float,
                      amplitude: float | None = None, noise: float = 1e-3, seed: int = 0,
                      start: str | None = None, *, eps: float | None = None,
                      A0: float | None = None, omega_model: str | None = None) -> LatticeState:
    """The paper's noisy plane wave (eq. `IC`, eq. (14) of the paper), or another start.

    Parameters
    ----------
    amplitude : float
        Peak rotation of the carrier (the paper's 2 eps A0; default 0.02, the paper's).
        ``eps=`` and ``A0=`` are accepted instead, as the paper's symbols.
    noise, seed : float, int
        b0 ~ U[-noise, noise] per site from ``numpy.random.default_rng(seed)``; every
        field is multiplied by (1 + b0).
    start : {"paper", "discrete", "travelling"}
        See ``numerics.lattice.STARTS`` (module ``_starts``): eq. `IC` with the continuum
        frequency (the paper's), with the lattice's, or the exact travelling wave.
        ``omega_model=`` ("continuum", "discrete", "travelling") is its earlier name.
    """
    checks.instance("material", material, Material)
    check_case(case)
    start = _start(start, omega_model)
    N = _check_sites(N)
    amplitude = _amplitude(amplitude, eps, A0)
    noise = checks.real("noise", noise, 0.0, 1.0, low_open=False, high_open=True)
    seed = checks.seed(seed)
    return build_start(start, material, case, k, amplitude, noise_field(N, noise, seed))


def noise_field(N: int, noise: float, seed: int) -> np.ndarray:
    """The noise law of every start: b0 ~ U[-noise, noise] per site, shape (N,), from
    ``numpy.random.default_rng(seed)``; a start multiplies its fields by (1 + b0)."""
    return np.random.default_rng(seed).uniform(-noise, noise, N)


def simulate(material: Material, case: str, N: int, k: float,
             amplitude: float | None = None, noise: float = 1e-3, seed: int = 0,
             t_end: float = 5000.0, dt: float | None = None, method: str | None = None,
             save_every: float | None = None, *, start: str | None = None,
             eps: float | None = None, A0: float | None = None,
             omega_model: str | None = None, tol: float | None = None,
             store: str = "snapshots",
             initial: LatticeState | None = None, progress: bool | None = None,
             rtol: float = 1e-10, atol: float = 1e-12, max_energy_error: float = 0.5,
             energy_tolerance: float = 1e-3, record_phase: int = 0) -> Run:
    """Run the paper's numerical experiment: a noisy plane wave on a periodic chain.

    Parameters
    ----------
    material, case : Material, {"rotation", "coupled"}
    N : int
        Number of sites (periodic).
    k : float
        Carrier wavenumber; snapped to 2 pi m / N when within 1e-3 relative.
    amplitude, noise, seed, start : the initial state, see :func:`initial_condition`
        (amplitude: peak rotation, default the paper's 0.02; or the paper's ``eps=``,
        ``A0=``; start: "paper" (eq. `IC`), "discrete" or "travelling").
    t_end, dt : float
        Duration and time step (defaults: the paper's run, T = 5000 with dt = 0.05).
    method : str, optional
        One of ``numerics.METHODS`` (default "rk4", the paper's).
    tol : float, optional
        Ask for accuracy instead of a step: the relative state error wanted at t_end;
        the method (unless given) and dt come from the error model of
        ``numerics._accuracy`` (then give no dt). ``run.method`` and ``run.dt`` say
        what was chosen.
    save_every : float, optional
        Time between saved records (rounded to whole steps); default about 1000 records.
    store : {"snapshots", "spectrum", "energy"}
        What is kept at each record: full fields, only |theta_hat| (and |U_hat|), or only
        the energy (always kept). Memory grows with the records, never with the steps.
    initial : LatticeState, optional
        Start from this state instead of eq. `IC` (e.g. to resume an interrupted run).
    progress : bool or None
        Progress bar; None shows it only on a terminal.
    max_energy_error : float
        A record whose energy is off by more than this fraction of the initial energy
        (or not finite) counts as a blow-up: the run is conservative, so this only
        happens when the step is unstable.
    energy_tolerance : float
        A run that completes with a relative energy error above this (default 1e-3)
        ends with an :class:`AccuracyWarning` naming a dt that meets it;
        ``run.energy_error`` holds the error of every run.
    record_phase : int
        Steps done since the last record, when ``initial`` is the state of an interrupted
        run (``SimulationInterrupted.record_phase``): the records keep that run's grid.

    Returns
    -------
    Run

    Raises
    ------
    BlowUpError
        Non-finite solution or energy off by more than ``max_energy_error``: the message
        names the time and a safe dt; ``.run`` keeps the records saved before.
    SimulationInterrupted
        Ctrl-C: ``.run`` keeps the records saved so far, ``.state`` the last state, from
        which ``simulate(..., initial=exc.state, t_end=remaining)`` resumes.
    """
    checks.instance("material", material, Material)
    check_case(case)
    if method is not None:
        get_method(method)
    checks.choice("store", store, STORE_CHOICES)
    energy_tolerance = check_energy_tolerance(energy_tolerance)
    max_energy_error = checks.positive("max_energy_error", max_energy_error)
    seed = checks.seed(seed)
    rtol, atol = check_tolerances(rtol, atol)
    if initial is not None:
        checks.instance("initial", initial, LatticeState)
    N = _check_sites(N)
    start = _start(start, omega_model)
    amplitude = _amplitude(amplitude, eps, A0)
    ks, mode = snap_wavenumber(k, N)
    if initial is None:
        state = initial_condition(material, case, N, ks, amplitude, noise, seed, start)
    else:
        state = initial.for_case(case)
        if state.N != N:
            raise ValueError(f"initial state has {state.N} sites, N = {N}")
    method, dt = resolve_step(state, material, case, t_end, dt, method, tol)
    m_ = get_method(method)
    nsteps, dt_eff = _check_time(t_end, dt)
    if save_every is None:
        per_save = max(1, round(nsteps / 1000))
    else:
        save_every = checks.positive("save_every", save_every)
        per_save = max(1, round(save_every / dt_eff))
    # records at 0, at first_record, every per_save steps after it, and at the end;
    # record_phase > 0 continues the record grid of an interrupted run (steps already done
    # since its last record)
    phase = checks.integer("record_phase", record_phase, 0, per_save)
    first_record = per_save - phase
    nrec = 2 + (0 if first_record >= nsteps else -(-(nsteps - first_record) // per_save))
    coupled = case == "coupled"
    nq = N // 2 + 1
    t = np.empty(nrec)
    en = np.empty(nrec)
    th_rec = np.empty((nrec, N)) if store == "snapshots" else None
    U_rec = np.empty((nrec, N)) if store == "snapshots" and coupled else None
    thh = np.empty((nrec, nq)) if store == "spectrum" else None
    Uh = np.empty((nrec, nq)) if store == "spectrum" and coupled else None

    st = _Stepper(state, material, case, m_, dt_eff, rtol, atol)
    run = Run(t=t, theta=th_rec, U=U_rec, energy=en, material=material, case=case, N=N, k=ks,
              m=mode, k_requested=float(k), amplitude=amplitude, noise=noise, seed=seed,
              method=m_.name, dt=dt_eff, t_end=float(t_end), save_every=per_save * dt_eff,
              store=store, start=start, theta_hat=thh, U_hat=Uh)

    def record(j, time):
        t[j] = time
        cur = LatticeState(st.U, st.V, st.th, st.w) if coupled else \
            LatticeState(None, None, st.th, st.w)
        en[j] = energy(cur, material, case)
        if th_rec is not None:
            th_rec[j] = st.th
            if U_rec is not None:
                U_rec[j] = st.U
        if thh is not None:
            thh[j] = spectrum(st.th)
            if Uh is not None:
                Uh[j] = spectrum(st.U)

    def truncate(j):
        for name in RECORDS:
            arr = getattr(run, name)
            if arr is not None:
                setattr(run, name, arr[:j])
        run.completed = False

    record(0, 0.0)
    steps = 0  # steps the stepper's state has done: its time is steps * dt_eff
    j = 1
    sub = _steps_per_call(N, m_, per_save)
    bar = _progress(float(t_end), progress)

    def blow_up(reason, drift=None):
        truncate(j)
        run.force_evaluations = st.evaluations
        raise BlowUpError(_blowup_message(steps * dt_eff, dt_eff, material, case, m_, reason,
                                          drift, max_energy_error), run, steps * dt_eff)

    try:
        with _deferred_interrupt() as interrupted:
            while steps < nsteps:
                target = min(first_record + (j - 1) * per_save, nsteps)  # the next record
                while steps < target:
                    n = min(sub, target - steps)
                    got = st.advance(n)
                    steps += got
                    if got < n:
                        blow_up("non-finite")
                    if interrupted() and steps < target:
                        raise _Interrupt(interrupted())
                record(j, steps * dt_eff)
                drift = abs(en[j] - en[0]) / abs(en[0])
                if not drift <= max_energy_error:  # also catches NaN
                    blow_up("energy", drift)
                if bar is not None:
                    bar.update(t[j] - t[j - 1])
                j += 1
                if interrupted() and steps < nsteps:
                    raise _Interrupt(interrupted())
    except (_Interrupt, KeyboardInterrupt) as exc:
        if isinstance(exc, SimulationInterrupted):
            raise
        signum = exc.args[0] if isinstance(exc, _Interrupt) else signal_number(exc)
        truncate(j)
        run.force_evaluations = st.evaluations
        left = nsteps - steps
        since = steps - (first_record + (j - 2) * per_save if j > 1 else -phase)
        raise SimulationInterrupted(
            f"interrupted at T = {steps * dt_eff:.10g} of {t_end:g}; exc.run keeps "
            f"{len(run.t)} records (to T = {run.t[-1]:g}). Resume with simulate(..., "
            f"initial=exc.state, t_end={left * dt_eff!r}, dt={dt_eff!r}, "
            f"record_phase={since}) (times then count from 0), or numerics.resume(exc, **the same arguments)",
            run=run, state=st.state(), time=steps * dt_eff, remaining=left * dt_eff,
            dt=dt_eff, record_phase=since, signum=signum) from None
    finally:
        if bar is not None:
            bar.close()
    run.final_state = st.state()
    run.force_evaluations = st.evaluations
    if m_.fixed_step:
        energy_check(run.energy_error, energy_tolerance, m_.name, dt_eff)
    return run


def resume(interrupted: SimulationInterrupted, **params) -> Run:
    """Finish the run that ``interrupted`` stopped: ``params`` are the keyword arguments
    of the original :func:`simulate` call. Returns the whole run, its records on the
    original time grid, equal to an uninterrupted run to round-off (tested: 1e-14)."""
    checks.instance("interrupted", interrupted, SimulationInterrupted)
    part = interrupted.run
    params = dict(params, initial=interrupted.state, t_end=interrupted.remaining,
                  dt=interrupted.dt, save_every=part.save_every, tol=None,
                  record_phase=interrupted.record_phase,
                  method=part.method)
    rest = simulate(**params)
    return joined(part, rest, interrupted.time, completed=True, final_state=rest.final_state)


#: the record arrays of a Run
RECORDS = ("t", "energy", "theta", "U", "theta_hat", "U_hat")


def joined(part: Run, rest: Run, time: float, **changes) -> Run:
    """``part`` followed by ``rest``, a run started from ``part``'s state at ``time``:
    rest's record 0 (that state, not a record of the grid) dropped, its times shifted."""
    merged = {}
    for name in RECORDS:
        a, b = getattr(part, name), getattr(rest, name)
        if a is not None:
            merged[name] = np.concatenate([a, b[1:] + time if name == "t" else b[1:]])
    return dataclasses.replace(part, **merged, force_evaluations=part.force_evaluations
                               + rest.force_evaluations, **changes)
