"""`flexmm map --model`: a model's map over two axes (the NLS per cell; the exact theory
with --exact; runs of the ring per cell, journalled, without --theory-only)."""

from __future__ import annotations

import json
from pathlib import Path

from .models import _emit, branch_of, load


# ------------------------------------------------------------------ map
def run_map(args) -> int:
    import numpy as np

    from numerics.maps import parse_spec
    from numerics.models import model_map

    model, axes = load(args, axes_ok=True)
    k_axis = None
    k_fixed = None
    if args.k is not None:
        vals = parse_spec(args.k, "--k")
        if vals.size > 1:
            k_axis = vals
        else:
            k_fixed = float(vals[0])
    named = list(axes.items()) + ([("k", k_axis)] if k_axis is not None else [])
    if len(named) != 2:
        raise ValueError(f"a model map sweeps two axes: --k SPEC and/or --param NAME=SPEC "
                         f"(SPEC v1,v2,... or start:stop:num); got {len(named)}: "
                         f"{', '.join(n for n, _ in named) or 'none'}")
    if k_axis is None and k_fixed is None:
        raise ValueError("--k: give the carrier wavenumber (one value, or a SPEC to sweep)")
    simulated = not getattr(args, "theory_only", False)
    unused = sorted(set(getattr(args, "given", ())) & {"--scheduler", "--workers", "--block",
                                                         "--timeout", "--yes", "--start"})
    if unused:
        raise ValueError(f"{', '.join(unused)}: a --model map runs its cells in this process "
                         "from the exact wave (they act on the paper chain's maps); drop them")
    if not simulated and ("--seeds" in getattr(args, "given", ())
                          or "--t-end" in getattr(args, "given", ())):
        raise ValueError("--seeds and --t-end act on a simulated model map: drop them, or "
                         "--theory-only")
    amp = args.amplitude
    from energy import check_value

    if check_value("--amplitude", amp) <= 0:
        raise ValueError(f"--amplitude must be > 0, got {amp!r}")
    if args.exact or simulated:  # the ring the exact theory and the runs use
        from numerics.models import check_ring

        try:
            check_ring(args.N)
        except ValueError as exc:
            raise ValueError(f"--N: {exc}") from None
    x, y = (named[1], named[0]) if named[0][0] == "k" else (named[0], named[1])
    if y[0] == "k":
        x, y = y, x
    exact = None
    if args.exact:
        from energy import ModelError
        from numerics.models import exact_gain_checked as exact_gain

        def exact(m, k, a, branch):
            # the command's own arguments were checked above: a ModelError here is this
            # cell's (no travelling wave at these values)
            try:
                spec = exact_gain(m, k, a, branch, N=args.N)
            except ModelError:
                return "undefined", float("nan")
            return spec.verdict, spec.peak_gain

    cell = done = on_cell = None
    out = Path(args.out)
    if simulated:  # each cell: the exact theory and runs of the ring, journalled
        from numerics.models import simulated_cell

        if args.exact:
            raise ValueError("--exact: a simulated model map has the exact lattice theory "
                             "per cell already")
        exact = None
        seeds, N = args.seeds, args.N
        if isinstance(seeds, bool) or not isinstance(seeds, int) or seeds < 1:
            raise ValueError(f"--seeds must be an integer >= 1, got {seeds!r}")
        t_end = args.t_end if "--t-end" in getattr(args, "given", ()) else None
        if t_end is not None and not (isinstance(t_end, (int, float)) and 0 < t_end < 1e12):
            raise ValueError(f"--t-end must be a finite time > 0, got {t_end!r}")

        def cell(m, k, a, branch):
            return simulated_cell(m, k, a, branch, N=N, seeds=seeds, t_end=t_end)

        head = {"model": model.name, "model_hash": model.lattice.content_hash,
                "parameters": dict(model.params), "amplitude": amp, "branch": str(args.branch),
                "axes": {x[0]: list(map(float, x[1])), y[0]: list(map(float, y[1]))},
                "k": k_fixed, "N": N, "seeds": seeds, "t_end": t_end}
    import contextlib

    from numerics.maps import store_lock

    journal = out / JOURNAL
    if simulated:
        out.mkdir(parents=True, exist_ok=True)  # removed again if the command fails empty
    with (store_lock(journal) if simulated else contextlib.nullcontext()):
        if simulated:
            done, on_cell = _journal(journal, head, args.overwrite)
        ds = model_map(model, x, y, amp, k=k_fixed, branch=branch_of(args), exact=exact,
                       cell=cell, done=done, on_cell=on_cell,
                       progress=None if simulated else False)
    mi = {v: float(np.mean(ds[v].values == "MI")) for v in ds.data_vars
          if v.startswith("verdict_")}
    out.mkdir(parents=True, exist_ok=True)
    nc = out / "map.nc"
    ds.to_netcdf(nc)
    png = out / "map.png"
    _plot_map(ds, png, model)
    if args.json:
        _emit({"model": model.name, "parameters": dict(model.params), "amplitude": amp,
               "axes": {x[0]: list(map(float, x[1])), y[0]: list(map(float, y[1]))},
               "mi_share": mi, "files": [str(nc), str(png)]})
        return 0
    fixed = ", ".join(f"{p} = {v:g}" for p, v in model.params.items()
                      if p not in (x[0], y[0]))
    print(f"model: {model.name} ({fixed}); amplitude {amp:g}; {y[0]} x {x[0]} = "
          f"{len(y[1])} x {len(x[1])} cells")
    for v, share in mi.items():
        print(f"MI share, {v.replace('verdict_', '')}: {share:.0%}")
    print(f"wrote {nc} and {png}")
    return 0


