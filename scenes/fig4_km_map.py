"""Fig. 4 (K_inst_map): most unstable wavenumber K_m over (delta, k), alpha = 2.5.

K_m (eq. `K_m`, A0 = 1) where g > 0, blank where stable; left case (I), right case
(II); the test points marked. The paper picks points with k + eps K_m < 3k (the fastest
sideband stays below the third harmonic): checked at the two unstable runs. Under a second.
"""

from __future__ import annotations

import numpy as np
from matplotlib.patches import Patch

from common import paper
from generated import coefficients as co
from numerics import Material, nls_summary

from ._plotting import (
    DELTA_LABEL,
    K_LABEL,
    case_title,
    figure,
    image,
    mark_points,
    reserve_quick_stamp,
)
from ._registry import Scene, check, register
from .fig3_g_sign import sign_grid


def compute(ctx):
    k, delta = sign_grid(ctx.quick)
    K, D = np.meshgrid(k, delta, indexing="xy")
    data = {"k": k, "delta": delta, "alpha": paper.ALPHA, "K_s": paper.K_S, "A0": paper.A0}
    for case in ("rotation", "coupled"):
        with np.errstate(all="ignore"):
            g = getattr(co, f"g_{case}")(K, paper.ALPHA, paper.K_S, paper.K_S - D)
            data[f"K_m_{case}"] = np.where(
                g > 0, co.mi_fastest(np.where(g > 0, g, 0.0), paper.A0), np.nan)
    checks = []
    for point, case in paper.MI_RUNS:
        kk = paper.k(point)
        th = nls_summary(Material.paper(point), case, kk, paper.EPS, paper.A0)
        reach = kk + paper.EPS * th["K_m"]
        checks.append(check(f"{point} point, case {case}: k + eps K_m < 3k (paper's choice)",
                            f"k + eps K_m = {reach:.3f}", f"3k = {3 * kk:.3f}", reach < 3 * kk))
    return data, {"checks": checks}


def plot(data):
    k, delta = data["k"], data["delta"]
    fig, axes = figure(1, 2, figsize=(11, 4.6), sharey=True)
    for ax, case in zip(axes, ("rotation", "coupled")):
        km = data[f"K_m_{case}"]
        im = image(ax, k, delta, km, cmap="viridis", vmax=np.nanpercentile(km, 95))
        fig.colorbar(im, ax=ax, extend="max",
                     label=fr"$K_m$ at $A_0 = {data['A0']:g}$ (NLS units;" "\n"
                     r"sideband offset $\epsilon K_m$ in rad/site)")
        mark_points(ax, label=True, ms=8)
        ax.set_title(fr"{case_title(case)}, $\alpha = {data['alpha']}$: paper's NLS (theory)",
                     fontsize=10)
        ax.set_xlabel(K_LABEL)
        ax.set_ylabel(DELTA_LABEL)
        ax.label_outer()
        ax.legend(handles=[Patch(facecolor="white", edgecolor="k", label=r"stable ($g < 0$)")]
                  + ax.get_legend_handles_labels()[0], fontsize=8, loc="upper right")
    fig.suptitle(r"Most unstable sideband $K_m$ over $(k, \delta)$ where $g > 0$ (MI)")
    return reserve_quick_stamp(fig, data)


SCENE = register(Scene("fig4-km-map", "K_m over (delta, k), alpha = 2.5, both cases, test "
                       "points marked", "Fig. 4 (K_inst_map)", "<1 s", False, compute, plot))
