"""Material parameters, lattice states and the conserved energy of eq. `norm`."""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from common import paper
from generated import lattice_model

from .checks import positive, real_array

CASES = ("rotation", "coupled")


def check_case(case: str) -> str:
    if not isinstance(case, str) or case not in CASES:
        raise ValueError(f"case must be 'rotation' (case I) or 'coupled' (case II), got {case!r}")
    return case


@dataclass(frozen=True)
class Material:
    """Normalised parameters of the chain (below eq. `norm` of the paper).

    Parameters
    ----------
    alpha : float
        Inertial parameter, > 0.
    K_s : float
        Shear stiffness k_s / k_l, > 0.
    K_theta : float
        Bending stiffness 4 k_theta / (k_l a^2), > 0.
    """

    alpha: float
    K_s: float
    K_theta: float

    def __post_init__(self):
        for name in ("alpha", "K_s", "K_theta"):
            object.__setattr__(self, name, positive(name, getattr(self, name)))

    @property
    def delta(self) -> float:
        """delta = K_s - K_theta: its sign sets the curvature of the rotational branch."""
        return self.K_s - self.K_theta

    @classmethod
    def paper(cls, point: str) -> Material:
        """The material of one of the paper's test points, ``"blue"`` or ``"green"``
        (Figs. 4-9; numbers in :mod:`common.paper`)."""
        return cls(paper.ALPHA, paper.K_S, paper.K_theta(point))

    @classmethod
    def from_physical(cls, m, J, a, k_l, k_s, k_theta) -> Material:
        """From mass m, moment of inertia J, cell length a and spring stiffnesses.

        alpha = a sqrt(m / (4 J)), K_s = k_s / k_l, K_theta = 4 k_theta / (k_l a^2).
        The paper prints alpha = a / sqrt(m / (4 J)), which is not dimensionless (erratum 3
        in docs/reliability.md); this is the dimensionless form consistent with T = t sqrt(k_l/m).
        """
        m, J, a, k_l, k_s, k_theta = (
            positive(n, v) for n, v in
            zip(("m", "J", "a", "k_l", "k_s", "k_theta"), (m, J, a, k_l, k_s, k_theta)))
        # each value may be fine in SI while a ratio leaves float64 (k_l a^2 underflowing to
        # 0, m / 4J to inf): that is the units' fault, not the material's; say so
        try:
            values = {"alpha": a * math.sqrt(m / (4 * J)), "K_s": k_s / k_l,
                      "K_theta": 4 * k_theta / (k_l * a**2)}
        except (ZeroDivisionError, OverflowError):
            values = {}
        bad = [n for n, v in values.items() if not (math.isfinite(v) and v > 0)] \
            if values else ["K_theta"]  # the one ratio that can divide by an underflowed 0
        if bad:
            raise ValueError(
                f"the normalised {', '.join(bad)} {'is' if len(bad) == 1 else 'are'} out of "
                "float64's range "
                "(over- or underflow); give m, J, a, k_l, k_s, k_theta in units nearer 1 "
                "(e.g. g and mm)")
        return cls(**values)

    def omega_max(self, case: str) -> float:
        """Highest linear frequency of the lattice (max of `discrete1`, `discrete2`)."""
        check_case(case)
        # both branches are monotone in sin^2(q/2): their maxima sit at q = 0 or q = pi
        ends = np.array([0.0, math.pi])
        w_rot = float(np.max(discrete_omega_rotation(ends, self)))
        return max(w_rot, float(discrete_omega_longitudinal(math.pi))) if case == "coupled" \
            else w_rot


def discrete_omega_rotation(q, material: Material):
    """Rotational branch of the lattice, eq. `discrete2` (positive root; generated)."""
    return lattice_model.omega_rotation(q, material.alpha, material.K_s, material.K_theta)


def discrete_omega_longitudinal(q):
    """Longitudinal branch of the lattice, eq. `discrete1` (generated)."""
    return lattice_model.omega_longitudinal(q)


