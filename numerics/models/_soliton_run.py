"""Any model's envelope soliton launched in its lattice and tracked (``flexmm soliton --model
... --simulate``), as ``numerics.theory.simulate_soliton`` does for the paper's chain; the
launch, the multiple-scales solution on the ring, is ``_soliton_ring``'s ``ring_soliton``.

The measurement (``_soliton_measure``): the carrier field's analytic signal z = u + i u_dot / Omega, band-passed
around +k (|q - k| < k/2: the mean at q = 0 and the second harmonic at 2k outside), is
2 E e^{i theta}; |z|^2 is fitted by a^2 sech^2 (bright) or a^2 (1 - D sech^2) (dark) for
the centre, amplitude and width; its phase, demodulated, gives the frequency; each
acoustic field's strain low-passed at |q| < k/2 and summed over +-8 widths gives its kink.
"""

from __future__ import annotations

import math
import numbers
from dataclasses import dataclass, field

import numpy as np

from energy import Model, ModelError

from ._args import scalar
from ._nls import nls
from ._soliton_measure import frequency_of, measure_snapshot, phasor
from ._soliton_ring import (
    KINDS,
    MAX_T_END,
    MIN_WIDTH,
    RingSoliton,
    default_ring,
    ring_soliton,
    ring_wavenumber,
    soliton_ring,
)


