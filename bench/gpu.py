"""GPU map cells against this machine's CPU cores -> bench/results_gpu.json (issue 34).

Run by ``make bench-gpu`` on a machine with an NVIDIA GPU and the ``gpu`` extra.

Keys: ``device`` (the GPU's name), ``ps_per_site_evaluation`` (the cell kernel: wall time of
one launch over chains x sites x force evaluations done), ``cells_per_s`` (the same launch),
``map_64x64_wall_s`` and ``map_512x512_wall_s`` (N = 500, T = 5000, paper start, one seed,
through ``flexmm map --device gpu``), ``cpu_cores`` and ``map_64x64_cpu_wall_s`` (the same
64 x 64 map through ``flexmm map`` on the CPU cores) and ``gpu_speedup`` (their ratio).
``--maps 32 --cpu-map 32`` times the 32 x 32 map on both instead (``map_32x32_wall_s``,
``map_32x32_cpu_wall_s``), where a device lease cannot hold the 64 x 64 CPU map;
``gpu_speedup_map`` names the size the speed-up was measured at (the largest with both).
The maps are measured, never estimated: a map the CLI cannot run on the GPU (no
``--device`` yet) is null with the reason in ``notes``. ``models``: every built-in model's
own kernel (its generated site force, ``numerics.maps.simulate_model_cells_gpu``'s launch):
``ps_per_site_evaluation`` and ``chains_per_s`` of one launch of MODEL_CHAINS chains (one
cell's seeds, N = MODEL_N, T = MODEL_T, srkn11b at the model runs' step, its records'
spectra included), or why a model has no number (a lossy model runs on the CPU).

Without a GPU it prints one line starting "no GPU" and exits 0, writing nothing.

Before the timed maps, a 2 x 2 map on the GPU and on the CPU, untimed, fills numba's disk
cache, so that neither timed map pays for compiles the other left behind.

Each stage's numbers are written as soon as it ends (a run cut off by a time limit keeps
what it measured; the stages not reached are null, said in ``notes``). ``versions``: numba,
numba-cuda and numpy, as measured.

    python -m bench.gpu [--quick] [--out DIR | --update] [--skip-cpu-map] [--maps 64,512]
                        [--cpu-map 64] [--resume]
"""

from __future__ import annotations

import argparse
import json
import math
import os
import shutil
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
#: the map of the goals: the paper's alpha and K_s, delta across zero, k over the branch
MAP = ["--alpha", "2.5", "--K-s", "0.01851", "--case", "coupled", "--N", "500",
       "--t-end", "5000", "--start", "paper", "--seeds", "1", "--overwrite", "--yes"]


#: the maps' sizes (cells a side) bench.gpu can time on the GPU, and on the CPU cores
GPU_MAP_SIZES = (32, 64, 512)
CPU_MAP_SIZES = (32, 64)


def map_args(n: int) -> list:
    return MAP + [f"--delta=-0.012:0.012:{n}", "--k", f"0.25:2.9:{n}"]


