"""Scenes: every figure of the paper (and two checks beyond it), declared as data.

A scene registers itself with :func:`scene`; ``flexmm scenes`` lists the registry and
the tests run every registered scene in quick mode. A scene returns its summary dict;
the runner writes ``summary.json``, the figure (PNG + PDF) and ``data.h5`` under
``OUT/NAME/``. Only simulation scenes start the simulator, through the on-disk cache.
"""

from __future__ import annotations

import json
import time
from dataclasses import dataclass, field
from pathlib import Path
from typing import Callable

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from generated import coefficients as co  # noqa: E402
from generated import lattice_coefficients as la  # noqa: E402

from . import _analysis as an  # noqa: E402
from ._cache import cached_simulate, write_h5  # noqa: E402
from ._hill import mi_gain, stability_map  # noqa: E402
from ._model import (Material, discrete_omega_longitudinal,  # noqa: E402
                     discrete_omega_rotation)

ALPHA, K_S = 2.5, 0.01851
POINTS = {"blue": {"k": 0.81681, "K_theta": 0.01551},
          "green": {"k": 0.92991, "K_theta": 0.02151}}
EPS, NOISE = 0.01, 1e-3
G_FUNCS = {"rotation": co.g_rotation, "coupled": co.g_coupled}
G2_FUNCS = {"rotation": co.g2_rotation, "coupled": co.g2_coupled}


def package_version() -> str:
    from importlib.metadata import PackageNotFoundError, version

    try:
        return version("flexmm-mi")
    except PackageNotFoundError:  # pragma: no cover
        return "unknown"


@dataclass(frozen=True)
class Scene:
    name: str
    description: str
    figure: str  # the paper's figure it reproduces, or "beyond the paper"
    runtime: str  # expected run time, full (quick)
    simulates: bool
    fn: Callable = field(repr=False)


REGISTRY: dict[str, Scene] = {}


def scene(name, description, figure, runtime, simulates):
    def deco(fn):
        if name in REGISTRY:
            raise ValueError(f"scene {name!r} registered twice")
        REGISTRY[name] = Scene(name, description, figure, runtime, simulates, fn)
        return fn
    return deco


@dataclass
class Context:
    """What a scene may use: where to write, quick or not, the seed, the cache."""

    out: Path
    quick: bool = False
    seed: int = 0
    force: bool = False
    cache_dir: Path | None = None

    def simulate(self, **params):
        params.setdefault("progress", None)
        return cached_simulate(self.cache_dir, self.force, **params)

    def save(self, fig, datasets: dict, attrs: dict):
        self.out.mkdir(parents=True, exist_ok=True)
        if self.quick:
            fig.text(0.99, 0.005, "QUICK MODE (reduced N / t_end / grid)", ha="right",
                     va="bottom", fontsize=7, color="red")
        fig.savefig(self.out / "figure.png", dpi=110)
        fig.savefig(self.out / "figure.pdf")
        plt.close(fig)
        attrs = dict(attrs, package_version=package_version(), quick=self.quick)
        write_h5(self.out / "data.h5", datasets, attrs)


def _image(ax, x, y, Z, **kw):
    """Raster image of Z over the uniform grids x, y (fast to draw and to save as PDF)."""
    return ax.imshow(Z, origin="lower", aspect="auto", interpolation="nearest",
                     extent=(x[0], x[-1], y[0], y[-1]), **kw)


def material(point: str) -> Material:
    return Material(ALPHA, K_S, POINTS[point]["K_theta"])


def theory(point: str, case: str, A0: float = 1.0) -> dict:
    p = dict(k=POINTS[point]["k"], alpha=ALPHA, K_s=K_S, K_theta=POINTS[point]["K_theta"])
    g = float(G_FUNCS[case](**p))
    g1 = float(co.g1(**p))
    out = {"g": g, "g1": g1, "g2": float(G2_FUNCS[case](**p)), "stable": bool(g < 0),
           "omega": float(co.omega(**p)), "v_g": float(co.group_velocity(**p))}
    if g > 0:
        out.update(K_c=float(co.mi_cutoff(g, A0)), K_m=float(co.mi_fastest(g, A0)),
                   peak_gain=float(EPS**2 * abs(g1) * co.mi_growth_rate(
                       co.mi_fastest(g, A0), g, A0)))
    return out


# --- theory-only scenes ----------------------------------------------------------------

@scene("fig2-dispersion", "discrete vs continuum dispersion, four K_theta (Fig. 2)",
       "Fig. 2 (disp_rel_example)", "<1 s", simulates=False)
def fig2(ctx: Context):
    """Fig. 2: eqs. `discrete1`, `discrete2` (solid) vs `continuum1`, `continuum2` (dashed).

    Checks the paper's claim that the continuum captures the lattice for q <= 1: records
    the largest relative gap of the rotational branch on q <= 1 for each K_theta.
    """
    kts = [1.534e-4, 0.1, 0.01551, 0.02151]
    q = np.linspace(0, np.pi, 200 if ctx.quick else 600)
    fig, axes = plt.subplots(2, 2, figsize=(8, 6), sharex=True)
    gaps, data = {}, {"q": q}
    for ax, kt, lab in zip(axes.flat, kts, "abcd"):
        m = Material(ALPHA, K_S, kt)
        wd2 = discrete_omega_rotation(q, m)
        with np.errstate(invalid="ignore"):
            wc2 = co.omega(q, ALPHA, K_S, kt)
        ax.plot(q, discrete_omega_longitudinal(q), "C0-", label="U, discrete1")
        ax.plot(q, q, "C0--", label="U, continuum1")
        ax.plot(q, wd2, "C3-", label="theta, discrete2")
        ax.plot(q, wc2, "C3--", label="theta, continuum2")
        ax.set_title(f"({lab}) K_theta = {kt:g}, delta = {K_S - kt:+.4g}", fontsize=9)
        ax.set_ylim(0, 3.2)
        sel = (q > 0) & (q <= 1)
        gaps[str(kt)] = float(np.max(np.abs(wc2[sel] - wd2[sel]) / wd2[sel]))
        data[f"discrete2_{lab}"], data[f"continuum2_{lab}"] = wd2, wc2
    axes[0, 0].legend(fontsize=7)
    for ax in axes[1]:
        ax.set_xlabel("q (rad per site)")
    for ax in axes[:, 0]:
        ax.set_ylabel("omega")
    fig.suptitle(f"Dispersion, alpha = {ALPHA}, K_s = {K_S}")
    fig.tight_layout()
    ctx.save(fig, data, {"alpha": ALPHA, "K_s": K_S, "K_theta": kts})
    return {"max_relative_gap_q_le_1": gaps,
            "checks": [{"check": "continuum vs discrete rotational branch, q <= 1 "
                        "(paper: 'captures well')", "theory": "gap small",
                        "numerics": f"max gap {max(gaps.values()):.2%}",
                        "pass": max(gaps.values()) < 0.05}]}


