"""The NLS coefficients and the MI band of any material at any k, for both NLS theories
(``flexmm coefficients``, ``flexmm point``'s header and the tutorial print them).

Instant: the generated closed forms only (``generated.coefficients``, the paper's continuum
NLS, and ``generated.lattice_coefficients``, the semi-discrete NLS), no SymPy, no
simulation. Both cases: (I) "rotation" (U = 0) and (II) "coupled".
"""

from __future__ import annotations

import math

import numpy as np

from common import paper

from ..lattice import Material, checks
from ._gain import nls_summary
from ._plane_wave import MAX_AMPLITUDE
from ._records import NLS_THEORIES

#: {the table's column: the generated module} of each NLS theory (``Theory.column``)
MODELS = {t.column: t.closed_forms() for t in NLS_THEORIES}


def nls_coefficients(material: Material, k: float, amplitude: float = paper.AMPLITUDE,
                 eps: float = paper.EPS) -> dict:
    """``{model: {quantity: value}}`` for both NLS models at carrier k.

    Quantities: omega (eq. `continuum2` / `discrete2`), v_g = d omega / dk, g1 (eq. `g_i`),
    and per case g2, g = g2 / g1, the band K_c, K_m (NLS units, eq. `kc`; offsets
    eps K in rad per site) and the peak lattice gain eps^2 |g1| Omega_I(K_m); and |c| of
    u2 = c B^2 e^{2 i sigma} + c.c. (eq. `u1`) with the forced U amplitude at 2k, |c| amp^2/2
    (amp the peak rotation).
    The plane wave's peak rotation ``amplitude`` is the paper's 2 eps A0.
    """
    checks.instance("material", material, Material)
    k = checks.real("k", k, 0.0, math.pi)
    amplitude = checks.real("amplitude", amplitude, 0.0, MAX_AMPLITUDE)
    A0 = amplitude / (2 * eps)
    p = (k, material.alpha, material.K_s, material.K_theta)
    out = {}
    for name, nls in MODELS.items():
        with np.errstate(all="ignore"):
            # omega, v_g, g1, g2, g, the band and the peak gain: nls_summary, their one home
            per_case = {case: nls_summary(material, case, k, eps, A0, nls=nls)
                        for case in ("rotation", "coupled")}
            c = complex(nls.u2_coefficient(*p))
        first = per_case["rotation"]
        shift = max(abs(pc["frequency_shift"]) for pc in per_case.values())
        if not math.isfinite(first["omega"]):  # no real carrier: no harmonic either
            c = complex("nan")
        row = {"omega": first["omega"], "v_g": first["v_g"], "g1": first["g1"],
               "shift_over_omega": shift / first["omega"] if first["omega"] else float("nan"),
               "u2 |c|": abs(c), "U at 2k": abs(c) * amplitude**2 / 2}
        for case, s in per_case.items():
            g = s["g"]
            why = s.get("undefined") or (None if math.isfinite(g) and g != 0
                                         else f"g = {g:.4g}")
            verdict = "undefined" if why else "MI" if g > 0 else "stable"
            row[case] = {"g2": s["g2"], "g": g, "verdict": verdict,
                         "K_c": s.get("K_c", float("nan")), "K_m": s.get("K_m", float("nan")),
                         # no verdict, no gain: NaN (shown "-"), never a stable 0
                         "peak_gain": float("nan") if why else s.get("peak_gain", 0.0)}
            if why:
                row[case]["undefined"] = why
        out[name] = row
    return out


__all__ = ["MODELS", "nls_coefficients"]
