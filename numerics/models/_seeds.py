"""The seeded runs of one point (``simulate_seeds`` -> ``SeededRuns``), split from
``_simulate``: ``seeds`` runs of the ring from the exact theory's wave (``simulate_model``)
and their verdict, one rule for a point and a map cell; the exact theory handed in is
checked to be that of this very wave on this ring.
"""

from __future__ import annotations

import math
import numbers
from dataclasses import dataclass

import numpy as np

from energy import Model, ModelError

from ._args import check_rate, scalar
from ._simulate import simulate_model, snap_ring


@dataclass(frozen=True)
class SeededRuns:
    """Runs of one point from the exact wave with seeds 0 .. n - 1, and their verdict.

    verdict : numerics.lattice.Verdict
        ``simulated_verdict`` of their growth factors (MI, "no growth within T",
        "undetermined"), with the median rate of the unstable runs.
    rate : float
        That median rate (1/time); nan where no run was unstable.
    runs : list of ModelRun
    t_end : float
        The runs' length.
    length : RunLength or None
        How T was chosen from the exact rate (None where ``t_end`` was given).
    """

    verdict: object
    rate: float
    runs: list
    t_end: float
    length: object = None


def _check_spec(model: Model, k: float, amplitude: float, spec, branch, N: int) -> None:
    """``spec`` is the exact theory of this very wave on this ring: the runs start from
    ``spec.wave``, so a spectrum of another k, amplitude, branch or model would start
    them from another wave, silently (seen: amplitude 0.5 asked, 0.05 run)."""

    wave = getattr(spec, "wave", None)
    if wave is None or not hasattr(spec, "peak_gain"):
        raise ModelError(f"spec must be the exact theory of the wave on this ring "
                         f"(numerics.models.exact_gain(model, k, amplitude, branch, N=N)), "
                         f"got {type(spec).__name__}")
    differ = _differences(model, snap_ring(k, N)[0], amplitude, wave, branch, "spec")
    ring = _spec_ring(spec)
    if ring != N:  # another ring's k can snap to the same 2 pi m / N: its offsets differ
        differ.append(f"ring N = {N} (spec: "
                      + ("the infinite chain, or no ring's offsets" if ring is None
                         else f"N = {ring}") + ")")
    if differ:
        raise ModelError(f"spec is the exact theory of another wave: {'; '.join(differ)}; "
                         f"give exact_gain(model, k, amplitude, branch, N=N) of these")


def _differences(model: Model, kr: float, amplitude: float, wave, branch, what: str) -> list:
    """How ``wave`` differs from the travelling wave of ``model`` at ring wavenumber kr,
    ``amplitude`` and ``branch``: one phrase per difference (k, amplitude, branch, model)."""
    from ._linear import branch_index, check_amplitude, check_model

    check_model(model)
    a = check_amplitude(amplitude)
    b = branch_index(model, kr, branch)
    return [f"{name} {got} ({what}: {want})" for name, got, want, same in (
        ("k on the ring", f"{kr:.6g}", f"{wave.k:.6g}", math.isclose(kr, wave.k, rel_tol=1e-12)),
        ("amplitude", f"{a:.6g}", f"{wave.amplitude:.6g}",
         math.isclose(a, wave.amplitude, rel_tol=1e-12)),
        ("branch", b, wave.carrier.branch, b == wave.carrier.branch),
        ("model", model.describe(), wave.model.describe(),
         # the content, not the Lattice object: the built-in fput and energy/models/
         # fput.toml (another source) are the same model (before: refused as 'fput (...)
         # (spec: fput (...))', both sides alike)
         wave.model.lattice.content_hash == model.lattice.content_hash
         and dict(wave.model.params) == dict(model.params)))
        if not same]


def check_wave(model: Model, kr: float, amplitude: float, wave, branch) -> None:
    """``simulate_model``'s ``wave`` is the travelling wave of this model at the ring's k,
    this amplitude and branch: the run starts from it and measures its deviation from it,
    so another wave (another model's, amplitude's or k's) would be run silently."""
    from ._exact import TravellingWave

    if not isinstance(wave, TravellingWave):
        raise ModelError(f"wave must be a TravellingWave (numerics.models.travelling_wave), "
                         f"got {type(wave).__name__}")
    differ = _differences(model, kr, amplitude, wave, branch, "wave")
    if differ:
        raise ModelError(f"wave is another wave: {'; '.join(differ)}; give "
                         f"travelling_wave(model, k, amplitude, branch) of these, k on the "
                         f"ring (snap_ring(k, N))")


def _spec_ring(spec) -> int | None:
    """The ring whose offsets 2 pi j / N (j = 1..N // 2) ``spec`` holds, from the offsets
    themselves (``exact_gain(..., N=N)`` takes exactly those), or None: the infinite
    chain's grid, or offsets of no ring."""
    from ._exact import ring_offsets

    q = np.asarray(getattr(spec, "offsets", ()), float).ravel()
    if not q.size or not np.isfinite(q).all() or q[0] <= 0:
        return None
    n = round(2 * math.pi / q[0])
    for N in (n, n + 1):  # N // 2 offsets: an odd ring's has the even ring's count
        want = ring_offsets(N)
        if want.shape == q.shape and np.allclose(q, want, rtol=1e-12, atol=0):
            return N
    return None


