"""Sideband gain sigma(q): measured from runs, and predicted by the three theories.

The three theories, for any material and carrier:

- ``"paper NLS"``: the continuum multiple-scales result (``generated.coefficients``),
  sigma(q) = eps^2 |g1| Omega_I((q - k) / eps) (eqs. `NLS`, `Omega_I`);
- ``"semi-discrete NLS"``: the same on the lattice (``generated.lattice_coefficients``);
- ``"exact lattice"``: Hill's method about the exact travelling wave (:func:`mi_gain`);
- ``"exact lattice, paper start"`` (``PAPER_START``): Hill's method about the state eq.
  `IC` launches (travelling wave + free waves, a torus: :func:`mi_gain` with
  ``start="paper"``), harmonics H = 1 (converged to 1e-4 relative at amplitude 0.02,
  tests/test_launched.py), about 0.2 s per offset.
"""

from __future__ import annotations

import numpy as np

from common.paper import EPS

from ..lattice import Material, check_case, checks, growth_rates, linear_stage
from ._hill import mi_gain
from ._plane_wave import MAX_AMPLITUDE
from ._records import EXACT_LATTICE, EXACT_PAPER_START, NLS_THEORIES, PAPER_NLS, SEMIDISCRETE_NLS

#: the labels of the three theories of a travelling wave (the records: ``_records``)
THEORIES = (PAPER_NLS.label, SEMIDISCRETE_NLS.label, EXACT_LATTICE.label)
#: the exact theory for the state eq. `IC` launches (not in THEORIES: it costs seconds)
PAPER_START = EXACT_PAPER_START.label
_NLS = {t.label: t.closed_forms() for t in NLS_THEORIES}


def _eps_A0(eps, A0, amplitude):
    """The paper's (eps, A0) from the public amplitude (peak rotation 2 eps A0, at the
    paper's eps), or as given (A0 defaults to 1)."""
    if amplitude is not None:
        if eps is not None or A0 is not None:
            raise ValueError("give amplitude (the peak rotation) or the paper's eps and A0, "
                             "not both")
        eps = EPS
        amplitude = checks.real("amplitude", amplitude, 0.0, MAX_AMPLITUDE, high_open=False)
        return eps, amplitude / (2 * eps)
    if eps is None:
        raise TypeError("give amplitude= (the peak rotation, rad) or eps (and A0)")
    return eps, 1.0 if A0 is None else A0


def nls_undefined(nls, material: Material, case: str, k: float) -> str | None:
    """Why an NLS model has no verdict at carrier k (None where it has one).

    - The continuum model's frequency omega^2 = alpha^2 (6 K_theta + delta k^2) (eq.
      `continuum2`) is negative for delta < 0 and k^2 > 6 K_theta / |delta|: no real carrier,
      the long-wave model does not reach that k (its g2 / g1 stays finite there, as the
      square roots cancel, but means nothing).
    - g1 = 0 (delta = 0 in the continuum model: no dispersion at this order), or singular.
    - g2 singular (the second harmonic resonates; case II: with U at 2k), or g2 = 0.

    ``nls`` is a theory's name ("paper NLS", "semi-discrete NLS") or its generated module.
    """
    if isinstance(nls, str):
        try:
            nls = _NLS[nls]
        except KeyError:
            raise ValueError(f"nls must be one of {tuple(_NLS)}, got {nls!r}") from None
    p = (k, material.alpha, material.K_s, material.K_theta)

    def evaluate(p):
        with np.errstate(over="raise", under="raise", divide="ignore", invalid="ignore"):
            return (float(nls.omega(*p)), float(nls.g1(*p)),
                    float(getattr(nls, f"g2_{case}")(*p)))

    try:  # an overflow or underflow is the arithmetic's limit, not the physics'
        omega, g1, g2 = evaluate(p)
    except FloatingPointError as exc:
        try:  # the same material at k = 1: whose fault it is decides the remedy
            evaluate((1.0,) + p[1:])
            remedy = "choose a larger k"
        except FloatingPointError:
            remedy = "rescale the material"
        return (f"an {str(exc).split()[0]} in float64 at k = {k:.4g}, alpha = "
                f"{material.alpha:g}, K_s = {material.K_s:g}, K_theta = {material.K_theta:g} "
                f"(not a resonance: the numbers leave float64's range); {remedy}")
    if not np.isfinite(omega):
        if nls is _NLS[PAPER_NLS.label]:
            return (f"no real carrier frequency: omega^2 = alpha^2 (6 K_theta + delta k^2) < 0 "
                    f"at k = {k:.4g} (eq. `continuum2`; the long-wave model does not reach it)")
        return f"no real carrier frequency at k = {k:.4g}"
    if g1 == 0:
        return ("g1 = 0: delta = 0, no dispersion at this order" if material.delta == 0
                else f"g1 = 0 at k = {k:.4g}: no dispersion at this order")
    if not np.isfinite(g1):
        return f"g1 is singular at k = {k:.4g} (omega = 0)"
    if not np.isfinite(g2):
        return (f"g2 is singular at k = {k:.4g}: the second harmonic resonates"
                + (" with U at 2k" if case == "coupled" else ""))
    if g2 == 0:
        return f"g2 = 0 at k = {k:.4g}: no cubic nonlinearity at this order"
    return None


