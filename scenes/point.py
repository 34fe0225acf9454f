"""`flexmm point`: the three theories of MI at one point of any material, and optionally
the simulation that checks them (measured sigma(q), verdict, figure)."""

from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np

from common.files import write_text
from common import paper
from numerics import Material, initial_condition, simulate, snap_wavenumber
from numerics.lattice import (DECIDE_E_FOLDINGS, GROWTH_THRESHOLD, LINEAR_STAGE_RULE,
                              band_summary, grows_beyond_threshold, paper_start_undefined,
                              run_length, simulated_verdict)
from numerics.maps import cell_step, growth_of
from numerics.theory import nls_undefined, predict_growth
from numerics.lattice import checks
from numerics.theory import PAPER_START, THEORIES, measure_gain, theory_gain

from .coefficients import coefficients, weak_nonlinearity_note

#: sideband offsets Q = |q - k| searched for the theories' bands (lattice units): the
#: whole zone, as the map searches it (sidebands k + Q beyond pi fold back, k - Q below 0
#: too: a band at any offset is found, whatever k)
Q_GRID = np.linspace(0, math.pi, 3001)
#: a simulated point records its spectrum every SAVE_EVERY T (and predicts those records)
SAVE_EVERY = 5.0
#: the NLS theories' small parameter (their formulas take the paper's eps, A0)
EPS = paper.EPS


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
        mat = Material.from_physical(*values)
        m, _, a, k_l = values[:4]
        return mat, Units.physical(m, k_l, a)
    missing = [n for n, v in (("--alpha", args.alpha), ("--K-s", args.K_s),
                              ("--K-theta", args.K_theta)) if v is None]
    if missing:
        raise ValueError(f"missing {', '.join(missing)} (or give --physical m,J,a,k_l,k_s,"
                         "k_theta)")
    for name, v in (("--alpha", args.alpha), ("--K-s", args.K_s), ("--K-theta", args.K_theta)):
        checks.positive(name, v)  # the wording every command uses
    return Material(args.alpha, args.K_s, args.K_theta), Units()


#: points of the paper-start exact curve (Hill's method on the torus: ~0.13 s per offset):
#: this many over the zone, and as many again around the peak resonance_map locates
START_CURVE_POINTS = 24


def _start_grid(material, case, k, amplitude):
    """q of the paper-start curve: a coarse zone grid plus a dense window around the peak
    that ``resonance_map`` finds from the bands' resonance conditions (a coarse grid alone
    misses bands narrower than its spacing)."""
    from numerics.maps import resonance_map

    res = resonance_map(k, case=case, material=material, K_theta=material.K_theta,
                        amplitude=amplitude, start="paper")
    qp = abs(float(res["q_peak"]))
    Q = [np.linspace(0.02, math.pi, START_CURVE_POINTS)]
    if math.isfinite(qp) and qp != 0:
        Q.append(qp * np.linspace(0.0, 2.5, 2 * START_CURVE_POINTS + 1))
        Q.append([qp])
    Q = np.unique(np.concatenate(Q))
    return Q[(Q > 1e-6) & (Q <= math.pi)]


def fold(q):
    """Wavenumbers folded into [0, pi] (a real field's q and -q, q and q + 2 pi, are one)."""
    return np.abs((np.asarray(q, float) + math.pi) % (2 * math.pi) - math.pi)


def offset_curve(q, sigma, spread, k):
    """A measured sigma over the rfft bins q (0 .. pi) as a curve over the sideband offset
    Q = 1 .. N/2 bins: a pair grows only where both its sidebands do, so sigma(Q) is the
    smaller of sigma at its two bins, fold(k + Q) and |k - Q|. A bin is shared by two
    pairs (k + Q beyond pi folds back onto another pair's sideband); the minimum keeps
    each band at its own offset, whatever k. Returns Q, sigma(Q) and the ``spread`` (per
    bin) of the bin that gave the minimum."""
    q, sigma = np.asarray(q, float), np.asarray(sigma, float)
    dq, top = q[1] - q[0], q.size - 1
    m = int(round(k / dq))
    d = np.arange(1, top + 1)
    N = int(round(2 * math.pi / dq))
    upper = np.where(m + d <= top, m + d, N - (m + d))  # fold(k + Q) into [0, pi]
    lower = np.abs(m - d)
    pick = np.where(sigma[upper] <= sigma[lower], upper, lower)
    return d * dq, sigma[pick], np.asarray(spread, float)[pick]


