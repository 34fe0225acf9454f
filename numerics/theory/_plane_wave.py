"""Exact nonlinear plane waves of the lattice, by harmonic balance.

A nonlinear plane wave of eq. `norm` is a travelling wave theta_n(T) = Theta(phi_n),
U_n(T) = V(phi_n), phi_n = k n - Omega T, with Theta 2 pi-periodic. The equations are odd
in theta, so Theta carries odd harmonics and V even ones; the reflection (n, T) -> (-n, -T),
U -> -U lets us take Theta even and V odd in phi:

    Theta = sum_{m odd} a_m cos(m phi),   V = sum_{m even >= 2} b_m sin(m phi).

Harmonic balance solves Omega^2 Theta'' = F_theta, Omega^2 V'' = F_U on a phase grid
(neighbours are exact phase shifts by +-k; F from ``generated.lattice_model``) with
Newton's method, the peak rotation Theta(0) = amplitude fixing the branch. Their linear
stability is in ``_hill``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from generated import lattice_model as model

from ..lattice import LatticeState, Material, check_case, checks, register_start

#: default truncation: theta harmonics |p| <= HARMONICS (odd), U harmonics |p| < HARMONICS.
HARMONICS = 4
#: largest peak rotation (rad) a plane wave may have here: the harmonic balance is tested
#: to 1 rad; beyond 1.5 its truncation is no longer converged
MAX_AMPLITUDE = 1.5
#: Newton on the harmonic balance: relative residual to reach, iterations allowed, and
#: the residual below which a solution counts as converged (the branch test)
NEWTON_TOL, NEWTON_ITERATIONS, BRANCH_RESIDUAL = 1e-13, 30, 1e-8
#: continuation in the amplitude when Newton from the linear wave fails: number of steps
CONTINUATION_STEPS = 8
#: a solution on the branch of the linear wave keeps its first harmonic within this
#: fraction of the peak rotation (else Newton found another orbit)
BRANCH_FIRST_HARMONIC = 0.5


class NoPlaneWaveError(ArithmeticError):
    """Harmonic balance finds no travelling wave of this amplitude on the branch of the
    linear wave (near a resonance of a harmonic with a lattice mode)."""


def _combine(coef, table):
    """sum_m coef_m f(m (phi + k)) on the grid, (B, M), from coef (B, H) and the table
    f(m (phi + k)) (B, H, M) of ``_tables``."""
    return np.einsum("bm,bmj->bj", coef, table)


def _table(harm, k, phi, kind):
    arg = harm[None, :, None] * (phi[None, None, :] + k[:, None, None])
    return np.cos(arg) if kind == "cos" else np.sin(arg)


def _tables(k, H, phi, coupled):
    """The phase tables of a wave's fields at sites n - 1, n, n + 1 for carriers k (B,):
    (kind, shift) -> (B, H, M), "cos" for theta's odd harmonics, "sin" for U's even ones
    (only if ``coupled``), shift -1, 0, 1 in units of k. They depend on k only, so Newton
    computes them once."""
    mo = 2.0 * np.arange(H) + 1
    zero = np.zeros_like(k)
    t = {}
    for s, shift in ((-1, -k), (0, zero), (1, k)):
        t["cos", s] = _table(mo, shift, phi, "cos")
        if coupled:
            t["sin", s] = _table(mo + 1, shift, phi, "sin")
    return t


@dataclass(frozen=True)
class PlaneWave:
    """A travelling wave of the lattice (see module docstring).

    Attributes
    ----------
    k, amplitude, omega : float
        Wavenumber (rad per site), peak rotation Theta(0), frequency Omega (1/T).
    omega_linear : float
        Frequency of eq. `discrete2` (the amplitude -> 0 limit).
    theta_harmonics : ndarray, shape (H,)
        a_m, m = 1, 3, 5, ...: Theta(phi) = sum a_m cos(m phi).
    U_harmonics : ndarray, shape (H,)
        b_m, m = 2, 4, ...: V(phi) = sum b_m sin(m phi); zeros in case "rotation".
    residual : float
        Max abs residual of the harmonic-balance equations on the phase grid.
    """

    case: str
    k: float
    amplitude: float
    omega: float
    omega_linear: float
    theta_harmonics: np.ndarray
    U_harmonics: np.ndarray
    residual: float

    def fields(self, n, t=0.0):
        """theta_n, theta_dot_n, U_n, U_dot_n at time t (arrays over the sites n)."""
        phi = self.k * np.asarray(n, dtype=float) - self.omega * t
        mo = 2 * np.arange(self.theta_harmonics.size) + 1
        me = mo + 1
        a, b = self.theta_harmonics, self.U_harmonics
        th = np.cos(np.outer(phi, mo)) @ a
        thd = self.omega * (np.sin(np.outer(phi, mo)) @ (mo * a))
        U = np.sin(np.outer(phi, me)) @ b
        Ud = -self.omega * (np.cos(np.outer(phi, me)) @ (me * b))
        return th, thd, U, Ud


    def complex_harmonics(self, M: int) -> dict:
        """Complex amplitudes c_m, m = 1 .. M, of theta and U at phi = 0 (Theta(phi) =
        Re sum_m c_m e^{i m phi}): theta a_m at odd m, U -i b_m at even m (b sin = Re[-i b
        e^{i m phi}]). ``{"theta": (M,), "U": (M,)}``, complex."""
        out = {f: np.zeros(M, complex) for f in ("theta", "U")}
        for start, field, coef in ((1, "theta", self.theta_harmonics),
                                   (2, "U", -1j * self.U_harmonics)):
            m = start + 2 * np.arange(coef.size)
            keep = m <= M
            out[field][m[keep] - 1] = coef[keep]
        return out


def _residual(x, k, amp, al, Ks, Kt, H, coupled, phi, tables=None):
    """Harmonic-balance residuals, batched: x = (a_1..a_H, b_1..b_H, Omega), shape (B, 2H+1).
    ``tables``: ``_tables(k, H, phi, coupled)``, if the caller keeps them."""
    mo = 2.0 * np.arange(H) + 1
    me = mo + 1
    a, b, W = x[:, :H], x[:, H:2 * H], x[:, -1]
    t = _tables(k, H, phi, coupled) if tables is None else tables
    thm, th0, thp = (_combine(a, t["cos", s]) for s in (-1, 0, 1))
    d2th = _combine(-a * mo**2, t["cos", 0])
    Um = U0 = Up = 0.0
    if coupled:
        Um, U0, Up = (_combine(b, t["sin", s]) for s in (-1, 0, 1))
    al, Ks, Kt = al[:, None], Ks[:, None], Kt[:, None]
    rt = W[:, None] ** 2 * d2th - model.acceleration_theta(Um, U0, Up, thm, th0, thp, al, Ks, Kt)
    M = phi.size
    proj_c = np.cos(np.outer(phi, mo)) * (2.0 / M)  # (M, H)
    R = [rt @ proj_c]
    if coupled:
        d2U = _combine(-b * me**2, t["sin", 0])
        ru = W[:, None] ** 2 * d2U - model.acceleration_U(Um, U0, Up, thm, th0, thp, al, Ks, Kt)
        R.append(ru @ (np.sin(np.outer(phi, me)) * (2.0 / M)))
    else:
        R.append(b)  # b = 0 in case (I)
    R.append((a.sum(axis=1) - amp)[:, None])
    return np.concatenate(R, axis=1)


def _solve_plane_waves(k, amp, al, Ks, Kt, coupled, H, tol=NEWTON_TOL,
                       max_iter=NEWTON_ITERATIONS, x0=None, points=None):
    """Newton on the batch; returns x (B, 2H+1) and the final residual norm (B,).
    ``points``: phase points of the harmonic balance (default max(32, 8 H))."""
    B = k.size
    M = max(32, 8 * H) if points is None else points
    phi = 2 * np.pi * np.arange(M) / M
    al2 = al**2
    n = 2 * H + 1
    if x0 is None:
        x = np.zeros((B, n))
        x[:, 0] = amp
        x[:, -1] = model.omega_rotation(k, al, Ks, Kt)
    else:
        x = x0.copy()
    scale = np.maximum(amp, 1e-300)
    active = np.arange(B)  # waves still iterating (converged ones are left alone)
    tables = _tables(k, H, phi, coupled)
    for _ in range(max_iter):
        xa, ka, ampa, ala, Ksa, Kta = (v[active] for v in (x, k, amp, al, Ks, Kt))
        ta = {key: v[active] for key, v in tables.items()}
        R = _residual(xa, ka, ampa, ala, Ksa, Kta, H, coupled, phi, ta)
        res = np.max(np.abs(R), axis=1) / np.maximum(scale[active] * al2[active], 1e-300)
        keep = res >= tol
        if not np.any(keep):
            break
        active, xa, R = active[keep], xa[keep], R[keep]
        ka, ampa, ala, Ksa, Kta = (v[keep] for v in (ka, ampa, ala, Ksa, Kta))
        ta = {key: v[keep] for key, v in ta.items()}
        J = np.empty((active.size, n, n))
        for j in range(n):
            h = 1e-7 * (scale[active] if j < 2 * H else xa[:, -1])
            xp = xa.copy()
            xp[:, j] += h
            J[:, :, j] = (_residual(xp, ka, ampa, ala, Ksa, Kta, H, coupled, phi, ta)
                          - R) / h[:, None]
        try:
            dx = np.linalg.solve(J, R[:, :, None])[:, :, 0]
        except np.linalg.LinAlgError:
            raise NoPlaneWaveError("harmonic balance: singular Jacobian (a harmonic of the "
                                  "wave is resonant with a lattice mode)") from None
        x[active] = xa - dx
    R = _residual(x, k, amp, al, Ks, Kt, H, coupled, phi, tables)
    res = np.max(np.abs(R), axis=1) / np.maximum(scale * al2, 1e-300)
    return x, res


def _check(material, case, k, amplitude):
    if not isinstance(material, Material):
        raise TypeError(f"material must be a Material, got {type(material).__name__}")
    check_case(case)
    k = checks.real("k", k, 0.0, math.pi)
    amplitude = checks.real("amplitude (peak rotation, rad)", amplitude, 0.0, MAX_AMPLITUDE)
    return k, amplitude


def plane_wave(material: Material, case: str, k: float, amplitude: float,
               harmonics: int = HARMONICS) -> PlaneWave:
    """Nonlinear plane wave of the lattice by harmonic balance (Newton).

    Parameters
    ----------
    material : Material
    case : {"rotation", "coupled"}
    k : float
        Carrier wavenumber, rad per site, in (0, pi).
    amplitude : float
        Peak rotation Theta(0) in rad (2 eps A0 for the paper's initial condition).
    harmonics : int
        Number H of odd theta harmonics (1, 3, ..., 2H - 1) and even U harmonics.

    Returns
    -------
    PlaneWave
        Its frequency ``omega`` includes the amplitude-dependent shift.

    Raises
    ------
    ArithmeticError
        If Newton (with continuation in the amplitude) does not converge to the branch
        of the linear wave. At the second-harmonic resonance sin^2 k = omega^2, where the
        NLS's u2 diverges, the exact wave still exists: its frequency shift detunes the
        resonance and the U harmonic grows like the amplitude instead of its square.
    """
    k, amplitude = _check(material, case, k, amplitude)
    H = _check_harmonics(harmonics)
    params = (np.array([material.alpha]), np.array([material.K_s]),
              np.array([material.K_theta]), case == "coupled", H)

    def solve(a, x0=None):
        return _solve_plane_waves(np.array([k]), np.array([a]), *params, x0=x0)

    x, res = solve(amplitude)
    if not _on_branch(x[0], res[0], amplitude):
        # continuation in the amplitude from the linear wave (large amplitudes)
        x = None
        for a in np.linspace(0, amplitude, CONTINUATION_STEPS + 1)[1:]:
            x, res = solve(a, x)
            if not _on_branch(x[0], res[0], a):
                break
    return _wave_from(x[0], res[0], material, case, k, amplitude, H)


def _on_branch(x, res, amplitude):
    """Converged, and still the continuation of the linear wave: Omega > 0 and the first
    harmonic carrying most of the peak (else Newton found another orbit). Batched over
    leading axes: x (..., 2H+1), res (...)."""
    return (np.all(np.isfinite(x), axis=-1) & (res < BRANCH_RESIDUAL)
            & (np.abs(x[..., 0] / amplitude - 1) < BRANCH_FIRST_HARMONIC) & (x[..., -1] > 0))


def _check_harmonics(h):
    return checks.integer("harmonics", h, 1, 65)


def _wave_from(x, res, material, case, k, amplitude, H):
    if not _on_branch(x, res, amplitude):
        raise NoPlaneWaveError(
            f"harmonic balance did not converge for case {case!r}, k = {k}, amplitude = "
            f"{amplitude} (residual {res:.2e}, or Newton left the branch of the linear "
            "wave); near a resonance of a harmonic with a "
            "lattice mode (e.g. sin^2 k = omega^2 for the U second harmonic) no small-"
            "amplitude plane wave exists")
    w_lin = float(model.omega_rotation(k, material.alpha, material.K_s, material.K_theta))
    return PlaneWave(case, k, amplitude, float(x[-1]), w_lin, x[:H].copy(),
                     x[H:2 * H].copy(), float(res))


def _travelling_start(material, case, k, amplitude, b0):
    """The "travelling" start: the exact plane wave of peak rotation ``amplitude`` (odd
    theta harmonics, the forced U harmonics and their velocities), every field multiplied
    by the same (1 + b0), so no free U waves beat against the forced ones."""
    th, thd, U, Ud = plane_wave(material, case, k, amplitude).fields(np.arange(b0.size))
    f = 1 + b0
    if case == "coupled":
        return LatticeState(U * f, Ud * f, th * f, thd * f)
    return LatticeState(None, None, th * f, thd * f)


register_start("travelling", _travelling_start)
