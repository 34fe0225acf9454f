"""The commands for any lattice model (``--model NAME|FILE.toml``): models, coefficients,
point, map and soliton. They parse, call ``numerics.models`` and print; what they compute
lives there."""

from __future__ import annotations

import json
import math

#: The paper chain's flags, which mean nothing for another model.
PAPER_FLAGS = ("alpha", "K_s", "K_theta", "physical", "case", "delta")


def add_model_args(p, json_help="print one JSON object on stdout and nothing else there"):
    """--model, --param, --branch, --json (shared by coefficients, point, map, soliton)."""
    g = p.add_argument_group("any lattice model (instead of the paper chain's flags)")
    g.add_argument("--model", metavar="NAME|FILE.toml",
                   help="a built-in model (`flexmm models`) or a model file (docs/models.md)")
    g.add_argument("--param", action="append", default=[], metavar="NAME=VALUE",
                   help="with --model: a parameter of the model (repeatable); the others "
                        "keep their defaults")
    g.add_argument("--branch", default=None, metavar="INDEX|FIELD",
                   help="with --model: dispersion branch: index (0 = lowest frequency at k) or the field "
                        "that carries most of its kinetic energy (default: the model's branch "
                        "field, else 0; for flexmm the rotational branch theta). The "
                        "amplitude a measures that field (an index: the model's branch "
                        "field, else the branch's most energetic field)")
    g.add_argument("--json", action="store_true", help=json_help)
    g.add_argument("--time-unit", dest="time_unit", type=float, metavar="SECONDS",
                   help="with --model: seconds per unit of the model's time; rates are then "
                        "also given in 1/s, times in s (the paper chain: --physical)")
    g.add_argument("--length-unit", dest="length_unit", type=float, metavar="METRES",
                   help="with --model: the lattice spacing in metres; wavenumbers are then "
                        "also given in rad/m (k / spacing)")


def check_amplitude(value) -> float:
    """--amplitude of a model's command: a number > 0, at most ``energy.MAX_VALUE`` (a
    wave of amplitude 1e200 overflowed its gain: a traceback, not an answer)."""
    from energy import MAX_VALUE
    from numerics.lattice import checks

    return checks.real("--amplitude", value, 0.0, MAX_VALUE, high_open=False)


def wants_model(args) -> bool:
    return getattr(args, "model", None) is not None


def refuse_paper_flags(args):
    given = [f for f in PAPER_FLAGS if getattr(args, f, None) not in (None, False)]
    if given:
        flags = ", ".join("--" + f.replace("_", "-") for f in given)
        raise ValueError(f"{flags}: the paper chain's flags; with --model give the model's "
                         "parameters as --param NAME=VALUE"
                         + (", and its units (SI answers) as --time-unit SECONDS and "
                            "--length-unit METRES" if "physical" in given else "")
                         # the case is a model (newuser 101: --case coupled with --model
                         # fput was told to give parameters, which picks no case)
                         + ("; the case is the model: --model flexmm (coupled) or "
                            "flexmm-rotation (rotation)" if "case" in given else ""))


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
    try:
        model = load_model(args.model, **fixed)
    except ValueError as exc:  # a value's check, named as the option it came from
        words = str(exc).split(" ", 2)
        if len(words) == 3 and words[0] == "parameter" and words[1] in fixed:
            raise type(exc)(f"--param {words[1]}={fixed[words[1]]!r}: {words[2]}") from None
        if "has no parameter" in str(exc):  # a typo: named as the option, the likely name
            _unknown_parameter(load_model(args.model), fixed)
        where = str(args.model)
        if "semi-definite" in str(exc) and fixed:  # probe 96: the --param that made R < 0
            given = ", ".join(f"--param {n}={v!r}" for n, v in fixed.items())
            raise type(exc)(f"{given}: {str(exc).split(': ', 1)[-1]}; a damping must keep "
                            "R >= 0 (a viscous coefficient >= 0)") from None
        if where.endswith(".toml") and not str(exc).startswith(where):
            # a check after parsing (a dissipation that is not >= 0 at the file's values):
            # the file named, as the parser's errors name it
            raise type(exc)(f"{where}: {exc}") from None
        raise
    _unknown_parameter(model, axes)
    b = branch_of(args)  # named as the option, before any work (an index or a field)
    if b is not None and not (isinstance(b, int) and 0 <= b < model.n_fields
                              or b in model.fields):
        raise ValueError(f"--branch {b}: give an index 0..{model.n_fields - 1} or a field of "
                         f"model {model.name!r} ({', '.join(model.fields)})")
    from numerics.models import check_rest_stable

    if not axes:
        try:
            check_rest_stable(model)
        except ValueError as exc:  # named as what the user gave: the values, or the file
            if "is not a minimum" not in str(exc):
                raise
            why = str(exc).split(": ", 1)[-1]  # past 'model NAME (values)'
            src = (", ".join(f"--param {n}={v:g}" for n, v in fixed.items()) if fixed
                   else str(args.model))
            raise type(exc)(f"{src}: model {model.name!r}: {why}") from None
    return (model, axes) if axes_ok else model


