"""``exact_gain`` of each built-in model's bench point (``bench.models.EXACT_POINTS``) on
the ring of N = 256 and on the infinite chain: CPU seconds (``time.process_time``, one
BLAS thread: ``exact_gain``'s own), warm, a fresh model object each round, best of
``reps``. ``--answers`` prints the peak gains at full precision instead, to compare trees.

    OMP_NUM_THREADS=1 python -m bench.exact_points [--reps 5] [--answers]
"""

from __future__ import annotations

import sys
import time

from bench.models import EXACT_POINTS
from energy import load_model
from numerics.models import exact_gain


def main(argv=None):
    argv = sys.argv[1:] if argv is None else argv
    reps = int(argv[argv.index("--reps") + 1]) if "--reps" in argv else 5
    names = [n for n in EXACT_POINTS if n in argv] or list(EXACT_POINTS)
    for name in names:
        params, k, a, br = EXACT_POINTS[name]
        base = load_model(name)
        model = base.with_params(**params) if params else base
        for N in (256, None):
            if "--answers" in argv:
                e = exact_gain(model, k, a, br, N=N)
                print(f"{name:20s} N {N}: {e.peak_gain!r} {e.fastest_offset!r}")
                continue
            exact_gain(model, k, a, br, N=N)  # warm-up: generated module, JIT
            best = float("inf")
            for _ in range(reps):
                m = model.with_params()
                t0 = time.process_time()
                exact_gain(m, k, a, br, N=N)
                best = min(best, time.process_time() - t0)
            print(f"{name:20s} N {str(N):5s} {best * 1e3:8.2f} ms", flush=True)


if __name__ == "__main__":
    main()