def _as_field(name, x, n=None):
    if x is None:
        raise TypeError(f"{name} must be an array of N >= 3 real numbers, got None")
    a = real_array(name, x).copy()
    if a.ndim != 1:
        raise ValueError(f"{name} must be a 1-D array, got shape {a.shape}")
    if a.size < 3:
        raise ValueError(f"{name} needs N >= 3 sites, got N = {a.size}")
    if n is not None and a.size != n:
        raise ValueError(f"{name} has {a.size} sites, theta has {n}")
    if not np.all(np.isfinite(a)):
        bad = int(np.flatnonzero(~np.isfinite(a))[0])
        raise ValueError(f"{name} is not finite (site {bad} = {a[bad]})")
    return a


@dataclass(frozen=True)
class LatticeState:
    """Positions and velocities of all N sites (copied and validated on construction).

    Attributes
    ----------
    U, U_dot : ndarray, shape (N,), or None
        Longitudinal displacement and velocity; None in case (I) "rotation".
    theta, theta_dot : ndarray, shape (N,)
        Rotation and angular velocity.
    """

    U: np.ndarray | None
    U_dot: np.ndarray | None
    theta: np.ndarray
    theta_dot: np.ndarray

    def __post_init__(self):
        th = _as_field("theta", self.theta)
        object.__setattr__(self, "theta", th)
        object.__setattr__(self, "theta_dot", _as_field("theta_dot", self.theta_dot, th.size))
        if (self.U is None) != (self.U_dot is None):
            raise ValueError("U and U_dot must both be arrays or both be None")
        if self.U is not None:
            object.__setattr__(self, "U", _as_field("U", self.U, th.size))
            object.__setattr__(self, "U_dot", _as_field("U_dot", self.U_dot, th.size))

    @property
    def N(self) -> int:
        return self.theta.size

    def for_case(self, case: str) -> LatticeState:
        """Check the state fits ``case``; returns the state a run of that case uses."""
        check_case(case)
        if case == "coupled":
            if self.U is None:
                raise ValueError("case 'coupled' needs U and U_dot (got None)")
            return self
        if self.U is not None and (np.any(self.U != 0) or np.any(self.U_dot != 0)):
            raise ValueError("case 'rotation' has no displacement: pass U = U_dot = None")
        return LatticeState(None, None, self.theta, self.theta_dot)


def versine(theta):
    """1 - cos(theta), accurate for small theta (no cancellation)."""
    c = np.cos(theta)
    s = np.sin(theta)
    with np.errstate(divide="ignore", invalid="ignore"):
        return np.where(c > 0, s * s / (1 + c), 1 - c)


def energy(state: LatticeState, material: Material, case: str) -> float:
    """Conserved energy of eq. `norm` (periodic chain).

    H = sum_n [2 U_dot^2 + theta_dot^2/(2 alpha^2) + 2 e_n^2
               + K_s/2 (sin th_{n+1} - sin th_n)^2 + K_theta ((th_{n+1}+th_n)^2/2 + th_n^2)],
    e_n = U_{n+1} - U_n + 1 - (cos th_{n+1} + cos th_n)/2. Case (I) has U = 0.
    That this H generates eq. `norm` is proven symbolically in tests/test_energy.py.
    """
    state = state.for_case(case)
    th, thd = state.theta, state.theta_dot
    thp = np.roll(th, -1)
    v = versine(th)
    e = (np.roll(v, -1) + v) / 2
    kin = np.sum(thd**2) / (2 * material.alpha**2)
    if case == "coupled":
        e = e + np.roll(state.U, -1) - state.U
        kin += 2 * np.sum(state.U_dot**2)
    pot = (2 * np.sum(e**2)
           + material.K_s / 2 * np.sum((np.sin(thp) - np.sin(th)) ** 2)
           + material.K_theta * np.sum((thp + th) ** 2 / 2 + th**2))
    return float(kin + pot)
