"""A model map's summary: summary.json's keys (the paper map's, with a lossy map's
observable shares) and the lines that say them (``cli.model_map``)."""

from __future__ import annotations

import math

from ._map_shares import mi_fraction as _mi_fraction
from ._model_map_figure import OBSERVABLE


def _summary(ds, verdicts: list, simulated: bool) -> dict:
    """summary.json, the paper map's keys: cells, cells simulated, each theory's share of
    MI among the cells it decides (``mi_fraction``, by theory name; NaN where it decides
    none: the paper map's definition) and its count of undetermined ones, and with runs how
    often each theory's verdict agrees with the simulation's (``numerics.maps.agreement``)."""
    import numpy as np

    from numerics.maps import agreement

    names = {v: v.removeprefix("verdict_") for v in verdicts}
    out = {"cells": int(ds["done"].size),
           "simulated": int(ds["done"].values.sum()) if simulated else 0,
           "mi_fraction": {n: _mi_fraction(ds[v].values) for v, n in names.items()},
           "undetermined_cells": {n: int((ds[v].values < 0).sum()) for v, n in names.items()}}
    if simulated:
        out["agreement_with_simulation_percent"] = agreement(ds)
        # runs that left the lattice's range (numerics.BlowUpError, or records past 1e154):
        # growth inf, the verdict undetermined; named, so that they are not read as MI
        out["blew_up_cells"] = int(((ds["verdict_simulated"].values < 0)
                                    & np.isposinf(ds["growth"].values)).sum())
    if "no_wave" in ds.data_vars:  # no wave of the amplitude: every theory undetermined
        out["no_wave_cells"] = int((ds["no_wave"].values == 1).sum())
    if "slow_for_T" in ds.data_vars:  # the runs whose T cannot reach their exact rate's 20x
        out["slow_for_T_cells"] = int(ds["slow_for_T"].attrs["cells"])
    out.update(_observable(ds, simulated))
    return out


def _observable(ds, simulated: bool) -> dict:
    """A lossy map's (``amplification_<theory>`` columns) share of observable cells
    (amplified 20x before the losses win) among those each theory, and the runs, answer
    (``mi_fraction``'s definition; NaN where none answers) with the count of cells without
    an answer, and with runs how often each theory's observable agrees with the runs' over
    the cells where both answer; {} for a lossless map. With losses the verdicts' MI (the
    gain beats the damping at t = 0) is not what a sample shows: growth is transient."""
    import numpy as np

    names = str(ds.attrs.get("amplification", "")).split()
    if not names:
        return {}
    seen = {}
    if simulated and "observable_simulated" in ds.data_vars:
        run = ds["observable_simulated"].values.astype(np.int8)
        if "slow_for_T" in ds.data_vars:
            # a run that could not decide (slow_for_T: capped before the exact theory's
            # peak, or too slow for its T) and did not reach 20x has no answer yet, as
            # point's 'not by cap'; one that reached 20x answered
            run = np.where((ds["slow_for_T"].values == 1) & (run == 0), -1, run)
        seen["simulated"] = run.astype(np.int8)
    for n in names:  # nan (no theory at the cell): -1, as a run not made
        a = ds[f"amplification_{n}"].values
        with np.errstate(invalid="ignore"):
            seen[n] = np.where(np.isnan(a), -1, a >= OBSERVABLE).astype(np.int8)
    out = {"observable_fraction": {n: _mi_fraction(v) for n, v in seen.items()},
           "observable_unanswered_cells": {n: int((v < 0).sum()) for n, v in seen.items()}}
    if "simulated" in seen:
        run = seen["simulated"]
        out["observable_agreement_with_simulation_percent"] = {
            n: (float(100 * np.mean(v[m] == run[m])) if (m := (v >= 0) & (run >= 0)).any()
                else math.nan) for n, v in seen.items() if n != "simulated"}
    return out


def _no_wave_text(ds, params, summary: dict) -> str:
    """The line that counts the cells where the model carries no wave of the amplitude
    (the store's ``no_wave``), with the first one's reason (``energy_not_real``: the
    largest amplitude allowed there)."""
    import numpy as np

    from numerics.models import energy_not_real

    i, j = (int(n) for n in np.argwhere(ds["no_wave"].values == 1)[0])
    values, k = params.cell(i, j)
    if params.ring:  # the cell's theories ran at the ring's k
        k = float(ds["k_simulated"].values[i, j])
    at = ", ".join(f"{n} = {float(ds[n].values[m]):g}" for n, m in zip(params.dims, (i, j)))
    why = energy_not_real(params.lattice_model.with_params(**values), k,
                          params.amplitude_at(i, j), params.branch_value)
    return (f"no wave of the amplitude (the model's energy is not real along it): "
            f"{summary['no_wave_cells']} of {summary['cells']} cells, undetermined by every "
            f"theory (no verdict of a wave that does not exist); first at {at}: {why}")


