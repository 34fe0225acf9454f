"""`flexmm coefficients`: the NLS coefficients and the MI band of any material at any k.

Instant: the generated closed forms only (``generated.coefficients``, the paper's continuum
NLS, and ``generated.lattice_coefficients``, the semi-discrete NLS), no SymPy, no
simulation. Both cases: (I) "rotation" (U = 0) and (II) "coupled".
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from common import paper
from generated import coefficients as continuum
from generated import lattice_coefficients as semidiscrete
from numerics import Material
from numerics.lattice import checks
from numerics.theory import nls_summary

MODELS = {"continuum (paper)": continuum, "semi-discrete": semidiscrete}


@dataclass(frozen=True)
class Units:
    """Lattice units and, from ``--physical``, their SI values: T = t sqrt(k_l / m)."""

    seconds_per_T: float | None = None  # sqrt(m / k_l)
    metres_per_site: float | None = None  # a

    @classmethod
    def physical(cls, m, k_l, a) -> "Units":
        return cls(math.sqrt(m / k_l), a)

    def rate(self, sigma: float) -> str:
        """A growth rate in 1/T, and in 1/s with its e-folding time."""
        s = f"{sigma:.4g} 1/T"
        if self.seconds_per_T and math.isfinite(sigma):
            s += f" = {sigma / self.seconds_per_T:.4g} 1/s"
        return s

    def time(self, T: float) -> str:
        s = f"{T:.4g} T"
        if self.seconds_per_T and math.isfinite(T):
            s += f" = {T * self.seconds_per_T:.4g} s"
        return s

    def wavenumber(self, k: float) -> str:
        s = f"{k:.5g} rad/site"
        if self.metres_per_site and math.isfinite(k):
            s += f" = {k / self.metres_per_site:.4g} rad/m"
        return s

    def describe(self) -> str:
        if not self.seconds_per_T:
            return ("lattice units: time T = t sqrt(k_l/m), wavenumber in rad per site, "
                    "rotation in rad")
        return (f"lattice units, and SI from --physical: 1 T = sqrt(m/k_l) = "
                f"{self.seconds_per_T:.4g} s, 1 site = a = {self.metres_per_site:.4g} m")


def coefficients(material: Material, k: float, amplitude: float = paper.AMPLITUDE,
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
    amplitude = checks.real("amplitude", amplitude, 0.0, 1.5)
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


#: the NLS is a weakly nonlinear expansion: past this ratio of the plane wave's own
#: frequency shift eps^2 |g2| A0^2 to omega its verdicts and bands are not to be trusted
WEAK_NONLINEARITY = 0.1


def weak_nonlinearity_note(co: dict, amplitude: float,
                           remedy: str = "flexmm point") -> str | None:
    """A warning line where either NLS's own frequency shift (``coefficients``' ``co``)
    exceeds WEAK_NONLINEARITY of omega (None below); ``remedy`` says where the exact
    lattice theory is."""
    ratio = max((c["shift_over_omega"] for c in co.values()
                 if math.isfinite(c["shift_over_omega"])), default=0.0)
    if not ratio > WEAK_NONLINEARITY:
        return None
    return (f"warning: at amplitude {amplitude:g} the plane wave's own frequency shift "
            f"(eps^2 |g2| A0^2) is {ratio:.0%} of omega: beyond the weakly nonlinear "
            f"expansion the NLS rests on; ask the exact lattice theory ({remedy})")


def format_coefficients(material: Material, k: float, amplitude: float, units: Units = Units(),
                        k_requested: float | None = None, eps: float = paper.EPS) -> str:
    """The table `flexmm coefficients` prints: inputs echoed, both models side by side."""
    co = coefficients(material, k, amplitude, eps)
    names = list(co)
    A0 = amplitude / (2 * eps)
    lines = [f"material: alpha = {material.alpha:g}, K_s = {material.K_s:g}, K_theta = "
             f"{material.K_theta:g} (delta = K_s - K_theta = {material.delta:.4g})",
             f"carrier:  k = {units.wavenumber(k)}"
             + (f" (asked {k_requested:g})" if k_requested not in (None, k) else "")
             + f", amplitude = {amplitude:g} rad (peak rotation = 2 eps A0, eps = {eps:g}, "
             f"A0 = {A0:.4g})",
             f"units:    {units.describe()}", ""]
    rows = [("omega (1/T)", "omega"), ("v_g (site/T)", "v_g"), ("g1", "g1")]
    table = [["quantity"] + names]
    for label, key in rows:
        table.append([label] + [f"{co[n][key]:.6g}" for n in names])
    for case, roman in (("rotation", "I"), ("coupled", "II")):
        table.append([f"case {roman} ({case})"] + [""] * len(names))
        for label, key in (("  g2", "g2"), ("  g = g2/g1", "g"), ("  verdict", "verdict"),
                           ("  K_c (NLS units)", "K_c"), ("  K_m (NLS units)", "K_m"),
                           ("  band |q - k| < eps K_c", "K_c*"),
                           ("  peak gain (1/T)", "peak_gain"),
                           ("  e-folding time (T)", "t_e")):
            cells = []
            for n in names:
                r = co[n][case]
                if key == "verdict":
                    cells.append(r["verdict"])
                elif key == "K_c*":
                    cells.append(f"{eps * r['K_c']:.4g} rad/site" if r["verdict"] == "MI"
                                 else "-")
                elif key == "t_e":
                    cells.append(f"{1 / r['peak_gain']:.4g}" if r["peak_gain"] > 0 else "-")
                elif key in ("K_c", "K_m") and r["verdict"] != "MI":
                    cells.append("-")
                elif key == "peak_gain" and r["verdict"] == "undefined":
                    cells.append("-")
                else:
                    cells.append(f"{r[key]:.6g}")
            table.append([label] + cells)
    table.append(["u2: |c| (eq. u1)"] + [f"{co[n]['u2 |c|']:.6g}" for n in names])
    table.append(["U at 2k = |c| amp^2/2"] + [f"{co[n]['U at 2k']:.4g}" for n in names])
    widths = [max(len(r[i]) for r in table) for i in range(len(table[0]))]
    for j, r in enumerate(table):
        lines.append("  ".join(c.ljust(w) if i == 0 else c.rjust(w)
                               for i, (c, w) in enumerate(zip(r, widths))).rstrip())
        if j == 0:
            lines.append("  ".join("-" * w for w in widths))
    note = weak_nonlinearity_note(co, amplitude)
    if note:
        lines.append(note)
    for n in names:
        for case, roman in (("rotation", "I"), ("coupled", "II")):
            if "undefined" in co[n][case]:
                lines.append(f"{n}, case {roman}: undefined: {co[n][case]['undefined']}")
    if units.seconds_per_T:
        lines.append("")
        for case in ("rotation", "coupled"):
            g = co["semi-discrete"][case]["peak_gain"]
            if g > 0:
                lines.append(f"case {case}: semi-discrete peak gain {units.rate(g)}, "
                             f"e-folding time {units.time(1 / g)}")
    return "\n".join(lines)
