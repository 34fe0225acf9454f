"""Any model's ring on a GPU (numba's CUDA target): its generated site force compiled for
the device, one CUDA block per chain.

The device source (``_cuda_print.device_source``) is printed from the model's generated
module; a model may instead register a hand-written device force (``DEVICE_FORCES``: the
flexmm models have the fused flexMM kernel's).

The kernel (:func:`model_kernel`) advances chain ``blockIdx.x`` with a symplectic RKN method
(the CPU's loop of ``numerics.models.simulate_model``: kick, drift where a != 0, force;
the force evaluation at the end of a step reused at the start of the next) and records,
every ``every`` steps, the spectrum of the deviation from the exact travelling wave: the
wave's profile at the record's time is summed on the chip from its Fourier coefficients,
the deviation kept in shared memory, its DFT taken over the ring (one bin a thread in
turn, the bins 0..N/2 of the real fields) and sqrt(sum over fields |DFT|^2) / N written to
``spectra[chain, record]``: the per-record row the CPU keeps, from which the host measures
the growth with the CPU's ``measure_growth``. Nothing else leaves the chip; the state
never does.

Layout of a block (``threads`` threads, site i owned by thread i mod threads): shared
memory (dynamic) holds the positions (d N), the site functions (n_f N), the deviation
(d N) and a flag; the velocities and accelerations of a thread's own sites are in local
arrays. A chain whose position leaves the polynomial's range (models with sin/cos) or
turns non-finite stops with status BAD: the host runs it again on the CPU.
"""

from __future__ import annotations

import math

import numpy as np
from numba import cuda, float64

from ._cuda import fewest_threads
from ._cuda_print import DeviceSourceError, device_source
from ._kernels import TRIG_LIMIT, _sincosvers

#: sites a thread owns at most (as the flexMM kernel)
PER_THREAD = 8
#: threads per block on a GPU (a power of two)
THREADS = 128
#: shared memory a block gets without opting in (bytes)
SHARED_LIMIT = 48 * 1024
#: statuses of a chain
STATUS_OK, STATUS_BAD = 0.0, 1.0

#: registered device forces: a model's MODEL_HASH (its energy's content hash) ->
#: (name, fields, parameters, builder); builder() -> (site_functions, site_force, n_f) with
#: the generated device functions' signatures. The paper chain's models register the
#: fused flexMM kernel's force (``_cuda``'s ``_acc``, today's GPU kernel's): a model file
#: with the same energy gets it too, any other model its printed force
DEVICE_FORCES: dict = {}


def register_device_force(model_hash: str, name: str, fields: tuple, parameters: tuple,
                          builder) -> None:
    """Register a hand-written device force for the model of ``model_hash`` (its fields
    and parameters in this order, checked at use)."""
    DEVICE_FORCES[model_hash] = (name, tuple(fields), tuple(parameters), builder)


def device_force_of(code, fast: bool = True):
    """(name, n_f): the device force a generated module's kernel uses, "generated" or a
    registered one (``DEVICE_FORCES``; ``fast`` False: always the generated), and the site
    functions it keeps per site (shared memory)."""
    entry = DEVICE_FORCES.get(getattr(code, "MODEL_HASH", None)) if fast else None
    if entry is not None and (tuple(code.FIELDS), tuple(code.PARAMETERS)) == entry[1:3]:
        return entry[0], 3
    return "generated", int(code.SITE_FUNCTIONS_ALL)


def _fused_flexmm(coupled: bool):
    """The fused flexMM kernel's site force (``_cuda``: eq. `norm`, theta's acceleration
    with alpha^2, U's) behind the generated functions' signatures: F holds sin, cos and
    1 - cos of theta (the polynomial), p = (alpha, K_s, K_theta)."""
    from ._cuda import _acc_d, _sincosvers_d

    @cuda.jit(device=True)
    def functions(u, F, p, n, N):
        s, c, v = _sincosvers_d(u[n])
        F[n] = s
        F[N + n] = c
        F[2 * N + n] = v

    @cuda.jit(device=True)
    def force(u, F, p, n, N, acc, r, m, l):
        U = u[N:2 * N] if coupled else u[0:N]  # case I never reads U
        at, aU = _acc_d(n, m, l, u[0:N], U, F[0:N], F[N:2 * N], F[2 * N:3 * N], coupled,
                        p[0] * p[0], p[1], p[2])
        acc[r] = at
        if coupled:
            acc[PER_THREAD + r] = aU

    return functions, force, 3


def _register_builtin() -> None:
    from generated.models import flexmm, flexmm_rotation

    for mod, coupled in ((flexmm, True), (flexmm_rotation, False)):
        register_device_force(mod.MODEL_HASH, f"fused flexMM ({mod.NAME})", mod.FIELDS,
                              mod.PARAMETERS, lambda c=coupled: _fused_flexmm(c))


_register_builtin()

_BUILT: dict = {}


