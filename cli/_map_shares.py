"""The one definition of a map's share of MI, shared by the paper chain's map
(``cli.map``) and a model map's summary (``cli._model_map_summary``)."""

from __future__ import annotations

import numpy as np


def mi_fraction(v: np.ndarray) -> float:
    """Share of MI among the cells a verdict decides (int8 tri-state: 1 MI, 0 stable, -1
    undetermined, left out); NaN where it decides none."""
    decided = v >= 0
    return float((v[decided] == 1).mean()) if decided.any() else float("nan")
