"""A model map's axes: the checks that need the model or the ring
(``ModelMapParameters.__post_init__``, said in one line before any cell runs) and the
attributes the store gives them."""

from __future__ import annotations

import math

import numpy as np


def same_ring_k(params) -> str | None:
    """Where two k values of the map snap to one ring wavenumber 2 pi m / N: a note (their
    columns run one carrier under two labels, the plot showing a k resolution the ring
    lacks); None where they are distinct or the map has no ring. The paper chain's map
    refuses them; a model map keeps them (its stores and scripts predate the rule)."""
    if not params.ring:
        return None
    seen = {}
    for v in dict([params.rows, params.cols]).get("k", ()):
        m = round(v * params.N / (2 * math.pi))
        if m in seen:
            return (f"--k {seen[m]:g} and {v:g} both snap to 2 pi {m}/{params.N} = "
                    f"{2 * math.pi * m / params.N:.6g} on the ring of N = {params.N}: their "
                    "columns are one carrier, computed twice; a larger --N separates them")
        seen[m] = v
    return None


def checked_branch(params) -> str:
    """The map's branch as stored (a str, as --branch gives it: an int index becomes
    '1'), refused in one line where the model has no such branch (every cell was
    undetermined, said nowhere)."""
    from energy import ModelError
    from numerics.models import branch_index

    branch = params.branch
    if isinstance(branch, (int, np.integer)) and not isinstance(branch, bool):
        branch = str(int(branch))
    if not isinstance(branch, str):
        raise TypeError(f"branch must be an index or a field name, got {branch!r}")
    value = int(branch) if branch.lstrip("-").isdigit() else branch
    try:
        branch_index(params.lattice_model, params.cell(0, 0)[1], value)
    except ModelError as exc:
        raise ValueError(str(exc)) from None
    return branch


def axis_attrs(name: str) -> dict:
    """A map axis' attributes: what it is and its unit (a parameter or amplitude axis had
    none, where every variable says its unit)."""
    from ._model_params import AXIS_AMPLITUDE

    if name == "k":
        return {"long_name": "carrier wavenumber asked (k_simulated: on the ring)",
                "units": "rad per site"}
    if name == AXIS_AMPLITUDE:
        return {"long_name": "amplitude a of the carrier's first harmonic in its field",
                "units": "the carrier field's own unit"}
    return {"long_name": f"model parameter {name}",
            "units": "the model file's (lattice units)"}
