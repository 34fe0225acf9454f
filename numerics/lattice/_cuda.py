"""Many map cells at once on a GPU (numba's CUDA target): one CUDA block per chain.

Each block advances one chain (one cell and seed) of eq. `norm` with a symplectic RKN method
(BAB, the coefficients of ``_integrators``: srkn11b at the map's step, as on the CPU) and
reduces its records on the chip to what a map cell keeps (``numerics.maps._cells``): the
largest non-carrier component of the theta (and U) spectrum over the carrier at each of the
RECORDS records (kept per record in global memory, ``tops``: 2 x 201 numbers a chain, sent
back with the row for the host's exponential reading), its running maximum, where it sits,
and the early stop once the factor and the exponential bound of the records so far passed
the threshold (``_bound.bound_of_records``, the CPU's function compiled for the device,
probe 96). Nothing per step leaves the GPU; one small row and series per chain come back.

The same site force as the CPU: ``_kernels._acc`` and ``_kernels._sincosvers`` (the
branch-free polynomial sin, cos and 1 - cos), compiled for the device from the same Python
source. Only the contraction of a*b + c into fused multiply-adds may differ between the
two compilers (and the CUDA simulator has none): the states agree to round-off.

Layout of a block (``threads`` threads, site i owned by thread i mod threads):

- shared memory (dynamic): theta, sin, cos, 1 - cos and U of the chain (5 N float64; a
  neighbour's values are read across threads), and the reduction's scratch (4 threads);
- registers/local memory: the velocities and accelerations of the thread's own sites
  (at most PER_THREAD of them);
- global memory: the initial state (read once), the DFT's twiddle table (read-only),
  the output row and, when asked, the theta spectrum of every record (for the measured
  peak gain).

The spectrum of a record is a direct DFT over the shared fields (O(N^2) per record, the
threads taking one bin each in turn): N = 500 is no power of two, and 200 records cost
little beside the steps. A position that leaves |theta| <= TRIG_LIMIT (or is not finite)
stops the chain with status BAD: the host runs that cell again on the CPU, whose libm
loops go on there (or report the blow-up), so a GPU map never differs from a CPU one by
a different treatment of such a cell.
"""

from __future__ import annotations

import math

import numpy as np
from numba import cuda, float64

from ._analysis import STAGE_END
from ._bound import bound_of_records
from ._kernels import TRIG_LIMIT, _acc, _sincosvers

#: sites a thread owns at most (its velocities and accelerations live in local arrays)
PER_THREAD = 8
#: threads per block on a GPU (a power of two: the reductions halve it)
THREADS = 128
#: the fewest threads a block gets on a GPU (one warp)
WARP = 32
#: the chains a launch holds from which each chain gets the fewest threads that hold it
#: (``threads_for``; bench.gpu_occupancy)
FILL_CHAINS = 512
#: the longest chain: PER_THREAD * THREADS sites; 5 N float64 in shared memory (40 KiB at
#: N = 1024, under the 48 KiB a block gets without opting in)
MAX_SITES = PER_THREAD * THREADS

# the output row of a chain (``out[chain, :]``)
OUT_RECORDS = 0   # records taken (1 + the last record's index)
OUT_TH0 = 1       # theta: top ratio at record 0 (the reference)
OUT_THMAX = 2     # theta: largest top ratio over the records (first record that has it)
OUT_THQ = 3       # theta: its bin
OUT_U0 = 4        # U: top ratio at record i0_U (the reference)
OUT_UMAX = 5      # U: largest top ratio over records >= i0_U
OUT_UQ = 6        # U: its bin
OUT_STATUS = 7    # STATUS_OK, or STATUS_BAD: a position left the polynomial's range
OUT_WIDTH = 8
STATUS_OK, STATUS_BAD = 0.0, 1.0

# shared scalars after the fields and the reduction scratch
_CARRIER, _STOP, _BAD = 0, 1, 2
_SCALARS = 3

