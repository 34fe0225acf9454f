"""The lattice simulator: the exact discrete equations of motion (eq. `norm`, eqs. (6)-(7)
of the paper) on a periodic chain, and the analysis of a run.

Imports neither ``numerics.theory`` nor ``numerics.maps``; the exact travelling wave reaches
it only through the registry of named starts (:data:`STARTS`), which theory fills.

Model         Material, LatticeState, energy, CASES, discrete_omega_rotation,
              discrete_omega_longitudinal
Runs          simulate -> Run, resume, initial_condition, noise_field, snap_wavenumber, STARTS,
              register_start, paper_start_undefined (where eq. `IC` has no state),
              cached_simulate, SIMULATOR_VERSION, source_hash
Stepping      integrate, METHODS, Method, get_method, choose_step (dominant_frequency,
              ERROR_CONSTANTS, STABILITY_MARGIN), Stepper (a run's work arrays, advanced
              chunk by chunk: map cells stop it early), check_time, blowup_message;
              ForceStepper: the same methods for any lattice with a compiled force (every
              model's run), with a linear damping (linear_damping, and its exact flows
              local_flow, band_flow for the Strang splitting); deferred_interrupt,
              steps_per_call: the run control's Ctrl-C between compiled calls of bounded
              work, for any lattice's runs
Fast forces   register_fast_force, fast_force, fast_forces, FastForce: a kernel that runs
              instead of a model's generated force where the energy is the one it
              implements (by content hash); flexmm_force, flexmm_rotation_force (FLEXMM_ROWS):
              the fused kernel of eq. `norm` as such a force
Kernel        FASTMATH, sincos_vers, site_acceleration: the site formula, for the torus;
              accel (a whole chain's force), numpy_accel, numpy_rk4 (the NumPy baseline
              the bench compares against)
Errors        BlowUpError, SimulationInterrupted, AccuracyWarning
Analysis      spectrum, mode, harmonic_bins, sideband_to_carrier, stability_verdict,
              linear_stage (LINEAR_STAGE_RULE: its rule in words), growth_rates,
              band_summary, spectrum_growth, forced_second_harmonic,
              carrier_amplitude, carrier_frequency; the growth criterion GROWTH_THRESHOLD
              and :func:`grows_beyond_threshold`; fit_soliton_profile -> ProfileFit (the
              sech^2 fit of a soliton's intensity on a ring, RADIATION_WINDOW), for the
              paper chain's and every model's soliton measurement
Verdicts      simulated_verdict -> Verdict ("MI", "no growth within T", "undetermined":
              VERDICT_WORDS), run_length -> RunLength (T from the fastest predicted
              rate, within T_CAP)
Input checks  ``numerics.lattice.checks`` (the limits every layer imports), check_case,
              check_start
"""

from . import _numba_cache  # before any kernel: a read-only install works
from . import checks
from ._accuracy import (ERROR_CONSTANTS, STABILITY_MARGIN, AccuracyWarning, choose_step,
                        dominant_frequency)
from ._analysis import (GROWTH_THRESHOLD, U_REFERENCE, band_summary, carrier_amplitude, carrier_frequency,
                        forced_second_harmonic, growth_rates, grows_beyond_threshold,
                        LINEAR_STAGE_RULE, harmonic_bins, linear_stage, mode, non_carrier_bins,
                        shortest_run, shortest_run_error, sideband_to_carrier, spectrum, spectrum_growth,
                        exponential_bound,
                        stability_verdict)
from ._cache import cached_simulate
from ._integrate import (BlowUpError, SimulationInterrupted, Stepper, blowup_message,
                         check_time, integrate)
from ._fast_forces import (FLEXMM_ROWS, FastForce, fast_force, fast_forces, flexmm_force,
                           flexmm_rotation_force, register_fast_force)
from ._force_steppers import ForceStepper, band_flow, linear_damping, local_flow
from ._integrators import METHODS, Method, get_method
from ._baseline import numpy_accel, numpy_rk4
from ._kernels import FASTMATH, TRIG_LIMIT, accel, sincos_vers, site_acceleration
from ._profile_fit import (RADIATION_WINDOW, KINK_WINDOW, ProfileFit, fit_soliton_profile,
                          kink_window, ring_distance)
from ._model import (CASES, LatticeState, Material, check_case, discrete_omega_longitudinal,
                     discrete_omega_rotation, energy)
from ._runcontrol import deferred_interrupt, steps_per_call
from ._simulate import (RUN_REL_TOL, Run, initial_condition, noise_field, resume, simulate,
                        snap_wavenumber)
from ._starts import STARTS, check_start, paper_start_undefined, register_start
from ._verdict import (DECIDE_E_FOLDINGS, T_CAP, VERDICT_WORDS, RunLength, Verdict,
                       run_length, simulated_verdict)
from ._version import SIMULATOR_VERSION, source_hash

def cuda_kernels():
    """The CUDA kernels of map cells (``_cuda``), imported on first use: numba.cuda loads
    only where a GPU map asks for it."""
    from . import _cuda

    return _cuda


def cuda_model_kernels():
    """The CUDA kernel of any model's chains (``_cuda_models``: its generated site force
    compiled for the device), imported on first use as :func:`cuda_kernels`."""
    from . import _cuda_models

    return _cuda_models


__all__ = ["cuda_kernels", "cuda_model_kernels", "TRIG_LIMIT", 
    "Material", "LatticeState", "energy", "CASES", "discrete_omega_rotation",
    "discrete_omega_longitudinal", "simulate", "Run", "resume", "initial_condition",
    "snap_wavenumber", "STARTS", "register_start", "paper_start_undefined", "cached_simulate",
    "SIMULATOR_VERSION",
    "source_hash", "integrate", "METHODS", "Method", "get_method", "choose_step",
    "BlowUpError", "SimulationInterrupted", "AccuracyWarning", "spectrum", "mode",
    "harmonic_bins", "non_carrier_bins", "sideband_to_carrier", "stability_verdict",
    "linear_stage", "LINEAR_STAGE_RULE", "growth_rates", "band_summary", "forced_second_harmonic",
    "carrier_amplitude", "carrier_frequency", "GROWTH_THRESHOLD", "grows_beyond_threshold",
    "checks", "noise_field", "spectrum_growth", "exponential_bound",
    # for the other rooms of numerics (theory, maps) and the bench: no private name crosses
    "Stepper", "blowup_message", "check_time", "check_case", "check_start",
    "dominant_frequency", "ERROR_CONSTANTS", "STABILITY_MARGIN", "FASTMATH", "sincos_vers",
    "site_acceleration", "accel", "numpy_accel", "numpy_rk4", "U_REFERENCE",
    "shortest_run", "shortest_run_error", "RUN_REL_TOL", "VERDICT_WORDS", "Verdict",
    "simulated_verdict", "RunLength", "run_length", "T_CAP", "DECIDE_E_FOLDINGS",
    # any lattice with a compiled force (numerics.models): the one SRKN / RK4 stepper
    "ForceStepper", "local_flow", "band_flow", "linear_damping", "deferred_interrupt",
    "steps_per_call",
    # fast forces a model's run uses where its energy is the one they implement
    "register_fast_force", "fast_force", "fast_forces", "FastForce", "flexmm_force",
    "flexmm_rotation_force", "FLEXMM_ROWS",
    # the soliton measurement of the paper chain (theory) and of any model (models)
    "fit_soliton_profile", "ProfileFit", "RADIATION_WINDOW", "ring_distance",
    "KINK_WINDOW", "kink_window",
]
