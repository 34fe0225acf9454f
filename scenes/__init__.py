"""Scenes: every figure of the paper (and checks beyond it), and the report.

The fourth layer of the pipeline (paper eq. -> derivation -> generated -> numerics ->
scenes -> report); the command line (``cli``) sits above it, and nothing here imports it. One module per figure; each defines ``compute(ctx) -> (data,
summary)`` and ``plot(data) -> Figure`` and registers a :class:`Scene`, so a figure can
be redrawn from its ``data.h5`` without simulating (``flexmm scene NAME --replot``).

Public API
----------
REGISTRY, Scene, get_scene          the registered scenes
run_scene(name, out, quick, seed, force) -> summary dict
replot_scene(name, out)             redraw a figure from its data.h5
run_all(out, quick, seed, force)    every scene and out/report.md
read_data(path)                     a scene's data dict from its data.h5
plt, image                          pyplot (Agg backend) and the raster image the figures use
"""

from ._registry import AGREE, REGISTRY, SCENE_NAMES, Scene, check, get_scene, known

#: the runner's names, imported on first use (it imports matplotlib: `flexmm --help` and
#: `flexmm coefficients` need none of it)
_RUNNER = ("Context", "read_data", "replot_scene", "run_all", "run_scene", "write_report")


#: the plotting names commands draw with (matplotlib, imported on first use)
_PLOTTING = ("image", "plt", "map_figure", "soliton_figure", "point_figure")


def __getattr__(name):
    if name in _RUNNER:
        from . import _runner

        return getattr(_runner, name)
    if name in _PLOTTING:
        from . import _plotting

        return getattr(_plotting, name)
    raise AttributeError(f"module 'scenes' has no attribute {name!r}")

__all__ = ["REGISTRY", "SCENE_NAMES", "Scene", "get_scene", "run_scene", "replot_scene", "run_all",
           "write_report", "read_data", "Context", "check", "known", "AGREE",
           "image", "plt", "map_figure", "soliton_figure"]