#: A simulated model map's journal in OUT: a header naming the map, one line per cell.
JOURNAL = "map.cells.jsonl"


def _line_sum(head_sum: str, i, j, columns) -> str:
    import hashlib

    text = json.dumps([head_sum, i, j, columns], sort_keys=True, allow_nan=True)
    return hashlib.sha256(text.encode()).hexdigest()[:32]


def _cell_record(head_sum: str, rec, shape):
    """(i, j, columns) of a journal line whose checksum and form hold, else None."""
    if not isinstance(rec, dict) or set(rec) != {"i", "j", "columns", "sum"}:
        return None
    i, j, cols = rec["i"], rec["j"], rec["columns"]
    if not (type(i) is int and type(j) is int and 0 <= i < shape[0] and 0 <= j < shape[1]):
        return None
    if not (isinstance(cols, dict) and cols and all(
            isinstance(k, str) and (v is None or type(v) in (int, float, str))
            for k, v in cols.items())):
        return None
    if rec["sum"] != _line_sum(head_sum, i, j, cols):
        return None
    return i, j, cols


def _journal(path: Path, head: dict, overwrite: bool):
    """(cells done, on_cell) of a simulated model map's journal ``path``: a header naming
    the map, then one JSON line per finished cell with its checksum (of the header and the
    line), each written and flushed whole. An interrupted map keeps every finished cell and
    the same command resumes it. The file is made with the first finished cell, so a
    refused or interrupted command before it leaves nothing behind; a line that fails its
    checksum or its form (torn, edited) is computed again, and said. A journal of another
    map is refused unless ``overwrite``, except one that holds no cell (nothing to lose)."""
    import hashlib
    import os

    head_text = json.dumps({"map": head}, allow_nan=False, sort_keys=True)
    head_sum = hashlib.sha256(head_text.encode()).hexdigest()
    axes = list(head["axes"].values())
    shape = (len(axes[1]), len(axes[0]))
    done = {}
    if path.exists():
        raw = path.read_bytes()
        lines = raw.decode("utf-8", errors="replace").split("\n")
        try:
            first = json.loads(lines[0])
        except ValueError:
            first = None
        records = []
        for line in lines[1:]:
            if not line.strip():
                continue
            try:
                records.append(json.loads(line))
            except ValueError:
                records.append(None)
        same = first == json.loads(head_text)
        if not same:
            if records and not overwrite:
                raise ValueError(f"{path} holds another map (or is damaged); "
                                 "replace it with --overwrite, or choose another --out")
            path.unlink()
        else:
            bad = 0
            for rec in records:
                cell = _cell_record(head_sum, rec, shape)
                if cell is None:
                    bad += 1
                    continue
                done[cell[:2]] = cell[2]
            if bad:
                print(f"note: {bad} line(s) of {path} failed their checksum or form (torn or "
                      "edited): those cells are computed again")
            # rewrite the journal from what holds (atomically), so later appends follow a
            # clean last line
            from common.files import write_text

            write_text(path, head_text + "\n" + "".join(
                json.dumps({"i": i, "j": j, "columns": c,
                            "sum": _line_sum(head_sum, i, j, c)}) + "\n"
                for (i, j), c in sorted(done.items())))
            if done:
                print(f"resuming {path}: {len(done)} cells already done")

    def on_cell(i, j, columns):
        if not path.exists():
            path.parent.mkdir(parents=True, exist_ok=True)
            from common.files import write_text

            write_text(path, head_text + "\n")
        line = json.dumps({"i": i, "j": j, "columns": columns,
                           "sum": _line_sum(head_sum, i, j, columns)})
        with open(path, "a", encoding="utf-8") as fh:
            fh.write(line + "\n")
            fh.flush()
            os.fsync(fh.fileno())

    return done, on_cell


