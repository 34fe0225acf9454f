"""One record per theory of MI: its one spelling in each layer, read by every layer (no
layer keeps a table translating one spelling into another).

label (API, tables)          key (store)   module (generated/)    cli (--theory)  column
paper NLS                    paper         coefficients           paper           continuum (paper)
semi-discrete NLS            semidiscrete  lattice_coefficients   semi-discrete   semi-discrete
exact lattice                exact
exact lattice, paper start   exact
exact lattice, every mode    exact_all
linear response              predicted

The derivation calls the two NLS models ``continuum`` and ``lattice`` (``make derive``'s
inputs, ``derivation/_multiscale.py``); their generated modules are the ``module`` column.
A map store's variables are ``verdict_<key>`` and ``peak_gain_<key>``; the exact theory of
either start fills the one ``exact`` column (the map's start is in its attributes).
"""

from __future__ import annotations

from dataclasses import dataclass
from importlib import import_module


@dataclass(frozen=True)
class Theory:
    """A theory of MI and its name in each layer.

    Attributes
    ----------
    key : str
        Short name: a map store's ``verdict_<key>`` / ``peak_gain_<key>`` and JSON keys.
    label : str
        The API's name (``theory_gain(theory=label)``) and the rows of ``flexmm point``.
    module : str or None
        The generated module of its closed forms (``generated/<module>.py``), for an NLS.
    cli : str or None
        The value a command's ``--theory`` option takes, for an NLS.
    column : str or None
        The column header of ``flexmm coefficients`` (and the key of
        ``nls_coefficients``' dict), for an NLS.
    """

    key: str
    label: str
    module: str | None = None
    cli: str | None = None
    column: str | None = None

    def closed_forms(self):
        """The generated module of its closed forms (``generated.<module>``)."""
        if self.module is None:
            raise ValueError(f"{self.label} has no generated closed forms")
        return import_module(f"generated.{self.module}")


PAPER_NLS = Theory("paper", "paper NLS", "coefficients", "paper", "continuum (paper)")
SEMIDISCRETE_NLS = Theory("semidiscrete", "semi-discrete NLS", "lattice_coefficients",
                          "semi-discrete", "semi-discrete")
EXACT_LATTICE = Theory("exact", "exact lattice")
#: the exact theory of the state eq. `IC` launches (travelling wave + free waves)
EXACT_PAPER_START = Theory("exact", "exact lattice, paper start")
#: every growing Hill mode of the travelling wave, not only sideband pairs
EXACT_ALL_MODES = Theory("exact_all", "exact lattice, every mode")
#: the growth factor predicted from the linear response of a run's own initial state
PREDICTED = Theory("predicted", "linear response")

#: every theory, in the order tables and summaries show them
THEORY_RECORDS = (PAPER_NLS, SEMIDISCRETE_NLS, EXACT_LATTICE, EXACT_PAPER_START,
                  EXACT_ALL_MODES, PREDICTED)
#: the two NLS theories (closed forms in generated/)
NLS_THEORIES = (PAPER_NLS, SEMIDISCRETE_NLS)
#: a map's theory verdict columns (``verdict_<key>``), in the order its summaries print them
MAP_COLUMNS = tuple(dict.fromkeys(t.key for t in THEORY_RECORDS))

__all__ = ["Theory", "THEORY_RECORDS", "NLS_THEORIES", "MAP_COLUMNS", "PAPER_NLS",
           "SEMIDISCRETE_NLS", "EXACT_LATTICE", "EXACT_PAPER_START", "EXACT_ALL_MODES",
           "PREDICTED"]
