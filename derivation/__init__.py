"""Symbolic pipeline: eq. `norm` -> continuum limit -> multiple scales -> NLS -> MI band.

Public API
----------
derive()                 all closed forms (a :class:`Derivation`), cached per process
derive_continuum()       Taylor expansion of the lattice to eqs. `eqnorm1`-`eqnorm2`
solve_case(case, model)  the multiple-scales hierarchy for "rotation" or "coupled",
                         on the continuum ("continuum") or on the lattice ("lattice")
analyse_mi()             MI analysis of the normalised NLS
model_energies(lattice)  any lattice model (energy.Lattice) read into SymPy, checked
equations_of_motion(e)   its equations of motion, from the energy (Lagrange)
compile_model(lat, path) its generated NumPy module (derivatives of the cell energy)
model_module_text(lat)   that module's text (only checked names and repr literals of the
                         model file reach it; its last line holds the body's hash)
paper                    the paper's numbers (test points, eps, noise, N, T) - no SymPy
paper_forms              the paper's closed forms typed by hand (for comparison)
ERRATA                   errata of the paper
atomic_write             write-then-rename, used by every layer that writes files

Importing the package is cheap: the SymPy modules load on first use of a name that
needs them (PEP 562), so ``from derivation import ERRATA`` costs nothing.
"""

from importlib import import_module

from common import paper
from common.files import atomic_write

from .errata import ERRATA

_LAZY = {
    "derive": ("._pipeline", "derive"),
    "Derivation": ("._pipeline", "Derivation"),
    "ClosedForm": ("._pipeline", "ClosedForm"),
    "derive_continuum": ("._continuum", "derive_continuum"),
    "solve_case": ("._multiscale", "solve_case"),
    "analyse_mi": ("._mi", "analyse"),
    "paper_forms": (".paper_forms", None),
    "compile_model": ("._model_code", "compile_model"),
    "model_module_text": ("._model_code", "model_module_text"),
    "model_energies": ("._energy", "energies"),
    "equations_of_motion": ("._energy", "equations_of_motion"),
}

__all__ = ["derive", "derive_continuum", "solve_case", "analyse_mi", "paper", "paper_forms",
           "ERRATA", "Derivation", "ClosedForm", "atomic_write", "compile_model",
           "model_module_text", "model_energies", "equations_of_motion"]


def __getattr__(name):
    try:
        module, attr = _LAZY[name]
    except KeyError:
        raise AttributeError(f"module 'derivation' has no attribute {name!r}") from None
    mod = import_module(module, __name__)
    value = mod if attr is None else getattr(mod, attr)
    globals()[name] = value
    return value


def __dir__():
    return sorted(__all__)
