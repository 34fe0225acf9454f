"""Small plotting helpers shared by the figure modules (matplotlib, Agg backend)."""

from __future__ import annotations

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402,F401  (re-exported for the figure modules)

from common import paper  # noqa: E402


def image(ax, x, y, Z, **kw):
    """Raster image of Z over the uniform grids x, y (fast to draw and to save as PDF)."""
    return ax.imshow(Z, origin="lower", aspect="auto", interpolation="nearest",
                     extent=(x[0], x[-1], y[0], y[-1]), **kw)


def mark_points(ax, **kw):
    """The paper's blue (square) and green (circle) test points in a (k, delta) plane."""
    for name, marker in (("blue", "s"), ("green", "o")):
        ax.plot(paper.k(name), paper.delta(name), marker, color=name, mec="k", **kw)


def case_label(case: str) -> str:
    return "I" if case == "rotation" else "II"
