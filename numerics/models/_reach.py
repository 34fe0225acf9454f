"""Where a model's energy stops being real along a plane wave, said in the model's words.

A model whose energy is real only in part of the strain space (a Hertz contact
``(d0 - (u_next - u))**(5/2)`` that opens past d0, a logarithm, a square root) has no
travelling wave of an amplitude whose linear profile leaves that part: the solver then
stops on non-finite residuals ("Residuals are not finite in the initial point."). This
module tells why, and the largest amplitude the model allows at that k:

amplitude_reach      the largest amplitude with the energy and force finite along the linear
                     wave at k (bisection), and the strain it reaches there
energy_not_real      the sentence (None where the energy is finite at this amplitude)
exact_gain_checked   ``exact_gain``, whose non-finite failures become a ModelError with
                     that sentence (the call sites of the travelling wave use it)
"""

from __future__ import annotations

import math

import numpy as np

from energy import Model, ModelError

from ._linear import check_amplitude

#: sites of the ring the linear profile is checked on (its phases k n mod 2 pi)
_SITES = 512
#: halvings of the amplitude at most: 2^-64 of it (5e-20) is no amplitude left. Without a
#: bound a model real at no amplitude (the bond r**(5/2), not real for r < 0, which every
#: wave reaches) looped forever: hi underflows to 5e-324, mid rounds to 0 (finite), and
#: hi - lo > rtol * hi reads 5e-324 > 0
MAX_HALVINGS = 64


def _profile(model: Model, k: float, amplitude: float, branch, car=None):
    """The linear plane wave's displacements and velocities on a ring of ``_SITES`` sites
    at the nearest k it carries: (u, v), each (d, N). ``car``: the carrier at (k, branch)
    where the caller has it (a map cell's NLS: its eigenproblem is most of the cost)."""
    from ._linear import carrier

    car = carrier(model, k, branch) if car is None else car
    m = max(1, round(k * _SITES / (2 * math.pi)))
    xi = 2 * math.pi * m / _SITES * np.arange(_SITES)
    e = car.e[:, None]
    u = amplitude * np.real(e * np.exp(1j * xi))
    v = amplitude * car.omega * np.real(-1j * e * np.exp(1j * xi))
    return np.ascontiguousarray(u), np.ascontiguousarray(v), car


def _finite(model: Model, k: float, amplitude: float, branch, car=None) -> bool:
    """Energy and force finite along the linear wave: every cell's energy and gradient,
    from the generated module's numpy functions (the compiled force would cost its
    compilation, ~1.5 s, in every process that asks: each worker of a map; the kinetic
    energy of finite velocities is finite)."""
    u, _, _ = _profile(model, k, amplitude, branch, car)
    x = np.concatenate([u, np.roll(u, -1, axis=1)])  # the cells (n, n + 1) of the ring
    grad = np.empty_like(x)
    with np.errstate(all="ignore"):
        energy = model.code.cell_energy(x, model.p)
        model.code.cell_gradient_into(x, model.p, grad)
        return bool(np.all(np.isfinite(energy)) and np.all(np.isfinite(grad)))


def _site_limited(model: Model, k: float, amplitude: float, branch) -> bool:
    """Whether the energy is not real already without strain: each cell of the linear wave
    at this amplitude taken with its neighbour displaced as itself (u_next = u), which
    leaves the site term (and the bond at rest strain). A square root or logarithm of a
    displacement (a site limit) is not real there; a Hertz contact's (a bond's) is."""
    u, _, _ = _profile(model, k, amplitude, branch)
    with np.errstate(all="ignore"):
        return not bool(np.all(np.isfinite(model.code.cell_energy(
            np.concatenate([u, u]), model.p))))


