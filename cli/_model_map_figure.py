"""The figure of a model's map (``flexmm map --model``): one panel per verdict variable, a
lossy map's critical-damping curves and observable contour."""

from __future__ import annotations

from pathlib import Path

#: the amplification a lossy map's figure marks observable (the runs' growth threshold)
OBSERVABLE = 20.0


#: the critical-damping curves of the other theories on a panel (its own: black)
CRITICAL_COLOURS = {"semidiscrete": "#1a9850", "fourwave": "#5e3c99", "exact": "#b2182b",
                    "simulated": "white"}

#: the theories' panels, in the order the figure draws them and the map prints them
PANELS = {"verdict_paper": "the paper's continuum NLS",
          "verdict_semidiscrete": "semi-discrete NLS",
          "verdict_fourwave": "four-wave",
          "verdict_exact": "exact lattice",
          "verdict_paper_start": "exact lattice, paper start (eq. IC)",
          "verdict_simulated": "simulated (MI: grew 20x)"}
VERDICT_ORDER = tuple(PANELS)


def _plot_map(ds, path: Path, model):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import numpy as np
    from matplotlib.colors import ListedColormap

    ydim, xdim = ds["verdict_semidiscrete"].dims
    x, y = ds[xdim].values, ds[ydim].values

    critical = {str(ds[n].attrs["theory"]): ds[n] for n in ds.data_vars
                if n.startswith("critical_")}
    damping = next(iter(critical.values())).attrs["damping_axis"] if critical else None
    # a damping axis over a decade or more: drawn in log scale (where MI hides, issue 42)
    logs = {d for d, v in ((xdim, x), (ydim, y)) if d == damping and v.size > 1
            and v.min() > 0 and v.max() >= 10 * v.min()}

    def edges(v, dim):
        if dim in logs:
            mid = np.sqrt(v[1:] * v[:-1]) if v.size > 1 else v
            return np.concatenate([[v[0] ** 2 / mid[0]], mid, [v[-1] ** 2 / mid[-1]]])
        if v.size == 1:
            e = np.array([v[0] - 0.5, v[0] + 0.5])
        else:
            mid = (v[1:] + v[:-1]) / 2
            e = np.concatenate([[2 * v[0] - mid[0]], mid, [2 * v[-1] - mid[-1]]])
        # a carrier's k lies in (0, pi]: its cells are drawn there only (the edges clipped)
        return np.clip(e, 0.0, np.pi) if dim == "k" else e

    code = {"stable": 0, "MI": 1, "undefined": 2}
    panels = [(v, PANELS[v]) for v in VERDICT_ORDER if v in ds]
    code = {**code, "no growth within T": 0, "undetermined": 2}
    # one row of panels, what they share said once above them; fixed margins (a tight
    # layout measures every text first: a third of the drawing's time, measured)
    import textwrap

    width = max(4.2 * len(panels), 6.0)
    fixed = ", ".join(f"{p} = {v:g}" for p, v in model.params.items() if p not in (xdim, ydim))
    runs_amplified = "observable_simulated" in ds  # a lossy model's runs (issue 42)
    marks = any(n.replace("verdict_", "amplification_") in ds for n, _ in panels)
    title = textwrap.wrap(
        f"{model.name}" + (f" ({fixed})" if fixed else "")  # all swept: none
        + (f", a = {ds.attrs['amplitude']:g}" if "amplitude" not in ds.dims else "")
        + ": orange MI, blue stable, grey undefined"
        + (f"; x: amplification >= {OBSERVABLE:g}x (observable with losses)" if marks else "")
        + (f"; line: critical {damping}, amplification {OBSERVABLE:g}x" if critical else ""),
        int(width * 14))  # ~14 characters of 10-point text an inch
    height = 4.2 + 0.18 * len(title)
    # the panels share their axes: the y ticks and label drawn once (a third less text to
    # lay out, measured)
    fig, axes = plt.subplots(1, len(panels), figsize=(width, height), squeeze=False, dpi=100,
                             sharex=True, sharey=True)
    fig.subplots_adjust(left=0.9 / width, right=1 - 0.2 / width, bottom=0.6 / height,
                        top=1 - (0.45 + 0.18 * len(title)) / height, wspace=0.12)
    fig.suptitle("\n".join(title), fontsize=10)
    for ax, (name, label) in zip(axes[0], panels):
        V = np.vectorize(lambda s: code.get(s, 2))(ds[name].values)
        if name == "verdict_simulated" and runs_amplified:
            # runs that stop once A(t) has halved: their rate rule reads the decay, so the
            # panel shows what they measure, whether the sidebands grew 20x (-1: no run)
            V = np.choose(np.asarray(ds["observable_simulated"].values, int) + 1, [2, 0, 1])
            label = f"simulated with losses (orange: grew {OBSERVABLE:g}x)"
        ax.pcolormesh(edges(x, xdim), edges(y, ydim), V,
                      cmap=ListedColormap(["#3b4cc0", "#f2a134", "#bbbbbb"]),
                      vmin=-0.5, vmax=2.5, shading="flat")
        amp = name.replace("verdict_", "amplification_")
        marked = amp in ds  # a lossy model's map: the cells whose sidebands grow 20x
        if marked:
            X, Y = np.meshgrid(x, y)
            seen = np.asarray(ds[amp].values, float) >= OBSERVABLE
            ax.scatter(X[seen], Y[seen], marker="x", color="black", s=30)
        own = name.replace("verdict_", "")
        for theory, crit in critical.items():  # the critical damping per value of the other
            other = crit.dims[0]
            vals = ds[other].values
            xs, ys = (vals, crit.values) if other == xdim else (crit.values, vals)
            mine = theory == own
            ax.plot(xs, ys, "-o" if mine else "--", lw=2 if mine else 1,
                    color="black" if mine else CRITICAL_COLOURS.get(theory, "0.3"),
                    ms=3 if mine else 0, label=f"critical {damping}, {theory}"
                    + (" (this panel)" if mine else ""))
        if critical:
            ax.legend(fontsize=6, loc="best")
        for d, setter in ((xdim, ax.set_xscale), (ydim, ax.set_yscale)):
            if d in logs:
                setter("log")
        ax.set_xlabel(xdim + (" (rad/site)" if xdim == "k" else ""))
        if ax is axes[0][0]:
            ax.set_ylabel(ydim + (" (rad/site)" if ydim == "k" else ""))
        ax.set_title(label + (" (x: observable)" if marked else ""), fontsize=10)
    fig.savefig(path)
    plt.close(fig)
