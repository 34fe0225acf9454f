"""What defines an MI map: its grid SPECs, its parameters (validated whole, before any
work), the run-time estimate, the criterion stored with it, and the cores of this machine."""

from __future__ import annotations

import math
import os
from dataclasses import InitVar, asdict, dataclass
from functools import cached_property

import numpy as np

from ..lattice import (
    GROWTH_THRESHOLD,
    Material,
    check_time,
    checks,
    get_method,
    non_carrier_bins,
    paper_start_undefined,
    shortest_run_error,
    snap_wavenumber,
)
from ..theory import MAX_AMPLITUDE, SITES
from ._cells import GROWTH_ERROR_CONSTANTS, GROWTH_TOL, RECORDS

#: k values per task (one delta row is split into blocks of this many cells)
DEFAULT_BLOCK = 4
#: seconds one simulated cell takes on one core of a 2-core laptop-class machine at
#: N = 500, T = 5000 with 11 force evaluations per unit time (srkn11b at dt = 1, about the
#: map's chosen step): bench/results.json "maps", 0.27 s at load average ~6 on the two
#: cores, ~0.12 s idle (RK4 at dt = 0.05, 80 evaluations per unit time: 0.86 s idle);
#: for the run-time estimate, scaled by the evaluations per unit time of the map's step
CELL_SECONDS = 0.15
#: seconds one cell's growth prediction takes on one core (numerics.theory.predict_growth,
#: N = 500, draws = 0, case II, the larger; measured on this machine under load ~1.5):
#: the exact travelling wave's Hill families, or, for eq. `IC`, first the torus of the
#: state it launches (~0.1 s of the 0.35 s)
PREDICT_SECONDS = {"travelling": 0.15, "paper": 0.35}
CRITERION = (f"MI when the largest non-carrier, non-harmonic component (theta; U: its "
             f"non-forced components, from its level at 5% of the run) grows more than "
             f"{GROWTH_THRESHOLD:g}x over the run, relative to the carrier (the scenes' "
             "criterion), exponentially: the factor at most exp(s L), s the log-slope over "
             "the linear stage's second half (growth_exponential; algebraic growth is no MI)"
             "; a run stops as soon as that happens (the verdict is then certain). With "
             "several seeds: the verdict of the majority, the median growth.")


#: values per map axis at most (a SPEC's num)
MAX_AXIS = 100_000


class _DropsBound(ValueError):
    """A range SPEC whose count cannot hold both of its ends."""


def parse_spec(text: str, name: str) -> np.ndarray:
    """``v1,v2,...`` or ``start:stop:num`` (inclusive) -> sorted values; ValueError else."""
    if not isinstance(text, str) or not text.strip():
        raise ValueError(f"{name}: empty SPEC; give v1,v2,... or start:stop:num")
    try:
        if ":" in text:
            parts = text.split(":")
            if len(parts) != 3:
                raise ValueError
            start, stop, num = float(parts[0]), float(parts[1]), int(parts[2])
            if num > 1 and start == stop:  # every value the same: one, said so
                raise _DropsBound(f"{name}: SPEC {text!r} asks for {num} values from "
                                  f"{start:g} to {stop:g} (start = stop: one value {num} "
                                  f"times); give start != stop, or the single value {start:g}")
            if num < 1:
                raise ValueError
            if num == 1 and start != stop:  # linspace would keep start and drop stop
                raise _DropsBound(f"{name}: SPEC {text!r} asks for 1 value between {start:g} "
                                  f"and {stop:g}, so it would drop {stop:g}; give num >= 2 "
                                  f"for both ends, or the single value {start:g}")
            values = np.linspace(start, stop, min(num, MAX_AXIS + 1))  # > MAX_AXIS: refused
            asked = num  # the count the SPEC asks for, not linspace's capped one
        else:
            values = np.array([float(v) for v in text.split(",")])
            asked = values.size
    except _DropsBound:
        raise
    except ValueError:
        raise ValueError(f"{name}: cannot read SPEC {text!r}; give v1,v2,... or "
                         "start:stop:num (num >= 1, inclusive)") from None
    if values.size > MAX_AXIS:
        raise ValueError(f"{name}: SPEC {text!r} asks for {asked} values; at most "
                         f"{MAX_AXIS} per axis")
    if not np.all(np.isfinite(values)):
        raise ValueError(f"{name}: SPEC {text!r} holds a non-finite value")
    if len(np.unique(values)) != len(values):
        raise ValueError(f"{name}: SPEC {text!r} repeats a value")
    return np.sort(values)


