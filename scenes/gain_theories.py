"""Beyond the paper: which theory of MI do the simulations obey?

At the two unstable test points (A0 = 0.8, 1, 1.4), at case II with k = 0.704, and at three
case II points where the paper's start and the travelling wave disagree (free U waves
launched by eq. `IC` pump rotational pairs the travelling wave leaves alone), the measured
growth rate of every sideband (linear-stage fits, mean and spread over seeds) from the
paper's initial condition (eq. `IC`) and from the exact travelling wave, against the
paper's NLS (eqs. `NLS`, `Omega_I`), the semi-discrete NLS
(generated/lattice_coefficients.py), the exact lattice gain of the travelling wave
(``numerics.mi_gain``) and of the state eq. `IC` launches (``mi_gain(start="paper")``).
Reports each theory's relative error of the peak gain and of the half-gain band edge, each
start's verdict (grows > 20x within the run) predicted and simulated, and each theory's
verdict on the four paper runs. About 4 min (quick about 1 min).
"""

from __future__ import annotations

import numpy as np

from common import paper
from numerics import Material
from numerics.lattice import GROWTH_THRESHOLD, band_summary, grows_beyond_threshold
from numerics.theory import (
    PAPER_START,
    THEORIES,
    gain_spectrum,
    measurement_length,
    mi_gain,
    relative_errors,
    theory_gain,
)

from ._plotting import Q_LABEL, SIGMA_LABEL, figure, reserve_quick_stamp
from ._registry import Scene, check, register
from ._runs import QUICK_N, measured_gain

#: (label, point, case, A0, k or None for the point's own, delta or None for the point's)
POINTS = (
    ("blue II A0=1", "blue", "coupled", 1.0, None, None),
    ("green I A0=1", "green", "rotation", 1.0, None, None),
    ("blue II A0=0.8", "blue", "coupled", 0.8, None, None),
    ("blue II A0=1.4", "blue", "coupled", 1.4, None, None),
    ("green I A0=0.8", "green", "rotation", 0.8, None, None),
    ("green I A0=1.4", "green", "rotation", 1.4, None, None),
    ("blue II k=0.704", "blue", "coupled", 1.0, 2 * np.pi * 28 / 250, None),
    # the starts disagree: eq. `IC` is unstable, the travelling wave is not (found by
    # scanning delta < 0 near k ~ 1.1-1.2, where omega_U(2k) = omega(k1) + omega(k2) with
    # k1 + k2 = 2k has solutions)
    ("II d=-0.0051 k=1.131", "green", "coupled", 1.0, 2 * np.pi * 90 / 500, -0.0051),
    ("II d=-0.006 k=1.169", "green", "coupled", 1.0, 2 * np.pi * 93 / 500, -0.006),
    ("II d=-0.007 k=1.194", "green", "coupled", 1.0, 2 * np.pi * 95 / 500, -0.007),
)
#: the two starts compared: eq. `IC` ("paper") and the exact travelling wave
STARTS = ("paper", "travelling")
#: the exact gain must match the measurement from the travelling wave within this
EXACT_TOLERANCE = 0.05
#: the paper-start theory against the measurement from eq. `IC`: peak, band edge (the
#: issue's goals, full runs); quick runs (N <= 250, 2 seeds) are held to EXACT_TOLERANCE
PAPER_START_TOLERANCE = (0.02, 0.03)


def _verdicts():
    """Each theory's verdict on the four paper runs (A0 = 1)."""
    q = np.linspace(0, np.pi, 2001)
    out = {}
    for point in paper.POINTS:
        mat, kk = Material.paper(point), paper.k(point)
        for case in ("rotation", "coupled"):
            v = {th: "MI" if theory_gain(th, mat, case, kk, offset=q - kk, eps=paper.EPS).max() > 0
                 else "stable" for th in THEORIES}
            # U-pair modes exist in case II only (seen in the green II run's U spectrum)
            v["exact lattice, U modes too"] = "n/a" if case == "rotation" else (
                "MI" if mi_gain(mat, case, kk, 2 * paper.EPS, q - kk, modes="all").max() > 0
                else "stable")
            out[f"{point}-{case}"] = v
    return out


def _quick_N(k):
    """Smallest chain of the quick runs on which k is a lattice wavenumber."""
    for n in (100, 200, 250, 500):
        if abs(k * n / (2 * np.pi) - round(k * n / (2 * np.pi))) < 1e-9:
            return n
    return 500