def _unknown_parameter(model, names) -> None:
    """Refuse a --param NAME the model does not have, naming the option, the closest of
    its parameters (a typo: 'betta') and all of them."""
    import difflib

    for name in names:
        if name not in model.params:
            lower = {n.lower(): n for n in model.params}  # 'D0' for 'd0' too
            close = [lower[c] for c in difflib.get_close_matches(name.lower(), list(lower),
                                                                 n=1)]
            raise ValueError(f"--param {name}: model {model.name!r} has no parameter "
                             f"{name!r}" + (f"; did you mean {close[0]!r}?" if close else "")
                             + f" (it has: {', '.join(model.params) or 'none'})")


def branch_of(args):
    b = getattr(args, "branch", None)
    return int(b) if isinstance(b, str) and b.isdigit() else b


def _emit(obj: dict):
    from common.output import strict_json  # a NaN or inf is null (as the library's rows)

    print(json.dumps(strict_json(obj), allow_nan=False, default=_plain))


def _plain(x):
    import numpy as np

    if isinstance(x, np.generic):
        return x.item()
    raise TypeError(f"not JSON: {type(x).__name__}")


# ------------------------------------------------------------------ flexmm models
def run_models(args) -> int:
    """List the built-in models: fields, parameters with defaults, one line each; with a
    NAME, print that model's file (a template for one's own)."""
    from energy import BUILTIN, builtin

    name = getattr(args, "name", None)
    if name is not None:
        if name not in BUILTIN:
            own = (f" (a model file of your own goes to a command: flexmm coefficients "
                   f"--model {name} --k 1)" if name.endswith(".toml") else "")
            raise ValueError(f"flexmm models {name}: no built-in model {name!r}; built-in: "
                             f"{', '.join(BUILTIN)}{own}")
        from numerics.maps import model_text

        text = model_text(name)
        if getattr(args, "json", False):
            _emit({"name": name, "file": text})
        else:
            print(text, end="" if text.endswith("\n") else "\n")
        return 0
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
    print("give one with --model NAME (or --model FILE.toml for your own, docs/models.md: "
          "`flexmm models NAME > mine.toml` starts one from a built-in's file); parameters "
          "with --param NAME=VALUE")
    return 0


# ------------------------------------------------------------------ coefficients
def _fmt(x, digits=6):
    if x is None:
        return "-"
    return f"{x + 0.0 if x == 0 else x:.{digits}g}"  # -0.0 (g = g2/g1 of g2 = 0) as 0


