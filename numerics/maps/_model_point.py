"""MI at one point of any lattice model, three ways: the semi-discrete NLS, the exact
lattice theory on the ring (and the four-wave theory beside it), and (``simulate``) seeded
runs of the ring; a lossy model's amplifications, the curves over the sideband offset and
the notes that say where a row cannot be trusted.

``measure_point(ModelPointSpec(...))`` is ``flexmm point --model`` without the command
line, as ``measure_point(material, case, k)`` is the paper flags' point: the command
prints and writes what it returns (``point.json`` is :meth:`ModelPoint.as_dict` with the
units the command adds).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

from . import _model_point_rows as rows
from ._point import register_point_kind


class PointInputError(ValueError):
    """A model point's input refused before any theory runs (or a run it cannot make).

    Attributes
    ----------
    field : str
        The ``ModelPointSpec`` field at fault ("N", "amplitude", "start", "simulate"), so
        a caller names it as its user spells it (the command: ``--N``).
    reason : str
        What is wrong and the remedy, without the field's name.
    """

    def __init__(self, field_name: str, reason: str, label: str | None = None):
        super().__init__(f"{label or field_name}: {reason}")
        self.field = field_name
        self.reason = reason


@dataclass(frozen=True)
class ModelPointSpec:
    """One point of a lattice model: what ``measure_point`` measures. Checked on
    construction (``PointInputError`` or ``ValueError`` naming the field).

    Attributes
    ----------
    model : energy.Model
        The loaded model (``energy.load_model``), its parameters set (a name is refused:
        TypeError).
    k : float
        Carrier wavenumber (rad per site) in (0, pi], snapped to 2 pi m / N (``k_ring``).
    amplitude : float
        The carrier's amplitude a (in the field its branch measures).
    branch : int or str, optional
        Dispersion branch: index or field (None: the model's branch field, else 0).
    N : int
        Sites of the ring.
    start : str
        The runs' start: "exact" (the travelling wave), "linear" (the linear plane wave),
        or a start the model registers (``numerics.models.extra_starts``: "paper").
    simulate : bool
        Also run ``seeds`` noisy rings and measure their growth.
    seeds : int
        Runs of a simulated point.
    t_end : float, optional
        Run length; default from the exact peak gain (``run_length``).
    k_ring : float
        ``k`` snapped to the ring (set on construction).
    launched : ExtraStart or None
        The registered start ``start`` names (set on construction; None for exact, linear).
    """

    model: object
    k: float
    amplitude: float
    branch: int | str | None = None
    N: int = 500
    start: str = "exact"
    simulate: bool = False
    seeds: int = 4
    t_end: float | None = None
    k_ring: float = field(init=False, repr=False)
    launched: object = field(init=False, repr=False, compare=False)

    def __post_init__(self):
        from energy import MAX_VALUE, Model, ModelError

        from ..lattice import checks
        from ..models import check_ring, extra_starts, nls, snap_ring
        from ._point import MAX_SEEDS, MAX_T_END

        checks.instance("model", self.model, Model)  # energy.load_model's, not its name
        checks.real("k", self.k, 0.0, math.pi, high_open=False)
        checks.real("amplitude", self.amplitude, 0.0, MAX_VALUE, high_open=False)
        if self.simulate:
            checks.integer("seeds", self.seeds, 1, MAX_SEEDS)
            if self.t_end is not None:
                checks.real("t_end", self.t_end, 0.0, MAX_T_END)
        starts = extra_starts(self.model)
        if self.start not in ("exact", "linear") and self.start not in starts:
            raise PointInputError("start", f"model {self.model.name} has no such start; "
                                  "use 'exact', 'linear'" + "".join(
                                      f", {n!r}" for n in starts), label=f"start {self.start!r}")
        try:  # the ring's size first: k snaps to it
            check_ring(self.N)
        except ValueError as exc:
            raise PointInputError("N", str(exc)) from None
        k, _ = snap_ring(self.k, self.N)
        object.__setattr__(self, "k_ring", k)
        try:  # an amplitude whose nonlinearity is rounding: refused, not three verdicts of it
            nls(self.model, k, self.branch).check_resolved(self.amplitude)
        except ModelError as exc:
            if str(exc).startswith("amplitude"):
                raise PointInputError("amplitude", str(exc)) from None
            # no NLS here (no carrier, a resonance): the point's theories say why
        launched = None  # a start the model registers (eq. IC): checked before any work
        if self.start not in ("exact", "linear"):
            launched = starts[self.start]
            try:
                launched.state(self.model, k, self.amplitude, self.N)
            except ModelError as exc:
                raise PointInputError("start", str(exc),
                                      label=f"start {self.start!r}") from None
        object.__setattr__(self, "launched", launched)


@dataclass(frozen=True)
class ModelPoint:
    """What ``measure_point`` found at one point of a model; ``as_dict()`` is its
    ``point.json`` (before the units a caller adds).

    Attributes
    ----------
    spec : ModelPointSpec
    rows : dict
        point.json's object: the inputs, one object per theory (and "simulated"),
        "ring_misses", "curves", "notes".
    ring_note, reach_note : str or None
        Where the ring carries none of the NLS's band; where the NLS fails against the
        exact lattice theory (both also in "notes").
    warnings : tuple of str
        The NLS coefficients' warnings (also in "notes").
    start_label : str or None
        The row of a registered start's own theory ("exact lattice, paper start").
    estimate : PointEstimate or None
        The runs' estimate, made before them (``simulate``).
    mode_note : str or None
        Where the exact lattice's fastest mode is not the carrier's sidebands (the NLS
        cannot see it), or the four-wave row's rate is 25% off the exact one (also in
        "notes").
    """

    spec: ModelPointSpec
    rows: dict
    ring_note: str | None
    reach_note: str | None
    warnings: tuple
    start_label: str | None
    estimate: object = None
    mode_note: str | None = None

    def as_dict(self) -> dict:
        """point.json's object (a new dict: a caller adds its units to it)."""
        return dict(self.rows)


