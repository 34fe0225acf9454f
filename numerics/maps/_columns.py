"""What a map store holds: its variables (tri-state verdicts; the simulated and predicted
columns a block writes, with their flags), the theory columns on the whole grid, and the
empty dataset a new store starts from."""

from __future__ import annotations

import math

import numpy as np

from ..lattice import GROWTH_THRESHOLD, grows_beyond_threshold
from ._cells import PREDICTED_STATUS
from ._params import MapParameters

#: Bloch offsets the exact theory searches per cell: the whole zone, densely. stability_map's
#: default (20 offsets in (0, 1.5], enough for the paper's sidebands) misses the narrow
#: resonances of case II and offsets beyond 1.5, where simulations found growth
EXACT_OFFSETS = np.linspace(0.005, math.pi, 400)

#: the verdict columns are tri-state (int8): these codes, and no _FillValue (xarray would
#: decode an integer variable with one to float)
MI, STABLE, UNDETERMINED = 1, 0, -1
VERDICT_ATTRS = {"flag_values": [UNDETERMINED, STABLE, MI],
                 "flag_meanings": "undetermined stable MI"}
#: the variables a simulated block writes (with ``done`` and the checksum); every other
#: data variable is written once, when the store is made (the theories)
SIMULATED = ("verdict_simulated", "growth", "growth_field", "growth_q", "t_simulated",
             "peak_gain", "growth_log_ratio", "growth_exponential")
#: the variables every block writes (with ``done_predicted``), theory-only maps included
PREDICTED = ("growth_predicted", "verdict_predicted", "rate_predicted", "predicted_status")
#: version of the store's layout (tri-state verdicts, checksums), in its attributes; 3: a
#: simulated verdict reads ``growth_exponential`` (probe 96; a store of format 2 counted
#: algebraic growth past 20x as MI, and holds no ``growth_exponential``: it is named as of
#: an older format, never resumed); 4: a cell that grew, but less than the threshold, is
#: undetermined (-1) as the point says (``_cells.cell_verdict``; format 3 stored it 0)
STORE_FORMAT = 4
#: what an older store's simulated verdicts meant (``MapParameters.other_map`` names it)
OLDER_FORMATS = {
    2: "its simulated verdicts read the raw growth factor, algebraic growth past 20x as MI, "
       "and it holds no growth_exponential",
    3: "its simulated verdicts stored a run that grew, but less than 20x, as stable (0) "
       "where this version says undetermined (-1)"}
#: a model map's store: its verdicts read the exponential reading since probe 95 (the
#: runs' ``measure_growth``), so its layout is unchanged
MODEL_STORE_FORMAT = 2