def _sign_grid(quick):
    n = 80 if quick else 400
    k = np.linspace(0.005, np.pi, n)
    delta = np.linspace(-0.015, 0.015, n)
    delta = delta[np.abs(delta) > 1e-9]
    return k, delta


@scene("fig3-g-sign", "sign of g over (k, delta): case I and case II for alpha = 1.5, 2.5, 3.5; "
       "plus semi-discrete NLS and exact lattice maps", "Fig. 3 (Panels_delta_map)",
       "~40 s (quick ~2 s)", simulates=False)
def fig3(ctx: Context):
    """Fig. 3: sign of g (white: g > 0, MI; black: g < 0), eqs. `g1`, `g2`.

    Top row, the paper's: (a) case (I), alpha = 2.5; (b-d) case (II), alpha = 1.5, 2.5,
    3.5; K_theta = K_s - delta. Bottom row, beyond the paper, alpha = 2.5: (e, f) sign of
    the semi-discrete NLS's g (generated/lattice_coefficients.py, mean flow included),
    (g, h) the exact lattice verdict at the paper's amplitude 2 eps A0 = 0.02: white where
    some sideband grows (Hill's method, `numerics.stability_map`, 200 x 200 full).
    Checks that case (I) has sign(g) = -sign(delta) everywhere.
    """
    k, delta = _sign_grid(ctx.quick)
    K, D = np.meshgrid(k, delta, indexing="xy")
    panels = [("rotation", 2.5), ("coupled", 1.5), ("coupled", 2.5), ("coupled", 3.5)]
    fig, axes = plt.subplots(2, 4, figsize=(13, 7), sharey=True)
    data = {"k": k, "delta": delta}

    def mark(ax):
        for name, mk in (("blue", "s"), ("green", "o")):
            p = POINTS[name]
            ax.plot(p["k"], K_S - p["K_theta"], mk, color=name, mec="k")

    for ax, (case, al), lab in zip(axes[0], panels, "abcd"):
        with np.errstate(all="ignore"):
            g = G_FUNCS[case](K, al, K_S, K_S - D)
        sign = np.sign(g)
        _image(ax, k, delta, sign, cmap="gray", vmin=-1, vmax=1)
        ax.set_title(f"({lab}) case {'I' if case == 'rotation' else 'II'}, alpha = {al}",
                     fontsize=9)
        if al == 2.5:
            mark(ax)
        data[f"sign_{lab}"] = sign
    # beyond the paper: semi-discrete NLS and exact lattice, alpha = 2.5
    n_exact = 40 if ctx.quick else 200
    ke = np.linspace(0.01, np.pi - 0.01, n_exact)
    de = np.linspace(-0.015, 0.015, n_exact)
    KE, DE = np.meshgrid(ke, de, indexing="xy")
    timing = {}
    for ax, case, lab in zip(axes[1, :2], ("rotation", "coupled"), "ef"):
        t0 = time.perf_counter()
        with np.errstate(all="ignore"):
            sign = np.sign(getattr(la, f"g_{case}")(K, ALPHA, K_S, K_S - D))
        timing[f"semi_discrete_{case}_s"] = time.perf_counter() - t0
        _image(ax, k, delta, sign, cmap="gray", vmin=-1, vmax=1)
        ax.set_title(f"({lab}) semi-discrete NLS, case {'I' if case == 'rotation' else 'II'}",
                     fontsize=9)
        mark(ax)
        data[f"sign_{lab}"] = sign
    for ax, case, lab in zip(axes[1, 2:], ("rotation", "coupled"), "gh"):
        t0 = time.perf_counter()
        gain = stability_map(KE, DE, case, ALPHA, K_S, 2 * EPS * 1.0)
        timing[f"exact_{case}_s"] = time.perf_counter() - t0
        verdict = np.where(np.isnan(gain), 0.0, np.where(gain > 0, 1.0, -1.0))
        _image(ax, ke, de, verdict, cmap="gray", vmin=-1, vmax=1)
        ax.set_title(f"({lab}) exact lattice, case {'I' if case == 'rotation' else 'II'}, "
                     "a = 0.02", fontsize=9)
        mark(ax)
        data[f"gain_{lab}"] = gain
    data["k_exact"], data["delta_exact"] = ke, de
    for ax in axes[1]:
        ax.set_xlabel("k")
    for row in axes:
        row[0].set_ylabel("delta")
    fig.tight_layout()
    ctx.save(fig, data, {"alpha": [2.5, 1.5, 2.5, 3.5, 2.5, 2.5, 2.5, 2.5], "K_s": K_S,
                         "amplitude_exact": 2 * EPS})
    ok_I = bool(np.all(data["sign_a"] == -np.sign(D)))
    frac = {lab: float(np.mean(data[f"sign_{lab}"] > 0)) for lab in "abcdef"}
    frac.update({lab: float(np.mean(data[f"gain_{lab}"] > 0)) for lab in "gh"})
    # how often each theory's verdict agrees with the exact one, on the exact grid
    agree = {}
    for case, lab in (("rotation", "g"), ("coupled", "h")):
        exact = data[f"gain_{lab}"] > 0
        with np.errstate(all="ignore"):
            paper = G_FUNCS[case](KE, ALPHA, K_S, K_S - DE) > 0
            semi = getattr(la, f"g_{case}")(KE, ALPHA, K_S, K_S - DE) > 0
        agree[case] = {"paper_nls": float(np.mean(paper == exact)),
                       "semi_discrete_nls": float(np.mean(semi == exact))}
    return {"focusing_fraction": frac, "verdict_agreement_with_exact": agree,
            "timing_s": timing, "exact_grid": [n_exact, n_exact], "checks": [
        {"check": "case I: sign(g) = -sign(delta) on the whole (k, delta) grid",
         "theory": "paper, Sec. 'Parametric study'", "numerics": str(ok_I), "pass": ok_I}]}


