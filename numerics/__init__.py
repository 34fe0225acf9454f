"""Lattice simulator of the discrete equations of motion (eq. `norm`), periodic chain.

Public API
----------
Material, LatticeState, energy          model, state, conserved energy
integrate(state, material, case, t_end, dt, method="rk4") -> LatticeState
simulate(material, case, N, k, ...) -> Run     the paper's noisy-plane-wave experiment
METHODS, get_method                     integrators: rk4, verlet, srkn6b, srkn11b, dop853, rk45
BlowUpError, SimulationInterrupted      errors that keep what was computed
AccuracyWarning, choose_step            runs that check their energy; dt for a tol=
plane_wave, mi_gain, PlaneWave          exact lattice plane wave and its sideband growth
                                        rate (harmonic balance + Hill's method)
launched_state, LaunchedState, FreeWave what eq. `IC` (or any state) launches: travelling
                                        wave + free waves, as a measured torus
gain_spectrum, GainSpectrum             growth per q with the growing field and wavenumber,
                                        from the travelling wave or a launched state
stability_map, hill_spectrum            batched verdicts over (k, delta); raw Hill spectrum
resonance_map                           exact MI maps from the bands' resonance conditions
                                        (sampling-independent), either start
THEORIES, theory_gain, nls_summary      sigma(q) of the paper NLS, semi-discrete NLS, exact
measure_gain, relative_errors           sigma(q) measured from runs; theory vs measurement
spectrum, stability_verdict, ...        spectral diagnostics of runs (``_analysis``)

Nothing here imports matplotlib: figures live in the ``scenes`` package.
"""

from ._accuracy import AccuracyWarning, choose_step
from ._analysis import (GROWTH_THRESHOLD, band_summary, carrier_amplitude, carrier_frequency,
                        forced_second_harmonic, growth_rates, harmonic_bins, linear_stage, mode,
                        sideband_to_carrier, spectrum, stability_verdict)
from ._gain import PAPER_START, THEORIES, measure_gain, nls_summary, relative_errors, theory_gain
from ._hill import gain_spectrum, hill_spectrum, mi_gain, stability_map
from ._launched import FreeWave, LaunchedState, launched_state
from ._quasiperiodic import GainSpectrum
from ._resonance import resonance_map
from ._integrate import BlowUpError, SimulationInterrupted, integrate
from ._integrators import METHODS, Method, get_method
from ._model import (CASES, LatticeState, Material, discrete_omega_longitudinal,
                     discrete_omega_rotation, energy)
from ._plane_wave import PlaneWave, plane_wave
from ._simulate import (SIMULATOR_VERSION, Run, initial_condition, resume, simulate,
                        snap_wavenumber)

__all__ = [
    "Material", "LatticeState", "energy", "integrate", "simulate", "Run", "METHODS", "Method",
    "get_method", "CASES", "BlowUpError", "SimulationInterrupted", "initial_condition",
    "snap_wavenumber", "discrete_omega_rotation", "discrete_omega_longitudinal",
    "SIMULATOR_VERSION", "plane_wave", "mi_gain", "PlaneWave", "hill_spectrum", "stability_map",
    "THEORIES", "PAPER_START", "theory_gain", "nls_summary", "measure_gain", "relative_errors",
    "GROWTH_THRESHOLD", "band_summary", "carrier_amplitude", "carrier_frequency",
    "forced_second_harmonic", "growth_rates", "harmonic_bins", "linear_stage", "mode",
    "sideband_to_carrier", "spectrum", "stability_verdict", "AccuracyWarning", "choose_step",
    "resume", "launched_state", "LaunchedState", "FreeWave", "gain_spectrum", "GainSpectrum", "resonance_map",
]
