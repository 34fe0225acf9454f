"""Would advancing several cells in one compiled call pay? An upper bound, measured.

A block's cells share the material (one delta) and differ in k: B chains of N sites could
be stepped in one fused pass over B N sites (per-chain boundaries aside). What such a pass
would save is the fixed cost per pass over N sites; it is bounded by the cost per site per
force evaluation of one chain of N sites against one chain of B N sites (the same loop,
its fixed cost spread over B times the sites). srkn11b, case II, N = 500, B = 4,
interleaved medians.

    python -m bench.batching
"""

from __future__ import annotations

import numpy as np

from bench.speed import interleaved
from common import paper
from numerics import Material, initial_condition
from numerics.lattice import Stepper, get_method


def main(N=500, B=4, T=200.0, dt=0.96, rounds=7):
    mat = Material.paper("blue")
    m = get_method("srkn11b")
    nsteps = int(round(T / dt))
    states = {n: initial_condition(mat, "coupled", n, 2 * np.pi * round(n * paper.k("blue")
                                                                        / (2 * np.pi)) / n)
              for n in (N, B * N)}

    def run(n):
        return lambda: Stepper(states[n], mat, "coupled", m, dt).advance(nsteps)

    configs = {f"{B} chains of {N} in turn": lambda: [run(N)() for _ in range(B)],
               f"one chain of {B * N}": run(B * N)}
    for f in configs.values():
        f()
    med = interleaved(configs, rounds)
    per_site = {k: t / (B * N * nsteps * m.evaluations) * 1e9 for k, t in med.items()}
    a, b = per_site.values()
    print("srkn11b, case II, ns per site per force evaluation: " + ", ".join(
        f"{k} {v:.2f}" for k, v in per_site.items()) + f"; one call would save at most "
        f"{100 * (1 - b / a):.0f}% of the stepping")
    return {"ns_per_site_per_evaluation": per_site, "largest_saving": 1 - b / a}


if __name__ == "__main__":
    main()