def _simulated_columns(shape) -> dict:
    """The simulated variables and ``done`` of cells not simulated yet."""
    fl = lambda: np.full(shape, np.nan)
    return {
        "verdict_simulated": (np.full(shape, UNDETERMINED, np.int8),
                              {"long_name": f"simulation: grows exponentially more than "
                                            f"{GROWTH_THRESHOLD:g}x within t_end (most "
                                            "seeds' growth_exponential)", **VERDICT_ATTRS,
                               "verdict_words": (
                                   f"MI -> 1 (most seeds grew more than {GROWTH_THRESHOLD:g}x); "
                                   "'no growth within T' -> 0 (stable within t_end: the median "
                                   f"stayed below {math.sqrt(GROWTH_THRESHOLD):.3g}x); "
                                   "undetermined -> -1 (grew between the two: a longer "
                                   "t_end decides; or no finite growth factor)"),
                               "undetermined": "not simulated yet (done = False), or "
                                               "undetermined (done = True: grew, less than "
                                               "the threshold)"}),
        "growth": (fl(), {"long_name": "largest growth factor over the run", "units": "1"}),
        "growth_exponential": (fl(), {
            "long_name": "the growth factor exponential growth accounts for (at most "
                         "exp(s L), s the log-slope over the linear stage's second half: "
                         "numerics.lattice.exponential_bound; median over the seeds): the "
                         "verdict's reading", "units": "1"}),
        "growth_field": (np.full(shape, -1, np.int8),
                         {"flag_values": [-1, 0, 1], "flag_meanings": "none theta U"}),
        "growth_q": (fl(), {"long_name": "wavenumber of the largest growth",
                            "units": "rad per site"}),
        "peak_gain": (fl(), {"long_name": "measured peak growth rate (linear-stage fit) where "
                                          "the simulation says MI",
                             "units": "1/T (lattice time)"}),
        "t_simulated": (fl(), {"units": "T (lattice time)"}),
        "done": (np.zeros(shape, bool), {"long_name": "cell simulated (the record of complete "
                                                      "cells; covered by checksum)"}),
        "growth_log_ratio": (fl(), {
            "long_name": "log10(predicted / measured growth) over the span simulated "
                         "(first seed)", "units": "1"}),
        "growth_predicted": (fl(), {
            "long_name": "growth factor the simulation measures, predicted: linear response "
                         "of the cell's own initial state (numerics.theory.predict_growth; "
                         "median over the seeds; NaN: undetermined, see predicted_status)",
            "units": "1"}),
        "verdict_predicted": (np.full(shape, UNDETERMINED, np.int8), {
            "long_name": f"predicted: grows more than {GROWTH_THRESHOLD:g}x within t_end",
            **VERDICT_ATTRS,
            "undetermined": "not predicted yet (done_predicted = False), or no linear theory "
                            "(predicted_status)"}),
        "rate_predicted": (fl(), {"long_name": "largest growth rate of the launched state's "
                                               "Hill modes", "units": "1/T (lattice time)"}),
        "predicted_status": (np.full(shape, -1, np.int8), {
            "flag_values": [-1] + list(PREDICTED_STATUS.values()),
            "flag_meanings": " ".join(["not_computed"] + [n.replace(" ", "_")
                                                          for n in PREDICTED_STATUS])}),
        "done_predicted": (np.zeros(shape, bool), {"long_name": "cell predicted"}),
    }


def empty_dataset(params: MapParameters, theory: dict):
    import xarray as xr

    from ._integrity import CHECKSUM, CHECKSUM_ATTRS, cell_checksums

    shape = (len(params.delta), len(params.k))
    dims = ("delta", "k")
    data = {name: (dims, values, attrs)
            for name, (values, attrs) in _simulated_columns(shape).items()}
    for name, values in theory.items():
        theory_name = name.removeprefix("peak_gain_").removeprefix("verdict_")
        if name.startswith("peak_gain"):
            attrs = {"long_name": f"{theory_name} theory: peak growth rate (NaN: "
                                  "undetermined)", "units": "1/T (lattice time)"}
        else:
            attrs = {"long_name": f"{theory_name} theory: grows more than "
                                  f"{GROWTH_THRESHOLD:g}x within t_end", **VERDICT_ATTRS}
        if name in UNDETERMINED_REASONS:
            attrs["undetermined"] = UNDETERMINED_REASONS[name]
        data[name] = (dims, values, attrs)
    data[CHECKSUM] = (dims, cell_checksums({n: v[1] for n, v in data.items()}), CHECKSUM_ATTRS)
    # the stiffnesses are ratios to the longitudinal spring's (K_s = k_s / k_l, eq. `norm`):
    # dimensionless, said as every other coordinate says its unit
    ratio = "1 (a stiffness over the longitudinal spring's k_l, eq. norm)"
    coords = {"delta": ("delta", np.asarray(params.delta), {"long_name": "K_s - K_theta",
                                                            "units": ratio}),
              "K_theta": ("delta", np.asarray(params.K_theta),
                          {"long_name": "K_theta of the row: its cells are simulated, and the "
                                        "theories evaluated, at it", "units": ratio}),
              "k": ("k", np.asarray(params.k), {"long_name": "k as requested",
                                                "units": "rad per site"}),
              "k_simulated": ("k", np.asarray(params.k_simulated),
                              {"long_name": "k snapped to 2 pi m / N: the wavenumber simulated "
                                            "and at which the theories are evaluated",
                               "units": "rad per site"})}
    return xr.Dataset(data, coords=coords, attrs={**params.attrs(), "store_format": STORE_FORMAT})