# the CPU kernels' force, compiled for the device from the same source
_sincosvers_d = cuda.jit(device=True)(_sincosvers.py_func)
_acc_d = cuda.jit(device=True)(_acc.py_func)
# the exponential reading of the records, the host's function (plain Python) for the device
_bound_d = cuda.jit(device=True)(bound_of_records)


def shared_bytes(N: int, threads: int) -> int:
    """Dynamic shared memory of one block: the 5 fields, 4 reduction lanes, the scalars."""
    return 8 * (5 * N + 4 * threads + _SCALARS)


@cuda.jit(device=True)
def _neighbours(i, n):
    return (i - 1 if i > 0 else n - 1), (i + 1 if i < n - 1 else 0)


@cuda.jit(device=True)
def _forces(th, U, s, c, v, ath, aU, coupled, a2, Ks, Kt, t, bs, n):
    """Accelerations of the thread's own sites into its local ath, aU."""
    for r in range(PER_THREAD):
        i = t + r * bs
        if i < n:
            im, ip = _neighbours(i, n)
            at, au = _acc_d(i, im, ip, th, U, s, c, v, coupled, a2, Ks, Kt)
            ath[r] = at
            aU[r] = au


@cuda.jit(device=True)
def _better(v_new, i_new, v_old, i_old):
    """np.argmax's order: a larger value, or the same value at a lower bin."""
    return v_new > v_old or (v_new == v_old and i_new >= 0 and (i_old < 0 or i_new < i_old))


@cuda.jit(device=True)
def _record(th, U, red, sh, cos_t, sin_t, mask_th, mask_U, m, coupled, spectra, keep, chain,
            j, t, bs, n):
    """The spectra |DFT| * 2/N of theta (and U) at this record, reduced over the bins of
    the masks: (largest theta, its bin, largest U, its bin) in red[0], red[bs], red[2bs],
    red[3bs]; the carrier's amplitude in sh[_CARRIER]. All threads call it."""
    nq = n // 2 + 1
    scale = 2.0 / n
    best_t, bin_t, best_u, bin_u = -1.0, -1, -1.0, -1
    for q in range(t, nq, bs):
        re = 0.0
        im = 0.0
        re_u = 0.0
        im_u = 0.0
        idx = 0
        for k in range(n):
            re += th[k] * cos_t[idx]
            im -= th[k] * sin_t[idx]
            if coupled:
                re_u += U[k] * cos_t[idx]
                im_u -= U[k] * sin_t[idx]
            idx += q
            if idx >= n:
                idx -= n
        amp = math.hypot(re, im) * scale
        if keep:
            spectra[chain, j, q] = amp
        if q == m:
            sh[_CARRIER] = amp
        if mask_th[q] != 0 and _better(amp, q, best_t, bin_t):
            best_t, bin_t = amp, q
        if coupled:
            amp_u = math.hypot(re_u, im_u) * scale
            if mask_U[q] != 0 and _better(amp_u, q, best_u, bin_u):
                best_u, bin_u = amp_u, q
    red[t] = best_t
    red[bs + t] = bin_t
    red[2 * bs + t] = best_u
    red[3 * bs + t] = bin_u
    cuda.syncthreads()
    half = bs // 2
    while half > 0:
        if t < half:
            o = t + half
            if _better(red[o], red[bs + o], red[t], red[bs + t]):
                red[t] = red[o]
                red[bs + t] = red[bs + o]
            if _better(red[2 * bs + o], red[3 * bs + o], red[2 * bs + t], red[3 * bs + t]):
                red[2 * bs + t] = red[2 * bs + o]
                red[3 * bs + t] = red[3 * bs + o]
        cuda.syncthreads()
        half //= 2