@scene("fig4-km-map", "K_m over (delta, k), alpha = 2.5, both cases, test points marked",
       "Fig. 4 (K_inst_map)", "<1 s", simulates=False)
def fig4(ctx: Context):
    """Fig. 4: most unstable wavenumber K_m (eq. `K_m`, A0 = 1) where g > 0; blank where
    stable. Left case (I), right case (II). The paper picks points with k + eps K_m < 3k."""
    k, delta = _sign_grid(ctx.quick)
    K, D = np.meshgrid(k, delta, indexing="xy")
    fig, axes = plt.subplots(1, 2, figsize=(10, 4), sharey=True)
    data = {"k": k, "delta": delta}
    for ax, case in zip(axes, ("rotation", "coupled")):
        with np.errstate(all="ignore"):
            g = G_FUNCS[case](K, ALPHA, K_S, K_S - D)
            km = np.where(g > 0, co.mi_fastest(np.where(g > 0, g, 0.0), 1.0), np.nan)
        im = _image(ax, k, delta, km, cmap="viridis", vmax=np.nanpercentile(km, 95))
        fig.colorbar(im, ax=ax, label="K_m (A0 = 1)")
        for name, mk in (("blue", "s"), ("green", "o")):
            p = POINTS[name]
            ax.plot(p["k"], K_S - p["K_theta"], mk, color=name, mec="k", ms=8)
        ax.set_title(f"case {'I' if case == 'rotation' else 'II'}, alpha = {ALPHA}")
        ax.set_xlabel("k")
        data[f"K_m_{case}"] = km
    axes[0].set_ylabel("delta")
    fig.tight_layout()
    ctx.save(fig, data, {"alpha": ALPHA, "K_s": K_S, "A0": 1.0})
    checks = []
    for point, case in (("blue", "coupled"), ("green", "rotation")):
        th = theory(point, case)
        kk = POINTS[point]["k"]
        ok = kk + EPS * th["K_m"] < 3 * kk
        checks.append({"check": f"{point} point, case {case}: k + eps K_m < 3k (paper's choice)",
                       "theory": f"k + eps K_m = {kk + EPS * th['K_m']:.3f}",
                       "numerics": f"3k = {3 * kk:.3f}", "pass": bool(ok)})
    return {"checks": checks}


# --- simulation scenes -------------------------------------------------------------------

def _sim_params(ctx, point, quick_N, quick_T, **extra):
    N = quick_N if ctx.quick else 500
    t_end = quick_T if ctx.quick else 5000.0
    base = dict(material=material(point), k=POINTS[point]["k"], N=N, eps=EPS, A0=1.0,
                noise=NOISE, seed=ctx.seed, t_end=t_end, dt=0.05, method="rk4")
    base.update(extra)
    return base


def _plane_wave_scene(ctx: Context, point: str, case: str, figure: str):
    # quick: smallest N commensurate with k (blue 13/100, green 37/250) and long enough
    # for the unstable runs to grow > 20x (measured: blue 40x at T = 1500, green 25x at 3000)
    quick_N, quick_T = (200, 2000.0) if point == "blue" else (250, 4000.0)
    params = _sim_params(ctx, point, quick_N, quick_T, case=case)
    params["save_every"] = params["t_end"] / (200 if ctx.quick else 500)
    run = ctx.simulate(**params)
    spec = an.spectrum(run.theta)
    verdict = an.stability_verdict(spec, run.m, run.N)
    th = theory(point, case)
    coupled = case == "coupled"
    ncol = 2
    nrow = 2 if coupled else 1
    fig, axes = plt.subplots(nrow, ncol, figsize=(10, 3.8 * nrow), squeeze=False)
    q = run.wavenumbers
    n = np.arange(run.N)
    fields = [("theta", run.theta, spec)]
    if coupled:
        fields.append(("U", run.U, an.spectrum(run.U)))
    for row, (name, f, sp) in enumerate(fields):
        a0, a1 = axes[row]
        im = _image(a0, n, run.t, np.abs(f), cmap="magma")
        fig.colorbar(im, ax=a0, label=f"|{name}|")
        a0.set_xlabel("n")
        a0.set_ylabel("T")
        im = _image(a1, q, run.t, np.log10(np.maximum(sp, 1e-12)), cmap="viridis",
                        vmin=np.log10(sp.max()) - 6)
        fig.colorbar(im, ax=a1, label=f"log10 |{name}_hat|")
        a1.axvline(run.k, color="w", lw=0.6, ls=":")
        a1.set_xlabel("q (rad per site)")
    fig.suptitle(f"{figure}: {point} point, case {'II' if coupled else 'I'} "
                 f"(k = {run.k:.5f}, delta = {run.material.delta:+.3f}); theory g = "
                 f"{th['g']:.4g} ({'stable' if th['stable'] else 'MI'}), numerics: "
                 f"{'stable' if verdict['stable'] else 'MI'} (x{verdict['growth_factor']:.3g})",
                 fontsize=9)
    fig.tight_layout()
    attrs = {n_: v for n_, v in params.items() if n_ not in ("material", "progress")}
    attrs.update(alpha=ALPHA, K_s=K_S, K_theta=POINTS[point]["K_theta"], k_snapped=run.k,
                 m=run.m)
    ctx.save(fig, {"t": run.t, "theta": run.theta, "U": run.U, "theta_hat": spec,
                   "energy": run.energy}, attrs)
    agree = th["stable"] == verdict["stable"]
    return {
        "scene": None, "case": case, "alpha": ALPHA, "K_s": K_S,
        "K_theta": POINTS[point]["K_theta"], "k": run.k, "N": run.N, "eps": EPS, "A0": 1.0,
        "seed": ctx.seed, "t_end": run.t_end, "dt": run.dt, "method": run.method,
        "theory": th, "numerics": verdict,
        "max_relative_energy_error": float(run.relative_energy_error.max()),
        "checks": [{"check": f"{figure} ({point}, case {case}): stability verdict",
                    "theory": f"g = {th['g']:.4g} -> {'stable' if th['stable'] else 'MI'}",
                    "numerics": f"sidebands x{verdict['growth_factor']:.3g} -> "
                                f"{'stable' if verdict['stable'] else 'MI'}",
                    "pass": agree}],
    }


