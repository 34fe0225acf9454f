"""Small plotting helpers shared by the figure modules (matplotlib, Agg backend).

Figures are meant to be shown in a talk: mathtext labels with units on every axis (lattice
units: time T = t sqrt(k_l / m), wavenumbers in rad per site), a key wherever colour
carries meaning, constrained layout so nothing is cut off.
"""

from __future__ import annotations

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # re-exported for the figure modules
import numpy as np
from matplotlib.colors import BoundaryNorm, ListedColormap
from matplotlib.lines import Line2D
from matplotlib.patches import Patch

from common import paper

#: axis labels in lattice units, one spelling for every figure
K_LABEL = r"$k$ (rad/site)"
Q_LABEL = r"$q$ (rad/site)"
DELTA_LABEL = r"$\delta = K_s - K_\theta$ (1)"
TIME_LABEL = r"$T$ (lattice units)"
SITE_LABEL = r"site $n$"
SIGMA_LABEL = r"growth rate $\sigma$ (1/T)"

#: binary verdict maps: black = stable, white = MI, grey = undefined (NaN or 0)
VERDICT_CMAP = ListedColormap(["black", "white"], name="verdict").with_extremes(bad="0.6")
VERDICT_NORM = BoundaryNorm([-1.5, 0.0, 1.5], 2)


def figure(nrows=1, ncols=1, **kw):
    """``plt.subplots`` with constrained layout (labels, colorbars and legends fit)."""
    return plt.subplots(nrows, ncols, layout="constrained", **kw)


def cell_edges(x) -> np.ndarray:
    """Edges of the cells centred on the sorted values ``x``: midpoints between neighbours and
    half a spacing beyond each end (non-uniform grids too). A single value gets a cell 10%
    of its size wide (1 wide at 0), so that a 1 x n map is drawn, centred, like any other.

    Returns
    -------
    ndarray, shape (len(x) + 1,)
    """
    x = np.asarray(x, float).ravel()
    if x.size == 0:
        raise ValueError("no values to draw cells around")
    if x.size == 1:
        half = 0.05 * abs(x[0]) or 0.5
        return np.array([x[0] - half, x[0] + half])
    mid = (x[1:] + x[:-1]) / 2
    return np.concatenate([[2 * x[0] - mid[0]], mid, [2 * x[-1] - mid[-1]]])


def image(ax, x, y, Z, **kw):
    """Cells of Z (shape (len(y), len(x))) centred on the grid values x, y, with their edges
    halfway between neighbouring values (``pcolormesh``): a cell sits where its value was
    computed, whatever the grid's shape (1 x n, n x 1, 1 x 1 and non-uniform grids too).
    Large images are rasterized (vector PDFs of 10^5 quads are slow)."""
    Z = np.ma.masked_invalid(np.asarray(Z, float))
    if Z.ndim != 2 or Z.shape != (np.size(y), np.size(x)):
        raise ValueError(f"Z has shape {Z.shape}; expected (len(y), len(x)) = "
                         f"({np.size(y)}, {np.size(x)})")
    kw.setdefault("rasterized", Z.size > 4096)
    return ax.pcolormesh(cell_edges(x), cell_edges(y), Z, shading="flat", **kw)


def cell_boundaries(ax, x, y, V, **kw):
    """The boundary of a verdict map drawn on the cells of :func:`image`: a line along every
    edge between two neighbouring cells whose verdicts differ (V: 1 MI, 0 stable; NaN or
    negative, undetermined: no line through it). Works for every grid shape, unlike a
    contour (which needs 2 x 2 values and cuts through cells). Returns the
    ``LineCollection``, or None when no edge separates two verdicts."""
    from matplotlib.collections import LineCollection

    V = np.asarray(V, float)
    V = np.where(V < 0, np.nan, V)
    xe, ye = cell_edges(x), cell_edges(y)
    segs = []
    a, b = V[:, :-1], V[:, 1:]  # neighbours along x: a vertical edge between them
    for i, j in zip(*np.nonzero(np.isfinite(a) & np.isfinite(b) & (a != b))):
        segs.append([(xe[j + 1], ye[i]), (xe[j + 1], ye[i + 1])])
    a, b = V[:-1, :], V[1:, :]  # neighbours along y: a horizontal edge
    for i, j in zip(*np.nonzero(np.isfinite(a) & np.isfinite(b) & (a != b))):
        segs.append([(xe[j], ye[i + 1]), (xe[j + 1], ye[i + 1])])
    if not segs:
        return None
    kw.setdefault("capstyle", "projecting")
    kw.setdefault("clip_on", False)  # a boundary along the outermost edge stays whole
    return ax.add_collection(LineCollection(segs, **kw))


