"""`flexmm table`: the NLS coefficients at the paper's two test points (instant: the
generated module only, no SymPy work)."""

from __future__ import annotations

import math

from common import paper
from numerics import Material, nls_summary

COLUMNS = ("point", "case", "k", "delta", "omega", "v_g", "g1", "g2", "g", "K_c", "K_m",
           "verdict")


def rows(A0: float = paper.A0):
    """One dict per (point, case) with omega, v_g, g1, g2, g, K_c, K_m, verdict."""
    out = []
    for point in paper.POINTS:
        for case in ("rotation", "coupled"):
            s = nls_summary(Material.paper(point), case, paper.k(point), paper.EPS, A0)
            out.append({"point": point, "case": case, "k": paper.k(point),
                        "delta": paper.delta(point), **s,
                        "K_c": s.get("K_c", float("nan")), "K_m": s.get("K_m", float("nan")),
                        "verdict": "stable (defocusing)" if s["stable"] else "MI (focusing)"})
    return out


def format_table(A0: float = paper.A0) -> str:
    lines = [f"NLS coefficients at the paper's test points (alpha = {paper.ALPHA}, K_s = "
             f"{paper.K_S}, A0 = {A0}; K in NLS units, sideband offset eps*K)", ""]
    table = [list(COLUMNS)]
    for r in rows(A0):
        # "-" where a value does not exist (K_c, K_m of a stable point), as `coefficients`
        table.append([r[c] if isinstance(r[c], str) else
                      f"{r[c]:.5g}" if math.isfinite(r[c]) else "-" for c in COLUMNS])
    widths = [max(len(row[i]) for row in table) for i in range(len(COLUMNS))]
    for j, row in enumerate(table):
        lines.append("  ".join(cell.rjust(w) for cell, w in zip(row, widths)))
        if j == 0:
            lines.append("  ".join("-" * w for w in widths))
    lines += ["", _which_nls(A0)]
    return "\n".join(lines)


def _which_nls(A0: float) -> str:
    """The line under the table: these are the paper's continuum NLS, and where the
    semi-discrete one (the lattice's own, the default everywhere else) says otherwise
    (newuser99: the table named no NLS, and a user who then ran `point` at blue, case II
    read 'semi-discrete NLS: stable' against the table's 'MI (focusing)')."""
    from numerics.theory import nls_coefficients

    differ = []
    for point in paper.POINTS:
        co = nls_coefficients(Material.paper(point), paper.k(point), 2 * paper.EPS * A0)
        for case in ("rotation", "coupled"):
            mine = co["semi-discrete"][case]["verdict"]
            if mine != co["continuum (paper)"][case]["verdict"]:
                differ.append(f"{point} {case}: {mine}")
    return ("these are the paper's continuum NLS (eq. NLS); the semi-discrete NLS, derived on "
            "the lattice (`flexmm coefficients`), "
            + (f"says otherwise at {', '.join(differ)}" if differ else "agrees on every verdict")
            + "; `flexmm point` asks the exact lattice")
