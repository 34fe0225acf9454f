"""`flexmm point --model`: a model checked at one point three ways (the semi-discrete NLS,
the exact lattice theory on the ring, runs of the ring with --simulate)."""

from __future__ import annotations

import math
from pathlib import Path

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


def _exact_row(spec) -> dict:
    from numerics.models import classify_mode

    row = {"verdict": spec.verdict, "peak_gain": spec.peak_gain,
           "fastest_offset": spec.fastest_offset, "mode": spec.mode,
           "modulational_gain": spec.modulational_gain,
           "omega": spec.wave.omega, "omega_linear": spec.wave.carrier.omega}
    row.update(classify_mode(spec))  # mode_kind, mode_waves and the pair's own offset
    return row


def _own_offset(row, k):
    """The exact fastest mode's own Hill offset |q| (its first wave at k + q), not a
    copy's; None where the mode is unnamed."""
    waves = row.get("mode_waves") or []
    if not waves:
        return None
    q = waves[0]["wavenumber"] - k
    return abs(-((-q + math.pi) % (2 * math.pi) - math.pi))


def _waves(row) -> str:
    return " and ".join(f"branch {w['branch']} ({w['field']}) at {w['wavenumber']:.4g}"
                        for w in row.get("mode_waves", []))


def _ring_misses(model, k, amplitude, branch, N) -> list:
    """The infinite chain's unstable bands that the ring's offsets do not sample:
    [{band, peak_gain, N}] (``numerics.models.ring_misses``)."""
    from numerics.models import ring_misses

    return [{"band": list(b["band"]), "peak_gain": b["peak_gain"], "N": b["N"]}
            for b in ring_misses(model, k, amplitude, branch, N=N)]


#: the infinite chain's unsampled bands a point's text lists in full (the fastest ones)
MISSES_SHOWN = 3


def _miss_text(b, N) -> str:
    return (f"the infinite chain grows at {b['peak_gain']:.3g} /time in the band of offsets "
            f"{b['band'][0]:.4g} to {b['band'][1]:.4g} rad/site, which no offset 2 pi j / N "
            f"of the ring of N = {N} samples: N = {b['N']} does (k snaps to 2 pi m / N)")