def _overdamped_text(ds, params) -> str | None:
    """A lossy map's line for the cells whose carrier is overdamped (|Re w| <= |Im w|: it
    decays before its phase turns, no wave to modulate; probe 96): their theories' 1x
    and 'stable' are the losses', as point's note says; None where there is none."""
    import numpy as np

    from energy import ModelError
    from numerics.models import carrier, damped_frequencies

    if not params.lossy:
        return None
    shape = ds["no_wave"].shape
    hit = []
    for i, j in np.ndindex(*shape):
        values, k = params.cell(i, j)
        if params.ring:  # the cell's theories ran at the ring's k
            k = float(ds["k_simulated"].values[i, j])
        try:
            m = params.lattice_model.with_params(**values)
            c = carrier(m, k, params.branch_value)
        except (ModelError, ValueError):  # no carrier here: the map says so elsewhere
            continue
        w = complex(np.asarray(damped_frequencies(m, c.k))[c.branch])
        if abs(w.real) <= abs(w.imag):
            hit.append((i, j, w))
    if not hit:
        return None
    i, j, w = hit[0]
    at = ", ".join(f"{n} = {float(ds[n].values[x]):g}" for n, x in zip(params.dims, (i, j)))
    return (f"a carrier that decays faster than its phase turns (|Im w| >= |Re w|, "
            f"overdamped where Re w = 0: no wave to modulate): {len(hit)} of "
            f"{shape[0] * shape[1]} cells, their 'stable' and 1x the losses'; first at "
            f"{at}: damped frequency {w.real + 0.0:.3g} {w.imag:+.3g}i; lower the damping "
            "for a wave")


def _print_observable(summary: dict) -> None:
    """A lossy map's observable shares and their agreement with the runs (``_observable``)."""
    if "observable_fraction" not in summary:
        return
    none = summary["observable_unanswered_cells"]
    print(f"observable (amplified {OBSERVABLE:g}x before the losses win), share of the "
          "cells answered: " + ", ".join(
              (f"{n} {s:.0%}" if math.isfinite(s) else f"{n}: no cell answered")  # not nan%
              + (f" ({none[n]} without an answer, left out)" if none[n] else "")
              for n, s in summary["observable_fraction"].items()))
    ag = summary.get("observable_agreement_with_simulation_percent")
    if ag:
        print("agreement with the runs on observable (cells both answer): " + ", ".join(
            f"{n} {v:.0f}%" if math.isfinite(v) else f"{n}: no cell both answer"
            for n, v in ag.items()))


def _differ_text(ds, params, model_arg: str) -> str | None:
    """The line for the cells whose semi-discrete NLS and exact verdicts (both decided)
    differ, with the first one, what the four-wave theory says there (a three-wave decay
    of the carrier, a pair the NLS cannot see) and the ``point`` command that names the
    mode that grows (probe 100: a map of a three-field chain read NLS 47% MI, exact 93%,
    and nothing said why); None where they agree or no exact column was computed."""
    import numpy as np

    from energy import ModelError
    from numerics.models import four_wave

    if "verdict_exact" not in ds.data_vars or not params.ring:
        return None
    nls, ex = ds["verdict_semidiscrete"].values, ds["verdict_exact"].values
    hit = np.argwhere((nls >= 0) & (ex >= 0) & (nls != ex))
    if not len(hit):
        return None
    i, j = (int(n) for n in hit[0])
    values, _ = params.cell(i, j)
    k = float(ds["k_simulated"].values[i, j])
    a = params.amplitude_at(i, j)
    at = ", ".join(f"{n} = {float(ds[n].values[m]):g}" for n, m in zip(params.dims, (i, j)))
    word = {0: "stable", 1: "MI"}
    try:
        fw = four_wave(params.lattice_model.with_params(**values), k, a, params.branch_value,
                       N=params.N)
        why = (f"four-wave undefined: {fw.undefined}" if fw.undefined
               else f"four-wave: the fastest pair is {fw.mode_kind}")
    except (ModelError, ValueError) as exc:  # the line stays; point says the rest
        why = f"four-wave: {exc}"
    cmd = " ".join([f"flexmm point --model {model_arg}"]
                   + [f"--param {n}={v:g}" for n, v in (dict(params.parameters) | values).items()]
                   + [f"--k {k:.6g} --amplitude {a:g} --N {params.N}"])
    return (f"the semi-discrete NLS and the exact lattice differ in {len(hit)} of {nls.size} "
            f"cells (the exact theory rates whatever grows on the ring: a three-wave decay "
            f"of the carrier, a backward or parametric pair the NLS cannot see, or the "
            f"NLS's a^2 error); first at {at}: NLS {word[int(nls[i, j])]}, exact "
            f"{word[int(ex[i, j])]}; {why}; `{cmd}` says what grows there, and why")