_NLS_REASON = ("the NLS coefficients are not finite there (delta = 0: g1 = 0, or a resonance "
               "k^2 = omega^2, or, for the paper NLS, no real continuum frequency: delta < 0 "
               "and k^2 > 6 K_theta / |delta|)")
_EXACT_REASON = ("no plane wave of this amplitude (harmonic balance finds no travelling wave "
                 "near a resonance of a harmonic with a lattice mode)")
#: why a theory column can be undetermined (NaN gain, verdict UNDETERMINED) at a cell
UNDETERMINED_REASONS = {f"{kind}_{name}": reason for kind in ("verdict", "peak_gain")
                        for name, reason in (("paper", _NLS_REASON),
                                             ("semidiscrete", _NLS_REASON),
                                             ("exact", _EXACT_REASON),
                                             ("exact_all", _EXACT_REASON))}
#: the theory columns of a store (recomputed from the parameters alone)
THEORY_NAMES = tuple(UNDETERMINED_REASONS)


def tri_state(gain: np.ndarray, t_end: float) -> np.ndarray:
    """int8 verdicts from peak gains: MI, STABLE, or UNDETERMINED where the gain is NaN."""
    return np.where(np.isfinite(gain), np.where(grows_beyond_threshold(
        np.nan_to_num(gain), t_end), MI, STABLE), UNDETERMINED).astype(np.int8)


def theory_columns(params: MapParameters) -> dict:
    """The theories on the whole grid, batched (seconds): their raw peak gains, and their
    verdicts on the simulation's question: does the plane wave grow more than
    GROWTH_THRESHOLD-fold within t_end (peak gain > ln(threshold) / t_end)? Where a theory
    cannot be evaluated its gain is NaN and its verdict UNDETERMINED (the reason is the
    variable's ``undetermined`` attribute), never "stable"."""
    from ..theory import NLS_THEORIES, stability_map

    # each row at its own K_theta (params.K_theta: as given, or K_s - delta)
    K, Kt = np.meshgrid(params.k_simulated, params.K_theta, indexing="xy")
    gains = {}
    for name, nls in ((t.key, t.closed_forms()) for t in NLS_THEORIES):
        with np.errstate(all="ignore"):
            g = getattr(nls, f"g_{params.case}")(K, params.alpha, params.K_s, Kt)
            g1 = nls.g1(K, params.alpha, params.K_s, Kt)
            gpos = np.where(g > 0, g, np.nan)
            peak = params.eps**2 * np.abs(g1) * nls.mi_growth_rate(
                nls.mi_fastest(gpos, params.A0), gpos, params.A0)
        # g <= 0: stable, no gain; g or g1 not finite: undetermined (NaN), never "stable"
        defined = np.isfinite(g) & np.isfinite(g1)
        gains[name] = np.where(defined, np.where(g > 0, peak, 0.0), np.nan)
    # stability_map: NaN where there is no plane wave of this amplitude (undetermined)
    grid = dict(case=params.case, alpha=params.alpha, K_s=params.K_s,
                amplitude=params.amplitude, K_theta=Kt)
    # any growing Hill mode of the travelling wave, in both cases, as the column is defined
    # (case I copied `exact`, which for --start paper is another state's sideband theory)
    gains["exact_all"] = stability_map(K, offset=EXACT_OFFSETS, modes="all", **grid)
    if params.start == "paper":
        # the exact theory of the state the map's runs start in: eq. `IC`'s launched state
        # (its free U waves pump bands of their own in case II), sampling-independent
        from ..theory import resonance_map

        gains["exact"] = resonance_map(K, start="paper", **grid)["peak_gain"]
    else:
        gains["exact"] = stability_map(K, offset=EXACT_OFFSETS, **grid)
    out = {}
    for name, gain in gains.items():
        out[f"verdict_{name}"] = tri_state(gain, params.t_end)
        out[f"peak_gain_{name}"] = gain
    return out


__all__ = ["MI", "STABLE", "UNDETERMINED", "SIMULATED", "PREDICTED", "STORE_FORMAT",
           "OLDER_FORMATS",
           "MODEL_STORE_FORMAT",
           "EXACT_OFFSETS", "UNDETERMINED_REASONS", "THEORY_NAMES", "tri_state", "theory_columns"]
