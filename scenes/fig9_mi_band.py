"""Fig. 9 (Spectrumline): the MI band Omega_I(K) for A0 = 0.8, 1.4 and early spectra.

(a, b) Omega_I (eq. `Omega_I`) for the blue point case II and the green point case I;
(c, d) |theta_hat| at the caption's times (blue: 2500, 1100; green: 5000, 1700 - the
caption says case II twice, erratum 2), with k + eps K_m (dotted) and k + eps K_c
(dashed). Checks, at each of the four runs, that the spectrum's largest growing component
(carrier and odd harmonics aside, anywhere in (0, pi]) has grown more than 20x over the
start's noise floor and lies inside the predicted band, abs(q - k) < eps K_c: the sidebands
come in pairs k +- q', so the lower one counts as much as the upper one (blue, A0 = 1.4:
the largest is the lower partner near q = 0). About 6 s (quick about 3 s), mostly the
figure files.
"""

from __future__ import annotations

import numpy as np
from matplotlib.lines import Line2D

from common import paper
from generated import coefficients as co
from numerics import Material
from numerics.lattice import GROWTH_THRESHOLD, non_carrier_bins
from numerics.theory import nls_summary

from ._plotting import Q_LABEL, case_title, figure, reserve_quick_stamp
from ._registry import Scene, check, register
from ._runs import run_parameters

AMPLITUDES = ((0.8, "C0"), (1.4, "C3"))
#: legend entries of the vertical lines (coloured by A0)
BAND_HANDLES = [Line2D([], [], color="0.4", ls=":", label=r"$k + \epsilon K_m$ (fastest)"),
                Line2D([], [], color="0.4", ls="--", label=r"$k + \epsilon K_c$ (band edge)")]


def compute(ctx):
    data, checks = {}, []
    for point, case in paper.MI_RUNS:
        kk = paper.k(point)
        for A0, _ in AMPLITUDES:
            th = nls_summary(Material.paper(point), case, kk, paper.EPS, A0)
            K = np.linspace(0, 1.05 * th["K_c"], 400)
            t_at = paper.FIG9_TIMES[(point, A0)]
            params = run_parameters(ctx, point, t_at, case=case, A0=A0, t_end=t_at,
                                    save_every=t_at, store="spectrum")
            run = ctx.simulate(**params)
            spec = run.theta_hat[-1]
            # the whole spectrum but the carrier and its odd harmonics: a window (k, 2k)
            # lay inside the band at blue A0 = 1.4 (k + eps K_c > 2k), so its check could
            # not fail, and a spectrum that had not grown passed as well
            mask = non_carrier_bins(run.m, run.N)
            j = np.flatnonzero(mask)[np.argmax(spec[mask])]
            q_peak = float(run.wavenumbers[j])
            grown = float(spec[j] / np.median(run.theta_hat[0][mask]))
            lo, hi = kk + paper.EPS * th["K_m"], kk + paper.EPS * th["K_c"]
            offset = q_peak - run.k
            checks.append(check(f"Fig. 9 {point} case {case} A0 = {A0}: the largest sideband "
                                f"at T = {t_at:g} has grown > {GROWTH_THRESHOLD:g}x and lies "
                                "in the band abs(q - k) < eps K_c",
                                f"eps K_c = {hi - kk:.3f} (k + eps K_m = {lo:.3f}, "
                                f"k + eps K_c = {hi:.3f})",
                                f"peak at q = {q_peak:.3f} (q - k = {offset:+.3f}), "
                                f"{grown:.3g}x the start's noise",
                                abs(offset) < hi - kk and grown > GROWTH_THRESHOLD))
            key = f"{point}_A0_{A0}"
            data.update({f"{key}_spectrum": spec, f"{key}_q": run.wavenumbers,
                         f"{key}_K": K, f"{key}_Omega_I": co.mi_growth_rate(K, th["g"], A0),
                         f"{key}_k_plus_eps_K_m": lo, f"{key}_k_plus_eps_K_c": hi,
                         f"{key}_T": t_at})
    data.update(alpha=paper.ALPHA, K_s=paper.K_S, eps=paper.EPS, noise=paper.NOISE)
    return data, {"checks": checks}


def plot(data):
    fig, axes = figure(2, 2, figsize=(11, 7.5))
    for col, (point, case) in enumerate(paper.MI_RUNS):
        kk = paper.k(point)
        for A0, color in AMPLITUDES:
            key = f"{point}_A0_{A0}"
            axes[0, col].plot(kk + data["eps"] * data[f"{key}_K"], data[f"{key}_Omega_I"],
                              color, label=fr"$A_0 = {A0}$")
            axes[1, col].semilogy(data[f"{key}_q"], data[f"{key}_spectrum"], color, lw=0.8,
                                  label=fr"$A_0 = {A0}$ at $T = {data[f'{key}_T']:g}$")
            for ax in axes[:, col]:
                ax.axvline(data[f"{key}_k_plus_eps_K_m"], color=color, ls=":")
                ax.axvline(data[f"{key}_k_plus_eps_K_c"], color=color, ls="--")
        axes[0, col].set_title(f"({'ab'[col]}) {point} point, {case_title(case)}: "
                               "MI band (theory, paper's NLS)", fontsize=10)
        axes[1, col].set_title(f"({'cd'[col]}) {point} point, {case_title(case)}: "
                               "spectrum (simulation)", fontsize=10)
        axes[0, col].set_xlabel(r"$k + \epsilon K$ (rad/site)")
        axes[0, col].set_ylabel(r"$\Omega_I$ (1/$\tilde\tau$, $\tilde\tau = "
                                r"\epsilon^2 |g_1| T$)")
        axes[1, col].set_xlabel(Q_LABEL)
        axes[1, col].set_ylabel(r"$|\hat\theta(q)|$ (rad)")
        axes[1, col].set_xlim(0, np.pi)
        for ax in axes[:, col]:
            ax.legend(handles=ax.get_legend_handles_labels()[0] + BAND_HANDLES, fontsize=8)
    fig.suptitle(r"MI band: theory (top) and early spectra of $\theta$ by simulation (bottom)")
    return reserve_quick_stamp(fig, data)


SCENE = register(Scene("fig9-mi-band", "MI band Omega_I(K) for A0 = 0.8, 1.4 and early-time "
                       "spectra", "Fig. 9 (Spectrumline)", "~6 s (quick ~3 s)", True,
                       compute, plot))