def _g2_mean_flow(nls, case, p) -> float:
    """The mean flow's part of ``nls``'s g2 in ``case``: the semi-discrete NLS's in case II
    (``lattice_g2_mean_flow``), none in case I or in the paper's NLS (which omits it)."""
    if case != "coupled" or not hasattr(nls, "mean_flow_coefficient"):
        return 0.0
    from generated import soliton

    return float(soliton.lattice_g2_mean_flow(*p))


def nls_summary(material: Material, case: str, k: float, eps: float | None = None,
                A0: float | None = None, nls=_NLS[PAPER_NLS.label], *,
                amplitude: float | None = None) -> dict:
    """The NLS at one carrier: omega, v_g, g1, g2, g, verdict, and for g > 0 the band
    K_c, K_m (NLS units) and the peak lattice growth rate eps^2 |g1| Omega_I(K_m); the
    plane wave's nonlinear frequency shift Omega - omega = -eps^2 (g2 - g2_mf) A0^2
    (``frequency_shift``; g2_mf the mean flow's part, which a uniform wave does not feel:
    the exact wave's shift at small amplitude, as the model engine's). Where
    the model has no verdict (:func:`nls_undefined`) g is NaN, ``stable`` None and
    ``undefined`` says why.

    The plane wave is given by ``amplitude`` (its peak rotation, rad: the project's one
    convention, converted here to the paper's A0 at eps = 0.01), or by the paper's
    ``eps`` and ``A0`` (default 1)."""
    checks.instance("material", material, Material)
    check_case(case)
    k = checks.real("k", k, 0.0, np.pi)
    eps, A0 = _eps_A0(eps, A0, amplitude)
    eps = checks.positive("eps", eps)
    # the plane wave's peak rotation 2 eps A0 within the range the theories accept
    A0 = checks.real("A0", A0, 0.0, MAX_AMPLITUDE / (2 * eps), high_open=False)
    p = (k, material.alpha, material.K_s, material.K_theta)
    why = nls_undefined(nls, material, case, k)
    with np.errstate(all="ignore"):
        g = float(getattr(nls, f"g_{case}")(*p)) if why is None else float("nan")
        g1 = float(nls.g1(*p))
        g2 = float(getattr(nls, f"g2_{case}")(*p))
        out = {"g": g, "g1": g1, "g2": g2,
               # no verdict (None) where g is undefined: False read as "unstable"
               "stable": None if why is not None else bool(g < 0),
               "omega": float(nls.omega(*p)),
               "v_g": float(nls.group_velocity(*p)),
               # the plane wave's own nonlinear frequency shift Omega - omega (1/T), as the
               # model engine's (``ModelNLS.frequency_shift``): -eps^2 (g2 - g2_mf) A0^2,
               # the mean flow's part g2_mf left out (a uniform wave drives no mean strain;
               # the paper's NLS has none); the expansion holds while it is small against
               # omega (probe 100: +eps^2 g2 A0^2 had the other sign and, at the semi-
               # discrete NLS in case II, k 1, 4.2x the exact wave's shift)
               "frequency_shift": float(-eps**2 * (g2 - _g2_mean_flow(nls, case, p))
                                        * A0**2)}
    if why is not None:
        out["undefined"] = why
    if g > 0:
        K_m = nls.mi_fastest(g, A0)
        out.update(K_c=float(nls.mi_cutoff(g, A0)), K_m=float(K_m),
                   peak_gain=float(eps**2 * abs(g1) * nls.mi_growth_rate(K_m, g, A0)))
    return out


