"""The plain NumPy RK4 everyone would write first (np.roll stencil): the speed baseline."""

from __future__ import annotations

import numpy as np

from generated import lattice_model

from ._model import LatticeState, Material


def numpy_accel(theta, U, material: Material, coupled: bool):
    """Eq. `norm` with np.roll neighbours and the generated right-hand sides
    (``generated.lattice_model``; sin/cos recomputed per use, as typed)."""
    tp, tm = np.roll(theta, -1), np.roll(theta, 1)
    if coupled:
        Um, Up = np.roll(U, 1), np.roll(U, -1)
    else:
        U = Um = Up = 0.0
    args = (Um, U, Up, tm, theta, tp, material.alpha, material.K_s, material.K_theta)
    ath = lattice_model.acceleration_theta(*args)
    aU = lattice_model.acceleration_U(*args) if coupled else None
    return ath, aU


def numpy_rk4(state: LatticeState, material: Material, case: str, t_end: float, dt: float
              ) -> LatticeState:
    """Classical RK4 with the NumPy force above; same step rule as ``integrate``."""
    coupled = case == "coupled"
    nsteps = int(np.ceil(t_end / dt - 1e-9))
    h = t_end / nsteps
    n = state.N
    y = np.concatenate([state.theta, state.theta_dot]
                       + ([state.U, state.U_dot] if coupled else []))

    def f(y):
        th, w = y[:n], y[n:2 * n]
        U = y[2 * n:3 * n] if coupled else None
        ath, aU = numpy_accel(th, U, material, coupled)
        parts = [w, ath] + ([y[3 * n:], aU] if coupled else [])
        return np.concatenate(parts)

    for _ in range(nsteps):
        k1 = f(y)
        k2 = f(y + h / 2 * k1)
        k3 = f(y + h / 2 * k2)
        k4 = f(y + h * k3)
        y = y + h / 6 * (k1 + 2 * k2 + 2 * k3 + k4)
    if coupled:
        return LatticeState(y[2 * n:3 * n], y[3 * n:], y[:n], y[n:2 * n])
    return LatticeState(None, None, y[:n], y[n:2 * n])
