"""Registers, threads per block and the kernels' speed on a GPU -> results_gpu.json's
``occupancy`` (docs/gpu.md, "What is known without a GPU").

ptxas gives the paper chain's cell kernel ~255 registers a thread, so an SM of 65536
registers holds two blocks of 128 threads. Whether that limits the rate, and whether a
register cap (``cuda.jit(max_registers=...)``) or fewer threads a chain (more chains an SM)
helps, is measured here, on the GPU, by timing the same launch as ``bench.gpu``'s kernel
row (4096 cells, N = 500, T = 5000, srkn11b, paper start) under each variant, and the
models' kernel (``bench.gpu``'s model rows: 2048 chains, N = 256, T = 500) of ``fput`` and
``flexmm`` at 128, 64 and 32 threads a chain, and smaller launches (SMALL_LAUNCHES chains)
at 128 and 32 (the rule of ``threads_for``: the fewest threads a chain from FILL_CHAINS
chains a launch). Every variant's growth must equal the
default's (the same arithmetic; the register cap only moves values to local memory):
a variant whose rows differ is reported, not timed as equal.

Each row: threads, max_registers (None: the compiler's choice), the registers ptxas gave,
local memory a thread (bytes: spills), blocks an SM by registers (65536 / (registers x
threads), allocation granularity ignored), wall of the launch and ps per site-evaluation.

Without a GPU it prints one line starting "no GPU" and exits 0.

    python -m bench.gpu_occupancy [--out DIR | --update] [--quick]
"""

from __future__ import annotations

import argparse
import json
import sys
import time
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
#: (threads, max_registers) of the paper kernel; None: the default (THREADS, no cap)
PAPER_VARIANTS = ((128, None), (64, None), (128, 128), (64, 128), (128, 168))
MODEL_THREADS = (128, 64, 32)
#: smaller launches (chains) timed at the most and the fewest threads a chain
SMALL_LAUNCHES = (66, 132, 264, 528)


def _regs(dispatcher) -> tuple[int | None, int | None]:
    try:
        regs = dispatcher.get_regs_per_thread()
        local = dispatcher.get_local_mem_per_thread()
    except Exception as exc:  # noqa: BLE001 -- a numba without the query: say so, go on
        print(f"[occupancy] registers not read: {exc}", flush=True)
        return None, None
    if isinstance(regs, dict):  # one entry per compiled signature
        regs, local = max(regs.values()), max(local.values())
    return int(regs), int(local)


def _blocks(regs, threads):
    return None if not regs else 65536 // (regs * threads)