@cuda.jit
def cells_kernel(theta0, w0, U0, V0, params, carrier_bin, mask_th, mask_U, coupled, acoef,
                 bcoef, dt, per_record, records, i0_U, threshold, cos_t, sin_t, out, spectra,
                 keep, tops, t_rec):
    """Advance chain ``blockIdx.x`` (theta0[chain], ...) record by record; see the module.

    params[chain] = (alpha^2, K_s, K_theta); carrier_bin[chain] = m; mask_*[chain] the
    bins that count (``non_carrier_bins``); i0_U the record of U's reference; ``out`` the
    rows OUT_*; ``spectra[chain, j]`` the theta spectrum of record j when ``keep``;
    ``tops[chain, f, j]`` field f's (theta, U) largest component over the carrier at
    record j (thread 0's: the exponential bound's series); ``t_rec[j]`` the record times.
    """
    chain = cuda.blockIdx.x
    t = cuda.threadIdx.x
    bs = cuda.blockDim.x
    n = theta0.shape[1]
    a2 = params[chain, 0]
    Ks = params[chain, 1]
    Kt = params[chain, 2]
    m = carrier_bin[chain]
    mth = mask_th[chain]
    mU = mask_U[chain]
    nst = acoef.size

    sh = cuda.shared.array(0, dtype=float64)
    th = sh[0:n]
    s = sh[n:2 * n]
    c = sh[2 * n:3 * n]
    v = sh[3 * n:4 * n]
    U = sh[4 * n:5 * n]
    red = sh[5 * n:5 * n + 4 * bs]
    scal = sh[5 * n + 4 * bs:5 * n + 4 * bs + _SCALARS]

    w = cuda.local.array(PER_THREAD, float64)
    V = cuda.local.array(PER_THREAD, float64)
    ath = cuda.local.array(PER_THREAD, float64)
    aU = cuda.local.array(PER_THREAD, float64)

    if t == 0:
        scal[_STOP] = 0.0
        scal[_BAD] = 0.0
    bad = 0
    for r in range(PER_THREAD):
        i = t + r * bs
        ath[r] = 0.0
        aU[r] = 0.0
        V[r] = 0.0
        w[r] = 0.0
        if i < n:
            x = theta0[chain, i]
            th[i] = x
            s[i], c[i], v[i] = _sincosvers_d(x)
            bad += 0 if abs(x) <= TRIG_LIMIT else 1
            w[r] = w0[chain, i]
            if coupled:
                U[i] = U0[chain, i]
                V[r] = V0[chain, i]
            else:
                U[i] = 0.0
    if bad:
        scal[_BAD] = 1.0
    cuda.syncthreads()
    _forces(th, U, s, c, v, ath, aU, coupled, a2, Ks, Kt, t, bs, n)  # first same as last

    # thread 0's bookkeeping of the records (cell_records' running parts)
    r_th0 = 0.0
    r_thmax = 0.0
    q_th = -1.0
    r_U0 = 0.0
    r_Umax = 0.0
    q_U = -1.0
    taken = 0
    status = STATUS_OK
    for j in range(records + 1):
        if j > 0:
            for _step in range(per_record):
                for st in range(nst):
                    hb = bcoef[st] * dt
                    if st > 0:
                        _forces(th, U, s, c, v, ath, aU, coupled, a2, Ks, Kt, t, bs, n)
                        cuda.syncthreads()  # every neighbour read before a site moves
                    last = st == nst - 1
                    ha = acoef[st] * dt
                    for r in range(PER_THREAD):
                        i = t + r * bs
                        if i < n:
                            w[r] += hb * ath[r]
                            if coupled:
                                V[r] += hb * aU[r]
                            if not last:
                                x = th[i] + ha * w[r]
                                th[i] = x
                                s[i], c[i], v[i] = _sincosvers_d(x)
                                bad += 0 if abs(x) <= TRIG_LIMIT else 1
                                if coupled:
                                    U[i] = U[i] + ha * V[r]
                    cuda.syncthreads()
            if bad:
                scal[_BAD] = 1.0
            cuda.syncthreads()
        if scal[_BAD] != 0.0:  # every thread reads it between the same two barriers
            if t == 0:
                status = STATUS_BAD
            break
        _record(th, U, red, scal, cos_t, sin_t, mth, mU, m, coupled, spectra, keep, chain,
                j, t, bs, n)
        if t == 0:
            taken = j + 1
            carrier = scal[_CARRIER]
            top_th = red[0] / carrier
            top_U = red[2 * bs] / carrier
            tops[chain, 0, j] = top_th
            tops[chain, 1, j] = top_U
            if j == 0:
                r_th0 = top_th
                r_thmax = top_th
                q_th = red[bs]
            elif top_th > r_thmax:
                r_thmax = top_th
                q_th = red[bs]
            if coupled and j >= i0_U:
                if j == i0_U:
                    r_U0 = top_U
                    r_Umax = top_U
                    q_U = red[3 * bs]
                elif top_U > r_Umax:
                    r_Umax = top_U
                    q_U = red[3 * bs]
            # the early stop of cell_records: the factor so far and its exponential bound
            # (the bound only where the factor passed: the records so far, O(j) once)
            # (one call site: each inlined copy of the bound costs registers)
            for f in range(2):
                lo = 0 if f == 0 else i0_U
                r0 = r_th0 if f == 0 else r_U0
                rmax = r_thmax if f == 0 else r_Umax
                if j > lo and (f == 0 or coupled) and r0 > 0 and rmax > threshold * r0:
                    if _bound_d(t_rec, tops[chain, f], lo, j + 1, STAGE_END) > threshold:
                        scal[_STOP] = 1.0
        cuda.syncthreads()
        if scal[_STOP] != 0.0:
            break
        cuda.syncthreads()  # nobody writes the reduction scratch before all read STOP
    if t == 0:
        row = out[chain]
        row[OUT_RECORDS] = taken
        row[OUT_TH0] = r_th0
        row[OUT_THMAX] = r_thmax
        row[OUT_THQ] = q_th
        row[OUT_U0] = r_U0
        row[OUT_UMAX] = r_Umax
        row[OUT_UQ] = q_U
        row[OUT_STATUS] = status


