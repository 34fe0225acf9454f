"""A model map's figure (issue 44, item 9): no empty parentheses in the title when every
parameter is swept, and cells drawn within k in (0, pi) only."""

from __future__ import annotations

import matplotlib.figure
import numpy as np

from cli.app import main as cli


def _figures(monkeypatch):
    """The figures the command saves: (titles, the meshes' x and y extents)."""
    seen = []

    def savefig(fig, *a, **kw):
        # what the panels share (the model, its fixed parameters, the amplitude) is the
        # figure's title, above them; each panel's own title names its theory
        for ax in fig.axes:
            mesh = ax.collections[0]
            xy = mesh.get_coordinates()
            seen.append((fig.get_suptitle() + " | " + ax.get_title(),
                         (xy[..., 0].min(), xy[..., 0].max()),
                         (xy[..., 1].min(), xy[..., 1].max())))

    monkeypatch.setattr(matplotlib.figure.Figure, "savefig", savefig)
    return seen


def test_title_without_empty_parentheses_when_every_parameter_is_swept(tmp_path, monkeypatch):
    seen = _figures(monkeypatch)
    assert cli(["map", "--model", "fput", "--param", "alpha=0.5,1", "--param", "beta=1,2",
                "--k", "2.5", "--amplitude", "0.1", "--theory-only", "--out",
                str(tmp_path / "m")]) == 0
    assert seen and all("()" not in title and title.startswith("fput, a = 0.1")
                        for title, _, _ in seen)


def test_cells_are_drawn_within_k_in_0_pi(tmp_path, monkeypatch):
    seen = _figures(monkeypatch)
    assert cli(["map", "--model", "fput", "--param", "alpha=1", "--param", "beta=1,2",
                "--k", "0.3:3.0:2", "--amplitude", "0.1", "--theory-only", "--out",
                str(tmp_path / "m")]) == 0
    assert seen
    for title, (x0, x1), _ in seen:
        assert "(alpha = 1)" in title
        assert 0 <= x0 and x1 <= np.pi
