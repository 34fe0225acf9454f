"""point.png of a model point (``flexmm point --model``): the same figure as the paper
chain's point (``cli.point._figure``), one gain curve per theory over the sideband offset
Q = |q - k|, and the measured sigma(Q) where the ring was run (the curves are
``numerics.maps``'s, in point.json)."""

from __future__ import annotations

import math

import numpy as np


def figure(model, out, curves, measured, seeds, simulate) -> bytes:
    """point.png's bytes: each theory's gain over the offset, the measured sigma(Q) with its
    spread; what is missing is said on the axes (as the paper chain's figure does)."""
    from scenes import plt

    fig, ax = plt.subplots(figsize=(7, 4), layout="constrained")
    if measured:
        ax.errorbar(measured["offset"], measured["sigma_by_offset"],
                    yerr=measured["std_by_offset"], fmt=".", ms=3, lw=0.5,
                    label=f"simulated ({measured['seeds']} of {seeds} seeds unstable)")
    styles = {"semi-discrete NLS": "k--", "exact lattice": "C3-", "four-wave": "C2:",
              "exact lattice, paper start": "C1-."}
    tops = []
    for name, c in curves.items():
        y = np.array([np.nan if v is None else v for v in c["curve"]], float)
        label = f"{name} (theory" + (f"; {len(c['copy_of'])} Hill copies +-q + l k left out"
                                     if c.get("copy_of") else "") + ")"
        ax.plot(c["offset"], y, styles.get(name, "C0-"), lw=1, label=label)
        if np.any(np.isfinite(y)):
            tops.append(float(np.nanmax(y)))
    if measured:
        tops.append(float(np.max(measured["sigma_by_offset"])))
    # with losses a sideband grows where its rate beats its damping (near k: the carrier's)
    damping = next((out[n]["carrier_damping"] for n in ("exact lattice", "semi-discrete NLS")
                    if isinstance(out.get(n, {}).get("carrier_damping"), (int, float))
                    and out[n]["carrier_damping"] > 0), None)
    if damping is not None:
        ax.axhline(damping, color="0.4", lw=0.8, ls="-.",
                   label=f"carrier damping {damping:.3g} (losses: a sideband near k grows "
                         "only above it)")
        tops.append(damping)
    top = max([v for v in tops if math.isfinite(v)], default=0.0)
    missing = [f"{n}: {out[n]['reason']}" for n in ("semi-discrete NLS", "exact lattice",
                                                    "four-wave", "exact lattice, paper start")
               if n in out and out[n].get("reason") and n not in curves]
    if simulate and not measured:
        missing.append("simulated: no run grew (" + out["simulated"]["text"] + ")"
                       if "simulated" in out else "simulated: not run")
    if missing:
        ax.text(0.02, 0.97, "\n".join(missing), transform=ax.transAxes, va="top",
                fontsize=7, wrap=True, bbox=dict(facecolor="w", edgecolor="0.7"))
    if top > 0:
        ax.set_ylim(-0.1 * top, 1.4 * top)
    else:
        ax.set_ylim(-1, 1)
        ax.text(0.5, 0.6, "stable: no growing sideband in any theory drawn"
                + (" or the simulation" if measured else ""), transform=ax.transAxes,
                ha="center", fontsize=10)
    ax.set_xlim(0, math.pi)
    ax.set_xlabel(r"sideband offset $Q = |q - k|$ (rad/site): sidebands at $k \pm Q$")
    ax.set_ylabel(r"growth rate $\sigma$ (1/time)")
    params = ", ".join(f"{n} = {v:g}" for n, v in out["parameters"].items())
    ax.set_title(f"{out['model']}" + (f" ({params})" if params else "")
                 + f"\n$k$ = {out['k']:.4g} rad/site, branch {out['branch']} "
                 f"({out['field']}), amplitude a = {out['amplitude']:g}", fontsize=9)
    if ax.get_legend_handles_labels()[0]:
        ax.legend(fontsize=7)
    import io

    buf = io.BytesIO()
    fig.savefig(buf, format="png", dpi=110)
    plt.close(fig)
    return buf.getvalue()
