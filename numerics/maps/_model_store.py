"""What a model map's store holds beyond its cells, split from ``_model_params``: the
empty store a map starts from (``ModelMapParameters.new_dataset``) and what a store of
another map holds (``ModelMapParameters.other_map``: the refusal to continue it). Each
takes the map's ``ModelMapParameters``.
"""

from __future__ import annotations

import numpy as np

from ._columns import MODEL_STORE_FORMAT, UNDETERMINED
from ._model_columns import (
    MODE_KIND_ATTRS,
    MODE_KIND_CODES,
    MODEL_VERDICT_ATTRS,
    NO_WAVE_ATTRS,
    OBSERVABLE_ATTRS,
    VARIABLE_ATTRS,
    simulated_verdict_attrs,
)


def other_map(params, attrs: dict) -> str:
    """What a store of another map holds: another model's, this model's before its
    energy changed, or this model's with other parameters."""
    if attrs.get("map_of") != "model" or attrs.get("model") is None:
        return "a map of the paper flags (or of an older format)"
    name = params.lattice_model.name
    if attrs.get("model") != name:
        return f"a map of model {attrs['model']!r}, not {name!r}"
    mine = params.lattice_model.lattice.content_hash
    if attrs.get("model_hash") != mine:
        return (f"a map of model {name!r} whose energy differs from this one's "
                f"(content hash {str(attrs.get('model_hash'))[:12]} against "
                f"{mine[:12]}: the model file changed)")
    if attrs.get("start", "exact") != params.start:
        return (f"a map of model {name!r} whose runs start from "
                f"{attrs.get('start', 'exact')!r}, not {params.start!r}")
    if attrs.get("no_wave") != params.attrs()["no_wave"]:
        return (f"a map of model {name!r} made before its no_wave column (its cells where "
                "the model carries no wave of the amplitude may hold an NLS verdict of a "
                "wave that does not exist)")
    stored, asked = str(attrs.get("theories")).split(), params.theory_columns()
    if set(stored) > set(asked):  # a simulated or --exact store asked without them
        return (f"a map of model {name!r} of more theories than this one asks "
                f"({' '.join(stored)} stored, {' '.join(asked)} asked: a simulated map's, "
                "or --theory-only --exact's; give its --exact, or leave out --theory-only, "
                "to continue it, or open it with xarray as it is)")
    if attrs.get("theories") != " ".join(params.theory_columns()):
        return (f"a map of model {name!r} of other theories ({attrs.get('theories')} "
                f"against {' '.join(params.theory_columns())}; a --theory-only map without "
                "--exact has no exact columns to continue, a store made before the "
                "four-wave columns none of those)")
    mine = params.attrs()
    if any(attrs.get(n, "") != mine.get(n, "") for n in ("amplification",
                                                        "amplification_time",
                                                        "amplification_runs")):
        return (f"a map of lossy model {name!r} made before its amplification columns "
                f"(amplification_<theory> and amplification_time_<theory> of "
                f"{' '.join(params.amplified())}"
                + (", and the runs' amplification_simulated" if params.ring else "")
                + ")")
    for unit in ("time_unit_s", "length_unit_m"):
        mine = getattr(params, unit)
        if mine is not None and attrs.get(unit) != mine:
            return (f"a map of model {name!r} with {unit} = {attrs.get(unit) or 'none'} "
                    f"(asked {mine:g}: the stored numbers are in lattice units either "
                    "way)")
    mine = params.identity()  # name what differs (the store's value, then this map's)

    def said(n):  # a fixed parameter by its own name, as --param gives it
        return n[len("param_"):] if n.startswith("param_") else n

    differ = [f"{said(n)} {attrs[n]!r} stored, {mine[n]!r} asked"
              + (": omit --block to continue with the store's" if n == "block" else "")
              for n in sorted(mine) if n in attrs and attrs[n] != mine[n]]
    differ += [f"{said(n)} {attrs[n]!r} stored, none asked" for n in sorted(attrs)
               if n.startswith("param_") and n not in mine]
    differ += [f"{said(n)} none stored, {mine[n]!r} asked" for n in sorted(mine)
               if n.startswith("param_") and n not in attrs]
    return (f"a map of model {name!r} with other parameters"
            + (f" ({'; '.join(differ[:4])})" if differ else ""))


def new_dataset(params):
    """The store before any task: every variable at its fill value, ``done`` False."""
    import xarray as xr

    from ._integrity import CHECKSUM, CHECKSUM_ATTRS, cell_checksums

    shape = params.grid_shape
    dims = params.dims
    data = {}
    flags = params.flag_columns()
    for name in (*flags["done_predicted"], *flags["done"]):
        if name in ("observable_simulated", "no_wave"):
            data[name] = (dims, np.full(shape, -1, np.int8), dict(
                OBSERVABLE_ATTRS if name == "observable_simulated" else NO_WAVE_ATTRS))
        elif name == "mode_kind_fourwave":
            data[name] = (dims, np.full(shape, MODE_KIND_CODES["undefined"], np.int8),
                          dict(MODE_KIND_ATTRS))
        elif name.startswith("verdict_"):
            theory = name.removeprefix("verdict_")
            attrs = {"long_name": f"{theory} theory's verdict", **MODEL_VERDICT_ATTRS}
            if theory == "simulated":
                attrs.update(simulated_verdict_attrs(params.theory_only))
            data[name] = (dims, np.full(shape, UNDETERMINED, np.int8), attrs)
        else:
            data[name] = (dims, np.full(shape, np.nan), dict(VARIABLE_ATTRS.get(name, {})))
    data["done"] = (dims, np.zeros(shape, bool), {"long_name": "cell simulated"})
    data["done_predicted"] = (dims, np.zeros(shape, bool),
                              {"long_name": "cell's theories computed"})
    data[CHECKSUM] = (dims, cell_checksums({n: v[1] for n, v in data.items()}),
                      CHECKSUM_ATTRS)
    from ._model_axes import axis_attrs

    coords = {n: (n, np.asarray(v), axis_attrs(n)) for n, v in params.store_coords().items()}
    return xr.Dataset(data, coords=coords, attrs={**params.attrs(),
                                                   "store_format": MODEL_STORE_FORMAT})
