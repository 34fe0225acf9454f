"""`flexmm point --model`: a model checked at one point three ways (the semi-discrete NLS,
the exact lattice theory on the ring, runs of the ring with --simulate); its rows and
their notes are made in ``_model_point_rows``, printed here."""

from __future__ import annotations

import math
from pathlib import Path

from . import _model_point_rows as rows
from .models import _emit, _fmt, branch_of, check_amplitude, load


# ------------------------------------------------------------------ point
def _start_of(args, model) -> str:
    """The run's start: "exact" (--start travelling, the default), "linear", or a start the
    model registers (``numerics.models.extra_starts``: "paper", eq. IC, for the paper
    chain's energy)."""
    from numerics.models import extra_starts

    start = getattr(args, "start", None)
    if start in (None, "travelling"):
        return "exact"
    if start == "linear" or start in extra_starts(model):
        return start
    raise ValueError(f"--start {start}: model {model.name} has no such start; it starts "
                     "from travelling (the exact wave, default) or linear (the linear plane "
                     "wave)" + ("; the paper's start (eq. IC) belongs to the paper chain's "
                                "energy, lossless (flexmm, flexmm-rotation)"
                                if start == "paper" else ""))


def _waves(row) -> str:
    return " and ".join(f"branch {w['branch']} ({w['field']}) at {w['wavenumber']:.4g}"
                        for w in row.get("mode_waves", []))


#: the infinite chain's unsampled bands a point's text lists in full (the fastest ones)
MISSES_SHOWN = 3


def _miss_text(b, N) -> str:
    return (f"the infinite chain grows at {b['peak_gain']:.3g} /time in the band of offsets "
            f"{b['band'][0]:.4g} to {b['band'][1]:.4g} rad/site, which no offset 2 pi j / N "
            f"of the ring of N = {N} samples: N = {b['N']} does (k snaps to 2 pi m / N)")


def _times(x, f):
    """x f, None where either is None."""
    return None if x is None or f is None else x * f


def _inverse(rate):
    """The e-folding time 1/rate of a positive rate, else None."""
    return 1 / rate if rate is not None and rate > 0 else None


def _loss_table(out, units=None) -> None:
    """The table of a lossy point's amplifications (printed after the verdicts; the time
    also in s where --time-unit is given)."""
    t_f = units.factor("time") if units is not None else None
    print(f"{'with losses':<20} {'carrier damping':>16} {'amplification':>14} "
          f"{'at time':>10} {'observable':>11}" + (f" {'at time (s)':>12}" if t_f else ""))
    for name in ("semi-discrete NLS", "four-wave", "exact lattice", "simulated"):
        t = out.get(name, {})
        if "amplification" not in t:
            continue
        amp = t["amplification"]
        amp_s = "inf" if amp is None and t["observable"] else _fmt(amp, 4)
        obs = {True: "yes (>= 20x)", False: "no", None: "-"}[t["observable"]]
        print(f"{name:<20} {_fmt(t.get('carrier_damping'), 3):>16} {amp_s:>14} "
              f"{_fmt(t['amplification_time'], 4):>10} {obs:>11}"
              + (f" {_fmt(_times(t['amplification_time'], t_f), 4):>12}" if t_f else ""))


def _log(args):
    """Where a point's messages go: stdout, or stderr where stdout is the JSON."""
    import sys

    return (lambda *a: print(*a, file=sys.stderr)) if args.json else print


def _estimate(model, k, args, spec, gain=None):
    """The runs of a simulated point and what follows them
    (``numerics.maps.estimate_model_point``: one run measured here), said before them;
    the PointEstimate."""
    from common.text import duration
    from numerics.lattice import run_length
    from numerics.maps import estimate_model_point

    t_end = args.t_end if args.t_end is not None else run_length(
        spec.peak_gain if gain is None else gain).t_end
    est = estimate_model_point(model, k, args.amplitude, branch_of(args), N=args.N,
                               seeds=args.seeds, t_end=t_end, figure=bool(args.out),
                               wave=spec.wave)
    _log(args)(f"estimate: about {duration(est.seconds)} more ({est.seeds} run(s) of T = "
               f"{est.t_end:g} on N = {args.N} sites ~{est.seeds * est.run:.2g} s of CPU, "
               "measured here"
               + (f"; the cores shared (load average {est.load:.1f} on {est.cores}): "
                  f"{est.slowdown:.1f}x slower, counted" if est.slowdown > 1 else "") + ")")
    return est


