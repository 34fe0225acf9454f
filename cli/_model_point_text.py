"""What `flexmm point --model` prints and writes (``cli.point.run_point`` calls it): the
estimate of the runs before them, point.json and point.png, then the table of every
theory's verdict (and a lossy model's amplifications) and the notes, or the JSON alone.
The numbers are ``numerics.maps.measure_point``'s (a ``ModelPoint``)."""

from __future__ import annotations

import sys
from pathlib import Path

from .models import _emit, _fmt


def log_to(args):
    """Where a point's messages go: stdout, or stderr where stdout is the JSON."""
    return (lambda *a: print(*a, file=sys.stderr)) if args.json else print


def say_estimate(args, est) -> None:
    """The runs of a simulated point and what follows them (``PointEstimate``: one run
    measured here), said before them."""
    from common.text import duration

    upto = " at most" if getattr(est, "at_most", False) else ""
    cap = (" (a lossy run's cap: it stops once A(t) has halved past the exact theory's "
           "peak)") if upto else ""
    log_to(args)(f"estimate: about {duration(est.seconds)} more{upto} ({est.seeds} run(s) of "
                 f"T = {est.t_end:g}{cap} on N = {args.N} sites "
                 f"~{est.seeds * est.run:.2g} s of CPU, measured here"
                 + (f"; the cores shared (load average {est.load:.1f} on {est.cores}): "
                    f"{est.slowdown:.1f}x slower, counted" if est.slowdown > 1 else "") + ")")


def _waves(row) -> str:
    """A row's pair in words, in the one order of every text (``waves_in_order``): the
    exact and four-wave rows named one parametric pair in opposite orders, read as two."""
    from numerics.maps import waves_in_order

    return " and ".join(f"branch {w['branch']} ({w['field']}) at {w['wavenumber']:.4g}"
                        for w in waves_in_order(row))


#: the infinite chain's unsampled bands a point's text lists in full (the fastest ones)
MISSES_SHOWN = 3


def _miss_text(b, N, k) -> str:
    lo, hi = b["band"]
    # digits enough to tell the edges apart (a band 1e-4 wide read "1.142 to 1.142")
    d = next((d for d in range(4, 10) if f"{lo:.{d}g}" != f"{hi:.{d}g}"), 10)
    # the ring advised has an offset where the band grows at half its peak or more
    ring = (f"no ring up to N = {64 * N} has an offset where it grows at half that"
            if b["N"] is None else
            f"N = {b['N']} with --k {k:.9g} does (a ring that carries this k, so this band)"
            if b.get("same_k") else
            f"N = {b['N']} does (k snaps to 2 pi m / N there: the band moves with it)")
    return (f"the infinite chain grows at {b['peak_gain']:.3g} /time in the band of offsets "
            f"{lo:.{d}g} to {hi:.{d}g} rad/site, which no offset 2 pi j / N "
            f"of the ring of N = {N} samples: {ring}")


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
    r_f = units.factor("rate") if units is not None else None
    print(f"{'with losses':<20} {'carrier damping':>16} {'amplification':>14} "
          f"{'at time':>10} {'observable':>11}" + (f" {'at time (s)':>12}" if t_f else "")
          + (f" {'damping (1/s)':>14}" if r_f else ""))
    for name in ("semi-discrete NLS", "four-wave", "exact lattice", "simulated"):
        t = out.get(name, {})
        if "amplification" not in t:
            continue
        amp = t["amplification"]
        amp_s = "inf" if amp is None and t["observable"] else _fmt(amp, 4)
        obs = {True: "yes (>= 20x)", False: "no", None: "-"}[t["observable"]]
        if (t["observable"] is False and t.get("peaked") is False
                and not t.get("ended_below_half")):
            obs = "not by cap"  # the runs stopped while A(t) still rose: no answer yet
        print(f"{name:<20} {_fmt(t.get('carrier_damping'), 3):>16} {amp_s:>14} "
              f"{_fmt(t['amplification_time'], 4):>10} {obs:>11}"
              + (f" {_fmt(_times(t['amplification_time'], t_f), 4):>12}" if t_f else "")
              + (f" {_fmt(_times(t.get('carrier_damping'), r_f), 3):>14}" if r_f else ""))


