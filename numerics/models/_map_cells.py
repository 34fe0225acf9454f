"""A model map's cells: the columns one cell holds (the NLS, the exact and four-wave theories
on the ring, a registered start's theory, the runs and, with losses, each theory's
amplification), computed as one task of ``numerics.maps.run_map`` computes a block of
them (``map_cells``); ``model_map`` in ``_map`` lays them out as a dataset."""

from __future__ import annotations

import math

import numpy as np

from energy import Model, ModelError

from ._nls import nls, remember_nls


def _map_cell(model: Model, k: float, amplitude: float, branch=None, *, exact: bool = False,
              simulate: bool = False, N: int = 256, seeds: int = 1,
              t_end: float | None = None, start: str = "exact", lossy=None) -> dict:
    from common.threads import one_blas_thread

    return one_blas_thread(_cell_columns)(model, k, amplitude, branch, exact=exact,
                                          simulate=simulate, N=N, seeds=seeds, t_end=t_end,
                                          start=start, lossy=lossy)


def _start_columns(model, k, amplitude, N, start) -> tuple:
    """A registered start's theory at the cell: ({verdict_<col>, peak_gain_<col>}, its
    rate for the runs' T (0 where the theory is undefined: T's default), whether the start
    has a state here (eq. IC has none where its frequency is not real: no run))."""
    from ._extras import extra_starts

    launched = extra_starts(model)[start]
    col = launched.column
    try:
        launched.state(model, k, amplitude, N)
    except ModelError:
        return {f"verdict_{col}": "undefined", f"peak_gain_{col}": math.nan}, 0.0, False
    th = launched.theory(model, k, amplitude, N)
    gain = th["peak_gain"]
    return ({f"verdict_{col}": th["verdict"],
             f"peak_gain_{col}": math.nan if gain is None else float(gain)},
            gain or 0.0, True)


