"""`flexmm point`: the theories of MI at one point of the paper's chain (its flags) or of
any lattice model (``--model``), and optionally the simulation that checks them (measured
sigma(q), verdict, figure). The numbers are ``numerics.maps.measure_point``'s, for a
Material or a ``ModelPointSpec``; this module checks the options, prints and writes (a
model point's table and files in ``_model_point_text``)."""

from __future__ import annotations

import json
import math
import time
from pathlib import Path

import numpy as np

from common.files import write_results
from common.output import prepare_output, strict_json
from common.paper import EPS
from common.text import duration
from numerics import Material
from numerics.lattice import (
    DECIDE_E_FOLDINGS,
    GROWTH_THRESHOLD,
    T_CAP,
    checks,
    grows_beyond_threshold,
    paper_start_undefined,
)
from numerics.maps import MAX_SEEDS, MAX_T_END, fold, measure_point, snap_carrier
from numerics.theory import (
    EXACT_LATTICE,
    MAX_AMPLITUDE,
    PAPER_NLS,
    SEMIDISCRETE_NLS,
    nls_coefficients,
)

from ._model_point_args import MIN_T_END, run_model_point
from ._slow import SLOW_PAPER_POINT, said_if_slow
from ._slow import to_stderr as _stderr
from .coefficients import weak_nonlinearity_note, wide_band_note

#: what point.json's numbers are in (the lattice units), beside the SI ones of --physical
UNITS = {"time": "T = t sqrt(k_l/m)", "gain": "1/T", "wavenumber": "rad/site",
         "curves": "theories: curve over offset Q = |q - k| (0 .. pi), q the upper sideband "
                   "folded into [0, pi]; simulated: sigma per rfft bin q, and "
                   "sigma_by_offset (the smaller of a pair's two sidebands)"}


def material_from(args):
    """(Material, Units) from --alpha/--K-s/--K-theta, or --physical m,J,a,k_l,k_s,k_theta
    (then answers are also given in seconds and metres)."""
    from .coefficients import Units

    if getattr(args, "physical", None):
        try:
            values = [float(v) for v in args.physical.split(",")]
        except ValueError:
            raise ValueError(f"--physical: cannot read {args.physical!r}; give six numbers "
                             "m,J,a,k_l,k_s,k_theta") from None
        if len(values) != 6:
            raise ValueError(f"--physical needs six numbers m,J,a,k_l,k_s,k_theta, got "
                             f"{len(values)}")
        if any(v is not None for v in (args.alpha, args.K_s, args.K_theta)):
            raise ValueError("give --physical or --alpha/--K-s/--K-theta, not both")
        try:  # its six values are one option's: named as it (m, J, a, k_l > 0 too)
            mat = Material.from_physical(*values)
        except ValueError as exc:
            raise ValueError(f"--physical m,J,a,k_l,k_s,k_theta: {exc}") from None
        m, _, a, k_l = values[:4]
        units = Units.physical(m, k_l, a)
        # sqrt(m / k_l) can leave float64 while the material is fine: seconds would be 0 or inf
        if not (math.isfinite(units.seconds_per_T) and units.seconds_per_T > 0):
            raise ValueError("--physical m,J,a,k_l,k_s,k_theta: the time unit sqrt(m / k_l) is "
                             "out of float64's range; give m and k_l in units nearer 1")
        return mat, units
    missing = [n for n, v in (("--alpha", args.alpha), ("--K-s", args.K_s),
                              ("--K-theta", args.K_theta)) if v is None]
    if missing:
        raise ValueError(f"missing {', '.join(missing)} (or give --physical m,J,a,k_l,k_s,"
                         "k_theta)")
    for name, v in (("--alpha", args.alpha), ("--K-s", args.K_s), ("--K-theta", args.K_theta)):
        checks.positive(name, v)  # the wording every command uses
    return Material(args.alpha, args.K_s, args.K_theta), Units()