def _estimate(spec, hill, gain, figure, peak_time=None):
    """The runs' estimate (``estimate_model_point``: one run measured here), their T the
    exact (or the start's) rate's unless ``t_end``; a lossy model's runs' the cap they run
    to at most (``rows.lossy_cap``, past the exact amplification's ``peak_time``: a point
    estimated at the lossless T = 2800 ran to 9.5e4, 8 s for 1 s estimated)."""
    from numerics.models import time_scale, visible_gain

    from ..lattice import run_length
    from ._estimate import estimate_model_point
    cap = rows.lossy_cap(spec.model, spec.t_end, hill, peak_time)
    t_end = cap if cap is not None else run_length(
        visible_gain(hill, spec.N) if gain is None else gain,
        time_scale=time_scale(spec.model)).t_end
    return estimate_model_point(spec.model, spec.k_ring, spec.amplitude, spec.branch,
                                N=spec.N, seeds=spec.seeds, t_end=t_end, figure=figure,
                                wave=hill.wave, at_most=cap is not None and spec.t_end is None)


def measure_model_point(spec: ModelPointSpec, *, on_estimate=None,
                        estimate_figure: bool = False) -> ModelPoint:
    """MI at one point of a model: its theories, and (``spec.simulate``) its runs.

    Parameters
    ----------
    spec : ModelPointSpec
    on_estimate : callable, optional
        Called with the runs' ``PointEstimate`` before they start (a command says it).
    estimate_figure : bool
        The caller draws point.png afterwards: counted in the estimate.

    Returns
    -------
    ModelPoint

    Raises
    ------
    PointInputError
        ``simulate`` where the model has no travelling wave at this point (field
        "simulate").
    """
    from energy import ModelError

    from ..models import exact_gain_checked, extra_theories, four_wave

    model, k, amplitude, branch, N = spec.model, spec.k_ring, spec.amplitude, spec.branch, \
        spec.N
    co = rows.coefficients_row(model, k, amplitude, branch)
    out = {"model": model.name, "parameters": dict(model.params), "k": co["k"],
           "k_requested": float(spec.k), "N": N, "amplitude": co["amplitude"],
           "branch": co["branch"], "field": co["field"]}
    if co.get("field_rule"):  # why a measures that field (one rule for index and name)
        out["field_rule"] = co["field_rule"]
    for extra in extra_theories(model):  # the paper chain's continuum NLS, say
        out[extra.label] = extra.row(model, k, amplitude)
    out["semi-discrete NLS"] = {"verdict": co["verdict"], "peak_gain": co["peak_gain"],
                                "fastest_offset": co["fastest_offset"],
                                "band_edge": co["band_edge"], "g1": co["g1"], "g2": co["g2"],
                                "reason": co["reason"]}
    ring_note = rows.ring_note(model, k, amplitude, branch, N, out["semi-discrete NLS"])
    try:
        hill = exact_gain_checked(model, k, amplitude, branch, N=N)
        out["exact lattice"] = rows.exact_row(hill)
    except ModelError as exc:  # no travelling wave: the theory has no verdict here
        hill = None
        out["exact lattice"] = {"verdict": "undefined", "peak_gain": None,
                                "reason": str(exc)}
    fw = four_wave(model, k, amplitude, branch, N=N)
    out["four-wave"] = fw.row()
    rows.decay_named(out)  # one name for the carrier's three-wave decay, as the notes'
    out["ring_misses"] = [] if hill is None else rows.missed_bands(model, k, amplitude,
                                                                   branch, N)
    start_curve, start_gain, start_label = None, None, None
    if spec.launched is not None:  # the theory of the state this start launches
        row = spec.launched.theory(model, k, amplitude, N)
        start_curve = row.pop("curve", None)
        start_label = row.pop("label")
        out[start_label] = row
        start_gain = row["peak_gain"] or 0.0
    if spec.simulate and hill is None:
        raise PointInputError("simulate", out["exact lattice"]["reason"])
    if model.lossy:
        rows.add_losses(model, k, amplitude, branch, N, out, hill, fw)
    estimate = None
    if spec.simulate:  # the long part (its T known from the exact rate): said before
        estimate = _estimate(spec, hill, start_gain, estimate_figure,
                             out["exact lattice"].get("amplification_time"))
        if on_estimate is not None:
            on_estimate(estimate)
        out["simulated"] = rows.simulated_row(
            model, k, amplitude, branch, N, spec.seeds, spec.t_end, hill, spec.start,
            out["exact lattice"].get("amplification_time"), gain=start_gain)
    from ._model_point_curves import CURVES, curve, model_theory_curves

    out["curves"] = {"description": CURVES,
                     **model_theory_curves(model, k, amplitude, branch, N, hill, fw,
                                           rows.own_offset(out["exact lattice"], k))}
    if start_curve is not None:
        out["curves"][start_label] = curve(*start_curve)
    if spec.simulate:
        out["curves"]["simulated"] = out["simulated"].pop("curve")
    # the table's notes for a script too (the rings' missed bands: ring_misses)
    reach = rows.reach_note(model, k, amplitude, branch, out)
    mode = rows.mode_note(out)
    blind = rows.harmonic_note(hill, N)
    unsettled = out["exact lattice"].get("not_converged")
    if unsettled:  # the exact row's rate is not converged: said on its line
        blind = f"{blind}; {unsettled}" if blind else unsettled
    if blind and mode:  # one sentence for the table's one line of the exact row
        mode = f"{mode}; {blind}"
    elif blind:
        mode = blind
    out["notes"] = [n for n in (mode, ring_note, reach) if n] + list(co["warnings"])
    return ModelPoint(spec=spec, rows=out, ring_note=ring_note, reach_note=reach,
                      warnings=tuple(co["warnings"]), start_label=start_label,
                      estimate=estimate, mode_note=mode)


register_point_kind(ModelPointSpec, measure_model_point)

__all__ = ["ModelPointSpec", "ModelPoint", "PointInputError", "measure_model_point"]
