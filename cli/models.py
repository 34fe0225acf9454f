"""The commands for any lattice model (``--model NAME|FILE.toml``): models, coefficients,
point, map and soliton. They parse, call ``numerics.models`` and print; what they compute
lives there."""

from __future__ import annotations

import json
import math
from pathlib import Path

#: The paper chain's flags, which mean nothing for another model.
PAPER_FLAGS = ("alpha", "K_s", "K_theta", "physical", "case", "delta")


def add_model_args(p, json_help="print one JSON object on stdout and nothing else there"):
    """--model, --param, --branch, --json (shared by coefficients, point, map, soliton)."""
    g = p.add_argument_group("any lattice model (instead of the paper chain's flags)")
    g.add_argument("--model", metavar="NAME|FILE.toml",
                   help="a built-in model (`flexmm models`) or a model file (docs/models.md)")
    g.add_argument("--param", action="append", default=[], metavar="NAME=VALUE",
                   help="a parameter of the model (repeatable); the others keep their "
                        "defaults")
    g.add_argument("--branch", default=None, metavar="INDEX|FIELD",
                   help="dispersion branch: index (0 = lowest frequency at k) or the field "
                        "that dominates it (default: the model's branch field, else 0; for "
                        "flexmm the rotational branch theta)")
    g.add_argument("--json", action="store_true", help=json_help)


def wants_model(args) -> bool:
    return getattr(args, "model", None) is not None


def refuse_paper_flags(args):
    given = [f for f in PAPER_FLAGS if getattr(args, f, None) not in (None, False)]
    if given:
        flags = ", ".join("--" + f.replace("_", "-") for f in given)
        raise ValueError(f"{flags}: the paper chain's flags; with --model give the model's "
                         "parameters as --param NAME=VALUE")


def params_of(args, axes_ok=False) -> tuple:
    """(fixed values, swept axes) from the --param options."""
    fixed, axes = {}, {}
    for item in args.param:
        if "=" not in item:
            raise ValueError(f"--param {item!r}: give NAME=VALUE")
        name, text = (s.strip() for s in item.split("=", 1))
        if not name:
            raise ValueError(f"--param {item!r}: the NAME is empty")
        if name in fixed or name in axes:
            raise ValueError(f"--param {name} given twice")
        if axes_ok and (":" in text or "," in text):
            from numerics.maps import parse_spec

            axes[name] = parse_spec(text, f"--param {name}")
            continue
        try:
            fixed[name] = float(text)
        except ValueError:
            raise ValueError(f"--param {name}={text!r}: the value must be a number"
                             + (" (a range start:stop:num is a map axis; only `map` sweeps)"
                                if ":" in text or "," in text else "")) from None
    return fixed, axes


def load(args, axes_ok=False):
    """The model with its --param values (and the swept axes for a map)."""
    from energy import load_model

    refuse_paper_flags(args)
    fixed, axes = params_of(args, axes_ok)
    model = load_model(args.model, **fixed)
    for name in axes:
        model.lattice.values({name: 0.0})  # an unknown axis name: the model's one-line error
    from numerics.models import check_rest_stable

    if not axes:
        check_rest_stable(model)
    return (model, axes) if axes_ok else model


def branch_of(args):
    b = getattr(args, "branch", None)
    return int(b) if isinstance(b, str) and b.isdigit() else b


def _emit(obj: dict):
    print(json.dumps(obj, allow_nan=False, default=_plain))


def _plain(x):
    import numpy as np

    if isinstance(x, np.generic):
        return x.item()
    raise TypeError(f"not JSON: {type(x).__name__}")


