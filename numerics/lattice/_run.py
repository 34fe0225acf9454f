"""A run of the simulator: its result (``Run``), the grid its records fall on, and the loop
that advances a stepper from record to record and fills them (``RunLoop``), stopping with
``BlowUpError`` or ``SimulationInterrupted`` keeping what was computed. ``simulate``
(``_simulate``) builds the start and the stepper and hands them to it.
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass

import numpy as np

from common.signals import signal_number

from . import checks
from ._accuracy import energy_check
from ._analysis import spectrum
from ._integrate import BlowUpError, SimulationInterrupted, blowup_message
from ._model import LatticeState, Material, energy
from ._runcontrol import _deferred_interrupt, _Interrupt, _progress, _steps_per_call


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

    def to_xarray(self):
        """The run as an ``xarray.Dataset``: ``theta``, ``U`` over (t, site) and/or
        ``theta_hat``, ``U_hat`` over (t, wavenumber), ``energy`` over t, with units in
        the variables' attrs and every input (material, case, k, amplitude, start, noise,
        seed, method, dt) in the dataset's attrs. ``ds.to_netcdf(path)`` or
        ``ds.to_zarr(path)`` stores it.

        Returns
        -------
        xarray.Dataset
        """
        import xarray as xr

        data = {"energy": ("t", self.energy, {"long_name": "total energy (eq. `norm`)",
                                             "units": "lattice units"})}
        for name, v, dims, what in (("theta", self.theta, ("t", "site"), "rotation"),
                                    ("U", self.U, ("t", "site"), "longitudinal displacement"),
                                    ("theta_hat", self.theta_hat, ("t", "wavenumber"),
                                     "|rfft(theta)| 2/N"),
                                    ("U_hat", self.U_hat, ("t", "wavenumber"),
                                     "|rfft(U)| 2/N")):
            if v is not None:
                data[name] = (dims, np.asarray(v), {
                    "long_name": what, "units": "rad" if name.startswith("theta")
                    else "lattice spacing a"})
        coords = {"t": ("t", self.t, {"long_name": "time T = t sqrt(k_l/m)",
                                      "units": "lattice time"})}
        if self.theta is not None or self.U is not None:
            coords["site"] = ("site", np.arange(self.N), {"long_name": "site n"})
        if self.theta_hat is not None or self.U_hat is not None:
            coords["wavenumber"] = ("wavenumber", self.wavenumbers,
                                    {"long_name": "wavenumber q (absolute)",
                                     "units": "rad per site"})
        m = self.material
        attrs = {"alpha": m.alpha, "K_s": m.K_s, "K_theta": m.K_theta, "case": self.case,
                 "N": self.N, "k": self.k, "m": self.m, "k_requested": self.k_requested,
                 "amplitude": self.amplitude, "noise": self.noise, "seed": self.seed,
                 "method": self.method, "dt": self.dt, "t_end": self.t_end,
                 "save_every": self.save_every, "store": self.store, "start": self.start,
                 "completed": int(self.completed), "units": "lattice units: T = t sqrt(k_l/m), "
                 "wavenumbers in rad per site, rotations in rad"}
        return xr.Dataset(data, coords=coords, attrs=attrs)

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


@dataclass(frozen=True)
class RecordGrid:
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


def record_grid(nsteps: int, dt: float, save_every, record_phase) -> RecordGrid:
    """The record grid of ``nsteps`` steps of ``dt``: a record every ``save_every``
    (rounded to whole steps; default about 1000 records), continued at ``record_phase``."""
    if save_every is None:
        per_save = max(1, round(nsteps / 1000))
    else:
        save_every = checks.positive("save_every", save_every)
        per_save = max(1, round(save_every / dt))
    phase = checks.integer("record_phase", record_phase, 0, per_save)
    return RecordGrid(nsteps, per_save, phase)


def empty_run(grid: RecordGrid, N: int, case: str, store: str, **fields) -> Run:
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


class RunLoop:
    """Advances a run's stepper from record to record, filling ``run``; stops with a
    BlowUpError or a SimulationInterrupted that keep the records taken."""

    def __init__(self, stepper, run: Run, grid: RecordGrid, max_energy_error: float):
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
        return BlowUpError(blowup_message(self.time(), st.dt, run.material, run.case,
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
