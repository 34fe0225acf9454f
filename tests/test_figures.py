"""Every figure is talk-ready: each panel with data has both axis labels, every colour map
has a key (a colorbar or a legend), the layout is constrained, no tick labels overlap and
nothing is cut off.

The scenes' figures are redrawn from the data.h5 of the session's quick run (the
``quick_scenes`` fixture of conftest.py): nothing is simulated here. The checker itself is
tested on deliberately bad figures, so a pass means something.
"""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest
from matplotlib.cm import ScalarMappable
from matplotlib.layout_engine import ConstrainedLayoutEngine
from matplotlib.transforms import Bbox

import scenes
from scenes import plt

ROOT = Path(__file__).resolve().parents[1]
#: a text may reach this far (pixels) past the canvas edge before it counts as cut off
EDGE_TOLERANCE = 1.0


def figure_problems(fig) -> list[str]:
    """What keeps ``fig`` from being shown in a talk, one line per problem (empty: none)."""
    fig.canvas.draw()  # positions and sizes of every text, as saved
    renderer = fig.canvas.get_renderer()
    colorbars = _colorbars(fig)
    cbar_axes = {id(cb.ax) for cb in colorbars}
    keyed = [(cb.mappable.get_cmap(), cb.mappable.norm) for cb in colorbars]
    panels = [ax for ax in fig.axes if id(ax) not in cbar_axes and ax.get_visible()
              and ax.axison and ax.has_data()]
    problems = []
    if not isinstance(fig.get_layout_engine(), ConstrainedLayoutEngine):
        problems.append("figure: not in constrained layout (labels may be cut off)")
    for i, ax in enumerate(panels):
        name = f"axes {i} ({ax.get_title() or ax.get_title('left') or 'untitled'!r})"
        for axis in ("x", "y"):
            if not _label(ax, axis, panels):
                problems.append(f"{name}: no {axis}label")
        for artist in _colour_mapped(ax):
            explained = (artist.colorbar is not None
                         or any(_same_mapping(artist, cmap, norm) for cmap, norm in keyed)
                         or ax.get_legend() is not None or fig.legends)
            if not explained:
                problems.append(f"{name}: {type(artist).__name__} maps colour without a "
                                "colorbar or legend")
        for axis in ("x", "y"):
            if _overlapping_ticks(ax, axis, renderer):
                problems.append(f"{name}: {axis} tick labels overlap")
    canvas = fig.bbox
    box = fig.get_tightbbox(renderer).transformed(fig.dpi_scale_trans)  # inches -> pixels
    if (box.x0 < canvas.x0 - EDGE_TOLERANCE or box.y0 < canvas.y0 - EDGE_TOLERANCE
            or box.x1 > canvas.x1 + EDGE_TOLERANCE or box.y1 > canvas.y1 + EDGE_TOLERANCE):
        problems.append(f"figure: drawn beyond the canvas (content {box.bounds}, canvas "
                        f"{canvas.bounds}): cut off when saved")
    return problems


def _colorbars(fig):
    """Every colorbar of the figure (found from the mappables and the colorbar axes)."""
    found = {}
    for ax in fig.axes:
        for artist in [*ax.images, *ax.collections]:
            cb = getattr(artist, "colorbar", None)
            if cb is not None:
                found[id(cb)] = cb
        cb = getattr(ax, "_colorbar", None)  # also a colorbar of a mappable on no axes
        if cb is not None:
            found[id(cb)] = cb
    return list(found.values())


def _colour_mapped(ax):
    """Images, meshes, contour sets and scatter plots of ``ax`` whose colour encodes data."""
    return [a for a in [*ax.images, *ax.collections]
            if isinstance(a, ScalarMappable) and a.get_array() is not None]


def _same_mapping(artist, cmap, norm) -> bool:
    """The colorbar of (cmap, norm) also reads ``artist``'s colours."""
    return (artist.get_cmap().name == cmap.name and type(artist.norm) is type(norm)
            and artist.norm.vmin == norm.vmin and artist.norm.vmax == norm.vmax)


def _label(ax, axis, panels) -> bool:
    """``ax`` has an ``axis`` label, or shares that axis with a panel that has one (a grid
    of panels labels its outer edge only)."""
    get = "get_xlabel" if axis == "x" else "get_ylabel"
    if getattr(ax, get)().strip():
        return True
    shared = ax.get_shared_x_axes() if axis == "x" else ax.get_shared_y_axes()
    return any(getattr(other, get)().strip() for other in shared.get_siblings(ax)
               if other is not ax and other in panels)