# ------------------------------------------------------------------ flexmm models
def run_models(args) -> int:
    """List the built-in models: fields, parameters with defaults, one line each."""
    from energy import BUILTIN, builtin

    rows = [builtin(n) for n in BUILTIN]
    if getattr(args, "json", False):
        _emit({"models": [{"name": m.name, "fields": list(m.fields),
                           "parameters": dict(m.parameters), "description": m.description,
                           "branch": m.branch} for m in rows]})
        return 0
    width = max(len(m.name) for m in rows)
    for m in rows:
        params = ", ".join(f"{p}={v:g}" for p, v in m.parameters.items())
        print(f"{m.name:<{width}}  fields {', '.join(m.fields):<9}  {params}")
        print(f"{'':<{width}}  {m.description}")
    print("give one with --model NAME (or --model FILE.toml for your own, docs/models.md); "
          "parameters with --param NAME=VALUE")
    return 0


# ------------------------------------------------------------------ coefficients
def _fmt(x, digits=6):
    if x is None:
        return "-"
    return f"{x:.{digits}g}"


def run_coefficients(args) -> int:
    from numerics.lattice import checks
    from numerics.models import model_coefficients

    model = load(args)
    checks.real("--k", args.k, 0.0, math.pi)
    checks.real("--amplitude", args.amplitude, 0.0, None)
    co = model_coefficients(model, args.k, args.amplitude, branch_of(args))
    if args.json:
        _emit(co)
        return 0
    print(f"model:    {model.describe()}")
    print(f"carrier:  k = {_fmt(co['k'])} rad/site on branch {co['branch']} (field "
          f"{co['field']}), amplitude a = {_fmt(co['amplitude'])} ({co['field']} = a cos(k n - "
          "omega t) + harmonics + mean)")
    parts = co["g2_parts"]
    rows = [("omega", co["omega"]), ("group velocity", co["group_velocity"]),
            ("g1 = d^2 omega/dk^2", co["g1"]), ("g2", co["g2"])]
    rows += [(f"  of which {p}", v) for p, v in parts.items()]
    rows += [("g = g2/g1", co["g"])]
    for name, v in rows:
        print(f"{name:<26} {_fmt(v):>14}")
    verdict = co["verdict"]
    if verdict != "undefined":
        verdict += " (focusing)" if verdict == "MI" else " (defocusing)"
    print(f"{'verdict (semi-discrete NLS)':<26} {verdict:>14}")
    for name, key in (("peak gain (1/time)", "peak_gain"), ("e-folding time", "e_folding_time"),
                      ("fastest offset (rad/site)", "fastest_offset"),
                      ("band edge (rad/site)", "band_edge"),
                      ("frequency shift", "frequency_shift")):
        print(f"{name:<26} {_fmt(co[key]):>14}")
    for f in model.fields:
        print(f"{f + ': 2k harmonic, mean':<26} {_fmt(co['second_harmonic'][f]):>14} "
              f"{_fmt(co['mean'][f]):>12}  (mean strain {_fmt(co['mean_strain'][f])})")
    if co["reason"]:
        print(f"undefined: {co['reason']}")
    for w in co["warnings"]:
        print(f"note: {w}")
    return 0