def kernel_rate(cells: int, N: int = 500, t_end: float = 5000.0) -> dict:
    """One launch of ``cells`` chains (one row of k at delta = 0.003, paper start)."""
    from numerics import Material
    from numerics.lattice import get_method
    from numerics.maps import simulate_cells_gpu
    from numerics.maps._cells import map_step

    mat = Material(2.5, 0.01851, 0.01851 - 0.003)
    ks = [2 * np.pi * m / N for m in np.linspace(10, N // 2 - 10, cells).round()]
    method, dt = map_step([mat], "coupled", ks, N, t_end, 0.02)
    simulate_cells_gpu(mat, "coupled", ks[:2], N, 50.0, 0.02, 1e-3, 1, "paper", method,
                       dt, peak_gain=False)  # compile
    t0 = time.perf_counter()
    runs = simulate_cells_gpu(mat, "coupled", ks, N, t_end, 0.02, 1e-3, 1, "paper", method,
                              dt, peak_gain=False)
    wall = time.perf_counter() - t0
    evals = get_method(method).evaluations
    site_evals = sum(round(r["t_simulated"] / r["dt"]) * evals * N for r in runs)
    return {"ps_per_site_evaluation": wall / site_evals * 1e12, "cells_per_s": cells / wall,
            "kernel_cells": cells, "kernel_method": method, "kernel_dt": runs[0]["dt"],
            "kernel_wall_s": wall}


#: one launch of each model's kernel: chains (seeds of one cell), ring, run length
MODEL_CHAINS, MODEL_N, MODEL_T = 2048, 256, 500.0


def model_rates(chains: int = MODEL_CHAINS, N: int = MODEL_N, t_end: float = MODEL_T) -> dict:
    """{model: {ps_per_site_evaluation, chains_per_s, ...} or {"note": why none}}: one
    launch of ``chains`` chains of every built-in model at its default parameters, k the
    ring mode nearest 0.3 pi, amplitude 0.05 (after a launch that compiles the kernel)."""
    from energy import BUILTIN, ModelError, load_model
    from numerics.lattice import get_method
    from numerics.maps._gpu_models import DeviceChain, chain_start, launch_chains
    from numerics.models import exact_gain_checked

    evals = get_method("srkn11b").evaluations
    out = {}
    for name in sorted(BUILTIN):
        model = load_model(name)
        if model.lossy:
            out[name] = {"note": "lossy: its runs are the CPU's damped steppers"}
            continue
        k = 2 * np.pi * round(0.15 * N) / N
        try:
            spec = exact_gain_checked(model, k, 0.05, None, N=N)
        except ModelError as exc:
            out[name] = {"note": f"no travelling wave at k = {k:.4g}: {exc}"}
            continue

        def chains_of(n, T, model=model, spec=spec, k=k):
            return [DeviceChain(model, spec, T, *chain_start(model, k, 0.05, spec, N, T, s),
                                seed=s) for s in range(n)]

        launch_chains(chains_of(2, 5.0), N)  # compile
        todo = chains_of(chains, t_end)
        t0 = time.perf_counter()
        res = launch_chains(todo, N)
        wall = time.perf_counter() - t0
        bad = int(sum(r[0] != 0 for r in res))
        site_evals = sum(c.nsteps for c in todo) * evals * N
        out[name] = {"ps_per_site_evaluation": wall / site_evals * 1e12,
                     "chains_per_s": chains / wall, "wall_s": wall, "chains": chains,
                     "N": N, "t_end": t_end, "dt": todo[0].dt, "fields": model.n_fields,
                     "chains_left_range": bad}
    return out


def timed_map(n: int, device: str | None, out: Path, notes: list,
              logs: Path | None = None) -> float | None:
    """Wall seconds of one ``flexmm map`` of n x n cells (None, with the reason in
    ``notes``, where it fails); its output saved in ``logs``/map_<n>_<device>.log."""
    cmd = [shutil.which("flexmm") or "flexmm", "map", *map_args(n), "--out", str(out)]
    if device:
        cmd += ["--device", device]
    t0 = time.perf_counter()
    res = subprocess.run(cmd, capture_output=True, text=True)
    wall = time.perf_counter() - t0
    if logs is not None:
        (logs / f"map_{n}_{device or 'cpu'}.log").write_text(res.stdout + res.stderr)
    if res.returncode:
        notes.append(f"{n}x{n} map on {device or 'cpu'}: exit {res.returncode}: "
                     + (res.stderr.strip().splitlines() or ["?"])[-1])
        return None
    return wall


def versions() -> dict:
    """numba, numba-cuda and numpy as imported (None where absent)."""
    from importlib.metadata import PackageNotFoundError, version

    got = {}
    for name in ("numba", "numba-cuda", "numpy", "llvmlite"):
        try:
            got[name] = version(name)
        except PackageNotFoundError:
            got[name] = None
    return got


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true", help="kernel only, 512 chains")
    ap.add_argument("--out", default="out/bench", help="folder of results_gpu.json")
    ap.add_argument("--update", action="store_true", help="write bench/results_gpu.json")
    ap.add_argument("--skip-cpu-map", action="store_true",
                    help="no CPU map (minutes): no map_64x64_cpu_wall_s, no gpu_speedup")
    ap.add_argument("--resume", action="store_true",
                    help="keep the stages a results_gpu.json of the same GPU already has")
    ap.add_argument("--maps", default="64,512",
                    help="which GPU maps to time (32, 64 and/or 512 cells a side)")
    ap.add_argument("--cpu-map", type=int, default=64, choices=CPU_MAP_SIZES,
                    help="cells a side of the CPU map timed against the GPU's (default 64)")
    a = ap.parse_args(argv)
    sizes = [int(n) for n in a.maps.split(",") if n.strip()]
    if bad := [n for n in sizes if n not in GPU_MAP_SIZES]:
        ap.error(f"--maps: {bad} not among {GPU_MAP_SIZES}")
    from numerics.maps._gpu import gpu_name, gpu_status, simulated

    ok, reason = gpu_status()
    if not ok or simulated():
        print(f"no GPU: bench.gpu measured nothing and wrote nothing ({reason})")
        return 0
    notes: list = []
    result = {"device": gpu_name(), "status": reason, "cpu_cores": os.cpu_count(),
              "versions": versions(), "notes": notes, "gpu_speedup": None,
              "gpu_speedup_map": None, "ps_per_site_evaluation": None, "cells_per_s": None,
              "models": {}}
    result.update({f"map_{n}x{n}_wall_s": None for n in GPU_MAP_SIZES})
    result.update({f"map_{n}x{n}_cpu_wall_s": None for n in CPU_MAP_SIZES})
    out = HERE / "results_gpu.json" if a.update else Path(a.out) / "results_gpu.json"
    out.parent.mkdir(parents=True, exist_ok=True)
    if a.resume and out.exists():
        old = json.loads(out.read_text())
        if old.get("device") == result["device"]:
            kept = {k: v for k, v in old.items() if v not in (None, {}, [])
                    and k not in ("status", "versions", "notes", "last_stage", "gpu_speedup",
                                  "gpu_speedup_map")}
            result.update(kept)
            print(f"[bench.gpu] resuming {out}: kept {', '.join(sorted(kept))}", flush=True)

    def save(stage: str) -> None:
        result["last_stage"] = stage
        out.write_text(json.dumps(result, indent=2, sort_keys=True) + "\n")
        print(f"[bench.gpu] {stage} done, saved {out}", flush=True)

    save("start")
    if result["ps_per_site_evaluation"] is None:
        result.update(kernel_rate(512 if a.quick else 4096))
        save("kernel")
    if not result["models"]:
        result["models"] = model_rates(256 if a.quick else MODEL_CHAINS)
        save("models")
    help_text = subprocess.run([shutil.which("flexmm") or "flexmm", "map", "--help"],
                               capture_output=True, text=True).stdout
    has_device = "--device" in help_text
    with tempfile.TemporaryDirectory() as tmp:
        tmp = Path(tmp)
        if has_device and not a.quick:
            # numba compiles each kernel once per machine (its disk cache): a 2 x 2 map on
            # each device first, untimed, so that neither timed map pays for the other's
            # compiles (the first try timed the GPU map cold and the CPU map warm)
            for device in ("gpu", "cpu"):
                timed_map(2, device, tmp / f"warm_{device}", notes)
        for n in GPU_MAP_SIZES:
            key = f"map_{n}x{n}_wall_s"
            if result[key] is not None:
                continue
            if a.quick or not has_device or n not in sizes:
                if not has_device:
                    notes.append(f"{key}: flexmm map has no --device option yet")
                elif n not in sizes and not a.quick and n != 32:
                    notes.append(f"{key}: not run (--maps {a.maps})")
                continue
            result[key] = timed_map(n, "gpu", tmp / f"gpu{n}", notes, out.parent)
            save(key)
        n = a.cpu_map
        key = f"map_{n}x{n}_cpu_wall_s"
        if not (a.quick or a.skip_cpu_map or result[key] is not None):
            result[key] = timed_map(n, "cpu" if has_device else None, tmp / f"cpu{n}",
                                    notes, out.parent)
            save(key)
    for n in sorted(CPU_MAP_SIZES, reverse=True):  # the largest map measured on both
        g, c = result[f"map_{n}x{n}_wall_s"], result[f"map_{n}x{n}_cpu_wall_s"]
        if g and c:
            result["gpu_speedup"], result["gpu_speedup_map"] = c / g, f"{n}x{n}"
            break
    save("done")
    for k in ("device", "ps_per_site_evaluation", "cells_per_s",
              *(f"map_{n}x{n}_wall_s" for n in GPU_MAP_SIZES),
              *(f"map_{n}x{n}_cpu_wall_s" for n in CPU_MAP_SIZES), "gpu_speedup",
              "gpu_speedup_map"):
        v = result[k]
        print(f"{k:>24}: {v:.4g}" if isinstance(v, float) and math.isfinite(v) else
              f"{k:>24}: {v}")
    for name, r in result["models"].items():
        print(f"{name:>24}: " + (f"{r['ps_per_site_evaluation']:.4g} ps per site-evaluation"
                                 if "note" not in r else r["note"]))
    print(f"wrote {out}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
