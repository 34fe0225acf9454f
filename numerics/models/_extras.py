"""Theories only some models have, registered by the model in one place (issue 40 item 4).

The paper's chain written as a model (``flexmm``: case II, ``flexmm-rotation``: case I)
has the paper's continuum NLS (eqs. `g_i` of the paper, ``generated/coefficients.py``)
beside the theories every model has: ``point --model`` prints it as the "continuum NLS"
row and a model map stores it as ``verdict_paper`` and ``peak_gain_paper``, as the paper
flags' maps do. The commands ask :func:`extra_theories`; none names a model. The match is
by the model's energy (``energy_hash``: fields, the parameters the energy uses, its
expressions; as the fused kernel's), and only without ``[dissipation]`` (the paper's NLS
has no losses): a file of the paper chain's energy under another name has the row, a
flexmm file whose energy changed or that adds losses (``flexmm-lossy``) has not.
"""

from __future__ import annotations

import functools
import math
from collections.abc import Callable
from dataclasses import dataclass

from energy import Model, builtin


@dataclass(frozen=True)
class ExtraTheory:
    """A theory one model has: ``column`` names its map variables (verdict_<column>,
    peak_gain_<column>), ``label`` its row in ``point``; ``energy_hash()`` the energy it
    belongs to (``energy_hash`` of a lossless model); ``row(model, k, amplitude)`` -> {"verdict", "peak_gain",
    "g1", "g2"} (peak_gain and the coefficients None where undefined)."""

    column: str
    label: str
    energy_hash: Callable[[], str]
    row: Callable


_EXTRAS: list = []


def register_extra_theory(column: str, label: str, energy_hash: Callable[[], str],
                          row: Callable) -> None:
    """Register a theory of the lossless models whose energy hashes to ``energy_hash()``
    (see :class:`ExtraTheory`); ``column`` a lower-case word (a map variable's suffix)."""
    if not column.isidentifier() or column != column.lower():
        raise ValueError(f"an extra theory's column must be a lower-case identifier, got "
                         f"{column!r}")
    _EXTRAS.append(ExtraTheory(column, label, energy_hash, row))


#: energy_hash by the file's content_hash (computed once per model file and process)
_ENERGY_HASHES: dict = {}


def extra_theories(model: Model) -> tuple:
    """The :class:`ExtraTheory` entries of ``model`` (by its energy; none for a model with
    losses), in the order registered; () for most models."""
    if model.lossy or not _EXTRAS:
        return ()
    from ._forces import energy_hash

    lattice = model.lattice
    mine = _ENERGY_HASHES.get(lattice.content_hash)
    if mine is None:
        mine = _ENERGY_HASHES[lattice.content_hash] = energy_hash(lattice)
    return tuple(e for e in _EXTRAS if e.energy_hash() == mine)


def _builtin_hash(name: str) -> Callable[[], str]:
    from ._forces import energy_hash

    return functools.cache(lambda: energy_hash(builtin(name)))


def _paper_nls(case: str) -> Callable:
    def row(model: Model, k: float, amplitude: float) -> dict:
        """The paper's continuum NLS at (k, amplitude): g1, g2 of eq. `g_i`; MI where
        g = g2/g1 > 0, peak gain |g2| a^2 / 4 (a the peak rotation, 2 eps A0)."""
        from generated import coefficients as c

        p = (k, model.params["alpha"], model.params["K_s"], model.params["K_theta"])
        g1, g2 = float(c.g1(*p)), float(getattr(c, f"g2_{case}")(*p))
        if not (math.isfinite(g1) and math.isfinite(g2)) or g1 == 0:
            return {"verdict": "undefined", "peak_gain": None, "g1": None, "g2": None}
        mi = g2 / g1 > 0
        return {"verdict": "MI" if mi else "stable",
                "peak_gain": abs(g2) * amplitude**2 / 4 if mi else 0.0, "g1": g1, "g2": g2}
    return row


register_extra_theory("paper", "continuum NLS", _builtin_hash("flexmm"), _paper_nls("coupled"))
register_extra_theory("paper", "continuum NLS", _builtin_hash("flexmm-rotation"),
                      _paper_nls("rotation"))

__all__ = ["ExtraTheory", "register_extra_theory", "extra_theories"]