def theories(material, case, k, amplitude, start="travelling") -> dict:
    """{theory: curve over Q_GRID, band summary, verdict}: the paper NLS, the semi-discrete
    NLS, and the exact lattice theory for ``start`` (the travelling wave; with "paper" the
    state eq. `IC` launches, on START_CURVE_POINTS offsets)."""
    A0 = amplitude / (2 * EPS)
    names = THEORIES if start == "travelling" else THEORIES[:2] + (PAPER_START,)
    out = {}
    for th in names:
        try:
            Q = Q_GRID if th != PAPER_START else _start_grid(material, case, k, amplitude)
            q = fold(k + Q)  # the upper sideband's wavenumber (k + Q beyond pi folds)
            with np.errstate(all="ignore"):
                curve = theory_gain(th, material, case, k, offset=Q, eps=EPS, A0=A0)
        except ArithmeticError as exc:  # no plane wave (a resonance): say so, no verdict
            out[th] = {"offset": Q, "q": q, "curve": np.full(q.shape, np.nan),
                       "verdict": "undefined", "reason": f"no plane wave: {exc}",
                       "peak_gain": float("nan"), "peak_offset": float("nan"),
                       "band_edge": float("nan")}
            continue
        if not np.all(np.isfinite(curve)):  # no real omega, g1 = 0 or a resonance
            why = (nls_undefined(th, material, case, k) if th in THEORIES[:2] else None) \
                or "a singular gain curve"
            out[th] = {"offset": Q, "q": q, "curve": curve, "verdict": "undefined",
                       "reason": why,
                       "peak_gain": float("nan"), "peak_offset": float("nan"),
                       "band_edge": float("nan")}
            continue
        s = band_summary(k + Q, curve, k)  # over the offsets (band_summary: q - k)
        out[th] = {"offset": Q, "q": q, "curve": curve,
                   "verdict": "MI" if s["peak_gain"] > 0 else "stable", **s}
    return out


def snapped(k_requested: float, N: int):
    """k on a periodic chain of N sites: the nearest 2 pi m / N, whatever k was typed."""
    k_requested = checks.real("--k", k_requested, 0.0, math.pi)
    N = checks.integer("--N", N, 8, 10**6)  # the bounds of simulate and predict_growth
    return snap_wavenumber(k_requested, N, return_index=True)


