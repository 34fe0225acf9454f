"""A paper map cell whose runs grew, but less than the threshold, is undetermined (-1), as
the point says; before, the map stored it 0 ("stable"), a verdict a longer run overturns.

The cell: the paper's green point, rotation case, N = 100, T = 2000 (one seed): its run
grows 7.5x (exponentially: ``growth_exponential`` 7.5), between sqrt(20) = 4.5 (below:
"no growth within T") and 20 (above: MI); at T = 2500 it grows 16x, at 4000 past 20x
(the exact lattice's rate ~1e-3: MI, a longer run decides it).
"""

from __future__ import annotations

import math

import numpy as np

from common import paper
from numerics import measure_point
from numerics.lattice import GROWTH_THRESHOLD
from numerics.maps import MapParameters, agreement, cell_verdict, run_map, simulate_block

GREEN = paper.POINTS["green"]
CELL = dict(case="rotation", alpha=paper.ALPHA, K_s=paper.K_S,
            delta=(paper.K_S - GREEN["K_theta"],), k=(GREEN["k"],),
            amplitude=paper.AMPLITUDE, N=100, t_end=2000.0, seeds=1)


def test_the_rule_is_the_points():
    """1 above the threshold (most seeds), 0 below its square root (the median), -1 between
    and where a run gave no finite factor."""
    low = math.sqrt(GROWTH_THRESHOLD)
    assert cell_verdict([1.2 * GROWTH_THRESHOLD], 100.0) == 1
    assert cell_verdict([0.9 * low], 100.0) == 0
    assert cell_verdict([1.1 * low], 100.0) == -1
    assert cell_verdict([0.9 * GROWTH_THRESHOLD], 100.0) == -1
    assert cell_verdict([math.inf], 100.0) == -1
    # two seeds of three past the threshold: MI; one of three: the median decides
    assert cell_verdict([30.0, 25.0, 1.0], 100.0) == 1
    assert cell_verdict([30.0, 1.0, 1.5], 100.0) == 0
    # a run stopped at its first record (t 0) or a NaN time: still a code, not an error
    assert cell_verdict([30.0], 0.0) == 1 and cell_verdict([1.0], math.nan) == 0


def test_a_cell_that_grew_less_than_the_threshold_is_undetermined_as_the_point_says(tmp_path):
    p = MapParameters(**CELL)
    row = simulate_block(p, 0, [0])["rows"][0]
    # the band: more than noise, less than the threshold (the cell is chosen for it)
    assert math.sqrt(GROWTH_THRESHOLD) < row["growth_exponential"] < GROWTH_THRESHOLD
    assert row["verdict_simulated"] == -1
    res = measure_point(p.material_at(0), p.case, p.k_simulated[0], p.amplitude, N=p.N,
                        simulate=True, t_end=p.t_end, seeds=p.seeds)
    assert res.simulated["verdict"] == "undetermined"
    # the store keeps it, the agreement leaves it out and counts it
    ds = run_map(p, tmp_path, workers=1, progress=False, log=lambda *_: None)
    assert bool(ds["done"].values.all())
    assert int(ds["verdict_simulated"].values[0, 0]) == -1
    assert "undetermined" in ds["verdict_simulated"].attrs["verdict_words"]
    ag = agreement(ds)
    assert ag["simulated_undetermined_cells"] == 1
    assert all(np.isnan(ag[n]) for n in ("exact", "paper", "semidiscrete") if n in ag)