def _curve(ctx, key, theory, mat, case, k, q):
    return ctx.memo("gain", dict(key, theory=theory, k=k, q=[q[0], q[-1], q.size]),
                    lambda: theory_gain(theory, mat, case, k, offset=q - k, eps=paper.EPS,
                                        A0=key["A0"]))


def _verdict(peak, t_end):
    return "MI" if grows_beyond_threshold(peak, t_end) else "stable"


def compute(ctx):
    data, rows, checks, starts = {"labels": [p[0] for p in POINTS]}, [], [], []
    qf = np.linspace(0, np.pi, 3001)
    qs = np.linspace(0, np.pi, 301 if ctx.quick else 1201)  # paper-start theory: 0.2 s each
    data["q_theory"], data["q_start"] = qf, qs
    for label, point, case, A0, kk, delta in ctx.progress(POINTS, "gain-theories: points"):
        mat = Material.paper(point) if delta is None else Material(paper.ALPHA, paper.K_S,
                                                                   paper.K_S - delta)
        k0 = paper.k(point) if kk is None else kk
        quick_N = _quick_N(k0) if kk is not None else QUICK_N[point]
        N = quick_N if ctx.quick else paper.N
        key = {"material": [mat.alpha, mat.K_s, mat.K_theta], "case": case, "eps": paper.EPS,
               "A0": A0}
        exact_peak = float(_curve(ctx, key, "exact lattice", mat, case, k0, qf).max())
        start_curve = _curve(ctx, key, PAPER_START, mat, case, k0, qs)
        t_end = measurement_length(max(exact_peak, float(start_curve.max())))
        meas = {}
        for start in STARTS:
            m = measured_gain(ctx, point, case, A0, t_end=t_end, quick_N=quick_N, k=k0,
                              start=start, material=mat)
            if m is not None:
                meas[start] = m
                data.update({f"{label}/{start}/q": m["q"], f"{label}/{start}/sigma": m["sigma"],
                             f"{label}/{start}/sigma_std": m["sigma_std"]})
        kr = meas["travelling"]["k"] if "travelling" in meas else k0
        curves = {th: _curve(ctx, key, th, mat, case, kr, qf) for th in THEORIES}
        data.update({f"{label}/{th}": c for th, c in curves.items()})
        data[f"{label}/{PAPER_START}"] = start_curve
        data[f"{label}/k"] = kr
        predicted = {th: band_summary(qf, c, kr) for th, c in curves.items()}
        predicted[PAPER_START] = band_summary(qs, start_curve, kr)
        theory_of = {"travelling": "exact lattice", "paper": PAPER_START}
        spec = _labels(mat, case, k0, A0, qs, start_curve)
        for start in STARTS:
            th = theory_of[start]
            starts.append({"point": label, "start": start, "t_end": t_end,
                           "predicted_peak": predicted[th]["peak_gain"],
                           "predicted": _verdict(predicted[th]["peak_gain"], t_end),
                           "simulated": "MI" if start in meas else "stable",
                           "measured_peak": (band_summary(meas[start]["q"],
                                                          meas[start]["sigma"], kr)["peak_gain"]
                                             if start in meas else None),
                           **(spec if start == "paper" else {})})
        for start, m in meas.items():
            m_sum = band_summary(m["q"], m["sigma"], kr)
            row = {"point": label, "start": start, "t_end": t_end, "N": N, "measured": m_sum}
            for th in THEORIES + (PAPER_START,):
                row[th] = {"peak_gain": predicted[th]["peak_gain"],
                           "band_edge": predicted[th]["band_edge"],
                           **relative_errors(m_sum, predicted[th])}
            rows.append(row)
            th = theory_of[start]
            if not row[th]["peak_gain"]:
                continue  # no sideband band: the growth is judged below (other modes)
            tol = ((EXACT_TOLERANCE, EXACT_TOLERANCE) if start == "travelling" or ctx.quick
                   else PAPER_START_TOLERANCE)
            ex = row[th]
            # a band that reaches the zone edge (pi) has no half-gain edge to compare
            judged = ("peak_error", "edge_error") if np.isfinite(ex["band_edge"]) \
                else ("peak_error",)
            ok = all(ex[e] is not None and abs(ex[e]) < t
                     for e, t in zip(judged, tol))
            name = ("exact lattice gain vs measured (travelling-wave start)"
                    if start == "travelling" else "paper-start exact gain vs measured (eq. IC)")
            edge = (f"band edge within {100 * tol[1]:g}%" if len(judged) == 2
                    else "no band edge (the band reaches pi)")
            checks.append(check(f"gain-theories {label}: {name}, peak within "
                                f"{100 * tol[0]:g}% and {edge}",
                                f"peak {ex['peak_gain']:.4g}, edge {ex['band_edge']:.4g}",
                                f"errors {_pct(ex['peak_error'])}, "
                                f"{_pct(ex['edge_error'])}", ok))
        for st in starts[-2:]:
            checks.append(_verdict_check(label, st, mat, case, k0, A0, qs))
    data.update(alpha=paper.ALPHA, K_s=paper.K_S, eps=paper.EPS, noise=paper.NOISE)
    verdicts = ctx.memo("verdicts", {"points": {p: dict(v) for p, v in paper.POINTS.items()},
                                     "alpha": paper.ALPHA, "K_s": paper.K_S, "eps": paper.EPS},
                        _verdicts)
    return data, {"rows": rows, "starts": starts, "verdicts": verdicts, "checks": checks}


