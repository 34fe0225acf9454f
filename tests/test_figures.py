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


def _map_dataset(n_delta, n_k, seed=0):
    """A map store's columns as ``flexmm map`` writes them, with random verdicts, for the
    figure alone (no simulation): shape (n_delta, n_k)."""
    import xarray as xr

    rng = np.random.default_rng(seed)
    k = np.linspace(0.5, 1.4, n_k) if n_k > 1 else np.array([0.8])  # start:stop:num
    d = np.linspace(-0.003, 0.003, n_delta) if n_delta > 1 else np.array([0.003])
    shape = (n_delta, n_k)

    def v():
        return rng.integers(-1, 2, shape).astype(np.int8)

    return xr.Dataset(
        {"done": (("delta", "k"), rng.random(shape) < 0.8),
         "verdict_simulated": (("delta", "k"), v()),
         "verdict_paper": (("delta", "k"), v()),
         "verdict_semidiscrete": (("delta", "k"), v()),
         "verdict_exact": (("delta", "k"), v())},
        coords={"k": k, "delta": d},
        attrs={"case": "coupled", "alpha": 2.5, "K_s": 0.01851, "start": "paper",
               "amplitude": 0.02, "N": 500, "t_end": 1000.0, "growth_threshold": 20.0})


def test_a_theory_only_maps_legend_says_what_its_colours_mean():
    """A theory-only map colours the cells by the predicted verdict: MI where the predicted
    growth passes 20x, stable where it does not (the legend said 'predicted growth > 20x:
    stable' for the black cells)."""
    from cli.map import plot_map

    ds = _map_dataset(3, 3, seed=1)
    ds["done"] = ds["done"] & False
    ds["done_predicted"] = ds["done"] | True
    ds["verdict_predicted"] = (("delta", "k"), np.array([[1, 0, 1], [0, 1, 0], [1, 1, 0]],
                                                        np.int8))
    fig = plot_map(ds)
    labels = [t.get_text() for leg in fig.legends + [a.get_legend() for a in fig.axes]
              if leg is not None for t in leg.get_texts()]
    assert "predicted: MI (grows > 20x)" in labels
    assert "predicted: stable (grows <= 20x)" in labels


SHAPES = ([(1, n) for n in range(1, 7)] + [(n, 1) for n in range(1, 7)]
          + [(2, 4), (3, 5), (6, 2)])


@pytest.mark.parametrize("shape", SHAPES, ids=[f"{a}x{b}" for a, b in SHAPES])
def test_map_figure_centres_every_cell_on_its_value(shape):
    """issue 35 item 1, issue 36 item 3: every grid shape draws (one delta row with 3 or 4 k
    values read as one RGBA colour before); each cell's centre is its (k, delta); each
    cell's colour is its verdict; the theories' boundaries lie on cell edges; the legend
    lists only what is drawn; the title names the material and the start."""
    from matplotlib.collections import LineCollection, QuadMesh

    from cli.map import plot_map
    from scenes._plotting import cell_edges

    ds = _map_dataset(*shape, seed=sum(shape))
    fig = plot_map(ds)
    ax = fig.axes[0]
    mesh = [c for c in ax.collections if isinstance(c, QuadMesh)]
    assert len(mesh) == 1
    corners = mesh[0].get_coordinates()  # (n_delta + 1, n_k + 1, 2)
    assert corners.shape == (shape[0] + 1, shape[1] + 1, 2)
    centre_k = (corners[:-1, :-1, 0] + corners[1:, 1:, 0]) / 2
    centre_d = (corners[:-1, :-1, 1] + corners[1:, 1:, 1]) / 2
    np.testing.assert_allclose(centre_k, np.broadcast_to(ds["k"].values, shape), rtol=1e-12)
    np.testing.assert_allclose(centre_d, np.broadcast_to(ds["delta"].values[:, None], shape),
                               rtol=1e-12, atol=1e-15)
    # the colour of each cell: white MI, black stable, grey not done or undetermined
    rgba = mesh[0].to_rgba(mesh[0].get_array()).reshape(*shape, 4)
    sim = ds["verdict_simulated"].values
    want = np.where(ds["done"].values & (sim >= 0), np.where(sim == 1, 1.0, 0.0), 0.6)
    np.testing.assert_allclose(rgba[..., 0], want, atol=0.01)
    # boundaries: every segment on a cell edge, between two cells of different verdicts
    xe, ye = cell_edges(ds["k"].values), cell_edges(ds["delta"].values)
    drawn = [c for c in ax.collections if isinstance(c, LineCollection)]
    for lc in drawn:
        for seg in lc.get_segments():
            (x0, y0), (x1, y1) = seg
            assert (np.isclose(x0, xe).any() and np.isclose(x1, xe).any()
                    and np.isclose(y0, ye).any() and np.isclose(y1, ye).any())
    labels = [t.get_text() for t in fig.legends[0].get_texts()]
    assert sum("boundary" in lab for lab in labels) == len(drawn)
    assert all(("MI" in lab) == (sim[ds["done"].values] == 1).any()
               for lab in labels if lab.startswith("simulated: MI"))
    assert "K_s = 0.01851" in ax.get_title() and "start paper" in ax.get_title()
    assert not figure_problems(fig)
    fig.savefig(__import__("io").BytesIO(), format="png")  # draws (the RGBA fault raised here)
    plt.close(fig)