def theory_gain(theory: str, material: Material, case: str, k: float,
                amplitude: float | None = None, offset=None, *, eps: float | None = None,
                A0: float | None = None) -> np.ndarray:
    """sigma at sideband offsets ``offset`` from the carrier, by one theory (lattice units).

    The argument order of :func:`mi_gain` (material, case, k, amplitude, offset), the
    theory's name first.

    Parameters
    ----------
    theory : str
        One of ``THEORIES`` ("paper NLS", "semi-discrete NLS", "exact lattice") or
        ``PAPER_START``.
    material : Material
    case : {"rotation", "coupled"}
    k : float
        Carrier wavenumber, rad per site.
    amplitude : float
        Peak rotation of the plane wave, rad (2 eps A0, eq. `IC`). Or give the paper's
        ``eps`` and ``A0`` (keywords) instead.
    offset : array_like
        Sideband offsets q = |sideband - k|, rad per site.

    Returns
    -------
    ndarray, same shape as offset
        sigma (1/T); NaN where an NLS has no verdict at k (:func:`nls_undefined`).
    """
    if offset is None:
        raise TypeError("theory_gain needs offset= (the sideband offsets, rad per site)")
    checks.instance("material", material, Material)
    check_case(case)
    k = checks.real("k", k, 0.0, np.pi)
    q_offset = checks.finite_array("offset", offset)
    eps, A0 = _eps_A0(eps, A0, amplitude)
    if theory == "exact lattice":
        return mi_gain(material, case, k, 2 * eps * A0, q_offset)
    if theory == PAPER_START:
        # the carrier's third harmonic too: the fundamental alone read the peak 0.7% low at
        # amplitude 0.045 (1e-5 at 0.02); a fifth changes it by < 1e-5 there; 2x the cost
        return mi_gain(material, case, k, 2 * eps * A0, q_offset, harmonics=2, start="paper")
    try:
        nls = _NLS[theory]
    except KeyError:
        raise ValueError(f"theory must be one of {THEORIES + (PAPER_START,)}, got "
                         f"{theory!r}") from None
    p = (k, material.alpha, material.K_s, material.K_theta)
    if nls_undefined(nls, material, case, k) is not None:  # no verdict: NaN, not a rate
        return np.full(np.shape(q_offset), np.nan)
    eps = checks.positive("eps", eps)
    A0 = checks.real("A0", A0, 0.0, MAX_AMPLITUDE / (2 * eps), high_open=False)
    g = getattr(nls, f"g_{case}")(*p)
    return eps**2 * abs(nls.g1(*p)) * nls.mi_growth_rate(q_offset / eps, g, A0)


#: run length of a gain measurement: this many e-foldings of the predicted peak gain
#: (rounded to 100 T), within these bounds (the linear stage must be over, the run finite)
E_FOLDINGS, T_BOUNDS = 9.0, (1000.0, 20000.0)


def measurement_length(peak_gain: float, default: float = 5000.0) -> float:
    """How long to simulate to measure sigma(q) growing at ``peak_gain`` (1/T): E_FOLDINGS
    e-foldings, rounded to 100 T, clipped to T_BOUNDS; ``default`` where nothing grows."""
    if not peak_gain > 0:
        return float(default)
    return float(np.clip(round(E_FOLDINGS / peak_gain, -2), *T_BOUNDS))


def measure_gain(simulate, seeds, **params) -> dict | None:
    """Sideband growth rates sigma(q) from linear-stage fits, mean and spread over seeds.

    Parameters
    ----------
    simulate : callable
        ``simulate(**params)`` returning a :class:`Run` with ``store="spectrum"``
        (:func:`numerics.simulate`, or a cached version of it).
    seeds : iterable of int
        Noise seeds, one run each.
    **params
        Everything else the run needs (material, case, N, k, A0, t_end, ...).

    Returns
    -------
    dict or None
        ``q`` (N//2 + 1,), ``k`` (snapped), ``N``, ``sigma`` and ``sigma_std`` (N//2 + 1,),
        the fit ``windows`` (T0, T1) per seed and the number of ``seeds`` that reached a
        linear stage; None when no run did (a stable run).
    """
    rates, windows, run = [], [], None
    for seed in seeds:
        run = simulate(**dict(params, seed=seed, store="spectrum"))
        win = linear_stage(run.theta_hat, run.m, run.N)
        if win is None:
            continue
        rates.append(growth_rates(run.t, run.theta_hat, win))
        windows.append((float(run.t[win[0]]), float(run.t[win[1]])))
    if not rates:
        return None
    rates = np.array(rates)
    spread = rates.std(axis=0, ddof=1) if len(rates) > 1 else np.zeros(rates.shape[1])
    return {"q": run.wavenumbers, "k": run.k, "N": run.N, "sigma": rates.mean(axis=0),
            "sigma_std": spread, "windows": windows, "seeds": len(rates)}


def relative_errors(measured: dict, predicted: dict) -> dict:
    """measured / predicted - 1 of the peak gain and the half-gain band edge (None where
    the theory predicts no gain, or has no edge); inputs from :func:`band_summary`."""
    if not predicted["peak_gain"]:
        return {"peak_error": None, "edge_error": None}
    edge = predicted["band_edge"]
    return {"peak_error": measured["peak_gain"] / predicted["peak_gain"] - 1,
            "edge_error": measured["band_edge"] / edge - 1 if np.isfinite(edge) else None}