def _verdict_check(label, st, mat, case, k, A0, q):
    """The start's verdict, predicted against simulated. Theta can also grow through a
    mode that is no sideband pair (a U-pair mode, 2 Omega = omega_U(q) + omega_U(q - 2k),
    whose theta part grows with it): when the sideband theory says stable and the run
    grows, the all-modes theory must predict that growth, rate within 5%."""
    name = (f"gain-theories {label}: verdict from the {st['start']} start (grows > "
            f"{GROWTH_THRESHOLD:g}x within T = {st['t_end']:g})")
    if st["predicted"] == st["simulated"] or st["simulated"] == "stable":
        return check(name, f"{st['predicted']} (sideband peak {st['predicted_peak']:.3g})",
                     st["simulated"], st["predicted"] == st["simulated"])
    start = "paper" if st["start"] == "paper" else "travelling"
    g = gain_spectrum(mat, case, k, 2 * paper.EPS * A0, q[1:] - k, start=start,
                      modes="all", harmonics=1)
    i = int(np.argmax(g.sigma))
    st.update(all_modes_peak=float(g.sigma[i]), all_modes_field=str(g.field[i]),
              all_modes_wavenumber=float(g.wavenumber[i]))
    err = st["measured_peak"] / g.sigma[i] - 1 if g.sigma[i] > 0 else float("inf")
    ok = _verdict(g.sigma[i], st["t_end"]) == "MI" and abs(err) < EXACT_TOLERANCE
    return check(name + "; no sideband band: the all-modes theory, rate within 5%",
                 f"MI through a {g.field[i]} mode at {g.wavenumber[i]:.3f} (peak "
                 f"{g.sigma[i]:.3g})", f"MI, measured theta peak {st['measured_peak']:.3g} "
                 f"({_pct(err)})", ok)


def _labels(mat, case, k, A0, q, curve):
    """What grows at the paper-start theory's peak: field, wavenumbers, frequency."""
    if not curve.max() > 0:
        return {"field": "", "wavenumbers": [], "frequency": None}
    q0 = q[int(np.argmax(curve))] - k
    g = gain_spectrum(mat, case, k, 2 * paper.EPS * A0, [q0], start="paper", harmonics=1)
    pair = sorted({round(abs(np.mod(k + s * q0 + np.pi, 2 * np.pi) - np.pi), 4)
                   for s in (1, -1)})
    return {"field": str(g.field[0]), "wavenumbers": pair, "frequency": float(g.frequency[0])}


def _pct(x):
    return "n/a" if x is None or not np.isfinite(x) else f"{100 * x:+.1f}%"


#: how the parameters in a point's label read in a title
_SYMBOLS = {"A0": "A_0", "d": r"\delta", "k": "k"}


def _title(label: str) -> str:
    """A point's label as a title: "II d=-0.006 k=1.169" -> case II, delta = ..., k = ..."""
    words = []
    for w in label.split():
        name, _, value = w.partition("=")
        if value:
            words.append(f"${_SYMBOLS[name]} = {value}$")
        else:
            words.append({"I": "case I", "II": "case II"}.get(w, f"{w} point"))
    return ", ".join(words)