def sign(x):
    """numpy.sign of a float (0 at 0, NaN at NaN): the derivative of an Abs."""
    return 1.0 if x > 0 else -1.0 if x < 0 else x * 0.0


_sign_d = cuda.jit(device=True)(sign)


def model_kernel(code, fast: bool = True):
    """(kernel, trig) for a generated model module: the CUDA kernel of its chains (compiled
    on first launch) and whether a position beyond TRIG_LIMIT stops a chain (its site
    functions' sin/cos are the polynomial). ``fast``: a registered device force where the
    model has one (``device_force_of``). Cached per module hash."""
    force_name, nf = device_force_of(code, fast)
    key = (code.__name__, code.MODEL_HASH, force_name)
    if key in _BUILT:
        return _BUILT[key]
    if force_name != "generated":
        site_functions, f_first, nf = DEVICE_FORCES[code.MODEL_HASH][3]()
        f_last = f_inner = f_first
        trig = True
    else:
        src, trig = device_source(code)
        sincos = cuda.jit(device=True)(_sincosvers.py_func)

        def _psin(x):
            return sincos(x)[0]

        def _pcos(x):
            return sincos(x)[1]

        ns = {"math": math, "PER_THREAD": PER_THREAD, "_psin": cuda.jit(device=True)(_psin),
              "_pcos": cuda.jit(device=True)(_pcos), "_sign": _sign_d}
        exec(compile(src, f"<device force of {code.__name__}>", "exec"), ns)
        site_functions = cuda.jit(device=True)(ns["_site_functions"])
        f_first = cuda.jit(device=True)(ns["_site_force_first"])
        f_last = cuda.jit(device=True)(ns["_site_force_last"])
        f_inner = cuda.jit(device=True)(ns["_site_force_inner"])
    D = len(code.FIELDS)
    NF = max(nf, 1)
    HAS_F = nf > 0
    LOCAL = D * PER_THREAD
    CHECK = bool(trig)
    LIMIT = TRIG_LIMIT

    @cuda.jit(device=True)
    def forces(u, F, p, acc, t, bs, n):
        for r in range(PER_THREAD):
            i = t + r * bs
            if i < n:
                if i == 0:
                    f_first(u, F, p, i, n, acc, r, n - 1, 1)
                elif i == n - 1:
                    f_last(u, F, p, i, n, acc, r, n - 2, 0)
                else:
                    f_inner(u, F, p, i, n, acc, r, i - 1, i + 1)

    @cuda.jit(device=True)
    def functions(u, F, p, t, bs, n):
        """The site functions of the thread's sites; 1 when a position is out of range."""
        bad = 0
        for r in range(PER_THREAD):
            i = t + r * bs
            if i < n:
                for a in range(D):
                    x = u[a * n + i]
                    if CHECK:
                        bad += 0 if abs(x) <= LIMIT else 1
                    elif not math.isfinite(x):
                        bad += 1
                if HAS_F:
                    site_functions(u, F, p, i, n)
        return bad

    @cuda.jit
    def kernel(u0, v0, params, dts, nsteps, every, acoef, bcoef, k, omega, cre, cim,
               cos_t, sin_t, spectra, status):
        """Chain ``blockIdx.x``: u0, v0 (chains, d N) flat; params (chains, P) (the
        generated force divides by the masses itself); dts, nsteps, every per chain;
        k, omega, cre, cim (chains, d, 2H + 1) the exact wave; spectra (chains, records,
        N/2 + 1) out; status (chains, 2) out: (STATUS_*, records taken)."""
        chain = cuda.blockIdx.x
        t = cuda.threadIdx.x
        bs = cuda.blockDim.x
        n = u0.shape[1] // D
        p = params[chain]
        dt = dts[chain]
        ns = nsteps[chain]
        ev = every[chain]
        kk = k[chain]
        om = omega[chain]
        nh = cre.shape[2]
        H = (nh - 1) // 2
        nq = n // 2 + 1
        nst = acoef.size

        sh = cuda.shared.array(0, dtype=float64)
        u = sh[0:D * n]
        F = sh[D * n:(D + NF) * n]
        dev = sh[(D + NF) * n:(2 * D + NF) * n]
        flag = sh[(2 * D + NF) * n:(2 * D + NF) * n + 1]

        w = cuda.local.array(LOCAL, float64)
        acc = cuda.local.array(LOCAL, float64)
        prof = cuda.local.array(D, float64)
        for r in range(PER_THREAD):
            i = t + r * bs
            for a in range(D):
                acc[a * PER_THREAD + r] = 0.0
                w[a * PER_THREAD + r] = 0.0
                if i < n:
                    u[a * n + i] = u0[chain, a * n + i]
                    w[a * PER_THREAD + r] = v0[chain, a * n + i]
        if t == 0:
            flag[0] = 0.0
        cuda.syncthreads()
        bad = functions(u, F, p, t, bs, n)
        cuda.syncthreads()
        forces(u, F, p, acc, t, bs, n)
        done = 0
        rec = 0
        while True:
            # the record at step ``done``: the deviation from the wave at t = done dt
            if bad:
                flag[0] = 1.0
            cuda.syncthreads()
            if flag[0] != 0.0:
                break
            tr = done * dt
            for r in range(PER_THREAD):
                i = t + r * bs
                if i < n:
                    # U_a(xi) = Re sum_h c[a, h] e^{i h xi}: cos(h xi), sin(h xi) by the
                    # angle-addition recurrence (its error grows as h eps, on harmonics
                    # whose size falls as a^h)
                    xi = kk * i - om * tr
                    c1 = math.cos(xi)
                    s1 = math.sin(xi)
                    for a in range(D):
                        prof[a] = cre[chain, a, H]
                    ch = 1.0
                    sh_ = 0.0
                    for h in range(1, H + 1):
                        ch, sh_ = ch * c1 - sh_ * s1, sh_ * c1 + ch * s1
                        for a in range(D):
                            prof[a] += ((cre[chain, a, H + h] + cre[chain, a, H - h]) * ch
                                        - (cim[chain, a, H + h] - cim[chain, a, H - h]) * sh_)
                    for a in range(D):
                        dev[a * n + i] = u[a * n + i] - prof[a]
            cuda.syncthreads()
            for q in range(t, nq, bs):
                tot = 0.0
                for a in range(D):
                    re = 0.0
                    im = 0.0
                    idx = 0
                    for j in range(n):
                        x = dev[a * n + j]
                        re += x * cos_t[idx]
                        im -= x * sin_t[idx]
                        idx += q
                        if idx >= n:
                            idx -= n
                    tot += re * re + im * im
                spectra[chain, rec, q] = math.sqrt(tot) / n
            rec += 1
            if done >= ns:
                break
            chunk = min(ev, ns - done)
            for _step in range(chunk):
                for st in range(nst):
                    hb = bcoef[st] * dt
                    for r in range(PER_THREAD):
                        for a in range(D):
                            w[a * PER_THREAD + r] += hb * acc[a * PER_THREAD + r]
                    if acoef[st] != 0.0:
                        ha = acoef[st] * dt
                        cuda.syncthreads()  # every neighbour's read of u done
                        for r in range(PER_THREAD):
                            i = t + r * bs
                            if i < n:
                                for a in range(D):
                                    u[a * n + i] += ha * w[a * PER_THREAD + r]
                        # a site's functions read its own fields only (no barrier before)
                        bad += functions(u, F, p, t, bs, n)
                        cuda.syncthreads()
                        forces(u, F, p, acc, t, bs, n)
            done += chunk
            cuda.syncthreads()  # the record's deviation array is free again
        if t == 0:
            status[chain, 0] = STATUS_BAD if flag[0] != 0.0 else STATUS_OK
            status[chain, 1] = rec

    _BUILT[key] = (kernel, trig)
    return _BUILT[key]


