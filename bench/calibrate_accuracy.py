"""Error constants C_m of the tol= model (numerics/_accuracy.py), measured.

e = C_m (w dt)^p (w T) with e the relative state error at T = 200 against srkn11b at
dt = 0.005, w the starting state's dominant frequency; at the paper's two points, a 10x
larger amplitude (strong MI: errors amplified, reported but not used) and two other
materials. ERROR_CONSTANTS keeps per method the largest C_m of the non-MI points.

    python -m bench.calibrate_accuracy
"""

from __future__ import annotations

import numpy as np

from common import paper
from numerics import Material, get_method, initial_condition, integrate
from numerics.lattice import ERROR_CONSTANTS, dominant_frequency

POINTS = {"blue II": (Material.paper("blue"), "coupled", paper.k("blue"), 1.0, True),
          "green I": (Material.paper("green"), "rotation", paper.k("green"), 1.0, True),
          "blue II, A0 = 10 (strong MI)": (Material.paper("blue"), "coupled", paper.k("blue"),
                                           10.0, False),
          "alpha 1.5, coupled": (Material(1.5, 0.05, 0.02), "coupled", 2 * np.pi * 100 / 500,
                                 5.0, True),
          "alpha 3.5, rotation": (Material(3.5, 0.01, 0.03), "rotation",
                                  2 * np.pi * 200 / 500, 3.0, True)}
STEPS = {"rk4": [0.1, 0.05, 0.025], "verlet": [0.05, 0.025, 0.0125],
         "srkn6b": [0.2, 0.1, 0.05], "srkn11b": [0.4, 0.2, 0.1],
         "kahanli8": [0.4, 0.2, 0.1]}
T = 200.0


def main():
    worst = {m: 0.0 for m in STEPS}
    for label, (mat, case, k, A0, used) in POINTS.items():
        s0 = initial_condition(mat, case, 500, k, A0=A0)
        ref = integrate(s0, mat, case, T, 0.005, "srkn11b")
        w = dominant_frequency(s0)
        scale = np.max(np.abs(ref.theta))
        print(f"{label}: w = {w:.4f}")
        for name, dts in STEPS.items():
            p = get_method(name).order
            cs = []
            for dt in dts:
                s = integrate(s0, mat, case, T, dt, name, energy_tolerance=1.0)
                e = np.max(np.abs(s.theta - ref.theta))
                if s.U is not None:
                    e = max(e, np.max(np.abs(s.U - ref.U)))
                cs.append(e / scale / ((w * dt) ** p * w * T))
            print(f"  {name:8} C = " + ", ".join(f"{c:.3g}" for c in cs))
            if used:
                worst[name] = max(worst[name], max(cs))
    print("largest C_m of the non-MI points:", {m: float(f"{c:.2g}") for m, c in worst.items()})
    print("numerics.lattice._accuracy.ERROR_CONSTANTS:", ERROR_CONSTANTS)


if __name__ == "__main__":
    main()