def _checked(args, mat):
    """(amplitude, k, m) after every option's check, named as the option (nothing is
    computed before the input is known good)."""
    from ._resolved import check_paper_amplitude, check_peak_rotation

    amplitude = check_peak_rotation(args.amplitude, MAX_AMPLITUDE)
    k, m = snap_carrier(args.k, args.N, names=("--k", "--N"))

    check_paper_amplitude(mat, k, amplitude)
    checks.integer("--seeds", args.seeds, 1, MAX_SEEDS)
    if args.t_end is not None:
        checks.real("--t-end", args.t_end, MIN_T_END, MAX_T_END, low_open=False)
    if args.start == "paper" and (why := paper_start_undefined(mat, k, ("travelling",))):
        raise ValueError(f"--start paper: {why}")
    return amplitude, k, m


def _log_header(log, args, mat, units, k, m, amplitude):
    """The inputs echoed (material, carrier, the semi-discrete NLS, units), before the
    theories and the simulation run."""
    N, k_req = args.N, args.k
    A0 = amplitude / (2 * EPS)
    co_all = nls_coefficients(mat, k, amplitude)
    co = co_all["semi-discrete"]
    log(f"material: alpha = {mat.alpha:g}, K_s = {mat.K_s:g}, K_theta = {mat.K_theta:g} "
        f"(delta = {mat.delta:.4g}); case {args.case}")
    log(f"carrier:  k = {units.wavenumber(k)} = 2 pi {m}/{N}"
        + (f" (asked {k_req:g}: the nearest a chain of N = {N} sites carries)"
           if abs(k - k_req) > 1e-9 * k_req else "")
        + f"; amplitude {amplitude:g} rad (peak rotation; eps = {EPS:g}, A0 = {A0:.4g}); "
        f"start {args.start}")
    log(f"NLS (semi-discrete): omega = {co['omega']:.6g} 1/T, v_g = {co['v_g']:.4g} site/T, "
        f"g1 = {co['g1']:.4g}, g2 = {co[args.case]['g2']:.4g}, g = {co[args.case]['g']:.4g}")
    log(f"units:    {units.describe()}")
    for note in (weak_nonlinearity_note(co_all, amplitude, remedy="the exact rows below"),
                 wide_band_note(co_all, amplitude, (args.case,))):
        if note:
            log(note)


def _rows(res) -> list:
    """The table's rows (theory, verdict, peak gain, its offset, half-gain edge); the
    theories keep their physical verdict, a simulation's row comes last."""
    rows = [(n, t["verdict"], t["peak_gain"], t["peak_offset"],
             t["band_edge"]) for n, t in res.theories.items()]
    sim = res.simulated
    if sim is not None:
        rows.append((f"simulated ({sim['seeds']} seeds, N = {res.N}, T = {res.t_end:g}, "
                     f"{sim['method']} dt = {sim['dt']:.3g})", sim["verdict"],
                     sim["peak_gain"], sim["peak_offset"], sim["band_edge"]))
    return rows


#: the predicted sidebands' size, over the carrier's, from which a run's own nonlinearity
#: can slow their growth: measured at the README's point (alpha 2, K_s 0.03, K_theta 0.02,
#: k 1.2, a 0.04, case II) the run is 2% below the linear prediction at 0.03 and 2.1x at
#: 0.24; at the blue point (case II, travelling, N 250) 0.1% at 0.03, 3% at 0.1, 11% at 0.24
SATURATION_ONSET = 0.03


def _seconds(units, t_end: float) -> str:
    """`` (= 100 s)`` beside a run length in T with --physical ('' without)."""
    s = getattr(units, "seconds_per_T", None)
    return f" (= {t_end * s:.4g} s)" if s else ""


