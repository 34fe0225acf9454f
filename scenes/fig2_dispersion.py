"""Fig. 2 (disp_rel_example): lattice vs continuum dispersion for four K_theta.

Eqs. `discrete1`, `discrete2` (solid, generated from eq. `norm`) against `continuum1`,
`continuum2` (dashed). Checks the paper's claim that the continuum captures the lattice
for q <= 1: the largest relative gap of either branch there, on a grid that ends at q = 1
(where both gaps are largest: 4.07% rotational, panel a; 4.29% longitudinal).
About 1 s, mostly the figure files.
"""

from __future__ import annotations

import numpy as np

from common import paper
from generated import coefficients as co
from numerics import Material, discrete_omega_longitudinal, discrete_omega_rotation

from ._plotting import Q_LABEL, figure, reserve_quick_stamp
from ._registry import Scene, check, register

#: K_theta of the four panels (the paper's Fig. 2 and the two test points)
K_THETAS = (1.534e-4, 0.1, paper.POINTS["blue"]["K_theta"], paper.POINTS["green"]["K_theta"])
#: a continuum branch within this relative gap "captures" the lattice (paper: 'well')
GAP_TOLERANCE = 0.05


def compute(ctx):
    q = np.linspace(0, np.pi, 200 if ctx.quick else 600)
    data = {"q": q, "alpha": paper.ALPHA, "K_s": paper.K_S, "K_theta": list(K_THETAS)}
    gaps = {}
    # the gaps grow with q: the plotting grid need not hit q = 1, this one ends there
    q1 = np.linspace(0, 1, 201)[1:]
    for kt, lab in zip(K_THETAS, "abcd"):
        material = Material(paper.ALPHA, paper.K_S, kt)
        wd2 = discrete_omega_rotation(q, material)
        with np.errstate(invalid="ignore"):
            wc2 = co.omega(q, paper.ALPHA, paper.K_S, kt)
        lattice = discrete_omega_rotation(q1, material)
        gaps[str(kt)] = float(np.max(np.abs(co.omega(q1, paper.ALPHA, paper.K_S, kt)
                                            - lattice) / lattice))
        data[f"discrete2_{lab}"], data[f"continuum2_{lab}"] = wd2, wc2
    data["discrete1"] = discrete_omega_longitudinal(q)
    lattice = discrete_omega_longitudinal(q1)
    gaps["longitudinal"] = float(np.max(np.abs(q1 - lattice) / lattice))  # continuum1: q
    gap = max(gaps.values())
    worst = max(gaps, key=gaps.get)
    where = "longitudinal" if worst == "longitudinal" else f"rotational, K_theta = {worst}"
    checks = [check("continuum vs discrete dispersion, both branches, q <= 1 (paper: "
                    "'captures well')", f"gap < {GAP_TOLERANCE:.0%}",
                    f"max gap {gap:.2%} ({where})", gap < GAP_TOLERANCE)]
    return data, {"max_relative_gap_q_le_1": gaps, "checks": checks}


def plot(data):
    q = data["q"]
    fig, axes = figure(2, 2, figsize=(8, 6), sharex=True, sharey=True)
    for ax, kt, lab in zip(axes.flat, data["K_theta"], "abcd"):
        ax.plot(q, data["discrete1"], "C0-", label=r"$U$, lattice (discrete1)")
        ax.plot(q, q, "C0--", label=r"$U$, continuum (continuum1)")
        ax.plot(q, data[f"discrete2_{lab}"], "C3-", label=r"$\theta$, lattice (discrete2)")
        ax.plot(q, data[f"continuum2_{lab}"], "C3--", label=r"$\theta$, continuum (continuum2)")
        point = next((f" ({p} point)" for p in paper.POINTS if paper.K_theta(p) == kt), "")
        ax.set_title(fr"({lab}) $K_\theta = {kt:g}$, $\delta = {data['K_s'] - kt:+.4g}${point}",
                     fontsize=10)
        ax.set_ylim(0, 3.2)
        ax.set_xlabel(Q_LABEL)
        ax.set_ylabel(r"$\omega$ (rad/T)")
        ax.label_outer()
    axes[0, 0].legend(fontsize=7)
    fig.suptitle(fr"Dispersion relations (theory), $\alpha = {data['alpha']}$, "
                 fr"$K_s = {data['K_s']}$; lattice units")
    return reserve_quick_stamp(fig, data)


SCENE = register(Scene("fig2-dispersion", "discrete vs continuum dispersion, four K_theta "
                       "(Fig. 2)", "Fig. 2 (disp_rel_example)", "~1 s", False, compute, plot))