# ------------------------------------------------------------------ soliton
def run_soliton(args) -> int:
    from numerics.lattice import checks
    from numerics.models import nls

    model = load(args)
    checks.real("--k", args.k, 0.0, math.pi)
    checks.real("--amplitude", args.amplitude, 0.0, None)
    if getattr(args, "simulate", False):
        raise ValueError("--simulate: soliton runs are for the paper chain (no --model) for "
                         "now; the prediction below is the model's NLS soliton")
    r = nls(model, args.k, branch_of(args))
    kind = getattr(args, "kind", None)
    if r.undefined:
        raise ValueError(f"no soliton at k = {args.k:g}: {r.undefined}")
    s = r.soliton(args.amplitude)
    if kind is not None and kind != s.kind:
        raise ValueError(f"--kind {kind}: the NLS at k = {args.k:g} has g = {r.g:.4g} "
                         f"({'> 0' if r.g > 0 else '< 0'}), so only {s.kind} solitons")
    out = {"model": model.name, "parameters": dict(model.params), "k": float(args.k),
           "branch": r.carrier.branch, "kind": s.kind, "amplitude": s.amplitude,
           "width": s.width, "velocity": s.velocity, "frequency": s.frequency,
           "kink": {f: float(v) for f, v in zip(model.fields, s.kink)},
           "g1": r.g1, "g2": r.g2}
    if args.json:
        _emit(out)
        return 0
    print(f"model:    {model.describe()}")
    print(f"carrier:  k = {args.k:g} rad/site on branch {r.carrier.branch}, omega = "
          f"{r.carrier.omega:.6g}; g1 = {r.g1:.6g}, g2 = {r.g2:.6g}")
    print(f"{s.kind} soliton, amplitude {s.amplitude:g}: width {s.width:.4g} sites, velocity "
          f"{s.velocity:.4g} sites/time, frequency {s.frequency:.6g}")
    for f, v in zip(model.fields, s.kink):
        if v != 0:
            print(f"kink of {f}: {v:.4g} (step of its mean displacement across the soliton)")
    if s.width < 8:
        print(f"note: {s.width:.3g} sites is too narrow for the envelope theory; lower the "
              "amplitude")
    return 0


# ------------------------------------------------------------------ map
def run_map(args) -> int:
    import numpy as np

    from numerics.maps import parse_spec
    from numerics.models import model_map

    model, axes = load(args, axes_ok=True)
    k_axis = None
    k_fixed = None
    if args.k is not None:
        vals = parse_spec(args.k, "--k")
        if vals.size > 1:
            k_axis = vals
        else:
            k_fixed = float(vals[0])
    named = list(axes.items()) + ([("k", k_axis)] if k_axis is not None else [])
    if len(named) != 2:
        raise ValueError(f"a model map sweeps two axes: --k SPEC and/or --param NAME=SPEC "
                         f"(SPEC v1,v2,... or start:stop:num); got {len(named)}: "
                         f"{', '.join(n for n, _ in named) or 'none'}")
    if k_axis is None and k_fixed is None:
        raise ValueError("--k: give the carrier wavenumber (one value, or a SPEC to sweep)")
    simulated = not getattr(args, "theory_only", False)
    unused = sorted(set(getattr(args, "given", ())) & {"--scheduler", "--workers", "--block",
                                                         "--timeout", "--yes", "--start"})
    if unused:
        raise ValueError(f"{', '.join(unused)}: a --model map runs its cells in this process "
                         "from the exact wave (they act on the paper chain's maps); drop them")
    if not simulated and ("--seeds" in getattr(args, "given", ())
                          or "--t-end" in getattr(args, "given", ())):
        raise ValueError("--seeds and --t-end act on a simulated model map: drop them, or "
                         "--theory-only")
    amp = args.amplitude
    x, y = (named[1], named[0]) if named[0][0] == "k" else (named[0], named[1])
    if y[0] == "k":
        x, y = y, x
    exact = None
    if args.exact:
        from energy import ModelError
        from numerics.models import exact_gain

        def exact(m, k, a, branch):
            try:
                spec = exact_gain(m, k, a, branch, N=args.N)
            except ModelError:  # no travelling wave at this cell
                return "undefined", float("nan")
            return spec.verdict, spec.peak_gain

    cell = done = on_cell = None
    out = Path(args.out)
    if simulated:  # each cell: the exact theory and runs of the ring, journalled
        from numerics.models import simulated_cell

        if args.exact:
            raise ValueError("--exact: a simulated model map has the exact lattice theory "
                             "per cell already")
        exact = None
        seeds, N = args.seeds, args.N
        if isinstance(seeds, bool) or not isinstance(seeds, int) or seeds < 1:
            raise ValueError(f"--seeds must be an integer >= 1, got {seeds!r}")
        t_end = args.t_end if "--t-end" in getattr(args, "given", ()) else None

        def cell(m, k, a, branch):
            return simulated_cell(m, k, a, branch, N=N, seeds=seeds, t_end=t_end)

        head = {"model": model.name, "model_hash": model.lattice.content_hash,
                "parameters": dict(model.params), "amplitude": amp, "branch": str(args.branch),
                "axes": {x[0]: list(map(float, x[1])), y[0]: list(map(float, y[1]))},
                "k": k_fixed, "N": N, "seeds": seeds, "t_end": t_end}
        done, on_cell = _journal(out / "map.cells.jsonl", head, args.overwrite)
        if done:
            print(f"resuming {out / 'map.cells.jsonl'}: {len(done)} cells already done")
    ds = model_map(model, x, y, amp, k=k_fixed, branch=branch_of(args), exact=exact,
                   cell=cell, done=done, on_cell=on_cell, progress=None if simulated else False)
    mi = {v: float(np.mean(ds[v].values == "MI")) for v in ds.data_vars
          if v.startswith("verdict_")}
    out.mkdir(parents=True, exist_ok=True)
    nc = out / "map.nc"
    ds.to_netcdf(nc)
    png = out / "map.png"
    _plot_map(ds, png, model)
    if args.json:
        _emit({"model": model.name, "parameters": dict(model.params), "amplitude": amp,
               "axes": {x[0]: list(map(float, x[1])), y[0]: list(map(float, y[1]))},
               "mi_share": mi, "files": [str(nc), str(png)]})
        return 0
    fixed = ", ".join(f"{p} = {v:g}" for p, v in model.params.items()
                      if p not in (x[0], y[0]))
    print(f"model: {model.name} ({fixed}); amplitude {amp:g}; {y[0]} x {x[0]} = "
          f"{len(y[1])} x {len(x[1])} cells")
    for v, share in mi.items():
        print(f"MI share, {v.replace('verdict_', '')}: {share:.0%}")
    print(f"wrote {nc} and {png}")
    return 0