def visible_gain(spec, N: int) -> float:
    """The exact ring theory's fastest rate over the offsets a run can measure: offset j
    (waves at ring modes m + j and m - j) is left out where both waves sit on harmonics of
    the carrier (h m mod N, |h| <= the wave's harmonics), which a run leaves out of its
    growth (``numerics.maps``' ``harmonic_note`` says so on a point). A run's default
    length is chosen from this rate: from the peak, a run's T held too few e-foldings of
    what it can see (probe 95: the probe's rotor chain, kt 0.997, w0 0.544, c -0.039, k
    1.767, a 0.078, 256 sites: peak 1.65e-3 on the mean flow and 2k, T 5500; the fastest
    visible mode, 1.05e-3, grew 5.9x by then: "no growth within T")."""
    gain = np.asarray(getattr(spec, "gain", ()), float)
    if not gain.size or not float(np.max(gain)) > 0:
        return float(getattr(spec, "peak_gain", 0.0))
    return float(np.max(gain[~harmonic_offsets(spec, N)], initial=0.0))


def harmonic_offsets(spec, N: int) -> np.ndarray:
    """Which of the ring's offsets j = 1 .. len(spec.gain) (``ring_offsets(N)``: q = 2 pi
    j / N) put both their waves, ring modes m + j and m - j, on harmonics of the carrier
    (h m mod N, |h| <= the wave's harmonics above the noise): the offsets a run leaves out of its growth
    (``visible_gain``; ``numerics.maps``' ``harmonic_note``). Boolean, shape (len(gain),)."""
    from ._simulate import NOISE

    m = int(round(spec.wave.k * N / (2 * math.pi)))
    H = int(spec.wave.harmonics)
    # only the harmonics a run can tell from its noise (``read_modes`` leaves out those
    # whose drift shows over the noise floor): |c_h| above a hundredth of the noise's
    # amplitude. Before probe 97 every h <= H counted: FPUT (alpha 0.5) at k = 2 pi 21/64,
    # a 0.12 has H = 16, and the fastest offset's waves sit on the 8th and 10th harmonics
    # (|c_h| ~ 1e-12, 1e-15): the note said a run leaves them out and 'may measure 0 /time',
    # the run's T was the no-growth default, where the run measured the exact 0.01597
    # (a wave given without its coefficients: every harmonic up to H counts)
    coefficients = getattr(spec.wave, "coefficients", None)
    if coefficients is None:
        seen = range(H + 1)
    else:
        size = np.max(np.abs(np.asarray(coefficients)), axis=0)[H:]  # |c_h|, h >= 0
        floor = 0.01 * NOISE * spec.wave.amplitude
        seen = [h for h in range(H + 1) if h <= 1 or size[h] > floor]
    harm = {(s * h * m) % N for h in seen for s in (1, -1)}
    return np.array([(m + j) % N in harm and (m - j) % N in harm
                     for j in range(1, len(spec.gain) + 1)], dtype=bool)


def simulate_seeds(model: Model, k: float, amplitude: float, spec, *, branch=None,
                   N: int = 256, seeds: int = 1, t_end: float | None = None,
                   start: str = "exact", gain: float | None = None, **run) -> SeededRuns:
    """``seeds`` runs of the ring from ``spec``'s exact wave (``exact_gain`` on this ring)
    and their verdict: one rule for a point and a map cell. T is ``run_length`` of the
    exact rate a run can see (``visible_gain``; ``gain``: of this rate instead, the theory of another ``start``'s state)
    unless ``t_end`` is given. ``run``: more keywords of ``simulate_model`` (``noise_on``,
    ``until_peak``: a lossy point's launch, issue 42)."""
    from numerics.lattice import run_length, simulated_verdict

    if isinstance(seeds, bool) or not isinstance(seeds, (int, np.integer)) or seeds < 1:
        raise ModelError(f"seeds must be an integer >= 1, got {seeds!r}")
    _check_spec(model, k, amplitude, spec, branch, N)
    t_end = scalar(t_end)
    if t_end is not None and (isinstance(t_end, bool) or not isinstance(t_end, numbers.Real)):
        raise ModelError(f"t_end must be a finite time > 0, got {type(t_end).__name__} "
                         f"{t_end!r}")
    if gain is not None:
        gain = check_rate("gain", gain)
    from ._time_scale import time_scale
    length = run_length(visible_gain(spec, N) if gain is None else gain,
                        time_scale=time_scale(model)) if t_end is None else None
    T = float(t_end) if t_end is not None else length.t_end
    runs = [simulate_model(model, k, amplitude, branch=branch, N=N, t_end=T, start=start,
                           seed=s, wave=spec.wave, **run) for s in range(int(seeds))]
    growth = [r.growth() for r in runs]
    rates = [g.rate for g in growth if g.verdict == "unstable"]
    rate = float(np.median(rates)) if rates else math.nan
    if model.lossy and run.get("until_peak"):
        # with losses growth is transient and these runs stop once A(t) has halved: their
        # factor is the amplification (max over t of A(t) / A(0)), not end over start,
        # and T is how long they ran
        factors = [r.amplification().amplification for r in runs]
        T_run = max(float(r.t[-1]) for r in runs)
        return SeededRuns(simulated_verdict(factors, T_run, rate, time_name="time"), rate,
                          runs, T_run, length)
    return SeededRuns(simulated_verdict([g.factor for g in growth], T, rate,
                                        time_name="time"), rate, runs, T,
                      length)
