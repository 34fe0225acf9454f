"""`python -m derivation.table`: the NLS coefficients at the paper's two test points.

Uses only the generated module (no SymPy work), so it is instant.
"""

from __future__ import annotations

import sys

from generated import coefficients as co

from ._report import TEST_POINTS

CASES = {"rotation": (co.g2_rotation, co.g_rotation), "coupled": (co.g2_coupled, co.g_coupled)}


def rows(A0: float = 1.0):
    """One dict per (point, case) with omega, v_g, g1, g2, g, K_c, K_m, verdict."""
    out = []
    for point, p in TEST_POINTS.items():
        for case, (g2f, gf) in CASES.items():
            g = float(gf(**p))
            unstable = g > 0
            out.append({
                "point": point, "case": case, "k": p["k"], "delta": p["K_s"] - p["K_theta"],
                "omega": float(co.omega(**p)), "v_g": float(co.group_velocity(**p)),
                "g1": float(co.g1(**p)), "g2": float(g2f(**p)), "g": g,
                "K_c": float(co.mi_cutoff(g, A0)) if unstable else float("nan"),
                "K_m": float(co.mi_fastest(g, A0)) if unstable else float("nan"),
                "verdict": "MI (focusing)" if unstable else "stable (defocusing)",
            })
    return out


def format_table(A0: float = 1.0) -> str:
    cols = ["point", "case", "k", "delta", "omega", "v_g", "g1", "g2", "g", "K_c", "K_m",
            "verdict"]
    lines = [f"NLS coefficients at the paper's test points (alpha = 2.5, K_s = 0.01851, "
             f"A0 = {A0}; K in NLS units, sideband offset eps*K)", ""]
    table = [cols]
    for r in rows(A0):
        table.append([r[c] if isinstance(r[c], str) else f"{r[c]:.5g}" for c in cols])
    widths = [max(len(row[i]) for row in table) for i in range(len(cols))]
    for j, row in enumerate(table):
        lines.append("  ".join(cell.rjust(w) for cell, w in zip(row, widths)))
        if j == 0:
            lines.append("  ".join("-" * w for w in widths))
    return "\n".join(lines)


if __name__ == "__main__":
    A0 = float(sys.argv[1]) if len(sys.argv) > 1 else 1.0
    print(format_table(A0))
