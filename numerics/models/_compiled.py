"""A model's generated code compiled with Numba: its force, the one its runs step with
where no fast force is registered for its energy (``_forces.run_force``), and its energy.

The force is the model's generated loop ``accelerations_into`` (over the bonds: each
bond's pulls on its two sites printed from the derivatives of the energy and computed once,
each site's own term beside them, the ring's ends outside the loop; the elementary functions
of one site's fields computed once per site in ``site_functions_all`` before, with the fused
kernel's polynomial sin and cos), compiled with Numba (fused multiply-adds allowed), on a
ring of N sites with (n_fields, N) arrays: ``force(u, p, out, S)``, the force of
``numerics.lattice.ForceStepper``.
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np

from energy import Model, ModelError

_KERNELS: dict = {}


def _fast_trig(f):
    """``f`` with numpy.sin / numpy.cos replaced by the fused kernel's branch-free
    polynomial (``numerics.lattice.sincos_vers``: within 1 ulp of libm for |x| <= TRIG_LIMIT,
    tests/test_kernels.py): the generated source, recompiled. A libm sin and cos cost
    ~10 ns a site; the polynomial inlines (~2 ns, bench/models.py). The kernel uses it only
    where every field of the site is within TRIG_LIMIT (a run beyond has blown up)."""
    import inspect
    import textwrap

    src = textwrap.dedent(inspect.getsource(f))
    if "numpy.sin(" not in src and "numpy.cos(" not in src:
        return f
    from numerics.lattice import sincos_vers

    def _psin(x):
        return sincos_vers(x)[0]

    def _pcos(x):
        return sincos_vers(x)[1]

    import numba

    src = src.replace("numpy.sin(", "_psin(").replace("numpy.cos(", "_pcos(")
    namespace = {"numpy": np,
                 "_psin": numba.njit(inline="always", fastmath={"contract"})(_psin),
                 "_pcos": numba.njit(inline="always", fastmath={"contract"})(_pcos)}
    exec(compile(src, f"<{f.__module__}.{f.__name__}, polynomial trig>", "exec"), namespace)
    return namespace[f.__name__]


class _Compiled(NamedTuple):
    """A model's compiled generated code: ``force(u, p, out, S)`` (the acceleration of
    every site, the steppers' force, ``numerics.lattice.ForceStepper``), ``rows`` (the
    site functions: S has max(rows, 1) rows), ``energy(u, v, p, masses, x)`` (the total)
    and ``site_loop(u, S, p, out)`` (the generated accelerations_into alone)."""

    force: object
    rows: int
    energy: object
    site_loop: object


def _kernels(model: Model) -> _Compiled:
    """The model's generated code compiled with Numba (``_Compiled``), once per module."""
    key = (model.code.__name__, model.code.MODEL_HASH)
    if key in _KERNELS:
        return _KERNELS[key]
    import numba

    code = model.code
    cell_energy = numba.njit(cache=False)(code.cell_energy)
    if not hasattr(code, "accelerations_into"):
        raise ModelError(f"model {model.describe()}: its generated module {code.__name__} "
                         "is of an older layout (no accelerations_into): run `make derive`")
    # the generated site loop: each site's acceleration from its equations of motion,
    # the elementary functions of single sites (sin, cos, exp, ...) computed once per
    # site in a pass before (the fused flexMM kernel's form)
    from numerics.lattice import TRIG_LIMIT

    nf = int(code.SITE_FUNCTIONS_ALL)
    fast = _fast_trig(code.site_functions_all)
    fast_sites = numba.njit(cache=False, boundscheck=False, fastmath={"contract"})(fast)
    libm_sites = numba.njit(cache=False, boundscheck=False)(code.site_functions_all)
    # contraction into fused multiply-adds, as the fused kernel (numerics.lattice.FASTMATH)
    site_loop = numba.njit(cache=False, boundscheck=False, fastmath={"contract"},
                           error_model="numpy")(code.accelerations_into)

    if nf == 0:  # no site functions: the bond loop alone

        @numba.njit(cache=False, boundscheck=False)
        def force(u, p, out, S):
            site_loop(u, S, p, out)

    elif fast is code.site_functions_all:  # no sin or cos: nothing to range-check

        @numba.njit(cache=False, boundscheck=False)
        def force(u, p, out, S):
            libm_sites(u, p, S)
            site_loop(u, S, p, out)

    else:

        @numba.njit(cache=False, boundscheck=False)
        def force(u, p, out, S):
            d, N = u.shape
            near = True  # the polynomial sin/cos where every field is within TRIG_LIMIT
            for a in range(d):
                for n in range(N):
                    near &= abs(u[a, n]) <= TRIG_LIMIT
            if near:
                fast_sites(u, p, S)
            else:
                libm_sites(u, p, S)
            site_loop(u, S, p, out)

    @numba.njit(cache=False)
    def energy(u, v, p, masses, x):
        d, N = u.shape
        e = 0.0
        for n in range(N):
            m = n + 1 if n + 1 < N else 0
            for a in range(d):
                x[a] = u[a, n]
                x[d + a] = u[a, m]
                e += 0.5 * masses[a] * v[a, n] ** 2
            e += cell_energy(x, p)
        return e

    _KERNELS[key] = _Compiled(force, nf, energy, site_loop)
    return _KERNELS[key]


def ring_state(model: Model, name: str, u) -> np.ndarray:
    """``u`` as a C-contiguous float array of shape (d, N), N >= 3, or a ModelError: the
    compiled kernels index d rows and the ring's neighbours without bounds checks (a
    (1, N) state of the two-field flexmm read and wrote past its end: NaN forces, then a
    segmentation fault or an LLVM assertion later in the process)."""
    a = np.asarray(u)
    d = model.n_fields
    if a.dtype.kind not in "fiu":
        raise ModelError(f"{name} must hold real numbers, got an array of dtype {a.dtype}")
    if a.ndim != 2 or a.shape[0] != d or a.shape[1] < 3:
        raise ModelError(f"{name} must have shape (d, N) = ({d}, N >= 3): one row per field "
                         f"of model {model.name!r} ({', '.join(model.fields)}), got shape "
                         f"{a.shape}")
    return np.ascontiguousarray(a, dtype=float)


def lattice_force(model: Model, u: np.ndarray) -> np.ndarray:
    """The acceleration of every site, shape (d, N), from the compiled force."""
    u = ring_state(model, "u", u)
    out = np.empty_like(u)
    compiled_force(model, u.shape[1])(u, out)
    return out


def compiled_force(model: Model, N: int):
    """force(u, out): the compiled acceleration of a ring of N sites into ``out`` (both
    (d, N), C-contiguous), its work buffers made once: for timing the kernel itself."""
    compiled = _kernels(model)
    nf, kernel, loop = compiled.rows, compiled.force, compiled.site_loop
    p = np.asarray(model.p, float)
    S = np.empty((max(nf, 1), N))

    if nf == 0:  # no site functions: the generated loop is the whole force (one call less)
        def force(u, out):
            loop(u, S, p, out)
    else:
        def force(u, out):
            kernel(u, p, out, S)

    return force


def lattice_energy(model: Model, u: np.ndarray, v: np.ndarray) -> float:
    """Total energy of a ring state (kinetic + every cell's W), from the model file."""
    energy = _kernels(model).energy
    u, v = ring_state(model, "u", u), ring_state(model, "v", v)
    if u.shape != v.shape:
        raise ModelError(f"u and v must have the same shape, got {u.shape} and {v.shape}")
    return float(energy(u, v,
                        np.asarray(model.p, float), np.asarray(model.masses, float),
                        np.empty(2 * model.n_fields)))