def _journal(path: Path, head: dict, overwrite: bool):
    """(cells done, on_cell) of a simulated model map's journal ``path``: one JSON line per
    finished cell after a header naming the map, each line written and flushed whole, so
    an interrupted map keeps every finished cell and the same command resumes it (a torn
    last line is dropped). A journal of another map is refused unless ``overwrite``."""
    import os

    done = {}
    if path.exists():
        text = path.read_text(encoding="utf-8", errors="replace")
        if text and not text.endswith("\n"):  # a line torn by a kill: cut it off
            with open(path, "r+b") as fh:
                fh.truncate(path.read_bytes().rfind(b"\n") + 1)
            text = text[:text.rfind("\n") + 1]
        lines = text.splitlines()
        try:
            first = json.loads(lines[0]) if lines else None
        except ValueError:
            first = None
        if first != {"map": head}:
            if not overwrite:
                raise ValueError(f"{path} holds another map (or is damaged); replace it with "
                                 "--overwrite, or choose another --out")
            path.unlink()
        else:
            for line in lines[1:]:
                try:
                    rec = json.loads(line)
                    done[(rec["i"], rec["j"])] = rec["columns"]
                except (ValueError, KeyError, TypeError):  # a line torn by a kill
                    continue
    path.parent.mkdir(parents=True, exist_ok=True)
    if not path.exists():
        with open(path, "w", encoding="utf-8") as fh:
            fh.write(json.dumps({"map": head}, allow_nan=False) + "\n")

    def on_cell(i, j, columns):
        with open(path, "a", encoding="utf-8") as fh:
            fh.write(json.dumps({"i": i, "j": j, "columns": columns}) + "\n")
            fh.flush()
            os.fsync(fh.fileno())

    return done, on_cell