def run_coefficients(args) -> int:
    from numerics.lattice import checks
    from numerics.models import model_coefficients

    from .units import KEYS, add_units, model_units

    model = load(args)
    units = model_units(args)
    checks.real("--k", args.k, 0.0, math.pi, high_open=False)
    check_amplitude(args.amplitude)
    co = model_coefficients(model, args.k, args.amplitude, branch_of(args))
    from numerics.models import four_wave

    fw = four_wave(model, args.k, args.amplitude, branch_of(args))
    co["four_wave"] = fw.row()
    if model.lossy:
        _add_losses(co, model, args.k, args.amplitude, branch_of(args), fw)
    if args.json:
        _emit(add_units(co, units))
        return 0
    kind_of = {key: kind for kind, keys in KEYS.items() for key in keys}
    print(f"model:    {model.describe()}")
    print(f"carrier:  k = {_fmt(co['k'])} rad/site{units.si(co['k'], 'wavenumber')} on branch "
          f"{co['branch']} (field {co['field']}), amplitude a = {_fmt(co['amplitude'])} "
          f"({co['field']} = a cos(k n - omega t) + harmonics + mean; a measures "
          f"{co['field']}: {co['field_rule']})")
    print(f"units:    {units.describe()}")
    if note := zero_damping_note(model):
        print(note)
    parts = co["g2_parts"]
    rows = [("omega (1/time)", co["omega"], "omega"),
            ("group velocity (site/time)", co["group_velocity"], "group_velocity"),
            ("g1 = d^2 omega/dk^2 (site^2/time)", co["g1"], "g1"),
            ("g2 (1/(time amplitude^2))", co["g2"], "g2")]
    rows += [(f"  of which {p}", v, None) for p, v in parts.items()]
    rows += [("g = g2/g1 (1/(site^2 amplitude^2))", co["g"], None)]
    W = 35  # the longest label: g = g2/g1 with its unit
    for name, v, key in rows:
        print(f"{name:<{W}} {_fmt(v):>14}" + (units.si(v, kind_of[key]) if key else "")
              # newuser 102: omega is angular; a shaker and a spectrum read f = omega/2pi
              + (f" (f = {hz:.4g} Hz)" if key == "omega" and (hz := units.hertz(v)) is not None
                 else ""))
    verdict = co["verdict"]
    if co.get("lossless_verdict"):  # focusing, but the losses win from t = 0
        verdict += " (damped)"
    elif verdict != "undefined":  # g2 = 0 (a linear chain): no cubic term, neither kind
        verdict += (" (focusing)" if verdict == "MI" else " (defocusing)" if co["g"]
                    else " (g2 = 0)")
    print(f"{'verdict (semi-discrete NLS)':<{W}} {verdict:>14}")
    for name, key in (("peak gain (1/time)", "peak_gain"),
                      ("e-folding time (time)", "e_folding_time"),
                      ("fastest offset (rad/site)", "fastest_offset"),
                      ("band edge (rad/site)", "band_edge"),
                      ("frequency shift (1/time)", "frequency_shift"),
                      ("carrier damping (1/time)", "carrier_damping")):
        if key in co:
            print(f"{name:<{W}} {_fmt(co[key]):>14}{units.si(co[key], kind_of[key])}")
    for f in model.fields:
        print(f"{f + ': 2k harmonic, mean':<{W}} {_fmt(co['second_harmonic'][f]):>14} "
              f"{_fmt(co['mean'][f]):>12}  (mean strain {_fmt(co['mean_strain'][f])})")
    fw = co["four_wave"]
    if fw.get("lossless_verdict"):
        fw = {**fw, "verdict": "stable (damped)"}
    from ._model_point_text import _waves  # point's words for a pair, in its order

    waves = _waves(fw)
    print(f"{'four-wave':<{W}} {fw['verdict']:>14}  peak gain {_fmt(fw['peak_gain'])}"
          + (f", {fw['mode_kind']} ({waves}), offset {_fmt(fw['fastest_offset'], 4)}"
             if fw["verdict"] == "MI" else ""))
    lossy = [f"{name} " + _losses_text(t, units) for name, t in (("semi-discrete NLS", co),
                                                          ("four-wave", fw))
             if "amplification" in t]
    if lossy:  # with losses growth is transient: the rates above alone mislead
        print("with losses (the sidebands' largest amplification along the decaying "
              "carrier): " + "; ".join(lossy))
    if co["reason"]:
        print(f"undefined: {co['reason']}")
    if fw["verdict"] == "undefined" and fw["reason"]:
        print(f"four-wave undefined: {fw['reason']}")
    for w in co["warnings"]:
        print(f"note: {w}")
    return 0


def _add_losses(co: dict, model, k: float, amplitude: float, branch, fw) -> None:
    """A lossy model's amplification (issue 42) into ``co`` (the semi-discrete NLS's) and
    ``co["four_wave"]`` (the four-wave theory's, the infinite chain's as its row):
    amplification, amplification_time, observable (>= 20x), as ``point``'s; a verdict MI
    whose gain no damping lets grow at t = 0 is "stable" (``lossless_verdict`` MI)."""
    from numerics.models import amplified_row, four_wave_amplification, nls_amplification

    for target, f in ((co, lambda: nls_amplification(model, k, amplitude, branch)),
                      (co["four_wave"], lambda: four_wave_amplification(
                          model, k, amplitude, branch, first=fw))):
        if target["verdict"] == "undefined":  # its reason is said; no amplification
            continue
        row = amplified_row(target["verdict"], f)  # the verdict physical, as point's
        row.pop("carrier_damping")  # printed once, as the carrier's
        target.update(row)


def _losses_text(t: dict, units) -> str:
    if t["observable"] is None:
        return f"no answer ({t['amplification_reason']})"
    amp, time = t["amplification"], t["amplification_time"]
    said = ("unbounded (the carrier is not damped)" if amp == math.inf
            else f"{_fmt(amp, 4)}x at t = {_fmt(time, 4)}{units.si(time, 'time')}")
    if t.get("lossless_verdict"):  # beside a gain printed above: why it is not MI
        said += (f" (the losses win from t = 0: net rate {_fmt(t['net_gain'], 3)} /time; "
                 "the peak gain above is the lossless chain's)")
    return said + (", observable (>= 20x)" if t["observable"] else ", not observable (< 20x)")


