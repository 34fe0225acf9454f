"""Four-wave pairs of an FPUT chain near a quarter wavelength (beyond the paper;
docs/theory.md, "The lattice's four-wave theory").

FPUT alpha = 0.5, beta = 1, a = 0.1. (a) Every pair (k1, k2), k1 + k2 = 2k, of carriers
k near pi/2, coloured by its four-wave growth rate (numerics.models.four_wave): the
sidebands around (k, k) and the backward (umklapp) pairs around (k - pi, k - pi). (b) The
fastest rate of each kind against k (infinite chain), the semi-discrete NLS's peak and the exact lattice
theory on a ring of 256 sites (k = 2 pi m / 256), each exact mode named by
numerics.models.classify_mode. Checks: the four-wave rate within 10% of the exact one,
and the same kind of pair, at each exact point. About 7 s (quick: 5 s, mostly the exact
theory and the figure files).
"""

from __future__ import annotations

import math

import numpy as np

from ._plotting import SIGMA_LABEL, figure, reserve_quick_stamp
from ._registry import Scene, check, register

PARAMS = {"alpha": 0.5, "beta": 1.0}
AMPLITUDE = 0.1
N = 256
#: the exact theory's ring carriers k = 2 pi m / N
RING_M = (60, 62, 63, 64, 65, 66, 68)
KINDS = ("sidebands", "backward")


def compute(ctx):
    from energy import load_model
    from numerics.models import classify_mode, exact_gain, four_wave, nls

    model = load_model("fput", **PARAMS)
    ks = np.linspace(math.pi / 2 - 0.15, math.pi / 2 + 0.15, 13 if ctx.quick else 61)
    k1, k2, rate, fastest = [], [], [], {kind: [] for kind in KINDS}
    nls_peak = []
    for k in ks:
        fw = four_wave(model, k, AMPLITUDE)  # the infinite chain
        r = np.nan_to_num(fw.rates[:, 0], nan=0.0)
        # each pair twice, (k + q, k - q) and (k - q, k + q): the plane is symmetric
        for a, b in ((k + fw.offsets, k - fw.offsets), (k - fw.offsets, k + fw.offsets)):
            k1.append(np.angle(np.exp(1j * a)))
            k2.append(np.angle(np.exp(1j * b)))
            rate.append(r)
        kr = fw.kind_rates()
        for kind in KINDS:
            fastest[kind].append(kr[kind])
        nls_peak.append(nls(model, k).peak_gain(AMPLITUDE))
    ring = RING_M[::3] if ctx.quick else RING_M
    exact = {"k": [], "gain": [], "kind": [], "four_wave": [], "four_wave_kind": []}
    for m in ring:
        k = 2 * math.pi * m / N
        ex = exact_gain(model, k, AMPLITUDE, N=N)
        fw = four_wave(model, k, AMPLITUDE, N=N)
        exact["k"].append(k)
        exact["gain"].append(ex.peak_gain)
        exact["kind"].append(classify_mode(ex)["mode_kind"])
        exact["four_wave"].append(fw.gain)
        exact["four_wave_kind"].append(fw.mode_kind)
    data = {"k": ks, "k1": np.concatenate(k1), "k2": np.concatenate(k2),
            "rate": np.concatenate(rate), "nls_peak": np.array(nls_peak),
            "sidebands": np.array(fastest["sidebands"]),
            "backward": np.array(fastest["backward"]),
            "exact_k": np.array(exact["k"]), "exact_gain": np.array(exact["gain"]),
            "exact_kind": list(exact["kind"]), "four_wave_gain": np.array(exact["four_wave"]),
            "amplitude": AMPLITUDE, **PARAMS}
    worst = float(np.max(np.abs(data["four_wave_gain"] / data["exact_gain"] - 1)))
    same = exact["kind"] == exact["four_wave_kind"]
    checks = [
        check("four-wave rate vs exact lattice (ring of 256), FPUT near k = pi/2",
              "within 10%", f"worst {worst:.1%}", worst < 0.10),
        check("four-wave fastest pair's kind vs the exact mode's (classify_mode)",
              "same kind", ", ".join(f"{a}/{b}" for a, b in
                                     zip(exact["four_wave_kind"], exact["kind"])), same)]
    return data, {"worst_relative_error": worst, "exact_kinds": exact["kind"],
                  "checks": checks}


def plot(data):
    fig, (ax, bx) = figure(1, 2, figsize=(10, 4.4))
    order = np.argsort(data["rate"])
    sc = ax.scatter(data["k1"][order], data["k2"][order], c=data["rate"][order] * 1e3, s=2,
                    cmap="magma", rasterized=True)
    fig.colorbar(sc, ax=ax, label=r"pair growth rate ($10^{-3}$/T)")
    for x, y, text in ((math.pi / 2, math.pi / 2, "sidebands"),
                       (-math.pi / 2, -math.pi / 2, "backward")):
        ax.annotate(text, (x, y), xytext=(x + 0.5, y + 0.9), color="C0", fontsize=9,
                    arrowprops=dict(arrowstyle="->", color="C0"))
    ax.set_xlim(-math.pi, math.pi)
    ax.set_ylim(-math.pi, math.pi)
    ax.set_xlabel(r"$k_1$ (rad/site)")
    ax.set_ylabel(r"$k_2 = 2k - k_1$ (rad/site)")
    ax.set_title(r"(a) pairs $k_1 + k_2 = 2k$, $k \in \pi/2 \pm 0.15$", fontsize=10)
    k = data["k"]
    bx.plot(k, data["sidebands"] * 1e3, "C0-", label="four-wave: sidebands")
    bx.plot(k, data["backward"] * 1e3, "C3-", label="four-wave: backward pair")
    bx.plot(k, data["nls_peak"] * 1e3, "k--", lw=1, label="semi-discrete NLS")
    for kind, marker in (("sidebands", "o"), ("backward", "s")):
        sel = np.array([kk == kind for kk in data["exact_kind"]], bool)
        if sel.any():
            bx.plot(data["exact_k"][sel], data["exact_gain"][sel] * 1e3, marker, mfc="none",
                    color="C0" if kind == "sidebands" else "C3",
                    label=f"exact lattice (N = 256): {kind}")
    bx.axvline(math.pi / 2, color="0.7", lw=0.8)
    bx.set_xlabel(r"carrier $k$ (rad/site)")
    bx.set_ylabel(SIGMA_LABEL.replace("(1/T)", r"($10^{-3}$/T)"))
    bx.set_title("(b) fastest pair of each kind", fontsize=10)
    bx.legend(fontsize=7)
    fig.suptitle(fr"FPUT $\alpha = {data['alpha']}$, $\beta = {data['beta']}$, "
                 fr"$a = {data['amplitude']}$: four-wave pairs near a quarter wavelength")
    return reserve_quick_stamp(fig, data)


SCENE = register(Scene("four-wave-pairs", "FPUT's four-wave pairs near k = pi/2: sidebands "
                       "and backward (umklapp) pairs against the exact theory",
                       "beyond the paper", "~7 s (quick ~5 s)", False, compute, plot))