def verdict_image(ax, x, y, V):
    """Image of a verdict map V (> 0: MI, white; < 0: stable, black; 0 or NaN: grey)."""
    V = np.asarray(V, float)
    return image(ax, x, y, np.where(V == 0, np.nan, V), cmap=VERDICT_CMAP, norm=VERDICT_NORM)


def verdict_colorbar(fig, im, ax, mi="MI", stable="stable", undefined=None, **kw):
    """The key of :func:`verdict_image`: two labelled blocks, white ``mi`` and black
    ``stable``; ``undefined`` (if given) says what grey cells mean."""
    cb = fig.colorbar(im, ax=ax, ticks=[-0.75, 0.75], **kw)
    cb.ax.set_yticklabels([stable, mi])
    if undefined:
        cb.set_label(f"grey: {undefined}", fontsize=8)
    return cb


def has_undefined(*maps) -> bool:
    """True if any verdict map has a grey (0 or NaN) cell."""
    for V in maps:
        V = np.asarray(V, float)
        if np.any((V == 0) | np.isnan(V)):
            return True
    return False


def verdict_patches(mi="MI", stable="stable"):
    """Legend entries of a verdict map (white ``mi``, black ``stable``)."""
    return [Patch(facecolor="white", edgecolor="k", label=mi),
            Patch(facecolor="black", edgecolor="k", label=stable)]


def mark_points(ax, label=False, **kw):
    """The paper's blue (square) and green (circle) test points in a (k, delta) plane;
    ``label=True`` names them in the axes' legend."""
    for name, marker in (("blue", "s"), ("green", "o")):
        ax.plot(paper.k(name), paper.delta(name), marker, color=name, mec="k",
                label=point_label(name) if label else None, **kw)


def point_handles(**kw):
    """Legend entries of the test points as :func:`mark_points` draws them."""
    return [Line2D([], [], ls="", marker=m, color=name, mec="k", label=point_label(name), **kw)
            for name, m in (("blue", "s"), ("green", "o"))]


def point_label(name: str) -> str:
    return fr"{name} point ($\delta = {paper.delta(name):+.3f}$)"


def case_label(case: str) -> str:
    return "I" if case == "rotation" else "II"


def case_title(case: str) -> str:
    """'case I (rotation only)' or 'case II (coupled)'."""
    return "case I (rotation only)" if case == "rotation" else "case II (coupled)"


def reserve_quick_stamp(fig, data):
    """Leave a strip at the bottom for the runner's 'QUICK MODE' stamp (quick runs only),
    so it overlaps no axis label."""
    if data.get("quick"):
        fig.get_layout_engine().set(rect=(0, 0.03, 1, 0.97))
    return fig


#: a map's theory columns as the map figure draws their MI boundaries: name, label, style
#: (drawn widest first, so that boundaries on the same cell edge all stay visible)
MAP_THEORIES = (("verdict_paper", "paper NLS", dict(color="C1", lw=5.0)),
                ("verdict_semidiscrete", "semi-discrete NLS", dict(color="C2", lw=3.0)),
                ("verdict_exact", "exact lattice", dict(color="C3", lw=1.3, ls="--")))


def material_title(attrs) -> str:
    """The full material, case and start of a map (its attrs), in two lines."""
    rows = "K_theta = K_s - delta"
    return (f"case {attrs['case']}, alpha = {attrs['alpha']:g}, K_s = {attrs['K_s']:g}, "
            f"{rows}\nstart {attrs.get('start', 'paper')}, amplitude "
            f"{attrs['amplitude']:g} rad, N = {attrs['N']}, T = {attrs['t_end']:g}")


