"""The exact travelling plane wave of any model by harmonic balance (the exact lattice
theory's first half; its Hill spectrum: ``_exact``).


Travelling wave. Every field is a 2 pi-periodic function of xi = k n - omega t,
u_j(n, t) = U_j(xi) = sum_{|h| <= H} c_{j,h} e^{i h xi} (a general Fourier ansatz, cos and
sin in every field: no parity is assumed). With W(x), x = (u_n, u_{n+1}), the cell energy,
the lattice's equations of motion become

    m_j omega^2 U_j''(xi) = -[d_j W(U(xi), U(xi + k)) + d_{d+j} W(U(xi - k), U(xi))],

solved by collocation at M points with the carrier's first harmonic fixed,
c_{f,1} = a / 2 (u_f = a cos xi + harmonics + mean: the ``amplitude`` of every command),
for omega and every other coefficient. The means along the acoustic directions (uniform
translations, a symmetry of W) are a gauge and set to 0: the ring's wave has no mean
strain. One equation is redundant (the phase of the wave: the residual is orthogonal to
U' for any U), so the system is solved in the least-squares sense and its residual
checked to be round-off.

How it is computed (``_wave_solve``): Gauss-Newton on the collocation equations with their
exact Jacobian, the DFT of the generated cell Hessian along the wave (Levenberg-Marquardt
with it where Newton does not settle). Where the wave's second harmonic is large
(``HARMONIC_CHECK``: flexmm carriers near 2 omega = omega_U(2k)) the continuation from small amplitude
(``_connected``) gives the wave, the harmonic balance from the linear wave solved only
where the continuation loses the branch.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from common.threads import one_blas_thread
from energy import Model, ModelError

from ._fourwave_kernel import second_harmonic_size
from ._linear import Carrier, carrier, check_amplitude, check_harmonics
from ._nls import kept_acoustic_directions
from ._wave_solve import RESIDUAL_TOL, _least_squares, _solve, _solve_fast


@dataclass(frozen=True)
class TravellingWave:
    """The exact travelling plane wave u_j(n, t) = sum_h c[j, h] e^{i h (k n - omega t)}.

    Attributes
    ----------
    model : Model
    carrier : Carrier
        The linear carrier it continues (k, branch, field, linear omega).
    amplitude : float
        a: the carrier field's first harmonic is a cos(k n - omega t).
    omega : float
        The wave's frequency (1/time, lattice units); ``omega - carrier.omega`` its
        nonlinear shift.
    coefficients : ndarray, shape (d, 2 H + 1), complex
        c[j, h + H] for h = -H..H.
    residual : float
        Largest collocation residual over m omega^2 a (round-off when converged).
    """

    model: Model
    carrier: Carrier
    amplitude: float
    omega: float
    coefficients: np.ndarray
    residual: float

    @property
    def k(self) -> float:
        return self.carrier.k

    @property
    def harmonics(self) -> int:
        return (self.coefficients.shape[1] - 1) // 2

    def profile(self, xi) -> np.ndarray:
        """U_j(xi), shape (d,) + xi.shape."""
        xi = np.asarray(xi, dtype=float)
        h = np.arange(-self.harmonics, self.harmonics + 1)
        return np.real(np.tensordot(self.coefficients, np.exp(1j * h[:, None] * xi.ravel()),
                                    axes=(1, 0))).reshape((-1,) + xi.shape)

    def ring_profile(self, N: int, k: float | None = None):
        """A function t -> U_j(k n - omega t) on the ring's N sites, shape (d, N): the
        same as ``profile`` (to round-off, ~1e-16 of the amplitude) at a fraction of its
        cost for many t (a run's records): the sites' harmonics e^{i h k n} once, then
        2H + 1 phases per t. ``k``: the ring's (default the wave's)."""
        h = np.arange(-self.harmonics, self.harmonics + 1)
        basis = np.exp(1j * h[:, None] * ((self.k if k is None else k) * np.arange(N)))
        c, w = self.coefficients, self.omega

        def at(t: float) -> np.ndarray:
            return np.real((c * np.exp(-1j * h * (w * t))) @ basis)
        return at

    def slope(self, xi) -> np.ndarray:
        """U_j'(xi)."""
        xi = np.asarray(xi, dtype=float)
        h = np.arange(-self.harmonics, self.harmonics + 1)
        return np.real(np.tensordot(self.coefficients * (1j * h),
                                    np.exp(1j * h[:, None] * xi.ravel()),
                                    axes=(1, 0))).reshape((-1,) + xi.shape)

    def state(self, N: int, t: float = 0.0):
        """(u, v) of the wave on a ring of N sites at time t, each shape (d, N)."""
        xi = self.k * np.arange(N) - self.omega * t
        return self.profile(xi), -self.omega * self.slope(xi)

    def harmonic_amplitudes(self) -> np.ndarray:
        """2 |c[j, h]| for h = 0..H (the mean as |c_0|), shape (d, H + 1)."""
        H = self.harmonics
        out = 2 * np.abs(self.coefficients[:, H:])
        out[:, 0] /= 2
        return out