def _strain(model: Model, k: float, amplitude: float, branch,
            site: bool = False) -> tuple[float, str]:
    """The largest bond strain |u_next - u| of the linear wave and its field (``site``:
    the largest displacement |u|)."""
    u, _, car = _profile(model, k, amplitude, branch)
    r = np.abs(u if site else np.roll(u, -1, axis=1) - u).max(axis=1)
    i = int(np.argmax(r))
    return float(r[i]), model.fields[i]


def amplitude_reach(model: Model, k: float, amplitude: float, branch=None, *,
                    rtol: float = 1e-4, carrier=None) -> float:
    """The largest amplitude a <= ``amplitude`` with the model's energy and force finite
    along the linear wave at ``k`` (bisection, to ``rtol``); ``amplitude`` itself where
    they are finite there, 0 where they are not finite at any amplitude tried.
    ``carrier``: the model's ``carrier(model, k, branch)``, where the caller has it."""
    amplitude = check_amplitude(amplitude)
    if _finite(model, k, amplitude, branch, carrier):
        return float(amplitude)
    lo, hi = 0.0, float(amplitude)
    for _ in range(MAX_HALVINGS):
        if hi - lo <= rtol * hi:
            break
        mid = (lo + hi) / 2
        lo, hi = (mid, hi) if _finite(model, k, mid, branch, carrier) else (lo, mid)
    return lo


def energy_not_real(model: Model, k: float, amplitude: float, branch=None, *,
                    carrier=None) -> str | None:
    """Why there is no wave of this amplitude at k, when its energy is not real there: the
    strain the linear wave reaches, the strain where the energy stops being real (with the
    parameter of that value, if one has it) and the largest amplitude allowed at this k.
    None where energy and force are finite along the linear wave. ``carrier``: the
    model's ``carrier(model, k, branch)`` where the caller has it (a map cell's NLS
    computed it: the check then costs the profile's energy, not a second eigenproblem)."""
    a_max = amplitude_reach(model, k, amplitude, branch, carrier=carrier)
    if a_max >= amplitude:
        return None
    site = _site_limited(model, k, amplitude, branch)
    strain, field = _strain(model, k, amplitude, branch, site)
    edge, _ = _strain(model, k, a_max, branch, site)
    named = [f"{n} = {v:g}" for n, v in model.params.items()
             if v and abs(edge / v - 1) < 2e-3]
    what = (f"displacement |{field}|" if site
            else f"strain |{field}_next - {field}|")
    where = (f"the {field} {what} of the linear wave reaches {strain:.3g}, beyond "
             f"{edge:.3g}"
             + (f" ({' or '.join(named)})" if named else "")
             + " where the model's energy stops being real")
    allowed = (f"the largest amplitude the model allows at k = {k:.4g} is about {a_max:.3g}"
               if a_max > 0 else "no amplitude tried had a real energy at this k")
    return (f"at amplitude {amplitude:g} the energy is not real: {where}; {allowed} "
            "(its linear wave keeps the energy real)")


def exact_gain_checked(model: Model, k: float, amplitude: float, branch=None, **kw):
    """``exact_gain``; where its solver stops on non-finite values, or finds no wave where
    the energy is not real along the linear wave, a ModelError that says the energy is not
    real there and the largest amplitude allowed (``energy_not_real``)."""
    import warnings

    from ._exact import exact_gain

    with warnings.catch_warnings(record=True) as caught:  # said again unless it fails here
        warnings.simplefilter("always")
        try:
            spec = exact_gain(model, k, amplitude, branch, **kw)
        except (ValueError, FloatingPointError) as exc:
            try:
                why = energy_not_real(model, k, amplitude, branch)
            except Exception:  # the check itself failed: the solver's own error stands
                why = None
            if why is None:
                raise
            if isinstance(exc, ModelError):  # no wave found, and the energy is not real
                why += " (the harmonic balance found no wave either)"  # along the linear one
            raise ModelError(why) from exc
    for w in caught:
        warnings.warn_explicit(w.message, w.category, w.filename, w.lineno)
    return spec
