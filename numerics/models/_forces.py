"""Which force a model's run uses, and the fast forces the built-in models register.

A run's force is the one generated from the model's energy (``compiled_force``: the
reference), unless a fast force is registered for that energy
(``numerics.lattice.register_fast_force``): the fused flexMM kernel of eq. `norm` for the
paper chain written as a model (``flexmm``: case II; ``flexmm-rotation``: case I; the
lossy ``flexmm-lossy`` has flexmm's energy, its damping added apart). The match is by
content (``energy_hash``: fields, parameter names and the energy's expressions), so a file
named flexmm with another energy runs its own generated force, and a file of another name
with the paper chain's energy runs the fused kernel. Both are tested equal (to 1e-12 of
the force) in tests/test_fast_forces.py.
"""

from __future__ import annotations

import ast
import hashlib
import json

import numpy as np

from energy import Lattice, Model, ModelError, builtin
from numerics.lattice import (
    FLEXMM_ROWS,
    fast_force,
    flexmm_force,
    flexmm_rotation_force,
    register_fast_force,
)

ENERGY_KEYS = ("kinetic", "bond", "site")
#: ``force=`` of a run: the registered fast force where the model's energy has one
#: ("auto"), or always the generated one ("generated", the reference)
FORCES = ("auto", "generated")


def energy_hash(lattice: Lattice) -> str:
    """sha256 of what defines a model's conservative force: its fields (in order), the
    names of the parameters its energy uses, and the energy's expressions (kinetic, bond,
    site); not its name, description, defaults, dissipation or the dissipation's
    parameters (the damping is a force of its own, added to whichever force runs)."""
    canon = lattice.canonical()
    used = {node.id for key in ENERGY_KEYS for node in ast.walk(lattice.tree(key))
            if isinstance(node, ast.Name)}
    text = json.dumps({"fields": canon["fields"], "energy": canon["energy"],
                       "parameters": sorted(set(canon["parameters"]) & used)},
                      sort_keys=True)
    return hashlib.sha256(text.encode()).hexdigest()


def _flexmm_parameters(params) -> np.ndarray:
    """The fused kernel's (alpha^2, K_s, K_theta) from a flexmm model's values."""
    return np.array([params["alpha"] ** 2, params["K_s"], params["K_theta"]], dtype=float)


def _builtin_hash(name: str):
    return lambda: energy_hash(builtin(name))


register_fast_force("flexmm", _builtin_hash("flexmm"), flexmm_force, FLEXMM_ROWS,
                    _flexmm_parameters)
register_fast_force("flexmm-rotation", _builtin_hash("flexmm-rotation"),
                    flexmm_rotation_force, FLEXMM_ROWS, _flexmm_parameters)


def run_force(model: Model, force: str = "auto"):
    """(force, p, rows, label) a run of ``model`` steps with (``ForceStepper``'s first
    three arguments): the registered fast force of its energy where there is one and
    ``force`` is "auto" (label "fast:NAME"), else its generated force (label
    "generated")."""
    if force not in FORCES:
        raise ModelError(f"force must be one of {', '.join(FORCES)}, got {force!r}")
    if force == "auto":
        fast = fast_force(energy_hash(model.lattice))
        if fast is not None:
            return (fast.force, fast.parameters(model.params), fast.rows,
                    f"fast:{fast.name}")
    from ._compiled import _kernels

    compiled = _kernels(model)
    return compiled.force, np.asarray(model.p, float), compiled.rows, "generated"