def _plot_map(ds, path: Path, model):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import numpy as np
    from matplotlib.colors import ListedColormap

    ydim, xdim = ds["verdict_semidiscrete"].dims
    x, y = ds[xdim].values, ds[ydim].values

    def edges(v):
        if v.size == 1:
            return np.array([v[0] - 0.5, v[0] + 0.5])
        mid = (v[1:] + v[:-1]) / 2
        return np.concatenate([[2 * v[0] - mid[0]], mid, [2 * v[-1] - mid[-1]]])

    code = {"stable": 0, "MI": 1, "undefined": 2}
    panels = [(v, label) for v, label in (("verdict_semidiscrete", "semi-discrete NLS"),
                                          ("verdict_exact", "exact lattice"),
                                          ("verdict_simulated", "simulated (MI: grew 20x)"))
              if v in ds]
    code = {**code, "no growth within T": 0, "undetermined": 2}
    fig, axes = plt.subplots(1, len(panels), figsize=(6 * len(panels), 4.5), squeeze=False)
    fixed = ", ".join(f"{p} = {v:g}" for p, v in model.params.items() if p not in (xdim, ydim))
    for ax, (name, label) in zip(axes[0], panels):
        V = np.vectorize(lambda s: code.get(s, 2))(ds[name].values)
        ax.pcolormesh(edges(x), edges(y), V,
                      cmap=ListedColormap(["#3b4cc0", "#f2a134", "#bbbbbb"]),
                      vmin=-0.5, vmax=2.5, shading="flat")
        ax.set_xlabel(xdim + (" (rad/site)" if xdim == "k" else ""))
        ax.set_ylabel(ydim + (" (rad/site)" if ydim == "k" else ""))
        ax.set_title(f"{model.name} ({fixed}), a = {ds.attrs['amplitude']:g}: {label}\n"
                     "orange MI, blue stable, grey undefined", fontsize=9)
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    plt.close(fig)



# ------------------------------------------------------------------ point
def _continuum(model, k, amplitude):
    """The paper's continuum NLS where the model is the paper's chain (flexmm: case II,
    flexmm-rotation: case I), else None: other models have the semi-discrete NLS only."""
    from energy import builtin

    case = {"flexmm": "coupled", "flexmm-rotation": "rotation"}.get(model.name)
    if case is None or model.lattice.content_hash != builtin(model.name).content_hash:
        return None
    from generated import coefficients as c

    p = (k, model.params["alpha"], model.params["K_s"], model.params["K_theta"])
    g1, g2 = float(c.g1(*p)), float(getattr(c, f"g2_{case}")(*p))
    if not (math.isfinite(g1) and math.isfinite(g2)) or g1 == 0:
        return {"verdict": "undefined", "peak_gain": None, "g1": None, "g2": None}
    mi = g2 / g1 > 0
    return {"verdict": "MI" if mi else "stable",
            "peak_gain": abs(g2) * amplitude**2 / 4 if mi else 0.0, "g1": g1, "g2": g2}


def _start_of(args) -> str:
    start = getattr(args, "start", None)
    if start == "paper":
        raise ValueError("--start paper: the paper's start (eq. IC) is for the paper chain "
                         "(no --model); with --model: travelling (the exact wave, default) "
                         "or linear (the linear plane wave)")
    return "linear" if start == "linear" else "exact"


def _exact_row(spec) -> dict:
    return {"verdict": spec.verdict, "peak_gain": spec.peak_gain,
            "fastest_offset": spec.fastest_offset, "mode": spec.mode,
            "modulational_gain": spec.modulational_gain,
            "omega": spec.wave.omega, "omega_linear": spec.wave.carrier.omega}