for _name, _point, _case, _fig in (
        ("fig5-blue-rotation", "blue", "rotation", "Fig. 5"),
        ("fig6-blue-coupled", "blue", "coupled", "Fig. 6"),
        ("fig7-green-rotation", "green", "rotation", "Fig. 7"),
        ("fig8-green-coupled", "green", "coupled", "Fig. 8")):
    def _make(point=_point, case=_case, figure=_fig):
        def fn(ctx):
            return _plane_wave_scene(ctx, point, case, figure)
        fn.__doc__ = (f"{figure}: noisy plane wave (eq. `IC`), {point} point, case {case}; "
                      "|theta| over (n, T) and its k-spectrum (and U for case II). Checks the "
                      "sign of g against the simulated sideband growth.")
        return fn
    scene(_name, f"{_fig}: N = 500 plane wave, {_point} point, case "
          f"{'I' if _case == 'rotation' else 'II'}; |theta|(n,T) and spectrum",
          _fig, "~2 s (quick <1 s)", simulates=True)(_make())


MI_CASES = (("blue", "coupled"), ("green", "rotation"))
FIG9_TIMES = {("blue", 0.8): 2500.0, ("blue", 1.4): 1100.0,
              ("green", 0.8): 5000.0, ("green", 1.4): 1700.0}


@scene("fig9-mi-band", "MI band Omega_I(K) for A0 = 0.8, 1.4 and early-time spectra",
       "Fig. 9 (Spectrumline)", "~6 s (quick ~2 s)", simulates=True)
def fig9(ctx: Context):
    """Fig. 9: (a, b) Omega_I (eq. `Omega_I`) for the blue point case II and green point
    case I at A0 = 0.8, 1.4; (c, d) |theta_hat| at the caption's times (blue: 2500, 1100;
    green: 5000, 1700 - the caption says case II twice, erratum 2), with k + eps K_m
    (dotted) and k + eps K_c (dashed). Checks the spectral peak lies inside the band."""
    fig, axes = plt.subplots(2, 2, figsize=(10, 7))
    checks, data = [], {}
    for col, (point, case) in enumerate(MI_CASES):
        kk = POINTS[point]["k"]
        for A0, color in ((0.8, "C0"), (1.4, "C3")):
            th = theory(point, case, A0)
            KK = np.linspace(0, 1.05 * th["K_c"], 400)
            rate = co.mi_growth_rate(KK, th["g"], A0)
            axes[0, col].plot(kk + EPS * KK, rate, color, label=f"A0 = {A0}")
            t_at = FIG9_TIMES[(point, A0)]
            quick_N = 200 if point == "blue" else 250
            params = _sim_params(ctx, point, quick_N, t_at, case=case, A0=A0)
            params.update(t_end=t_at, save_every=t_at, store="spectrum")
            run = ctx.simulate(**params)
            sp = run.theta_hat[-1]
            axes[1, col].semilogy(run.wavenumbers, sp, color, lw=0.8, label=f"A0 = {A0}, T = {t_at:g}")
            for ax in axes[:, col]:
                ax.axvline(kk + EPS * th["K_m"], color=color, ls=":")
                ax.axvline(kk + EPS * th["K_c"], color=color, ls="--")
            mask = np.ones(sp.size, bool)
            mask[an.harmonic_bins(run.m, run.N)] = False
            upper = mask & (run.wavenumbers > run.k) & (run.wavenumbers < 2 * run.k)
            j = np.flatnonzero(upper)[np.argmax(sp[upper])]
            q_peak = float(run.wavenumbers[j])
            inside = run.k < q_peak < run.k + EPS * th["K_c"]
            checks.append({"check": f"Fig. 9 {point} case {case} A0 = {A0}: spectral peak "
                                    f"at T = {t_at:g} inside the band",
                           "theory": f"k + eps K_m = {kk + EPS * th['K_m']:.3f}, "
                                     f"k + eps K_c = {kk + EPS * th['K_c']:.3f}",
                           "numerics": f"peak at q = {q_peak:.3f}", "pass": bool(inside)})
            data[f"{point}_A0_{A0}_spectrum"] = sp
            data[f"{point}_A0_{A0}_q"] = run.wavenumbers
        axes[0, col].set_title(f"{point} point, case {'II' if case == 'coupled' else 'I'}")
        axes[0, col].set_xlabel("k + eps K")
        axes[0, col].set_ylabel("Omega_I (NLS time)")
        axes[1, col].set_xlabel("q (rad per site)")
        axes[1, col].set_xlim(0, np.pi)
        axes[0, col].legend(fontsize=8)
        axes[1, col].legend(fontsize=8)
    fig.tight_layout()
    ctx.save(fig, data, {"alpha": ALPHA, "K_s": K_S, "eps": EPS, "noise": NOISE,
                         "seed": ctx.seed, "times": {f"{p}_{a}": t for (p, a), t in
                                                     FIG9_TIMES.items()}})
    return {"checks": checks}


