"""Lattice models from their energy: the first room of the pipeline.

    energy -> derivation -> generated -> numerics -> scenes, cli

A model is one unit cell's energy (kinetic, bond to the next cell, on-site) over named
fields, written as a TOML file (``docs/models.md``) or as a :class:`Lattice`. This package
reads and checks models without SymPy (importing it costs milliseconds) and hands them to
the rest:

Lattice, ModelError          the model as data; the one error a bad model raises
read_model, parse_model      a model file (path or text) -> Lattice
BUILTIN, builtin             the built-in models (energy/models/*.toml) by name
load_model -> Model          a model with parameter values and its generated code (derived
                             on first use and cached by the content hash of its energy)
check_generated              is a generated module whole (its body's hash) and of this energy
check_name, RESERVED         the rule for field and parameter names
check_value, MAX_VALUE       the rule for a parameter's value (finite, |v| <= 1e15)
"""

from __future__ import annotations

from ._model import (
    BUILTIN,
    Model,
    ModelCacheWarning,
    builtin,
    check_generated,
    load_model,
    module_name,
    resolve_model,
    with_body_hash,
)
from ._spec import (
    FUNCTIONS,
    MAX_VALUE,
    RESERVED,
    Lattice,
    ModelError,
    check_name,
    check_value,
    parse_model,
    read_model,
)

__all__ = ["Lattice", "ModelError", "read_model", "parse_model", "BUILTIN", "builtin",
           "load_model", "resolve_model", "module_name", "Model", "FUNCTIONS", "RESERVED",
           "check_name", "check_value", "MAX_VALUE", "ModelCacheWarning", "check_generated",
           "with_body_hash"]
