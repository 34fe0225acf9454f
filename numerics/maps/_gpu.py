"""Map cells on a GPU: :func:`simulate_cells_gpu`, the GPU twin of ``simulate_cell``, and
:func:`gpu_status` (is there a GPU this project can use, and if not, what is missing).

Every (cell, seed) is one chain, one CUDA block of ``numerics.lattice._cuda.cells_kernel``;
all chains advance in one kernel launch (or a few, when the spectra kept for the peak gain
would not fit ``max_spectra_bytes``). The initial states are the CPU's
(``initial_condition``: same seed, same state), uploaded once; one row per chain comes back,
which this module turns into ``simulate_cell``'s fields by ``growth_of``'s rules.

``numba.cuda`` is imported only here and only when called, so that the CUDA simulator
(``NUMBA_ENABLE_CUDASIM=1``, read by numba at that import) can be chosen by the caller,
and importing ``numerics`` costs nothing more.
"""

from __future__ import annotations

import importlib.util
import math
import os

import numpy as np

from ..lattice import (
    GROWTH_THRESHOLD,
    RUN_REL_TOL,
    U_REFERENCE,
    Material,
    check_case,
    cuda_kernels,
    exponential_bound,
    get_method,
    initial_condition,
    non_carrier_bins,
    snap_wavenumber,
)
from ._cells import RECORDS, measured_peak_gain, simulate_cell

#: what a user installs to get the GPU path
INSTALL_HINT = "pip install -e '.[gpu]'"


def simulated() -> bool:
    """True when numba's CUDA simulator is chosen (NUMBA_ENABLE_CUDASIM=1): kernels run as
    Python threads, for tests only."""
    return os.environ.get("NUMBA_ENABLE_CUDASIM", "0") not in ("", "0")


def gpu_status() -> tuple[bool, str]:
    """(available, reason): whether a map can run on a GPU here, in one line.

    Needs both numba's CUDA target from the ``gpu`` extra (``numba-cuda``, with its CUDA
    toolkit wheels) and a CUDA device. The reason names what is missing, or the device
    (its name and compute capability); under the simulator it says so (available, but
    for tests: ``--device auto`` should not choose it, see :func:`simulated`).
    """
    if simulated():
        return True, ("numba's CUDA simulator (NUMBA_ENABLE_CUDASIM=1): kernels run as "
                      "Python threads, for tests only")
    extra = importlib.util.find_spec("numba_cuda") is not None
    try:
        from numba import cuda

        device = bool(cuda.is_available())
    except Exception:  # a broken driver or toolkit reads as no device
        device = False
    missing = []
    if not device:
        missing.append("no GPU: numba.cuda finds no CUDA device")
    if not extra:
        missing.append(f"the gpu extra is not installed: {INSTALL_HINT}")
    if missing:
        return False, "; and ".join(missing)
    dev = cuda.get_current_device()
    name = dev.name.decode() if isinstance(dev.name, bytes) else str(dev.name)
    return True, f"GPU {name} (compute capability {dev.compute_capability[0]}." \
                 f"{dev.compute_capability[1]})"


def gpu_name() -> str:
    """The GPU's name (or "CUDA simulator"), for a store's attributes and the bench."""
    if simulated():
        return "CUDA simulator"
    from numba import cuda

    name = cuda.get_current_device().name
    return name.decode() if isinstance(name, bytes) else str(name)


def record_step(t_end: float, dt: float) -> tuple[int, float]:
    """(steps per record, step used): t_end / (RECORDS n) for a whole n, as cell_records."""
    record = t_end / RECORDS
    per_record = max(1, math.ceil(record / dt - 1e-9))
    return per_record, record / per_record


def _chains(materials, case, ks, N, amplitude, noise, seeds, start):
    """The chains' initial states and parameters: one per (cell, seed), cell-major."""
    if isinstance(materials, Material):
        materials = [materials] * len(ks)
    if len(materials) != len(ks):
        raise ValueError(f"give one material per k (or one for all): {len(materials)} "
                         f"materials, {len(ks)} values of k")
    seeds = list(range(seeds)) if isinstance(seeds, (int, np.integer)) else list(seeds)
    coupled = case == "coupled"
    nq = N // 2 + 1
    cells = []
    th, w, U, V, params, bins, mth, mU = ([] for _ in range(8))
    for mat, k in zip(materials, ks):
        k_s, m = snap_wavenumber(k, N, rel_tol=RUN_REL_TOL, return_index=True)
        for seed in seeds:
            st = initial_condition(mat, case, N, k_s, amplitude, noise, seed, start)
            cells.append((mat, k, k_s, m, seed))
            th.append(st.theta)
            w.append(st.theta_dot)
            U.append(st.U if coupled else np.zeros(N))
            V.append(st.U_dot if coupled else np.zeros(N))
            params.append((mat.alpha**2, mat.K_s, mat.K_theta))
            bins.append(m)
            mth.append(non_carrier_bins(m, N, "theta"))
            mU.append(non_carrier_bins(m, N, "U") if coupled else np.zeros(nq, bool))
    arrays = {"theta0": np.array(th), "w0": np.array(w), "U0": np.array(U),
              "V0": np.array(V), "params": np.array(params, float),
              "carrier_bin": np.array(bins, np.int64),
              "mask_th": np.array(mth, np.int8), "mask_U": np.array(mU, np.int8)}
    return cells, arrays