def run_point(args) -> int:
    import time

    from common.output import strict_json
    from numerics.lattice import checks
    from numerics.models import exact_gain_checked, snap_ring

    from .units import add_units, model_units

    model = load(args)
    units = model_units(args)
    checks.real("--k", args.k, 0.0, math.pi, high_open=False)
    check_amplitude(args.amplitude)
    if args.t_end is not None and not args.simulate:
        raise ValueError("--t-end acts with --simulate only")
    if not args.simulate and ("--seeds" in getattr(args, "given", ()) or args.seeds != 4):
        # the paper chain's point predicts its growth per seed; a model's seeds are runs
        raise ValueError("--seeds: a model point's seeds are its runs'; add --simulate, "
                         "or leave --seeds out")
    if args.simulate:  # the runs' options, as the paper chain's point checks them: before
        from numerics.maps import MAX_SEEDS, MAX_T_END  # any theory (--t-end 1e30 hung

        checks.integer("--seeds", args.seeds, 1, MAX_SEEDS)  # in the estimate's probe)
        if args.t_end is not None:
            checks.real("--t-end", args.t_end, 0.0, MAX_T_END)
    start = _start_of(args, model)
    from numerics.models import check_ring

    try:  # the ring's size, named as the option (as `map --model` does)
        check_ring(args.N)
    except ValueError as exc:
        raise ValueError(f"--N: {exc}") from None
    k, _ = snap_ring(args.k, args.N)
    from energy import ModelError
    from numerics.models import nls

    try:  # an amplitude whose nonlinearity is rounding: refused, not three verdicts of it
        nls(model, k, branch_of(args)).check_resolved(args.amplitude)
    except ModelError as exc:
        if str(exc).startswith("amplitude"):
            raise ValueError(f"--amplitude: {exc}") from None
        # no NLS here (no carrier, a resonance): the theories below say why
    launched = None  # a start the model registers (eq. IC): checked before any work
    if start not in ("exact", "linear"):
        from energy import ModelError
        from numerics.models import extra_starts

        launched = extra_starts(model)[start]
        try:
            launched.state(model, k, args.amplitude, args.N)
        except ModelError as exc:  # the API's start names, said as the options are
            why = str(exc).replace("use start 'exact' or 'linear'",
                                   "use --start travelling or linear")
            raise ValueError(f"--start {start}: {why}") from None
    if args.out:
        from common.output import check_output
        check_output(args.out, cache=False)
    if args.simulate:  # said before anything that takes time
        _log(args)(f"point: the theories, then an estimate of the {args.seeds} run(s) "
                   "(a model's first run compiles its force for this machine, once: "
                   "seconds to tens of seconds)")
    co = rows.coefficients_row(model, k, args.amplitude, branch_of(args))
    out = {"model": model.name, "parameters": dict(model.params), "k": co["k"],
           "k_requested": float(args.k), "N": args.N, "amplitude": co["amplitude"],
           "branch": co["branch"], "field": co["field"]}
    if co.get("field_rule"):  # why a measures that field (one rule for index and name)
        out["field_rule"] = co["field_rule"]
    from numerics.models import extra_theories

    for extra in extra_theories(model):  # the paper chain's continuum NLS, say
        out[extra.label] = extra.row(model, k, args.amplitude)
    out["semi-discrete NLS"] = {"verdict": co["verdict"], "peak_gain": co["peak_gain"],
                                "fastest_offset": co["fastest_offset"],
                                "band_edge": co["band_edge"], "g1": co["g1"], "g2": co["g2"],
                                "reason": co["reason"]}
    ring_note = rows.ring_note(model, k, args.amplitude, branch_of(args), args.N,
                               out["semi-discrete NLS"])
    try:
        spec = exact_gain_checked(model, k, args.amplitude, branch_of(args), N=args.N)
        out["exact lattice"] = rows.exact_row(spec)
    except Exception as exc:  # no travelling wave: the theory has no verdict here
        from energy import ModelError
        if not isinstance(exc, ModelError):
            raise
        spec = None
        out["exact lattice"] = {"verdict": "undefined", "peak_gain": None,
                                "reason": str(exc)}
    from numerics.models import four_wave

    fw = four_wave(model, k, args.amplitude, branch_of(args), N=args.N)
    out["four-wave"] = fw.row()
    misses = [] if spec is None else rows.missed_bands(model, k, args.amplitude,
                                                       branch_of(args), args.N)
    out["ring_misses"] = misses
    start_curve, start_gain, start_label = None, None, None
    if launched is not None:  # the theory of the state this start launches
        row = launched.theory(model, k, args.amplitude, args.N)
        start_curve = row.pop("curve", None)
        start_label = row.pop("label")
        out[start_label] = row
        start_gain = row["peak_gain"] or 0.0
    if args.simulate:
        if spec is None:
            raise ValueError(f"--simulate: {out['exact lattice']['reason']}")
    if model.lossy:
        rows.add_losses(model, k, args.amplitude, branch_of(args), args.N, out, spec, fw)
    estimate = None
    if args.simulate:  # the long part (its T known from the exact rate): said before
        estimate = _estimate(model, k, args, spec, start_gain)
        estimated_at = time.perf_counter()
        out["simulated"] = rows.simulated_row(model, k, args, spec, start,
                                              out["exact lattice"].get("amplification_time"),
                                              gain=start_gain)
    from .model_figure import CURVES, theory_curves

    out["curves"] = {"description": CURVES,
                     **theory_curves(model, k, args.amplitude, branch_of(args), args.N,
                                     spec, fw, rows.own_offset(out["exact lattice"], k))}
    if start_curve is not None:
        from .model_figure import _curve

        out["curves"][start_label] = _curve(*start_curve)
    if args.simulate:
        out["curves"]["simulated"] = out["simulated"].pop("curve")
    # the table's notes for a script too (the rings' missed bands: ring_misses)
    reach = rows.reach_note(model, k, args.amplitude, branch_of(args), out)
    out["notes"] = [n for n in (ring_note, reach) if n] + list(co["warnings"])
    out = strict_json(add_units(out, units))
    if args.out:
        import json

        from common.files import write_text
        from common.output import prepare_output
        folder = prepare_output(args.out, cache=False)
        write_text(folder / "point.json", json.dumps(out, indent=1, allow_nan=False) + "\n")
        from .model_figure import figure
        curves = {n: c for n, c in out["curves"].items() if n not in ("description",
                                                                       "simulated")}
        figure(folder / "point.png", model, out, curves, out["curves"].get("simulated"),
               getattr(args, "seeds", 1), args.simulate)
    if estimate is not None:
        from common.text import duration

        _log(args)(f"took {duration(time.perf_counter() - estimated_at)} after the estimate "
                   f"(estimated {duration(estimate.seconds)})")
    if args.json:
        _emit(out)
        return 0
    print(f"model:    {model.describe()}")
    # the k asked, where the ring moved it (by 30% from 1 on N = 9), as the paper's point
    asked = "" if f"{co['k']:g}" == f"{args.k:g}" else f", asked {args.k:g}"
    print(f"carrier:  k = {co['k']:g} rad/site (2 pi m / N on the ring of N = {args.N}"
          f"{asked}) on branch {co['branch']} (field {co['field']}), amplitude a = "
          f"{co['amplitude']:g}"
          + (f"; k{units.si(co['k'], 'wavenumber')}" if units.metres_per_site else ""))
    print(f"units:    {units.describe()}")
    rate_f, k_f = units.factor("rate"), units.factor("wavenumber")
    w = max(20, len(start_label or ""))  # the names' column
    print(f"{'theory':<{w}} {'verdict':>19} {'peak gain (1/time)':>19} {'at offset':>10}"
          + (f" {'peak gain (1/s)':>16} {'e-folding (s)':>14}" if rate_f else "")
          + (f" {'offset (rad/m)':>15}" if k_f else ""))
    for name in ("continuum NLS", "semi-discrete NLS", "four-wave", "exact lattice",
                 *([start_label] if start_label else []), "simulated"):
        if name in out:
            t = out[name]
            word = t.get("simulation_verdict", t["verdict"])  # a run says what T shows
            gain = t["peak_gain"] if word == "MI" or name != "simulated" else None
            off = t.get("fastest_offset")
            print(f"{name:<{w}} {word:>19} {_fmt(gain, 4):>19} {_fmt(off, 4):>10}"
                  + (f" {_fmt(_times(gain, rate_f), 4):>16} "
                     f"{_fmt(_times(_inverse(gain), units.seconds_per_T), 4):>14}"
                     if rate_f else "")
                  + (f" {_fmt(_times(off, k_f), 4):>15}" if k_f else ""))
    if model.lossy:
        _loss_table(out, units)
    if co["reason"]:
        print(f"undefined: {co['reason']}")
    ex = out["exact lattice"]
    if ex.get("reason"):
        print(f"exact lattice undefined: {ex['reason']}")
    elif ex["verdict"] == "MI" and ex["mode_kind"] != "sidebands":
        what = "a resonance" if ex["mode_kind"] == "resonance" else f"a {ex['mode_kind']} pair"
        print(f"note: the exact lattice's fastest mode is {what} ({_waves(ex)}), not the "
              "carrier's sidebands: the NLS cannot see it")
    fw = out["four-wave"]
    if fw.get("reason"):  # the exact lattice's reason said once (the energy not real)
        print("four-wave undefined: " + ("as the exact lattice" if fw["reason"] ==
                                         ex.get("reason") else fw["reason"]))
    if fw["verdict"] == "MI":
        print(f"four-wave: the fastest pair is {fw['mode_kind']} ({_waves(fw)})")
    if start_label and out[start_label].get("reason"):
        print(f"{start_label} undefined: {out[start_label]['reason']}")
    if "simulated" in out:
        sim = out["simulated"]
        drift = (f"energy balance error {sim['energy_balance']:.1g} (dE/dt = -2R)"
                 if "energy_balance" in sim else f"energy drift {sim['energy_drift']:.1g}")
        text = sim["text"]
        if "amplification" in sim:  # with losses growth is transient: say the factor first
            text = (f"the sidebands grew {sim['amplification']:.4g}x by t = "
                    f"{sim['amplification_time']:.4g} (the rate rule over the run: {text})")
        origin = (launched.describe if launched is not None else
                  f"the {'exact travelling' if start == 'exact' else 'linear plane'} wave")
        print(f"simulated: {text}; {sim['seeds']} seed(s) from {origin}, {drift}")
        if "peaked" in sim:
            print("simulated with losses: noise on the carrier field's positions; the runs "
                  f"went on to t = {sim['t_end']:.4g}, " + (
                      "where A(t) had fallen to half its peak" if sim["peaked"] else
                      "their cap (A(t) had not fallen to half its peak)"))
        if sim.get("note"):
            print(f"note: {sim['note']}")
    if ring_note:
        print(f"note: {ring_note}")
    if reach:
        print(f"note: {reach}")
    # the fastest few in full; near the zone boundary a small ring can miss a dozen bands
    shown = sorted(misses, key=lambda m: -m["peak_gain"])[:MISSES_SHOWN]
    for m in sorted(shown, key=lambda m: m["band"][0]):
        print(f"note: {_miss_text(m, args.N)}")
    if len(misses) > len(shown):
        rest = [m for m in misses if m not in shown]
        print(f"note: {len(rest)} more such bands, growing at up to "
              f"{max(m['peak_gain'] for m in rest):.3g} /time (all in ring_misses: --json, "
              f"or point.json with --out); N = {min(m['N'] for m in misses)} samples one")
    for w in co["warnings"]:
        print(f"note: {w}")
    if args.out:
        print(f"wrote {Path(args.out) / 'point.json'} and {Path(args.out) / 'point.png'}")
    return 0