@dataclass(frozen=True)
class ModelSolitonRun:
    """A model's soliton launched on a ring and tracked.

    Attributes
    ----------
    predicted : RingSoliton
        At the ring's k (``k_asked`` is what was asked).
    N, t_end, dt, method : the run.
    snapshots : tuple of ModelSnapshot, one per record (the first at t = 0).
    frequency : float
        Measured carrier frequency (1/time).
    energy : ndarray, shape (n_snapshots,)
        Total energy at each record.
    fields : ndarray, shape (n_snapshots, d, N)
        The recorded displacements, for the figure.
    """

    predicted: RingSoliton
    k_asked: float
    N: int
    t_end: float
    dt: float
    method: str
    snapshots: tuple
    frequency: float
    energy: np.ndarray = field(repr=False)
    fields: np.ndarray = field(repr=False)

    @property
    def model(self) -> Model:
        return self.predicted.nls.model

    @property
    def t(self) -> np.ndarray:
        return np.array([s.t for s in self.snapshots])

    def series(self, name: str) -> np.ndarray:
        return np.array([getattr(s, name) for s in self.snapshots])

    @property
    def velocity(self) -> float:
        """Least-squares slope of the unwrapped centre against time (sites per time)."""
        return float(np.polyfit(self.t, self.series("centre"), 1)[0])

    @property
    def energy_drift(self) -> float:
        """max |E(t) - E(0)| / |E(0)| over the records (E = 0 at rest)."""
        return float(np.max(np.abs(self.energy - self.energy[0])) / abs(self.energy[0]))

    def measured(self) -> dict:
        """The counterparts of :meth:`RingSoliton.summary` (width, amplitude and kinks:
        the median over the second half of the run, the settled soliton, which a ripple
        of the launch's radiation crossing it at one record does not move), the radiation
        and shape misfit at the end, the distance travelled in widths, the energy drift
        and the drifts (end / start - 1) of width and amplitude."""
        first, last = self.snapshots[0], self.snapshots[-1]
        late = self.snapshots[len(self.snapshots) // 2:]
        names = self.model.fields
        out = {"velocity": self.velocity,
               "width": float(np.median([s.width for s in late])),
               "amplitude": float(np.median([s.amplitude for s in late])),
               "frequency": self.frequency}
        for i in self.predicted.kink_fields():
            out[f"kink_{names[i]}"] = float(np.median([s.kink[i] for s in late]))
        out.update({"radiation": last.radiation, "shape_misfit": last.shape_misfit,
                    "travelled_widths": abs(last.centre - first.centre) / self.predicted.width,
                    "energy_drift": self.energy_drift,
                    "drift": {"width": last.width / first.width - 1,
                              "amplitude": last.amplitude / first.amplitude - 1}})
        if self.predicted.kind == "dark":
            out["depth"] = last.depth
        return out

    def errors(self) -> dict:
        """measured / predicted - 1 of each quantity of the prediction's summary."""
        p = self.predicted.summary(self.model.fields)
        m = self.measured()
        return {key: (m[key] / p[key] - 1) if p[key] else math.nan for key in p}


#: the shortest travel measured (widths): fput (beta 1) at k = 1, a 0.05 measured its
#: velocity within 0.3% from travel 1e-3 to 1, off by 7% at 1e-10 and by 1e89 at 1e-100
#: (its position's round-off over a step of 1e-100 widths; probe 99)
MIN_TRAVEL = 0.1

#: the narrowest soliton launched (sites): narrower, the envelope is no envelope
MIN_LAUNCH_WIDTH = 2.0
#: the band-pass at |q - k| < k/2 keeps the envelope's spectrum (sech(pi q w / 2)) to 1e-4
#: of its peak where k w >= 6 (to 9% at k w = 2)
MIN_SEPARATION = 6.0


def check_soliton_launch(model: Model, pred: RingSoliton, k_asked: float | None = None):
    """Refuse (ModelError) a launch of ``pred`` (``ring_soliton``'s) the lattice cannot
    carry or the measurement cannot see, each with its remedy: what ``simulate_soliton``
    asks before it runs (a command asks it before estimating the run). ``k_asked``: the
    k the ring's was moved from (the remedy's ring moves it again)."""
    from ._reach import energy_not_real

    if model.lossy and any(np.any(m != 0) for m in model.damping):
        raise ModelError(f"model {model.describe()} has [dissipation]: its soliton decays, "
                         "and the NLS it is measured against is lossless; give its damping "
                         "parameters 0 with --param (flexmm soliton --model ... --param "
                         "NAME=0) to launch the lossless one")
    a, w = pred.soliton.amplitude, pred.width
    why = energy_not_real(model, pred.k, a, pred.nls.carrier.branch)
    if why is not None:
        raise ModelError(why)
    if w < MIN_LAUNCH_WIDTH:
        raise ModelError(f"the {pred.kind} soliton of amplitude {a:g} is {w:.3g} sites wide "
                         f"(< {MIN_LAUNCH_WIDTH:g}): no envelope; amplitude <= "
                         f"{a * w / MIN_WIDTH:.3g} makes it {MIN_WIDTH:g} sites wide")
    if pred.k * w < MIN_SEPARATION:
        # the wider soliton's ring (20 widths) moves k again, by up to pi / N: from the
        # asked k (KG k = 0.01, dark: ring k 0.0144 advised 0.00392, whose ring's k 0.0102
        # was refused in turn), k w' >= 6 + pi/20 keeps the ring's k w' >= 6
        k0 = pred.k if k_asked is None else min(pred.k, float(k_asked))
        advice = a * k0 * w / (MIN_SEPARATION + math.pi / 20) / 1.006  # 3 digits printed
        raise ModelError(f"k x width = {pred.k:.4g} x {w:.3g} = {pred.k * w:.3g} < "
                         f"{MIN_SEPARATION:g}: the envelope's spectrum reaches the mean "
                         "flow (q = 0), so the carrier cannot be told from it; a larger k or "
                         f"an amplitude <= {advice:.3g} (wider)")


def travel_time(pred: RingSoliton, travel: float) -> float:
    """The run time T for ``pred`` to move ``travel`` widths at v_g, or a ModelError past
    ``MAX_T_END`` naming the travel and the amplitude that fit (asked before a command's
    estimate, whose own short run on such a ring took minutes before the refusal)."""
    travel = scalar(travel)
    if isinstance(travel, (bool, np.bool_)) or not (
            isinstance(travel, numbers.Real) and math.isfinite(travel)
            and travel >= MIN_TRAVEL):
        raise ModelError(f"travel must be a number of widths >= {MIN_TRAVEL:g} (shorter, "
                         f"the measured velocity is round-off), got {travel!r}")
    travel = float(travel)
    t_end = travel * pred.width / max(abs(pred.velocity), 1e-12)
    if t_end > MAX_T_END:
        a = pred.soliton.amplitude  # T ~ width ~ 1 / a; 0.6%: the 3 digits printed
        raise ModelError(
            f"the soliton moves at {pred.velocity:.3g} sites/time: {travel:g} widths "
            f"take T = {t_end:.3g} (> {MAX_T_END:g}); give travel <= "
            f"{travel * MAX_T_END / t_end / 1.006:.3g}, or amplitude >= "
            f"{1.006 * a * t_end / MAX_T_END:.3g} "
            "(its width shrinks as 1 / amplitude)")
    return t_end


def simulate_soliton(model: Model, k: float, amplitude: float, kind: str | None = None, *,
                     branch=None, N: int | None = None, travel: float = 20.0,
                     t_end: float | None = None, snapshots: int = 21,
                     method: str = "srkn11b", dt: float | None = None) -> ModelSolitonRun:
    """Launch ``model``'s NLS soliton on a ring, integrate and track it.

    Parameters
    ----------
    model : Model
    k : float
        Carrier wavenumber (rad/site), moved to the nearest :func:`ring_wavenumber`.
    amplitude : float
        The carrier's first-harmonic amplitude a in its field: at the peak (bright) or of
        the background (dark).
    kind : {"bright", "dark"}, optional
        Default: the one the NLS has (bright where g > 0); the other is an error.
    branch : int or str, optional
        As :func:`numerics.models.nls`.
    N : int, optional
        Ring size; default :func:`default_ring` (20 widths, at least 256 sites).
    travel : float
        Run until the soliton has moved this many widths at v_g (unless ``t_end``).
    snapshots : int
        Records, t = 0 included.
    method, dt
        As :func:`numerics.models.simulate_model` (default dt: a fifth of the method's
        stability limit).

    Returns
    -------
    ModelSolitonRun
    """
    from ._exact import travelling_wave
    from ._simulate import check_count, check_ring, simulate_model, snap_ring

    if kind is not None and kind not in KINDS:
        raise ModelError(f"kind must be one of {KINDS}, got {kind!r}")
    probe = nls(model, k, branch)
    if probe.undefined:
        raise ModelError(f"no soliton at k = {k:.6g}: {probe.undefined}")
    N = soliton_ring(probe.soliton(amplitude)) if N is None else check_ring(N)
    pred = ring_soliton(model, k, amplitude, N, kind, probe.carrier.branch)
    check_soliton_launch(model, pred, k)
    snapshots = check_count("snapshots", snapshots, least=3)
    if t_end is None:
        t_end = travel_time(pred, travel)
    t_end = scalar(t_end)
    if isinstance(t_end, (bool, np.bool_)) or not (
            isinstance(t_end, numbers.Real) and math.isfinite(t_end) and t_end > 0):
        raise ModelError(f"t_end must be a finite time > 0, got {t_end!r}")
    u, v = pred.state()
    # the plane wave the segment runs compare with (their records are not used here)
    wave = travelling_wave(model, snap_ring(pred.k, N)[0], amplitude, pred.nls.carrier.branch)
    times = np.linspace(0.0, t_end, snapshots)
    snaps, phases, fields, energy = [], [], [], []
    centre, step = N / 2, None
    for i, ti in enumerate(times):
        if i:
            run = simulate_model(model, wave.carrier.k, amplitude, N=N, t_end=ti - times[i - 1],
                                 dt=dt, method=method, noise=0.0, records=1, wave=wave,
                                 initial=(u, v), branch=wave.carrier.branch)
            u, v = run.state
            step = run.dt
            if not energy:
                energy.append(float(run.energy[0]))
            energy.append(float(run.energy[-1]))
        guess = centre + (pred.velocity * (ti - times[i - 1]) if i else 0.0)
        try:
            snap = measure_snapshot(u, v, pred, float(ti), guess)
        except ValueError:  # the fit's own error (a non-finite start): no soliton to fit
            raise ModelError(f"at T = {ti:.4g} no {pred.kind} soliton is left to fit (it "
                             "broke up or radiated away): lower the amplitude") from None
        centre = snap.centre
        snaps.append(snap)
        phases.append(phasor(u, v, pred, centre, float(ti)))
        fields.append(u.copy())
    return ModelSolitonRun(predicted=pred, k_asked=float(k), N=N, t_end=float(t_end),
                           dt=float(step), method=method, snapshots=tuple(snaps),
                           frequency=frequency_of(times, phases, pred),
                           energy=np.array(energy), fields=np.array(fields))


def soliton_report(pred: RingSoliton, run: ModelSolitonRun | None = None) -> dict:
    """The JSON of ``flexmm soliton --model``: kind, predicted, measured (None without a
    run), errors, inputs and the run."""
    model = pred.nls.model
    out = {"model": model.name, "parameters": dict(model.params), "kind": pred.kind,
           "k": pred.k, "branch": pred.nls.carrier.branch, "amplitude": pred.soliton.amplitude,
           "g1": pred.nls.g1, "g2": pred.nls.g2,
           "predicted": pred.summary(model.fields),
           "measured": None if run is None else run.measured(),
           "errors": None if run is None else run.errors()}
    if run is not None:
        out["run"] = {"N": run.N, "k_asked": run.k_asked, "k_ring": pred.k,
                      "t_end": run.t_end, "dt": run.dt, "method": run.method,
                      "snapshots": len(run.snapshots)}
    return out


__all__ = ["ring_wavenumber", "default_ring", "soliton_ring", "travel_time", "RingSoliton",
           "ring_soliton",
           "ModelSolitonRun", "simulate_soliton", "soliton_report"]