def journal_cells(out) -> int | None:
    """How many finished cells the model map journal in ``out`` keeps (None: no journal)."""
    path = Path(out) / JOURNAL
    try:
        lines = path.read_text(encoding="utf-8", errors="replace").splitlines()
    except OSError:
        return None
    return max(0, sum(1 for line in lines[1:] if line.strip()))


def _plot_map(ds, path: Path, model):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import numpy as np
    from matplotlib.colors import ListedColormap

    ydim, xdim = ds["verdict_semidiscrete"].dims
    x, y = ds[xdim].values, ds[ydim].values

    def edges(v, dim):
        if v.size == 1:
            e = np.array([v[0] - 0.5, v[0] + 0.5])
        else:
            mid = (v[1:] + v[:-1]) / 2
            e = np.concatenate([[2 * v[0] - mid[0]], mid, [2 * v[-1] - mid[-1]]])
        # a carrier's k lies in (0, pi]: its cells are drawn there only (the edges clipped)
        return np.clip(e, 0.0, np.pi) if dim == "k" else e

    code = {"stable": 0, "MI": 1, "undefined": 2}
    panels = [(v, label) for v, label in (("verdict_semidiscrete", "semi-discrete NLS"),
                                          ("verdict_exact", "exact lattice"),
                                          ("verdict_simulated", "simulated (MI: grew 20x)"))
              if v in ds]
    code = {**code, "no growth within T": 0, "undetermined": 2}
    fig, axes = plt.subplots(1, len(panels), figsize=(6 * len(panels), 4.5), squeeze=False)
    fixed = ", ".join(f"{p} = {v:g}" for p, v in model.params.items() if p not in (xdim, ydim))
    for ax, (name, label) in zip(axes[0], panels):
        V = np.vectorize(lambda s: code.get(s, 2))(ds[name].values)
        ax.pcolormesh(edges(x, xdim), edges(y, ydim), V,
                      cmap=ListedColormap(["#3b4cc0", "#f2a134", "#bbbbbb"]),
                      vmin=-0.5, vmax=2.5, shading="flat")
        ax.set_xlabel(xdim + (" (rad/site)" if xdim == "k" else ""))
        ax.set_ylabel(ydim + (" (rad/site)" if ydim == "k" else ""))
        ax.set_title(f"{model.name}" + (f" ({fixed})" if fixed else "")  # all swept: none
                     + f", a = {ds.attrs['amplitude']:g}: {label}\n"
                     "orange MI, blue stable, grey undefined", fontsize=9)
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    plt.close(fig)