def _log_growth(log, res, units=None):
    """The predicted (and measured) growth factor per seed, and what it means."""
    t_end, pred = res.t_end, res.prediction
    if pred is None:
        log(f"growth factor within T = {t_end:g}{_seconds(units, t_end)}: no prediction "
            f"({res.predicted['reason']})")
        return
    predicted = res.predicted["growth"]
    log(f"growth factor within T = {t_end:g}{_seconds(units, t_end)} (the largest "
        "non-carrier component over the "
        f"carrier, per seed): predicted "
        + ", ".join(f"{g:.3g}x" for g in predicted)
        + ("; measured " + ", ".join(f"{g['growth']:.3g}x" for g in res.growths)
           if res.growths is not None else "")
        + ("" if pred.linear else " (the prediction leaves the linear stage: MI, the "
           "factor an upper bound)"))
    reach = max((float(np.max(r)) for r in pred.ratio.values() if np.size(r)), default=0.0)
    if pred.linear and reach > SATURATION_ONSET:
        log(f"note: the predicted factors are the linear stage's: by T = {t_end:g} the "
            f"predicted sidebands reach {reach:.2g} of the carrier's amplitude (seed 0); "
            "from a few % of it on, the run's own nonlinearity slows their growth and "
            "depletes the carrier, so a run measures less: there the prediction is an "
            "upper bound")
    if (np.median(predicted) > GROWTH_THRESHOLD
            and not grows_beyond_threshold(pred.rate, t_end)):
        log(f"note: no Hill mode grows fast enough for {GROWTH_THRESHOLD:g}x within T "
            f"(fastest {pred.rate:.3g} /T): the predicted factor is the linear response "
            "itself (modes that beat, a transient), as the run will show it, not an "
            "exponential instability")
    side = res.theories[res.exact_theory]["peak_gain"]
    if (grows_beyond_threshold(pred.rate, t_end) and math.isfinite(side)
            and pred.rate > 1.1 * side):
        log(f"note: the fastest growing Hill mode ({pred.rate:.4g} /T) is not a sideband "
            f"pair, which the '{res.exact_theory}' row shows ({side:.4g} /T): a map's "
            "exact_all column counts every mode")


def _log_verdicts(log, res, args):
    log("verdicts: a theory's MI = the plane wave is unstable (peak gain > 0, however "
        "slow); a run's: MI (grew more than "
        f"{GROWTH_THRESHOLD:g}x), no growth within T, or undetermined")
    if res.simulated is not None:
        log(f"grows more than {GROWTH_THRESHOLD:g}x within T = {res.t_end:g} (theories: "
            "exp(peak gain x T)): " + ", ".join(
                f"{n} {'yes' if t['grows_beyond_threshold_within_t_end'] else 'no'}"
                for n, t in res.theories.items()
                if t.get("grows_beyond_threshold_within_t_end") is not None)
            + "; measured " + ", ".join(f"{g['growth']:.3g}x" for g in res.growths))
        if res.simulated.get("note"):
            log(f"note: {res.simulated['note']}")
    length = res.length
    if length.capped and not args.t_end:
        log(f"note: {length.note()} decide (the cap T = {length.cap:g} keeps a point "
            "within about a minute)")
    elif args.t_end and length.rate * res.t_end < DECIDE_E_FOLDINGS:
        log(f"note: --t-end {res.t_end:g} holds {length.rate * res.t_end:.2g} e-foldings of "
            f"the fastest predicted rate {length.rate:.4g} /T; {DECIDE_E_FOLDINGS:g} decide: "
            f"--t-end {length.decides_at:g} would")


def _log_fastest(log, rows, k, units):
    """The most faithful row that grows: the simulation, else the exact theory, else an
    NLS; its sidebands and e-folding time."""
    growing = [r for r in rows if math.isfinite(r[2]) and r[2] > 0]
    best = None
    for kind in ("simulated", EXACT_LATTICE.label, SEMIDISCRETE_NLS.label, PAPER_NLS.label):
        group = [r for r in growing if r[0].startswith(kind)]
        if group:
            best = max(group, key=lambda r: r[2])
            break
    if best is not None:
        Q = best[3]
        up, low = fold([k + Q, k - Q])
        log(f"fastest growth ({best[0]}): offset q - k = {Q:.4g}, sidebands q at "
            f"{up:.4g} and {low:.4g} rad/site (folded into [0, pi]), e-folding "
            f"time {units.time(1 / best[2])}")