def run_point(args, log=print) -> dict:
    mat, units = material_from(args)
    amplitude = checks.real("--amplitude", args.amplitude, 0.0, 1.5)
    N, k_req = args.N, args.k
    k, m = snapped(k_req, N)
    checks.integer("--seeds", args.seeds, 1, 1000)
    if args.t_end is not None:
        checks.real("--t-end", args.t_end, 0.0, 1e7)
    if args.start == "paper" and (why := paper_start_undefined(mat, k, ("travelling",))):
        raise ValueError(f"--start paper: {why}")
    if args.out:  # before any computation (a simulation may take minutes)
        from ._runner import prepare_output

        prepare_output(args.out, cache=False)
    A0 = amplitude / (2 * EPS)
    co_all = coefficients(mat, k, amplitude)
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
    note = weak_nonlinearity_note(co_all, amplitude, remedy="the exact rows below")
    if note:
        log(note)
    th = theories(mat, args.case, k, amplitude, args.start)
    result = {"material": {"alpha": mat.alpha, "K_s": mat.K_s, "K_theta": mat.K_theta,
                           "delta": mat.delta},
              "case": args.case, "N": N, "m": m, "k": k, "k_requested": k_req,
              "amplitude": amplitude, "eps": EPS, "A0": A0, "start": args.start,
              "units": {"time": "T = t sqrt(k_l/m)", "gain": "1/T", "wavenumber": "rad/site",
                        "curves": "theories: curve over offset Q = |q - k| (0 .. pi), q the "
                                  "upper sideband folded into [0, pi]; simulated: sigma per "
                                  "rfft bin q, and sigma_by_offset (the smaller of a pair's "
                                  "two sidebands)",
                        "seconds_per_T": units.seconds_per_T,
                        "metres_per_site": units.metres_per_site},
              "semidiscrete_nls": {"omega": co["omega"], "v_g": co["v_g"], "g1": co["g1"],
                                   "g2": co[args.case]["g2"], "g": co[args.case]["g"]},
              "theories": {n: {key: (v.tolist() if isinstance(v, np.ndarray) else v)
                               for key, v in t.items()} for n, t in th.items()}}
    rows = [(n, t["verdict"], t["peak_gain"], t["peak_offset"], t["band_edge"])
            for n, t in th.items()]
    meas = None
    exact_name = "exact lattice" if args.start == "travelling" else PAPER_START
    exact = th[exact_name]["peak_gain"]
    # T from the fastest predicted rate: enough e-foldings to decide, within a stated cap
    length = run_length(exact if math.isfinite(exact) else 0.0)
    t_end = args.t_end or length.t_end
    seeds = checks.integer("--seeds", args.seeds, 1, 1000)
    # the growth factor the simulation measures, predicted from each seed's initial state
    # (records every 5 T, as the simulation below saves them)
    try:
        pred = predict_growth(mat, args.case, k, amplitude, start=args.start, N=N,
                              t_end=t_end, seed=0, draws=seeds - 1,
                              records=max(2, min(4000, int(round(t_end / SAVE_EVERY)))))
        predicted = [pred.growth, *pred.growth_draws.tolist()]
        result["predicted"] = {
            "growth": predicted, "verdict": simulated_verdict(predicted, t_end).word,
            "t_end": t_end, "seeds": seeds, "rate": pred.rate,
            "linear": pred.linear, "approximate": pred.approximate,
            "method": "linear response of each seed's initial state (numerics.theory."
                      "predict_growth)"}
    except ArithmeticError as exc:
        predicted = None
        result["predicted"] = {"growth": None, "verdict": "undefined",
                               "reason": str(exc).splitlines()[0]}
    if args.simulate:
        runs = []

        def sim(**kw):
            run = simulate(**kw)
            runs.append(run)
            return run

        # method and step as a map cell picks them: from the accuracy the growth factor
        # needs over t_end (not the paper's RK4 at dt = 0.05, too coarse for stiff
        # materials), the step a whole fraction of the 5 T between records
        method, dt = cell_step(initial_condition(mat, args.case, N, k, amplitude, 1e-3, 0,
                                                 args.start), mat, args.case, t_end)
        dt = SAVE_EVERY / math.ceil(SAVE_EVERY / dt - 1e-9)
        meas = measure_gain(sim, range(args.seeds), material=mat, case=args.case, N=N, k=k,
                            amplitude=amplitude, t_end=t_end, method=method, dt=dt,
                            save_every=SAVE_EVERY, start=args.start, progress=None,
                            energy_tolerance=1.0)
        growths = [growth_of(r.t, r.theta_hat, r.U_hat, r.m, r.N) for r in runs]
        # no seed with a linear stage (linear_stage's rule): no rate to fit, shown as "-",
        # not as a gain of 0
        if meas:  # sigma over the offset Q, once: the table, the JSON and the figure
            meas["offset"], meas["sigma_by_offset"], meas["std_by_offset"] = offset_curve(
                meas["q"], meas["sigma"], meas["sigma_std"], k)
        s = band_summary(k + meas["offset"], meas["sigma_by_offset"], k) if meas else \
            {"peak_gain": float("nan"), "peak_offset": float("nan"), "band_edge": float("nan"),
             "no_rate": f"no seed had a linear stage to fit a rate over ({LINEAR_STAGE_RULE})"}
        sv = simulated_verdict([g["growth"] for g in growths], t_end, s["peak_gain"])
        # the theories keep their physical verdict; "grows 20x within T" is an observable
        for n, r in zip(th, rows):
            result["theories"][n]["grows_beyond_threshold_within_t_end"] = (
                bool(grows_beyond_threshold(r[2], t_end)) if math.isfinite(r[2]) else None)
        rows.append((f"simulated ({args.seeds} seeds, N = {N}, T = {t_end:g}, {method} "
                     f"dt = {dt:.3g})", sv.word, s["peak_gain"], s["peak_offset"],
                     s["band_edge"]))
        result["simulated"] = {**s, **sv.to_dict(), "t_end": t_end,
                               "seeds": args.seeds, "method": method, "dt": dt,
                               "growth": [g["growth"] for g in growths],
                               "growth_field": [g["growth_field"] for g in growths],
                               "criterion": f"MI when most seeds' largest non-carrier theta "
                                            f"or U component grows more than "
                                            f"{GROWTH_THRESHOLD:g}x within t_end; no growth "
                                            f"within T below sqrt({GROWTH_THRESHOLD:g})x; "
                                            "undetermined between",
                               "peak_gain": s["peak_gain"],
                               **({"q": meas["q"].tolist(), "sigma": meas["sigma"].tolist(),
                                   "sigma_std": meas["sigma_std"].tolist(),
                                   "offset": meas["offset"].tolist(),
                                   "sigma_by_offset": meas["sigma_by_offset"].tolist()}
                                  if meas else {})}
    log("")
    if predicted is not None:
        log(f"growth factor within T = {t_end:g} (the largest non-carrier component over the "
            f"carrier, per seed): predicted "
            + ", ".join(f"{g:.3g}x" for g in predicted)
            + ("; measured " + ", ".join(f"{g['growth']:.3g}x" for g in growths)
               if args.simulate else "")
            + ("" if pred.linear else " (the prediction leaves the linear stage: MI, the "
               "factor an upper bound)"))
        if (np.median(predicted) > GROWTH_THRESHOLD
                and not grows_beyond_threshold(pred.rate, t_end)):
            log(f"note: no Hill mode grows fast enough for {GROWTH_THRESHOLD:g}x within T "
                f"(fastest {pred.rate:.3g} /T): the predicted factor is the linear response "
                "itself (modes that beat, a transient), as the run will show it, not an "
                "exponential instability")
        side = th[exact_name]["peak_gain"]
        if (grows_beyond_threshold(pred.rate, t_end) and math.isfinite(side)
                and pred.rate > 1.1 * side):
            log(f"note: the fastest growing Hill mode ({pred.rate:.4g} /T) is not a sideband "
                f"pair, which the '{exact_name}' row shows ({side:.4g} /T): a map's exact_all "
                "column counts every mode")
    else:
        log(f"growth factor within T = {t_end:g}: no prediction ({result['predicted']['reason']})")
    log("verdicts: a theory's MI = the plane wave is unstable (peak gain > 0, however "
        "slow); a run's: MI (grew more than "
        f"{GROWTH_THRESHOLD:g}x), no growth within T, or undetermined")
    if args.simulate:
        log(f"grows more than {GROWTH_THRESHOLD:g}x within T = {t_end:g} (theories: exp(peak "
            "gain x T)): " + ", ".join(
                f"{n} {'yes' if t['grows_beyond_threshold_within_t_end'] else 'no'}"
                for n, t in result["theories"].items()
                if t.get("grows_beyond_threshold_within_t_end") is not None)
            + "; measured " + ", ".join(f"{g['growth']:.3g}x" for g in growths))
    if length.capped and not args.t_end:
        log(f"note: {length.note()} decide (the cap T = {length.cap:g} keeps a point "
            "within about a minute)")
    elif args.t_end and length.rate * t_end < DECIDE_E_FOLDINGS:
        log(f"note: --t-end {t_end:g} holds {length.rate * t_end:.2g} e-foldings of the "
            f"fastest predicted rate {length.rate:.4g} /T; {DECIDE_E_FOLDINGS:g} decide: "
            f"--t-end {length.decides_at:g} would")
    log(_table(rows, units))
    for n, t in th.items():
        if "reason" in t:
            log(f"{n}: {t['reason']}")
    if args.simulate:
        log(f"simulated verdict: {result['simulated']['text']}")
    if args.simulate and "no_rate" in result["simulated"]:
        log(f"simulated: {result['simulated']['no_rate']}")
    # the most faithful row that grows: the simulation, else the exact theory, else an NLS
    growing = [r for r in rows if math.isfinite(r[2]) and r[2] > 0]
    best = None
    for kind in ("simulated", "exact lattice", "semi-discrete NLS", "paper NLS"):
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
    if args.out:
        out = Path(args.out)
        out.mkdir(parents=True, exist_ok=True)
        from ._runner import _strict

        _figure(out, th, meas, k, args, amplitude, mat,
                result.get("simulated", {}).get("no_rate"))
        write_text(out / "point.json", json.dumps(_strict(result), indent=2) + "\n")
        log(f"wrote {out / 'point.json'} and {out / 'point.png'}")
    return result


def _table(rows, units=None) -> str:
    head = ("theory", "verdict", "peak gain (1/T)", "e-folding (T)", "at q - k (rad/site)",
            "half-gain edge q - k")
    cells = [head] + [(r[0], r[1], f"{r[2]:.4g}" if math.isfinite(r[2]) else "-",
                       f"{1 / r[2]:.4g}" if math.isfinite(r[2]) and r[2] > 0 else "-",
                       f"{r[3]:.4g}", f"{r[4]:.4g}") for r in rows]
    widths = [max(len(c[i]) for c in cells) for i in range(len(head))]
    lines = ["  ".join(c.ljust(w) for c, w in zip(row, widths)) for row in cells]
    lines.insert(1, "  ".join("-" * w for w in widths))
    return "\n".join(lines)


def _figure(out, th, meas, k, args, amplitude, mat=None, no_rate=None):
    from common.files import atomic_write

    from ._plotting import plt

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
    with atomic_write(out / "point.png", mode=None) as tmp:
        fig.savefig(tmp, format="png", dpi=110)
    plt.close(fig)