def test_cell_edges_of_any_grid():
    from scenes._plotting import cell_edges

    np.testing.assert_allclose(cell_edges([1.0, 2.0, 4.0]), [0.5, 1.5, 3.0, 5.0])
    np.testing.assert_allclose(cell_edges([2.0]), [1.9, 2.1])
    np.testing.assert_allclose(cell_edges([0.0]), [-0.5, 0.5])
    # a non-uniform list (--k 0.5,0.6,1.4): no cells can be centred on every value; each
    # cell is then where its value is the nearest one (edges halfway), the value inside it
    x = np.array([0.5, 0.6, 1.4])
    e = cell_edges(x)
    assert np.all((e[:-1] < x) & (x < e[1:]))
    probe = np.linspace(e[0], e[-1], 1001)[1:-1]
    nearest = np.argmin(np.abs(probe[:, None] - x), axis=1)
    np.testing.assert_array_equal(np.searchsorted(e, probe) - 1, nearest)


def test_point_figure_of_a_failed_run_says_so(tmp_path):
    """A simulation without a linear stage and a theory without a curve leave a note on
    point.png, never an empty axes; the title names the material."""
    from types import SimpleNamespace

    import matplotlib.image as mpimg

    from cli import point
    from numerics import Material

    Q = np.linspace(0, np.pi, 11)
    th = {"paper NLS": {"offset": Q, "curve": np.full(Q.shape, np.nan),
                        "reason": "g1 = 0: no NLS"},
          "semi-discrete NLS": {"offset": Q, "curve": np.full(Q.shape, np.nan),
                                "reason": "g1 = 0: no NLS"}}
    args = SimpleNamespace(simulate=True, seeds=2, case="coupled", start="travelling")
    captured = {}

    def keep(fig):
        captured["fig"] = fig

    import scenes._plotting as P

    old = P.plt.close
    P.plt.close = keep
    try:
        png = point._figure(th, None, 1.0, args, 0.02, Material(2.0, 0.03, 0.02),
                            "no seed had a linear stage to fit a rate over")
    finally:
        P.plt.close = old
    fig = captured["fig"]
    texts = [t.get_text() for t in fig.axes[0].texts]
    assert any("no seed had a linear stage" in t for t in texts)
    assert any("g1 = 0" in t for t in texts)
    assert "K_s = 0.03" in fig.axes[0].get_title()
    (tmp_path / "point.png").write_bytes(png)  # point._figure renders; the command writes
    assert mpimg.imread(tmp_path / "point.png").shape[0] > 100
    plt.close(fig)
