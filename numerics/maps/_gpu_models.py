"""Any model's map cells on a GPU: :func:`simulate_model_cells_gpu`, the GPU twin of the
simulated columns of ``numerics.models.map_cells``, and :func:`model_rows_gpu`, a batch of a
model map's blocks (theories on the CPU, runs on the GPU) for ``run_map``'s device path.

Every (cell, seed) is one chain, one CUDA block of the model's kernel
(``numerics.lattice.cuda_model_kernels().model_kernel``: the generated site force compiled
for the device). The chains start from the CPU's state (``simulate_model``'s: the exact
travelling wave of ``exact_gain_checked`` on the ring, the seeded noise, the same step and
records) and are all advanced in one launch (or a few, when the records' spectra would not
fit ``max_spectra_bytes``). Each chain sends back one spectrum per record (the deviation
from the exact wave, summed over the fields, reduced on the chip from the state that never
leaves it), from which the CPU's ``measure_growth`` reads the growth: one rule on both
devices.

What the GPU does not run goes to the CPU with one line saying why: a lossy model (the
damped steppers are the CPU's), a chain that does not fit a block's shared memory (fields x
sites), and a chain whose positions left the polynomial sin/cos's range or blew up (run
again by ``simulate_model``, which continues on libm or reports the blow-up).
"""

from __future__ import annotations

import inspect
import math
from dataclasses import dataclass

import numpy as np


def _default(name: str):
    """``simulate_model``'s default of ``name`` (records, noise: of its exact start, the
    GPU's): one value on both devices."""
    from numerics.models import NOISE, simulate_model

    if name == "noise":  # simulate_model's None: its start's own, NOISE for the exact wave
        return NOISE
    return inspect.signature(simulate_model).parameters[name].default


@dataclass(frozen=True)
class _Records:
    """What ``measure_growth`` reads of a run: its ring, wave and records."""

    N: int
    k: float
    amplitude: float
    wave: object
    t: np.ndarray
    spectrum: np.ndarray


@dataclass
class DeviceChain:
    """One chain of a launch: the model (at the cell's parameters), its exact wave
    (``spec``, an ``exact_gain_checked`` result), the run's length, its start (u, v),
    step, steps and record spacing (``chain_start``), and which cell and seed it is."""

    model: object
    spec: object
    t_end: float
    u: np.ndarray
    v: np.ndarray
    dt: float
    nsteps: int
    every: int
    cell: int = 0
    seed: int = 0


