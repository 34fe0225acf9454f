"""MI maps over (delta, k): exact theory maps and maps by simulation.

Imports ``numerics.lattice`` and ``numerics.theory``; nothing below imports it.

Exact maps       resonance_map (re-exported from numerics.theory, where the engine lives)
One cell         simulate_cell (the simulated verdict, growth factor, early stop),
                 cell_step (its method and step), seed_majority (the seeds' verdict),
                 cell_verdict (a cell's stored verdict code: the point's three words),
                 growth_of, measured_peak_gain
One point        measure_point -> PointResult (`flexmm point`: the theories over the
                 sideband offsets, the predicted growth, a simulation with a cell's step
                 choice and seed majority); of a ModelPointSpec (any model's point: its
                 theories, runs, notes; PointInputError) -> ModelPoint (POINT_KINDS,
                 register_point_kind: each kind of point by its type), point_step, theory_curves, offset_curve, fold,
                 snap_carrier (k -> 2 pi m / N, checked), MAX_SEEDS, MAX_T_END
Maps by sim.     MapParameters (what defines a map; ModelMapParameters: a lattice model's,
                 model_text its file's text), parse_spec (``v1,v2`` or
                 ``start:stop:num``), run_map (cells as tasks on a Dask cluster, results in
                 a resumable Zarr store), theory_columns, agreement (AGREEMENT_MARGIN)
Their parts      cell_records, predict_cell, GROWTH_TOL, GROWTH_ERROR_CONSTANTS (a cell's
                 step accuracy), tri_state (gains -> verdicts), store_lock (one writer),
                 cells_done (what a store holds), local_cluster (the LocalCluster a map
                 starts: LOCAL_CLUSTER_CONFIG, Dask's settings for it)
With losses      critical_damping (where an amplification falls below 20x along a damping
                 axis: a lossy model map's critical_<damping>_<theory>), damping_parameters
Run time         estimate_map -> MapEstimate (start-up + cells at this machine's measured
                 speed, machine_speed, cached), slowed by the load average;
                 estimate_model_map (a model's map: one cell measured here,
                 probe_model_cell -> ModelCellCost); estimate_model_point (a model's
                 point after its exact theory -> PointEstimate); estimate_paper_point
                 (the paper chain's point: one short run of its ring -> PointEstimate)
On a GPU         gpu_status (is there one, or what is missing), simulate_cells_gpu
                 (simulate_cell for many cells in one launch), simulate_map_cells_gpu;
                 simulate_model_cells_gpu (any model's cells, its generated force on the
                 GPU); DEVICE_PATHS, DevicePath, register_device_path (each map kind's GPU
                 path: its theories on the CPU workers, its runs in one launch)
"""

from ..theory import resonance_map  # the exact-map engine lives with the theory
from ._agreement import MARGIN as AGREEMENT_MARGIN
from ._agreement import agreement
from ._blocks import simulate_block
from ._cells import (
                     GROWTH_ERROR_CONSTANTS,
                     GROWTH_TOL,
                     cell_records,
                     cell_step,
                     cell_verdict,
                     growth_of,
                     measured_peak_gain,
                     predict_cell,
                     seed_majority,
                     simulate_cell,
)
from ._cluster import LOCAL_CLUSTER_CONFIG, local_cluster
from ._columns import theory_columns, tri_state
from ._critical import critical_damping, damping_parameters
from ._devices import DEVICE_PATHS, DEVICES, DevicePath, register_device_path, resolve_device
from ._estimate import (
                     MapEstimate,
                     ModelCellCost,
                     PointEstimate,
                     estimate_map,
                     estimate_model_map,
                     estimate_model_point,
                     machine_speed,
                     probe_model_cell,
)
from ._gpu import gpu_status, simulate_cells_gpu, simulate_map_cells_gpu
from ._gpu_models import simulate_model_cells_gpu
from ._integrity import store_lock
from ._model_params import MODE_KIND_CODES, VERDICT_CODES, ModelMapParameters, model_text
from ._model_point import ModelPoint, ModelPointSpec, PointInputError
from ._model_point_rows import waves_in_order
from ._paper_point_estimate import estimate_paper_point
from ._params import CRITERION, MapParameters, local_cores, parse_spec
from ._point import (
                     MAX_SEEDS,
                     MAX_T_END,
                     POINT_KINDS,
                     PointResult,
                     fold,
                     measure_point,
                     offset_curve,
                     point_step,
                     register_point_kind,
                     snap_carrier,
                     theory_curves,
)
from ._store import MapCellError, cells_done, open_or_create, run_map
from ._store_open import check_store

__all__ = [
    "resonance_map", "simulate_cell", "cell_step", "growth_of", "measured_peak_gain",
    "MapParameters", "ModelMapParameters", "model_text", "VERDICT_CODES", "MODE_KIND_CODES",
    "parse_spec", "run_map", "DEVICES", "resolve_device", "theory_columns", "agreement", "AGREEMENT_MARGIN",
    "open_or_create", "check_store",
    "simulate_block", "CRITERION", "MapCellError", "local_cores",
    "seed_majority", "cell_verdict", "PointResult", "measure_point", "point_step", "theory_curves",
    "ModelPointSpec", "ModelPoint", "PointInputError", "waves_in_order", "POINT_KINDS", "register_point_kind",
    "offset_curve", "fold", "snap_carrier", "MAX_SEEDS", "MAX_T_END",
    "cell_records", "predict_cell", "GROWTH_TOL", "GROWTH_ERROR_CONSTANTS", "tri_state",
    "store_lock", "cells_done", "local_cluster", "LOCAL_CLUSTER_CONFIG",
    "simulate_block", "CRITERION", "MapCellError", "local_cores", "MapEstimate",
    "estimate_map", "machine_speed", "ModelCellCost", "probe_model_cell", "estimate_model_map",
    "PointEstimate", "estimate_model_point", "estimate_paper_point",
    "gpu_status", "simulate_cells_gpu", "simulate_map_cells_gpu", "simulate_model_cells_gpu",
    "DEVICE_PATHS", "DevicePath", "register_device_path", "critical_damping", "damping_parameters",
]
