"""A model map's variables: the verdict words' int8 codes, each variable's attributes,
the task a worker runs on a block of cells (:func:`model_block`) and the cells whose NLS
band no ring offset samples (:func:`unsampled_band`), for
``_model_params.ModelMapParameters``."""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

import numpy as np

from ..lattice import GROWTH_THRESHOLD
from ._columns import MI, STABLE, UNDETERMINED, VERDICT_ATTRS

if TYPE_CHECKING:
    from ._model_params import ModelMapParameters

#: a model's verdict words (``numerics.models``) -> the store's int8 codes
VERDICT_CODES = {"MI": MI, "stable": STABLE, "no growth within T": STABLE,
                 "undetermined": UNDETERMINED, "undefined": UNDETERMINED}
#: the mapping, stored with each theory's verdict variable (the runs' own:
#: ``simulated_verdict_attrs``)
MODEL_VERDICT_ATTRS = {**VERDICT_ATTRS, "verdict_words": (
    "MI -> 1 (MI); stable -> 0 (stable); undefined (no carrier, no travelling wave or no "
    "theory at the cell: its reason is the point's) or not predicted yet (done_predicted "
    "False) -> -1 (undetermined)")}
def simulated_verdict_attrs(theory_only: bool) -> dict:
    """``verdict_simulated``'s own words: -1 is also "not simulated" (done False), and a
    theory-only map's store holds no run at all (what its cells say until a simulated map
    of the same parameters resumes the store)."""
    words = (f"MI -> 1 (MI: most seeds grew more than {GROWTH_THRESHOLD:g}x); 'no growth "
             "within T' -> 0 (stable); -1 (undetermined): not simulated where done is "
             "False (no run made), else undefined (no travelling wave at the cell) or "
             "undetermined (a run grew, but less than the threshold; or it blew up, the "
             "state leaving the lattice's range: growth inf, t_simulated when)")
    if theory_only:
        return {"long_name": "simulated verdict: not simulated (a theory-only map makes no "
                             "run; -1 in every cell where done is False)",
                "verdict_words": words, "undetermined": "not simulated: no run made"}
    return {"long_name": f"simulated: most seeds grew more than {GROWTH_THRESHOLD:g}x",
            "verdict_words": words,
            "undetermined": "not simulated yet where done is False (no run made)"}


#: the four-wave theory's fastest pair (``FourWave.mode_kind``) -> the store's int8 codes
MODE_KIND_CODES = {"undefined": -1, "none": 0, "sidebands": 1, "backward": 2,
                   "parametric": 3}
#: the mapping, stored with ``mode_kind_fourwave``
MODE_KIND_ATTRS = {
    "long_name": "four-wave theory's fastest pair (the lossless chain's, as "
                 "peak_gain_fourwave is its rate)", "flag_values": [-1, 0, 1, 2, 3],
    "flag_meanings": "undefined none sidebands backward parametric",
    # a damped cell keeps its lossless pair, as point's four-wave row keeps its mode_kind:
    # code 0 would say the lossless chain is stable, which it is not
    "mode_kinds": "-1 undefined (no theory), 0 none (the lossless chain stable), 1 "
                  "sidebands (k +- q on the carrier's branch, q <= pi/2), 2 backward (q > "
                  "pi/2), 3 parametric (a pair on other branches); with losses where the "
                  "damping wins at t = 0 (verdict_fourwave stable) the pair that would grow "
                  "without them"}
#: the variables a simulated block writes (with ``done``)
SIMULATED_COLUMNS = ("verdict_simulated", "peak_gain_simulated", "growth", "growth_q",
                     "t_simulated")
#: and a lossy model's runs (issue 42: launched as a point's, until A(t) halves)
LOSSY_SIMULATED_COLUMNS = ("amplification_simulated", "amplification_time_simulated",
                           "observable_simulated")
#: where the model carries no wave of the cell's amplitude (``numerics.models.map_cells``'
#: ``no_wave``): int8, every theory's verdict undetermined there
NO_WAVE_ATTRS = {
    "long_name": "the model carries no wave of this amplitude at k: its energy is not real "
                 "along the linear wave (numerics.models.energy_not_real), so no theory has "
                 "a verdict (every verdict -1)",
    "flag_values": [-1, 0, 1], "flag_meanings": "not_computed_or_no_carrier wave no_wave",
    "remedy": "a lower amplitude (flexmm point --model at the cell says the largest)"}
