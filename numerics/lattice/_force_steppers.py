"""The fixed-step loops of any lattice whose force is a compiled function: the one SRKN and
the one RK4 implementation behind every model's run (``numerics.models.simulate_model``).

A *force* is a Numba function ``force(u, p, out, S)``: the acceleration of every site of
the ring state ``u`` (shape (d, N), C-contiguous) into ``out`` (same shape), with
parameters ``p`` (1-d float array) and work rows ``S`` (shape (rows, N)). The generated
force of a model file is one (``numerics.models.compiled_force``); a registered fast force
(``register_fast_force``, the fused flexMM kernel) is another.

The loops take the force (and the velocity-dependent parts below) as first-class
arguments: Numba compiles one specialisation per force, in which the call is direct, so
the loop costs what a loop written around that force would.

- ``srkn_force_steps``: the symplectic RKN methods of kind "srkn" (``Method.a``,
  ``Method.b``: verlet, srkn6b, srkn11b, kahanli8; BAB form, the kick that ends a step and
  the one that starts the next sharing one force evaluation), each step optionally wrapped
  in a velocity flow (``flow``, ``flow_args``): the exact half-step flow of a linear
  damping, i.e. a Strang splitting (order 2). ``no_flow`` for a lossless lattice.
- ``rk4_force_steps``: classical RK4 on (u, v) with an optional velocity-dependent force
  (``damping``, ``damping_args``) added in every stage; ``no_damping`` for a lossless
  lattice (an empty function Numba inlines: nothing of it is left in the loop).
- ``local_flow``, ``band_flow``: the exact flows of dv/dt = -M^-1 C v of a site-local
  damping (one (d, d) matrix per site) and of a bond damping (a short circulant
  convolution over the ring), ``linear_damping``: -M^-1 dR/dv of a quadratic Rayleigh
  function R (site and bond Hessians).

Every loop returns the number of steps completed with a finite state (it stops after the
first step whose u[0, 0] is not finite; the caller checks the whole state).
"""

from __future__ import annotations

import numpy as np
from numba import njit

from ._fast_forces import flexmm_force, flexmm_rotation_force
from ._integrators import Method

_FAST = {"contract"}


@njit(inline="always")
def no_flow(v, args):
    """The identity flow (a lossless lattice: nothing between two SRKN steps)."""


@njit(inline="always")
def no_damping(v, args, out):
    """No velocity-dependent force (a lossless lattice)."""


# inline="always": called from another compiled function (the cached loops below), its
# body is inlined there; called from Python, it is compiled as any function of functions
@njit(inline="always", cache=False, nogil=True, fastmath=_FAST, boundscheck=False)
def srkn_force_steps(force, flow, flow_args, u, v, p, S, acc, A, B, dt, nsteps):
    """``nsteps`` steps of the symplectic RKN method (A, B) (BAB: kick B[0], drift A[0],
    kick B[1], ...; A[-1] = 0), each between two ``flow(v, flow_args)``.

    ``acc`` must hold the acceleration of the current ``u`` on entry (``force(u, p, acc,
    S)``); it holds that of the final state on exit (the last kick of one step and the
    first of the next share it). Returns the steps completed while u[0, 0] is finite.
    """
    d, N = u.shape
    for step in range(nsteps):
        flow(v, flow_args)
        for j in range(B.size):
            hb = B[j] * dt
            for a in range(d):
                for n in range(N):
                    v[a, n] += hb * acc[a, n]
            if A[j] != 0.0:
                ha = A[j] * dt
                for a in range(d):
                    for n in range(N):
                        u[a, n] += ha * v[a, n]
                force(u, p, acc, S)
        flow(v, flow_args)
        if not np.isfinite(u[0, 0]):
            return step
    return nsteps


