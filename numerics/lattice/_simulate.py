"""The paper's numerical experiment: ``simulate`` a noisy plane wave on a periodic chain.

Builds the initial condition (eq. `IC`, or the exact travelling wave), snaps k to the
chain, and runs it in named steps: the record grid (``_record_grid`` -> ``_RecordGrid``), a
Run with room for its records (``_empty_run``), and the stepping loop (``_RunLoop``:
``_integrate._Stepper`` advanced record by record, keeping only what is asked for), which
stops with ``BlowUpError`` or ``SimulationInterrupted`` keeping what was computed.
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
    grid = _record_grid(nsteps, dt_eff, save_every, record_phase)
    run = _empty_run(grid, N, case, store, material=material, k=ks, m=mode,
                     k_requested=float(k), amplitude=amplitude, noise=noise, seed=seed,
                     method=m_.name, dt=dt_eff, t_end=float(t_end),
                     save_every=grid.per_save * dt_eff, start=start)
    loop = _RunLoop(_Stepper(state, material, case, m_, dt_eff, rtol, atol), run, grid,
                    max_energy_error)
    loop.run_to_end(progress)
    return loop.finish(energy_tolerance)


@dataclass(frozen=True)
class _RecordGrid:
    """The steps of a run and its records: at step 0, at ``first``, every ``per_save``
    steps after it, and at the last step ``nsteps``."""

    nsteps: int
    per_save: int
    #: steps done since the last record, when resuming an interrupted run: the records
    #: keep that run's grid
    phase: int = 0

    @property
    def first(self) -> int:
        """The step of record 1."""
        return self.per_save - self.phase

    @property
    def count(self) -> int:
        """The number of records, those at step 0 and at the last step included."""
        return 2 + (0 if self.first >= self.nsteps
                    else -(-(self.nsteps - self.first) // self.per_save))

    def step_of(self, j: int) -> int:
        """The step of record j >= 1."""
        return min(self.first + (j - 1) * self.per_save, self.nsteps)

    def since_record(self, steps: int, j: int) -> int:
        """Steps done since the last record when record j is the next (a resume's phase)."""
        return steps - (self.first + (j - 2) * self.per_save if j > 1 else -self.phase)


def _record_grid(nsteps: int, dt: float, save_every, record_phase) -> _RecordGrid:
    """The record grid of ``nsteps`` steps of ``dt``: a record every ``save_every``
    (rounded to whole steps; default about 1000 records), continued at ``record_phase``."""
    if save_every is None:
        per_save = max(1, round(nsteps / 1000))
    else:
        save_every = checks.positive("save_every", save_every)
        per_save = max(1, round(save_every / dt))
    phase = checks.integer("record_phase", record_phase, 0, per_save)
    return _RecordGrid(nsteps, per_save, phase)


def _empty_run(grid: _RecordGrid, N: int, case: str, store: str, **fields) -> Run:
    """A Run with room for the grid's records of what ``store`` keeps (energy always)."""
    nrec, nq = grid.count, N // 2 + 1
    coupled = case == "coupled"
    snapshots, spectra = store == "snapshots", store == "spectrum"
    return Run(t=np.empty(nrec), energy=np.empty(nrec),
               theta=np.empty((nrec, N)) if snapshots else None,
               U=np.empty((nrec, N)) if snapshots and coupled else None,
               theta_hat=np.empty((nrec, nq)) if spectra else None,
               U_hat=np.empty((nrec, nq)) if spectra and coupled else None,
               case=case, N=N, store=store, **fields)


class _RunLoop:
    """Advances a run's stepper from record to record, filling ``run``; stops with a
    BlowUpError or a SimulationInterrupted that keep the records taken."""

    def __init__(self, stepper, run: Run, grid: _RecordGrid, max_energy_error: float):
        self.st, self.run, self.grid = stepper, run, grid
        self.max_energy_error = max_energy_error
        self.steps = 0  # steps the stepper's state has done: its time is steps * dt
        self.j = 0  # the next record

    def time(self) -> float:
        """The stepper's time."""
        return self.steps * self.st.dt

    def record(self):
        """Take record j of the stepper's state (what ``run.store`` keeps)."""
        st, run, j = self.st, self.run, self.j
        run.t[j] = self.time()
        cur = LatticeState(st.U, st.V, st.th, st.w) if st.coupled else \
            LatticeState(None, None, st.th, st.w)
        run.energy[j] = energy(cur, run.material, run.case)
        if run.theta is not None:
            run.theta[j] = st.th
            if run.U is not None:
                run.U[j] = st.U
        if run.theta_hat is not None:
            run.theta_hat[j] = spectrum(st.th)
            if run.U_hat is not None:
                run.U_hat[j] = spectrum(st.U)

    def run_to_end(self, progress):
        """Record the initial state, then step and record to the end, Ctrl-C deferred to
        the end of a compiled call (then SimulationInterrupted)."""
        self.record()
        self.j += 1
        bar = _progress(self.run.t_end, progress)
        try:
            with _deferred_interrupt() as interrupted:
                self._step_and_record(interrupted, bar)
        except (_Interrupt, KeyboardInterrupt) as exc:
            if isinstance(exc, SimulationInterrupted):
                raise
            signum = exc.args[0] if isinstance(exc, _Interrupt) else signal_number(exc)
            raise self.interruption(signum) from None
        finally:
            if bar is not None:
                bar.close()

    def _step_and_record(self, interrupted, bar):
        """The stepping loop: chunks of at most one compiled call, a record at each grid
        point, the energy checked there; ``interrupted()`` is the signal that came (or 0)."""
        grid, st, run = self.grid, self.st, self.run
        sub = _steps_per_call(run.N, st.method, grid.per_save)
        while self.steps < grid.nsteps:
            target = grid.step_of(self.j)  # the next record
            while self.steps < target:
                n = min(sub, target - self.steps)
                got = st.advance(n)
                self.steps += got
                if got < n:
                    raise self.blow_up("non-finite")
                if interrupted() and self.steps < target:
                    raise _Interrupt(interrupted())
            self.record()
            j = self.j
            drift = abs(run.energy[j] - run.energy[0]) / abs(run.energy[0])
            if not drift <= self.max_energy_error:  # also catches NaN
                raise self.blow_up("energy", drift)
            if bar is not None:
                bar.update(run.t[j] - run.t[j - 1])
            self.j += 1
            if interrupted() and self.steps < grid.nsteps:
                raise _Interrupt(interrupted())

    def keep_records(self):
        """Cut the run to the records before record j (taken or not), not completed."""
        run = self.run
        for name in RECORDS:
            arr = getattr(run, name)
            if arr is not None:
                setattr(run, name, arr[:self.j])
        run.completed = False
        run.force_evaluations = self.st.evaluations

    def blow_up(self, reason: str, drift: float | None = None) -> BlowUpError:
        """The BlowUpError of a failure now (``reason``: "non-finite", or "energy" in the
        record j just taken), with the records before it."""
        self.keep_records()
        st, run = self.st, self.run
        return BlowUpError(_blowup_message(self.time(), st.dt, run.material, run.case,
                                           st.method, reason, drift, self.max_energy_error),
                           run, self.time())

    def interruption(self, signum: int) -> SimulationInterrupted:
        """The SimulationInterrupted of a stop now: the records taken, the state, and the
        call that resumes the run on its record grid."""
        self.keep_records()
        st, run = self.st, self.run
        dt = st.dt
        left = self.grid.nsteps - self.steps
        since = self.grid.since_record(self.steps, self.j)
        return SimulationInterrupted(
            f"interrupted at T = {self.time():.10g} of {run.t_end:g}; exc.run keeps "
            f"{len(run.t)} records (to T = {run.t[-1]:g}). Resume with simulate(..., "
            f"initial=exc.state, t_end={left * dt!r}, dt={dt!r}, "
            f"record_phase={since}) (times then count from 0), or numerics.resume(exc, "
            "**the same arguments)",
            run=run, state=st.state(), time=self.time(), remaining=left * dt,
            dt=dt, record_phase=since, signum=signum)

    def finish(self, energy_tolerance: float) -> Run:
        """The completed run: its final state, its force evaluations, and the accuracy
        check (fixed-step methods)."""
        st, run = self.st, self.run
        run.final_state = st.state()
        run.force_evaluations = st.evaluations
        if st.method.fixed_step:
            energy_check(run.energy_error, energy_tolerance, st.method.name, st.dt)
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