def twiddles(N: int) -> tuple[np.ndarray, np.ndarray]:
    """cos and sin of 2 pi j / N, j = 0 .. N - 1 (the DFT's table)."""
    j = np.arange(N)
    return np.cos(2 * np.pi * j / N), np.sin(2 * np.pi * j / N)


def threads_for(N: int, simulated: bool = False, chains: int | None = None) -> int:
    """Threads per block for N sites: the fewest powers of two that hold N in PER_THREAD
    sites each, at least a warp on a GPU, where a launch has ``chains`` >= FILL_CHAINS (or
    ``chains`` is not given); THREADS on a GPU for a smaller launch. Under the simulator
    (every thread a Python thread) always the fewest."""
    return fewest_threads(N, PER_THREAD, THREADS, simulated, chains)


def fewest_threads(N: int, per_thread: int, most: int, simulated: bool = False,
                   chains: int | None = None) -> int:
    """The rule of both kernels' ``threads_for`` (measured by ``bench.gpu_occupancy`` on an
    H200, docs/gpu.md 'Threads a chain': a full launch runs 1.23x (paper kernel, 64
    threads) to 1.39x (flexmm's) and 1.86x (fput's, models' kernel, 32 threads) faster at
    the fewest threads a chain than at 128, more chains sharing an SM
    where ~170-255 registers a thread allow few threads an SM; a launch of few chains
    leaves SMs idle, and more threads a chain finish each chain sooner)."""
    bs = 1
    while bs * per_thread < N:
        bs *= 2
    if simulated:
        return bs
    if chains is not None and chains < FILL_CHAINS:
        return max(bs, most)
    return max(bs, WARP)


__all__ = ["cells_kernel", "shared_bytes", "twiddles", "threads_for", "fewest_threads",
           "PER_THREAD", "THREADS", "MAX_SITES", "WARP", "FILL_CHAINS"]