def paper_variants(cells: int, N: int = 500, t_end: float = 5000.0) -> list:
    from numba import cuda

    from numerics import Material
    from numerics.lattice import cuda_kernels, get_method
    from numerics.maps import simulate_cells_gpu
    from numerics.maps._cells import map_step

    K = cuda_kernels()
    default = K.cells_kernel
    mat = Material(2.5, 0.01851, 0.01851 - 0.003)
    ks = [2 * np.pi * m / N for m in np.linspace(10, N // 2 - 10, cells).round()]
    method, dt = map_step([mat], "coupled", ks, N, t_end, 0.02)
    evals = get_method(method).evaluations
    rows, reference = [], None
    try:
        for threads, cap in PAPER_VARIANTS:
            K.cells_kernel = (default if cap is None else
                              cuda.jit(max_registers=cap)(default.py_func))
            args = ("coupled", ks, N, t_end, 0.02, 1e-3, 1, "paper", method, dt)
            simulate_cells_gpu(mat, "coupled", ks[:2], N, 50.0, 0.02, 1e-3, 1, "paper",
                               method, dt, peak_gain=False, threads=threads)  # compile
            t0 = time.perf_counter()
            runs = simulate_cells_gpu(mat, *args, peak_gain=False, threads=threads)
            wall = time.perf_counter() - t0
            growth = np.array([r["growth"] for r in runs])
            if reference is None:
                reference = growth
            diff = float(np.max(np.abs(growth - reference)) / np.max(np.abs(reference)))
            site_evals = sum(round(r["t_simulated"] / r["dt"]) * evals * N for r in runs)
            regs, local = _regs(K.cells_kernel)
            rows.append({"threads": threads, "max_registers": cap, "registers": regs,
                         "local_bytes": local, "blocks_per_sm_by_registers":
                         _blocks(regs, threads), "wall_s": wall,
                         "ps_per_site_evaluation": wall / site_evals * 1e12,
                         "growth_max_rel_diff": diff})
            print(f"[occupancy] paper kernel {rows[-1]}", flush=True)
    finally:
        K.cells_kernel = default
    return rows


def model_variants(chains: int, N: int = 256, t_end: float = 500.0) -> dict:
    from energy import load_model
    from numerics.lattice import cuda_model_kernels, get_method
    from numerics.maps._gpu_models import DeviceChain, chain_start, launch_chains
    from numerics.models import exact_gain_checked

    K = cuda_model_kernels()
    evals = get_method("srkn11b").evaluations
    out = {}
    for name in ("fput", "flexmm"):
        model = load_model(name)
        k = 2 * np.pi * round(0.15 * N) / N
        spec = exact_gain_checked(model, k, 0.05, None, N=N)

        def chains_of(n, T, model=model, spec=spec, k=k):
            return [DeviceChain(model, spec, T, *chain_start(model, k, 0.05, spec, N, T, s),
                                seed=s) for s in range(n)]

        rows, reference = [], None
        for threads in MODEL_THREADS:
            launch_chains(chains_of(2, 5.0), N, threads)  # compile
            todo = chains_of(chains, t_end)
            t0 = time.perf_counter()
            res = launch_chains(todo, N, threads)
            wall = time.perf_counter() - t0
            last = np.array([r[2][r[1] - 1] for r in res])  # each chain's last record
            if reference is None:
                reference = last
            diff = float(np.max(np.abs(last - reference)) / np.max(np.abs(reference)))
            regs, local = _regs(K.model_kernel(model.code, True)[0])
            site_evals = sum(c.nsteps for c in todo) * evals * N
            rows.append({"threads": threads, "chains": chains, "registers": regs, "local_bytes": local,
                         "blocks_per_sm_by_registers": _blocks(regs, threads),
                         "wall_s": wall, "ps_per_site_evaluation":
                         wall / site_evals * 1e12, "spectrum_max_rel_diff": diff})
            print(f"[occupancy] {name} {rows[-1]}", flush=True)
        for n in SMALL_LAUNCHES:  # few chains: does the fewest threads a chain still pay?
            for threads in (MODEL_THREADS[0], MODEL_THREADS[-1]):
                todo = chains_of(n, t_end)
                t0 = time.perf_counter()
                launch_chains(todo, N, threads)
                wall = time.perf_counter() - t0
                site_evals = sum(c.nsteps for c in todo) * evals * N
                rows.append({"threads": threads, "chains": n, "wall_s": wall,
                             "ps_per_site_evaluation": wall / site_evals * 1e12})
                print(f"[occupancy] {name} {rows[-1]}", flush=True)
        out[name] = rows
    return out


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--out", default="out/bench", help="folder of results_gpu.json")
    ap.add_argument("--update", action="store_true", help="write bench/results_gpu.json")
    ap.add_argument("--quick", action="store_true", help="512 cells, 256 model chains")
    a = ap.parse_args(argv)
    from numerics.maps._gpu import gpu_name, gpu_status, simulated

    ok, reason = gpu_status()
    if not ok or simulated():
        print(f"no GPU: bench.gpu_occupancy measured nothing and wrote nothing ({reason})")
        return 0
    out = HERE / "results_gpu.json" if a.update else Path(a.out) / "results_gpu.json"
    out.parent.mkdir(parents=True, exist_ok=True)
    result = json.loads(out.read_text()) if out.exists() else {}
    occ = {"device": gpu_name(), "paper_kernel": None, "models": None,
           "measured": time.strftime("%Y-%m-%d", time.gmtime())}
    result["occupancy"] = occ
    occ["paper_kernel"] = paper_variants(512 if a.quick else 4096)
    out.write_text(json.dumps(result, indent=2, sort_keys=True) + "\n")
    occ["models"] = model_variants(256 if a.quick else 2048)
    out.write_text(json.dumps(result, indent=2, sort_keys=True) + "\n")
    print(f"wrote {out}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