def _overlapping_ticks(ax, axis, renderer) -> bool:
    """Two visible tick labels of one axis (major or minor) that overlap; side by side (x)
    they must also be an em apart, or they read as one label."""
    ax_box = ax.get_window_extent(renderer)
    lo, hi = (ax_box.x0, ax_box.x1) if axis == "x" else (ax_box.y0, ax_box.y1)
    a = ax.xaxis if axis == "x" else ax.yaxis
    boxes = []
    for label in [*a.get_ticklabels(), *a.get_ticklabels(minor=True)]:
        if not (label.get_visible() and label.get_text().strip()):
            continue
        b = label.get_window_extent(renderer)
        centre = (b.x0 + b.x1) / 2 if axis == "x" else (b.y0 + b.y1) / 2
        if not lo - 1 <= centre <= hi + 1:  # ticks outside the view are not drawn
            continue
        if axis == "x":
            half_em = label.get_fontsize() * ax.figure.dpi / 72 / 2
            b = Bbox.from_extents(b.x0 - half_em, b.y0, b.x1 + half_em, b.y1)
        boxes.append(b)
    return any(b.overlaps(c) for i, b in enumerate(boxes) for c in boxes[i + 1:])


# --- the checker finds what it should -------------------------------------------------

def test_checker_flags_an_unlabelled_panel():
    fig, ax = plt.subplots(layout="constrained")
    ax.plot([0, 1], [0, 1])
    ax.set_xlabel("x (1)")
    problems = figure_problems(fig)
    plt.close(fig)
    assert problems == ["axes 0 ('untitled'): no ylabel"]


def test_checker_flags_a_colour_map_without_key_and_accepts_it_with_one():
    fig, ax = plt.subplots(layout="constrained")
    im = ax.imshow(np.arange(12.0).reshape(3, 4))
    ax.set(xlabel="x (1)", ylabel="y (1)")
    assert figure_problems(fig) == ["axes 0 ('untitled'): AxesImage maps colour without a "
                                    "colorbar or legend"]
    fig.colorbar(im, ax=ax, label="z (1)")
    assert figure_problems(fig) == []
    plt.close(fig)


def test_checker_accepts_one_colorbar_for_panels_of_the_same_colour_map():
    fig, axes = plt.subplots(1, 2, layout="constrained", sharey=True)
    Z = np.arange(12.0).reshape(3, 4)
    for ax in axes:
        im = ax.pcolormesh(Z, vmin=0, vmax=11)
        ax.set_xlabel("x (1)")
    axes[0].set_ylabel("y (1)")  # the shared y axis carries one label
    fig.colorbar(im, ax=axes.tolist())
    assert figure_problems(fig) == []
    axes[1].pcolormesh(Z, vmin=-5, vmax=5, cmap="gray")  # a second, unexplained mapping
    assert figure_problems(fig) == ["axes 1 ('untitled'): QuadMesh maps colour without a "
                                    "colorbar or legend"]
    plt.close(fig)


def test_checker_flags_overlapping_ticks_tight_layout_and_cut_off_text():
    fig, ax = plt.subplots(figsize=(3, 2))  # no constrained layout
    ax.bar([f"a long category name {i}" for i in range(4)], [1, 2, 3, 4])
    ax.set(xlabel="category", ylabel="value (1)")
    problems = figure_problems(fig)
    plt.close(fig)
    assert "figure: not in constrained layout (labels may be cut off)" in problems
    assert "axes 0 ('untitled'): x tick labels overlap" in problems
    assert any("beyond the canvas" in p for p in problems)


# --- every scene's figure, from its stored data ----------------------------------------

@pytest.mark.parametrize("name", list(scenes.REGISTRY))
def test_scene_figure_is_talk_ready(name, quick_scenes):
    data = scenes.read_data(quick_scenes[0] / name / "data.h5")
    fig = scenes.get_scene(name).plot(data)
    try:
        problems = figure_problems(fig)
    finally:
        plt.close(fig)
    assert not problems, "\n".join(problems)


def test_benchmark_figures_are_talk_ready(monkeypatch, tmp_path):
    """The work-precision and long-run plots, from the committed bench/results.json."""
    from bench import work_precision

    results = json.loads((ROOT / "bench" / "results.json").read_text())
    figures = []
    monkeypatch.setattr(work_precision.plt, "close", figures.append)  # keep, not close
    work_precision.plot(results["work_precision"], tmp_path / "wp.png")
    work_precision.plot_long_time(results["long_time"], tmp_path / "long.png")
    monkeypatch.undo()
    assert len(figures) == 2
    for fig in figures:
        problems = figure_problems(fig)
        plt.close(fig)
        assert not problems, "\n".join(problems)
