"""`flexmm coefficients`: the NLS coefficients and the MI band of any material at any k,
as a table (the numbers: ``numerics.theory.nls_coefficients``; instant, no simulation)."""

from __future__ import annotations

import math
from dataclasses import dataclass

from common import paper
from numerics import Material
from numerics.theory import nls_coefficients as coefficients  # the table's numbers


@dataclass(frozen=True)
class Units:
    """Lattice units and, from ``--physical``, their SI values: T = t sqrt(k_l / m)."""

    seconds_per_T: float | None = None  # sqrt(m / k_l)
    metres_per_site: float | None = None  # a
    #: the lattice time's name in the printed units ("T" for the paper chain, "time" for a
    #: model, whose file sets its time unit: cli/units.py)
    time_name: str = "T"

    @classmethod
    def physical(cls, m, k_l, a) -> Units:
        return cls(math.sqrt(m / k_l), a)

    def rate(self, sigma: float) -> str:
        """A growth rate in 1/T, and in 1/s with its e-folding time."""
        s = f"{sigma:.4g} 1/{self.time_name}"
        if self.seconds_per_T and math.isfinite(sigma):
            s += f" = {sigma / self.seconds_per_T:.4g} 1/s"
        return s

    def time(self, T: float) -> str:
        s = f"{T:.4g} {self.time_name}"
        if self.seconds_per_T and math.isfinite(T):
            s += f" = {T * self.seconds_per_T:.4g} s"
        return s

    def hertz(self, omega: float) -> float | None:
        """An angular frequency in 1/T as a frequency in Hz, omega / (2 pi) per second (what
        a shaker or a spectrum analyser reads; None without a time unit)."""
        if not self.seconds_per_T or not math.isfinite(omega):
            return None
        return omega / (2 * math.pi * self.seconds_per_T)

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


#: the NLS is a weakly nonlinear expansion: past this ratio of the plane wave's own
#: frequency shift eps^2 |g2 - g2_mf| A0^2 (``nls_summary``'s, the mean flow's part left
#: out: the exact wave's) to omega its verdicts and bands are not to be trusted
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
            f"(eps^2 |g2 - g2_mf| A0^2, the mean flow's part g2_mf left out) is {ratio:.0%} "
            "of omega: beyond the weakly nonlinear "
            f"expansion the NLS rests on; ask the exact lattice theory ({remedy})")


def wide_band_note(co: dict, amplitude: float, cases=("rotation", "coupled"),
                   eps: float = paper.EPS) -> str | None:
    """A warning line where an NLS's MI band |q - k| < eps K_c reaches past pi/2 (as a
    model's ``coefficients`` says): the envelope expansion does not hold that far from the
    carrier, and past pi its gain curve (offsets up to pi) peaks at the grid's end
    (newuser99: amplitude 0.5 at alpha 2, K_s 0.03, K_theta 0.02, k 1 read 'fastest growth
    offset 3.142, sidebands at 2.136 and 2.136', a band 6.5 rad/site wide)."""
    wide = [(n, case, eps * c[case]["K_c"]) for n, c in co.items() for case in cases
            if c[case]["verdict"] == "MI" and math.isfinite(c[case]["K_c"])
            and eps * c[case]["K_c"] > math.pi / 2]
    if not wide:
        return None
    which = ", ".join(f"{n} case {'I' if case == 'rotation' else 'II'} to {edge:.3g}"
                      for n, case, edge in wide)
    return (f"warning: at amplitude {amplitude:g} the NLS's MI band reaches offset |q - k| "
            f"beyond pi/2 rad/site ({which}): the envelope's long-wave expansion does not "
            "hold that far from the carrier, and its peak offset is no wavenumber the "
            "lattice selects; lower the amplitude, or trust the exact lattice theory")


def _number(x: float, spec: str) -> str:
    """A table cell: '-' where the number is undefined (nan, inf), as every other
    undefined cell of the table."""
    return format(x, spec) if math.isfinite(x) else "-"


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
        table.append([label] + [_number(co[n][key], ".6g") for n in names])
        if key == "omega" and units.seconds_per_T:  # newuser 102: a shaker's f, not omega
            table.append(["f = omega/2pi (Hz)"]
                         + [_number(units.hertz(co[n]["omega"]) or math.nan, ".6g")
                            for n in names])
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
                else:  # g = g2/g1 at g1 = 0 (delta = 0): undefined, said below the table
                    cells.append(_number(r[key], ".6g"))
            table.append([label] + cells)
    table.append(["u2: |c| (eq. u1)"] + [_number(co[n]['u2 |c|'], ".6g") for n in names])
    table.append(["U at 2k = |c| amp^2/2"] + [_number(co[n]['U at 2k'], ".4g") for n in names])
    widths = [max(len(r[i]) for r in table) for i in range(len(table[0]))]
    for j, r in enumerate(table):
        lines.append("  ".join(c.ljust(w) if i == 0 else c.rjust(w)
                               for i, (c, w) in enumerate(zip(r, widths))).rstrip())
        if j == 0:
            lines.append("  ".join("-" * w for w in widths))
    for note in (weak_nonlinearity_note(co, amplitude), wide_band_note(co, amplitude, eps=eps)):
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
