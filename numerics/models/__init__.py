"""Any lattice model (``energy.Model``): linear waves, the semi-discrete NLS with its mean
flow, simulation of the lattice and the exact plane-wave theory.

carrier, branches, check_rest_stable   linear waves: k -> omega, v_g, g1 on a branch
nls -> ModelNLS                         the semi-discrete NLS (g1, g2, second harmonic,
                                        mean flow), MI verdict, gain curve, soliton
model_coefficients                      the NLS at one carrier as a JSON-ready dict
travelling_wave -> TravellingWave       the exact plane wave (harmonic balance)
hill_spectrum -> HillSpectrum           its sidebands' growth rates (Hill/Floquet)
exact_gain                              both at one point: the exact lattice theory
not_converged                           its sentence where the fastest mode does not
                                        persist across Hill truncations
four_wave -> FourWave                   every four-wave pair's rate (Zakharov's kernel of the
                                        lattice): sidebands, backward pairs, parametric pairs
classify_mode, ring_misses              what an exact mode is; bands a ring does not sample
field_groups, wave_sheet, sheet_pair_kind, sheet_branches   dispersion sheets: a wave's own branch where
                                        branches of uncoupled fields cross
energy_not_real, amplitude_reach        where the energy stops being real along a wave: why
exact_gain_checked                      there is no travelling wave, the largest amplitude
simulate_model -> ModelRun              a ring of the model; .growth() -> Growth
time_scale                              the unit of a run's length bounds (a stiff chain's)
run_step, local_frequency               a run's step: the branches', the start state's or
                                        the damping's fastest rate; a dt past the limit refused
simulate_soliton -> ModelSolitonRun     its NLS soliton launched on a ring and tracked
                                        (ring_soliton: the prediction on that ring)
lattice_force, lattice_energy           the compiled force and the model's energy
run_force, energy_hash, FORCES          the force a run steps with: a registered fast force
                                        (the fused flexMM kernel) where the energy is the
                                        one it implements, else the generated one
model_map                               MI map over two parameters, or a parameter and k
map_cells                               the columns of a block of map cells (a run_map task)
nls_amplification, four_wave_amplification, exact_amplification
                                        with [dissipation]: each theory's sidebands'
                                        amplification along the decaying carrier
lossy_runs                              a lossy cell's runs and their amplification
carrier_overdamped                      whether the carrier's damped root does not oscillate
extra_theories, register_extra_theory   theories only some models have (the paper chain's
                                        continuum NLS), registered by content, not named
                                        by the commands
"""

from ._exact import (
                     HillSpectrum,
                     TravellingWave,
                     exact_gain,
                     hill_spectrum,
                     ring_offsets,
                     travelling_wave,
)
from ._extras import (
                     ExtraStart,
                     ExtraTheory,
                     extra_starts,
                     extra_theories,
                     register_extra_start,
                     register_extra_theory,
)
from ._forces import FORCES, energy_hash, run_force
from ._fourwave import FourWave, four_wave, pair_rates
from ._growth import read_modes, saturation_record, settled_rate
from ._hill_dense import not_converged
from ._linear import (
                     Carrier,
                     branch_index,
                     branches,
                     carrier,
                     carrier_damping,
                     check_rest_stable,
                     damped_frequencies,
                     damping_matrix,
                     damping_rates,
)
from ._losses import (
                     Amplified,
                     amplified_row,
                     exact_amplification,
                     four_wave_amplification,
                     nls_amplification,
)
from ._losses_rates import carrier_overdamped
from ._map import model_map, simulated_cell
from ._map_cells import lossy_runs, map_cells
from ._modes import (
                     classify_mode,
                     field_groups,
                     ring_misses,
                     sheet_branches,
                     sheet_pair_kind,
                     wave_sheet,
)
from ._nls import ModelNLS, ModelSoliton, acoustic_directions, nls
from ._reach import amplitude_reach, energy_not_real, exact_gain_checked
from ._seeds import SeededRuns, harmonic_offsets, simulate_seeds, visible_gain
from ._simulate import (
                     NOISE,
                     Growth,
                     ModelRun,
                     check_ring,
                     compiled_force,
                     lattice_energy,
                     lattice_force,
                     measure_growth,
                     saturation_time,
                     simulate_model,
                     snap_ring,
)
from ._soliton_ring import RingSoliton, ring_soliton
from ._soliton_run import (
                     MIN_TRAVEL,
                     ModelSolitonRun,
                     check_soliton_launch,
                     simulate_soliton,
                     soliton_report,
                     travel_time,
)
from ._step import local_frequency, run_step
from ._summary import model_coefficients
from ._time_scale import time_scale

__all__ = ["Carrier", "carrier", "branches", "branch_index", "check_rest_stable", "ModelNLS",
           "ModelSoliton", "nls", "acoustic_directions", "model_map", "map_cells",
           "simulated_cell", "model_coefficients", "carrier_damping", "damped_frequencies", "carrier_overdamped",
           "damping_matrix", "damping_rates", "TravellingWave", "HillSpectrum",
           "travelling_wave", "hill_spectrum", "exact_gain", "exact_gain_checked", "not_converged",
           "energy_not_real", "amplitude_reach", "FourWave", "four_wave", "pair_rates",
           "classify_mode", "field_groups", "sheet_branches", "sheet_pair_kind", "wave_sheet", "ring_misses", "ring_offsets", "simulate_model", "simulate_seeds", "run_step", "local_frequency",
           "SeededRuns", "ModelRun", "NOISE", "Growth", "measure_growth", "saturation_record",
           "settled_rate", "read_modes", "visible_gain", "harmonic_offsets",
           "saturation_time", "check_ring", "compiled_force",
           "lattice_force", "lattice_energy", "snap_ring", "Amplified", "amplified_row", "nls_amplification",
           "four_wave_amplification", "exact_amplification", "simulate_soliton",
           "ModelSolitonRun", "RingSoliton", "ring_soliton", "check_soliton_launch",
           "soliton_report", "travel_time", "MIN_TRAVEL", "lossy_runs",
           "FORCES", "energy_hash", "run_force", "ExtraTheory", "extra_theories",
           "register_extra_theory", "ExtraStart", "extra_starts", "register_extra_start",
           "time_scale"]