@dataclass(frozen=True)
class MapParameters:
    """Everything that defines a map (stored in the dataset's attributes; its rows' K_theta
    and delta, and its k, as coordinates).

    The material is ``material=`` (a Material: its alpha and K_s; the rows give K_theta), or
    ``alpha=`` and ``K_s=``. The rows are ``delta=`` (K_theta = K_s - delta) or ``K_theta=``,
    kept as given (``delta`` is then K_s - K_theta, the map's coordinate): a row's cells
    simulate, and its theories are evaluated at, ``K_theta[i]``, never K_s - (K_s - K_theta).

    Examples
    --------
    >>> from numerics import Material
    >>> p = MapParameters(case="coupled", material=Material.paper("blue"),
    ...                   K_theta=(0.01551, 0.02151), k=(0.8168,), amplitude=0.02)
    >>> p.alpha, p.K_s, p.K_theta[0], round(p.delta[0], 6)
    (2.5, 0.01851, 0.01551, 0.003)
    """

    case: str
    alpha: float | None = None  # given, or material.alpha
    K_s: float | None = None  # given, or material.K_s
    delta: tuple | None = None  # the rows: K_s - K_theta
    k: tuple | None = None
    amplitude: float | None = None  # peak rotation 2 eps A0
    eps: float = 0.01
    N: int = 500
    t_end: float = 5000.0
    seeds: int = 1
    start: str = "paper"
    dt: float | None = None  # None: chosen with the method for growth_tol (cell_step)
    method: str | None = None
    growth_tol: float = GROWTH_TOL  # relative accuracy of the growth factor the cells ask for
    noise: float = 1e-3
    theory_only: bool = False
    block: int = DEFAULT_BLOCK
    K_theta: tuple | None = None  # each row's K_theta: given, or K_s - delta[i]
    material: InitVar[Material | None] = None  # alpha and K_s (its K_theta is not used)

    def __post_init__(self, material):
        if material is not None:
            checks.instance("material", material, Material)
            if self.alpha is not None or self.K_s is not None:
                raise TypeError("give the material as material= or as alpha and K_s, not both")
            object.__setattr__(self, "alpha", material.alpha)
            object.__setattr__(self, "K_s", material.K_s)
        for name in ("alpha", "K_s", "k", "amplitude"):
            if getattr(self, name) is None:
                raise TypeError(f"MapParameters needs {name}" + (
                    " (or material=, a Material)" if name in ("alpha", "K_s") else ""))
        checks.choice("case", self.case, ("rotation", "coupled"))
        checks.choice("start", self.start, ("paper", "travelling"))
        checks.positive("alpha", self.alpha)
        checks.positive("K_s", self.K_s)
        checks.real("amplitude", self.amplitude, 0.0, MAX_AMPLITUDE)
        checks.positive("eps", self.eps)
        checks.integer("N", self.N, *SITES)  # every cell is predicted
        checks.positive("t_end", self.t_end)
        checks.integer("seeds", self.seeds, 1, 1000)
        checks.integer("block", self.block, 1, 10**6)
        checks.real("growth_tol", self.growth_tol, 1e-8, 0.5)
        checks.real("noise", self.noise, 0.0, 1.0, low_open=False)
        if self.method is not None and not get_method(self.method).fixed_step:
            raise ValueError(f"method: map cells need a fixed-step method, got "
                             f"{self.method!r}")
        if not isinstance(self.theory_only, (bool, np.bool_)):
            raise TypeError(f"theory_only must be True or False, got {self.theory_only!r}")
        if self.dt is not None:
            checks.positive("dt", self.dt)
        elif self.method is not None and self.method not in GROWTH_ERROR_CONSTANTS:
            raise ValueError(f"method: {self.method!r} has no growth-error constant to choose "
                             f"its step; give dt with it, or one of "
                             f"{', '.join(GROWTH_ERROR_CONSTANTS)}")
        k = np.asarray(checks.real_values("k", self.k))
        if np.any((k <= 0) | (k >= math.pi)):
            raise ValueError(f"k must be in (0, {math.pi:g}), got {self.k}")
        self._rows()
        # a cell advances in RECORDS pieces of t_end / RECORDS: a given step must fit in
        # one, and the run must not take an absurd number of steps (checked here, not on a
        # worker); a step still to be chosen is at most the largest stable one
        record = self.t_end / RECORDS
        dt = self.dt if self.dt is not None else min(record, _largest_stable_step(
            self.alpha, self.K_s, self.extreme_K_theta(), self.case))
        try:
            check_time(record, dt)
            check_time(self.t_end, dt)
        except ValueError as exc:
            raise ValueError(f"t_end = {self.t_end:g} with dt = {dt:g}: a cell records its "
                             f"spectrum every t_end / {RECORDS}, and {exc}") from None
        snapped = self.k_simulated
        for x, ks in zip(self.k, snapped):
            m = round(ks * self.N / (2 * math.pi))
            if m < 1 or 2 * m >= self.N or not non_carrier_bins(m, self.N).any():
                if m < 1 or 2 * m >= self.N:  # at 0 or pi: the point's words, whose remedy
                    snap_wavenumber(x, self.N)  # knows where no N up to 10^6 helps
                raise ValueError(f"N = {self.N} sites carry no wavenumber near k = {x:g} with "
                                 "sidebands to grow (k snaps to 2 pi m / N with 0 < m < N/2 "
                                 "and needs bins besides its harmonics); give a larger N")
        if self.start == "paper":  # eq. `IC` needs a real continuum frequency at every cell
            bad = [(i, why) for i in range(len(self.K_theta))
                   if (why := paper_start_undefined(self.material_at(i), snapped,
                                                    ("travelling",)))]
            if bad:
                more = f" and {len(bad) - 1} more rows" if len(bad) > 1 else ""
                raise ValueError(f"--start paper: at K_theta = {self.K_theta[bad[0][0]]:g}{more}, "
                                 f"{bad[0][1]}, or narrow --k")
        short = shortest_run_error(
            "t_end", self.t_end, [(self.material_at(i), snapped)
                                  for i in range(len(self.K_theta))], self.case)
        if short:
            raise ValueError(short)
        for j in range(1, len(snapped)):
            if snapped[j] == snapped[j - 1]:
                m = round(snapped[j] * self.N / (2 * math.pi))
                raise ValueError(
                    f"--k: {self.k[j - 1]:g} and {self.k[j]:g} both snap to 2 pi {m}/{self.N}"
                    f" = {snapped[j]:.6g}, the nearest wavenumber of a chain of N = {self.N}"
                    " sites; give fewer k values or a larger --N")

    def _rows(self):
        """Check the rows, given as delta or as K_theta, and fill in the other one."""
        if self.K_theta is None and self.delta is None:
            raise TypeError("MapParameters needs its rows: delta= or K_theta=")
        if self.K_theta is None:
            d = checks.real_values("delta", self.delta)
            if any(self.K_s - x <= 0 for x in d):
                raise ValueError(f"delta must be < K_s = {self.K_s:g} (K_theta = K_s - delta > "
                                 f"0), got {max(d):g}")
            object.__setattr__(self, "K_theta", tuple(self.K_s - x for x in d))
            return
        Kt = checks.real_values("K_theta", self.K_theta)
        if any(x <= 0 for x in Kt):
            raise ValueError(f"K_theta must be finite and > 0, got {min(Kt):g}")
        object.__setattr__(self, "K_theta", Kt)
        if self.delta is None:
            object.__setattr__(self, "delta", tuple(self.K_s - x for x in Kt))
            return
        # both (dataclasses.replace passes both): either must be K_s minus the other
        d = checks.real_values("delta", self.delta)
        if tuple(self.K_s - x for x in Kt) != d and tuple(self.K_s - x for x in d) != Kt:
            raise ValueError("give the rows as delta= or as K_theta=, not both (these "
                             "disagree: delta = K_s - K_theta)")

    def material_at(self, i: int) -> Material:
        """The material of row i: alpha, K_s and the row's K_theta."""
        return Material(self.alpha, self.K_s, self.K_theta[i])

    def extreme_K_theta(self) -> list:
        """K_theta of the rows with the smallest and the largest delta (one if they are
        the same), in order of delta: a carrier's frequency is monotone in K_theta (linear
        in it under the root of eqs. `discrete1`, `discrete2`), so the grid's fastest
        carriers sit there."""
        rows = {}
        for i, d in enumerate(self.delta):
            rows.setdefault(d, i)
        return [self.K_theta[rows[d]] for d in sorted({min(self.delta), max(self.delta)})]

    @property
    def k_simulated(self) -> tuple:
        """Each k snapped to the nearest 2 pi m / N: the wavenumber a periodic chain of N
        sites carries, which the simulation runs and the theories are evaluated at."""
        out = []
        for x in self.k:
            m = round(x * self.N / (2 * math.pi))
            out.append(2 * math.pi * m / self.N)  # m < 1: refused on construction
        return tuple(out)

    def estimated_seconds(self, workers: int = 1) -> float:
        """Rough run time: the predictions (PREDICT_SECONDS per cell) and, unless
        theory_only, the simulations (CELL_SECONDS per cell at N = 500, T = 5000, scaled
        by N t_end and the seeds; the early stop of MI cells makes it shorter)."""
        cells = len(self.k) * len(self.delta)
        predict = cells * PREDICT_SECONDS[self.start] * max(self.N / 500, 1.0)
        if self.theory_only:
            return predict / max(workers, 1)

        method, dt = self.cell_step
        per_time = get_method(method).evaluations / dt / 11  # relative to CELL_SECONDS'
        simulate = (cells * self.seeds * CELL_SECONDS * per_time * (self.N / 500)
                    * (self.t_end / 5000))
        return (predict + simulate) / max(workers, 1)

    @cached_property
    def cell_step(self) -> tuple:
        """(method, dt) every cell runs: as given, or chosen for ``growth_tol`` at the
        grid's fastest carrier (``numerics.maps._cells.map_step``)."""
        if self.dt is not None and self.method is not None:
            return self.method, float(self.dt)
        from ._cells import map_step

        mats = [Material(self.alpha, self.K_s, Kt) for Kt in self.extreme_K_theta()]
        method, dt = map_step(mats, self.case, self.k_simulated, self.N, self.t_end,
                              self.amplitude, self.start, self.growth_tol,
                              None if self.method is None else [self.method])
        return self.method or method, float(dt if self.dt is None else self.dt)

    @property
    def A0(self) -> float:
        return self.amplitude / (2 * self.eps)

    def attrs(self) -> dict:
        out = {n: v for n, v in asdict(self).items() if n not in ("delta", "k", "K_theta")}
        chosen = self.dt is None or self.method is None
        out["method"], out["dt"] = self.cell_step
        out["step"] = (f"chosen for a relative growth-factor error of {self.growth_tol:g} "
                       "(numerics.maps._cells.map_step: the error model with the growth "
                       "factor's constants, at the grid's fastest carrier)" if chosen
                       else "given")
        out.update(A0=self.A0, criterion=CRITERION, growth_threshold=GROWTH_THRESHOLD,
                   verdicts=f"True = MI: grows more than {GROWTH_THRESHOLD:g}x within t_end "
                            "(simulated: measured; theories: peak gain > ln(threshold) / "
                            "t_end, their raw peak gains beside)")
        return out


    # --- what the map engine (``_store.run_map``) asks of any map: the paper chain's
    # answers here, a lattice model's in ``_model_params.ModelMapParameters``

    @property
    def grid_shape(self) -> tuple:
        """(rows, columns) of the store: (delta, k)."""
        return len(self.delta), len(self.k)

    @property
    def dims(self) -> tuple:
        return "delta", "k"

    def axis_values(self) -> tuple:
        """The rows' and the columns' values (cells named in messages)."""
        return self.delta, self.k

    def store_coords(self) -> dict:
        """The coordinates a store of this map holds, as this map gives them (a store whose
        coordinates differ holds another map)."""
        return {n: getattr(self, n) for n in ("delta", "K_theta", "k", "k_simulated")}

    def theory_names(self) -> frozenset:
        """The variables recomputed from the parameters alone (where a store lost them)."""
        from ._columns import THEORY_NAMES

        return frozenset(THEORY_NAMES)

    def flag_columns(self) -> dict:
        """Each done flag and the variables its tasks write."""
        from ._columns import PREDICTED, SIMULATED

        return {"done": SIMULATED, "done_predicted": PREDICTED}

    def identity(self) -> dict:
        """The attributes a store of this map holds (a store whose attributes differ
        holds another map): all but theory_only (a simulated map resumes a theory-only
        one's store)."""
        return {n: v for n, v in self.attrs().items() if n != "theory_only"}

    def other_map(self, attrs: dict) -> str:
        """What a store of another map holds, in words (its attributes ``attrs``)."""
        if attrs.get("map_of") == "model":  # `map --model`'s store, not this chain's flags
            return f"a map of model {attrs.get('model')!r} (flexmm map --model)"
        from ._columns import OLDER_FORMATS, STORE_FORMAT

        fmt = attrs.get("store_format")
        if isinstance(fmt, int) and fmt < STORE_FORMAT:
            return (f"a map of an older format (store_format {fmt}, this version writes "
                    f"{STORE_FORMAT}: {OLDER_FORMATS.get(fmt, OLDER_FORMATS[2])})")
        return "a map with other parameters (or of an older format)"

    def new_dataset(self):
        """The store's dataset before any task: the theory columns filled in."""
        from ._columns import empty_dataset, theory_columns

        return empty_dataset(self, theory_columns(self))

    @property
    def task(self):
        """The function a worker runs on a block: ``task(params, i, js, simulate)``."""
        from ._blocks import simulate_block

        return simulate_block

    def block_cost(self, i: int, js: list, arrays=None) -> tuple:
        """The block's expected cost, for the longest-first order: a cell the exact theory
        calls stable runs the whole t_end (an MI cell stops once it passed 20x), and a
        prediction's Bloch families grow with k (one per 2 pi / N up to k)."""
        exact = None if arrays is None else arrays.get("verdict_exact")
        k = np.asarray(self.k_simulated, float)
        stable = 0 if exact is None or self.theory_only else sum(
            exact[i, j] != 1 for j in js)
        return (stable, float(k[list(js)].sum()))


def _largest_stable_step(alpha, K_s, K_theta, case) -> float:
    """The largest step any map method may take on this grid (its extreme K_theta): 0.8 of
    the most stable method's limit over the grid's highest frequency
    (``_accuracy.STABILITY_MARGIN``)."""
    from ..lattice import ERROR_CONSTANTS, STABILITY_MARGIN

    w = max(Material(alpha, K_s, Kt).omega_max(case) for Kt in K_theta)
    limit = max(get_method(m).stability_limit() for m in {*ERROR_CONSTANTS,
                                                          *GROWTH_ERROR_CONSTANTS})
    return STABILITY_MARGIN * limit / w


def local_cores() -> int:
    """Cores this process may use: the default number of LocalCluster workers."""
    return max(1, len(os.sched_getaffinity(0)) if hasattr(os, "sched_getaffinity")
               else os.cpu_count() or 1)
