"""Units for any model (``--time-unit SECONDS --length-unit METRES``): a model's numbers are
in its lattice units (time as its file sets it, wavenumbers in rad per site); given the
seconds per unit of lattice time and the lattice spacing in metres, rates are also given in
1/s, wavenumbers in rad/m, times in s, as the paper chain's ``--physical`` gives them (the
formatting is ``cli.coefficients.Units``'s)."""

from __future__ import annotations

import math
from dataclasses import dataclass

from .coefficients import Units

#: what each kind of number is in: (lattice unit, SI unit)
KINDS = {"rate": ("1/time", "1/s"), "time": ("time", "s"),
         "wavenumber": ("rad/site", "rad/m"), "velocity": ("site/time", "m/s"),
         "length": ("site", "m"),
         # the NLS's coefficients: g1 = d^2 omega/dk^2; g2 multiplies |a|^2, a in the
         # carrier field's own unit (length or angle: the model's), never converted
         "dispersion": ("site^2/time", "m^2/s"),
         "nonlinearity": ("1/(time amplitude^2)", "1/(s amplitude^2)")}

#: the keys of the commands' JSON whose numbers carry a unit, by kind (every other number
#: is a ratio or a count; g = g2/g1 and g2's parts are in g2's units over g1's)
KEYS = {
    "rate": ("peak_gain", "ring_peak_gain", "modulational_gain", "carrier_damping", "omega",
             "omega_linear", "frequency_shift", "frequency", "slowest_visible_rate",
             "net_gain"),
    "time": ("e_folding_time", "amplification_time", "t_end"),
    "wavenumber": ("k", "k_requested", "fastest_offset", "band_edge", "wavenumber"),
    "velocity": ("group_velocity", "velocity"),
    "length": ("width",),
    "dispersion": ("g1",),
    "nonlinearity": ("g2",),
}
_KIND_OF = {key: kind for kind, keys in KEYS.items() for key in keys}


@dataclass(frozen=True)
class ModelUnits(Units):
    """A model's lattice units and, from --time-unit and --length-unit, their SI values."""

    time_name: str = "time"

    def describe(self) -> str:
        lattice = "lattice units: time as in the model file, wavenumber rad/site"
        si = []
        if self.seconds_per_T:
            si.append(f"1 time unit = {self.seconds_per_T:.4g} s (--time-unit)")
        if self.metres_per_site:
            si.append(f"1 site = {self.metres_per_site:.4g} m (--length-unit)")
        return lattice + ("; SI: " + ", ".join(si) if si else "")

    def factor(self, kind: str) -> float | None:
        """What a number of ``kind`` in lattice units is multiplied by to be in SI (None
        where the unit it needs was not given)."""
        t, a = self.seconds_per_T, self.metres_per_site
        return {"rate": 1 / t if t else None, "time": t,
                "wavenumber": 1 / a if a else None,
                "velocity": a / t if a and t else None, "length": a,
                "dispersion": a * a / t if a and t else None,
                "nonlinearity": 1 / t if t else None}[kind]

    def si(self, x: float | None, kind: str) -> str:
        """`` = VALUE UNIT`` of a lattice number in SI ('' where not given, or not finite)."""
        f = self.factor(kind)
        if f is None or x is None or not math.isfinite(x * f):
            return ""
        return f" = {x * f:.4g} {KINDS[kind][1]}"

    def json(self, obj: dict) -> tuple[dict, dict | None]:
        """(the "units" object, the "si" object) of a command's JSON ``obj``: the factors,
        each key's unit in lattice units and in SI; ``si`` the numbers of ``obj`` that have
        a unit, in SI (None where neither unit was given)."""
        found = {}

        def walk(o):
            out = {}
            for key, v in o.items():
                if isinstance(v, dict) and key not in ("parameters", "curves"):
                    sub = walk(v)
                    if sub:
                        out[key] = sub
                elif key in _KIND_OF and isinstance(v, (int, float)) \
                        and not isinstance(v, bool):
                    kind = _KIND_OF[key]
                    found[key] = kind
                    f = self.factor(kind)
                    if f is not None and math.isfinite(v * f):
                        out[key] = v * f
            return out

        si = walk(obj)
        units = {"time_unit_s": self.seconds_per_T, "length_unit_m": self.metres_per_site,
                 "lattice": {k: KINDS[kind][0] for k, kind in found.items()},
                 "si": {k: KINDS[kind][1] for k, kind in found.items()
                        if self.factor(kind) is not None}}
        return units, (si if self.seconds_per_T or self.metres_per_site else None)


def model_units(args) -> ModelUnits:
    """The units of --time-unit and --length-unit (each optional; checked: finite, > 0)."""
    from numerics.lattice import checks

    t, a = getattr(args, "time_unit", None), getattr(args, "length_unit", None)
    if t is not None:
        checks.positive("--time-unit", t)
    if a is not None:
        checks.positive("--length-unit", a)
    units = ModelUnits(t, a)
    # probe 99: --time-unit 5e-324 printed "omega = inf 1/s" and "peak gain 0 = nan 1/s"
    for kind, (_, si) in KINDS.items():
        f = units.factor(kind)
        if f is not None and not (math.isfinite(f) and f > 0):
            given = " and ".join(f"{o} {v:g}" for o, v in (("--time-unit", t),
                                                             ("--length-unit", a)) if v)
            raise ValueError(f"{given} put the SI values past float64's range (1 "
                             f"{KINDS[kind][0]} = {f:g} {si}); give units between 1e-150 "
                             f"and 1e150")
    return units


def add_units(out: dict, units: ModelUnits) -> dict:
    """``out`` with its "units" object (and "si" where a unit was given), last."""
    u, si = units.json(out)
    out["units"] = u
    if si is not None:
        out["si"] = si
    return out