def _wrap(x):
    """|x| wrapped to [0, pi]."""
    return np.abs((np.asarray(x) + np.pi) % (2 * np.pi) - np.pi)


@one_blas_thread
def travelling_wave(model: Model, k: float, amplitude: float, branch=None, *,
                    harmonics: int | None = None,
                    start: TravellingWave | None = None) -> TravellingWave:
    """The exact travelling plane wave of ``model`` on ``branch`` at wavenumber ``k`` whose
    carrier field has first harmonic ``amplitude`` cos(k n - omega t).

    ``start``: a wave of the same model, k and branch at another amplitude a1 (the
    harmonic balance starts from it, each harmonic h scaled by (a / a1)^|h|, the mean and
    the nonlinear frequency shift by (a / a1)^2, the lowest orders of a weakly nonlinear
    wave, instead of from the linear wave: fewer Newton steps; the same equations,
    truncation H = 8 (doubled as without) and residual test, so the same wave to
    round-off).

    Without ``start``, a wave far from the linear one (frequency shift over
    ``SHIFT_CHECK``, second harmonic over ``HARMONIC_CHECK`` of the first) is the one
    continued from small amplitude (``_connected``): the carrier's family, where the
    harmonic balance from the linear wave can land on another.

    ``harmonics``: the truncation H (an integer >= 1; default None: 8, doubled while the
    harmonics reach it, up to 32).

    Raises ModelError where none is found (a resonance with another harmonic, an
    amplitude beyond the branch's nonlinear range): said in one line. Small dense algebra:
    on one BLAS thread (``common.threads``).
    """
    # the collocation's set-up once for the direct solve and the continuation's steps
    # (``_solve_fast``: the same values, to the bit). The chord's Jacobian taken again once
    # where its rate is slow (``chord_newton``'s refresh): from the linear wave at H = 8
    # the chord converges at ~0.04 a step (fput alpha 0.5, beta 1, a 0.1: 10 residuals);
    # the fixed point is the same (the wave within 2e-18), the wave with the carrier passed
    # on (``second_harmonic_size``) 1.31 -> 1.14 ms (best of 150, alternating)
    harmonics = check_harmonics(harmonics, 1, "the wave's first harmonic is its carrier")
    if start is not None and not isinstance(start, TravellingWave):
        raise ModelError(f"start must be a TravellingWave of the same model, k and branch "
                         f"(numerics.models.travelling_wave), got {type(start).__name__}")
    fast = {"refresh": 1}
    a = check_amplitude(amplitude)
    size = math.nan
    if start is None:
        fast["car"] = carrier(model, k, branch)
        size = second_harmonic_size(model, fast["car"].k, a, branch, car=fast["car"])
        if size >= HARMONIC_CHECK:
            # the continuation decides, whatever the direct solve finds: that solve only
            # where the continuation loses the branch (``_connected``)
            return _connected(model, k, a, branch, harmonics, None, fast)
    wave = _travelling_wave(model, k, amplitude, branch, harmonics, start, fast)
    shift = (wave.omega - wave.carrier.omega) / wave.carrier.omega
    if start is None and not (abs(shift) < SHIFT_CHECK and size < HARMONIC_CHECK):
        return _connected(model, k, a, branch, harmonics, wave, fast)
    return wave


