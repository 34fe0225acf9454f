"""`flexmm point`: the three theories of MI at one point of any material, and optionally
the simulation that checks them (measured sigma(q), verdict, figure)."""

from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np

from common.files import write_text
from common import paper
from numerics import Material, simulate, snap_wavenumber
from numerics.lattice import GROWTH_THRESHOLD, band_summary
from numerics.maps import growth_of
from numerics.theory import THEORIES, measure_gain, measurement_length, theory_gain

#: offsets searched for the theories' bands (lattice units)
Q_GRID = np.linspace(0, math.pi, 3001)
#: the NLS theories' small parameter (their formulas take the paper's eps, A0)
EPS = paper.EPS


def material_from(args) -> Material:
    """From --alpha/--K-s/--K-theta, or --physical m,J,a,k_l,k_s,k_theta."""
    if args.physical:
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
        return Material.from_physical(*values)
    missing = [n for n, v in (("--alpha", args.alpha), ("--K-s", args.K_s),
                              ("--K-theta", args.K_theta)) if v is None]
    if missing:
        raise ValueError(f"missing {', '.join(missing)} (or give --physical m,J,a,k_l,k_s,"
                         "k_theta)")
    return Material(args.alpha, args.K_s, args.K_theta)


def theories(material, case, k, amplitude) -> dict:
    """{theory: curve, band summary, verdict} at offsets Q_GRID - k."""
    A0 = amplitude / (2 * EPS)
    out = {}
    for th in THEORIES:
        try:
            with np.errstate(all="ignore"):
                curve = theory_gain(th, material, case, k, Q_GRID - k, EPS, A0)
        except ArithmeticError as exc:  # no plane wave (a resonance): say so
            curve = np.full(Q_GRID.shape, np.nan)
            out[th] = {"curve": curve, "verdict": f"no plane wave ({exc})"[:60],
                       "peak_gain": float("nan"), "peak_offset": float("nan"),
                       "band_edge": float("nan")}
            continue
        if not np.all(np.isfinite(curve)):  # delta = 0 (g1 = 0) or k^2 = omega^2
            out[th] = {"curve": np.nan_to_num(curve), "verdict": "undefined (singular g)",
                       "peak_gain": float("nan"), "peak_offset": float("nan"),
                       "band_edge": float("nan")}
            continue
        s = band_summary(Q_GRID, curve, k)
        out[th] = {"curve": curve, "verdict": "MI" if s["peak_gain"] > 0 else "stable", **s}
    return out


def run_point(args, log=print) -> dict:
    mat = material_from(args)
    k_req = args.k
    N = args.N
    k, m = snap_wavenumber(k_req, N) if args.simulate else (float(k_req), None)
    if args.simulate and abs(k - k_req) > 1e-12:
        log(f"note: k = {k_req:g} snapped to 2 pi m / N = {k:.6g} (m = {m}, N = {N}), the "
            "nearest wavenumber a periodic chain of N sites carries; every row below uses it")
    th = theories(mat, args.case, k, args.amplitude)
    result = {"material": {"alpha": mat.alpha, "K_s": mat.K_s, "K_theta": mat.K_theta,
                           "delta": mat.delta},
              "case": args.case, "k": k, "k_requested": k_req, "amplitude": args.amplitude,
              "theories": {n: {key: v for key, v in t.items() if key != "curve"}
                           for n, t in th.items()}}
    rows = [(n, t["verdict"], t["peak_gain"], t["peak_offset"], t["band_edge"])
            for n, t in th.items()]
    if args.simulate:
        exact = th["exact lattice"]["peak_gain"]
        t_end = args.t_end or measurement_length(exact)
        runs = []

        def sim(**kw):
            run = simulate(**kw)
            runs.append(run)
            return run

        meas = measure_gain(sim, range(args.seeds), material=mat, case=args.case, N=N, k=k,
                            amplitude=args.amplitude, t_end=t_end,
                            save_every=5.0, start=args.start, progress=None,
                            energy_tolerance=1.0)
        growths = [growth_of(r.t, r.theta_hat, r.U_hat, r.m, r.N) for r in runs]
        verdict = sum(g["growth"] > GROWTH_THRESHOLD for g in growths) * 2 > len(growths)
        s = band_summary(meas["q"], meas["sigma"], k) if meas else \
            {"peak_gain": 0.0, "peak_offset": float("nan"), "band_edge": float("nan")}
        rows.append((f"simulated ({args.seeds} seeds, N = {N}, T = {t_end:g})",
                     "MI" if verdict else "stable", s["peak_gain"], s["peak_offset"],
                     s["band_edge"]))
        result["simulated"] = {"verdict": "MI" if verdict else "stable", **s, "t_end": t_end,
                               "N": N, "seeds": args.seeds, "start": args.start,
                               "growth": [g["growth"] for g in growths],
                               "growth_field": [g["growth_field"] for g in growths],
                               "criterion": f"growth > {GROWTH_THRESHOLD:g}x (the scenes')"}
        if args.out:
            _figure(Path(args.out), th, meas, k, args)
    log(_table(rows))
    if args.out:
        out = Path(args.out)
        out.mkdir(parents=True, exist_ok=True)
        from ._runner import _strict

        write_text(out / "point.json", json.dumps(_strict(result), indent=2) + "\n")
        log(f"wrote {out / 'point.json'}" + (f" and {out / 'point.png'}" if args.simulate
                                             else ""))
    return result


def _table(rows) -> str:
    head = ("theory", "verdict", "peak gain", "at q - k", "half-gain edge q - k")
    cells = [head] + [(r[0], r[1], f"{r[2]:.4g}", f"{r[3]:.4g}", f"{r[4]:.4g}") for r in rows]
    widths = [max(len(c[i]) for c in cells) for i in range(len(head))]
    lines = ["  ".join(c.ljust(w) for c, w in zip(row, widths)) for row in cells]
    lines.insert(1, "  ".join("-" * w for w in widths))
    return "\n".join(lines)


def _figure(out, th, meas, k, args):
    from common.files import atomic_write

    from ._plotting import plt

    fig, ax = plt.subplots(figsize=(7, 4))
    if meas:
        ax.errorbar(meas["q"], meas["sigma"], yerr=meas["sigma_std"], fmt=".", ms=3, lw=0.5,
                    label=f"measured ({meas['seeds']} seeds)")
    for (name, t), style in zip(th.items(), ("k--", "C2-", "C3-")):
        ax.plot(Q_GRID, t["curve"], style, lw=1, label=name)
    top = max(max(t["curve"].max() for t in th.values()), 1e-12)
    ax.set_ylim(-0.1 * top, 1.4 * top)
    ax.set_xlabel("q (rad per site)")
    ax.set_ylabel("growth rate sigma (1/T)")
    ax.set_title(f"case {args.case}, k = {k:.4g}, amplitude {args.amplitude:g}", fontsize=9)
    ax.legend(fontsize=7)
    fig.tight_layout()
    out.mkdir(parents=True, exist_ok=True)
    with atomic_write(out / "point.png", mode=None) as tmp:
        fig.savefig(tmp, format="png", dpi=110)
    plt.close(fig)