def map_figure(ds, ax=None):
    """The figure of a `flexmm map` store ``ds``: each cell centred on its (k, delta), white
    where the simulation (a theory-only map: the predicted growth) says MI, black stable,
    grey not done or undetermined; the theories' MI boundaries on the cell edges where their
    verdicts change. Any grid shape. The legend lists only what is drawn; a theory without
    a boundary in the map is named below the axes with its verdict everywhere."""
    if ax is None:
        fig, ax = plt.subplots(figsize=(6.4, 4.8), layout="constrained")
    else:
        fig = ax.figure
    k, d = ds["k"].values, ds["delta"].values
    done = ds["done"].values
    shown, what, mi, stable = "verdict_simulated", "simulated", "", ""
    if not done.any() and "verdict_predicted" in ds and "done_predicted" in ds:
        # a cell's predicted verdict: MI where its growth factor passes the threshold
        # (numerics.maps' verdict_predicted), stable where it does not
        threshold = ds.attrs.get("growth_threshold", 20)
        shown, what = "verdict_predicted", "predicted"
        mi, stable = f" (grows > {threshold:g}x)", f" (grows <= {threshold:g}x)"
        done = ds["done_predicted"].values & (ds["verdict_predicted"].values >= 0)
    v = ds[shown].values  # tri-state: a done cell the runs cannot decide (-1) stays grey
    background = np.where(done & (v >= 0), np.where(v == 1, 1.0, -1.0), np.nan)
    verdict_image(ax, k, d, background)
    handles = [Patch(facecolor=c, edgecolor="k", label=lab)
               for c, lab, present in (("white", f"{what}: MI{mi}", background > 0),
                                       ("black", f"{what}: stable{stable}", background < 0),
                                       ("0.6", "not done or undetermined",
                                        np.isnan(background))) if present.any()]
    notes = []
    for name, label, style in MAP_THEORIES:
        if name not in ds:
            continue
        v = ds[name].values.astype(float)
        if cell_boundaries(ax, k, d, v, **style) is not None:
            handles.append(Line2D([], [], **style, label=f"{label}: MI boundary"))
        else:
            decided = v[v >= 0]
            notes.append(f"{label}: " + ("undetermined everywhere" if not decided.size else
                                         "MI in every cell it decides" if decided.all() else
                                         "stable in every cell it decides" if not decided.any()
                                         else "no MI cell next to a stable one (undetermined "
                                         "cells between)"))
    xe, ye = cell_edges(k), cell_edges(d)
    ax.set_xlim(xe[0], xe[-1])
    ax.set_ylim(ye[0], ye[-1])
    if len(k) <= 8:  # few cells: a tick at each cell's value
        ax.set_xticks(k, [f"{v:.4g}" for v in k])
    if len(d) <= 8:
        ax.set_yticks(d, [f"{v:.4g}" for v in d])
    ax.tick_params(labelsize=7)
    ax.set_xlabel(K_LABEL + (("\n" + "\n".join(notes))
                             if notes else ""), fontsize=8)
    ax.set_ylabel(DELTA_LABEL)
    ax.set_title(material_title(ds.attrs), fontsize=8)
    fig.legend(handles=handles, fontsize=7, loc="outside lower center", ncols=2)
    return fig


