"""The time step of a model's run (``simulate_model``): the default from the lattice's
fastest frequency, the linear branches' or the start state's own, and the refusal of a
step past the method's stability limit.

Probe 98: a given ``dt`` past the limit ran silently (a cosine-bond chain, top frequency
2.39, dt = 5 with srkn11b: the energy grew 520x, at dt = 1e6 to 7e27 times, the run
returned as sound); a start state far stiffer than the linear chain (a Morse bond
compressed to r = -2, local frequency ~84 where the branches end at 3) ran at the linear
chain's default step, omega dt ~ 8, its energy off by 4.7% with no word.
"""

from __future__ import annotations

import math

import numpy as np

from energy import Model, ModelError

#: the default step: this fraction of the method's stability limit over the fastest
#: frequency (the carrier's nonlinear one and the noise's harmonics need the margin)
STEP_FRACTION = 0.2

#: power iterations of the local frequency estimate: it rises to the largest |eigenvalue|
#: from below; 30 bring a band's top within a few percent (checked on the probe's chains),
#: well inside the default's factor 5 of margin
_ITERATIONS = 30


def local_frequency(force, p, rows: int, u: np.ndarray) -> float:
    """The fastest local frequency of a ring state: sqrt of the largest |eigenvalue| of
    the Jacobian of the acceleration ``force(u, p, out, S)`` at ``u`` (the stiffness the
    step meets there, M^-1 times the Hessian of the energy), by power iteration with
    central differences. At rest it is the linear branches' top; a strongly compressed
    bond's is its own."""
    u = np.ascontiguousarray(u, float)
    S = np.empty((max(int(rows), 1), u.shape[1]))
    plus, minus = np.empty_like(u), np.empty_like(u)
    # the start vector a pointwise function of the state, scrambled: a shifted state
    # gives the shifted iteration bit for bit, so its step and its run are the shifted
    # ones (a random start made a Morse run's step, and its end, differ by 4e-9 from its
    # shifted twin's); at rest, or on a pure plane wave, it lacks the band's top, which
    # the branches' top in ``run_step`` covers
    w = np.sin(7919.0 * u + 1.0) + np.cos(104729.0 * u + 2.0) * 1e-3
    h = 1e-6 * (1.0 + float(np.max(np.abs(u))))
    lam = 0.0
    with np.errstate(all="ignore"):
        for _ in range(_ITERATIONS):
            w /= float(np.max(np.abs(w))) or 1.0
            force(np.ascontiguousarray(u + h * w), p, plus, S)
            force(np.ascontiguousarray(u - h * w), p, minus, S)
            jw = (plus - minus) / (2 * h)
            size = float(np.max(np.abs(jw)))
            if not math.isfinite(size) or size == 0.0:
                break
            lam = size  # |J w| with |w| = 1 in the max norm: rises to |lambda_max|
            w = jw
    return math.sqrt(lam) if math.isfinite(lam) else math.inf


def run_step(model: Model, method, wave, dt, u, force, p, rows) -> tuple[float, float]:
    """(step, the frequency it is set by) of a run: ``dt`` as given, refused where it is
    past the method's stability limit at the lattice's fastest frequency (the linear
    branches' top, or the start state's own where higher); None: ``STEP_FRACTION`` of the
    limit over the larger of 1.1 times the branches' top plus the carrier's frequency (the
    rule since the start) and 1.1 times the start state's local frequency."""
    from ._linear import branches

    top = float(np.nanmax(branches(model, np.linspace(0, math.pi, 129))))
    local = local_frequency(force, p, rows, u)
    limit = method.stability_limit()
    if dt is None:
        fastest = max(top * 1.1 + wave.omega, 1.1 * local)
        if model.lossy:
            # the damping's fastest rate c bounds the step like a frequency: rk4 takes the
            # damping in every stage (an overdamped mode's eigenvalue near -c must stay
            # in its region), and the SRKN splitting, exact in the damping alone, errs as
            # (c dt)^2 in the creep of an overdamped mode (probe 98, a unit chain with
            # site damping gamma = 100, T = 20: rk4 blew up at the oscillation's step,
            # srkn11b ended at E = 1.1e-3 where the overdamped creep keeps 0.13; at
            # gamma 1e4 its energy balance read 900)
            from ._damping import LOSS_DECAY, loss_spacing

            fastest = max(fastest, LOSS_DECAY / loss_spacing(model, u.shape[1]))
        if not math.isfinite(fastest):
            raise ModelError(f"model {model.describe()}: the start state's stiffness is not "
                             "finite (a bond past its range); lower the amplitude")
        return STEP_FRACTION * limit / fastest, fastest
    if isinstance(dt, bool) or not isinstance(dt, (int, float, np.floating)) or not (
            math.isfinite(dt) and dt > 0):
        raise ModelError(f"dt must be a finite step > 0, got {dt!r}")
    fastest = max(top, local)
    if dt * fastest > limit:
        where = ("the lattice's top frequency" if top >= local else
                 "the start state's fastest local frequency")
        raise ModelError(
            f"dt = {dt:g} is past the stability limit of {method.name} at {where} "
            f"{fastest:.4g} (omega dt = {dt * fastest:.3g} > {limit:.3g}): the run would "
            f"go unstable; give dt below {limit / fastest:.3g}, or leave it out for "
            f"{STEP_FRACTION:g} of the limit")
    return float(dt), fastest