def measured_gain(ctx, point, case, A0=1.0, seeds=None, t_end=None, quick_N=None, **extra):
    """Sideband growth rates sigma(q) from linear-stage fits, mean and std over seeds.

    Defaults: t_end = 3000 / A0^2 (blue) or 5000 / A0^2 (green); N = 500, or in quick
    mode 200 (blue) / 250 (green). ``extra`` goes to the simulation (k, omega_model...).
    """
    seeds = seeds if seeds is not None else (range(2) if ctx.quick else range(4))
    quick_N = quick_N or (200 if point == "blue" else 250)
    T = 3000.0 if point == "blue" else 5000.0
    t_end = T / A0**2 if t_end is None else t_end
    rates, windows = [], []
    for s in seeds:
        params = _sim_params(ctx, point, quick_N, T, case=case, A0=A0, seed=ctx.seed + s,
                             t_end=t_end, save_every=5.0, store="spectrum", **extra)
        run = ctx.simulate(**params)
        win = an.linear_stage(run.theta_hat, run.m, run.N)
        if win is None:
            continue
        rates.append(an.growth_rates(run.t, run.theta_hat, win))
        windows.append((float(run.t[win[0]]), float(run.t[win[1]])))
    if not rates:
        return None
    rates = np.array(rates)
    return {"q": run.wavenumbers, "k": run.k, "N": run.N, "sigma": rates.mean(axis=0),
            "sigma_std": rates.std(axis=0, ddof=1) if len(rates) > 1 else np.zeros(
                rates.shape[1]), "windows": windows, "seeds": len(rates)}


def nls_gain(q, k, point, case, A0=1.0):
    """Paper's prediction in lattice units: sigma(q) = eps^2 |g1| Omega_I((q - k)/eps)."""
    th = theory(point, case, A0)
    return EPS**2 * abs(th["g1"]) * co.mi_growth_rate((q - k) / EPS, th["g"], A0)


@scene("gain-spectrum", "measured sideband growth rate sigma(q) vs eps^2 |g1| Omega_I",
       "beyond the paper", "~15 s (quick ~3 s)", simulates=True)
def gain_spectrum(ctx: Context):
    """Growth rate of every sideband from log-linear fits of |theta_hat(q, t)| over the
    linear stage (from 5x growth to 3% of the carrier), mean and spread over seeds, for
    the two unstable runs; against the paper's eps^2 |g1| Omega_I (eqs. `NLS`, `Omega_I`).
    Reports peak gain and band edge (where the gain falls to half its peak)."""
    fig, axes = plt.subplots(1, 2, figsize=(11, 4))
    checks, data, results = [], {}, {}
    for ax, (point, case) in zip(axes, MI_CASES):
        meas = measured_gain(ctx, point, case)
        if meas is None:
            checks.append({"check": f"gain {point}/{case}", "theory": "MI",
                           "numerics": "no linear stage found", "pass": False})
            continue
        q, k = meas["q"], meas["k"]
        qf = np.linspace(0, np.pi, 4000)
        th_curve = nls_gain(qf, k, point, case)
        m_sum = an.band_summary(q, meas["sigma"], k)
        t_sum = an.band_summary(qf, th_curve, k)
        th = theory(point, case)
        results[f"{point}-{case}"] = {
            "theory": dict(t_sum, eps_K_c=EPS * th["K_c"], eps_K_m=EPS * th["K_m"]),
            "measured": m_sum, "seeds": meas["seeds"], "windows": meas["windows"],
            "peak_ratio": m_sum["peak_gain"] / t_sum["peak_gain"],
            "edge_ratio": m_sum["band_edge"] / t_sum["band_edge"]}
        ax.errorbar(q, meas["sigma"], yerr=meas["sigma_std"], fmt=".", ms=3, lw=0.6,
                    label=f"measured ({meas['seeds']} seeds)")
        ax.plot(qf, th_curve, "k-", label="paper NLS: eps^2 |g1| Omega_I")
        ax.set_xlim(max(0, k - 1.2 * EPS * th["K_c"]), min(np.pi, k + 1.2 * EPS * th["K_c"]))
        ax.set_ylim(-0.2 * t_sum["peak_gain"], 1.6 * max(t_sum["peak_gain"], m_sum["peak_gain"]))
        ax.set_xlabel("q (rad per site)")
        ax.set_ylabel("growth rate sigma (1/T)")
        ax.set_title(f"{point} point, case {'II' if case == 'coupled' else 'I'}")
        ax.legend(fontsize=8)
        data[f"{point}_q"], data[f"{point}_sigma"] = q, meas["sigma"]
        data[f"{point}_sigma_std"] = meas["sigma_std"]
        r = results[f"{point}-{case}"]
        for what in ("peak", "edge"):
            ratio = r[f"{what}_ratio"]
            checks.append({
                "check": f"gain {point} case {case}: {what} "
                         f"{'gain' if what == 'peak' else '(half-gain point)'} measured/NLS",
                "theory": f"{t_sum['peak_gain' if what == 'peak' else 'band_edge']:.4g}",
                "numerics": f"{m_sum['peak_gain' if what == 'peak' else 'band_edge']:.4g} "
                            f"(ratio {ratio:.2f})",
                "pass": bool(abs(ratio - 1) < 0.25)})
    fig.tight_layout()
    ctx.save(fig, data, {"alpha": ALPHA, "K_s": K_S, "eps": EPS, "A0": 1.0,
                         "noise": NOISE, "seed": ctx.seed})
    return {"results": results, "checks": checks}