def soliton_figure(sol, run=None):
    """The figure of `flexmm soliton`: (a) the profile, theta_n and the predicted envelope
    +-2|E| (measured: the run's last record, the envelope at its fitted centre); (b) the kink
    of U across the soliton (case II; measured beside predicted); (c) the trajectory, the
    fitted centre against the predicted v_g t. Without a run, the prediction alone.

    Parameters
    ----------
    sol : numerics.theory.Soliton
        The prediction (on the ring's k when there is a run: ``run.predicted``).
    run : numerics.theory.SolitonRun, optional
    """
    from numerics.theory import soliton_state

    m = sol.material
    fig, axes = plt.subplots(1, 3, figsize=(12, 3.8), layout="constrained")
    w = sol.width
    span = 8 * w
    if run is not None:
        last = run.snapshots[-1]
        n = np.arange(run.N)
        xi = (n - last.centre + run.N / 2) % run.N - run.N / 2
        order = np.argsort(xi)
        keep = order[np.abs(xi[order]) < span]
        axes[0].plot(xi[keep], run.theta[-1][keep], ".", ms=2, color="0.5",
                     label=fr"$\theta_n$ measured at $T = {last.t:.4g}$")
    xs = np.linspace(-span, span, 801)
    env = 2 * np.abs(sol.envelope(xs))
    axes[0].plot(xs, env, "C3-", lw=1.2, label=r"predicted envelope $\pm 2|E|$")
    axes[0].plot(xs, -env, "C3-", lw=1.2)
    axes[0].set(xlabel="site from the centre $n - n_c$", ylabel=r"$\theta_n$ (rad)",
                title=f"(a) {sol.kind} soliton: profile", xlim=(-span, span))
    if sol.kind == "bright":  # room above the peak for the legend
        axes[0].set_ylim(-1.1 * env.max(), 1.6 * env.max())
    axes[0].legend(fontsize=7, loc="upper right" if sol.kind == "bright" else "lower right")
    ax = axes[1]
    if sol.case == "coupled":
        if run is not None:  # on the ring, as launched (its uniform strain included)
            N = run.N
            pred = soliton_state(sol, N)  # centred at N / 2
            n = np.arange(N)
            d = n - N / 2
            sel = np.abs(d) < span
            ax.plot(d[sel], pred.U[sel] - pred.U[sel][0], "C3-", lw=1.2,
                    label=f"predicted (kink height {sol.kink_height:.3g})")
        else:  # on an infinite chain: U = sum of the strain mu (|E|^2 - background)
            bg = 0.0 if sol.kind == "bright" else (sol.amplitude / 2) ** 2
            U = np.cumsum(sol.mu * (np.abs(sol.envelope(xs)) ** 2 - bg)) * (xs[1] - xs[0])
            ax.plot(xs, U - U[0], "C3-", lw=1.2,
                    label=f"predicted (kink height {sol.kink_height:.3g})")
        if run is not None and run.U is not None:
            d = (n - last.centre + N / 2) % N - N / 2
            order = np.argsort(d)
            sel = order[np.abs(d[order]) < span]
            ax.plot(d[sel], run.U[-1][sel] - run.U[-1][sel][0], ".", ms=2, color="0.4",
                    label=f"measured (kink height {last.kink_height:.3g})")
        ax.legend(fontsize=7)
    else:
        ax.text(0.5, 0.5, "case rotation: no U field, no kink", transform=ax.transAxes,
                ha="center")
    ax.set(xlabel="site from the centre $n - n_c$", ylabel="$U_n - U$ at the left edge",
           title="(b) kink of U", xlim=(-span, span))
    ax = axes[2]
    if run is not None:
        t, c = run.t, run.series("centre")
        ax.plot(t, c - c[0], "o", ms=3, color="0.3",
                label=f"measured (v = {run.velocity:.4g} sites/T)")
        ax.plot(t, sol.velocity * t, "C3-", lw=1.2,
                label=f"predicted v_g t (v_g = {sol.velocity:.4g} sites/T)")
        ax.legend(fontsize=7)
    else:
        t = np.linspace(0, 20 * w / max(abs(sol.velocity), 1e-12), 50)
        ax.plot(t, sol.velocity * t, "C3-", lw=1.2,
                label=f"predicted (v_g = {sol.velocity:.4g} sites/T)")
        ax.text(0.05, 0.85, "no run: --simulate measures it", transform=ax.transAxes,
                fontsize=8)
        ax.legend(fontsize=7, loc="lower right")
    ax.set(xlabel="$T$ (lattice units)", ylabel="centre moved (sites)",
           title="(c) trajectory")
    fig.suptitle(f"alpha = {m.alpha:g}, K_s = {m.K_s:g}, K_theta = {m.K_theta:g}; case "
                 f"{sol.case}, k = {sol.k:.6g}, amplitude {sol.amplitude:g} rad, "
                 f"{sol.theory}" + (f"; ring N = {run.N}" if run is not None else ""),
                 fontsize=9)
    return fig