#: the runs' observable flag: int8, -1 where no run (not simulated, or no travelling wave)
OBSERVABLE_ATTRS = {
    "long_name": f"the median seed's sidebands grew {GROWTH_THRESHOLD:g}x (issue 42)",
    "flag_values": [-1, 0, 1], "flag_meanings": "no_run no yes",
    # as point's 'not by cap': summary.json's observable share leaves such cells out
    "comment": "a 0 where slow_for_T is 1 is no answer: the run was too short to show the "
               "exact theory's rate or its peak"}
_GAIN = {"units": "1/T (lattice time)"}
VARIABLE_ATTRS = {
    "peak_gain_semidiscrete": {"long_name": "semi-discrete NLS peak growth rate", **_GAIN},
    "peak_gain_paper": {"long_name": "the paper's continuum NLS peak growth rate, |g2| a^2 / 4 "
                                     "(eq. g_i; the paper chain's models only)", **_GAIN},
    "peak_gain_exact": {"long_name": "exact lattice theory's peak growth rate on the ring",
                        **_GAIN},
    "peak_gain_fourwave": {"long_name": "four-wave theory's fastest pair's rate on the ring",
                           **_GAIN},
    "peak_gain_paper_start": {"long_name": "Hill's method about the state eq. IC launches "
                                           "(the runs' start; the paper chain's models), "
                                           "peak rate on the ring", **_GAIN},
    **{f"amplification_{t}": {
        "long_name": f"{t} theory's largest amplification of the sidebands along the "
                     "decaying carrier (inf: the carrier is not damped and a mode grows)",
        "observable_from": GROWTH_THRESHOLD, "units": "1"} for t in ("semidiscrete", "exact",
                                                               "fourwave")},
    **{f"amplification_time_{t}": {
        "long_name": f"when the {t} theory's amplification peaks (inf where it is inf)",
        "units": "T (lattice time)"} for t in ("semidiscrete", "exact", "fourwave")},
    "peak_gain_simulated": {
        "long_name": "the seeds' median measured rate where MI; where no growth within T "
                     "(verdict_simulated 0), the upper bound ln(growth_threshold) / "
                     "t_simulated on the rate", **_GAIN,
        # which cells hold a bound, not a measurement: those the runs call stable
        "bound_where": "verdict_simulated == 0",
        "bound": "upper: a faster rate would have grown past growth_threshold within "
                 "t_simulated; NaN where undetermined (grew, less than the threshold) or "
                 "undefined"},
    "amplification_simulated": {
        "long_name": "the median seed's max_t A(t) / A(0), A the largest ring mode that is "
                     "not a carrier harmonic (the exact lossless wave launched with noise on "
                     "the carrier field's positions, run until A(t) halves or its cap)",
        "observable_from": GROWTH_THRESHOLD, "units": "1"},
    "amplification_time_simulated": {"long_name": "when that seed's A(t) peaked",
                                     "units": "T (lattice time)"},
    "g1": {"long_name": "d^2 omega/dk^2", "units": "site^2/T (lattice time)"},
    "g2": {"long_name": "NLS nonlinear coefficient (mean flow included)",
           "units": "1/(T amplitude^2) (lattice time; the amplitude in the carrier "
                    "field's own unit)"},
    "k_simulated": {"long_name": "k snapped to 2 pi m / N where the ring is used",
                    "units": "rad per site"},
    "growth": {"long_name": "the seeds' median growth factor of the sidebands", "units": "1"},
    "growth_q": {"long_name": "wavenumber of the fastest mode (seed that grew most)",
                 "units": "rad per site"},
    "t_simulated": {"long_name": "the longest run's length: T, or where its linear stage "
                                 "saturated (an MI run stops there)",
                    "units": "T (lattice time)"},
}