def _simulated_row(model, k, args, spec, start) -> dict:
    """Seeded runs of the ring from the exact wave (or the linear one) and the verdict
    ``numerics.lattice.simulated_verdict`` gives their growth factors, as for the paper's
    chain: MI, 'no growth within T' or 'undetermined'."""
    import numpy as np

    from numerics.lattice import run_length, simulated_verdict
    from numerics.models import simulate_model

    seeds = args.seeds
    if isinstance(seeds, bool) or not isinstance(seeds, int) or seeds < 1:
        raise ValueError(f"--seeds must be an integer >= 1, got {seeds!r}")
    length = run_length(spec.peak_gain) if args.t_end is None else None
    t_end = args.t_end if args.t_end is not None else length.t_end
    runs = [simulate_model(model, k, args.amplitude, branch=branch_of(args), N=args.N,
                           t_end=t_end, start=start, seed=s, wave=spec.wave)
            for s in range(seeds)]
    growth = [r.growth() for r in runs]
    rates = [g.rate for g in growth if g.verdict == "unstable"]
    rate = float(np.median(rates)) if rates else float("nan")
    v = simulated_verdict([g.factor for g in growth], t_end, rate)
    # the JSON's verdict speaks the theories' three words (MI, stable, undefined: the
    # contract every theory's object keeps); the run's own word, which never claims more
    # than T shows, is ``simulation_verdict``, with the slowest rate it could show
    word = {"MI": "MI", "no growth within T": "stable"}.get(v.word, "undefined")
    row = {"verdict": word, "simulation_verdict": v.word,
           "peak_gain": rate if v.word == "MI" else (0.0 if word == "stable" else None),
           "text": str(v), "t_end": t_end, "seeds": seeds, "start": start,
           "growth": list(v.growth), "slowest_visible_rate": v.slowest_visible,
           "energy_drift": max(r.energy_drift for r in runs), "dt": runs[0].dt,
           "method": runs[0].method}
    if length is not None and length.note():
        row["note"] = length.note()
    return row


def _coefficients_or_undefined(model, k, amplitude, branch) -> dict:
    """The NLS row, or (at k = pi, where 2k is the mean: no expansion) an undefined one
    with its reason: the exact theory and a simulation still answer there."""
    from energy import ModelError
    from numerics.models import carrier, model_coefficients

    try:
        return model_coefficients(model, k, amplitude, branch)
    except ModelError as exc:
        if k < math.pi:
            raise
        car = carrier(model, k, branch)
        return {"k": k, "amplitude": float(amplitude), "branch": car.branch,
                "field": model.fields[car.field], "verdict": "undefined", "peak_gain": None,
                "fastest_offset": None, "band_edge": None, "g1": car.g1, "g2": None,
                "reason": f"{exc} (at k = pi the second harmonic 2k is the mean, 0 mod 2 pi)",
                "warnings": []}


def _ring_note(model, k, amplitude, branch, N, row) -> str | None:
    """The NLS's peak gain over the offsets a ring of N sites carries (2 pi j / N), into
    ``row["ring_peak_gain"]``; a sentence when its band is too narrow for the ring (the
    NLS's verdict is the infinite chain's: the ring, the exact theory on it and the runs
    cannot show that band)."""
    import numpy as np

    from numerics.models import nls, ring_offsets

    if row["verdict"] != "MI":
        row["ring_peak_gain"] = row["peak_gain"]
        return None
    r = nls(model, k, branch)
    ring = float(np.max(r.gain(ring_offsets(N), amplitude)))
    row["ring_peak_gain"] = ring
    if ring > 0:
        return None
    edge = row["band_edge"]
    return (f"the semi-discrete NLS's band (offsets below {edge:.3g}) is narrower than the "
            f"ring's first sideband offset 2 pi / N = {2 * math.pi / N:.3g}: a ring of "
            f"N = {N} carries none of it; --N above {math.ceil(2 * math.pi / edge)} does")


