"""Simulation of any lattice model on a ring: ``simulate_model`` -> ``ModelRun`` (the
seeded runs of a point, ``simulate_seeds``: ``_seeds``).

A run steps in ``numerics.lattice.ForceStepper``, the one implementation of the registry's
fixed-step integrators (``numerics.METHODS``) for a compiled force: the symplectic SRKN
family (srkn11b by default, order 6), verlet, kahanli8 and rk4, with the coefficients of
``numerics.lattice.Method``; the kick that ends a step and the one that starts the next
share one force evaluation. The force is the model's generated one (``_compiled``), or the
fast force registered for its energy (``_forces``: the fused flexMM kernel). A lossy model
adds its damping (``_damping``).

Start. ``start="exact"`` (default) launches the exact travelling wave (harmonic balance,
``travelling_wave``) plus seeded noise; ``start="linear"`` the linear plane wave, which
leaves free second-harmonic and mean-flow waves beside the carrier; a start registered by
the model (``_extras``: ``"paper"``, eq. `IC`, for the paper chain's energy) its own state
and noise. The growth is measured against the exact wave in every case.

Measurement: ``_growth`` (``ModelRun.growth``, ``ModelRun.amplification``).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from common.threads import one_blas_thread
from energy import Model, ModelError

from ._args import (  # MAX_RING, check_ring, snap_ring: here too, for their importers
    MAX_RING,  # noqa: F401
    check_count,
    check_noise,
    check_rate,
    check_ring,  # noqa: F401
    scalar,
    snap_ring,
)

# compiled_force, lattice_energy, lattice_force: here too, for the modules that import them
# from here (the package's __init__, _reach)
from ._compiled import _kernels, compiled_force, lattice_energy, lattice_force  # noqa: F401
from ._damping import damping_flow, loss_spacing, rayleigh
from ._growth import (
    SATURATION,
    Amplification,
    Growth,
    _lower_keep,
    amplitude_series,
    harmonic_drift,
    measure_amplification,
    measure_growth,
)

#: noise relative to the amplitude: 16 e-foldings fit below SATURATION
NOISE = 1e-8
STARTS = ("exact", "linear")

class _Stop(Exception):
    """Ctrl-C noticed between two compiled calls of a run; ``args[0]``: the signal."""


#: the most steps a run may take: 1e10 steps of a small ring are hours of CPU; a run past
#: it is a stiff model (a mass of 1e-300 puts a branch at 1e150: 1e154 steps, where the
#: run and the estimate's probe hung without a word) or a T no one can wait for
MAX_STEPS = 1e10


def _exp_integral(h: float, f0: float, f1: float) -> float:
    """The integral of a power (2R >= 0) over an interval of length h between samples f0
    and f1, taking it exponential through both: h (f1 - f0) / ln(f1 / f0), the
    trapezoid's h (f0 + f1) / 2 where they are equal (the log's cancellation) or one is 0.
    A damped wave's 2R decays exponentially, and a long run's records are far apart:
    trapezoids were off by (h 2 Gamma)^2 / 12 of it per interval (issue 94: a Klein-Gordon
    run of T = 38500 with 400 records, h 2 Gamma = 2.3, read 0.41 of E(0) where this reads
    3e-4); second order like them elsewhere."""
    r = math.log(f1 / f0) if f0 > 0 and f1 > 0 else 0.0
    return h * (f1 - f0) / r if abs(r) >= 1e-6 else h * (f0 + f1) / 2


def _lost_power(t: np.ndarray, power: np.ndarray) -> np.ndarray:
    """``_exp_integral`` over each interval between records (the records' 2R)."""
    return np.array([_exp_integral(float(h), float(f0), float(f1)) for h, f0, f1 in
                     zip(np.diff(t), power[:-1], power[1:])], float)


#: a damped run's samples of 2R for its energy balance, in radians of the carrier: 2R of
#: the ring wavers at 2 omega (the decaying carrier sheds free harmonics), and samples
#: near pi / omega apart alias it. Issue 94, lossy Klein-Gordon (k 3.09, a 0.0465, T 8000,
#: records 20 apart): balance error 2.0e-3 from the records; from samples 1, 2, 3, 4 and 8
#: radians apart 3.6e-6, 4.3e-5, 9.8e-4, 1.6e-4, 1.9e-4, the run's CPU time 4.9x, 2.9x,
#: 2.1x, 1.8x, 1.3x (a compiled call per sample). At T 38500 (records 96 apart; from the
#: records alone 5.5e-4): 2, 4 and 8 radians 3.5e-5, 8.1e-5, 1.7e-5 at 3.9x, 2.4x, 1.7x the
#: CPU of the same run recording no energy (one process). 8: the balance stays 1e-4-level
#: (a diagnostic; the tests' bar 1e-3 .. 2e-4) at the least cost. A map cell records no
#: energy: no samples.
LOSS_SAMPLE = 8.0


def _spend(spent: list, t: float, power: float) -> None:
    """Add the integral of 2R from ``spent``'s last sample to (t, power) to ``spent`` =
    [integral, last time, last 2R] (``_exp_integral``, the records' rule)."""
    spent[0] += _exp_integral(t - spent[1], spent[2], power)
    spent[1], spent[2] = t, power


@dataclass(frozen=True)
class ModelRun:
    """A run of a model's ring: what it recorded and the growth it measured.

    Attributes
    ----------
    k, amplitude, N, t_end, dt, method, start, noise, seed
        The run's inputs (k snapped to the ring; start "initial" where one was given).
    wave : TravellingWave
        The exact wave the deviation is measured from.
    t : ndarray
        Record times.
    spectrum : ndarray, shape (records, N)
        |FFT of the deviation| per ring mode j, summed over fields in quadrature.
    deviation : ndarray
        rms deviation from the exact wave over sites and fields, per record.
    energy : ndarray
        Total energy per record (from the model file).
    """

    model: Model
    k: float
    amplitude: float
    N: int
    t_end: float
    dt: float
    method: str
    start: str
    noise: float
    seed: int
    wave: object
    t: np.ndarray
    spectrum: np.ndarray
    deviation: np.ndarray
    energy: np.ndarray
    #: 2 R (the power the losses take) per record; None for a lossless model
    dissipation: np.ndarray | None = None
    #: int_0^t 2 R dt' at each record, from 2 R sampled every ``LOSS_SAMPLE`` radians of
    #: the carrier (``simulate_model``); None: from the records' ``dissipation``
    lost: np.ndarray | None = None
    #: whether the run stopped where its amplification had peaked (``until_peak``)
    peaked: bool | None = None
    #: (u, v) at the run's end, each (d, N)
    state: tuple | None = None
    #: the force that ran: "generated" (from the energy) or "fast:NAME", a registered fast
    #: force (``numerics.models.run_force``)
    force: str = "generated"

    def energy_balance(self) -> float:
        """max over the records of |E(t) - E(0) + int_0^t 2 R dt'| / E(0): the error of
        dE/dt = -2 R (0 for a lossless model). Between two records 2R is integrated as an
        exponential through both (``_lost_power``), unless the run kept the integral from
        finer samples (``lost``)."""
        if self.dissipation is None:
            return self.energy_drift
        lost = self.lost if self.lost is not None else np.concatenate(
            [[0.0], np.cumsum(_lost_power(self.t, self.dissipation))])
        return float(np.max(np.abs(self.energy - self.energy[0] + lost)) / abs(
            self.energy[0]))

    def amplification(self) -> Amplification:
        """The sidebands' amplification (issue 42): A(t), the largest |mode| over the ring
        modes that are not harmonics of the carrier; max A(t) / A(0) and when."""
        return measure_amplification(self)

    @property
    def energy_drift(self) -> float:
        """max |E(t) - E(0)| / |E(0) - E_rest| over the run (E_rest = 0 at rest)."""
        return float(np.max(np.abs(self.energy - self.energy[0])) / abs(self.energy[0]))

    def to_xarray(self):
        """The records as an ``xarray.Dataset`` over ``t``: ``deviation`` (rms from the
        exact wave), ``energy`` and ``spectrum`` (over ring mode j); inputs in attrs."""
        import xarray as xr

        attrs = {"model": self.model.name, "k": self.k, "amplitude": self.amplitude,
                 "N": self.N, "t_end": self.t_end, "dt": self.dt, "method": self.method,
                 "start": self.start, "noise": self.noise, "seed": self.seed,
                 "omega": self.wave.omega, "force": self.force}
        attrs.update({f"param_{n}": v for n, v in self.model.params.items()})
        j = np.arange(self.N)
        return xr.Dataset(
            {"deviation": ("t", self.deviation, {"long_name": "rms deviation from the exact "
                                                               "travelling wave"}),
             "energy": ("t", self.energy, {"long_name": "total energy (model file)"}),
             "spectrum": (("t", "mode"), self.spectrum,
                          {"long_name": "|FFT of the deviation| / N, fields in quadrature"})},
            coords={"t": ("t", self.t, {"units": "time (lattice units)"}),
                    "mode": ("mode", j, {"long_name": "ring mode j: wavenumber 2 pi j / N"})},
            attrs=attrs)

    def growth(self) -> Growth:
        """What the run shows: unstable with a rate, or no growth within T."""
        return measure_growth(self)


def saturation_time(rate: float, noise: float = NOISE) -> float:
    """About when a run with ``until_saturated`` stops: its fastest mode, ``rate`` (1/time),
    grown from the noise (``noise`` of the amplitude) to ``SATURATION`` of the amplitude,
    ln(SATURATION / noise) / rate; inf where nothing grows (the run goes to T). For a
    map's estimate: the noise spreads over the modes, so the stop comes a little later."""
    if not (math.isfinite(rate) and rate > 0 and noise > 0):
        return math.inf
    # noise at or above SATURATION is saturated from the start (was a negative time)
    return max(0.0, math.log(SATURATION / noise) / rate)


#: ``until_peak`` stops a run once A(t) has risen this much (sqrt(20), the runs' own
#: boundary of "no growth") and fallen to half its top: a launch transient (a new user's
#: damped chain rose 2.4x by t = 52, fell, and the sidebands peaked near t = 1700) is not
#: the sidebands' peak
PEAK_RISE = math.sqrt(20.0)


# one BLAS thread: each record's wave on the ring is a (d, 2H+1) @ (2H+1, N) product, 3.8 ms
# a call on OpenBLAS' two threads of a loaded 2-core machine against microseconds on one
# (a new user's pendulum chain, N 256, T 100: 0.79 s wall against 0.017 s; a map's probe
# read its run as 3.2-3.7 s of CPU for 0.07-0.09 s and estimated 4 min for a 34 s map)
@one_blas_thread
def simulate_model(model: Model, k: float, amplitude: float, *, branch=None, N: int = 256,
                   t_end: float | None = None, dt: float | None = None,
                   method: str = "srkn11b", start: str = "exact", noise: float | None = None,
                   seed: int = 0, records: int = 400, expected_gain: float | None = None,
                   wave=None, until_peak: bool = False,
                   noise_on: str = "all", initial=None, force: str = "auto",
                   on_steps=None, energy: bool = True,
                   until_saturated: bool = False) -> ModelRun:
    """Run the ring of ``model`` from a plane wave at ``k`` (snapped to the ring) with
    first harmonic ``amplitude`` in its carrier field, plus seeded noise (``noise`` of the
    amplitude, None: NOISE). ``start``: "exact" (the exact travelling wave), "linear", or a
    start the model registers (``extra_starts``: "paper", eq. `IC`, for the paper chain's
    energy, with its own noise law, b0 ~ U[-noise, noise], None: the paper's 1e-3).

    ``t_end`` None: ``numerics.lattice.run_length`` of ``expected_gain`` (default: the
    exact theory's on this ring), as for the paper's chain: 9 e-foldings within
    [1 000, 100 000], 5 000 where nothing is predicted to grow. ``dt`` None: a fifth of
    the method's stability limit over the highest frequency of the lattice, or of the
    start state where it is stiffer (``_step``); a ``dt`` past the limit is refused.

    A model with [dissipation] runs with its damping force -M^-1 dR/dv: ``rk4`` takes it
    in every stage; an SRKN method is wrapped in a Strang splitting (the damping flow's
    exact half steps around each symplectic step: order 2). ``until_peak``: stop once
    the sidebands' amplitude A(t) (``amplitude_series``) has risen ``PEAK_RISE`` (sqrt 20)
    times and fallen to half its maximum (else ``t_end`` is the cap); a time: not before it
    (> 0, the theory's peak: a first band may peak and fall before a later one, probe 98). ``noise_on="carrier"``: the noise on the
    carrier field's positions only (the amplification's launch, issue 42). ``initial``:
    (u, v), each shape (d, N), the state to start from instead of ``start`` (noise added).
    ``force="generated"``: the force generated from the energy even where a fast force
    is registered for it ("auto", the default: the fused flexMM kernel for the paper
    chain's energy, ``numerics.lattice.register_fast_force``); ``ModelRun.force`` says
    which ran. ``on_steps(n, nsteps)``: called after every stretch of ``n`` of the run's
    ``nsteps`` steps (a progress bar). ``energy=False``: the total energy is not recorded
    (``ModelRun.energy`` NaN, its drift NaN): a map cell's columns do not use it, and the
    model's energy kernel (compiled per process, no disk cache: ~1.3 s) is then never
    compiled. ``until_saturated``: stop at the record where the sidebands (every carrier
    harmonic left out) reach ``SATURATION`` of the amplitude (``saturation_record``): the
    linear stage has ended there, so ``growth()`` is that of the whole run, bit for bit (a
    map cell's run: an MI cell stops there, a stable one runs T); ``t_end`` is then the
    last record's time. A state that stops being finite raises ``numerics.BlowUpError``
    (a FloatingPointError; its ``time`` when the stepper saw it).
    """
    from common.signals import signal_number
    from numerics.lattice import (
        BlowUpError,
        ForceStepper,
        SimulationInterrupted,
        band_flow,
        deferred_interrupt,
        get_method,
        local_flow,
        run_length,
        steps_per_call,
    )

    from ._exact import ring_offsets, travelling_wave
    from ._forces import FORCES, run_force
    from ._step import run_step

    meth = get_method(method)
    if meth.kind not in ("srkn", "rk4"):
        raise ModelError(f"method {method!r} is not a fixed-step method; choose one of "
                         "srkn11b, srkn6b, kahanli8, verlet, rk4")
    extra = None
    if start not in STARTS:  # a start only some models have (the paper's eq. IC)
        from ._extras import extra_starts

        theirs = extra_starts(model)
        extra = theirs.get(start)
        if extra is None:
            raise ModelError(
                f"start must be one of {', '.join((*STARTS, *theirs))} for model "
                f"{model.describe()}, got {start!r}" + (
                    " (start 'paper', the paper's eq. IC, belongs to the paper chain's "
                    "energy, lossless)" if start == "paper" else ""))
    if force not in FORCES:
        raise ModelError(f"force must be one of {', '.join(FORCES)}, got {force!r}")
    if noise is None:  # the start's own: 1e-8 of the amplitude, the paper's b0 for eq. IC
        noise = extra.noise if extra is not None else NOISE
    noise = check_noise(noise)
    records = check_count("records", records)
    seed = check_count("seed", seed, least=0)
    k_ring, _ = snap_ring(k, N)
    if wave is None:
        wave = travelling_wave(model, k_ring, amplitude, branch)
    else:  # before: another model's, amplitude's or k's wave was run silently
        from ._seeds import check_wave
        check_wave(model, k_ring, amplitude, wave, branch)
    if expected_gain is not None:
        expected_gain = check_rate("expected_gain", expected_gain)
    if t_end is None:
        if expected_gain is None and extra is not None:  # the launched state's theory
            expected_gain = extra.theory(model, k_ring, amplitude, N)["peak_gain"] or 0.0
        if expected_gain is None:
            from ._exact import hill_spectrum
            expected_gain = hill_spectrum(wave, ring_offsets(N)).peak_gain
        from ._time_scale import time_scale
        t_end = run_length(expected_gain, time_scale=time_scale(model)).t_end
    t_end = scalar(t_end)
    if isinstance(t_end, bool) or not isinstance(t_end, (int, float, np.floating)) or not (
            math.isfinite(t_end) and t_end > 0):
        raise ModelError(f"t_end must be a finite time > 0, got {t_end!r}")
    d = model.n_fields
    rng = np.random.default_rng(seed)
    u, v = wave.state(N)
    if start == "linear":
        xi = k_ring * np.arange(N)
        e = wave.carrier.e[:, None]
        w0 = wave.carrier.omega
        u = amplitude * np.real(e * np.exp(1j * xi))
        v = amplitude * w0 * np.real(-1j * e * np.exp(1j * xi))
    added = noise  # the noise added below: an extra start's own law is in its state
    if extra is not None and initial is None:
        u, v = extra.state(model, k_ring, amplitude, N, noise, seed)
        added = 0.0
    if initial is not None:  # before: numpy's "cannot reshape array of size 64 ..."
        if not (isinstance(initial, (tuple, list)) and len(initial) == 2) or any(
                np.size(x) != d * N for x in initial):
            raise ModelError(f"initial must be a pair (u, v), each of shape (d, N) = "
                             f"({d}, {N}), got {type(initial).__name__} of shapes "
                             f"{[np.shape(x) for x in initial][:2]}")
        u, v = (np.array(x, dtype=float).reshape(d, N) for x in initial)
        if not (np.all(np.isfinite(u)) and np.all(np.isfinite(v))):  # was a BlowUpError
            raise ModelError("initial must be finite: its (u, v) hold nan or inf")
    if noise_on not in ("all", "carrier"):
        raise ModelError(f"noise_on must be 'all' or 'carrier', got {noise_on!r}")
    if noise_on == "carrier":
        kick = np.zeros((d, N))
        kick[wave.carrier.field] = rng.standard_normal(N)
        u = np.ascontiguousarray(u + added * amplitude * kick)
        v = np.ascontiguousarray(v)
    elif added:
        u = np.ascontiguousarray(u + added * amplitude * rng.standard_normal((d, N)))
        v = np.ascontiguousarray(v + added * amplitude * wave.omega * rng.standard_normal(
            (d, N)))
    else:
        u, v = np.ascontiguousarray(u, float), np.ascontiguousarray(v, float)
    kernel, p_force, rows, force_label = run_force(model, force)
    dt, wmax = run_step(model, meth, wave, dt, u, kernel, p_force, rows)
    if t_end / dt > MAX_STEPS:
        raise ModelError(f"the lattice's highest frequency {wmax:.3g} asks for a step dt = "
                         f"{dt:.3g}: a run of T = {t_end:g} would take {t_end / dt:.2g} "
                         f"steps, more than "
                         f"{MAX_STEPS:g}; a model whose frequencies span less (a mass near "
                         "0 is stiff), or a shorter T")
    nsteps = max(1, int(math.ceil(t_end / dt)))
    dt = t_end / nsteps
    every = max(1, nsteps // records)
    energy_of = _kernels(model).energy if energy else None
    p = np.asarray(model.p, float)
    masses = np.asarray(model.masses, float)
    x = np.empty(2 * d)
    ts, spec, dev, en, diss, lost = [], [], [], [], [], []
    lossy = model.lossy
    damping = flow = None
    if lossy:
        S_d, B_d = model.damping
        damping = (np.ascontiguousarray(S_d), np.ascontiguousarray(B_d), 1 / masses)
        if meth.kind == "srkn":  # Strang: the damping's exact half-step flow around a step
            E_modes, E_local = damping_flow(model, N, dt / 2)
            flow = ((local_flow, (np.ascontiguousarray(E_local),)) if E_local is not None
                    else (band_flow, (*E_modes, np.empty((d, N)))))
    stepper = ForceStepper(kernel, p_force, rows, u, v, meth, dt,
                           damping=damping, flow=flow)

    wave_at = wave.ring_profile(N, k_ring)  # wave.profile on the ring, for many t
    launch = "initial" if initial is not None else start  # off the family (harmonic_drift)

    def record(t):
        U = wave_at(t)
        delta = u - U
        ts.append(t)
        # a state past 1e154 overflows its squares to inf: a run leaving the lattice's range,
        # which the stepper's check or a map's saturation stop says (numpy's warnings did not)
        with np.errstate(over="ignore", invalid="ignore"):
            spec.append(np.sqrt(np.sum(np.abs(np.fft.fft(delta, axis=1)) ** 2, axis=0)) / N)
            dev.append(float(np.sqrt(np.mean(delta**2))))
        en.append(energy_of(u, v, p, masses, x) if energy_of is not None else math.nan)
        if lossy:
            diss.append(2 * rayleigh(model, v, (S_d, B_d)))
            lost.append(spent[0])

    def run_so_far(t_last):
        """The run's records so far (to ``t_last``) and its state now."""
        return ModelRun(model=model, k=k_ring, amplitude=float(amplitude), N=N,
                        t_end=t_last, dt=dt, method=method, start=launch, noise=float(noise),
                        seed=int(seed), wave=wave, t=np.array(ts), spectrum=np.array(spec),
                        deviation=np.array(dev), energy=np.array(en),
                        dissipation=np.array(diss) if lossy else None,
                        lost=np.array(lost) if lossy and energy else None, peaked=peaked,
                        state=(u.copy(), v.copy()), force=force_label)

    spent = [0.0, 0.0, 2 * rayleigh(model, v, (S_d, B_d))] if lossy else None
    record(0.0)
    done = 0
    peaked = None
    saturated = False
    if until_saturated:
        lower = _lower_keep(N, int(round(k_ring * N / (2 * math.pi))), wave.harmonics)
        level = SATURATION * float(amplitude)
    if until_peak:
        # measure_amplification's modes (``amplitude_series``)
        drift = harmonic_drift(wave, N, k_ring, launch == "exact")
        a0 = float(amplitude_series(spec[0], drift))
        top = a0
        peaked = False
        hold = 0.0 if until_peak is True else float(until_peak)  # no stop before it
    # Ctrl-C (SIGINT, or SIGTERM where handled as one) is deferred to the end of a compiled
    # call of bounded work (numerics.lattice's run control): the run stops on a state whose
    # time is known, with its records kept (SimulationInterrupted)
    per_call = steps_per_call(N * d, meth, every)
    # a damped run that records its energy integrates 2R between records from samples
    # LOSS_SAMPLE radians of the carrier apart, at most ``loss_spacing`` (``spent``)
    sub = max(1, int(min(LOSS_SAMPLE / wave.omega, loss_spacing(model, N)) / dt)) \
        if lossy and energy else per_call
    try:
        with deferred_interrupt() as interrupted:
            while done < nsteps:
                before = done
                target = min(done + every, nsteps)
                while done < target:
                    n = min(per_call, target - done, sub)
                    got = stepper.advance(n)
                    done += got
                    if lossy:
                        _spend(spent, done * dt, 2 * rayleigh(model, v, (S_d, B_d)))
                    if got < n or not np.all(np.isfinite(u)):
                        raise BlowUpError(
                            f"model {model.describe()}: the run blew up by t = "
                            f"{done * dt:.4g} (dt = {dt:.3g}, method {method}): the wave "
                            "left the lattice's range; lower the amplitude or dt",
                            time=done * dt)
                    if interrupted() and done < nsteps:
                        raise _Stop(interrupted())
                record(done * dt)
                if on_steps is not None:
                    on_steps(done - before, nsteps)
                if until_saturated and math.sqrt(2 * float(np.sum(
                        spec[-1][lower] ** 2))) > level:  # saturation_record's reading
                    saturated = True
                    break
                if until_peak:
                    a = float(amplitude_series(spec[-1], drift))
                    top = max(top, a)
                    if top >= PEAK_RISE * a0 and a <= top / 2 and done * dt >= hold:
                        peaked = True
                        break
            if interrupted():  # at the last record: the run is whole, and says it stopped
                raise _Stop(interrupted())
    except (_Stop, KeyboardInterrupt) as exc:
        if isinstance(exc, SimulationInterrupted):
            raise
        signum = exc.args[0] if isinstance(exc, _Stop) else signal_number(exc)
        # a KeyboardInterrupt (a second Ctrl-C) may land inside a record: keep whole ones
        whole = min(len(r) for r in (ts, spec, dev, en) + ((diss, lost) if lossy else ()))
        for r in (ts, spec, dev, en, diss, lost):
            del r[whole:]
        kept = run_so_far(float(ts[-1]))
        raise SimulationInterrupted(
            f"model {model.describe()}: interrupted at t = {done * dt:.10g} of "
            f"{t_end:g}; exc.run keeps {len(ts)} records (to t = {ts[-1]:g}), exc.state "
            "the state at exc.time", run=kept, state=(u.copy(), v.copy()), time=done * dt,
            remaining=(nsteps - done) * dt, dt=dt, signum=signum) from None
    return run_so_far(float(ts[-1]) if until_peak or saturated else float(t_end))
