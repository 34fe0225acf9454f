"""Lattice simulator of the discrete equations of motion (eq. `norm`), periodic chain.

Public API
----------
Material, LatticeState, energy          model, state, conserved energy
integrate(state, material, case, t_end, dt, method="rk4") -> LatticeState
simulate(material, case, N, k, ...) -> Run     the paper's noisy-plane-wave experiment
METHODS, get_method                     integrators: rk4, verlet, srkn6b, srkn11b, dop853, rk45
BlowUpError, SimulationInterrupted      errors that keep what was computed
plane_wave, mi_gain, PlaneWave          exact lattice plane wave and its sideband growth
                                        rate (harmonic balance + Hill's method)
stability_map, hill_spectrum            batched verdicts over (k, delta); raw Hill spectrum
"""

from ._hill import PlaneWave, hill_spectrum, mi_gain, plane_wave, stability_map
from ._integrators import METHODS, Method, get_method
from ._model import (CASES, LatticeState, Material, discrete_omega_longitudinal,
                     discrete_omega_rotation, energy)
from ._simulate import (SIMULATOR_VERSION, BlowUpError, Run, SimulationInterrupted,
                        initial_condition, integrate, simulate, snap_wavenumber)

__all__ = [
    "Material", "LatticeState", "energy", "integrate", "simulate", "Run", "METHODS", "Method",
    "get_method", "CASES", "BlowUpError", "SimulationInterrupted", "initial_condition",
    "snap_wavenumber", "discrete_omega_rotation", "discrete_omega_longitudinal",
    "SIMULATOR_VERSION", "plane_wave", "mi_gain", "PlaneWave", "hill_spectrum", "stability_map",
]