def report(args, point, units, since=None) -> dict:
    """Write (``--out``) point.json and point.png, say how long the runs took after their
    estimate (``since``: when it was said), then print the JSON (``--json``) or the table
    and its notes. Returns point.json's object."""
    import time

    from common.output import strict_json

    from .units import add_units

    model, out = point.spec.model, strict_json(add_units(point.as_dict(), units))
    start, launched, start_label = point.spec.start, point.spec.launched, point.start_label
    misses = point.rows["ring_misses"]  # as measured (out: strict JSON)
    if args.out:
        import json

        from common.files import write_results
        from common.output import prepare_output
        folder = prepare_output(args.out, cache=False)
        from .model_figure import figure
        curves = {n: c for n, c in out["curves"].items() if n not in ("description",
                                                                       "simulated")}
        png = figure(model, out, curves, out["curves"].get("simulated"),
                     getattr(args, "seeds", 1), args.simulate)
        write_results({folder / "point.json": json.dumps(out, indent=1, allow_nan=False)
                       + "\n", folder / "point.png": png})
    if point.estimate is not None:
        from common.text import duration

        log_to(args)(f"took {duration(time.perf_counter() - since)} after the estimate "
                     f"(estimated {duration(point.estimate.seconds)})")
    if args.json:  # the files written named, as a map's --json does (no "wrote" line here)
        _emit(out | ({"files": [str(Path(args.out) / "point.json"),
                                str(Path(args.out) / "point.png")]} if args.out else {}))
        return out
    print(f"model:    {model.describe()}")
    from .models import zero_damping_note

    if note := zero_damping_note(model):
        print(note)
    # the k asked, where the ring moved it (by 30% from 1 on N = 9), as the paper's point
    asked = "" if f"{out['k']:g}" == f"{args.k:g}" else f", asked {args.k:g}"
    print(f"carrier:  k = {out['k']:g} rad/site (2 pi m / N on the ring of N = {args.N}"
          f"{asked}) on branch {out['branch']} (field {out['field']}), amplitude a = "
          f"{out['amplitude']:g}"
          + (f"; k{units.si(out['k'], 'wavenumber')}" if units.metres_per_site else ""))
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
        damped = [name for name in ("semi-discrete NLS", "four-wave", "exact lattice")
                  if out.get(name, {}).get("lossless_verdict")]
        if damped and all(out[n].get("carrier_overdamped") for n in damped):
            # 'net rate at best 0' read as a sideband balanced by its damping (probe 98)
            print(f"note: {', '.join(damped)}: stable with these losses, the carrier is "
                  "damped past critical (its root does not oscillate: a relaxation, not a "
                  "wave to modulate); the peak gain shown is the lossless chain's, which is "
                  "MI")
        elif damped:  # its verdict stable beside a gain: said why
            print(f"note: {', '.join(damped)}: stable with these losses, no sideband "
                  "outgrows its damping at t = 0 (net rate at best "
                  + ", ".join(f"{_fmt(out[n]['net_gain'], 3)}" for n in damped)
                  + " /time); the peak gain shown is the lossless chain's, which is MI")
    why_nls = out["semi-discrete NLS"]["reason"]
    if why_nls:
        print(f"undefined: {why_nls}")
    ex = out["exact lattice"]
    if ex.get("reason"):  # the NLS's reason said once (the energy not real)
        print("exact lattice undefined: " + ("as the semi-discrete NLS" if ex["reason"] ==
                                             why_nls else ex["reason"]))
    elif point.mode_note:
        print(f"note: {point.mode_note}")
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
                      "their cap (A(t) never rose 4.5x and ended below half its largest: "
                      "nothing grew)" if sim.get("ended_below_half") else
                      "their cap (A(t) had not fallen to half its peak)"))
        if sim.get("note"):
            print(f"note: {sim['note']}")
    if point.ring_note:
        print(f"note: {point.ring_note}")
    if point.reach_note:
        print(f"note: {point.reach_note}")
    # the fastest few in full; near the zone boundary a small ring can miss a dozen bands
    shown = sorted(misses, key=lambda m: -m["peak_gain"])[:MISSES_SHOWN]
    for m in sorted(shown, key=lambda m: m["band"][0]):
        print(f"note: {_miss_text(m, args.N, out['k'])}")
    if len(misses) > len(shown):
        rest = [m for m in misses if m not in shown]
        print(f"note: {len(rest)} more such bands, growing at up to "
              f"{max(m['peak_gain'] for m in rest):.3g} /time (all in ring_misses: --json, "
              f"or point.json with --out)" + (
                  f"; N = {min(ns)} samples one" if (ns := [m["N"] for m in misses
                                                            if m["N"] is not None]) else ""))
    for w in point.warnings:
        print(f"note: {w}")
    if args.out:
        print(f"wrote {Path(args.out) / 'point.json'} and {Path(args.out) / 'point.png'}")
    return out
