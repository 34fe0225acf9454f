"""Fig. 3 (Panels_delta_map): sign of g over (k, delta), and the verdicts beyond the NLS.

Top row, the paper's (white: g > 0, MI; black: g < 0), eqs. `g1`, `g2`: (a) case (I),
alpha = 2.5; (b-d) case (II), alpha = 1.5, 2.5, 3.5; K_theta = K_s - delta. Bottom row,
beyond the paper, alpha = 2.5: (e, f) sign of the semi-discrete NLS's g
(generated/lattice_coefficients.py, mean flow included), (g, h) the exact lattice verdict
at the paper's amplitude 2 eps A0 = 0.02: white where some sideband grows more than 20x
within the paper's T = 5000 (``numerics.resonance_map``: bands from their resonance
conditions, rates from Hill's method there; 200 x 200 full), (i) the same for the state
eq. `IC` launches in case II (its free U waves pump more bands; in case I eq. `IC` gives
panel g). Checks that case (I) has sign(g) = -sign(delta) everywhere. About 1 min (quick
about 3 s).
"""

from __future__ import annotations

import time

import numpy as np

from common import paper
from generated import coefficients as co
from generated import lattice_coefficients as la
from numerics.lattice import GROWTH_THRESHOLD
from numerics.maps import resonance_map

from ._plotting import (
    DELTA_LABEL,
    K_LABEL,
    case_label,
    case_title,
    figure,
    has_undefined,
    mark_points,
    point_handles,
    reserve_quick_stamp,
    verdict_colorbar,
    verdict_image,
    verdict_patches,
)
from ._registry import Scene, check, register

#: the paper's panels (a-d): (case, alpha)
PANELS = (("rotation", 2.5), ("coupled", 1.5), ("coupled", 2.5), ("coupled", 3.5))
#: delta range of Figs. 3-4
DELTA_MAX = 0.015
#: the exact panels' question: grows more than GROWTH_THRESHOLD-fold within the paper's run
THRESHOLD = np.log(GROWTH_THRESHOLD) / paper.T_END


def sign_grid(quick):
    """The (k, delta) grid of Figs. 3-4, without delta = 0 (where g1 = 0)."""
    n = 80 if quick else 400
    k = np.linspace(0.005, np.pi, n)
    delta = np.linspace(-DELTA_MAX, DELTA_MAX, n)
    return k, delta[np.abs(delta) > 1e-9]


def compute(ctx):
    k, delta = sign_grid(ctx.quick)
    K, D = np.meshgrid(k, delta, indexing="xy")
    Ks = paper.K_S
    data = {"k": k, "delta": delta, "K_s": Ks, "alpha": [a for _, a in PANELS],
            "amplitude_exact": paper.AMPLITUDE}
    for (case, al), lab in zip(PANELS, "abcd"):
        with np.errstate(all="ignore"):
            data[f"sign_{lab}"] = np.sign(getattr(co, f"g_{case}")(K, al, Ks, Ks - D))
    n_exact = 40 if ctx.quick else 200
    ke = np.linspace(0.01, np.pi - 0.01, n_exact)
    de = np.linspace(-DELTA_MAX, DELTA_MAX, n_exact)
    KE, DE = np.meshgrid(ke, de, indexing="xy")
    data["k_exact"], data["delta_exact"] = ke, de
    timing, agree = {}, {}
    for case, lab_s, lab_x in (("rotation", "e", "g"), ("coupled", "f", "h")):
        t0 = time.perf_counter()
        with np.errstate(all="ignore"):
            data[f"sign_{lab_s}"] = np.sign(getattr(la, f"g_{case}")(K, paper.ALPHA, Ks, Ks - D))
        timing[f"semi_discrete_{case}_s"] = time.perf_counter() - t0
        t0 = time.perf_counter()
        gain = resonance_map(KE, DE, case, paper.ALPHA, Ks, data["amplitude_exact"])["peak_gain"]
        timing[f"exact_{case}_s"] = time.perf_counter() - t0
        data[f"gain_{lab_x}"] = gain
        # how often each NLS verdict agrees with the exact one, on the exact grid
        with np.errstate(all="ignore"):
            paper_mi = getattr(co, f"g_{case}")(KE, paper.ALPHA, Ks, Ks - DE) > 0
            semi_mi = getattr(la, f"g_{case}")(KE, paper.ALPHA, Ks, Ks - DE) > 0
        agree[case] = {"paper_nls": float(np.mean(paper_mi == (gain > THRESHOLD))),
                       "semi_discrete_nls": float(np.mean(semi_mi == (gain > THRESHOLD)))}
    t0 = time.perf_counter()
    data["gain_i"] = resonance_map(KE, DE, "coupled", paper.ALPHA, Ks, data["amplitude_exact"],
                                   start="paper")["peak_gain"]
    timing["exact_coupled_paper_start_s"] = time.perf_counter() - t0
    data["threshold"] = THRESHOLD
    ok_I = bool(np.all(data["sign_a"] == -np.sign(D)))
    frac = {lab: float(np.mean(data[f"sign_{lab}"] > 0)) for lab in "abcdef"}
    frac.update({lab: float(np.mean(data[f"gain_{lab}"] > THRESHOLD)) for lab in "ghi"})
    checks = [check("case I: sign(g) = -sign(delta) on the whole (k, delta) grid",
                    "paper, Sec. 'Parametric study'", str(ok_I), ok_I)]
    return data, {"focusing_fraction": frac, "verdict_agreement_with_exact": agree,
                  "timing_s": timing, "exact_grid": [n_exact, n_exact], "checks": checks}