def _simulated_row(model, k, args, spec, start, peak_time=None, gain=None) -> dict:
    """Seeded runs of the ring from the exact wave (or the linear one) and the verdict
    ``numerics.lattice.simulated_verdict`` gives their growth factors, as for the paper's
    chain: MI, 'no growth within T' or 'undetermined'."""
    from numerics.models import simulate_seeds

    seeds = args.seeds
    if isinstance(seeds, bool) or not isinstance(seeds, int) or seeds < 1:
        raise ValueError(f"--seeds must be an integer >= 1, got {seeds!r}")
    # a lossy model's runs are launched as issue 42 measures an amplification: noise on
    # the carrier field's positions, run until A(t) has fallen to half its peak (T a cap)
    launch = {"noise_on": "carrier", "until_peak": True} if model.lossy else {}
    t_end = args.t_end
    if model.lossy and t_end is None and peak_time is not None and math.isfinite(peak_time):
        # the cap reaches past the exact theory's peak (1.5x its time), at least the
        # lossless run's length
        from numerics.lattice import run_length
        t_end = max(run_length(spec.peak_gain).t_end, 1.5 * peak_time)
    from common.progress import progress_class
    tqdm = progress_class()

    # progress over the runs (stderr, where it is a terminal: as the maps' bar)
    with tqdm(total=float(seeds), unit="run", desc="point runs", disable=None,
              bar_format="{l_bar}{bar}| {n:.1f}/{total:.0f} runs [{elapsed}<{remaining}]"
              ) as bar:
        sim = simulate_seeds(model, k, args.amplitude, spec, branch=branch_of(args),
                             N=args.N, seeds=seeds, t_end=t_end, start=start, gain=gain,
                             on_steps=lambda n, total: bar.update(n / total), **launch)
    v, rate, runs, t_end, length = sim.verdict, sim.rate, sim.runs, sim.t_end, sim.length
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
    blind = [g for g in (r.growth() for r in runs) if g.verdict == "undetermined"]
    if blind and not model.lossy:  # the ring shows nothing but the carrier's own modes
        row["note"] = f"the runs on N = {args.N} sites: {blind[0].label}"
    from .model_figure import simulated_curve

    row["curve"] = simulated_curve(runs, k)  # sigma(q) measured; None where none grew
    if model.lossy:  # the runs' own amplification: the median seed's
        amps = sorted((r.amplification() for r in runs), key=lambda a: a.amplification)
        med = amps[len(amps) // 2]
        row.update(med.row())
        row["t_end"] = max(float(r.t[-1]) for r in runs)
        row["energy_balance"] = max(r.energy_balance() for r in runs)
        row.pop("energy_drift")  # a damped run's energy falls: its balance is the check
    return row


def _losses(model, k, amplitude, branch, N, out, spec, fw) -> None:
    """A lossy model's amplification per theory (issue 42), into each theory's object:
    carrier_damping, amplification (max over modes and times along the decaying
    carrier), amplification_time, observable (amplification >= 20)."""
    from energy import ModelError
    from numerics.models import (
        exact_amplification,
        four_wave_amplification,
        nls_amplification,
    )

    def put(name, f):
        try:
            a = f()
            out[name].update(a.row())
            if a.amplification == math.inf:  # JSON null: said in words
                out[name]["amplification_note"] = (
                    "unbounded: the carrier is not damped (Gamma = 0), its sidebands grow "
                    "without end")
        except ModelError as exc:  # no theory here: the verdict's reason says why
            out[name].update({"carrier_damping": None, "amplification": None,
                              "amplification_time": None, "observable": None,
                              "amplification_reason": str(exc)})

    if out["semi-discrete NLS"]["verdict"] != "undefined":
        put("semi-discrete NLS", lambda: nls_amplification(model, k, amplitude, branch))
    if fw is not None:
        put("four-wave", lambda: four_wave_amplification(model, k, amplitude, branch, N=N,
                                                         first=fw))
    if spec is not None:
        put("exact lattice", lambda: exact_amplification(model, k, amplitude, branch, N=N,
                                                         first=spec))


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


def _coefficients_or_undefined(model, k, amplitude, branch) -> dict:
    """The NLS row (``model_coefficients``; at k = pi too, the zone boundary, where its
    coefficients are their limit k -> pi)."""
    from numerics.models import model_coefficients

    return model_coefficients(model, k, amplitude, branch)


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


def _reach_note(model, k, amplitude, branch, out) -> str | None:
    """A sentence where the NLS's sidebands grow on the ring and the exact lattice has
    nothing growing, or where the exact lattice's sidebands grow well beyond the NLS's (25% on the
    same ring; the ring samples can only lower the exact row, so the excess is the
    amplitude's): the NLS is the a -> 0 limit, its relative error O(a^2) with a
    coefficient that grows as g2 is a small remainder of large parts. Measured: fput
    alpha 1, beta 1.5, k 2.45, g2 = -0.80 left of parts of 15 (the cubic against the mean
    flow): exact / NLS - 1 = 0.30, 0.076, 0.019 at a = 0.05, 0.025, 0.0125 (4x per
    halving), 1.1 at a = 0.1, where a run measures the exact row."""
    ex, row = out.get("exact lattice", {}), out["semi-discrete NLS"]
    if row["verdict"] == "MI" and row.get("ring_peak_gain") and ex.get("verdict") == "stable":
        # the opposite: sidebands the NLS grows on this ring, and nothing grows in the
        # exact theory (a rotor chain at k 1, a 0.05: NLS 0.006 /time, a run of T = 5000
        # shows no growth, as the exact row says)
        from numerics.models import nls

        parts = nls(model, k, branch).parts
        big = max(parts, key=lambda p: abs(parts[p]))
        return (f"the semi-discrete NLS's sidebands grow on this ring (peak "
                f"{row['ring_peak_gain']:.3g} /time) but nothing grows there in the exact lattice "
                f"theory: the NLS is the a -> 0 limit and fails at a = {amplitude:g} (g2 = "
                f"{row['g2']:.3g}, its largest part the {big}, {parts[big]:.3g}); trust the "
                "exact row (--simulate measures it)")
    if (ex.get("verdict") != "MI" or ex.get("mode_kind") != "sidebands"
            or row["verdict"] != "MI" or not row.get("ring_peak_gain")):
        return None
    ratio = ex["peak_gain"] / row["ring_peak_gain"]
    if ratio < 1.25:
        return None
    from numerics.models import nls

    parts = nls(model, k, branch).parts
    big = max(parts, key=lambda p: abs(parts[p]))
    left = abs(row["g2"]) / abs(parts[big]) if parts[big] else 1.0
    why = (f"g2 = {row['g2']:.3g} is what is left of parts as large as {parts[big]:.3g} "
           f"({big}), so the NLS's O(a^2) error is large here" if left < 0.25 else
           "its relative error grows as a^2")
    return (f"the exact lattice's sidebands grow {ratio:.2g}x as fast as the semi-discrete "
            f"NLS's on this ring: the NLS is the a -> 0 limit and {why}; at a = "
            f"{amplitude:g} trust the exact row (--simulate measures it)")


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
    co = _coefficients_or_undefined(model, k, args.amplitude, branch_of(args))
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
    ring_note = _ring_note(model, k, args.amplitude, branch_of(args), args.N,
                           out["semi-discrete NLS"])
    try:
        spec = exact_gain_checked(model, k, args.amplitude, branch_of(args), N=args.N)
        out["exact lattice"] = _exact_row(spec)
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
    misses = [] if spec is None else _ring_misses(model, k, args.amplitude, branch_of(args),
                                                  args.N)
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
        _losses(model, k, args.amplitude, branch_of(args), args.N, out, spec, fw)
    estimate = None
    if args.simulate:  # the long part (its T known from the exact rate): said before
        estimate = _estimate(model, k, args, spec, start_gain)
        estimated_at = time.perf_counter()
        out["simulated"] = _simulated_row(model, k, args, spec, start,
                                          out["exact lattice"].get("amplification_time"),
                                          gain=start_gain)
    from .model_figure import CURVES, theory_curves

    out["curves"] = {"description": CURVES,
                     **theory_curves(model, k, args.amplitude, branch_of(args), args.N,
                                     spec, fw, _own_offset(out["exact lattice"], k))}
    if start_curve is not None:
        from .model_figure import _curve

        out["curves"][start_label] = _curve(*start_curve)
    if args.simulate:
        out["curves"]["simulated"] = out["simulated"].pop("curve")
    # the table's notes for a script too (the rings' missed bands: ring_misses)
    reach = _reach_note(model, k, args.amplitude, branch_of(args), out)
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
    print(f"carrier:  k = {co['k']:g} rad/site (2 pi m / N on the ring of N = {args.N}) on "
          f"branch {co['branch']} (field {co['field']}), amplitude a = {co['amplitude']:g}"
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