def shared_bytes(d: int, n_functions: int, N: int) -> int:
    """Dynamic shared memory of one chain: positions, site functions, deviation, a flag."""
    return 8 * ((2 * d + max(n_functions, 1)) * N + 1)


def fits(d: int, n_functions: int, N: int) -> str | None:
    """None where a chain of N sites fits one block, else why not (one line)."""
    need = shared_bytes(d, n_functions, N)
    if N > PER_THREAD * THREADS:
        return (f"N = {N} sites is over the {PER_THREAD * THREADS} a block holds "
                f"({THREADS} threads x {PER_THREAD} sites)")
    if need > SHARED_LIMIT:
        return (f"a chain of {d} fields x {N} sites needs {need} bytes of shared memory, "
                f"over the {SHARED_LIMIT} a block gets")
    return None


def twiddles(N: int) -> tuple[np.ndarray, np.ndarray]:
    """cos and sin of 2 pi j / N, j = 0 .. N - 1 (the DFT's table)."""
    j = np.arange(N)
    return np.cos(2 * np.pi * j / N), np.sin(2 * np.pi * j / N)


def threads_for(N: int, simulated: bool = False, chains: int | None = None) -> int:
    """Threads per block: the paper kernel's rule (``_cuda.fewest_threads``): the fewest
    powers of two that hold N in PER_THREAD sites, at least a warp on a GPU, where a launch
    holds ``chains`` >= FILL_CHAINS; THREADS on a GPU for fewer chains."""
    return fewest_threads(N, PER_THREAD, THREADS, simulated, chains)


__all__ = ["model_kernel", "device_source", "sign", "device_force_of", "register_device_force",
           "DEVICE_FORCES", "shared_bytes", "fits", "twiddles",
           "threads_for", "DeviceSourceError", "PER_THREAD", "THREADS", "SHARED_LIMIT",
           "STATUS_OK", "STATUS_BAD"]