def model_block(params: ModelMapParameters, i: int, js: list, simulate: bool = True) -> dict:
    """The cells (i, j), j in ``js``, of a model's map (runs on a worker): their theories
    and, unless ``simulate`` is False, their runs, as the store's rows."""
    from numerics.models import map_cells

    from ._blocks import keep_freed_memory

    keep_freed_memory()
    rows: list = [None] * len(js)
    for amplitude, ns in params.by_amplitude([(i, j) for j in js]):
        got = map_cells(params.lattice_model, [params.cell(i, js[n]) for n in ns], amplitude,
                        params.branch_value, exact=params.ring, simulate=simulate,
                        N=params.N, seeds=params.seeds, t_end=params.t_end,
                        start=params.start, lossy=params.lossy)
        for n, row in zip(ns, got):
            rows[n] = row
    flags = params.flag_columns()
    keep = set(flags["done_predicted"]) | (set(flags["done"]) if simulate else set())
    out = []
    for row in rows:
        out.append({n: (np.int8(VERDICT_CODES[v]) if n.startswith("verdict_") else
                        np.int8(MODE_KIND_CODES[v]) if n == "mode_kind_fourwave" else
                        np.int8(-1 if not v == v else int(v))
                        if n in ("observable_simulated", "no_wave")
                        else
                        float(v) if v is not None else math.nan)
                    for n, v in row.items() if n in keep})
    return {"i": i, "js": list(js), "rows": out, "simulated": simulate}


def unsampled_band(params: ModelMapParameters, arrays: dict) -> dict:
    """``nls_band_unsampled`` (int8 per cell: 1 where the semi-discrete NLS finds MI in
    a band of offsets 0 < |q| <= a sqrt(g2/g1) that lies below the ring's smallest
    offset 2 pi / N, so that no ring offset samples it and the ring's theories and runs
    cannot show that MI; 0 elsewhere; -1 where the cell has no theory yet), with the
    count in its attributes and in the store's (``nls_band_unsampled_cells``, what
    ``flexmm map --model`` prints). Empty for a map without the ring (theory-only
    without ``exact``)."""
    if not params.ring or not {"verdict_semidiscrete", "g1", "g2"} <= set(arrays):
        return {}
    rings = [t for t in ("exact", "fourwave") if f"verdict_{t}" in arrays]
    if not params.theory_only and "verdict_simulated" in arrays:
        rings.append("simulated")
    shape = params.grid_shape
    amplitude = np.array([[params.amplitude_at(i, j) for j in range(shape[1])]
                          for i in range(shape[0])])
    g1, g2 = np.asarray(arrays["g1"], float), np.asarray(arrays["g2"], float)
    with np.errstate(invalid="ignore", divide="ignore"):
        edge = amplitude * np.sqrt(g2 / g1)  # the NLS band edge (docs/models.md)
    smallest = 2 * math.pi / params.N
    done = np.asarray(arrays["done_predicted"], bool)
    below = (done & (np.asarray(arrays["verdict_semidiscrete"]) == MI)
             & np.isfinite(edge) & (edge <= smallest))
    flag = np.where(done, below, -1).astype(np.int8)
    not_mi = {t: int((below & (np.asarray(arrays[f"verdict_{t}"]) != MI)).sum())
              for t in rings}
    attrs = {
        "long_name": "the semi-discrete NLS's MI band lies below the ring's smallest "
                     "offset 2 pi / N: no ring offset samples it",
        "flag_values": [-1, 0, 1], "flag_meanings": "not_computed sampled unsampled",
        "cells": int(below.sum()), "of": int(below.size),
        "ring_smallest_offset": smallest,
        "widest_band_edge": float(np.max(edge[below])) if below.any() else "none",
        **{f"ring_not_MI_{t}": n for t, n in not_mi.items()},
        "remedy": "a larger N (--N) samples the band"}
    return {"nls_band_unsampled": (params.dims, flag, attrs)}


