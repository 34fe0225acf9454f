"""The paper's numerical experiment: ``simulate`` a noisy plane wave on a periodic chain.

Builds the initial condition (eq. `IC`, or the exact travelling wave), snaps k to the
chain, chooses the step, and runs it in named steps (``_run``): the record grid
(``record_grid`` -> ``RecordGrid``), a Run with room for its records (``empty_run``), and
the stepping loop (``RunLoop``: ``_integrate.Stepper`` advanced record by record, keeping
only what is asked for), which stops with ``BlowUpError`` or ``SimulationInterrupted``
keeping what was computed.
"""

from __future__ import annotations

import math
import numbers

import numpy as np

from common.paper import A0 as PAPER_A0
from common.paper import EPS as PAPER_EPS

from . import checks
from ._accuracy import check_energy_tolerance
from ._integrate import SimulationInterrupted, Stepper, check_time, check_tolerances, resolve_step
from ._integrators import get_method
from ._model import LatticeState, Material, check_case
from ._run import RECORDS, Run, RunLoop, empty_run, joined, record_grid
from ._starts import LEGACY_OMEGA_MODELS, build_start, check_start

STORE_CHOICES = ("snapshots", "spectrum", "energy")


def _check_sites(N):
    """N: an integer in [3, 1e8] (more sites than that does not fit a 24 GiB machine)."""
    return checks.integer("N", N, 3, 10**8 + 1)


#: simulate() and a map cell refuse a k further than this (relative) from 2 pi m / N
RUN_REL_TOL = 1e-3


def snap_wavenumber(k: float, N: int, *, rel_tol: float | None = None,
                    return_index: bool = False):
    """The periodic wavenumber 2 pi m / N nearest to k, on a chain of N sites.

    Parameters
    ----------
    k : float
        Wavenumber (rad per site), in (0, pi).
    N : int
        Sites of the periodic chain (>= 3).
    rel_tol : float, optional
        Strictness: raise ValueError when the nearest 2 pi m / N is further than
        ``rel_tol * k`` from k. None (default): always snap.
    return_index : bool, optional
        Also return the mode number m (as ``numpy.unique``'s ``return_index``).

    Returns
    -------
    k_snapped : float
        2 pi m / N.
    m : int
        The mode number, only when ``return_index`` is True.

    Raises
    ------
    ValueError
        k outside (0, pi), k that snaps to 0 or to pi (no sidebands there), or, with
        ``rel_tol``, further from 2 pi m / N than it allows.

    Examples
    --------
    >>> snap_wavenumber(0.8, 500)
    0.8042477193189871
    >>> snap_wavenumber(0.8, 500, return_index=True)
    (0.8042477193189871, 64)
    """
    if isinstance(k, (bool, np.bool_)) or not isinstance(k, numbers.Real):
        raise TypeError(f"k must be a real number, got {type(k).__name__} {k!r}")
    N = _check_sites(N)
    k = float(k)
    if not math.isfinite(k) or k <= 0 or k >= math.pi:
        raise ValueError(f"k must be in (0, {math.pi:g}), got {k!r}")
    if rel_tol is not None and not rel_tol >= 0:  # NaN too: it would turn the check off
        raise ValueError(f"rel_tol must be >= 0 or None, got {rel_tol!r}")
    m = int(round(k * N / (2 * math.pi)))
    ks = 2 * math.pi * m / N
    if m == 0:
        raise ValueError(
            f"k = {k:g} is below the longest wave N = {N} periodic sites carry, 2 pi / N = "
            f"{2 * math.pi / N:.4g}: choose k >= {2 * math.pi / N:.4g}, or more sites (N >= "
            f"{math.ceil(2 * math.pi / k)})")
    if 2 * m >= N:  # the zone boundary: k = pi carries no sidebands (and k < pi)
        need = math.floor(math.pi / (math.pi - k)) + 1
        raise ValueError(
            f"k = {k:g} snaps to pi on N = {N} periodic sites (2 pi m / N with m = N / 2), "
            f"where no sidebands exist: choose k <= {2 * math.pi * ((N - 1) // 2) / N:.4g}"
            + (f", or more sites (N >= {need})" if need <= 10**6 else
               f" (k is within {math.pi - k:.2g} of pi: no chain of up to 10^6 sites "
               "carries it)"))
    if rel_tol is not None and abs(ks - k) > rel_tol * k:
        raise ValueError(
            f"k = {k} is not commensurate with N = {N} periodic sites: the nearest "
            f"2 pi m / N is {ks:.6g} (m = {m}), {abs(ks - k) / k:.2e} away (> {rel_tol:g} "
            f"relative); choose k = 2 pi m / N (snap_wavenumber(k, N) gives it)")
    return (ks, m) if return_index else ks


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
    ks, mode = snap_wavenumber(k, N, rel_tol=RUN_REL_TOL, return_index=True)
    if initial is None:
        state = initial_condition(material, case, N, ks, amplitude, noise, seed, start)
    else:
        state = initial.for_case(case)
        if state.N != N:
            raise ValueError(f"initial state has {state.N} sites, N = {N}")
    method, dt = resolve_step(state, material, case, t_end, dt, method, tol)
    m_ = get_method(method)
    nsteps, dt_eff = check_time(t_end, dt)
    grid = record_grid(nsteps, dt_eff, save_every, record_phase)
    run = empty_run(grid, N, case, store, material=material, k=ks, m=mode,
                    k_requested=float(k), amplitude=amplitude, noise=noise, seed=seed,
                    method=m_.name, dt=dt_eff, t_end=float(t_end),
                    save_every=grid.per_save * dt_eff, start=start)
    loop = RunLoop(Stepper(state, material, case, m_, dt_eff, rtol, atol), run, grid,
                   max_energy_error)
    loop.run_to_end(progress)
    return loop.finish(energy_tolerance)


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


__all__ = ["simulate", "resume", "initial_condition", "noise_field", "snap_wavenumber",
           "Run", "RECORDS", "joined", "STORE_CHOICES"]