#: A wave whose frequency is this far (relative) from the linear one, or whose second
#: harmonic (weakly nonlinear estimate, ``second_harmonic_size``) is this large against
#: its first, is checked against the wave continued from small amplitude: near a
#: harmonic's resonance the harmonic balance started from the linear wave can land on
#: another family (the flexmm chain at k = 2 pi 18/128: omega +0.3% at a = 0.07 where the
#: family's is -3.6%, then -0.146 at 0.09: its second harmonic 19x the first at a 0.07).
#: Elsewhere no extra solve (FPUT at a = 0.1: 0.19 at k = 0.5, 0.003-0.09 at k >= 1).
SHIFT_CHECK, HARMONIC_CHECK = 0.05, 0.3
#: continuation steps from a / CONTINUATION_STEPS to a
CONTINUATION_STEPS = 4


def _connected(model, k, a, branch, harmonics, direct, fast=None):
    """The wave at amplitude a continued from small amplitude (each step's harmonic
    balance started from the previous wave): the one on the carrier's branch. ``direct``
    where it is the same wave; a one-line ModelError where the continuation loses the
    branch (its harmonic balance fails: the family folds near a harmonic's resonance).
    ``fast``: the direct solve's set-up (``_travelling_wave``). A step after the first
    starts at the previous wave's truncation (its tail test, and the doubling where the
    tail is not yet below 1e-13, as from H = 8: the same wave to the tail's 1e-13), not
    at H = 8 again: one solve a step instead of two.

    ``direct`` None (the continuation asked before the direct solve: a large second
    harmonic): the direct solve is done only where the continuation loses the branch;
    else the continued wave is returned, which is ``direct`` to round-off where they are
    one family and the wave returned before where they are not. (Before, a direct solve
    that failed raised even where the continuation found the carrier's wave.)"""
    base = fast
    # the steps' least squares by QR, the steps before the last converged to 1e-11 (each
    # only the next one's start)
    fast = dict(fast or {}, qr=True, refresh=6)
    prev = None
    for j in range(1, CONTINUATION_STEPS + 1):
        aj = a * j / CONTINUATION_STEPS
        fast["done"] = 1e-14 if j == CONTINUATION_STEPS else 1e-11
        try:
            prev = _travelling_wave(model, k, aj, branch, harmonics, prev, fast,
                                    first=None if prev is None else prev.harmonics)
        except ModelError:
            prev = None
        if prev is None or not prev.omega > 0:
            if direct is None:
                direct = _travelling_wave(model, k, a, branch, harmonics, None, base)
            shift = abs(direct.omega - direct.carrier.omega) / direct.carrier.omega
            if direct.omega > 0 and shift < SHIFT_CHECK:
                # no other family seen, and the direct wave's frequency is the linear
                # one's: it stands (a long acoustic wave whose small-amplitude balance
                # misses the residual test)
                return direct
            done = a * (j - 1) / CONTINUATION_STEPS
            raise ModelError(
                f"model {model.describe()}: no travelling wave of amplitude {a:g} at k = "
                f"{k:.6g} on the carrier's branch: continued from the linear wave it is lost "
                f"between a = {done:.3g} and {aj:.3g} (its family folds, a harmonic near "
                f"resonance with a branch); the harmonic balance from the linear wave finds "
                f"another family (frequency {direct.omega:.4g}, linear {direct.carrier.omega:.4g})"
                "; try an amplitude below it")
    if direct is None or abs(prev.omega - direct.omega) > 1e-8 * abs(direct.carrier.omega):
        return prev
    return direct


