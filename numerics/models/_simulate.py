"""Simulation of any lattice model on a ring, and the growth a run measures.

The force is the model's generated loop ``accelerations_into`` (over the bonds: each
bond's pulls on its two sites printed from the derivatives of the energy and computed once,
each site's own term beside them, the ring's ends outside the loop; the elementary functions
of one site's fields computed once per site in ``site_functions_all`` before, with the fused
kernel's polynomial sin and cos), compiled with Numba (fused multiply-adds allowed), on a
ring of N sites with (n_fields, N) arrays. The integrators are the registry's
(``numerics.METHODS``): the symplectic SRKN family (srkn11b by default, order 6), verlet,
kahanli8 and rk4, each with the coefficients the paper's chain uses; the kick that ends a
step and the one that starts the next share one force evaluation.

Start. ``start="exact"`` (default) launches the exact travelling wave (harmonic balance,
``travelling_wave``) plus seeded noise; ``start="linear"`` the linear plane wave, which
leaves free second-harmonic and mean-flow waves beside the carrier.

Measurement. The deviation delta = u - U_exact(k n - omega t) from the exact wave is
Fourier transformed over the ring at each record. The sidebands are every ring mode but
the carrier's harmonics that stand above the noise (where the integrator's phase error and
the noise's drift of the centre of mass grow secularly; a harmonic far below the noise is
kept, as on a small ring it aliases onto a sideband); they are followed until their rms
reaches a tenth of the amplitude (``SATURATION``). The run is "unstable" when the
sidebands grew ``GROWTH_FACTOR`` (20x) and exponentially (the log-slope over the linear
stage's second half, run over the whole stage, bounds the factor: algebraic growth of a
stable wave's near-carrier pairs does not pass), with the rate the least-squares slope of
the largest mode's log amplitude over its stretch above ten times its start; otherwise
"no growth within T", with the slowest rate the run could have shown.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from energy import Model, ModelError

#: deviation (rms over sites, relative to the amplitude) where the linear growth ends
SATURATION = 0.1
#: growth of a mode that makes a run "unstable" (the verdict's threshold, as for maps)
GROWTH_FACTOR = 20.0
#: noise relative to the amplitude: 16 e-foldings fit below SATURATION
NOISE = 1e-8
STARTS = ("exact", "linear")

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


def _kernels(model: Model):
    """(accel, srkn_steps, rk4_steps, energy, number of site functions, force, site_loop)
    compiled for the model's generated code (force(u, p, out, S): accel's work, four
    arguments; site_loop(u, S, p, out): the generated accelerations_into)."""
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

    @numba.njit(cache=False, boundscheck=False)
    def accel(u, p, minv, out, x, g, S):
        force(u, p, out, S)

    @numba.njit(cache=False)
    def srkn_steps(u, v, p, minv, A, B, dt, nsteps, acc, x, g):
        d, N = u.shape
        S = np.empty((max(nf, 1), N))
        accel(u, p, minv, acc, x, g, S)
        for _ in range(nsteps):
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
                    accel(u, p, minv, acc, x, g, S)
            if not np.isfinite(u[0, 0]):
                return False
        return True

    @numba.njit(cache=False)
    def rk4_steps(u, v, p, minv, dt, nsteps, acc, x, g):
        d, N = u.shape
        S = np.empty((max(nf, 1), N))
        k1u = np.empty_like(u)
        k1v = np.empty_like(u)
        k2u = np.empty_like(u)
        k2v = np.empty_like(u)
        k3u = np.empty_like(u)
        k3v = np.empty_like(u)
        k4v = np.empty_like(u)
        tu = np.empty_like(u)
        for _ in range(nsteps):
            accel(u, p, minv, k1v, x, g, S)
            k1u[:] = v
            tu[:] = u + 0.5 * dt * k1u
            accel(tu, p, minv, k2v, x, g, S)
            k2u[:] = v + 0.5 * dt * k1v
            tu[:] = u + 0.5 * dt * k2u
            accel(tu, p, minv, k3v, x, g, S)
            k3u[:] = v + 0.5 * dt * k2v
            tu[:] = u + dt * k3u
            accel(tu, p, minv, k4v, x, g, S)
            k4u = v + dt * k3v
            u += dt / 6 * (k1u + 2 * k2u + 2 * k3u + k4u)
            v += dt / 6 * (k1v + 2 * k2v + 2 * k3v + k4v)
            if not np.isfinite(u[0, 0]):
                return False
        return True

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

    _KERNELS[key] = (accel, srkn_steps, rk4_steps, energy, nf, force, site_loop)
    return _KERNELS[key]


_DAMPED: dict = {}


def _damped_kernels(model: Model):
    """(damp, rk4_damped, split_local) for a model with [dissipation]:

    damp(v, S, Bd, minv, out)   out = -M^-1 dR/dv: the damping acceleration, site by site
                                (S the site block, Bd the bond's (2 d, 2 d) Hessian);
    rk4_damped                  RK4 with the velocity-dependent force;
    split_local                 Strang: the exact damping flow v <- E v over half a step
                                (E = expm(-dt/2 M^-1 C), site-local damping), a step of
                                the symplectic SRKN method, the half flow again (order 2);
    split_band                  the same with bond damping: the flow is a circulant
                                convolution v_n <- sum_r K_r v_{n-r} (``damping_flow``).
    """
    key = (model.code.__name__, model.code.MODEL_HASH)
    if key in _DAMPED:
        return _DAMPED[key]
    import numba

    accel, srkn_steps = _kernels(model)[:2]
    nf = _kernels(model)[4]

    @numba.njit(cache=False, boundscheck=False)
    def damp(v, S, Bd, minv, out):
        d, N = v.shape
        for n in range(N):
            m = n - 1 if n > 0 else N - 1
            l_ = n + 1 if n + 1 < N else 0
            for a in range(d):
                f = 0.0
                for b in range(d):
                    f += (S[a, b] + Bd[a, b] + Bd[d + a, d + b]) * v[b, n]
                    f += Bd[a, d + b] * v[b, l_] + Bd[d + a, b] * v[b, m]
                out[a, n] = -minv[a] * f

    @numba.njit(cache=False)
    def rk4_damped(u, v, p, minv, S, Bd, dt, nsteps, acc, x, g):
        d, N = u.shape
        F = np.empty((max(nf, 1), N))
        k1v = np.empty_like(u)
        k2v = np.empty_like(u)
        k3v = np.empty_like(u)
        k4v = np.empty_like(u)
        w = np.empty_like(u)
        tu = np.empty_like(u)
        tv = np.empty_like(u)
        for _ in range(nsteps):
            accel(u, p, minv, k1v, x, g, F)
            damp(v, S, Bd, minv, w)
            k1v += w
            k1u = v.copy()
            tu[:] = u + 0.5 * dt * k1u
            tv[:] = v + 0.5 * dt * k1v
            accel(tu, p, minv, k2v, x, g, F)
            damp(tv, S, Bd, minv, w)
            k2v += w
            k2u = tv.copy()
            tu[:] = u + 0.5 * dt * k2u
            tv[:] = v + 0.5 * dt * k2v
            accel(tu, p, minv, k3v, x, g, F)
            damp(tv, S, Bd, minv, w)
            k3v += w
            k3u = tv.copy()
            tu[:] = u + dt * k3u
            tv[:] = v + dt * k3v
            accel(tu, p, minv, k4v, x, g, F)
            damp(tv, S, Bd, minv, w)
            k4v += w
            k4u = tv
            u += dt / 6 * (k1u + 2 * k2u + 2 * k3u + k4u)
            v += dt / 6 * (k1v + 2 * k2v + 2 * k3v + k4v)
            if not np.isfinite(u[0, 0]):
                return False
        return True

    @numba.njit(cache=False)
    def split_local(u, v, p, minv, A, B, dt, nsteps, acc, x, g, E):
        d, N = u.shape
        tmp = np.empty(d)
        for _ in range(nsteps):
            for n in range(N):
                for a in range(d):
                    tmp[a] = 0.0
                    for b in range(d):
                        tmp[a] += E[a, b] * v[b, n]
                for a in range(d):
                    v[a, n] = tmp[a]
            if not srkn_steps(u, v, p, minv, A, B, dt, 1, acc, x, g):
                return False
            for n in range(N):
                for a in range(d):
                    tmp[a] = 0.0
                    for b in range(d):
                        tmp[a] += E[a, b] * v[b, n]
                for a in range(d):
                    v[a, n] = tmp[a]
        return True

    @numba.njit(cache=False)
    def _band(v, offs, K, w):
        d, N = v.shape
        for n in range(N):
            for a in range(d):
                w[a, n] = 0.0
            for i in range(offs.size):
                m = (n - offs[i]) % N
                for a in range(d):
                    for b in range(d):
                        w[a, n] += K[i, a, b] * v[b, m]
        v[:, :] = w

    @numba.njit(cache=False)
    def split_band(u, v, p, minv, A, B, dt, nsteps, acc, x, g, offs, K):
        w = np.empty_like(v)
        for _ in range(nsteps):
            _band(v, offs, K, w)
            if not srkn_steps(u, v, p, minv, A, B, dt, 1, acc, x, g):
                return False
            _band(v, offs, K, w)
        return True

    _DAMPED[key] = (damp, rk4_damped, split_local, split_band)
    return _DAMPED[key]


def damping_flow(model: Model, N: int, h: float):
    """The exact flow of dv/dt = -M^-1 C v over time h on a ring of N sites: where the
    damping is site-local, (None, E) with E = expm(-h M^-1 C) (d, d); else ((offs, K),
    None), the flow as a circulant convolution v_n <- sum_i K_i v_{n - offs_i}: K is the
    ring's inverse FFT of E_j = expm(-h M^-1 C(2 pi j / N)), kept where it exceeds 1e-15
    of its largest entry (exp of a banded matrix of small norm: a few sites each side)."""
    from scipy.linalg import expm

    from ._linear import damping_matrix

    S, Bd = model.damping
    d = model.n_fields
    minv = 1 / np.asarray(model.masses, float)
    if not (Bd[:d, d:].any() or Bd[d:, :d].any()):
        return None, expm(-h * minv[:, None] * (S + Bd[:d, :d] + Bd[d:, d:]))
    kap = 2 * math.pi * np.arange(N) / N
    E = np.array([expm(-h * minv[:, None] * damping_matrix(model, q)) for q in kap])
    K = np.real(np.fft.ifft(E, axis=0))  # K[r]: offset r mod N
    size = np.max(np.abs(K), axis=(1, 2))
    r = np.arange(N)
    dist = np.minimum(r, N - r)
    R = int(np.max(dist[size > 1e-15 * size.max()]))
    keep = dist <= R
    return (np.ascontiguousarray(r[keep].astype(np.int64)), np.ascontiguousarray(K[keep])), None


def rayleigh(model: Model, v: np.ndarray) -> float:
    """R of a ring's velocities (d, N): sum over cells of the site and bond functions."""
    S, Bd = model.damping
    vn = np.concatenate([v, np.roll(v, -1, axis=1)])
    return float(0.5 * (np.einsum("an,ab,bn->", v, S, v) + np.einsum("an,ab,bn->", vn, Bd,
                                                                      vn)))


def lattice_force(model: Model, u: np.ndarray) -> np.ndarray:
    """The acceleration of every site, shape (d, N), from the compiled force."""
    u = np.ascontiguousarray(u, dtype=float)
    out = np.empty_like(u)
    compiled_force(model, u.shape[1])(u, out)
    return out


def compiled_force(model: Model, N: int):
    """force(u, out): the compiled acceleration of a ring of N sites into ``out`` (both
    (d, N), C-contiguous), its work buffers made once: for timing the kernel itself."""
    nf, kernel, loop = _kernels(model)[4:7]
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
    energy = _kernels(model)[3]
    return float(energy(np.ascontiguousarray(u, float), np.ascontiguousarray(v, float),
                        np.asarray(model.p, float), np.asarray(model.masses, float),
                        np.empty(2 * model.n_fields)))


#: The largest ring (sites): a run keeps ``records`` spectra of N values each.
MAX_RING = 2**20


def check_ring(N) -> int:
    """A ring size: an integer in [8, MAX_RING] (not a bool)."""
    if isinstance(N, bool) or not isinstance(N, (int, np.integer)) or not 8 <= N <= MAX_RING:
        raise ModelError(f"N must be an integer in [8, {MAX_RING}], got {N!r}")
    return int(N)


def check_count(name: str, value, least: int = 1) -> int:
    """An integer option (records, samples, seed, ...) >= ``least``, not a bool."""
    if isinstance(value, bool) or not isinstance(value, (int, np.integer)) or value < least:
        raise ModelError(f"{name} must be an integer >= {least}, got {value!r}")
    return int(value)


def snap_ring(k: float, N: int) -> tuple[float, int]:
    """(2 pi m / N, m) nearest to k on a ring of N sites; k = pi is allowed (N even)."""
    N = check_ring(N)
    if not (isinstance(k, (int, float, np.floating)) and math.isfinite(k) and 0 < k <= math.pi):
        raise ModelError(f"k must be in (0, pi], got {k!r}")
    m = int(round(k * N / (2 * math.pi)))
    if m == 0:
        raise ModelError(f"k = {k:g} snaps to 0 on a ring of N = {N} (no wave): raise N "
                         f"above {math.ceil(math.pi / k)}")
    return 2 * math.pi * m / N, m


@dataclass(frozen=True)
class ModelRun:
    """A run of a model's ring: what it recorded and the growth it measured.

    Attributes
    ----------
    k, amplitude, N, t_end, dt, method, start, noise, seed
        The run's inputs (k snapped to the ring).
    wave : TravellingWave
        The exact wave the deviation is measured from.
    t : ndarray
        Record times.
    spectrum : ndarray, shape (records, N)
        |FFT of the deviation| per ring mode j, summed over fields in quadrature.
    deviation : ndarray
        rms deviation from the exact wave over sites and fields, per record.
    energy : ndarray
        Total energy per record (from the model file).
    """

    model: Model
    k: float
    amplitude: float
    N: int
    t_end: float
    dt: float
    method: str
    start: str
    noise: float
    seed: int
    wave: object
    t: np.ndarray
    spectrum: np.ndarray
    deviation: np.ndarray
    energy: np.ndarray
    #: 2 R (the power the losses take) per record; None for a lossless model
    dissipation: np.ndarray | None = None
    #: whether the run stopped where its amplification had peaked (``until_peak``)
    peaked: bool | None = None
    #: (u, v) at the run's end, each (d, N)
    state: tuple | None = None

    def energy_balance(self) -> float:
        """max over the records of |E(t) - E(0) + int_0^t 2 R dt'| / E(0) (trapezoids over
        the records): the error of dE/dt = -2 R (0 for a lossless model)."""
        if self.dissipation is None:
            return self.energy_drift
        lost = np.concatenate([[0.0], np.cumsum(np.diff(self.t) * (
            self.dissipation[1:] + self.dissipation[:-1]) / 2)])
        return float(np.max(np.abs(self.energy - self.energy[0] + lost)) / abs(
            self.energy[0]))

    def amplification(self) -> Amplification:
        """The sidebands' amplification (issue 42): A(t), the largest |mode| over the ring
        modes that are not harmonics of the carrier; max A(t) / A(0) and when."""
        return measure_amplification(self)

    @property
    def energy_drift(self) -> float:
        """max |E(t) - E(0)| / |E(0) - E_rest| over the run (E_rest = 0 at rest)."""
        return float(np.max(np.abs(self.energy - self.energy[0])) / abs(self.energy[0]))

    def to_xarray(self):
        """The records as an ``xarray.Dataset`` over ``t``: ``deviation`` (rms from the
        exact wave), ``energy`` and ``spectrum`` (over ring mode j); inputs in attrs."""
        import xarray as xr

        attrs = {"model": self.model.name, "k": self.k, "amplitude": self.amplitude,
                 "N": self.N, "t_end": self.t_end, "dt": self.dt, "method": self.method,
                 "start": self.start, "noise": self.noise, "seed": self.seed,
                 "omega": self.wave.omega}
        attrs.update({f"param_{n}": v for n, v in self.model.params.items()})
        j = np.arange(self.N)
        return xr.Dataset(
            {"deviation": ("t", self.deviation, {"long_name": "rms deviation from the exact "
                                                               "travelling wave"}),
             "energy": ("t", self.energy, {"long_name": "total energy (model file)"}),
             "spectrum": (("t", "mode"), self.spectrum,
                          {"long_name": "|FFT of the deviation| / N, fields in quadrature"})},
            coords={"t": ("t", self.t, {"units": "time (lattice units)"}),
                    "mode": ("mode", j, {"long_name": "ring mode j: wavenumber 2 pi j / N"})},
            attrs=attrs)

    def growth(self) -> Growth:
        """What the run shows: unstable with a rate, or no growth within T."""
        return measure_growth(self)


@dataclass(frozen=True)
class Growth:
    """The growth a run measured.

    Attributes
    ----------
    verdict : 'unstable' or 'no growth within T'
    rate : float
        The fastest mode's rate (1/time) where unstable, else nan.
    wavenumber : float
        That mode's ring wavenumber (rad/site) in (-pi, pi], else nan.
    factor : float
        The sidebands' growth: their largest rms in the linear stage over their start.
    detectable : float
        The slowest rate that would have grown GROWTH_FACTOR within the run's linear stage.
    t_linear : float
        Where the linear stage ended (the deviation reached SATURATION, or T).
    """

    verdict: str
    rate: float
    wavenumber: float
    factor: float
    detectable: float
    t_linear: float

    @property
    def label(self) -> str:
        if self.verdict == "unstable":
            return f"unstable (measured rate {self.rate:.4g})"
        return (f"no growth within T (a rate below {self.detectable:.2g} cannot show by "
                f"t = {self.t_linear:.4g})")


@dataclass(frozen=True)
class Amplification:
    """A run's amplification: ``amplification`` = max_t A(t) / A(0), at
    ``amplification_time``; ``observable`` = amplification >= GROWTH_FACTOR; ``peaked``:
    A(t) fell to half its maximum before the run's end (else the run's cap ended it)."""

    amplification: float
    amplification_time: float
    observable: bool
    peaked: bool
    A: np.ndarray

    def row(self) -> dict:
        return {"amplification": self.amplification,
                "amplification_time": self.amplification_time,
                "observable": self.observable, "peaked": self.peaked}


def _sideband_modes(N: int, m: int, H: int) -> np.ndarray:
    """Ring modes that are not harmonics of the carrier mode m: h m mod N, |h| <= H (the
    exact wave's harmonics), and the mean (h = 0)."""
    harm = {(h * m) % N for h in range(-H, H + 1)}
    return np.array([j not in harm for j in range(N)])


def sideband_amplitude(spectrum: np.ndarray, N: int, k: float, H: int) -> np.ndarray:
    """A(t): the largest |FFT| / N over the ring modes that are not carrier harmonics
    (up to the H-th)."""
    m = int(round(k * N / (2 * math.pi)))
    return np.max(np.asarray(spectrum)[..., _sideband_modes(N, m, H)], axis=-1)


def measure_amplification(run: ModelRun) -> Amplification:
    A = sideband_amplitude(run.spectrum, run.N, run.k, run.wave.harmonics)
    i = int(np.argmax(A))
    amp = float(A[i] / max(A[0], 1e-300))
    peaked = bool(np.any(A[i:] <= A[i] / 2)) if run.peaked is None else bool(run.peaked)
    return Amplification(amp, float(run.t[i]), amp >= GROWTH_FACTOR, peaked, A)


def measure_growth(run: ModelRun) -> Growth:
    N = run.N
    m = int(round(run.k * N / (2 * math.pi)))
    # the carrier's harmonics whose phase drift could show: the wave's phase error phi
    # (integrator, noise) makes harmonic h deviate by ~ h phi |c_h| (secular); phi is read
    # off the carrier's own mode. A harmonic whose drift stays below a tenth of the noise is
    # kept: on a small ring a high harmonic aliases onto a sideband (h k = k + q mod 2 pi;
    # measured: FPUT on 64 sites, the 5th harmonic on the fastest sideband)
    H = run.wave.harmonics
    size = np.max(np.abs(run.wave.coefficients), axis=0)[H:]  # |c_h|, h = 0..H
    others = np.array([j not in (0, m % N, (-m) % N) for j in range(N)])
    floor = float(np.median(run.spectrum[0, others]))
    phase = float(np.max(run.spectrum[:, m % N])) / max(size[1], 1e-300)
    harmonics = {0, m % N, (-m) % N} | {
        (s * h * m) % N for h in range(2, H + 1) for s in (1, -1)
        if h * phase * size[h] > 0.1 * floor}
    keep = np.array([j not in harmonics and 0 < j <= N // 2 for j in range(N)])
    # the sidebands' rms (the carrier's harmonics left out: a linear start slips in phase)
    sidebands = np.sqrt(2 * np.sum(run.spectrum[:, keep] ** 2, axis=1))
    sat = np.nonzero(sidebands > SATURATION * run.amplitude)[0]
    end = int(sat[0]) if sat.size else len(run.t) - 1
    end = max(end, 1)
    S = run.spectrum[:end + 1, keep]
    start = np.maximum(np.median(run.spectrum[:3, keep], axis=0), 1e-300)
    factor = np.max(S, axis=0) / start
    # the verdict reads the sidebands' rms: one mode's share of the noise can swing
    # between its stable eigenmodes (measured: 20x on stable FPUT and flexmm rings), their
    # sum cannot
    total = float(np.max(sidebands[:end + 1]) / max(np.median(sidebands[:3]), 1e-300))
    t_lin = float(run.t[end])
    # ... and an exponential one: the log-slope over the linear stage's second half, run
    # over the whole stage, bounds the factor. Algebraic growth near the carrier (the
    # near-degenerate Bogoliubov pairs of a stable wave exchange amplitude, measured 5x on
    # flexmm-rotation at k = 1, a = 0.1) has a slope of at most ln 2 / (T / 2) there: 4x
    half = run.t[:end + 1] >= t_lin / 2
    if half.sum() >= 3:
        slope = np.polyfit(run.t[:end + 1][half], np.log(np.maximum(
            sidebands[:end + 1][half], 1e-300)), 1)[0]
        total = min(total, float(math.exp(min(max(slope, 0.0) * t_lin, 700.0))))
    detectable = math.log(GROWTH_FACTOR) / t_lin if t_lin > 0 else math.inf
    if not factor.size or total < GROWTH_FACTOR:
        return Growth("no growth within T", math.nan, math.nan, total, detectable, t_lin)
    # the largest mode at the end of the linear stage is the fastest: products of growing
    # modes (rates 2 sigma, 3 sigma) rise late from below it, so their slopes are not read
    i = int(np.argmax(S[-1]))
    y = np.log(np.maximum(S[:, i], 1e-300))
    above = np.nonzero(y > math.log(10 * start[i]))[0]
    first = int(above[0]) if above.size else 0
    if S.shape[0] - first < 4:
        first = max(0, S.shape[0] - 4)
    rate = float(np.polyfit(run.t[first:end + 1], y[first:], 1)[0])
    j = np.nonzero(keep)[0][i]
    kap = 2 * math.pi * j / N
    return Growth("unstable", rate, float((kap + math.pi) % (2 * math.pi) - math.pi),
                  total, detectable, t_lin)


def simulate_model(model: Model, k: float, amplitude: float, *, branch=None, N: int = 256,
                   t_end: float | None = None, dt: float | None = None,
                   method: str = "srkn11b", start: str = "exact", noise: float = NOISE,
                   seed: int = 0, records: int = 400, expected_gain: float | None = None,
                   wave=None, until_peak: bool = False,
                   noise_on: str = "all", initial=None, on_steps=None) -> ModelRun:
    """Run the ring of ``model`` from a plane wave at ``k`` (snapped to the ring) with
    first harmonic ``amplitude`` in its carrier field, plus seeded noise.

    ``t_end`` None: ``numerics.lattice.run_length`` of ``expected_gain`` (default: the
    exact theory's on this ring), as for the paper's chain: 9 e-foldings within
    [1 000, 100 000], 5 000 where nothing is predicted to grow. ``dt`` None: a fifth of
    the method's stability limit over the highest frequency of the lattice.

    A model with [dissipation] runs with its damping force -M^-1 dR/dv: ``rk4`` takes it
    in every stage; an SRKN method is wrapped in a Strang splitting (the damping flow's
    exact half steps around each symplectic step: order 2). ``until_peak``: stop once
    the sidebands' amplitude A(t) (``sideband_amplitude``) has risen 2x and fallen to half
    its maximum (else ``t_end`` is the cap). ``noise_on="carrier"``: the noise on the
    carrier field's positions only (the amplification's launch, issue 42). ``initial``:
    (u, v), each shape (d, N), the state to start from instead of ``start`` (noise added).
    ``on_steps(n, nsteps)``: called after every stretch of ``n`` of the run's ``nsteps``
    steps (a progress bar).
    """
    from numerics.lattice import get_method, run_length

    from ._exact import ring_offsets, travelling_wave
    from ._linear import branches

    meth = get_method(method)
    if meth.kind not in ("srkn", "rk4"):
        raise ModelError(f"method {method!r} is not a fixed-step method; choose one of "
                         "srkn11b, srkn6b, kahanli8, verlet, rk4")
    if start not in STARTS:
        raise ModelError(f"start must be one of {', '.join(STARTS)}, got {start!r}")
    if isinstance(noise, bool) or not (isinstance(noise, (int, float)) and math.isfinite(
            noise) and noise >= 0):
        raise ModelError(f"noise must be a finite number >= 0, got {noise!r}")
    records = check_count("records", records)
    seed = check_count("seed", seed, least=0)
    k_ring, _ = snap_ring(k, N)
    if wave is None:
        wave = travelling_wave(model, k_ring, amplitude, branch)
    if t_end is None:
        if expected_gain is None:
            from ._exact import hill_spectrum
            expected_gain = hill_spectrum(wave, ring_offsets(N)).peak_gain
        t_end = run_length(expected_gain).t_end
    if not (math.isfinite(t_end) and t_end > 0):
        raise ModelError(f"t_end must be a finite time > 0, got {t_end!r}")
    wmax = float(np.nanmax(branches(model, np.linspace(0, math.pi, 129)))) * 1.1 + wave.omega
    if dt is None:
        dt = 0.2 * meth.stability_limit() / wmax
    if not (math.isfinite(dt) and dt > 0):
        raise ModelError(f"dt must be a finite step > 0, got {dt!r}")
    nsteps = max(1, int(math.ceil(t_end / dt)))
    dt = t_end / nsteps
    every = max(1, nsteps // records)
    d = model.n_fields
    rng = np.random.default_rng(seed)
    u, v = wave.state(N)
    if start == "linear":
        xi = k_ring * np.arange(N)
        e = wave.carrier.e[:, None]
        w0 = wave.carrier.omega
        u = amplitude * np.real(e * np.exp(1j * xi))
        v = amplitude * w0 * np.real(-1j * e * np.exp(1j * xi))
    if initial is not None:
        u, v = (np.array(x, dtype=float).reshape(d, N) for x in initial)
    if noise_on not in ("all", "carrier"):
        raise ModelError(f"noise_on must be 'all' or 'carrier', got {noise_on!r}")
    if noise_on == "carrier":
        kick = np.zeros((d, N))
        kick[wave.carrier.field] = rng.standard_normal(N)
        u = np.ascontiguousarray(u + noise * amplitude * kick)
        v = np.ascontiguousarray(v)
    else:
        u = np.ascontiguousarray(u + noise * amplitude * rng.standard_normal((d, N)))
        v = np.ascontiguousarray(v + noise * amplitude * wave.omega * rng.standard_normal(
            (d, N)))
    accel, srkn, rk4, energy = _kernels(model)[:4]
    p = np.asarray(model.p, float)
    masses = np.asarray(model.masses, float)
    minv = 1 / masses
    acc, x, g = np.empty_like(u), np.empty(2 * d), np.empty(2 * d)
    A = np.asarray(meth.a, float)
    B = np.asarray(meth.b, float)
    ts, spec, dev, en, diss = [], [], [], [], []
    lossy = model.lossy
    if lossy:
        damp, rk4_damped, split_local, split_band = _damped_kernels(model)
        S_d, B_d = model.damping
        S_d, B_d = np.ascontiguousarray(S_d), np.ascontiguousarray(B_d)
        if meth.kind == "srkn":
            E_modes, E_local = damping_flow(model, N, dt / 2)

    def advance(n):
        if not lossy:
            return (srkn(u, v, p, minv, A, B, dt, n, acc, x, g) if meth.kind == "srkn"
                    else rk4(u, v, p, minv, dt, n, acc, x, g))
        if meth.kind == "rk4":
            return rk4_damped(u, v, p, minv, S_d, B_d, dt, n, acc, x, g)
        if E_local is not None:
            return split_local(u, v, p, minv, A, B, dt, n, acc, x, g, E_local)
        # bond damping: the exact flow as a short circulant convolution (compiled)
        return split_band(u, v, p, minv, A, B, dt, n, acc, x, g, *E_modes)

    def record(t):
        U = wave.profile(k_ring * np.arange(N) - wave.omega * t)
        delta = u - U
        ts.append(t)
        spec.append(np.sqrt(np.sum(np.abs(np.fft.fft(delta, axis=1)) ** 2, axis=0)) / N)
        dev.append(float(np.sqrt(np.mean(delta**2))))
        en.append(energy(u, v, p, masses, x))
        if lossy:
            diss.append(2 * rayleigh(model, v))

    record(0.0)
    done = 0
    peaked = None
    if until_peak:
        modes = _sideband_modes(N, int(round(k_ring * N / (2 * math.pi))), wave.harmonics)
        a0 = float(np.max(spec[0][modes]))
        top = a0
        peaked = False
    while done < nsteps:
        n = min(every, nsteps - done)
        ok = advance(n)
        done += n
        if not ok or not np.all(np.isfinite(u)):
            raise FloatingPointError(
                f"model {model.describe()}: the run blew up by t = {done * dt:.4g} "
                f"(dt = {dt:.3g}, method {method}): the wave left the lattice's range; "
                "lower the amplitude or dt")
        record(done * dt)
        if on_steps is not None:
            on_steps(n, nsteps)
        if until_peak:
            a = float(np.max(spec[-1][modes]))
            top = max(top, a)
            if top >= 2 * a0 and a <= top / 2:
                peaked = True
                break
    return ModelRun(model=model, k=k_ring, amplitude=float(amplitude), N=N,
                    t_end=float(ts[-1]) if until_peak else float(t_end),
                    dt=dt, method=method, start=start, noise=float(noise), seed=int(seed),
                    wave=wave, t=np.array(ts), spectrum=np.array(spec),
                    deviation=np.array(dev), energy=np.array(en),
                    dissipation=np.array(diss) if lossy else None, peaked=peaked,
                    state=(u.copy(), v.copy()))


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


def simulate_seeds(model: Model, k: float, amplitude: float, spec, *, branch=None,
                   N: int = 256, seeds: int = 1, t_end: float | None = None,
                   start: str = "exact", **run) -> SeededRuns:
    """``seeds`` runs of the ring from ``spec``'s exact wave (``exact_gain`` on this ring)
    and their verdict: one rule for a point and a map cell. T is ``run_length`` of the
    exact rate unless ``t_end`` is given. ``run``: more keywords of ``simulate_model``
    (``noise_on``, ``until_peak``: a lossy point's launch, issue 42)."""
    from numerics.lattice import run_length, simulated_verdict

    if isinstance(seeds, bool) or not isinstance(seeds, (int, np.integer)) or seeds < 1:
        raise ModelError(f"seeds must be an integer >= 1, got {seeds!r}")
    length = run_length(spec.peak_gain) if t_end is None else None
    T = float(t_end) if t_end is not None else length.t_end
    runs = [simulate_model(model, k, amplitude, branch=branch, N=N, t_end=T, start=start,
                           seed=s, wave=spec.wave, **run) for s in range(int(seeds))]
    growth = [r.growth() for r in runs]
    rates = [g.rate for g in growth if g.verdict == "unstable"]
    rate = float(np.median(rates)) if rates else math.nan
    return SeededRuns(simulated_verdict([g.factor for g in growth], T, rate), rate, runs, T,
                      length)