def run_point(args, log=print) -> dict:
    """`flexmm point`: check the options, echo them, ``measure_point``, print the table
    and (``--out``) write point.json and point.png. Returns point.json's dict.

    With ``--model`` the point is the model's (``ModelPointSpec``), printed by
    ``_model_point_text`` (``log`` is the paper flags' only: a model point's messages go
    to stderr with --json)."""
    if getattr(args, "model", None) is not None:
        return run_model_point(args)
    mat, units = material_from(args)
    amplitude, k, m = _checked(args, mat)
    if args.out:  # before any computation (a simulation may take minutes)
        prepare_output(args.out, cache=False)
    _log_header(log, args, mat, units, k, m, amplitude)
    if args.simulate:  # said before the runs, which take seconds to minutes
        log(f"point: the theories and each seed's predicted growth, then {args.seeds} "
            f"run(s) of the ring of N = {args.N} sites, T = "
            + (f"{args.t_end:g}" if args.t_end else "9 e-foldings of the exact rate (at most "
               f"{T_CAP:g})") + ": seconds to minutes")
    said = []  # (when the runs' estimate was said, its seconds), as a model point's
    slow = []  # the slow note's timer: the runs' estimate, once said, says the rest

    def on_estimate(est):
        for timer in slow:
            timer.cancel()
        _say_estimate(log, est, args.N)
        said.append((time.perf_counter(), est.seconds))

    # said only where slow (the predicted growth: 15 s under load; with runs, the theories
    # before the runs' estimate: 32 s of silence in a fresh clone, the kernels compiling)
    with said_if_slow(_stderr, SLOW_PAPER_POINT) as timer:
        slow.append(timer)
        res = measure_point(mat, args.case, args.k, amplitude, N=args.N, start=args.start,
                            simulate=args.simulate, t_end=args.t_end, seeds=args.seeds,
                            on_estimate=on_estimate, estimate_figure=bool(args.out))
    result = res.as_dict(units={**UNITS, "seconds_per_T": units.seconds_per_T,
                                "metres_per_site": units.metres_per_site})
    rows = _rows(res)
    log("")
    _log_growth(log, res, units)
    _log_verdicts(log, res, args)
    log(_table(rows, units))
    for n, t in res.theories.items():
        if "reason" in t:
            log(f"{n}: {t['reason']}")
    if (why := _why_no_gain(res, mat, args.case, amplitude)) is not None:
        log(why)
    if (unsampled := _ring_note(res)) is not None:
        log(unsampled)
    if res.simulated is not None:
        log(f"simulated verdict: {res.simulated['text']}")
    if res.simulated is not None and "no_rate" in res.simulated:
        log(f"simulated: {res.simulated['no_rate']}")
    _log_fastest(log, rows, k, units)
    if args.out:
        out = Path(args.out)
        out.mkdir(parents=True, exist_ok=True)
        png = _figure(res.theories, res.measured, k, args, amplitude, mat,
                      (res.simulated or {}).get("no_rate"))
        write_results({out / "point.png": png,
                       out / "point.json": json.dumps(strict_json(result), indent=2) + "\n"})
    if said:
        log(f"took {duration(time.perf_counter() - said[0][0])} after the estimate "
            f"(estimated {duration(said[0][1])})")
    if args.out:
        log(f"wrote {out / 'point.json'} and {out / 'point.png'}")
    return result


def _say_estimate(log, est, N) -> None:
    """The runs' estimate (``PointEstimate``, one short run measured here), said before
    them, as ``flexmm point --model --simulate`` says its own."""
    log(f"estimate: about {duration(est.seconds)} more ({est.seeds} run(s) of T = "
        f"{est.t_end:g} on N = {N} sites ~{est.seeds * est.run:.2g} s of CPU, measured here"
        + (f"; the cores shared (load average {est.load:.1f} on {est.cores}): "
           f"{est.slowdown:.1f}x slower, counted" if est.slowdown > 1 else "") + ")")


