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

from . import (
               fig2_dispersion,
               fig3_g_sign,
               fig3_simulated,
               fig4_km_map,
               fig5_8_plane_waves,
               fig9_mi_band,
               gain_spectrum,
               gain_theories,
               harmonics,
               solitons,
)
from ._plotting import image, plt
from ._registry import AGREE, REGISTRY, Scene, check, get_scene, known
from ._runner import Context, read_data, replot_scene, run_all, run_scene, write_report

__all__ = ["REGISTRY", "Scene", "get_scene", "run_scene", "replot_scene", "run_all",
           "write_report", "read_data", "Context", "check", "known", "AGREE",
           "image", "plt"]