def run_point(args) -> int:
    from common.output import strict_json
    from numerics.lattice import checks
    from numerics.models import exact_gain, snap_ring

    model = load(args)
    checks.real("--k", args.k, 0.0, math.pi)
    checks.real("--amplitude", args.amplitude, 0.0, None)
    if args.t_end is not None and not args.simulate:
        raise ValueError("--t-end acts with --simulate only")
    start = _start_of(args)
    k, _ = snap_ring(args.k, args.N)
    if args.out:
        from common.output import check_output
        check_output(args.out, cache=False)
    co = _coefficients_or_undefined(model, k, args.amplitude, branch_of(args))
    out = {"model": model.name, "parameters": dict(model.params), "k": co["k"],
           "k_requested": float(args.k), "N": args.N, "amplitude": co["amplitude"],
           "branch": co["branch"], "field": co["field"]}
    cont = _continuum(model, k, args.amplitude)
    if cont is not None:
        out["continuum NLS"] = cont
    out["semi-discrete NLS"] = {"verdict": co["verdict"], "peak_gain": co["peak_gain"],
                                "fastest_offset": co["fastest_offset"],
                                "band_edge": co["band_edge"], "g1": co["g1"], "g2": co["g2"],
                                "reason": co["reason"]}
    ring_note = _ring_note(model, k, args.amplitude, branch_of(args), args.N,
                           out["semi-discrete NLS"])
    try:
        spec = exact_gain(model, k, args.amplitude, branch_of(args), N=args.N)
        out["exact lattice"] = _exact_row(spec)
    except Exception as exc:  # no travelling wave: the theory has no verdict here
        from energy import ModelError
        if not isinstance(exc, ModelError):
            raise
        spec = None
        out["exact lattice"] = {"verdict": "undefined", "peak_gain": None,
                                "reason": str(exc)}
    if args.simulate:
        if spec is None:
            raise ValueError(f"--simulate: {out['exact lattice']['reason']}")
        out["simulated"] = _simulated_row(model, k, args, spec, start)
    out = strict_json(out)
    if args.out:
        import json

        from common.files import write_text
        from common.output import prepare_output
        folder = prepare_output(args.out, cache=False)
        write_text(folder / "point.json", json.dumps(out, indent=1, allow_nan=False) + "\n")
    if args.json:
        _emit(out)
        return 0
    print(f"model:    {model.describe()}")
    print(f"carrier:  k = {co['k']:g} rad/site (2 pi m / N on the ring of N = {args.N}) on "
          f"branch {co['branch']} (field {co['field']}), amplitude a = {co['amplitude']:g}")
    print(f"{'theory':<20} {'verdict':>19} {'peak gain (1/time)':>19} {'at offset':>10}")
    for name in ("continuum NLS", "semi-discrete NLS", "exact lattice", "simulated"):
        if name in out:
            t = out[name]
            word = t.get("simulation_verdict", t["verdict"])  # a run says what T shows
            gain = t["peak_gain"] if word == "MI" or name != "simulated" else None
            print(f"{name:<20} {word:>19} {_fmt(gain, 4):>19} "
                  f"{_fmt(t.get('fastest_offset'), 4):>10}")
    if co["reason"]:
        print(f"undefined: {co['reason']}")
    ex = out["exact lattice"]
    if ex.get("reason"):
        print(f"exact lattice undefined: {ex['reason']}")
    elif ex["verdict"] == "MI" and ex["mode"] != "sidebands k +- q":
        print(f"note: the exact lattice's fastest mode is a {ex['mode']}, not a sideband "
              "pair of the carrier: the NLS cannot see it (the sidebands' own fastest rate: "
              f"{_fmt(ex['modulational_gain'], 4)})")
    if "simulated" in out:
        sim = out["simulated"]
        print(f"simulated: {sim['text']}; {sim['seeds']} seed(s) from the "
              f"{'exact travelling' if start == 'exact' else 'linear plane'} wave, "
              f"energy drift {sim['energy_drift']:.1g}")
        if sim.get("note"):
            print(f"note: {sim['note']}")
    if ring_note:
        print(f"note: {ring_note}")
    for w in co["warnings"]:
        print(f"note: {w}")
    if args.out:
        print(f"wrote {Path(args.out) / 'point.json'}")
    return 0
