"""Registry of time integrators (``numerics.METHODS``).

Fixed-step methods run their whole loop in compiled code (``_kernels``); ``dop853``
(and ``rk45``) wrap scipy's adaptive ``solve_ivp`` as a reference, not a hot path.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

# Blanes & Moan, J. Comput. Appl. Math. 142 (2002) 313, symmetric BAB SRKN methods
# (positions drift with a_i, velocities are kicked with b_i; a_last = 0).
_SRKN6B_A = (0.24529895718427100, 0.60487266571108000, -0.35017162289535100,
             -0.35017162289535100, 0.60487266571108000, 0.24529895718427100, 0.0)
_SRKN6B_B = (0.082984406417405200, 0.39630980149836800, -0.039056304922348600,
             0.1195241940131508, -0.039056304922348600, 0.39630980149836800,
             0.082984406417405200)
_SRKN11B_A = (0.12322977594627100, 0.29055379779955800, -0.12704921262541700,
              -0.24633176106207500, 0.35720887279592800, 0.2047770542914700,
              0.35720887279592800, -0.24633176106207500, -0.12704921262541700,
              0.29055379779955800, 0.12322977594627100, 0.0)
_SRKN11B_B = (0.041464998518262400, 0.19812867191806700, -0.040006192104153300,
              0.075253984301580700, -0.011511387420687900, 0.23666992478693110,
              0.23666992478693110, -0.011511387420687900, 0.075253984301580700,
              -0.040006192104153300, 0.19812867191806700, 0.041464998518262400)

# Kahan & Li, Math. Comp. 66 (1997) 1089, "Composition constants for raising the orders of
# unconventional schemes for ordinary differential equations", scheme s17odr8a: a
# symmetric composition of 17 Stormer-Verlet steps of lengths gamma_i h, order 8 (also in
# Hairer, Lubich & Wanner, Geometric Numerical Integration, 2nd ed., sec. V.3.2). The first
# nine gammas; the rest mirror them (gamma_{18-i} = gamma_i).
_KAHANLI8_GAMMA = (0.13020248308889008087881763, 0.56116298177510838456196441,
                   -0.38947496264484728640807860, 0.15884190655515560089621075,
                   -0.39590389413323757733623154, 0.18453964097831570709183254,
                   0.25837438768632204729397911, 0.29501172360931029887096624,
                   -0.60550853383003451169892108)


def verlet_composition(gamma_half):
    """(a, b) of the BAB form of the symmetric composition of Verlet steps gamma_1 h, ...,
    gamma_s h (``gamma_half`` the first (s + 1)/2, the rest mirrored): each Verlet step
    kicks gamma/2, drifts gamma, kicks gamma/2, and adjacent half kicks merge."""
    g = tuple(gamma_half) + tuple(gamma_half[-2::-1])
    a = g + (0.0,)
    b = (g[0] / 2,) + tuple((g[i] + g[i + 1]) / 2 for i in range(len(g) - 1)) + (g[-1] / 2,)
    return a, b


@dataclass(frozen=True)
class Method:
    """One integrator: name, order, force evaluations per step, kind."""

    name: str
    order: int
    evaluations: int  # force evaluations per step (fixed-step methods)
    kind: str  # "rk4", "srkn" or "scipy"
    symplectic: bool
    description: str
    a: tuple = field(default=(), repr=False)
    b: tuple = field(default=(), repr=False)

    @property
    def fixed_step(self) -> bool:
        return self.kind != "scipy"

    def stability_limit(self) -> float:
        """Largest omega*dt for which the method is stable on x'' = -omega^2 x.

        Computed from the coefficients (one-step matrix of the harmonic oscillator,
        stable while |trace|/2 <= 1), once per method; RK4 gives 2 sqrt(2).
        """
        if self.name not in _LIMITS:
            _LIMITS[self.name] = self._stability_limit()
        return _LIMITS[self.name]

    def _stability_limit(self) -> float:
        if not self.fixed_step:
            return float("inf")

        def stable(h):
            return np.max(np.abs(np.linalg.eigvals(self._oscillator_matrix(h)))) <= 1 + 1e-9

        hs = np.linspace(1e-3, 8.0, 8000)
        # the grid's first unstable h from all its one-step matrices at once (one at a time:
        # ~0.3 s, paid by every process that runs a model, each map worker), confirmed one
        # at a time around it; else the grid walked one at a time
        batch = np.max(np.abs(np.linalg.eigvals(self._oscillator_matrices(hs))), axis=1)
        first = np.flatnonzero(~(batch <= 1 + 1e-9))
        bad = int(first[0]) if first.size else None
        if not (bad is None or (not stable(hs[bad]) and (bad == 0 or stable(hs[bad - 1])))):
            bad = next((i for i, h in enumerate(hs) if not stable(h)), None)
        if bad is None:
            return float(hs[-1])
        lo, hi = hs[bad - 1], hs[bad]
        for _ in range(50):  # bisection on the first loss of stability
            mid = 0.5 * (lo + hi)
            lo, hi = (mid, hi) if stable(mid) else (lo, mid)
        return float(lo)

    def _oscillator_matrices(self, hs):
        """``_oscillator_matrix`` at every step of ``hs``, shape (len(hs), 2, 2)."""
        hs = np.asarray(hs, float)[:, None, None]
        eye = np.broadcast_to(np.eye(2), hs.shape[:1] + (2, 2))
        if self.kind == "rk4":
            Ah = np.array([[0.0, 1.0], [-1.0, 0.0]]) * hs
            M = eye.copy()
            term = eye.copy()
            for j in range(1, 5):
                term = term @ Ah / j
                M = M + term
            return M
        M = eye.copy()
        for j, bj in enumerate(self.b):
            kick = eye.copy()
            kick[:, 1, 0] = -bj * hs[:, 0, 0]
            M = kick @ M
            if j < len(self.a) and self.a[j] != 0:
                drift = eye.copy()
                drift[:, 0, 1] = self.a[j] * hs[:, 0, 0]
                M = drift @ M
        return M

    def _oscillator_matrix(self, h):
        if self.kind == "rk4":
            A = np.array([[0.0, 1.0], [-1.0, 0.0]])
            Ah = A * h
            M = np.eye(2)
            term = np.eye(2)
            for j in range(1, 5):
                term = term @ Ah / j
                M = M + term
            return M
        M = np.eye(2)
        for j, bj in enumerate(self.b):
            M = np.array([[1.0, 0.0], [-bj * h, 1.0]]) @ M  # kick
            if j < len(self.a) and self.a[j] != 0:
                M = np.array([[1.0, self.a[j] * h], [0.0, 1.0]]) @ M  # drift
        return M


_REGISTRY: dict[str, Method] = {}
_LIMITS: dict[str, float] = {}  # stability limits, computed on first use


def register(method: Method) -> Method:
    if method.name in _REGISTRY:
        raise ValueError(f"method {method.name!r} registered twice")
    _REGISTRY[method.name] = method
    return method


register(Method("rk4", 4, 4, "rk4", False, "classical Runge-Kutta 4 (the paper's method)"))
register(Method("verlet", 2, 1, "srkn", True, "Stormer-Verlet (kick-drift-kick)",
                a=(1.0, 0.0), b=(0.5, 0.5)))
register(Method("srkn6b", 4, 6, "srkn", True,
                "Blanes & Moan 2002 SRKN6b, symplectic RKN order 4", _SRKN6B_A, _SRKN6B_B))
register(Method("srkn11b", 6, 11, "srkn", True,
                "Blanes & Moan 2002 SRKN11b, symplectic RKN order 6", _SRKN11B_A, _SRKN11B_B))
register(Method("kahanli8", 8, 17, "srkn", True,
                "Kahan & Li 1997 s17odr8a, 17-stage Verlet composition, symplectic order 8",
                *verlet_composition(_KAHANLI8_GAMMA)))
register(Method("dop853", 8, 0, "scipy", False, "scipy solve_ivp DOP853 (adaptive reference)"))
register(Method("rk45", 5, 0, "scipy", False, "scipy solve_ivp RK45 (adaptive)"))

#: Names of all integrators, usable as ``method=``.
METHODS = tuple(_REGISTRY)


def get_method(name: str) -> Method:
    try:
        return _REGISTRY[name]
    except (KeyError, TypeError):
        raise ValueError(f"unknown method {name!r}; choose one of {', '.join(METHODS)}") from None
