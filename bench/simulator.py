"""Simulator speed, measured in one run (ratios are what to read; machines are noisy).

Reports: ns per site per force evaluation of the compiled kernel and of the plain NumPy
force; compiled RK4 vs the plain NumPy RK4 (np.roll stencil) at the same dt; the paper's
run (N = 500, t_end = 5000, dt = 0.05, case II) wall time. Writes simulator.json.

Also the helpers every bench script shares: where results go (:func:`output_dir`: out/bench/
by default, the committed bench/ only with ``--update``), the command line
(:func:`arguments`), the machine (:func:`machine`) and the one writer of results.json
sections (:func:`write_sections`).

    python -m bench.simulator [--quick] [--update | --out DIR]
"""

from __future__ import annotations

import argparse
import json
import os
import platform
import time
from pathlib import Path

import numpy as np

from common import paper
from common.files import write_text
from numerics import Material, integrate, simulate
from numerics.lattice import accel, numpy_accel, numpy_rk4

HERE = Path(__file__).resolve().parent
ROOT = HERE.parent
#: Where a bench run writes unless told otherwise: gitignored, so the git tree stays clean.
DEFAULT_OUT = ROOT / "out" / "bench"
BLUE = Material.paper("blue")
PARAMS = (BLUE.alpha**2, BLUE.K_s, BLUE.K_theta)


def best_of(fn, repeat):
    times = []
    for _ in range(repeat):
        t0 = time.perf_counter()
        fn()
        times.append(time.perf_counter() - t0)
    return min(times)


def machine():
    """The machine and the versions that affect the numbers (shared by every bench script)."""
    import numba
    import scipy
    import sympy

    return {"python": platform.python_version(), "machine": platform.machine(),
            "processor": platform.processor() or platform.machine(), "cpus": os.cpu_count(),
            "numpy": np.__version__, "scipy": scipy.__version__, "sympy": sympy.__version__,
            "numba": numba.__version__}


def output_dir(update: bool = False, out=None) -> Path:
    """The folder results go to (created): bench/ itself with ``update`` (the committed
    numbers, `make bench-update` / `make stress-update`), else ``out``, else out/bench/."""
    if update and out is not None:
        raise ValueError("update writes into bench/; give either update or out, not both")
    d = HERE if update else Path(out) if out is not None else DEFAULT_OUT
    d.mkdir(parents=True, exist_ok=True)
    return d


def arguments(description: str | None = None, argv=None) -> tuple[bool, Path]:
    """The command line every bench script takes: ``--quick`` and where to write
    (``--update`` or ``--out DIR``; default out/bench/). Returns (quick, output folder)."""
    ap = argparse.ArgumentParser(description=description,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--quick", action="store_true",
                    help="small sizes (seconds); writes *_quick files")
    where = ap.add_mutually_exclusive_group()
    where.add_argument("--update", action="store_true",
                       help="rewrite the committed results in bench/ (default: out/bench/)")
    where.add_argument("--out", type=Path, metavar="DIR",
                       help="write the results into DIR (default: out/bench/)")
    args = ap.parse_args(argv)
    return args.quick, output_dir(args.update, args.out)


def results_path(quick: bool, out=None) -> Path:
    """results.json (results_quick.json when quick) in ``out`` (default out/bench/)."""
    return output_dir(out=out) / ("results_quick.json" if quick else "results.json")


def write_sections(sections: dict, quick: bool, out=None) -> Path:
    """Put each ``{name: res}`` of ``sections`` into results.json (results_quick.json when
    quick) in ``out``, keeping the other scripts' sections: the one writer of that file."""
    path = results_path(quick, out)
    data = json.loads(path.read_text()) if path.exists() else {}
    data.update(sections)
    write_text(path, json.dumps(data, indent=2) + "\n")
    return path


def write_section(name: str, res: dict, quick: bool, out=None) -> Path:
    """Put ``res`` under ``name`` in results.json (see :func:`write_sections`)."""
    return write_sections({name: res}, quick, out)


def main(quick=False, out=None):
    rng = np.random.default_rng(0)
    N = 500
    th, U = rng.normal(0, 0.02, N), rng.normal(0, 1e-4, N)
    s, c, v, a1, a2 = (np.empty(N) for _ in range(5))
    reps = 2000 if quick else 20000
    accel(th, U, True, *PARAMS, s, c, v, a1, a2)  # compile

    def kernel():
        for _ in range(reps):
            accel(th, U, True, *PARAMS, s, c, v, a1, a2)

    def sincos():
        for _ in range(reps):
            np.sin(th, out=s)
            np.cos(th, out=c)

    def npforce():
        for _ in range(reps // 10):
            numpy_accel(th, U, BLUE, True)

    t_kernel = best_of(kernel, 3) / reps / N * 1e9
    t_sincos = best_of(sincos, 3) / reps / N * 1e9
    t_np = best_of(npforce, 3) / (reps // 10) / N * 1e9

    state = simulate(BLUE, "coupled", N, paper.k("blue"), t_end=1.0, dt=paper.DT).final_state
    T = 20.0 if quick else 100.0
    integrate(state, BLUE, "coupled", 1.0, 0.05)  # compile
    t_rk4 = best_of(lambda: integrate(state, BLUE, "coupled", T, 0.05), 3)
    t_np_rk4 = best_of(lambda: numpy_rk4(state, BLUE, "coupled", T, 0.05), 1 if quick else 2)

    t_end = 500.0 if quick else 5000.0
    t0 = time.perf_counter()
    run = simulate(BLUE, "coupled", N, paper.k("blue"), t_end=t_end, dt=paper.DT, store="spectrum",
                   save_every=5.0, progress=False)
    t_paper = time.perf_counter() - t0
    res = {
        "machine": machine(),
        "force_ns_per_site_compiled": t_kernel,
        "force_ns_per_site_numpy": t_np,
        "sincos_ns_per_site_numpy": t_sincos,
        "kernel_over_sincos": t_kernel / t_sincos,
        "rk4_compiled_s": t_rk4, "rk4_numpy_s": t_np_rk4, "rk4_T": T,
        "rk4_speedup_vs_numpy": t_np_rk4 / t_rk4,
        "paper_run_s": t_paper, "paper_run_t_end": t_end,
        "paper_run_energy_error": float(run.relative_energy_error.max()),
        "quick": quick,
    }
    path = output_dir(out=out) / ("simulator_quick.json" if quick else "simulator.json")
    write_text(path, json.dumps(res, indent=2) + "\n")
    print(f"force kernel: {t_kernel:.1f} ns/site (NumPy force {t_np:.1f}, NumPy sin+cos alone "
          f"{t_sincos:.1f}; kernel/sincos = {t_kernel / t_sincos:.2f})")
    print(f"RK4 over T = {T:g}, N = {N}: compiled {t_rk4 * 1e3:.1f} ms, NumPy "
          f"{t_np_rk4 * 1e3:.1f} ms -> {t_np_rk4 / t_rk4:.1f}x")
    print(f"paper run (case II, N = 500, T = {t_end:g}, dt = 0.05): {t_paper:.2f} s, "
          f"max relative energy error {res['paper_run_energy_error']:.2e}")
    return res


if __name__ == "__main__":
    main(*arguments(__doc__))
