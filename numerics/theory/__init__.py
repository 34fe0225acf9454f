"""Theory of the lattice's plane waves: exact states and their stability.

Imports ``numerics.lattice`` (the model, the integrators for the torus, the checks), never
``numerics.maps``. Importing it registers the ``"travelling"`` start with the simulator.

Exact states    plane_wave -> PlaneWave (harmonic balance), launched_state ->
                LaunchedState, FreeWave (what eq. `IC` launches: travelling wave + free
                waves, measured as a torus)
Exact maps      resonance_map (MI bands over (k, delta) from their resonance conditions,
                sampling-independent; the engine: _resonance, _pencil, _reduced)
Stability       mi_gain (Hill's method about the state a start launches),
                gain_spectrum -> GainSpectrum (per offset: rate, growing field and
                wavenumber), hill_spectrum, stability_map (batched over (k, delta))
Theories        Theory, THEORY_RECORDS (one record per theory: its label, store key,
                generated module, CLI name and table column), NLS_THEORIES, MAP_COLUMNS
NLS theories    THEORIES, PAPER_START (their labels), theory_gain, nls_summary (paper NLS and
                semi-discrete NLS from ``generated/``, and the exact lattice),
                nls_undefined (why an NLS has no verdict at k), nls_coefficients (both
                NLS theories' coefficients and bands at any k: `flexmm coefficients`)
Prediction      predict_growth -> GrowthPrediction: the growth factor a run measures,
                from the linear response of its own initial state (Hill modes of the
                launched state, the noise projected on them)
Measurement     measure_gain, relative_errors (sigma(q) measured from runs)
Solitons        soliton -> Soliton (bright or dark, width, velocity, frequency, kink of U),
                ring_wavenumber, soliton_state (the lattice launch), simulate_soliton ->
                SolitonRun (tracked: centre, width, amplitude, kink, radiation),
                measure_state, soliton_report (the JSON of `flexmm soliton`);
                shortest_ring, ring_too_short (a ring that holds 12 widths at its own k)
"""

from ._coefficients import nls_coefficients
from ._gain import (
                       PAPER_START,
                       THEORIES,
                       measure_gain,
                       measurement_length,
                       nls_summary,
                       nls_undefined,
                       relative_errors,
                       theory_gain,
)
from ._hill import gain_spectrum, hill_spectrum, mi_gain, stability_map
from ._launched import FreeWave, LaunchedState, launched_state
from ._plane_wave import MAX_AMPLITUDE, NoPlaneWaveError, PlaneWave, plane_wave
from ._quasiperiodic import GainSpectrum
from ._records import (
                       EXACT_ALL_MODES,
                       EXACT_LATTICE,
                       EXACT_PAPER_START,
                       MAP_COLUMNS,
                       NLS_THEORIES,
                       PAPER_NLS,
                       PREDICTED,
                       SEMIDISCRETE_NLS,
                       THEORY_RECORDS,
                       Theory,
)
from ._resonance import resonance_map
from ._response import SITES, GrowthPrediction, predict_growth
from ._soliton import (
                       KINDS,
                       MIN_WIDTH,
                       SOLITON_THEORIES,
                       Soliton,
                       SolitonWarning,
                       ring_wavenumber,
                       soliton,
)
from ._soliton_launch import (
    RunTooLong,
    default_ring,
    ring_too_short,
    shortest_ring,
    simulate_soliton,
    soliton_state,
)
from ._soliton_measure import Snapshot, SolitonRun, measure_state, soliton_report

__all__ = [
    "PlaneWave", "plane_wave", "LaunchedState", "FreeWave", "launched_state", "mi_gain",
    "gain_spectrum", "GainSpectrum", "hill_spectrum", "stability_map", "THEORIES",
    "PAPER_START", "theory_gain", "nls_summary", "nls_undefined", "measure_gain", "measurement_length",
    "relative_errors", "predict_growth", "GrowthPrediction", "NoPlaneWaveError",
    "KINDS", "MIN_WIDTH", "MAX_AMPLITUDE", "nls_coefficients", "resonance_map",
    "Theory", "THEORY_RECORDS", "NLS_THEORIES", "MAP_COLUMNS", "PAPER_NLS", "SEMIDISCRETE_NLS",
    "EXACT_LATTICE", "EXACT_PAPER_START", "EXACT_ALL_MODES", "PREDICTED",
    "SOLITON_THEORIES", "Snapshot", "Soliton", "SolitonRun", "SolitonWarning", "default_ring",
    "measure_state", "ring_wavenumber", "simulate_soliton", "soliton", "soliton_report",
    "soliton_state", "RunTooLong", "SITES", "shortest_ring", "ring_too_short",
]
