"""A map of any lattice model (``flexmm map --model``) for the one map engine.

``ModelMapParameters`` answers what ``_store.run_map`` asks of a map (its grid, coordinates,
variables, attributes and the task a worker runs on a block of cells), as ``MapParameters``
does for the paper chain: the same store (``OUT/map.zarr``: int8 tri-state verdicts,
checksums, lock, resume, repair, consolidated metadata), the same Dask tasks.

Dims are the map's two axes, named by the parameter's own name, or ``k`` (rows first: the
parameter, then k when k is an axis). A task (:func:`model_block`) computes its cells with
``numerics.models.map_cells``: the semi-discrete NLS per cell, the exact lattice theory and
the four-wave theory on the ring of N sites (``exact``, or a simulated map), and the seeded
runs from the exact wave; its variables' codes and attributes are ``_model_columns``'.
The model travels to the workers as its file text and is loaded there once per process.
"""

from __future__ import annotations

import functools
import math
from dataclasses import asdict, dataclass

import numpy as np

from ..lattice import GROWTH_THRESHOLD
from ._columns import MI
from ._model_columns import (
    LOSSY_SIMULATED_COLUMNS,
    MODE_KIND_CODES,
    SIMULATED_COLUMNS,
    VERDICT_CODES,
    derived_attrs,
    model_block,
    simulated_verdict_attrs,
    slow_for_run,
    unsampled_band,
)
from ._model_store import new_dataset, other_map
from ._params import DEFAULT_BLOCK

#: rough seconds per cell on one core (the resume message's estimate): the NLS, the exact
#: theory on a ring of 128 sites, one run of T = 1000 on 128 sites; measured serially for
#: flexmm (k 0.6 .. 1.2, a = 0.1) on the 2-core VM at load ~4: exact 2-5 s, a run of
#: T = 2000 0.4-0.5 s once compiled. Other models and rings differ (a one-field chain's
#: Hill problem is smaller): an order of magnitude, not a measurement of this map
CELL_SECONDS = {"nls": 0.01, "exact": 3.0, "run": 0.25}
#: the map axis of the carrier's amplitude (beside "k" and the model's parameters)
AXIS_AMPLITUDE = "amplitude"


@functools.cache
def _load(model: str, text: str, parameters: tuple):
    """The model (loaded once per process): a built-in by name when ``text`` is its file,
    else parsed from ``text``."""
    from energy import BUILTIN, load_model, parse_model

    if model in BUILTIN and model_text(model) == text:
        return load_model(model, **dict(parameters))
    return load_model(parse_model(text, model), **dict(parameters))


def model_text(model: str) -> str:
    """The text of a model's file: a built-in name's, or the file ``model``."""
    from pathlib import Path

    import energy

    # the built-in models' files ship in the energy package (energy/models/NAME.toml)
    path = (Path(energy.__file__).parent / "models" / f"{model}.toml"
            if model in energy.BUILTIN else Path(model))
    return path.read_text(encoding="utf-8")


