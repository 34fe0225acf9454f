"""Theories and starts only some models have, registered by the model in one place (issue 40
item 4).

The paper's chain written as a model (``flexmm``: case II, ``flexmm-rotation``: case I)
has the paper's continuum NLS (eqs. `g_i` of the paper, ``generated/coefficients.py``)
beside the theories every model has: ``point --model`` prints it as the "continuum NLS"
row and a model map stores it as ``verdict_paper`` and ``peak_gain_paper``, as the paper
flags' maps do. The commands ask :func:`extra_theories`; none names a model. The match is
by the model's energy (``energy_hash``: fields, the parameters the energy uses, its
expressions; as the fused kernel's), and only without ``[dissipation]`` (the paper's NLS
has no losses): a file of the paper chain's energy under another name has the row, a
flexmm file whose energy changed or that adds losses (``flexmm-lossy``) has not.

The same models have the paper's start, eq. `IC` (``start="paper"``: the plane wave
theta = a cos(k n) with the continuum frequency, U = 0, every field times (1 + b0),
b0 ~ U[-noise, noise]; ``numerics.lattice.initial_condition``), and its theory, Hill's
method about the state that start launches ("exact lattice, paper start",
``numerics.theory.theory_gain``): ``simulate_model(start="paper")``, ``point --model
flexmm --start paper``. Both are the paper engine's own functions, on the model's
parameters; the model's runs step the same fused force (the registered fast force).
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
    mine = _energy_hash_of(model)
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


@dataclass(frozen=True)
class ExtraStart:
    """A start one model has (beside every model's "exact" and "linear"): ``name`` the
    ``start=`` value, ``describe`` what it launches (words), ``energy_hash()`` the energy it
    belongs to; ``state(model, k, amplitude, N, noise, seed)`` -> (u, v), each (d, N),
    its own noise law included (``noise`` None: the start's default), a ModelError where it
    has no state; ``noise`` the default; ``theory(model, k, amplitude, N)`` -> {"label",
    "verdict", "peak_gain", "fastest_offset", "curve": (offsets, rates)} on the ring's
    offsets (and "reason", without "curve", where undefined), the theory of the state it
    launches."""

    name: str
    describe: str
    energy_hash: Callable[[], str]
    state: Callable
    noise: float
    theory: Callable


_STARTS: list = []


def register_extra_start(name: str, describe: str, energy_hash: Callable[[], str],
                         state: Callable, noise: float, theory: Callable) -> None:
    """Register a start of the lossless models whose energy hashes to ``energy_hash()``
    (see :class:`ExtraStart`); ``name`` a lower-case word other than "exact", "linear"."""
    if not name.isidentifier() or name != name.lower() or name in ("exact", "linear"):
        raise ValueError(f"an extra start's name must be a lower-case identifier other than "
                         f"'exact' and 'linear', got {name!r}")
    _STARTS.append(ExtraStart(name, describe, energy_hash, state, float(noise), theory))


def _energy_hash_of(model: Model) -> str:
    from ._forces import energy_hash

    lattice = model.lattice
    mine = _ENERGY_HASHES.get(lattice.content_hash)
    if mine is None:
        mine = _ENERGY_HASHES[lattice.content_hash] = energy_hash(lattice)
    return mine


def extra_starts(model: Model) -> dict:
    """{name: :class:`ExtraStart`} of ``model`` (by its energy; none for a model with
    losses); {} for most models."""
    if model.lossy or not _STARTS:
        return {}
    mine = _energy_hash_of(model)
    return {e.name: e for e in _STARTS if e.energy_hash() == mine}


def _material(model: Model):
    from numerics.lattice import Material

    p = model.params
    return Material(p["alpha"], p["K_s"], p["K_theta"])


def _paper_state(case: str) -> Callable:
    def state(model: Model, k: float, amplitude: float, N: int, noise: float | None = None,
              seed: int = 0):
        """Eq. `IC` of the paper on the model's parameters: (u, v) with u = (theta, U)
        (case II) or (theta,) (case I), as ``initial_condition(start="paper")`` builds
        it for the paper engine (the same arrays)."""
        import numpy as np

        from energy import ModelError
        from numerics.lattice import initial_condition, paper_start_undefined

        mat = _material(model)
        why = paper_start_undefined(mat, k, ("exact", "linear"))
        if why is not None:
            raise ModelError(why)
        st = initial_condition(mat, case, N, k, amplitude, PAPER_NOISE if noise is None
                               else noise, seed, "paper")
        if case == "coupled":
            return np.stack([st.theta, st.U]), np.stack([st.theta_dot, st.U_dot])
        return st.theta[None].copy(), st.theta_dot[None].copy()
    return state


def _paper_start_theory(case: str) -> Callable:
    def theory(model: Model, k: float, amplitude: float, N: int) -> dict:
        """Hill's method about the state eq. `IC` launches (``theory_gain``'s
        "exact lattice, paper start") at the ring's offsets 2 pi j / N, j = 1 .. N/2."""
        import numpy as np

        from numerics.theory import PAPER_START, theory_gain

        q = 2 * np.pi * np.arange(1, N // 2 + 1) / N
        undefined = {"label": PAPER_START, "verdict": "undefined", "peak_gain": None,
                     "fastest_offset": None}
        try:
            sigma = np.asarray(theory_gain(PAPER_START, _material(model), case, k, amplitude,
                                           q))
        except ArithmeticError as exc:  # not a torus, or no plane wave: no linear theory
            return {**undefined, "reason": str(exc)}
        if not np.any(np.isfinite(sigma)):
            return {**undefined, "reason": "no sideband offset of the ring has a rate"}
        i = int(np.nanargmax(sigma))
        mi = bool(sigma[i] > 0)
        return {"label": PAPER_START, "verdict": "MI" if mi else "stable",
                "peak_gain": float(sigma[i]) if mi else 0.0,
                "fastest_offset": float(q[i]) if mi else None, "curve": (q, sigma)}
    return theory


#: the paper's noise on eq. `IC`: every field times (1 + b0), b0 ~ U[-1e-3, 1e-3] (as its
#: runs, ``numerics.lattice.initial_condition``'s default)
PAPER_NOISE = 1e-3

register_extra_start("paper", "the paper's plane wave (eq. IC)", _builtin_hash("flexmm"),
                     _paper_state("coupled"), PAPER_NOISE, _paper_start_theory("coupled"))
register_extra_start("paper", "the paper's plane wave (eq. IC)",
                     _builtin_hash("flexmm-rotation"), _paper_state("rotation"), PAPER_NOISE,
                     _paper_start_theory("rotation"))

__all__ = ["ExtraTheory", "register_extra_theory", "extra_theories", "ExtraStart",
           "register_extra_start", "extra_starts"]
