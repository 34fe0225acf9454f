"""The lattice simulator: the exact discrete equations of motion (eq. `norm`, eqs. (6)-(7)
of the paper) on a periodic chain, and the analysis of a run.

Imports neither ``numerics.theory`` nor ``numerics.maps``; the exact travelling wave reaches
it only through the registry of named starts (:data:`STARTS`), which theory fills.

Model         Material, LatticeState, energy, CASES, discrete_omega_rotation,
              discrete_omega_longitudinal
Runs          simulate -> Run, resume, initial_condition, noise_field, snap_wavenumber, STARTS,
              register_start, paper_start_undefined (where eq. `IC` has no state),
              cached_simulate, SIMULATOR_VERSION, source_hash
Stepping      integrate, METHODS, Method, get_method, choose_step
Errors        BlowUpError, SimulationInterrupted, AccuracyWarning
Analysis      spectrum, mode, harmonic_bins, sideband_to_carrier, stability_verdict,
              linear_stage (LINEAR_STAGE_RULE: its rule in words), growth_rates,
              band_summary, spectrum_growth, forced_second_harmonic,
              carrier_amplitude, carrier_frequency; the growth criterion GROWTH_THRESHOLD
              and :func:`grows_beyond_threshold`
Verdicts      simulated_verdict -> Verdict ("MI", "no growth within T", "undetermined":
              VERDICT_WORDS), run_length -> RunLength (T from the fastest predicted
              rate, within T_CAP)
Input checks  ``numerics.lattice.checks`` (the limits every layer imports)
"""

from . import _numba_cache  # noqa: F401 - before any kernel: a read-only install works
from . import checks
from ._accuracy import AccuracyWarning, choose_step
from ._analysis import (GROWTH_THRESHOLD, band_summary, carrier_amplitude, carrier_frequency,
                        forced_second_harmonic, growth_rates, grows_beyond_threshold,
                        LINEAR_STAGE_RULE, harmonic_bins, linear_stage, mode, non_carrier_bins,
                        sideband_to_carrier, spectrum, spectrum_growth, stability_verdict)
from ._cache import cached_simulate
from ._integrate import BlowUpError, SimulationInterrupted, integrate
from ._integrators import METHODS, Method, get_method
from ._model import (CASES, LatticeState, Material, discrete_omega_longitudinal,
                     discrete_omega_rotation, energy)
from ._simulate import (Run, initial_condition, noise_field, resume, simulate,
                        snap_wavenumber)
from ._starts import STARTS, paper_start_undefined, register_start
from ._verdict import (DECIDE_E_FOLDINGS, T_CAP, VERDICT_WORDS, RunLength, Verdict,
                       run_length, simulated_verdict)
from ._version import SIMULATOR_VERSION, source_hash

__all__ = [
    "Material", "LatticeState", "energy", "CASES", "discrete_omega_rotation",
    "discrete_omega_longitudinal", "simulate", "Run", "resume", "initial_condition",
    "snap_wavenumber", "STARTS", "register_start", "paper_start_undefined", "cached_simulate",
    "SIMULATOR_VERSION",
    "source_hash", "integrate", "METHODS", "Method", "get_method", "choose_step",
    "BlowUpError", "SimulationInterrupted", "AccuracyWarning", "spectrum", "mode",
    "harmonic_bins", "non_carrier_bins", "sideband_to_carrier", "stability_verdict",
    "linear_stage", "LINEAR_STAGE_RULE", "growth_rates", "band_summary", "forced_second_harmonic",
    "carrier_amplitude", "carrier_frequency", "GROWTH_THRESHOLD", "grows_beyond_threshold",
    "checks", "noise_field", "spectrum_growth", "VERDICT_WORDS", "Verdict",
    "simulated_verdict", "RunLength", "run_length", "T_CAP", "DECIDE_E_FOLDINGS",
]