@njit(cache=False, nogil=True, fastmath=_FAST, boundscheck=False)
def rk4_force_steps(force, damping, damping_args, u, v, p, S, dt, nsteps):
    """``nsteps`` classical RK4 steps of u' = v, v' = force(u) + damping(v).

    ``damping(v, damping_args, out)`` adds the velocity-dependent acceleration of ``v``
    to ``out`` (``no_damping``: none). Returns the steps completed while u[0, 0] is
    finite.
    """
    d, N = u.shape
    tu = np.empty_like(u)  # the stage's state
    tv = np.empty_like(u)
    kv = np.empty_like(u)  # the stage's acceleration
    su = np.empty_like(u)  # k1 + 2 k2 + 2 k3 + k4, of u and of v
    sv = np.empty_like(u)
    half = 0.5 * dt
    for step in range(nsteps):
        for a in range(d):
            for n in range(N):
                tu[a, n] = u[a, n]
                tv[a, n] = v[a, n]
                su[a, n] = 0.0
                sv[a, n] = 0.0
        for stage in range(4):
            force(tu, p, kv, S)
            damping(tv, damping_args, kv)
            w = 1.0 if stage == 0 or stage == 3 else 2.0
            c = dt if stage == 2 else half  # the next stage's offset (unused after the last)
            for a in range(d):
                for n in range(N):
                    x = tv[a, n]
                    su[a, n] += w * x
                    sv[a, n] += w * kv[a, n]
                    tu[a, n] = u[a, n] + c * x
                    tv[a, n] = v[a, n] + c * kv[a, n]
        h6 = dt / 6.0
        for a in range(d):
            for n in range(N):
                u[a, n] += h6 * su[a, n]
                v[a, n] += h6 * sv[a, n]
        if not np.isfinite(u[0, 0]):
            return step
    return nsteps


@njit(cache=True, boundscheck=False)
def local_flow(v, args):
    """v_n <- E v_n at every site (``args = (E,)``, E (d, d)): the exact flow of a
    site-local linear damping over a half step."""
    E = args[0]
    d, N = v.shape
    tmp = np.empty(d)
    for n in range(N):
        for a in range(d):
            t = 0.0
            for b in range(d):
                t += E[a, b] * v[b, n]
            tmp[a] = t
        for a in range(d):
            v[a, n] = tmp[a]


@njit(cache=True, boundscheck=False)
def band_flow(v, args):
    """v_n <- sum_i K_i v_{n - offs_i} (``args = (offs, K, w)``: offsets (r,), kernels
    (r, d, d), work (d, N)): the exact flow of a bond damping over a half step, a short
    circulant convolution over the ring."""
    offs, K, w = args
    d, N = v.shape
    w[:, :] = 0.0
    # one tap at a time over the whole ring, in two contiguous runs (the wrap, then the
    # rest; offs in [0, N)): loops the compiler vectorises, and every site's sum takes
    # its terms in the same order as a loop over the sites would (the same bits)
    for i in range(offs.size):
        o = offs[i]
        for a in range(d):
            for b in range(d):
                c = K[i, a, b]
                for n in range(o):
                    w[a, n] += c * v[b, n - o + N]
                for n in range(o, N):
                    w[a, n] += c * v[b, n - o]
    v[:, :] = w


@njit(cache=True, boundscheck=False)
def linear_damping(v, args, out):
    """out -= M^-1 dR/dv for R = sum_n (v_n C_s v_n + (v_n, v_{n+1}) C_b (v_n, v_{n+1})) / 2
    (``args = (C_s (d, d), C_b (2 d, 2 d), minv (d,))``): each site's pull from its own
    velocity and from both bonds it belongs to."""
    Cs, Cb, minv = args
    d, N = v.shape
    for n in range(N):
        m = n - 1 if n > 0 else N - 1
        l_ = n + 1 if n + 1 < N else 0
        for a in range(d):
            f = 0.0
            for b in range(d):
                f += (Cs[a, b] + Cb[a, b] + Cb[d + a, d + b]) * v[b, n]
                f += Cb[a, d + b] * v[b, l_] + Cb[d + a, b] * v[b, m]
            out[a, n] -= minv[a] * f


# srkn_force_steps takes its force as an argument, which Numba compiles in every process
# (no disk cache for a function of a function: ~1.3 s, in each map worker). The paper
# chain's fused forces get the same loop (``srkn_force_steps``, inlined) around a direct call to
# a *global* force, cached on disk; lossless runs only (no flow). Written out, not made by
# a factory: a closure over the force recompiles in each process (Numba keys its cache on
# the pickled closure cells, a dispatcher's pickle holds a per-process id), and a
# dispatcher passed as a value cannot be cached ("dynamic globals").
# tests/test_force_steppers.py: bit for bit the states of the generic loop.
@njit(cache=True, nogil=True, fastmath=_FAST, boundscheck=False)
def _srkn_flexmm_steps(u, v, p, S, acc, A, B, dt, nsteps):
    """``srkn_force_steps(flexmm_force, no_flow, (), ...)``, cached on disk."""
    return srkn_force_steps(flexmm_force, no_flow, (), u, v, p, S, acc, A, B, dt, nsteps)