def _ring_note(res) -> str | None:
    """Where the exact theory's band (the infinite chain's) holds no offset 2 pi j / N of
    the ring, one line: no ring mode grows, so a run of N sites cannot show that MI (as
    ``point --model`` says with ``ring_misses``); with the N that samples it."""
    ex = res.theories.get(res.exact_theory)
    if not ex or ex["verdict"] != "MI":
        return None
    Q, c = np.asarray(ex["offset"], float), np.asarray(ex["curve"], float)
    grows = np.isfinite(c) & (c > 0)
    if not grows.any():
        return None
    lo, hi = float(Q[grows].min()), float(Q[grows].max())
    ring = 2 * np.pi * np.arange(1, res.N // 2 + 1) / res.N
    if np.any(np.interp(ring, Q, np.where(grows, c, 0.0)) > 0):
        return None
    # the ring advised has an offset where the band grows at half its peak (at its edge
    # the rate is ~0, a run shows nothing): the samples at or above it about the peak
    top = int(np.argmax(np.where(grows, c, -np.inf)))
    half = np.concatenate([[False], np.where(grows, c, 0.0) >= c[top] / 2, [False]])
    rlo = float(Q[top - int(np.argmin(half[top + 1::-1])) + 1])
    rhi = float(Q[top + int(np.argmin(half[top + 1:])) - 1])
    from common.rings import advised_ring  # one that keeps k first, as a model's point

    n, same = advised_ring(rlo, rhi, res.N, round(res.k * res.N / (2 * np.pi)))
    return (f"note: the band of the '{res.exact_theory}' theory (offsets {lo:.3g} to "
            f"{hi:.3g} rad/site, the infinite chain's) holds no offset 2 pi j / N of the ring of N = {res.N} (the smallest "
            f"{2 * math.pi / res.N:.3g}): no ring mode grows, so a run shows no MI here"
            + (f"; N = {n} with --k {res.k:.9g} samples it (a ring that carries this k)"
               if n and same else
               f"; N = {n} samples it (k snaps to 2 pi m / N there)" if n else
               f"; no ring up to N = {64 * res.N} has an offset where it grows at half its "
               "peak"))


def _why_no_gain(res, mat, case, amplitude) -> str | None:
    """Where the exact theory has no growing sideband but the semi-discrete NLS has one,
    one line on why: the exact band at a quarter of the amplitude tells a band that closes
    as the amplitude grows from one the lattice never has at this k."""
    import numpy as np

    from numerics.theory import theory_gain

    ex = res.theories.get(res.exact_theory)
    nls = res.theories.get("semi-discrete NLS")
    if not ex or not nls or ex["verdict"] != "stable" or nls["verdict"] != "MI":
        return None
    small = amplitude / 4
    try:
        curve = theory_gain(res.exact_theory, mat, case, res.k, amplitude=small,
                            offset=ex["offset"])
    except ValueError:
        return None
    peak = float(np.nanmax(curve)) if np.size(curve) else 0.0
    if peak > 0:
        return (f"note: the {res.exact_theory} has no growing sideband at amplitude "
                f"{amplitude:g} but has one at {small:g} (peak gain {peak:.3g} /T): its band "
                "closes between these amplitudes, where the NLS (the small-amplitude limit) "
                "keeps it open; a smaller --amplitude shows the instability")
    return (f"note: the {res.exact_theory} has no growing sideband at amplitude {amplitude:g}"
            f" nor at {small:g}: at this k the lattice's sidebands do not grow where the NLS "
            "says they do (a discreteness effect beyond the NLS)")


def _table(rows, units=None) -> str:
    """The theories' table in lattice units and, with --physical (``units`` with seconds
    and metres), the same rates, times and offsets in 1/s, s and rad/m beside them."""
    def num(v, f=1.0):
        return f"{v * f:.4g}" if math.isfinite(v) else "-"

    def efold(rate, f=1.0):
        return f"{f / rate:.4g}" if math.isfinite(rate) and rate > 0 else "-"

    s = getattr(units, "seconds_per_T", None)
    a = getattr(units, "metres_per_site", None)
    head = ("theory", "verdict", "peak gain (1/T)", "e-folding (T)", "at q - k (rad/site)",
            "half-gain edge q - k") + (("peak gain (1/s)", "e-folding (s)") if s else ()) \
        + (("at q - k (rad/m)",) if a else ())
    cells = [head] + [(r[0], r[1], num(r[2]), efold(r[2]), num(r[3]), num(r[4]))
                      + ((num(r[2], 1 / s), efold(r[2], s)) if s else ())
                      + ((num(r[3], 1 / a),) if a else ())
                      for r in rows]
    widths = [max(len(c[i]) for c in cells) for i in range(len(head))]
    lines = ["  ".join(c.ljust(w) for c, w in zip(row, widths)) for row in cells]
    lines.insert(1, "  ".join("-" * w for w in widths))
    return "\n".join(lines)


def _figure(th, meas, k, args, amplitude, mat=None, no_rate=None) -> bytes:
    """point.png's bytes."""
    from scenes import plt

    fig, ax = plt.subplots(figsize=(7, 4), layout="constrained")
    if meas:
        ax.errorbar(meas["offset"], meas["sigma_by_offset"], yerr=meas["std_by_offset"],
                    fmt=".", ms=3, lw=0.5,
                    label=(f"simulated ({meas['seeds']} of {args.seeds} seeds with a linear "
                           "stage" if meas["seeds"] < args.seeds
                           else f"simulated ({meas['seeds']} seeds") + ")")
    for (name, t), style in zip(th.items(), ("k--", "C2-", "C3-")):
        ax.plot(t["offset"], t["curve"], style, lw=1, label=f"{name} (theory)")
    tops = [np.nanmax(t["curve"]) for t in th.values() if np.any(np.isfinite(t["curve"]))]
    if meas:
        tops.append(float(np.max(meas["sigma"])))
    top = max([v for v in tops if np.isfinite(v)], default=0.0)
    # what is missing is said on the figure, never an empty axes (a failed run, no theory)
    missing = [f"simulated: {no_rate}"] if args.simulate and not meas and no_rate else []
    missing += [f"{n}: {t['reason']}" for n, t in th.items()
                if "reason" in t and not np.any(np.isfinite(t["curve"]))]
    if missing:
        ax.text(0.02, 0.97, "\n".join(missing), transform=ax.transAxes, va="top",
                fontsize=7, wrap=True, bbox=dict(facecolor="w", edgecolor="0.7"))
    if top > 0:
        ax.set_ylim(-0.1 * top, 1.4 * top)
    else:  # nothing grows: say so instead of an empty plot on a 1e-12 axis
        ax.set_ylim(-1, 1)
        if meas or any(np.any(np.isfinite(t["curve"])) for t in th.values()):
            ax.text(0.5, 0.6, "stable: no growing sideband in any theory" +
                    (" or the simulation" if meas else ""), transform=ax.transAxes,
                    ha="center", fontsize=10)
    ax.set_xlabel(r"sideband offset $Q = |q - k|$ (rad/site): sidebands at $k \pm Q$")
    ax.set_ylabel(r"growth rate $\sigma$ (1/T)")
    ax.set_title((f"alpha = {mat.alpha:g}, K_s = {mat.K_s:g}, K_theta = {mat.K_theta:g}; "
                  if mat is not None else "")
                 + f"case {args.case}\n$k$ = {k:.4g}, amplitude {amplitude:g} rad, "
                 f"start {args.start}", fontsize=9)
    ax.legend(fontsize=7)
    import io

    buf = io.BytesIO()
    fig.savefig(buf, format="png", dpi=110)
    plt.close(fig)
    return buf.getvalue()
