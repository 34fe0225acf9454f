"""Issue 41's exact-theory rows of ``bench.models``: the exact lattice theory against the run
it predicts, per built-in model at one point (``EXACT_POINTS``), with the chain's floor
(``solve_floor``), and a theory-only ``--exact`` map of fput through the command line
(``exact_map``). ``bench.models``' docstring says what each row measures and how to run it
(``python -m bench.models --exact-only``).
"""

from __future__ import annotations

import time

import numpy as np
from numba import njit

from energy import load_model
from numerics.models import exact_gain

REPEATS_EXACT = 3
#: one point per built-in model: params, k, amplitude, branch
EXACT_POINTS = {
    "fput": (dict(alpha=0.5, beta=1.0), 2 * np.pi * 66 / 256, 0.1, None),
    "klein-gordon": (dict(alpha=0.5), 2.5, 0.05, None),
    "sine-gordon": ({}, 1.0, 0.3, None),
    "diatomic-fput": ({}, 1.0, 0.1, 0),
    "flexmm": (dict(K_theta=0.016), 2 * np.pi * 36 / 256, 0.1, None),
    "flexmm-rotation": ({}, 1.0, 0.1, None),
    "flexmm-stiff-hinge": ({}, 1.0, 0.1, None),
}


@njit(cache=True)
def _solves(A, b, reps):
    """``reps`` dense LU solves of ``A x = b`` (LAPACK zgesv, as the kernels' own)."""
    s = 0j
    for _ in range(reps):
        s += np.linalg.solve(A, b)[0]
    return s


def solve_floor(n: int, reps: int = 400, repeats: int = 5) -> float:
    """CPU seconds of one dense complex n x n solve (best of ``repeats`` loops of ``reps``)."""
    rng = np.random.default_rng(1)
    A = rng.standard_normal((n, n)) + 1j * rng.standard_normal((n, n)) + 2 * n * np.eye(n)
    b = rng.standard_normal(n) + 0j
    _solves(A, b, 2)
    return _cpu(lambda: _solves(A, b, reps), repeats)[0] / reps


def _cpu(f, reps):
    """Best CPU seconds of ``f()`` over ``reps`` calls, and its last result."""
    best, out = float("inf"), None
    for _ in range(reps):
        t0 = time.process_time()
        out = f()
        best = min(best, time.process_time() - t0)
    return best, out


def exact_against_runs(quick=False, N=256):
    """exact_gain (ring of N, infinite chain) against one seeded run, CPU seconds."""
    from energy import ModelError
    from numerics.models import simulate_seeds

    rows = {}
    for name, (params, k, a, br) in EXACT_POINTS.items():
        model = load_model(name).with_params(**params) if params else load_model(name)
        try:
            exact_gain(model, k, a, br, N=N)
        except ModelError as exc:
            rows[name] = {"error": str(exc)}
            continue
        reps = 1 if quick else REPEATS_EXACT
        ring_s, spec = _cpu(lambda m=model, k=k, a=a, b=br: exact_gain(m, k, a, b, N=N), reps)
        chain_s, chain = _cpu(lambda m=model, k=k, a=a, b=br: exact_gain(m, k, a, b), reps)
        simulate_seeds(model, k, a, spec, branch=br, N=N, seeds=1, t_end=10.0)  # compile
        t_end = 200.0 if quick else None
        run_s, runs = _cpu(lambda m=model, k=k, a=a, b=br, s=spec, T=t_end: simulate_seeds(
            m, k, a, s, branch=b, N=N, seeds=1, t_end=T), 1)
        # the floor of any method that touches every chain offset's whole Hill pencil
        # (n = fields x (2 P + 1)) once: the wave and one LU solve per offset
        from numerics.models import travelling_wave

        wave_s = _cpu(lambda m=model, k=k, a=a, b=br: travelling_wave(m, k, a, b), reps)[0]
        n = model.n_fields * (2 * spec.truncations[0] + 1)
        offsets = chain.offsets.size  # the chain's samples and its refined peak
        floor_s = wave_s + offsets * solve_floor(n)
        rows[name] = {"params": params, "k": spec.wave.k, "amplitude": a, "branch": br, "N": N,
                      "exact_ring_cpu_s": ring_s, "exact_chain_cpu_s": chain_s,
                      "wave_cpu_s": wave_s, "pencil_size": n, "chain_offsets": offsets,
                      "chain_floor_cpu_s": floor_s,
                      "run_cpu_s": run_s, "run_t_end": runs.t_end,
                      "ring_over_run": ring_s / run_s, "chain_over_run": chain_s / run_s,
                      "chain_floor_over_run": floor_s / run_s,
                      "ring_peak_gain": spec.peak_gain, "chain_peak_gain": chain.peak_gain,
                      "truncations": list(spec.truncations)}
    return rows


def exact_map(quick=False, N=256):
    """A theory-only --exact map of fput through the command line: (wall s, CPU s, cells)."""
    import contextlib
    import io
    import tempfile

    from cli.app import main as cli

    n = 8 if quick else 64
    with tempfile.TemporaryDirectory() as tmp:
        argv = ["map", "--model", "fput", "--param", "alpha=0.5", "--param",
                f"beta=0.5:2.0:{n}", "--k", f"0.5:3.0:{n}", "--amplitude", "0.1", "--N",
                str(N), "--theory-only", "--exact", "--out", tmp]
        t0, c0 = time.perf_counter(), time.process_time()
        with contextlib.redirect_stdout(io.StringIO()):
            code = cli(argv)
        wall, cpu = time.perf_counter() - t0, time.process_time() - c0
    return {"cells": n * n, "N": N, "wall_s": wall, "cpu_s": cpu, "exit": code,
            "argv": argv[:-1]}


def print_exact_against_runs(against: dict) -> None:
    """``exact_against_runs``'s rows, a line per model (``main`` and ``--exact-only``)."""
    print("exact_gain against one seeded run (CPU s, N = 256; goal: ratio <= 0.1):")
    for name, r in against.items():
        if "error" in r:
            print(f"  {name:<18} {r['error']}")
            continue
        print(f"  {name:<18} ring {r['exact_ring_cpu_s']:.4f} s, chain "
              f"{r['exact_chain_cpu_s']:.4f} s, run {r['run_cpu_s']:.3f} s "
              f"(T = {r['run_t_end']:g}): ring/run {r['ring_over_run']:.3f}, chain/run "
              f"{r['chain_over_run']:.3f} (floor {r['chain_floor_over_run']:.3f}: the wave "
              f"{r['wave_cpu_s'] * 1e3:.1f} ms + {r['chain_offsets']} solves of "
              f"{r['pencil_size']} x {r['pencil_size']})")