def plot(data):
    k, delta, ke, de = data["k"], data["delta"], data["k_exact"], data["delta_exact"]
    fig, axes = figure(2, 5, figsize=(16, 7.5), sharex=True, sharey=True)
    for ax, (case, al), lab in zip(axes[0], PANELS, "abcd"):
        im = verdict_image(ax, k, delta, data[f"sign_{lab}"])
        ax.set_title(f"({lab}) paper's NLS, {case_title(case)},\n"
                     fr"$\alpha = {al}$: sign of $g$ (theory)", fontsize=9)
        if al == paper.ALPHA:
            mark_points(ax)
    for ax, case, lab in zip(axes[1, :2], ("rotation", "coupled"), "ef"):
        verdict_image(ax, k, delta, data[f"sign_{lab}"])
        ax.set_title(f"({lab}) semi-discrete NLS, {case_title(case)}:\n"
                     r"sign of $g$ (theory)", fontsize=9)
        mark_points(ax)
    thr = float(data.get("threshold", 0.0))
    verdicts = []
    for ax, case, lab in zip(axes[1, 2:], ("rotation", "coupled", "coupled"), "ghi"):
        gain = data[f"gain_{lab}"]
        verdict = np.where(np.isnan(gain), np.nan, np.where(gain > thr, 1.0, -1.0))
        verdicts.append(verdict)
        verdict_image(ax, ke, de, verdict)
        start = "eq. IC start" if lab == "i" else "travelling wave"
        ax.set_title(f"({lab}) exact lattice (theory), case {case_label(case)},\n"
                     f"{start}, amplitude {data['amplitude_exact']:g} rad", fontsize=9)
        mark_points(ax)
    for ax in axes.flat:
        ax.set_xlabel(K_LABEL)
        ax.set_ylabel(DELTA_LABEL)
        ax.label_outer()
    undefined = has_undefined(*(data[f"sign_{lab}"] for lab in "abcdef"), *verdicts)
    verdict_colorbar(fig, im, axes.ravel().tolist(), mi="MI", stable="stable",
                     undefined="g = 0 or not computed" if undefined else None, shrink=0.6)
    key = axes[0, 4]
    key.axis("off")
    times = fr"{GROWTH_THRESHOLD:g}\times"
    key.legend(handles=verdict_patches(fr"MI: $g > 0$ (a-f); grows $> {times}$ within"
                                       "\n" fr"$T = {paper.T_END:g}$ (g-i)",
                                       r"stable: $g < 0$ (a-f);" "\n"
                                       fr"grows $< {times}$ (g-i)") + point_handles(),
               loc="center", fontsize=8, title="key (all panels theory)", title_fontsize=9,
               frameon=False)
    fig.suptitle(r"Modulational instability over $(k, \delta)$: NLS theories (a-f) and the "
                 "exact lattice theory (g-i)")
    return reserve_quick_stamp(fig, data)


SCENE = register(Scene(
    "fig3-g-sign", "sign of g over (k, delta): case I and case II for alpha = 1.5, 2.5, 3.5; "
    "plus semi-discrete NLS and exact lattice maps (travelling wave and eq. IC)",
    "Fig. 3 (Panels_delta_map)", "~1 min (quick ~3 s)", False, compute, plot))