THEORY_POINTS = (  # (label, point, case, A0, k or None for the point's own)
    ("blue II A0=1", "blue", "coupled", 1.0, None),
    ("green I A0=1", "green", "rotation", 1.0, None),
    ("blue II A0=0.8", "blue", "coupled", 0.8, None),
    ("blue II A0=1.4", "blue", "coupled", 1.4, None),
    ("green I A0=0.8", "green", "rotation", 0.8, None),
    ("green I A0=1.4", "green", "rotation", 1.4, None),
    ("blue II k=0.704", "blue", "coupled", 1.0, 2 * np.pi * 28 / 250),
)
THEORIES = ("paper NLS", "semi-discrete NLS", "exact lattice")


def theory_gain(theory, q_offset, k, point, case, A0):
    """sigma(q) of one theory at offsets q from the carrier (lattice units)."""
    mat = material(point)
    args = (k, ALPHA, K_S, POINTS[point]["K_theta"])
    if theory == "exact lattice":
        return mi_gain(mat, case, k, 2 * EPS * A0, q_offset)
    mod = co if theory == "paper NLS" else la
    g = getattr(mod, f"g_{case}")(*args)
    return EPS**2 * abs(mod.g1(*args)) * mod.mi_growth_rate(q_offset / EPS, g, A0)


@scene("gain-theories", "measured sigma(q) vs paper NLS, semi-discrete NLS and exact lattice "
       "gain (Hill), 7 points, both starts", "beyond the paper", "~2 min (quick ~25 s)",
       simulates=True)
def gain_theories(ctx: Context):
    """Which theory do the simulations obey? At the two unstable test points (A0 = 0.8,
    1, 1.4) and at case II with k = 0.704, the measured growth rate of every sideband
    (linear-stage fits, mean and spread over seeds) from the paper's initial condition
    (eq. `IC`) and from the exact travelling wave, against: the paper's NLS (eqs. `NLS`,
    `Omega_I`), the semi-discrete NLS (generated/lattice_coefficients.py) and the exact
    lattice gain (numerics.mi_gain). Reports each theory's relative error of the peak gain
    and of the half-gain band edge, and each theory's verdict on the four paper runs."""
    n = len(THEORY_POINTS)
    ncol = 4
    fig, axes = plt.subplots(2, ncol, figsize=(15, 7))
    axes = axes.ravel()
    data, rows, checks = {}, [], []
    qf = np.linspace(0, np.pi, 3001)
    for ax, (label, point, case, A0, kk) in zip(axes, THEORY_POINTS):
        k0 = POINTS[point]["k"] if kk is None else kk
        quick_N = 250 if kk is not None else (200 if point == "blue" else 250)
        N = quick_N if ctx.quick else 500
        exact_peak = float(theory_gain("exact lattice", qf - k0, k0, point, case, A0).max())
        t_end = float(np.clip(round(9.0 / exact_peak, -2), 1000, 20000))
        meas = {}
        for start in ("continuum", "travelling"):
            m = measured_gain(ctx, point, case, A0, t_end=t_end, quick_N=quick_N, k=k0,
                              omega_model=start)
            if m is not None:
                meas[start] = (m["q"], m["sigma"], m["sigma_std"], m["k"])
        for start, (q, sig, err, kr) in meas.items():
            ax.errorbar(q, sig, yerr=err, fmt="." if start == "travelling" else "x", ms=3,
                        lw=0.5, label="measured, " + ("travelling wave" if start == "travelling"
                                                      else "paper IC"))
            data[f"{label}/{start}/q"], data[f"{label}/{start}/sigma"] = q, sig
            data[f"{label}/{start}/sigma_std"] = err
        kr = meas["travelling"][3] if "travelling" in meas else k0
        curves = {}
        for th, style in zip(THEORIES, ("k--", "C2-", "C3-")):
            curves[th] = theory_gain(th, qf - kr, kr, point, case, A0)
            ax.plot(qf, curves[th], style, lw=1, label=th)
            data[f"{label}/{th}"] = curves[th]
        top = max(c.max() for c in curves.values())
        ax.set_ylim(-0.1 * top, 1.3 * top)
        ax.set_title(label, fontsize=9)
        ax.set_xlabel("q (rad per site)")
        for start, (q, sig, err, _) in meas.items():
            m_sum = an.band_summary(q, sig, kr)
            row = {"point": label, "start": start, "t_end": t_end, "N": N,
                   "measured": m_sum}
            for th in THEORIES:
                t_sum = an.band_summary(qf, curves[th], kr)
                pe = m_sum["peak_gain"] / t_sum["peak_gain"] - 1 if t_sum["peak_gain"] else None
                ee = (m_sum["band_edge"] / t_sum["band_edge"] - 1
                      if t_sum["peak_gain"] and np.isfinite(t_sum["band_edge"]) else None)
                row[th] = {"peak_gain": t_sum["peak_gain"], "band_edge": t_sum["band_edge"],
                           "peak_error": pe, "edge_error": ee}
            rows.append(row)
            if start == "travelling":
                ex = row["exact lattice"]
                ok = ex["peak_error"] is not None and abs(ex["peak_error"]) < 0.05 and \
                    ex["edge_error"] is not None and abs(ex["edge_error"]) < 0.05
                checks.append({"check": f"gain-theories {label}: exact lattice gain vs measured "
                               "(travelling-wave start), peak and band edge within 5%",
                               "theory": f"peak {ex['peak_gain']:.4g}, edge {ex['band_edge']:.4g}",
                               "numerics": f"errors {_pct(ex['peak_error'])}, "
                                           f"{_pct(ex['edge_error'])}",
                               "pass": bool(ok)})
    axes[0].set_ylabel("growth rate sigma (1/T)")
    axes[0].legend(fontsize=7)
    for ax in axes[n:]:
        ax.axis("off")
    fig.tight_layout()
    ctx.save(fig, data, {"alpha": ALPHA, "K_s": K_S, "eps": EPS, "noise": NOISE,
                         "seed": ctx.seed})
    # verdicts of the four paper runs, per theory
    verdicts = {}
    q = np.linspace(0, np.pi, 2001)
    for point in POINTS:
        for case in ("rotation", "coupled"):
            kk = POINTS[point]["k"]
            verdicts[f"{point}-{case}"] = {
                th: ("MI" if theory_gain(th, q - kk, kk, point, case, 1.0).max() > 0 else "stable")
                for th in THEORIES}
            # U-pair modes exist in case II only (verified in the green II run's U spectrum)
            verdicts[f"{point}-{case}"]["exact lattice, U modes too"] = "n/a" if \
                case == "rotation" else ("MI" if mi_gain(material(point), case, kk, 2 * EPS,
                                                         q - kk, modes="all").max() > 0
                                         else "stable")
    return {"rows": rows, "verdicts": verdicts, "checks": checks}