def _cell_columns(model, k, amplitude, branch, *, exact, simulate, N, seeds, t_end,
                  start="exact", lossy=None):
    from numerics.lattice import BlowUpError

    from ._reach import energy_not_real, exact_gain_checked
    from ._simulate import snap_ring

    row = {"verdict_semidiscrete": "undefined", "peak_gain_semidiscrete": math.nan,
           "g1": math.nan, "g2": math.nan, "reason": "", "carrier": False,
           "no_wave": math.nan}
    if exact or simulate:  # every theory at the ring's k, as point and the paper chain's
        k = snap_ring(k, N)[0]  # map (the NLS at k = 2 and the runs at 1.96 disagreed)
    try:
        r = nls(model, k, branch)
        remember_nls(model, k, branch, r)  # the ring theories' amplitude check reads it
        row.update(verdict_semidiscrete=r.verdict, peak_gain_semidiscrete=r.peak_gain(amplitude),
                   g1=r.g1, g2=r.g2, reason=r.undefined or "", carrier=True)
    except ModelError as exc:  # e.g. no carrier on this branch at these values
        row["reason"] = str(exc)
    # a wave of this amplitude the model cannot carry (its energy not real along it: the
    # check point's note and the four-wave theory use): no theory's verdict, not an NLS
    # verdict of a wave that does not exist (Toda at a = 2000 was 'stable')
    why = energy_not_real(model, k, amplitude, branch, carrier=r.carrier) \
        if row["carrier"] else None
    if row["carrier"]:
        row["no_wave"] = 0.0 if why is None else 1.0
    if why is not None:
        row.update(verdict_semidiscrete="undefined", peak_gain_semidiscrete=math.nan,
                   reason=why)
    from ._extras import extra_theories

    for extra in extra_theories(model):  # the paper chain's continuum NLS, say
        got = ({"verdict": "undefined", "peak_gain": None} if why is not None
               else extra.row(model, k, amplitude))
        row[f"verdict_{extra.column}"] = got["verdict"]
        row[f"peak_gain_{extra.column}"] = (math.nan if got["peak_gain"] is None
                                            else float(got["peak_gain"]))
    if lossy is None:  # the map's columns: a damping axis from 0 too (map_cells)
        lossy = model.lattice.lossy
    if lossy:  # issue 42: the sidebands' amplification along the decaying carrier
        from ._losses import nls_amplification

        _amplification(row, "semidiscrete", lambda: nls_amplification(
            model, k, amplitude, branch, first=r) if row["carrier"] and why is None
            else None)
    if not (exact or simulate):
        row["k_simulated"] = float(k)
        return row
    row["k_simulated"] = snap_ring(k, N)[0]
    fw_columns, fw = ((_four_wave_columns(model, k, amplitude, branch, N)) if why is None
                      else (_UNDEFINED_FOUR_WAVE, None))
    row.update(verdict_exact="undefined", peak_gain_exact=math.nan, **fw_columns)
    if lossy:
        from ._losses import four_wave_amplification

        _amplification(row, "exact", lambda: None)
        _amplification(row, "fourwave", lambda: None if fw is None else
                       four_wave_amplification(model, k, amplitude, branch, N=N, first=fw))
    if simulate:
        row.update(verdict_simulated="undefined", peak_gain_simulated=math.nan,
                   growth=math.nan, growth_q=math.nan, t_simulated=math.nan)
        if lossy:
            row.update(amplification_simulated=math.nan,
                       amplification_time_simulated=math.nan, observable_simulated=math.nan)
    if start != "exact":  # a block's rows share their columns: undefined until computed
        from ._extras import extra_starts

        col = extra_starts(model)[start].column
        row.update({f"verdict_{col}": "undefined", f"peak_gain_{col}": math.nan})
    if why is not None:  # no wave to solve for, launch or measure
        return row
    try:  # the energy not real along the wave: undefined, as without a travelling wave
        spec = exact_gain_checked(model, k, amplitude, branch, N=N)
    except ModelError:  # no travelling wave here: nothing to launch or measure from
        return row
    row.update(verdict_exact=spec.verdict, peak_gain_exact=spec.peak_gain)
    start_gain, launch_ok = None, True
    if start != "exact":  # the runs' own start (eq. IC) and its theory
        cols, start_gain, launch_ok = _start_columns(model, row["k_simulated"], amplitude, N,
                                                     start)
        row.update(cols)
    peak_time = None
    if lossy:
        from ._losses import exact_amplification

        _amplification(row, "exact", lambda: exact_amplification(
            model, k, amplitude, branch, N=N, first=spec))
        peak_time = row["amplification_time_exact"]
    if simulate:
        try:
            return _simulated_columns(row, model, k, amplitude, spec, branch=branch, N=N,
                                      seeds=seeds, t_end=t_end, start=start,
                                      start_gain=start_gain, launch_ok=launch_ok,
                                      peak_time=peak_time, lossy=lossy)
        except BlowUpError as exc:
            # a run that left the lattice's range (a softening bond past its barrier, say):
            # the cell's runs say nothing more about MI, and the other cells stand; stored
            # as a run whose records overflowed first is (growth inf, undetermined), with
            # the time it blew up
            row.update(verdict_simulated="undetermined", peak_gain_simulated=math.nan,
                       growth=math.inf, growth_q=math.nan,
                       t_simulated=math.nan if exc.time is None else float(exc.time))
    return row


def _simulated_columns(row, model, k, amplitude, spec, *, branch, N, seeds, t_end, start,
                       start_gain, launch_ok, peak_time, lossy):
    """A cell's runs and their columns (``_cell_columns``'s last part)."""
    from ._seeds import simulate_seeds

    if lossy:  # the map's columns: a damping axis from 0 too  # issue 42: launched as a point's, the runs' amplification
        sim, amp = lossy_runs(model, k, amplitude, spec, branch=branch, N=N, seeds=seeds,
                              t_end=t_end, peak_time=peak_time, energy=False)
        row.update(amp)
    else:
        # energy=False: a cell's columns do not use the runs' energy, whose kernel
        # (compiled in every worker, no disk cache) would cost more than the cell;
        # until_saturated: a run stops where its linear stage has ended (the growth it
        # measures is the whole run's, bit for bit): an MI cell no longer runs all of T
        if not launch_ok:  # eq. IC has no state here: nothing to run
            return row
        sim = simulate_seeds(model, k, amplitude, spec, branch=branch, N=N, seeds=seeds,
                             t_end=t_end, energy=False, until_saturated=True,
                             start=start, gain=start_gain)
    growth = [run.growth() for run in sim.runs]
    top = max(growth, key=lambda g: g.factor if math.isfinite(g.factor) else -1.0)
    # a lossy run goes on until A(t) has halved: the rate rule's log-slope bound reads that
    # fall as no growth (factor 1 where a run grew 167x); its factor is what its verdict
    # reads, max_t A(t) / A(0)
    factors = ([r.amplification().amplification for r in sim.runs] if lossy
               else [g.factor for g in growth])
    row.update(verdict_simulated=sim.verdict.word,
               peak_gain_simulated=sim.verdict.map_rate,
               growth=float(np.median(factors)),
               growth_q=float(top.wavenumber), t_simulated=float(
                   max(r.t[-1] for r in sim.runs) if lossy else max(
                       r.t_end for r in sim.runs)))
    return row


