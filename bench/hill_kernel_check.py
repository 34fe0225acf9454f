"""The compiled Hill kernel of this tree against another tree's (a copy of its
``numerics/models/_sidebands.py``), in one process: ``exact_gain`` of random points of the
built-in one-field and two-field models (k in [0.3, 2.9], a in [0.02, 0.3], rings of 64
and 256 and the chain), each kernel in turn. Prints the points whose peak gain moved by
more than 1e-12 relative, or whose fastest offset or truncations differ, and the worst
relative change. Then single offsets asked alone (``hill_spectrum(wave, [q])``: the
ring's fastest offset and three random ones per point), each kernel's rate against the
ring call's and against the dense eigenproblem at the compiled path's truncation: a mode
lost or kept by one path only shows there (README's fput point lost one at q = pi / 2).
The rest of the theory (waves, strong-coupling and dense paths) is this tree's for both,
and so is what the copy imports: since the cluster solve moved to ``_cluster_solve``, a
copy of a later ``_sidebands.py`` compares the disc pass alone (a copy from before it
moved carries its own).

    OMP_NUM_THREADS=1 python -m bench.hill_kernel_check --baseline /tmp/main_sidebands.py
"""

from __future__ import annotations

import importlib.util
import inspect
import math
import sys
from pathlib import Path

import numpy as np

import numerics.models._sidebands as kernel
from energy import load_model
from numerics.models import exact_gain, hill_spectrum

MODELS = (("fput", {}), ("fput", dict(alpha=0.5)), ("klein-gordon", {}),
          ("klein-gordon", dict(alpha=0.5)), ("sine-gordon", {}), ("diatomic-fput", {}),
          ("flexmm-rotation", {}))


def main(argv=None):
    argv = sys.argv[1:] if argv is None else argv
    if "--baseline" not in argv or argv.index("--baseline") + 1 >= len(argv):
        raise SystemExit("usage: python -m bench.hill_kernel_check --baseline "
                         "OTHER_TREE/numerics/models/_sidebands.py")
    path = argv[argv.index("--baseline") + 1]
    # named by its file's stem: numba's on-disk cache of that file records the module name
    # inside this tree's package, so that its relative imports (``._small_algebra``)
    # resolve: the kernel's helpers are this tree's for both
    stem = f"numerics.models._baseline{Path(path).stem}"
    spec = importlib.util.spec_from_file_location(stem, path)
    old = importlib.util.module_from_spec(spec)
    old.__package__ = "numerics.models"
    sys.modules[stem] = old
    spec.loader.exec_module(old)
    new = kernel.sideband_modes
    if "zero_only" not in inspect.signature(old.sideband_modes.py_func).parameters:
        # a kernel from before the ring's copies (``_ring_copies``): every central
        # cluster's modes where the ring asks only those holding an l = 0 root, a superset
        # the kept-mode rule picks from as before
        older = old.sideband_modes

        def old_kernel(*args, zero_only=False):
            return older(*args[:10])
    else:
        old_kernel = old.sideband_modes
    rng = np.random.default_rng(7)
    worst, moved, n = 0.0, 0, 0
    alone = []  # (this tree's kernel?, spectrum, q, ring call's rates, rate alone, its P)
    for name, params in MODELS:
        base = load_model(name)
        model = base.with_params(**params) if params else base
        branch = 0 if name == "diatomic-fput" else None
        for _ in range(4):
            k, a = float(rng.uniform(0.3, 2.9)), float(rng.uniform(0.02, 0.3))
            for N in (64, 256, None):
                res, qs = [], None
                for fn in (old_kernel, new):
                    kernel.sideband_modes = fn  # ``_exact`` imports it at each call
                    e = exact_gain(model.with_params(), k, a, branch, N=N)
                    res.append((e.peak_gain, e.fastest_offset, e.truncations))
                    if N is not None and qs is None:
                        i = int(np.argmax(e.gain))
                        qs = [float(e.offsets[i]), *rng.uniform(1e-3, math.pi, 3)]
                        ring = dict(zip(e.offsets[[i]], e.gain[[i]]))
                    for q in qs or ():
                        one = hill_spectrum(e.wave, [q])
                        alone.append((fn is new, e, q, ring, one.gain[0], one.truncations[0]))
                kernel.sideband_modes = new
                n += 1
                g0, g1 = res[0][0], res[1][0]
                rel = abs(g0 - g1) / abs(g0) if g0 else abs(g1)
                worst = max(worst, rel)
                same = ((math.isnan(res[0][1]) and math.isnan(res[1][1]))
                        or res[0][1] == res[1][1])
                if rel > 1e-12 or not same or res[0][2] != res[1][2]:
                    moved += 1
                    print(f"{name} {params} k {k:.4f} a {a:.4f} N {N}: {res[0]} -> {res[1]}")
    print(f"{n} points: worst relative peak-gain change {worst:.2e}; {moved} with a change "
          "above 1e-12, another fastest offset or other truncations")
    # tolerance 1e-9 relative (1e-12 of omega absolute): Newton and eig settle the same
    # root to ~1e-12; a lost or extra mode moves the rate by O(1)
    off, worst1 = 0, 0.0
    for mine, e, q, ring, g, P in alone:
        dense = hill_spectrum(e.wave, [q], harmonics=P).gain[0]
        refs = [dense] + ([ring[q]] if q in ring else [])
        for ref in refs:
            rel = abs(g - ref) / max(abs(ref), 1e-12 * e.wave.omega / 1e-9)
            worst1 = max(worst1, rel)
            if rel > 1e-9:
                off += 1
                print(f"{'this' if mine else 'baseline'} kernel, {e.wave.model.lattice.name}"
                      f" k {e.wave.k:.4f} a {e.wave.amplitude:.4f} q {q:.4f} alone: {g} "
                      f"against {ref}")
    print(f"{len(alone)} single-offset calls: worst relative change against the ring's and "
          f"the dense rates {worst1:.2e}; {off} above 1e-9")


if __name__ == "__main__":
    main()
