"""Named initial states: the one vocabulary for what a run starts from.

A *start* is a name that every layer uses alike: ``simulate(start=...)``, the theories
(``mi_gain``, ``launched_state``, ``gain_spectrum``), the maps and ``flexmm --start``.

========== ======================================================================
name        what the chain starts in (peak rotation ``amplitude``, noise b0 per site)
========== ======================================================================
paper       eq. `IC` (eq. (14) of the paper): theta = a (1 + b0) cos(k n), theta_dot
            from the continuum frequency of eq. `continuum2`, U = U_dot = 0
discrete    eq. `IC` with the lattice's linear frequency (eq. `discrete2`)
travelling  the lattice's exact nonlinear plane wave (``numerics.theory.plane_wave``),
            every field times (1 + b0); registered by ``numerics.theory``
========== ======================================================================

The simulator only knows the registry; the exact travelling wave is theory, which fills
its entry on import (as integrators register in ``METHODS``), so ``numerics.lattice``
never imports ``numerics.theory``.
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np

from generated import coefficients as _continuum

from . import checks
from ._model import LatticeState, Material, discrete_omega_rotation

#: every start's name, in the order the CLI lists them
STARTS = ("paper", "discrete", "travelling")
#: the names earlier versions used for ``simulate(omega_model=...)``
LEGACY_OMEGA_MODELS = {"continuum": "paper", "discrete": "discrete", "travelling": "travelling"}

_BUILDERS: dict[str, Callable] = {}


def register_start(name: str, build: Callable) -> None:
    """Register ``build(material, case, k, amplitude, b0) -> LatticeState`` under ``name``
    (one of :data:`STARTS`); ``b0`` is the per-site noise, shape (N,)."""
    checks.choice("start", name, STARTS)
    _BUILDERS[name] = build


def check_start(start) -> str:
    """``start`` if it is a known start name; ValueError naming the choices otherwise."""
    return checks.choice("start", start, STARTS)


def build_start(start: str, material: Material, case: str, k: float, amplitude: float,
                b0: np.ndarray) -> LatticeState:
    check_start(start)
    try:
        build = _BUILDERS[start]
    except KeyError:
        raise ValueError(f"start {start!r} is provided by numerics.theory; "
                         "`import numerics` registers it") from None
    return build(material, case, k, amplitude, b0)


def _ic(omega, name):
    def build(material, case, k, amplitude, b0):
        with np.errstate(invalid="ignore"):
            w = float(omega(k, material))
        if not np.isfinite(w):
            raise ValueError((paper_start_undefined(material, k) if name == "paper" else None)
                             or f"start {name!r}: no real carrier frequency at k = {k:.6g}")
        n = np.arange(b0.size)
        amp = amplitude * (1 + b0)
        theta, theta_dot = amp * np.cos(k * n), amp * w * np.sin(k * n)
        if case == "coupled":
            return LatticeState(np.zeros(b0.size), np.zeros(b0.size), theta, theta_dot)
        return LatticeState(None, None, theta, theta_dot)
    return build


def paper_start_undefined(material: Material, k,
                          others: tuple = ("discrete", "travelling")) -> str | None:
    """Why eq. `IC` (start "paper") has no state at carrier k, or None where it has one:
    it takes theta_dot from the continuum frequency omega = alpha sqrt(6 K_theta + delta
    k^2) (eq. `continuum2`), which is not real where delta < 0 and k^2 > 6 K_theta / |delta|
    (the long-wave model does not reach such k)."""
    k = np.asarray(k, float)
    bad = 6 * material.K_theta + material.delta * k**2 < 0  # omega = 0 still builds (at rest)
    if not np.any(bad):
        return None
    k_max = float(np.sqrt(6 * material.K_theta / -material.delta))
    where = (f"at k = {float(k):.6g}" if k.ndim == 0 else
             f"at {int(bad.sum())} of {bad.size} k values")
    return (f"start 'paper' (eq. `IC`) takes theta_dot from the continuum frequency alpha "
            f"sqrt(6 K_theta + delta k^2) (eq. `continuum2`), which is not real {where} for "
            f"this material (delta = {material.delta:.4g}: only k < {k_max:.6g}); use start "
            + " or ".join(repr(o) for o in others))


register_start("paper", _ic(lambda k, m: _continuum.omega(k, m.alpha, m.K_s, m.K_theta),
                            "paper"))
register_start("discrete", _ic(discrete_omega_rotation, "discrete"))