def _pct(x):
    return "n/a" if x is None else f"{100 * x:+.1f}%"


@scene("harmonics", "stable case II: U at 2k vs |u2|, carrier frequency vs omega(k)",
       "beyond the paper", "~2 s (quick <1 s)", simulates=True)
def harmonics(ctx: Context):
    """Green point, case II (stable): the part of U at 2k locked to the carrier against
    the second harmonic of eq. `u1` (amplitude 2 eps^2 |c| A0^2; continuum c and its
    lattice version c_L = i sin 2k / (8 (sin^2 k - omega^2)) at the measured carrier
    frequency and amplitude a: |c_L| a^2 / 2), separated from the free
    waves the paper's initial condition launches (erratum 6); and the measured carrier
    frequency against `continuum2`, `discrete2` and discrete2 - eps^2 g2 A0^2 (the NLS
    nonlinear shift)."""
    point, case = "green", "coupled"
    T = 400.0 if ctx.quick else 1000.0
    params = _sim_params(ctx, point, 250, T, case=case, t_end=T, save_every=0.5,
                         noise=0.0, omega_model="discrete")
    run = ctx.simulate(**params)
    m = material(point)
    k = run.k
    wd = float(discrete_omega_rotation(k, m))
    wc = float(co.omega(k, ALPHA, K_S, m.K_theta))
    g2 = float(co.g2_coupled(k, ALPHA, K_S, m.K_theta))
    w_meas = an.carrier_frequency(run.t, run.theta, run.m)
    w_nl = wd - EPS**2 * g2 * 1.0
    W = float(discrete_omega_longitudinal(2 * k))
    fit = an.forced_second_harmonic(run.t, run.U, run.m, w_meas, W)
    c_cont = abs(complex(co.u2_coefficient(k, ALPHA, K_S, m.K_theta)))
    # lattice second harmonic driven at the carrier as it is: measured frequency, amplitude
    c_latt = abs(np.sin(2 * k) / (8 * (np.sin(k) ** 2 - w_meas**2)))
    a = an.carrier_amplitude(run.theta, run.m)  # theta = a cos(...), a = 2 eps A0 at T = 0
    F_cont, F_latt = 2 * EPS**2 * c_cont, c_latt * a**2 / 2
    fig, axes = plt.subplots(1, 2, figsize=(10, 3.8))
    U2 = an.mode(run.U, 2 * run.m)
    axes[0].plot(run.t, np.abs(U2), lw=0.7, label="|U_hat(2k, t)|")
    axes[0].axhline(fit["forced"], color="k", label="fitted forced part")
    axes[0].axhline(F_cont, color="C1", ls="--", label="2 eps^2 |c| (continuum, eq. u1)")
    axes[0].axhline(F_latt, color="C2", ls=":", label="|c_L| a^2/2 (lattice)")
    axes[0].set_xlabel("T")
    axes[0].legend(fontsize=7)
    labels = ["measured", "continuum2", "discrete2", "discrete2 - eps^2 g2 A0^2"]
    vals = [w_meas, wc, wd, w_nl]
    axes[1].bar(labels, vals, color=["k", "C1", "C2", "C3"])
    axes[1].set_ylim(min(vals) - 0.01, max(vals) + 0.01)
    axes[1].set_ylabel("carrier frequency")
    axes[1].tick_params(axis="x", labelsize=7)
    fig.tight_layout()
    ctx.save(fig, {"t": run.t, "U_hat_2k": np.abs(U2)},
             {"alpha": ALPHA, "K_s": K_S, "K_theta": m.K_theta, "k": k, "N": run.N,
              "eps": EPS, "A0": 1.0, "t_end": T, "dt": run.dt, "noise": 0.0})
    checks = [
        {"check": "harmonics: forced U at 2k vs continuum 2 eps^2 abs(c) (eq. u1)",
         "theory": f"{F_cont:.4e}", "numerics": f"{fit['forced']:.4e} "
         f"(ratio {fit['forced'] / F_cont:.3f})", "pass": abs(fit["forced"] / F_cont - 1) < 0.2},
        {"check": "harmonics: forced U at 2k vs lattice abs(c_L) a^2 / 2",
         "theory": f"{F_latt:.4e}", "numerics": f"{fit['forced'] / F_latt:.3f} ratio",
         "pass": abs(fit["forced"] / F_latt - 1) < 0.05},
        {"check": "harmonics: carrier frequency vs discrete2 - eps^2 g2 A0^2",
         "theory": f"{w_nl:.6f} (continuum2 {wc:.6f}, discrete2 {wd:.6f})",
         "numerics": f"{w_meas:.6f}", "pass": abs(w_meas - w_nl) < abs(w_meas - wd)},
    ]
    return {"forced_fit": fit, "F_continuum": F_cont, "F_lattice": F_latt,
            "omega_measured": w_meas, "omega_continuum": wc, "omega_discrete": wd,
            "omega_discrete_nonlinear": w_nl, "checks": checks}