def chain_start(model, k: float, amplitude: float, spec, N: int, t_end: float, seed: int,
                method: str = "srkn11b", noise: float | None = None):
    """(u, v, dt, nsteps, every): ``simulate_model``'s start from ``spec``'s exact wave
    (its step, record spacing and seeded noise, drawn in the same order)."""
    from numerics.lattice import get_method
    from numerics.models import run_force, run_step

    meth = get_method(method)
    noise = _default("noise") if noise is None else noise
    wave = spec.wave
    d = model.n_fields
    rng = np.random.default_rng(seed)
    u, v = wave.state(N)
    u = u + noise * amplitude * rng.standard_normal((d, N))
    v = v + noise * amplitude * wave.omega * rng.standard_normal((d, N))
    # the CPU run's step rule (``numerics.models``' ``run_step``: the branches' top or the
    # start state's own local frequency, probe 98), read with the CPU force
    kernel, p_force, rows, _ = run_force(model)
    dt, _ = run_step(model, meth, wave, None, np.ascontiguousarray(u), kernel, p_force, rows)
    nsteps = max(1, int(math.ceil(t_end / dt)))
    dt = t_end / nsteps
    every = max(1, nsteps // _default("records"))
    return np.ascontiguousarray(u), np.ascontiguousarray(v), dt, nsteps, every


def launch_chains(chains: list, N: int, threads: int | None = None,
                  max_spectra_bytes: int = 2 << 30, fast_force: bool = True) -> list:
    """Run ``chains`` (DeviceChain, one model's, N sites each) on the GPU in one launch (or
    a few: the records' spectra within ``max_spectra_bytes``): per chain (status, records
    taken, spectra (records, N/2 + 1)); status is the kernel's STATUS_OK or STATUS_BAD.
    ``fast_force``: the model's registered device force where it has one (the fused
    flexMM kernel's for the paper chain's models), else its generated force."""
    from numba import cuda

    from numerics.lattice import cuda_model_kernels, get_method

    from ._gpu import simulated

    K = cuda_model_kernels()
    code = chains[0].model.code
    kernel, _ = K.model_kernel(code, fast_force)
    d = chains[0].model.n_fields
    nf = K.device_force_of(code, fast_force)[1]
    if threads is not None and (threads & (threads - 1) or threads * K.PER_THREAD < N):
        raise ValueError(f"threads = {threads}: a power of two with threads * "
                         f"{K.PER_THREAD} >= N")
    meth = get_method("srkn11b")
    acoef = cuda.to_device(np.array(meth.a, float))
    bcoef = cuda.to_device(np.array(meth.b, float))
    cos_t, sin_t = (cuda.to_device(a) for a in K.twiddles(N))
    nq = N // 2 + 1
    nrec = [1 + -(-c.nsteps // c.every) for c in chains]
    H = max((c.spec.wave.coefficients.shape[1] - 1) // 2 for c in chains)
    per_chain = max(nrec) * nq * 8
    batch = max(1, max_spectra_bytes // per_chain)
    bs = threads or K.threads_for(N, simulated(), min(batch, len(chains)))
    out = []
    for b0 in range(0, len(chains), batch):
        part = chains[b0:b0 + batch]
        nb = len(part)
        R = max(nrec[b0:b0 + batch])
        cre = np.zeros((nb, d, 2 * H + 1))
        cim = np.zeros((nb, d, 2 * H + 1))
        for c, ch in enumerate(part):
            co = ch.spec.wave.coefficients
            h = (co.shape[1] - 1) // 2
            cre[c, :, H - h:H + h + 1] = co.real
            cim[c, :, H - h:H + h + 1] = co.imag
        host = {"u0": np.array([c.u.ravel() for c in part]),
                "v0": np.array([c.v.ravel() for c in part]),
                "params": np.array([np.asarray(c.model.p, float) for c in part]),
                "dts": np.array([c.dt for c in part]),
                "nsteps": np.array([c.nsteps for c in part], np.int64),
                "every": np.array([c.every for c in part], np.int64),
                "k": np.array([c.spec.wave.k for c in part]),
                "omega": np.array([c.spec.wave.omega for c in part]),
                "cre": cre, "cim": cim}
        dev = {n: cuda.to_device(np.ascontiguousarray(a)) for n, a in host.items()}
        spectra = cuda.device_array((nb, R, nq))
        status = cuda.device_array((nb, 2))
        kernel[nb, bs, 0, K.shared_bytes(d, nf, N)](
            dev["u0"], dev["v0"], dev["params"], dev["dts"], dev["nsteps"], dev["every"],
            acoef, bcoef, dev["k"], dev["omega"], dev["cre"], dev["cim"], cos_t, sin_t,
            spectra, status)
        st = status.copy_to_host()
        sp = spectra.copy_to_host()
        for c in range(nb):
            out.append((st[c, 0], int(st[c, 1]), sp[c, :int(st[c, 1])]))
    return out


def _growth(chain: DeviceChain, N: int, amplitude: float, half: np.ndarray) -> tuple:
    """(``measure_growth`` of a chain's records, their times, their spectra (records, N):
    the half spectrum mirrored, the fields being real)."""
    from numerics.models import measure_growth

    j = np.arange(N)
    full = half[:, np.minimum(j, N - j)]
    t = np.minimum(np.arange(full.shape[0]) * chain.every, chain.nsteps) * chain.dt
    return measure_growth(_Records(N, chain.spec.wave.k, float(amplitude), chain.spec.wave,
                                   t, full)), t, full


def _read_to(t, spectrum, chain_wave, N: int, amplitude: float, t_end: float) -> float:
    """How far ``map_cells`` would have run this chain: to the record where its linear
    stage saturated (``simulate_model(until_saturated=True)``), else T."""
    from numerics.models import saturation_record

    s = saturation_record(spectrum, N, chain_wave.k, chain_wave.harmonics, amplitude)
    return float(t_end) if s is None else float(t[s])


def _cell_row(growth: list, t_end: float, read_to=None) -> dict:
    """The simulated columns of a cell from its seeds' growth (``map_cells``' rule);
    ``read_to`` each seed's run length (default ``t_end``)."""
    from numerics.lattice import simulated_verdict

    rates = [g.rate for g in growth if g.verdict == "unstable"]
    rate = float(np.median(rates)) if rates else math.nan
    verdict = simulated_verdict([g.factor for g in growth], t_end, rate)
    top = max(growth, key=lambda g: g.factor if math.isfinite(g.factor) else -1.0)
    return {"verdict_simulated": verdict.word,
            # map_cells' own rule (no growth within T: the bound ln(threshold) / T)
            "peak_gain_simulated": verdict.map_rate,
            "growth": float(np.median([g.factor for g in growth])),
            "growth_q": float(top.wavenumber),
            "t_simulated": float(t_end if read_to is None else max(read_to))}


UNDEFINED_ROW = {"verdict_simulated": "undefined", "peak_gain_simulated": math.nan,
                 "growth": math.nan, "growth_q": math.nan, "t_simulated": math.nan}


def simulate_model_cells_gpu(model, cells, amplitude: float, branch=None, *, N: int = 256,
                             seeds: int = 1, t_end: float | None = None,
                             noise: float | None = None, specs=None,
                             threads: int | None = None, log=print, records: bool = False,
                             fast_force: bool = True,
                             max_spectra_bytes: int = 2 << 30) -> list[dict]:
    """The simulated columns of a model's map cells, their runs on the GPU.

    Parameters
    ----------
    model : energy.Model
    cells : sequence of (dict, float)
        Each cell's parameter values and carrier k (as ``numerics.models.map_cells``).
    amplitude, branch, N, seeds, t_end
        As ``map_cells``: ``seeds`` runs per cell from the exact wave on the ring of N
        sites, each ``t_end`` long (None: ``run_length`` of the exact rate a run can see,
        ``visible_gain``).
    noise : float, optional
        The seeded noise relative to the amplitude (``simulate_model``'s default).
    specs : sequence, optional
        Each cell's ``exact_gain_checked`` on the ring, or what the runs read of it (an
        object with its ``wave`` and ``peak_gain``); computed here where not given (or
        None); a ModelError in its place marks a cell without a travelling wave.
    threads : int, optional
        Threads per block (a power of two; default ``threads_for``).
    log : callable
        Gets one line for each reason the CPU runs some chains instead.
    records : bool
        Also return each seed's records: ``records`` [(t, spectrum (records, N)), ...],
        the deviation's spectrum as ``ModelRun.spectrum``.
    fast_force : bool
        The model's registered device force where it has one (``flexmm`` and
        ``flexmm-rotation``: the fused flexMM kernel's, as the paper flags' maps run);
        False: its generated force, the reference.

    Returns
    -------
    list of dict, one per cell: ``verdict_simulated`` (MI, "no growth within T",
    "undetermined", "undefined"), ``peak_gain_simulated``, ``growth``, ``growth_q``,
    ``t_simulated`` (``map_cells``' columns), ``growth_runs`` (each seed's ``Growth``)
    and ``device`` ("gpu", "cpu", or "gpu+cpu" where some seeds ran again on the CPU).
    """
    from energy import ModelError
    from numerics.lattice import BlowUpError, cuda_model_kernels, run_length
    from numerics.models import (
        check_ring,
        exact_gain_checked,
        simulate_model,
        simulate_seeds,
        visible_gain,
    )

    N = check_ring(N)
    if isinstance(seeds, bool) or not isinstance(seeds, (int, np.integer)) or seeds < 1:
        raise ModelError(f"seeds must be an integer >= 1, got {seeds!r}")
    if isinstance(amplitude, bool) or not (isinstance(amplitude, (int, float, np.floating))
                                           and math.isfinite(amplitude) and amplitude > 0):
        raise ModelError(f"amplitude must be a finite number > 0, got {amplitude!r}")
    K = cuda_model_kernels()
    noise = _default("noise") if noise is None else noise
    if isinstance(noise, bool) or not (isinstance(noise, (int, float, np.floating))
                                       and math.isfinite(noise) and noise >= 0):
        raise ModelError(f"noise must be a finite number >= 0, got {noise!r}")
    cells = list(cells)
    models = [model.with_params(**values) for values, _ in cells]
    specs = [None] * len(cells) if specs is None else list(specs)
    for c, (m, (_, k)) in enumerate(zip(models, cells)):
        if specs[c] is None:
            try:
                specs[c] = exact_gain_checked(m, k, amplitude, branch, N=N)
            except ModelError as exc:
                specs[c] = exc
    why_cpu = None
    if model.lossy:
        why_cpu = ("its losses ([dissipation]) run in the CPU's damped steppers")
    else:
        why_cpu = K.fits(model.n_fields, K.device_force_of(model.code, fast_force)[1], N)
    rows: list = [None] * len(cells)
    chains: list = []
    from numerics.models import time_scale
    for c, ((_, k), m, spec) in enumerate(zip(cells, models, specs)):
        if isinstance(spec, Exception):
            rows[c] = dict(UNDEFINED_ROW, growth_runs=[], device="cpu")
            continue
        T = float(t_end) if t_end is not None else run_length(
            visible_gain(spec, N), time_scale=time_scale(m)).t_end
        if why_cpu is not None:
            try:
                sim = simulate_seeds(m, k, amplitude, spec, branch=branch, N=N, seeds=seeds,
                                     t_end=T, noise=noise, until_saturated=True)
            except BlowUpError as exc:  # the state left the lattice's range
                rows[c] = _blown_row(exc.time, records)
                continue
            growth = [r.growth() for r in sim.runs]
            rows[c] = dict(_cell_row(growth, T, [r.t_end for r in sim.runs]),
                           growth_runs=growth, device="cpu")
            if records:
                rows[c]["records"] = [(r.t, r.spectrum) for r in sim.runs]
            continue
        for s in range(seeds):
            u, v, dt, nsteps, every = chain_start(m, k, amplitude, spec, N, T, s, noise=noise)
            chains.append(DeviceChain(m, spec, T, u, v, dt, nsteps, every, c, s))
    if why_cpu is not None and any(r is not None and r["growth_runs"] for r in rows):
        log(f"model {model.name}: its cells run on the CPU, not the GPU: {why_cpu}")
    results = (launch_chains(chains, N, threads, max_spectra_bytes, fast_force) if chains
               else [])
    per_cell: dict = {}
    t_of = {ch.cell: ch.t_end for ch in chains}
    again = 0
    blown: dict = {}  # cell -> when a run of it blew up on the CPU (as map_cells says it)
    for ch, (status, _, half) in zip(chains, results):
        if status != K.STATUS_OK:
            again += 1
            try:
                run = simulate_model(ch.model, ch.spec.wave.k, amplitude, branch=branch,
                                     N=N, t_end=ch.t_end, seed=ch.seed, wave=ch.spec.wave,
                                     noise=noise, until_saturated=True)
            except BlowUpError as exc:  # the state left the lattice's range
                blown[ch.cell] = exc.time
                continue
            per_cell.setdefault(ch.cell, []).append((run.growth(), run.t, run.spectrum,
                                                     "cpu", run.t_end))
        else:
            g, t, full = _growth(ch, N, amplitude, half)
            per_cell.setdefault(ch.cell, []).append(
                (g, t, full, "gpu", _read_to(t, full, ch.spec.wave, N, amplitude, ch.t_end)))
    if again:
        log(f"model {model.name}: {again} of {len(chains)} runs left the GPU's range (a "
            "position beyond the polynomial sin/cos's or not finite): run again on the CPU")
    for c, runs in per_cell.items():
        growth = [r[0] for r in runs]
        where = {r[3] for r in runs}
        rows[c] = dict(_cell_row(growth, t_of[c], [r[4] for r in runs]), growth_runs=growth,
                       device="gpu" if where == {"gpu"} else "cpu" if where == {"cpu"}
                       else "gpu+cpu")
        if records:
            rows[c]["records"] = [(r[1], r[2]) for r in runs]
    for c, when in blown.items():
        rows[c] = _blown_row(when, records)
    return rows


def _blown_row(when, records: bool) -> dict:
    """A cell one of whose runs blew up (``BlowUpError`` at time ``when``), as
    ``numerics.models.map_cells`` stores it: undetermined, growth inf."""
    row = dict(UNDEFINED_ROW, verdict_simulated="undetermined", growth=math.inf,
               t_simulated=math.nan if when is None else float(when), growth_runs=[],
               device="cpu")
    if records:
        row["records"] = []
    return row


@dataclass(frozen=True)
class _Exact:
    """What a cell's runs read of its exact theory: the wave and the peak gain."""

    wave: object
    peak_gain: float


def _wave_of(params, values: dict, k: float, peak_gain: float, amplitude: float):
    """A cell's runs' start without its exact theory again: the theory column's peak gain
    (run_length's input) and the travelling wave on the ring (``exact_gain``'s own: the
    harmonic balance at k snapped to the ring), or None (computed by
    ``simulate_model_cells_gpu``) where the column has no gain, or the ModelError of a
    cell without a wave."""
    from energy import ModelError
    from numerics.models import snap_ring, travelling_wave

    if not math.isfinite(peak_gain):
        return None
    model = params.lattice_model.with_params(**values)
    try:
        return _Exact(travelling_wave(model, snap_ring(k, params.N)[0], amplitude,
                                      params.branch_value), float(peak_gain))
    except ModelError as exc:
        return exc


def model_theories(params, i: int, js: list) -> tuple:
    """A model map's block (i, js) before its runs, on a CPU: (``model_block``'s theory
    columns, each cell's wave for its runs, ``_wave_of``)."""
    from energy import ModelError

    from ._model_columns import model_block

    block = model_block(params, i, js, simulate=False)
    # a cell without a wave of its amplitude (no_wave 1) is not launched, as on the CPU
    specs = [ModelError("no wave of this amplitude (no_wave)") if row.get("no_wave") == 1
             else _wave_of(params, *params.cell(i, j), row.get("peak_gain_exact", math.nan),
                           params.amplitude_at(i, j)) for j, row in zip(js, block["rows"])]
    return block, specs


def model_rows_gpu(params, batch: list, log=print, theories: list | None = None) -> list:
    """A model map's blocks [(i, js), ...] as ``model_block`` writes them, simulated: the
    theories of every cell (``theories``, :func:`model_theories` of each block, or computed
    here), the runs of all of them in one GPU launch; returns [(i, js, rows)] with the
    store's codes."""
    from ._model_columns import SIMULATED_COLUMNS, VERDICT_CODES

    if params.start != "exact":
        raise ValueError(f"the GPU launches the exact wave; a map whose runs start from "
                         f"{params.start!r} runs on the CPU")
    if theories is None:
        theories = [model_theories(params, i, js) for i, js in batch]
    where = [(i, j) for i, js in batch for j in js]
    specs = [spec for _, block_specs in theories for spec in block_specs]
    sims: list = [None] * len(where)
    for amplitude, ns in params.by_amplitude(where):  # one launch per amplitude
        got = simulate_model_cells_gpu(params.lattice_model,
                                       [params.cell(*where[n]) for n in ns], amplitude,
                                       params.branch_value, N=params.N, seeds=params.seeds,
                                       t_end=params.t_end, specs=[specs[n] for n in ns],
                                       log=log)
        for n, sim in zip(ns, got):
            sims[n] = sim
    out, n = [], 0
    for (i, js), (block, _) in zip(batch, theories):
        rows = []
        for row in block["rows"]:
            sim = sims[n]
            n += 1
            row = dict(row)
            for name in SIMULATED_COLUMNS:
                v = sim[name]
                row[name] = (np.int8(VERDICT_CODES[v]) if name.startswith("verdict_")
                             else float(v))
            rows.append(row)
        out.append((i, list(js), rows))
    return out


__all__ = ["simulate_model_cells_gpu", "model_rows_gpu", "model_theories", "chain_start", "launch_chains",
           "DeviceChain", "UNDEFINED_ROW"]