def lossy_runs(model: Model, k: float, amplitude: float, spec, *, branch=None,
               N: int = 256, seeds: int = 1, t_end: float | None = None,
               peak_time: float | None = None, energy: bool = True) -> tuple:
    """Seeded runs of a lossy model's cell launched as issue 42 measures a run's
    amplification (the exact wave of the lossless model plus noise on the carrier field's
    positions, run until A(t) has fallen to half its maximum), as ``point --model
    --simulate`` runs them, and the median seed's amplification.

    The cap: ``t_end`` where given, else 1.5x the exact theory's peak time ``peak_time``
    (its ``amplification_time``), at least ``run_length`` of the exact rate (the lossless
    run's length; the cap alone where the theory has no finite peak time).
    ``energy=False``: the runs record no energy (``simulate_model``; a map cell's).

    Returns
    -------
    (SeededRuns, dict)
        The runs, and ``amplification_simulated`` (max_t A(t) / A(0)),
        ``amplification_time_simulated``, ``observable_simulated`` (1.0 where the median
        seed grew 20x, else 0.0) of the median seed.
    """
    from numerics.lattice import run_length

    from ._seeds import simulate_seeds

    if t_end is None and peak_time is not None and math.isfinite(peak_time):
        from ._time_scale import time_scale
        t_end = max(run_length(spec.peak_gain, time_scale=time_scale(model)).t_end,
                    1.5 * peak_time)
    # not stopped before the exact theory's peak (probe 98: kg-cubic, k 2.27, a 0.41, gamma
    # 1.15e-3 on 64 sites: the near-carrier band peaked at 86x at t 561 and halved, the
    # run stopped at 680; the band of offset 1.96 the theory's 4.5e6x at t 1516 grows on,
    # 2540x by t 2500)
    hold = peak_time if peak_time is not None and 0 < peak_time < math.inf else True
    sim = simulate_seeds(model, k, amplitude, spec, branch=branch, N=N, seeds=seeds,
                         t_end=t_end, noise_on="carrier", until_peak=hold, energy=energy)
    amps = sorted((r.amplification() for r in sim.runs), key=lambda a: a.amplification)
    med = amps[len(amps) // 2]
    return sim, {"amplification_simulated": float(med.amplification),
                 "amplification_time_simulated": float(med.amplification_time),
                 "observable_simulated": float(med.observable)}


#: a cell's four-wave columns where the theory has no answer
_UNDEFINED_FOUR_WAVE = {"verdict_fourwave": "undefined", "peak_gain_fourwave": math.nan,
                        "mode_kind_fourwave": "undefined"}


def _four_wave_columns(model, k, amplitude, branch, N) -> tuple:
    """The four-wave theory on the ring of N sites (as ``point``'s four-wave row):
    ({verdict_fourwave, peak_gain_fourwave, mode_kind_fourwave ('sidebands', 'backward',
    'parametric', 'none' where stable; 'undefined' without a theory)}, the FourWave or
    None where it is undefined)."""
    from ._fourwave import four_wave

    try:
        fw = four_wave(model, k, amplitude, branch, N=N)
    except ModelError:  # no carrier on this branch at these values
        fw = None
    if fw is None or fw.undefined:
        return dict(_UNDEFINED_FOUR_WAVE), None
    return {"verdict_fourwave": fw.verdict, "peak_gain_fourwave": fw.gain,
            "mode_kind_fourwave": fw.mode_kind}, fw


def _amplification(row: dict, theory: str, f) -> None:
    """A theory's columns with losses, into ``row``: ``amplification_<theory>``
    (``Amplified``'s: inf where the carrier is not damped and a mode grows) and
    ``amplification_time_<theory>`` (when it peaks, inf there: growth is transient, its
    time is half the answer); nan where the theory has none here (``f`` returns None or
    raises ModelError). Its verdict MI becomes "stable" where no gain beats its damping at
    t = 0 (the verdict is physical, ``_losses``; ``peak_gain_<theory>`` stays the lossless
    rate), as ``point``'s."""
    try:
        a = f()
    except ModelError:
        a = None
    row[f"amplification_{theory}"] = math.nan if a is None else float(a.amplification)
    row[f"amplification_time_{theory}"] = (math.nan if a is None
                                           else float(a.amplification_time))
    if a is not None:  # the verdict physical (``Amplified.damped_verdict``), as point's
        v = f"verdict_{theory}"
        row[v] = a.damped_verdict(row.get(v)).get("verdict", row.get(v))


def map_cells(model: Model, cells, amplitude: float, branch=None, *, exact: bool = False,
              simulate: bool = False, N: int = 256, seeds: int = 1,
              t_end: float | None = None, start: str = "exact", lossy=None) -> list:
    """The columns of a block of map cells (what one task of ``numerics.maps.run_map``
    computes), on one BLAS thread.

    Parameters
    ----------
    model : energy.Model
    cells : sequence of (dict, float)
        Each cell's parameter values (the map's axes among the model's parameters) and its
        carrier k.
    amplitude : float
    branch : int or str, optional
    exact : bool
        The exact lattice theory on the ring of ``N`` sites (``exact_gain``).
    simulate : bool
        Also ``seeds`` runs of the ring from the exact wave (``simulate_seeds``; T is
        ``run_length`` of the exact rate unless ``t_end``); implies ``exact``.
    start : str
        Where the runs start: "exact" (the exact wave), or a start the model registers
        (``extra_starts``: "paper", eq. IC, for the paper chain's energy); then, on the
        ring, its theory's ``verdict_<start>_start`` and ``peak_gain_<start>_start``, and
        the runs' T from that theory's rate.
    lossy : bool, optional
        Whether the cells take a lossy model's columns and runs (amplifications; runs
        launched as issue 42 measures one, ``lossy_runs``): the map's
        (``ModelMapParameters.lossy``). None: wherever the model's file has a
        [dissipation] (a damping axis from 0). A file whose damping is zero over the whole
        map is the lossless map: False runs its cells as the lossless model's, bit for bit.

    Returns
    -------
    list of dict
        Per cell: ``verdict_semidiscrete`` ("MI", "stable", "undefined"),
        ``peak_gain_semidiscrete``, ``g1``, ``g2``, ``reason`` (why undefined),
        ``carrier`` (False where the branch has no carrier at the cell), ``no_wave`` (1.0
        where the model carries no wave of this amplitude at k, its energy not real along
        the linear wave, ``energy_not_real``: every theory's verdict is then "undefined",
        the reason that sentence; 0.0 where it does; nan without a carrier),
        ``k_simulated`` (k snapped to the ring where the ring is used); with ``exact`` or
        ``simulate`` ``verdict_exact``, ``peak_gain_exact`` and the four-wave theory on
        the same ring, ``verdict_fourwave``, ``peak_gain_fourwave``, ``mode_kind_fourwave``
        ("sidebands", "backward", "parametric", "none" where stable, "undefined"); for a
        lossy model (``[dissipation]``) ``amplification_<theory>`` of each theory computed
        (the sidebands' largest amplification along the decaying carrier, inf where the
        carrier is not damped and a mode grows; nan without a theory) and
        ``amplification_time_<theory>`` (when it peaks); with
        ``simulate``
        ``verdict_simulated`` (MI, "no growth within T", "undetermined", "undefined"),
        ``peak_gain_simulated`` (the seeds' median rate where MI; with "no growth within
        T" the upper bound ln(GROWTH_THRESHOLD) / T on the rate), ``growth`` (median
        growth factor; a lossy model's runs': max_t A(t) / A(0)), ``growth_q`` (wavenumber of the fastest mode of the seed that grew
        most) and ``t_simulated`` (the longest run: a run stops at the record where its
        linear stage has saturated, ``saturation_record``, else runs T); for a lossy model the runs are
        launched as issue 42 measures an amplification (``lossy_runs``) and add
        ``amplification_simulated``, ``amplification_time_simulated`` and
        ``observable_simulated`` (1.0 or 0.0) of the median seed. A cell whose run blew
        up (``numerics.BlowUpError``: the state left the lattice's range, as a softening
        bond's past its barrier) is "undetermined" with ``growth`` inf and
        ``t_simulated`` the time it blew up; the other cells stand.
    """
    return [_map_cell(model.with_params(**values), k, amplitude, branch, exact=exact,
                      simulate=simulate, N=N, seeds=seeds, t_end=t_end, start=start,
                      lossy=lossy)
            for values, k in cells]