def _row_to_cell(row, tops, N, t_end, i0_U, coupled):
    """simulate_cell's growth fields from a chain's output row and its per-record top
    ratios ``tops`` (2, RECORDS + 1: theta, U) (growth_of's rules)."""
    K = cuda_kernels()

    n = int(row[K.OUT_RECORDS])
    t = np.arange(RECORDS + 1) * (t_end / RECORDS)
    growth, field, q, expo = 0.0, "theta", float("nan"), 0.0
    r0 = row[K.OUT_TH0]
    g = row[K.OUT_THMAX] / r0 if r0 > 0 else 0.0
    if g > growth:
        growth, q = g, 2 * np.pi * row[K.OUT_THQ] / N
    # the exponential reading: each field's factor at most its bound (the CPU's
    # exponential_bound of the series the chip kept), the larger field's
    expo = max(expo, min(g, exponential_bound(t[:n], tops[0, :n])))
    # U's reference: the record at U_REFERENCE t_end, when the run got past it
    if coupled and min(i0_U, n) < n - 1:
        r0 = row[K.OUT_U0]
        g = row[K.OUT_UMAX] / r0 if r0 > 0 else 0.0
        if g > growth:
            growth, field, q = g, "U", 2 * np.pi * row[K.OUT_UQ] / N
        expo = max(expo, min(g, exponential_bound(t[i0_U:n], tops[1, i0_U:n])))
    t_sim = float(t[n - 1])
    return {"verdict_simulated": bool(expo > GROWTH_THRESHOLD), "growth": float(growth),
            "growth_exponential": float(expo),
            "growth_field": field, "growth_q": float(q), "t_simulated": t_sim,
            "stopped_early": bool(t_sim < t_end * (1 - 1e-9))}, t[:n]


