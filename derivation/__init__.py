"""Symbolic pipeline: eq. `norm` -> continuum limit -> multiple scales -> NLS -> MI band.

Public API
----------
derive()                 all closed forms (a :class:`Derivation`), cached per process
derive_continuum()       Taylor expansion of the lattice to eqs. `eqnorm1`-`eqnorm2`
solve_case(case)         the multiple-scales hierarchy for "rotation" or "coupled"
analyse_mi()             MI analysis of the normalised NLS
paper_forms              the paper's closed forms typed by hand (for comparison)
ERRATA                   errata of the paper
"""

from . import paper_forms
from ._continuum import derive_continuum
from ._mi import analyse as analyse_mi
from ._multiscale import solve_case
from ._pipeline import ClosedForm, Derivation, derive
from .errata import ERRATA

__all__ = ["derive", "derive_continuum", "solve_case", "analyse_mi", "paper_forms",
           "ERRATA", "Derivation", "ClosedForm"]