# ------------------------------------------------------------------ soliton
def _refuse_no_envelope(model, k: float, amplitude: float, branch) -> None:
    """Refuse a soliton that cannot exist, before a table of numbers about it (the paper
    chain refuses an amplitude of 1 rad or more): where the model carries no wave of this
    amplitude (its energy not real along it; the check ``point`` and the map use), and
    where the envelope would be narrower than one site, so that the NLS's slowly varying
    envelope, its width, speed and frequency, describe nothing on the lattice (at 1e3 on
    fput: 0.0005 sites, a frequency 1e6 times omega). Between one site and MIN_WIDTH
    (numerics.theory's) the result stands with its note: the theory is rough there, not
    void."""
    from energy import ModelError
    from numerics.models import energy_not_real, nls

    why = energy_not_real(model, k, amplitude, branch)
    if why is not None:
        raise ValueError(f"--amplitude: no soliton: {why}; lower --amplitude")
    try:
        r = nls(model, k, branch)
        width = None if r.undefined else r.soliton(amplitude).width
    except ModelError:  # no carrier here: the command's own error says why
        return
    if width is not None and width < 1:
        raise ValueError(narrower_than_a_site(amplitude, width))


def narrower_than_a_site(amplitude: float, width: float) -> str:
    """The refusal of a soliton narrower than one site (any model's, the paper chain's),
    with the amplitude that gives MIN_WIDTH sites: an NLS soliton's width goes as
    1 / amplitude."""
    from numerics.theory import MIN_WIDTH

    return (f"--amplitude {amplitude:g}: the soliton would be {width:.3g} sites wide, "
            "narrower than one site: the envelope theory has no soliton there; lower "
            f"--amplitude (about {amplitude * width / MIN_WIDTH:.3g} gives {MIN_WIDTH:g} "
            "sites, the narrowest it describes)")


def run_soliton(args) -> int:
    from numerics.lattice import checks
    from numerics.models import nls

    from .units import add_units, model_units

    if getattr(args, "theory", "semi-discrete") == "paper":  # every path, printing too
        raise ValueError("--theory paper: the paper's continuum NLS is the paper chain's "
                         "(no --model); a model's soliton is its semi-discrete NLS's")
    model = load(args)
    units = model_units(args)
    checks.real("--k", args.k, 0.0, math.pi, high_open=False)
    check_amplitude(args.amplitude)
    simulate = getattr(args, "simulate", False)
    if not simulate:  # a launch refuses these itself (check_soliton_launch: < 2 sites)
        _refuse_no_envelope(model, args.k, args.amplitude, branch_of(args))
    if simulate or getattr(args, "out", None):
        from .model_soliton import run_model_soliton

        run_model_soliton(args, model, units, branch_of(args))
        return 0
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
    from numerics.theory import MIN_WIDTH

    from .model_soliton import lossy_note

    damping, lossy = lossy_note(model, args.k, r.carrier.branch, units)
    if damping > 0:  # the NLS's soliton is lossless; the chain's decays
        out["carrier_damping"] = damping
    if args.json:
        _emit(add_units(out, units))
        return 0
    print(f"model:    {model.describe()}")
    print(f"carrier:  k = {args.k:g} rad/site{units.si(args.k, 'wavenumber')} on branch "
          f"{r.carrier.branch}, omega = {r.carrier.omega:.6g}; g1 = {r.g1:.6g}, "
          f"g2 = {r.g2:.6g}")
    print(f"units:    {units.describe()}")
    # the field the amplitude measures (it can change with k: diatomic fput's acoustic
    # branch at k = pi moves v only, so a there is v's, at k = 3.1 u's)
    print(f"{s.kind} soliton, amplitude {s.amplitude:g} (first harmonic of "
          f"{model.fields[r.carrier.field]}): width {s.width:.4g} sites"
          f"{units.si(s.width, 'length')}, velocity {s.velocity:.4g} sites/time"
          f"{units.si(s.velocity, 'velocity')}, frequency {s.frequency:.6g}"
          f"{units.si(s.frequency, 'rate')}")
    for f, v in zip(model.fields, s.kink):
        if v != 0:
            print(f"kink of {f}: {v:.4g} (step of its mean displacement across the soliton)")
    if s.width < MIN_WIDTH:
        print(f"note: {s.width:.3g} sites is too narrow for the envelope theory; lower the "
              "amplitude")
    if lossy:
        print(lossy)
    return 0


def zero_damping_note(model) -> str | None:
    """One line where a model file's [dissipation] damps nothing at its values: the
    answers are the lossless chain's (``Model.lossy`` False), said so; else None."""
    if model.lossy or not model.lattice.lossy:
        return None
    from numerics.maps import damping_parameters

    names = damping_parameters(model.lattice)
    at = ", ".join(f"{n} = {model.params[n]:g}" for n in names)
    return (f"damping:  zero at these values ({at or 'its [dissipation]'}): the chain is "
            "lossless here, and so are these answers")

