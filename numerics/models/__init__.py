"""Any lattice model (``energy.Model``): linear waves, the semi-discrete NLS with its mean
flow, simulation of the lattice and the exact plane-wave theory.

carrier, branches, check_rest_stable   linear waves: k -> omega, v_g, g1 on a branch
nls -> ModelNLS                         the semi-discrete NLS (g1, g2, second harmonic,
                                        mean flow), MI verdict, gain curve, soliton
model_coefficients                      the NLS at one carrier as a JSON-ready dict
model_map                               MI map over two parameters, or a parameter and k
"""

from ._linear import Carrier, branch_index, branches, carrier, check_rest_stable
from ._map import model_map
from ._nls import ModelNLS, ModelSoliton, acoustic_directions, nls
from ._summary import model_coefficients

__all__ = ["Carrier", "carrier", "branches", "branch_index", "check_rest_stable", "ModelNLS",
           "ModelSoliton", "nls", "acoustic_directions", "model_map",
           "model_coefficients"]
