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


def image(ax, x, y, Z, **kw):
    """Raster image of Z over the uniform grids x, y (fast to draw and to save as PDF)."""
    return ax.imshow(Z, origin="lower", aspect="auto", interpolation="nearest",
                     extent=(x[0], x[-1], y[0], y[-1]), **kw)


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