@njit(cache=True, nogil=True, fastmath=_FAST, boundscheck=False)
def _srkn_flexmm_rotation_steps(u, v, p, S, acc, A, B, dt, nsteps):
    """``srkn_force_steps(flexmm_rotation_force, no_flow, (), ...)``, cached on disk."""
    return srkn_force_steps(flexmm_rotation_force, no_flow, (), u, v, p, S, acc, A, B, dt,
                            nsteps)


#: force -> its SRKN loop compiled for it and cached on disk (lossless runs): the
#: registered fast forces of the paper chain; any other force compiles
#: ``srkn_force_steps`` in each process
_CACHED_SRKN = {flexmm_force: _srkn_flexmm_steps,
                flexmm_rotation_force: _srkn_flexmm_rotation_steps}


class ForceStepper:
    """One run's stepping of a lattice with a compiled force: its state, work arrays and
    method; ``advance(n)`` does n steps (the run control calls it chunk by chunk).

    Parameters
    ----------
    force : Numba function
        ``force(u, p, out, S)`` (see the module docstring).
    p : ndarray
        The force's parameters.
    rows : int
        Work rows of the force (S has shape (max(rows, 1), N)).
    u, v : ndarray, shape (d, N)
        The state; advanced in place (C-contiguous float64).
    method : Method
        A fixed-step method: kind "srkn" or "rk4".
    dt : float
    damping : tuple, optional
        ``(C_s, C_b, minv)`` of a linear damping (``linear_damping``); None: lossless.
    flow : tuple, optional
        For an SRKN method with damping: ``(flow, args)``, the exact half-step flow of the
        damping (``local_flow``, ``band_flow``) that wraps each step (Strang splitting).
    """

    def __init__(self, force, p, rows, u, v, method: Method, dt: float, damping=None,
                 flow=None):
        if method.kind not in ("srkn", "rk4"):
            raise ValueError(f"method {method.name!r} is not a fixed-step method of kind "
                             "'srkn' or 'rk4'")
        if damping is not None and method.kind == "srkn" and flow is None:
            raise ValueError("an SRKN method with damping needs the damping's flow "
                             "(Strang splitting): symplectic kicks take no velocity force")
        self.force, self.p, self.method, self.dt = force, p, method, float(dt)
        self.u, self.v = u, v
        self.S = np.empty((max(int(rows), 1), u.shape[1]))
        self.damping = damping
        self.flow = flow
        self.evaluations = 0
        if method.kind == "srkn":
            self.A = np.asarray(method.a, float)
            self.B = np.asarray(method.b, float)
            self.acc = np.empty_like(u)
            force(u, p, self.acc, self.S)  # first same as last: kept between calls
            self.evaluations += 1

    def advance(self, nsteps: int) -> int:
        """Advance ``nsteps`` steps; returns the number completed while finite."""
        if self.method.kind == "srkn":
            cached = _CACHED_SRKN.get(self.force) if self.flow is None else None
            if cached is not None:
                done = cached(self.u, self.v, self.p, self.S, self.acc, self.A, self.B,
                              self.dt, nsteps)
                self.evaluations += done * self.method.evaluations
                return int(done)
            fl, args = self.flow if self.flow is not None else (no_flow, ())
            done = srkn_force_steps(self.force, fl, args, self.u, self.v, self.p, self.S,
                                    self.acc, self.A, self.B, self.dt, nsteps)
        elif self.damping is not None:
            done = rk4_force_steps(self.force, linear_damping, self.damping, self.u, self.v,
                                   self.p, self.S, self.dt, nsteps)
        else:
            done = rk4_force_steps(self.force, no_damping, (), self.u, self.v, self.p,
                                   self.S, self.dt, nsteps)
        self.evaluations += done * self.method.evaluations
        return int(done)