def _scaled_start(start, car, a, H):
    """(omega, coefficients at H harmonics) of ``start`` moved to amplitude a: the first
    guess of ``_travelling_wave`` (``travelling_wave``'s ``start``)."""
    if (start.coefficients.shape[0] != car.e.size or start.carrier.branch != car.branch or abs(start.k - car.k) > 1e-12
            or not np.isfinite(start.omega)):
        raise ModelError(f"start must be a wave of the model at the same k ({car.k:.6g}) "
                         f"and branch "
                         f"({car.branch}), got k = {start.k:.6g}, branch "
                         f"{start.carrier.branch}")
    r = a / start.amplitude
    H1 = start.harmonics
    c0 = np.zeros((start.coefficients.shape[0], 2 * H + 1), complex)
    m = min(H, H1)
    h = np.arange(-m, m + 1)
    c0[:, H - m:H + m + 1] = (start.coefficients[:, H1 - m:H1 + m + 1]
                              * r ** np.where(h == 0, 2, np.abs(h)))
    return car.omega + (start.omega - car.omega) * r**2, c0


def _travelling_wave(model, k, amplitude, branch, harmonics, start=None, fast=None,
                     first=None):
    """``travelling_wave`` without its family check. ``fast``: a dict kept across the
    calls of one carrier (``continued_wave``): the carrier, the acoustic directions and
    the collocation's linear maps (``_collocation``) computed once. ``first``: the first
    truncation H tried where ``harmonics`` is None (default 8; doubled while the tail is
    above 1e-13 of the amplitude, up to 32)."""
    least_squares = _least_squares
    a = check_amplitude(amplitude)
    if fast is None:
        car = carrier(model, k, branch)
        masses = np.asarray(model.masses, float)
        acoustic = kept_acoustic_directions(model)
    else:
        if "acoustic" not in fast:
            if "car" not in fast:
                fast["car"] = carrier(model, k, branch)
            fast.update(acoustic=kept_acoustic_directions(model),
                        masses=np.asarray(model.masses, float))
        car, acoustic, masses = fast["car"], fast["acoustic"], fast["masses"]
    d = model.n_fields
    solve = _solve if fast is None else _solve_fast
    kw = {} if fast is None else {"qr": bool(fast.get("qr")), "done": fast.get("done", 1e-14),
                                  "kept": fast.setdefault("layouts", {}),
                                  "refresh": int(fast.get("refresh", 0))}
    H = harmonics or first or 8
    if start is not None:
        omega0, c0 = _scaled_start(start, car, a, H)
    else:
        c0 = np.zeros((d, 2 * H + 1), complex)
        c0[:, H + 1] = a / 2 * car.e
        c0[:, H - 1] = np.conj(c0[:, H + 1])
        omega0 = car.omega
    while True:
        omega, c, res = solve(model, car, a, masses, acoustic, H, c0, omega0, least_squares,
                              **kw)
        wave = TravellingWave(model=model, carrier=car, amplitude=a, omega=omega,
                              coefficients=c, residual=res)
        tail = np.max(np.abs(wave.coefficients[:, [0, -1]])) / a
        if harmonics or tail < 1e-13 or H >= 32:
            break
        H2 = 2 * H  # the harmonics reach the truncation: twice as many
        c0 = np.zeros((d, 2 * H2 + 1), complex)
        c0[:, H2 - H:H2 + H + 1] = wave.coefficients
        omega0, H = wave.omega, H2
    scale = max(np.max(masses) * wave.omega**2, 1e-300)
    if not (wave.residual < RESIDUAL_TOL) or not np.isfinite(wave.omega):
        raise ModelError(
            f"model {model.describe()}: no travelling wave of amplitude {a:g} at k = {k:.6g} "
            f"(harmonic balance residual {wave.residual:.2g} of m omega^2 a = {scale * a:.3g}; "
            "a harmonic resonant with a branch, or an amplitude beyond the branch's range)")
    return wave


def continued_wave(model: Model, car: Carrier, amplitude: float, start: TravellingWave,
                   fast: dict) -> TravellingWave:
    """``travelling_wave(model, car.k, amplitude, car.branch, start=start)`` by the fast
    solve (``_solve_fast``): the lower amplitudes of a damped point
    (``_losses_sampling``), ``fast`` one dict per carrier. The caller holds the BLAS
    threads (``one_blas_thread``)."""
    return _travelling_wave(model, car.k, amplitude, car.branch, None, start, fast)
