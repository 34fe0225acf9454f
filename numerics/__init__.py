"""Numerics of the flexible metamaterial chain, in three rooms that import one way only::

    numerics.lattice   the simulator of eq. `norm` (eqs. (6)-(7)) and the analysis of a run
    numerics.theory    exact plane waves, what eq. `IC` launches, Hill's method, the NLS gains
    numerics.maps      MI maps over (delta, k): exact, and by simulation on a Dask cluster

lattice imports neither theory nor maps; theory imports lattice; maps imports both. All of
them read ``generated/`` (the closed forms written by ``make derive``) and never
``derivation/``. This facade re-exports what most users need; everything else is public in
its subpackage (``from numerics.lattice import spectrum``).

Material, LatticeState, energy      the model (parameters below eq. `norm`)
simulate -> Run, resume             the paper's experiment (noisy plane wave, periodic chain)
initial_condition, STARTS           the named starts: "paper" (eq. `IC`), "discrete",
                                    "travelling" (the exact plane wave)
snap_wavenumber                     k -> the nearest 2 pi m / N a periodic chain carries
integrate, METHODS, get_method      integrators: rk4, verlet, srkn6b, srkn11b, dop853, rk45
BlowUpError, SimulationInterrupted, AccuracyWarning
GROWTH_THRESHOLD                    the MI criterion: grows more than 20x within t_end
plane_wave, PlaneWave               the exact travelling wave
launched_state                      what a start launches (wave + free waves, as a torus)
mi_gain, gain_spectrum              sideband growth rate sigma(q) by Hill's method
nls_summary, theory_gain, THEORIES  the NLS coefficients and gain curves (paper, semi-discrete)
resonance_map                       exact MI map over (k, delta)
MapParameters, run_map              simulated MI maps (Dask + Zarr)
"""

from importlib import import_module as _import_module

# maps (Dask, xarray, Zarr) is imported on first use: `flexmm coefficients` needs none of it;
# theory registers its start with lattice (the import order is the point)
from . import lattice, theory
from .lattice import (GROWTH_THRESHOLD, METHODS, STARTS, AccuracyWarning, BlowUpError,
                      LatticeState, Material, Run, SimulationInterrupted, energy, get_method,
                      initial_condition, integrate, resume, simulate, snap_wavenumber)
from .theory import (THEORIES, PlaneWave, gain_spectrum, launched_state, mi_gain,
                     nls_summary, plane_wave, theory_gain)

__all__ = [
    "lattice", "theory", "maps",
    "Material", "LatticeState", "energy", "simulate", "Run", "resume", "initial_condition",
    "STARTS", "snap_wavenumber", "integrate", "METHODS", "get_method", "BlowUpError",
    "SimulationInterrupted", "AccuracyWarning", "GROWTH_THRESHOLD",
    "plane_wave", "PlaneWave", "launched_state", "mi_gain", "gain_spectrum", "nls_summary",
    "theory_gain", "THEORIES", "resonance_map", "MapParameters", "run_map",
]


def __getattr__(name):
    if name == "maps":
        return _import_module(".maps", __name__)
    # every other public name of a subpackage stays reachable as numerics.<name>
    for sub in ("lattice", "theory", "maps"):
        mod = _import_module(f".{sub}", __name__)
        if name in mod.__all__:
            return getattr(mod, name)
    raise AttributeError(f"module 'numerics' has no attribute {name!r}")