def simulate_cells_gpu(materials, case: str, ks, N: int, t_end: float,
                       amplitude: float = 0.02, noise: float = 1e-3, seeds=1,
                       start: str = "paper", method: str = "srkn11b",
                       dt: float | None = None, *, peak_gain: bool = True,
                       threads: int | None = None,
                       max_spectra_bytes: int = 2 << 30) -> list[dict]:
    """Simulate many map cells at once on the GPU: ``simulate_cell``'s answer for each.

    Parameters
    ----------
    materials : Material, or a sequence of them (one per k)
    case : {"rotation", "coupled"}
    ks : sequence of float
        The cells' carriers (each snapped to 2 pi m / N, as ``simulate_cell``).
    N, t_end, amplitude, noise, start : as ``simulate_cell``
    seeds : int or sequence of int
        The noise seeds of every cell: 0 .. seeds - 1 (a map's ``seeds``), or these.
    method, dt : str, float
        A symplectic RKN method (``Method.kind == "srkn"``: srkn11b, srkn6b, kahanli8,
        verlet) and its step, one for all cells (a map's ``cell_step``); the step used is
        t_end / (RECORDS n), as on the CPU.
    peak_gain : bool
        Keep the theta spectrum of every record on the GPU to measure the linear stage's
        peak gain of the MI cells (``measured_peak_gain``, on the host); False leaves it
        NaN and keeps nothing but one row per chain.
    threads : int, optional
        Threads per block (a power of two; default ``_cuda.threads_for``).
    max_spectra_bytes : int
        The kept spectra's memory per launch: more chains than fit go in several launches.

    Returns
    -------
    list of dict, one per (cell, seed), cell-major (cell 0 seed 0, cell 0 seed 1, ...):
    ``simulate_cell``'s fields (verdict_simulated, growth, growth_exponential,
    growth_field, growth_q,
    peak_gain, t_simulated, stopped_early, k, method, dt) and ``seed`` and ``device``
    ("gpu", or "cpu" for a chain whose theta left the polynomial's range, run again by
    ``simulate_cell``: the libm loops continue it there, or it reports the blow-up).
    """
    from numba import cuda

    K = cuda_kernels()

    check_case(case)
    meth = get_method(method)
    if meth.kind != "srkn":
        raise ValueError(f"the GPU runs the symplectic RKN methods (srkn11b, srkn6b, "
                         f"kahanli8, verlet), not {method!r}")
    if dt is None:
        raise ValueError("give dt (a map's cell_step; simulate_cell chooses one per cell)")
    if not 3 <= N <= K.MAX_SITES:
        raise ValueError(f"N = {N}: the GPU holds chains of 3 to {K.MAX_SITES} sites on chip")
    if threads is not None and (threads & (threads - 1) or threads * K.PER_THREAD < N):
        raise ValueError(f"threads = {threads}: a power of two with threads * "
                         f"{K.PER_THREAD} >= N")
    coupled = case == "coupled"
    per_record, dt_eff = record_step(t_end, dt)
    t_grid = np.arange(RECORDS + 1) * (t_end / RECORDS)
    i0_U = int(np.searchsorted(t_grid, U_REFERENCE * t_end)) if coupled else RECORDS + 1
    cells, host = _chains(materials, case, ks, N, amplitude, noise, seeds, start)
    nq = N // 2 + 1
    per_chain = (RECORDS + 1) * nq * 8
    batch = max(1, max_spectra_bytes // per_chain) if peak_gain else len(cells)
    bs = threads or K.threads_for(N, simulated(), min(batch, len(cells)))
    cos_t, sin_t = (cuda.to_device(a) for a in K.twiddles(N))
    t_rec = cuda.to_device(t_grid)
    acoef, bcoef = cuda.to_device(np.array(meth.a)), cuda.to_device(np.array(meth.b))
    rows, spectra, series = [], [], []
    for b0 in range(0, len(cells), batch):
        part = {name: cuda.to_device(np.ascontiguousarray(a[b0:b0 + batch]))
                for name, a in host.items()}
        nb = part["theta0"].shape[0]
        out = cuda.device_array((nb, K.OUT_WIDTH))
        spec = cuda.device_array((nb, RECORDS + 1, nq) if peak_gain else (1, 1, 1))
        tops = cuda.device_array((nb, 2, RECORDS + 1))  # 3.2 kB a chain
        K.cells_kernel[nb, bs, 0, K.shared_bytes(N, bs)](
            part["theta0"], part["w0"], part["U0"], part["V0"], part["params"],
            part["carrier_bin"], part["mask_th"], part["mask_U"], coupled, acoef, bcoef,
            dt_eff, per_record, RECORDS, i0_U, GROWTH_THRESHOLD, cos_t, sin_t, out, spec,
            peak_gain, tops, t_rec)
        rows.append(out.copy_to_host())
        series.append(tops.copy_to_host())
        if peak_gain:
            spectra.append(spec.copy_to_host())
    rows = np.concatenate(rows)
    series = np.concatenate(series)
    spectra = np.concatenate(spectra) if peak_gain else None
    results = []
    for c, ((mat, k, k_s, m, seed), row) in enumerate(zip(cells, rows)):
        if row[K.OUT_STATUS] != K.STATUS_OK:
            res = simulate_cell(mat, case, k, N, t_end, amplitude, noise, seed, start,
                                dt, method)
            results.append({**res, "seed": seed, "device": "cpu"})
            continue
        res, t = _row_to_cell(row, series[c], N, t_end, i0_U, coupled)
        res["peak_gain"] = (measured_peak_gain(t, spectra[c, :len(t)], m, N)
                            if peak_gain and res["verdict_simulated"] else float("nan"))
        results.append({**res, "k": k_s, "method": meth.name, "dt": dt_eff, "seed": seed,
                        "device": "gpu"})
    return results


def aggregate_seeds(runs: list) -> dict:
    """A map cell's simulated columns from its seeds' runs: ``simulated_row``'s rule, the
    one ``simulate_block`` applies (the seed-majority verdict, the median growth, field
    and q of the seed that grew most, the longest time simulated, the median measured
    peak gain), without the prediction's ratio."""
    from ._blocks import simulated_row

    row = simulated_row(runs, None)
    del row["growth_log_ratio"]
    return row


def simulate_map_cells_gpu(params, cells, peak_gain: bool = True) -> dict:
    """The simulated columns of a map's cells, all in one launch (or a few, see
    ``max_spectra_bytes``): {(i, j): ``aggregate_seeds`` row} for the (i, j) in ``cells``
    (``params`` a MapParameters; its ``cell_step``, seeds 0 .. seeds - 1). The runs of every
    seed are under ``(i, j, "runs")``, for the caller's growth_log_ratio (first seed)."""
    method, dt = params.cell_step
    cells = list(cells)
    runs = simulate_cells_gpu([params.material_at(i) for i, _ in cells], params.case,
                              [params.k_simulated[j] for _, j in cells], params.N,
                              params.t_end, params.amplitude, params.noise, params.seeds,
                              params.start, method, dt, peak_gain=peak_gain)
    out = {}
    for n, (i, j) in enumerate(cells):
        mine = runs[n * params.seeds:(n + 1) * params.seeds]
        out[(i, j)] = aggregate_seeds(mine)
        out[(i, j, "runs")] = mine
    return out


__all__ = ["simulate_cells_gpu", "simulate_map_cells_gpu", "aggregate_seeds", "gpu_status",
           "gpu_name", "simulated", "record_step", "INSTALL_HINT"]
