"""The critical damping of a lossy model's map (issue 42, item 5): along a damping axis, where
a theory's (or the runs') amplification falls below the observable 20x, per value of the
other axis (k, or another parameter).

With losses the sidebands' growth is transient, and its largest factor A falls with the
damping gamma: the carrier's gain is spent within ~ 1 / Gamma, so ln A ~ c / gamma (the
integral of sigma0 e^{-2 Gamma t} - G along the decaying carrier, ``numerics.models``'
``_losses``). Between the two cells that bracket the crossing, ln(ln A) is therefore taken
linear in ln gamma (exact for that law, the log of an amplification against the log of the
damping); where the cell after the crossing has not grown at all (A <= 1: ln ln A undefined)
ln A is taken linear in ln gamma instead. Nothing is extrapolated: where the crossing is not
inside the axis the critical damping is nan, and the reason says which side it lies on.
"""

from __future__ import annotations

import math

import numpy as np

#: the amplification the critical damping is read at (the runs' 20x)
THRESHOLD = 20.0
#: the theories' largest amplification, e^700 (numerics.models' along_decay and damped
#: NLS: past it a factor is only a lower bound; probe 96)
CAP = math.exp(700.0)


def damping_parameters(lattice) -> tuple:
    """The parameters of ``lattice`` (``energy.Lattice``, or a ``Model``: its lattice) its
    [dissipation] functions use, sorted; () for a lossless model."""
    import ast

    from energy import Lattice, Model

    if isinstance(lattice, Model):
        lattice = lattice.lattice
    if not isinstance(lattice, Lattice):  # 'x' said: 'str' object has no attribute 'lossy'
        raise TypeError(f"lattice must be an energy.Lattice or Model (energy.parse_model, "
                        f"energy.load_model), got {type(lattice).__name__} {lattice!r}")
    if not lattice.lossy:
        return ()
    names = set()
    for key in lattice.dissipation:
        tree = lattice.tree("dissipation." + key)
        names |= {n.id for n in ast.walk(tree) if isinstance(n, ast.Name)}
    return tuple(sorted(names & set(lattice.parameters)))


def critical_damping(damping, amplification, threshold: float = THRESHOLD,
                     name: str = "damping") -> tuple[np.ndarray, list]:
    """The damping where ``amplification`` falls below ``threshold`` for good, per column.

    Parameters
    ----------
    damping : array, shape (n,)
        The damping axis (any order; values >= 0).
    amplification : array, shape (n, m)
        Amplification per cell, the damping along axis 0 (nan: no answer at that cell,
        left out; inf: an undamped growing mode).
    threshold : float
    name : str
        The damping's name, for the reasons.

    Returns
    -------
    critical : ndarray, shape (m,)
        Per column, the damping above which every cell of the axis stays below
        ``threshold``, interpolated between the two cells that bracket its last crossing
        (module docstring); nan where there is none inside the axis.
    reasons : list of str, length m
        Why a column's critical damping is nan ("" where it is not).
    """
    g = np.asarray(damping, float)
    A = np.asarray(amplification, float)
    if A.ndim != 2 or A.shape[0] != g.size:
        raise ValueError(f"amplification must have shape ({g.size}, m), got {A.shape}")
    order = np.argsort(g, kind="stable")
    g, A = g[order], A[order]
    critical = np.full(A.shape[1], np.nan)
    reasons = []
    for c in range(A.shape[1]):
        have = ~np.isnan(A[:, c])
        gc, ac = g[have], A[have, c]
        if gc.size < 2:
            reasons.append(f"fewer than two cells with an amplification ({gc.size})")
            continue
        above = ac >= threshold
        if above.all():
            reasons.append(f"at least {threshold:g}x over the whole axis: the critical "
                           f"{name} is above {gc[-1]:g}")
            continue
        if not above.any():
            reasons.append(f"below {threshold:g}x over the whole axis: the critical {name} "
                           f"is below {gc[0]:g}, or nothing grows")
            continue
        i = int(np.flatnonzero(above)[-1])
        if i == gc.size - 1:
            reasons.append(f"at least {threshold:g}x at the largest {name} {gc[-1]:g} "
                           "(below it somewhere inside the axis): the critical "
                           f"{name} is above {gc[-1]:g}")
            continue
        (g0, g1), (a0, a1) = gc[i:i + 2], ac[i:i + 2]
        if not (g0 > 0 and math.isfinite(a0)):
            reasons.append(f"crosses {threshold:g}x between {name} = {g0:g} (amplification "
                           f"{a0:g}) and {g1:g}: no log interpolation from there; add "
                           "values in between")
            continue
        if a0 >= CAP * (1 - 1e-9):  # a lower bound: ln ln A from it lands low (32% below)
            reasons.append(f"crosses {threshold:g}x between {name} = {g0:g} (amplification "
                           f"at least e^700, the theories' cap) and {g1:g}: no log "
                           "interpolation from a bound; add values in between")
            continue
        if a1 > 1:  # ln ln A linear in ln gamma
            y0, y1, y = math.log(math.log(a0)), math.log(math.log(a1)), math.log(
                math.log(threshold))
        else:  # the next cell did not grow: ln A linear in ln gamma
            y0, y1, y = math.log(a0), math.log(max(a1, 1e-300)), math.log(threshold)
        f = (y - y0) / (y1 - y0) if y1 != y0 else 0.0
        critical[c] = math.exp(math.log(g0) + f * (math.log(g1) - math.log(g0)))
        reasons.append("")
    return critical, reasons


def critical_variables(params, arrays: dict) -> dict:
    """Over a damping axis of the model map ``params`` (a ModelMapParameters),
    ``critical_<damping>_<theory>`` per value of the other axis, for each theory's
    amplification and, where cells were simulated, the runs' (``critical_<damping>_
    simulated``): the damping where the amplification falls below 20x
    (:func:`critical_damping`), nan where it does not cross inside the axis (the
    variable's ``reason`` attribute says why, per value). {} without a damping axis."""
    from ._model_axes import axis_attrs

    out = {}
    axis = params.damping_axis()
    if axis is None or not params.amplified():
        return out
    along = params.dims.index(axis)
    other = params.dims[1 - along]
    damping, values = params.axis_values()[along], params.axis_values()[1 - along]
    theories = list(params.amplified())
    if "amplification_simulated" in arrays and np.any(arrays["done"]):
        theories.append("simulated")
    for theory in theories:
        amp = np.asarray(arrays[f"amplification_{theory}"], float)
        done = np.asarray(arrays["done" if theory == "simulated" else "done_predicted"],
                          bool)
        amp = np.where(done, amp, np.nan)
        crit, why = critical_damping(damping, amp if along == 0 else amp.T, THRESHOLD,
                                     axis)
        reason = "; ".join(f"{other} = {v:g}: {w}" for v, w in zip(values, why) if w)
        out[f"critical_{axis}_{theory}"] = ((other,), crit, {
            "long_name": f"critical {axis}: where the {theory} amplification falls below "
                         f"{THRESHOLD:g}x for good along the {axis} axis (the sidebands "
                         "are not observable above it)",
            # the damping axis' unit (probe 98: the only float variable without one)
            "units": axis_attrs(axis)["units"],
            "damping_axis": axis, "theory": theory, "threshold": THRESHOLD,
            "interpolation": "between the two cells that bracket the crossing: "
                             "ln(ln A) linear in ln of the damping (ln A where the "
                             "next cell is <= 1); no extrapolation",
            "reason": reason or "every value crosses inside the axis"})
    return out