def plot(data):
    fig, axes = figure(2, 5, figsize=(18, 7.5))
    axes = axes.ravel()
    qf, qs = data["q_theory"], data["q_start"]
    for ax, label in zip(axes, data["labels"]):
        for start in STARTS:
            if f"{label}/{start}/q" not in data:
                continue
            ax.errorbar(data[f"{label}/{start}/q"], data[f"{label}/{start}/sigma"],
                        yerr=data[f"{label}/{start}/sigma_std"],
                        fmt="." if start == "travelling" else "x", ms=3, lw=0.5,
                        color="C0" if start == "travelling" else "C4",
                        label="simulation, " + ("travelling-wave start" if start == "travelling"
                                                else "eq. IC start"))
        top = max([data[f"{label}/{th}"].max() for th in THEORIES + (PAPER_START,)]
                  + [1e-6])
        for th, style in zip(THEORIES, ("k--", "C2-", "C3-")):
            ax.plot(qf, data[f"{label}/{th}"], style, lw=1, label=f"theory: {th}")
        ax.plot(qs, data[f"{label}/{PAPER_START}"], "C1:", lw=1.5, label=f"theory: {PAPER_START}")
        if f"{label}/k" in data:  # the pair's other member, k - q (eq. IC is not symmetric)
            ax.plot(np.abs(2 * data[f"{label}/k"] - qs), data[f"{label}/{PAPER_START}"],
                    "C1:", lw=1.5)
        ax.set_ylim(-0.1 * top, 1.3 * top)
        ax.set_title(_title(label), fontsize=10, pad=14)  # above the y offset text
        ax.set_xlabel(Q_LABEL)
        ax.set_ylabel(SIGMA_LABEL)
        ax.ticklabel_format(axis="y", style="sci", scilimits=(-2, 2), useMathText=True)
    for ax in axes[len(data["labels"]):]:
        ax.axis("off")
    handles, labels = axes[0].get_legend_handles_labels()
    fig.legend(handles, labels, loc="outside lower center", ncols=3, fontsize=9)
    fig.suptitle(r"Sideband growth rate $\sigma(q)$: simulations (points, mean and spread over "
                 "seeds) against four theories (lines), lattice units")
    return reserve_quick_stamp(fig, data)


def report(summary):
    if not summary.get("rows"):
        return []
    cols = THEORIES + (PAPER_START,)
    lines = ["## Which theory the simulations obey (scene gain-theories)", "",
             "Relative error of each theory's peak gain and half-gain band edge against "
             "the measured sigma(q) (measured / theory - 1). Start: `paper` = eq. `IC` "
             "(U at rest), `travelling` = the lattice's exact plane wave; n/a: the "
             "theory predicts no gain there. The last column is the theory of the state "
             "eq. `IC` launches (travelling wave + free waves, `mi_gain(start=\"paper\")`): "
             "it answers the paper-start rows.", "",
             "| point | start | " + " | ".join(f"{t}: peak, edge" for t in cols) + " |",
             "|---|---|" + "---|" * len(cols)]
    for r in summary["rows"]:
        cells = [f"{_pct(r[t]['peak_error'])}, {_pct(r[t]['edge_error'])}" for t in cols]
        lines.append(f"| {r['point']} | {r['start']} | " + " | ".join(cells) + " |")
    if summary.get("starts"):
        lines += ["", f"Verdicts by start (grows more than {GROWTH_THRESHOLD:g}x within the run): "
                  "predicted by the exact theory of that start (peak gain x T > ln "
                  f"{GROWTH_THRESHOLD:g}) and simulated (a linear stage of theta growth "
                  "found); for the paper start, what the theory says grows at its peak.", "",
                  "| point | start | T | predicted peak | predicted | measured peak | "
                  "simulated | grows (theory) |", "|---|---|---|---|---|---|---|---|"]
        for st in summary["starts"]:
            mp = "-" if st["measured_peak"] is None else f"{st['measured_peak']:.4g}"
            what = (f"{st['field']} at {', '.join(f'{w:.3f}' for w in st['wavenumbers'])} "
                    f"(freq {st['frequency']:.3f})" if st.get("field") else "-")
            lines.append(f"| {st['point']} | {st['start']} | {st['t_end']:g} | "
                         f"{st['predicted_peak']:.4g} | {st['predicted']} | {mp} | "
                         f"{st['simulated']} | {what} |")
    verdicts = summary["verdicts"]
    lines += ["", "Stability verdicts of the four paper runs (A0 = 1):", "",
              "| run | " + " | ".join(next(iter(verdicts.values()))) + " |",
              "|---|" + "---|" * (len(THEORIES) + 1)]
    for run, v in verdicts.items():
        lines.append(f"| {run} | " + " | ".join(v.values()) + " |")
    return lines


SCENE = register(Scene("gain-theories", "measured sigma(q) vs paper NLS, semi-discrete NLS, "
                       "exact lattice gain of the travelling wave and of the state eq. IC "
                       "launches, 10 points, both starts", "beyond the paper",
                       "~4 min (quick ~1 min)", True, compute, plot, report))
