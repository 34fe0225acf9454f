"""Figs. 5-8: the paper's noisy plane wave (eq. `IC`) at the two test points, both cases.

|theta| over (n, T) and its k-spectrum (and U for case II). Checks the sign of g (the
paper's NLS) against the simulated sideband growth (``numerics.stability_verdict``:
the largest non-carrier, non-harmonic theta component relative to the carrier grows more
than 20x over the run for "MI"). About 2 s for case I, 3 s for case II (quick 1 s and
2 s), mostly drawing and writing the figure files (case II draws four image panels).
"""

from __future__ import annotations

import functools

import numpy as np

from common import paper
from numerics import nls_summary, spectrum, stability_verdict

from ._plotting import (
    Q_LABEL,
    SITE_LABEL,
    TIME_LABEL,
    case_label,
    case_title,
    figure,
    image,
    reserve_quick_stamp,
)
from ._registry import Scene, check, register
from ._runs import plain_parameters, run_parameters

#: quick mode: long enough for the unstable runs to grow > 20x (measured: blue 40x at
#: T = 1500, green 25x at 3000)
QUICK_T = {"blue": 2000.0, "green": 4000.0}
#: records kept per run (full, quick)
RECORDS = (500, 200)


def compute(ctx, point, case, figure):
    params = run_parameters(ctx, point, QUICK_T[point], case=case)
    params["save_every"] = params["t_end"] / RECORDS[ctx.quick]
    run = ctx.simulate(**params)
    spec = spectrum(run.theta)
    verdict = stability_verdict(spec, run.m, run.N)
    th = nls_summary(run.material, case, paper.k(point), paper.EPS, paper.A0)
    data = {"t": run.t, "theta": run.theta, "U": run.U, "theta_hat": spec,
            "U_hat": None if run.U is None else spectrum(run.U), "energy": run.energy,
            **plain_parameters(params), "k_snapped": run.k, "m": run.m, "figure": figure,
            "point": point, "g": th["g"], "theory_stable": th["stable"],
            "numerics_stable": verdict["stable"], "growth_factor": verdict["growth_factor"]}
    word = {True: "stable", False: "MI"}
    checks = [check(f"{figure} ({point}, case {case}): stability verdict",
                    f"g = {th['g']:.4g} -> {word[th['stable']]}",
                    f"sidebands x{verdict['growth_factor']:.3g} -> {word[verdict['stable']]}",
                    th["stable"] == verdict["stable"])]
    summary = {"case": case, "alpha": paper.ALPHA, "K_s": paper.K_S,
               "K_theta": run.material.K_theta, "k": run.k, "N": run.N, "eps": paper.EPS,
               "A0": paper.A0, "t_end": run.t_end, "dt": run.dt, "method": run.method,
               "theory": th, "numerics": verdict,
               "max_relative_energy_error": float(run.relative_energy_error.max()),
               "checks": checks}
    return data, summary


def plot(data):
    coupled = data["case"] == "coupled"
    nrow = 2 if coupled else 1
    fig, axes = figure(nrow, 2, figsize=(11, 4.2 * nrow + 0.4), squeeze=False)
    N = data["theta"].shape[1]
    n, q = np.arange(N), 2 * np.pi * np.arange(N // 2 + 1) / N
    fields = [(r"\theta", "rad", data["theta"], data["theta_hat"])]
    if coupled:
        fields.append(("U", "lattice units", data["U"], data["U_hat"]))
    for row, (name, unit, f, spec) in enumerate(fields):
        a0, a1 = axes[row]
        fig.colorbar(image(a0, n, data["t"], np.abs(f), cmap="magma"), ax=a0,
                     label=fr"$|{name}_n|$ ({unit})")
        a0.set_xlabel(SITE_LABEL)
        a0.set_ylabel(TIME_LABEL)
        a0.set_title(fr"$|{name}_n(T)|$ (simulation)", fontsize=10)
        im = image(a1, q, data["t"], np.log10(np.maximum(spec, 1e-12)), cmap="viridis",
                   vmin=np.log10(spec.max()) - 6)
        fig.colorbar(im, ax=a1, extend="min",
                     label=fr"$\log_{{10}} |\hat {name}(q)|$ ({unit})")
        a1.axvline(data["k_snapped"], color="w", lw=0.6, ls=":", label=r"carrier $k$")
        a1.set_xlabel(Q_LABEL)
        a1.set_ylabel(TIME_LABEL)
        a1.set_title(fr"spectrum $|\hat {name}(q, T)|$ (simulation); dotted: carrier $k$",
                     fontsize=10)
    word = {True: "stable", False: "MI"}
    fig.suptitle(f"{data['figure']}: {data['point']} point, {case_title(data['case'])}, "
                 fr"$k = {data['k_snapped']:.5f}$ rad/site, "
                 fr"$\delta = {data['K_s'] - data['K_theta']:+.3f}$" "\n"
                 fr"theory (paper's NLS): $g = {data['g']:.4g}$ "
                 f"({word[bool(data['theory_stable'])]}); simulation: "
                 f"{word[bool(data['numerics_stable'])]} (sidebands "
                 fr"$\times{data['growth_factor']:.3g}$)", fontsize=10)
    return reserve_quick_stamp(fig, data)


#: run time (full, quick) by case: measured on 2 cores, mostly the figure files
RUNTIME = {"rotation": "~2 s (quick ~1 s)", "coupled": "~3 s (quick ~2 s)"}

for _name, _point, _case, _fig in (
        ("fig5-blue-rotation", "blue", "rotation", "Fig. 5"),
        ("fig6-blue-coupled", "blue", "coupled", "Fig. 6"),
        ("fig7-green-rotation", "green", "rotation", "Fig. 7"),
        ("fig8-green-coupled", "green", "coupled", "Fig. 8")):
    register(Scene(_name, f"{_fig}: N = 500 plane wave, {_point} point, case "
                   f"{case_label(_case)}; |theta|(n,T) and spectrum", _fig,
                   RUNTIME[_case], True,
                   functools.partial(compute, point=_point, case=_case, figure=_fig), plot))