def slow_for_run(params: ModelMapParameters, arrays: dict) -> dict:
    """``slow_for_T`` (int8 per cell: 1 where the exact theory calls the cell MI at a rate
    too slow to grow GROWTH_THRESHOLD-fold within the run's length T (``t_simulated``:
    peak_gain_exact T < ln(threshold)), so the run cannot decide and its verdict is "no
    growth within T" or undetermined, not a disagreement with the theory; 0 for the other
    simulated cells; -1 where no run was made), with the count in its attributes and in
    the store's (``slow_for_T_cells``, what ``flexmm map --model`` prints): the paper
    chain's map asks its theories the runs' question (a rate above ln(threshold) /
    t_end), a model map says which cells its T cannot decide. Empty for a theory-only
    map."""
    need = {"done", "verdict_exact", "peak_gain_exact", "t_simulated"}
    if params.theory_only or not need <= set(arrays):
        return {}
    done = np.asarray(arrays["done"], bool)
    with np.errstate(invalid="ignore"):
        reach = np.asarray(arrays["peak_gain_exact"], float) * np.asarray(
            arrays["t_simulated"], float)
    slow = done & (np.asarray(arrays["verdict_exact"]) == MI) & (reach < math.log(
        GROWTH_THRESHOLD))
    lossy = "amplification_time_exact" in arrays
    if lossy and params.t_end is not None:
        # with losses growth is transient: a run that reached its cap (--t-end; a run
        # that peaked and halved stops before it, and answered) before the exact theory's
        # peak, past the threshold, cannot show it (7x by t = 50 where the theory peaks at
        # 146x near t = 137, lossy FPUT, gamma 0.012). Without --t-end the cap is 1.5x that
        # peak time.
        t_run = np.asarray(arrays["t_simulated"], float)
        with np.errstate(invalid="ignore"):
            slow |= done & (np.asarray(arrays["amplification_exact"], float)
                            >= GROWTH_THRESHOLD) & (np.asarray(
                                arrays["amplification_time_exact"], float) > t_run) & (
                t_run >= float(params.t_end) * (1 - 1e-9))
    flag = np.where(done, slow, -1).astype(np.int8)
    words = {n: int((slow & (np.asarray(arrays["verdict_simulated"]) == c)).sum())
             for n, c in (("no_growth", STABLE), ("undetermined", UNDETERMINED),
                          ("MI", MI))} if "verdict_simulated" in arrays else {}
    attrs = {
        "long_name": f"the exact theory's rate cannot grow {GROWTH_THRESHOLD:g}x within the "
                     "run's T (peak_gain_exact t_simulated < ln(growth_threshold))"
                     + (", or its amplification, past the threshold, peaks after the run's "
                        "end (amplification_time_exact > t_simulated)" if lossy else "")
                     + ": the run cannot decide",
        "flag_values": [-1, 0, 1], "flag_meanings": "not_simulated decidable too_slow_for_T",
        "cells": int(slow.sum()), "of": int(slow.size), "lossy": int(lossy),
        **{f"runs_{n}": v for n, v in words.items()},
        "remedy": "a longer --t-end (or none: each cell's T from its exact rate)"}
    return {"slow_for_T": (params.dims, flag, attrs)}


def derived_attrs(derived: dict) -> dict:
    """The store's attributes from the derived variables: the count of cells whose NLS
    band no ring offset samples (``nls_band_unsampled_cells``, of how many), and of
    cells whose runs are too short for their exact rate (``slow_for_T_cells``)."""
    out = {}
    if "slow_for_T" in derived:
        a = derived["slow_for_T"][2]
        out.update(slow_for_T_cells=a["cells"], slow_for_T_note=(
            f"{a['cells']} of {a['of']} cells: the exact theory's rate is too slow to "
            f"grow {GROWTH_THRESHOLD:g}x within the run's T"
            + (", or its amplification peaks after the run's end" if a.get("lossy") else "")
            + ", so their runs cannot decide (variable slow_for_T)"))
    if "nls_band_unsampled" not in derived:
        return out
    a = derived["nls_band_unsampled"][2]
    return {**out, "nls_band_unsampled_cells": a["cells"],
            "nls_band_unsampled_note": (
                f"{a['cells']} of {a['of']} cells: the semi-discrete NLS's MI band lies "
                f"below the ring's smallest offset 2 pi / N = "
                f"{a['ring_smallest_offset']:.4g}, which no ring offset samples "
                "(variable nls_band_unsampled)")}


__all__ = ["model_block", "unsampled_band", "slow_for_run", "derived_attrs", "simulated_verdict_attrs", "VERDICT_CODES", "MODE_KIND_CODES", "NO_WAVE_ATTRS",
           "MODE_KIND_ATTRS", "MODEL_VERDICT_ATTRS", "SIMULATED_COLUMNS", "LOSSY_SIMULATED_COLUMNS",
           "OBSERVABLE_ATTRS", "VARIABLE_ATTRS"]