# --- running -----------------------------------------------------------------------------

def get_scene(name: str) -> Scene:
    if name not in REGISTRY:
        raise ValueError(f"unknown scene {name!r}; `flexmm scenes` lists: "
                         f"{', '.join(REGISTRY)}")
    return REGISTRY[name]


def run_scene(name: str, out: Path | str = "out", quick: bool = False, seed: int = 0,
              force: bool = False) -> dict:
    """Run one scene; writes OUT/NAME/{figure.png, figure.pdf, data.h5, summary.json}."""
    sc = get_scene(name)
    if not isinstance(seed, int) or seed < 0:
        raise ValueError(f"seed must be a non-negative integer, got {seed!r}")
    out = Path(out)
    ctx = Context(out=out / name, quick=quick, seed=seed, force=force,
                  cache_dir=out / ".cache")
    summary = sc.fn(ctx)
    summary = {"scene": name, **{k: v for k, v in summary.items() if k != "scene"},
               "quick": quick, "package_version": package_version()}
    ctx.out.mkdir(parents=True, exist_ok=True)
    (ctx.out / "summary.json").write_text(json.dumps(summary, indent=2, default=_jsonable)
                                          + "\n")
    return summary


def _jsonable(x):
    if isinstance(x, (np.floating, np.integer)):
        return x.item()
    if isinstance(x, np.bool_):
        return bool(x)
    if isinstance(x, np.ndarray):
        return x.tolist()
    raise TypeError(type(x))


def write_report(summaries: dict, out: Path, quick: bool) -> Path:
    """out/report.md: one row per check, theory vs numerics, pass/fail, disagreements."""
    lines = ["# Theory versus numerics", "",
             f"Mode: {'quick (reduced N / t_end / grids; see each figure)' if quick else 'full'}."
             f" Package {package_version()}.", "",
             "| scene | check | theory | numerics | result |", "|---|---|---|---|---|"]
    failed = []
    for name, s in summaries.items():
        for c in s.get("checks", []):
            res = "pass" if c["pass"] else "**FAIL**"
            if not c["pass"]:
                failed.append((name, c))
            lines.append(f"| {name} | {c['check']} | {c['theory']} | {c['numerics']} | {res} |")
    lines.append("")
    if failed:
        lines.append("## Where theory and numerics disagree")
        for name, c in failed:
            lines.append(f"- **{name}** - {c['check']}: theory {c['theory']}, numerics "
                         f"{c['numerics']}.")
    else:
        lines.append("Theory and numerics agree on every check.")
    gs = summaries.get("gain-spectrum", {}).get("results", {})
    if gs:
        lines += ["", "## Sideband gain: paper's NLS vs measured", "",
                  "| run | peak gain NLS | peak gain measured | ratio | band edge NLS | "
                  "band edge measured | ratio |", "|---|---|---|---|---|---|---|"]
        for run, r in gs.items():
            lines.append(f"| {run} | {r['theory']['peak_gain']:.4g} | "
                         f"{r['measured']['peak_gain']:.4g} | {r['peak_ratio']:.2f} | "
                         f"{r['theory']['band_edge']:.4g} | {r['measured']['band_edge']:.4g}"
                         f" | {r['edge_ratio']:.2f} |")
        lines.append("")
        lines.append("Band edge: offset q - k where the gain falls to half its peak "
                     "(same definition for both curves).")
    gt = summaries.get("gain-theories", {})
    if gt.get("rows"):
        lines += ["", "## Which theory the simulations obey (scene gain-theories)", "",
                  "Relative error of each theory's peak gain and half-gain band edge against "
                  "the measured sigma(q) (measured / theory - 1). Start: `paper` = eq. `IC` "
                  "(U at rest), `travelling` = the lattice's exact plane wave; n/a: the "
                  "theory predicts no gain there.", "",
                  "| point | start | " + " | ".join(f"{t}: peak, edge" for t in THEORIES) + " |",
                  "|---|---|" + "---|" * len(THEORIES)]
        for r in gt["rows"]:
            cells = [f"{_pct(r[t]['peak_error'])}, {_pct(r[t]['edge_error'])}" for t in THEORIES]
            start = "travelling" if r["start"] == "travelling" else "paper"
            lines.append(f"| {r['point']} | {start} | " + " | ".join(cells) + " |")
        lines += ["", "Stability verdicts of the four paper runs (A0 = 1):", "",
                  "| run | " + " | ".join(gt["verdicts"][next(iter(gt["verdicts"]))]) + " |",
                  "|---|" + "---|" * (len(THEORIES) + 1)]
        for run, v in gt["verdicts"].items():
            lines.append(f"| {run} | " + " | ".join(v.values()) + " |")
    path = Path(out) / "report.md"
    path.write_text("\n".join(lines) + "\n")
    return path


def run_all(out="out", quick=False, seed=0, force=False, names=None) -> Path:
    summaries = {}
    for name in names or REGISTRY:
        summaries[name] = run_scene(name, out, quick, seed, force)
    return write_report(summaries, Path(out), quick)