@dataclass(frozen=True)
class ModelMapParameters:
    """Everything that defines a model's map (stored in the store's attributes).

    ``model`` is a built-in name or a model file's path; ``text`` its file's text (what the
    workers load); ``parameters`` every parameter's value, as (name, value) pairs (an axis'
    entry is its default, unused). ``rows`` and ``cols`` are (name, values): the axes, a
    parameter, ``"k"`` or ``"amplitude"``; ``k`` the carrier when neither axis is k;
    ``amplitude`` the carrier's amplitude, None where it is an axis. ``t_end`` None: each
    cell's runs last ``run_length`` of its exact rate.
    """

    model: str
    text: str
    parameters: tuple
    rows: tuple
    cols: tuple
    amplitude: float | None
    k: float | None = None
    branch: str | None = None
    exact: bool = False
    theory_only: bool = False
    N: int = 256
    seeds: int = 1
    t_end: float | None = None
    block: int = DEFAULT_BLOCK
    #: seconds per unit of the model's time and the lattice spacing in metres (the
    #: store's numbers stay in lattice units; these say how to convert them)
    time_unit_s: float | None = None
    length_unit_m: float | None = None
    #: where the runs start: "exact" (the exact wave), or a start the model registers
    #: (``numerics.models.extra_starts``: "paper", eq. IC, for the paper chain's energy)
    start: str = "exact"

    def __post_init__(self):
        from energy import check_value

        from ..lattice import checks
        from ._model_axes import checked_branch

        for name in ("rows", "cols"):
            given = getattr(self, name)
            if not (isinstance(given, (tuple, list)) and len(given) == 2):
                raise TypeError(f"{name} must be (axis name, values), e.g. ('k', [1.0, 2.0]), "
                                f"got {str(given)[:60]}")
            axis, values = given
            if not isinstance(axis, str):
                raise TypeError(f"{name}: the axis name must be a string, got {axis!r}")
            values = checks.real_values(f"{name} ({axis})", tuple(np.ravel(values)))
            for v in values:  # a model's numbers (a parameter's value, an amplitude) are
                check_value(f"{name} ({axis})", v)  # bounded: beyond, coefficients overflow
            if len(set(values)) < len(values):  # one cell twice, under one label
                raise ValueError(f"{name} ({axis}) repeats a value: {list(values)}")
            if axis == "k" and any(not 0 < v <= math.pi for v in values):
                raise ValueError(f"k must be in (0, pi], got {min(values):g}..{max(values):g}")
            if axis == AXIS_AMPLITUDE and any(not v > 0 for v in values):
                raise ValueError(f"amplitude must be > 0, got {min(values):g}..."
                                 f"{max(values):g}")
            object.__setattr__(self, name, (axis, values))
        if "k" in (self.rows[0], self.cols[0]) and "k" in {
                str(n) for n, _ in self.parameters}:
            # a model parameter named k: the axis 'k' is the carrier's, and a sweep of the
            # parameter read as the carrier's silently (probe 95: --param k=0.3,0.6
            # --amplitude 0.1,0.2 --k 1 mapped carriers 0.3, 0.6 and ignored --k 1)
            raise ValueError("map axis 'k' is ambiguous: the model has a parameter named 'k' "
                             "(the carrier's wavenumber is the axis 'k'); rename it in the "
                             "model file to sweep one of them")
        if self.rows[0] == self.cols[0]:
            raise ValueError(f"the two map axes must differ, got {self.rows[0]!r} twice")
        if "k" not in (self.rows[0], self.cols[0]) and self.k is None:
            raise ValueError("give k (the carrier) when neither map axis is 'k'")
        if self.k is not None:
            checks.real("k", self.k, 0.0, math.pi, high_open=False)
        object.__setattr__(self, "parameters", tuple(
            (str(n), checks.real(f"parameter {n}", v)) for n, v in self.parameters))
        names = {n for n, _ in self.parameters}
        if AXIS_AMPLITUDE in (self.rows[0], self.cols[0]):
            if AXIS_AMPLITUDE in names:
                raise ValueError(f"map axis {AXIS_AMPLITUDE!r} is ambiguous: the model has a "
                                 f"parameter named {AXIS_AMPLITUDE!r}; rename it in the model "
                                 "file to sweep one of them")
            if self.amplitude is not None:
                raise ValueError(f"amplitude is a map axis: give amplitude=None, not "
                                 f"{self.amplitude!r}")
        elif self.amplitude is None:
            raise ValueError("amplitude: give the carrier's amplitude (> 0), or make "
                             f"{AXIS_AMPLITUDE!r} one of the map's axes")
        else:
            check_value("amplitude", checks.positive("amplitude", self.amplitude))
        for axis in (self.rows[0], self.cols[0]):
            if axis not in ("k", AXIS_AMPLITUDE) and axis not in names:
                raise ValueError(f"map axis {axis!r} is neither 'k', 'amplitude' nor a "
                                 f"parameter of the model "
                                 f"({', '.join(sorted(names)) or 'none'})")
        for flag in ("exact", "theory_only"):
            if not isinstance(getattr(self, flag), (bool, np.bool_)):
                raise TypeError(f"{flag} must be True or False, got {getattr(self, flag)!r}")
        # the ring of the exact theory and the runs; checked where no ring is used too, as
        # the command line does (N = 3 went into a theory-only map's store)
        checks.integer("N", self.N, 8, 2**20 + 1)
        checks.integer("seeds", self.seeds, 1, 1001)
        checks.integer("block", self.block, 1, 10**6 + 1)
        if self.t_end is not None:
            checks.positive("t_end", self.t_end)
        for unit in ("time_unit_s", "length_unit_m"):
            if getattr(self, unit) is not None:
                object.__setattr__(self, unit, checks.positive(unit, getattr(self, unit)))
        if self.branch is not None:  # an impossible branch made every cell undetermined
            object.__setattr__(self, "branch", checked_branch(self))
        if self.start != "exact":
            from numerics.models import extra_starts

            theirs = extra_starts(self.lattice_model)
            if self.start not in theirs:
                raise ValueError(f"start must be one of {', '.join(('exact', *theirs))} for "
                                 f"model {self.lattice_model.name}, got {self.start!r}")
            if not self.ring:
                raise ValueError(f"start {self.start!r}: its runs and its theory use the "
                                 "ring: a simulated map, or exact=True")

    @classmethod
    def from_model(cls, model: str, rows: tuple, cols: tuple, amplitude: float,
                   params: dict | None = None, **options) -> ModelMapParameters:
        """The map of the built-in model or model file ``model`` at ``params`` (the other
        parameters at their defaults) over the axes ``rows`` and ``cols``; ``options``:
        the other fields (k, branch, exact, theory_only, N, seeds, t_end, block).

        Examples
        --------
        >>> p = ModelMapParameters.from_model("fput", ("beta", [0.8, 1.6]), ("k", [2.6, 2.8]),
        ...                                   0.1, params={"alpha": 1.0}, theory_only=True)
        >>> p.dims, p.grid_shape
        (('beta', 'k'), (2, 2))
        """
        from energy import load_model

        loaded = load_model(model, **(params or {}))
        return cls(model=str(model), text=model_text(str(model)),
                   parameters=tuple(loaded.params.items()), rows=rows, cols=cols,
                   amplitude=amplitude, **options)

    # --- the model and its cells
    @property
    def lattice_model(self):
        """The model at ``parameters`` (loaded once per process)."""
        return _load(self.model, self.text, self.parameters)

    @property
    def ring(self) -> bool:
        """Whether the cells use the ring of N sites (the exact theory, the runs)."""
        return self.exact or not self.theory_only

    def cell(self, i: int, j: int) -> tuple[dict, float]:
        """(the parameter values of the axes, k) at cell (i, j); its amplitude:
        :meth:`amplitude_at`."""
        at = {self.rows[0]: self.rows[1][i], self.cols[0]: self.cols[1][j]}
        k = at.pop("k", self.k)
        at.pop(AXIS_AMPLITUDE, None)
        return at, float(k)

    def amplitude_at(self, i: int, j: int) -> float:
        """The carrier's amplitude at cell (i, j): the amplitude axis' value, or the map's."""
        if self.rows[0] == AXIS_AMPLITUDE:
            return float(self.rows[1][i])
        if self.cols[0] == AXIS_AMPLITUDE:
            return float(self.cols[1][j])
        return float(self.amplitude)

    def by_amplitude(self, cells: list) -> list:
        """[(amplitude, [n, ...]), ...]: the positions n in ``cells`` (a list of (i, j))
        grouped by their cells' amplitude, in the order of first appearance (what takes one
        amplitude for many cells, ``map_cells`` and the GPU's launch, runs per group)."""
        groups: dict = {}
        for n, (i, j) in enumerate(cells):
            groups.setdefault(self.amplitude_at(i, j), []).append(n)
        return list(groups.items())

    def undefined_reason(self) -> str:
        """Why the first cell has no verdict (the semi-discrete NLS's reason)."""
        from energy import ModelError
        from numerics.models import energy_not_real, nls

        values, k = self.cell(0, 0)
        model = self.lattice_model.with_params(**values)
        try:
            r = nls(model, k, self.branch_value)
        except ModelError as exc:
            return str(exc)
        return (r.undefined or energy_not_real(model, k, self.amplitude_at(0, 0),
                                               self.branch_value)
                or "no theory has a verdict")

    def same_ring_k(self) -> str | None:
        """A note where two k values snap to one ring wavenumber (else None)."""
        from ._model_axes import same_ring_k

        return same_ring_k(self)

    @property
    def branch_value(self):
        """The branch as the model functions take it (an index or a field name)."""
        if self.branch is None:
            return None
        return int(self.branch) if self.branch.lstrip("-").isdigit() else self.branch

    # --- what the map engine asks
    @property
    def grid_shape(self) -> tuple:
        return len(self.rows[1]), len(self.cols[1])

    @property
    def dims(self) -> tuple:
        return self.rows[0], self.cols[0]

    def axis_values(self) -> tuple:
        return self.rows[1], self.cols[1]

    def store_coords(self) -> dict:
        return {self.rows[0]: self.rows[1], self.cols[0]: self.cols[1]}

    def theory_names(self) -> frozenset:
        """None: every column is a task's (the NLS per cell as well)."""
        return frozenset()

    def theory_columns(self) -> tuple:
        """The theories of this map's cells, as variable names' suffixes."""
        from numerics.models import extra_theories

        own = ("semidiscrete", "exact", "fourwave") if self.ring else ("semidiscrete",)
        if self.start != "exact":  # the theory of the state the runs start in
            from numerics.models import extra_starts

            own += (extra_starts(self.lattice_model)[self.start].column,)
        # what only this model has (the paper chain's continuum NLS: ``paper``)
        # (none on a lossy map: a damping axis from 0 has an undamped model, damped cells)
        return own + tuple(dict.fromkeys(e.column for e in
                                         extra_theories(self.lattice_model)
                                         if not self.lossy))

    def amplified(self) -> tuple:
        """The theories whose amplification a cell stores: each of ``theory_columns`` for a
        lossy model (``[dissipation]``, issue 42), none for a lossless one."""
        own = ("semidiscrete", "exact", "fourwave")  # an extra theory has no losses
        return (tuple(t for t in self.theory_columns() if t in own)
                if self.lossy else ())

    def simulated_columns(self) -> tuple:
        """The variables a simulated block writes (with ``done``): a lossy model's runs add
        their amplification (``numerics.models.lossy_runs``)."""
        return SIMULATED_COLUMNS + (LOSSY_SIMULATED_COLUMNS if self.lossy else ())

    @property
    def lossy(self) -> bool:
        """Whether the map is a lossy model's: its model damps at its values, or an axis is
        a damping parameter (the cells at zero damping then answer the lossless limit).
        A [dissipation] whose damping is zero over the whole map is the lossless map."""
        return self.lattice_model.lossy or (self.lattice_model.lattice.lossy
                                            and self.damping_axis() is not None)

    def flag_columns(self) -> dict:
        theory = ["g1", "g2", "k_simulated", "no_wave"] + [f"{kind}_{name}" for name in
                                                self.theory_columns()
                                                for kind in ("verdict", "peak_gain")]
        if "fourwave" in self.theory_columns():
            theory.append("mode_kind_fourwave")
        theory += [f"amplification{t}_{name}" for name in self.amplified()
                   for t in ("", "_time")]
        return {"done": self.simulated_columns(), "done_predicted": tuple(sorted(theory))}

    def damping_axis(self) -> str | None:
        """The map's damping axis: the rows' parameter where the model's [dissipation] uses
        it, else the columns' (``_critical.damping_parameters``); None without one."""
        from ._critical import damping_parameters

        used = damping_parameters(self.lattice_model.lattice)
        return next((a for a in self.dims if a in used), None)

    def derived_variables(self, arrays: dict) -> dict:
        """Variables computed from the finished cells (``run_map`` writes them after the
        tasks): ``nls_band_unsampled``, ``slow_for_T`` and, over a damping axis,
        ``critical_<damping>_<theory>`` per value of the other axis
        (``_critical.critical_variables``)."""
        from ._critical import critical_variables

        out = self.unsampled_band(arrays)
        out.update(slow_for_run(self, arrays))
        out.update(critical_variables(self, arrays))
        return out

    def unsampled_band(self, arrays: dict) -> dict:
        """``nls_band_unsampled`` of this map's cells (``_model_columns.unsampled_band``)."""
        return unsampled_band(self, arrays)

    def derived_attrs(self, derived: dict) -> dict:
        """The store's attributes from the derived variables (``_model_columns``)."""
        return derived_attrs(derived)

    def simulated_attrs(self) -> dict:
        """The attributes of the runs' variables as this map writes them (``run_map`` puts
        them on a theory-only store that a simulated map resumed)."""
        return {} if self.theory_only else {
            "verdict_simulated": simulated_verdict_attrs(False)}

    @property
    def task(self):
        return model_block

    def block_cost(self, i: int, js: list, arrays=None) -> tuple:
        """Longest first: a cell the exact theory calls stable runs its whole T."""
        exact = None if arrays is None else arrays.get("verdict_exact")
        stable = 0 if exact is None or self.theory_only else sum(
            exact[i, j] != MI for j in js)
        return (stable, len(js))

    def estimated_seconds(self, workers: int = 1) -> float:
        """Rough run time (CELL_SECONDS per cell, the runs scaled by N and T)."""
        cells = int(np.prod(self.grid_shape))
        per = CELL_SECONDS["nls"] + (CELL_SECONDS["exact"] * self.N / 128 if self.ring else 0)
        if not self.theory_only:
            per += (self.seeds * CELL_SECONDS["run"] * self.N / 128
                    * (self.t_end or 1000.0) / 1000.0)
        return cells * per / max(workers, 1)

    def attrs(self) -> dict:
        """The store's attributes: the model (name, file text, content hash), every
        parameter, the amplitude, N, T, seeds, the method and step of the runs."""
        out = {n: v for n, v in asdict(self).items()
               if n not in ("rows", "cols", "parameters", "text", "k", "branch", "t_end",
                            "time_unit_s", "length_unit_m", "start")}
        out.update(model=self.lattice_model.name, model_file=self.text,
                   model_hash=self.lattice_model.lattice.content_hash,
                   axes=f"{self.rows[0]} {self.cols[0]}",
                   amplitude="" if self.amplitude is None else float(self.amplitude),
                   branch="" if self.branch is None
                   else str(self.branch), k="" if self.k is None else float(self.k),
                   t_end=("run_length of each cell's exact rate" if self.t_end is None
                          else float(self.t_end)),
                   method="srkn11b (numerics.models.simulate_model)",
                   step="per cell: 0.2 of the method's stability limit over the lattice's "
                        "highest frequency, rounded so that the steps fill T",
                   growth_threshold=GROWTH_THRESHOLD, map_of="model",
                   # the layout with the no_wave flag: a store made before it (whose
                   # no-wave cells may hold an NLS verdict) is another map's
                   no_wave="no_wave: 1 where the model carries no wave of the amplitude",
                   theories=" ".join(self.theory_columns()))
        if self.start != "exact":  # a store of the exact wave's runs keeps its identity
            out["start"] = self.start
        if self.amplified():  # a lossy model's store only (a lossless store's identity kept)
            out["amplification"] = " ".join(self.amplified())
            # when each peaks (a store made before these columns has no such attribute)
            out["amplification_time"] = " ".join(self.amplified())
            if self.ring:  # the runs' columns (a theory-only --exact store has them empty)
                out["amplification_runs"] = " ".join(LOSSY_SIMULATED_COLUMNS)
        out.update({f"param_{n}": v for n, v in self.parameters
                    if n not in (self.rows[0], self.cols[0])})
        # netCDF-safe (a user's to_netcdf of the opened store): no bools, no lists of text
        out.update(exact=int(self.exact), theory_only=int(self.theory_only))
        # the units, where given ("" none: lattice units only; netCDF has no None)
        out.update(time_unit_s="" if self.time_unit_s is None else self.time_unit_s,
                   length_unit_m="" if self.length_unit_m is None else self.length_unit_m,
                   units="lattice units: time as in the model file, wavenumbers rad per "
                         "site; in SI: rates / time_unit_s (1/s), times * time_unit_s (s), "
                         "wavenumbers / length_unit_m (rad/m)")
        return out

    def identity(self) -> dict:
        """The attributes a store of this map holds: all but theory_only and exact (a
        simulated map continues a theory-only store of the same theories, ``theories``)
        and the model file's text (its comments and description may change; its energy
        is the content hash, its parameter values the ``param_`` attributes)."""
        return {n: v for n, v in self.attrs().items()
                if n not in ("theory_only", "exact", "model_file", "units")
                and not (n in ("time_unit_s", "length_unit_m") and v == "")}


    def other_map(self, attrs: dict) -> str:
        """What a store of another map holds: another model's, this model's before its
        energy changed, or this model's with other parameters (``_model_store``)."""
        return other_map(self, attrs)

    def new_dataset(self):
        """The store before any task: every variable at its fill value, ``done`` False
        (``_model_store``)."""
        return new_dataset(self)

__all__ = ["ModelMapParameters", "model_block", "model_text", "VERDICT_CODES",
           "MODE_KIND_CODES"]
