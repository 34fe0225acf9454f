"""What ``flexmm map`` checks before its work: the cells a store already holds (both
maps), and for ``--model`` parameter values without a rest state, an axis by its option."""

from __future__ import annotations

from pathlib import Path


def check_rest(model, named) -> None:
    """Refuse, before any work, a parameter value of the axes (each combination, where
    both axes are parameters) at which the energy is not real or not finite at rest (a
    Hertz contact's d0 < 0): the model has no rest state there, and its cells would only
    be undefined, after NumPy's warnings; or at which the rest state is no minimum (a
    coupling of the wrong sign), as a point refuses it: a map called such cells MI at the
    NLS's slow rate, while the chain at rest is itself unstable. ~0.3 ms a value."""
    import itertools
    import warnings

    import numpy as np

    from energy import ModelError
    from numerics.models import check_rest_stable

    axes = [(n, v) for n, v in named if n in model.params]
    if not axes:
        return
    zero = np.zeros(2 * model.n_fields)
    with warnings.catch_warnings(), np.errstate(all="ignore"):
        warnings.simplefilter("ignore")
        for combo in itertools.product(*(v for _, v in axes)):
            values = {n: float(v) for (n, _), v in zip(axes, combo)}
            given = ", ".join(f"--param {n}={v:g}" for n, v in values.items())
            try:  # a damping of the wrong sign (R < 0): its value named (probe 96)
                m = model.with_params(**values)
                m.damping  # noqa: B018 (reading it checks R >= 0)
            except ModelError as exc:
                if "semi-definite" not in str(exc):
                    raise
                why = str(exc).split(": ", 1)[-1]
                raise ValueError(f"{given}: {why}; a damping must keep R >= 0 (a viscous "
                                 "coefficient >= 0): leave such values out of the axis"
                                 ) from None
            if (np.all(np.isfinite(np.asarray(m.code.cell_energy(zero, m.p))))
                    and np.all(np.isfinite(np.asarray(m.code.taylor(m.p)[0], float)))):
                try:
                    check_rest_stable(m)
                except ModelError as exc:
                    why = str(exc).split(": ", 1)[-1]  # past 'model NAME (values)'
                    raise ValueError(f"{given}: {why}; leave such values out of the "
                                     "axis") from None
                continue
            raise ValueError(f"{given}: the energy of {model.name} is not real at the rest "
                             "state (every field 0) there (a division by zero, or a square "
                             "root, log or fractional power of a quantity negative at rest?); "
                             "leave such values out of the axis")


def option(axis: str) -> str:
    """The option that gave a map's axis (a parameter's: --param NAME)."""
    return f"--{axis}" if axis in ("k", "amplitude") else f"--param {axis}"


def cells_done(out, params) -> tuple:
    """(cells done, cells) of this map in ``OUT/map.zarr``: done is simulated, or predicted
    for a theory-only map; 0 where the store holds another map (its identity attributes),
    none, or anything unreadable (the engine says what it is)."""
    import numpy as np
    import zarr

    from numerics import maps

    cells = int(np.prod(params.grid_shape))
    store = Path(out) / "map.zarr"
    try:
        attrs = dict(zarr.open_group(str(store), mode="r", use_consolidated=False).attrs)
        if any(attrs.get(n) != v for n, v in params.identity().items()):
            return 0, cells
    except Exception:  # no store, another format, a damaged one: the engine decides
        return 0, cells
    # the engine's reader: a garbled chunk is never decoded, whatever its bytes
    # and a cell counts where its checksum holds (a tampered one is computed again: the
    # estimate said "none needed" and 0 s before 2 cells ran 13.7 s)
    done = maps.cells_done(store, "done_predicted" if params.theory_only else "done",
                           params)
    return done if done is not None and done[1] == cells else (0, cells)


def branch_jumps(model, ks, branch, rows=None) -> str | None:
    """A note where ``--branch FIELD`` names a different branch index along the k axis
    (each k's carrier is the branch that field dominates there: across an avoided crossing
    it moves to another root, and the map's omega, g1 and verdicts jump with it), at the
    model's fixed values, or per value of ``rows`` = (parameter, values) where the other
    axis is a parameter (newuser 101: a two-field chain's map over eta and k gave the file's
    eta's index ranges and omegas for every row); None where the index holds, or the branch
    is an index (probe 100: a three-field hinge chain's theta carrier went from index 2 to
    1 to 0 over k, its frequency 1.05 -> 0.49 between k 2.2 and 2.4, and nothing said so)."""
    if branch is None or str(branch).lstrip("-").isdigit():
        return None
    if rows is not None and rows[0] in model.params:
        name, values = rows
        parts = [(v, _index_runs(model.with_params(**{name: float(v)}), ks, branch))
                 for v in values]
        parts = [(v, w) for v, w in parts if w]
        where = "; ".join(f"at {name} = {float(v):g}: {w}" for v, w in parts)
    else:
        where = _index_runs(model, ks, branch)
    if not where:
        return None
    return (f"the branch of field {branch} changes along k: {where}; each k's carrier is "
            f"the branch {branch} dominates there: across a crossing omega is continuous, "
            "across an avoided crossing the carrier moves to another root and omega, g1 "
            "and the verdicts jump (--branch INDEX follows one index)")


def _index_runs(model, ks, branch) -> str:
    """'index b at k lo to hi (omega w0 to w1), ...' along ``ks`` at the model's values, or
    '' where one index holds."""
    from energy import ModelError
    from numerics.models import carrier

    runs = []  # [index, first k, last k, omega at the first, omega at the last]
    for k in ks:
        try:
            c = carrier(model, float(k), branch)
        except (ModelError, ValueError):
            continue
        if runs and runs[-1][0] == c.branch:
            runs[-1][2], runs[-1][4] = float(k), c.omega
        else:
            runs.append([c.branch, float(k), float(k), c.omega, c.omega])
    if len(runs) < 2:
        return ""
    return ", ".join(f"index {b} at k {lo:g}" + (f" to {hi:g}" if hi != lo else "")
                     + f" (omega {w0:.4g}" + (f" to {w1:.4g})" if hi != lo else ")")
                     for b, lo, hi, w0, w1 in runs)
