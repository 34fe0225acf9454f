"""MI maps over (delta, k): exact theory maps and maps by simulation.

Imports ``numerics.lattice`` and ``numerics.theory``; nothing below imports it.

Exact maps       resonance_map (bands from their resonance conditions, sampling-independent)
One cell         simulate_cell (the simulated verdict, growth factor, early stop),
                 cell_step (its method and step), growth_of, measured_peak_gain
Maps by sim.     MapParameters (what defines a map), parse_spec (``v1,v2`` or
                 ``start:stop:num``), run_map (cells as tasks on a Dask cluster, results in
                 a resumable Zarr store), theory_columns, agreement (AGREEMENT_MARGIN)
On a GPU         gpu_status (is there one, or what is missing), simulate_cells_gpu
                 (simulate_cell for many cells in one launch), simulate_map_cells_gpu
"""

from ._cells import cell_step, growth_of, measured_peak_gain, simulate_cell
from ._resonance import resonance_map
from ._params import CRITERION, MapParameters, local_cores, parse_spec
from ._agreement import MARGIN as AGREEMENT_MARGIN, agreement
from ._blocks import simulate_block
from ._columns import theory_columns
from ._store import MapCellError, open_or_create, run_map
from ._gpu import gpu_status, simulate_cells_gpu, simulate_map_cells_gpu

__all__ = [
    "resonance_map", "simulate_cell", "cell_step", "growth_of", "measured_peak_gain",
    "MapParameters",
    "parse_spec", "run_map", "theory_columns", "agreement", "AGREEMENT_MARGIN",
    "open_or_create",
    "simulate_block", "CRITERION", "MapCellError", "local_cores",
    "gpu_status", "simulate_cells_gpu", "simulate_map_cells_gpu",
]
