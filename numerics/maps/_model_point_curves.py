"""The sigma(q) curves of a model point (``measure_point`` of a ``ModelPointSpec``): one gain
curve per theory over the sideband offset Q = |q - k|, each Floquet mode once, and the
measured sigma(Q) where the ring was run (``cli.model_figure`` draws them)."""

from __future__ import annotations

import math

import numpy as np

#: what the curves in point.json are (the model's own units: time as in the model file)
CURVES = ("theories: growth rate (1/time) over the sideband offset Q = |q - k| (rad/site), "
          "sidebands k +- Q; four-wave: the fastest pair's rate at each offset q; "
          "simulated: sigma per ring mode q (rfft bins 0 .. pi) and sigma_by_offset (the "
          "smaller of a pair's two sidebands)")


def curve(offset, gain) -> dict:
    offset, gain = np.asarray(offset, float), np.asarray(gain, float)
    return {"offset": offset.tolist(),
            "curve": [g if math.isfinite(g) else None for g in gain.tolist()]}


def _wrap(x: float) -> float:
    """x wrapped to (-pi, pi]."""
    return -((-x + math.pi) % (2 * math.pi) - math.pi)


def hill_copies(offsets, gain, k, own=None) -> dict:
    """Which unstable Hill offsets are copies of another: a Floquet mode at offset q is
    also an eigenvector at +-q + l k (its harmonics relabelled), with the same eigenvalue,
    so an exact gain curve over q shows each mode once per copy.

    The band holding ``own`` (the fastest mode's own offset, ``classify_mode``'s) is kept
    first, then the other bands from the carrier outwards; an unstable offset is a copy
    where +-q + l k (|l| <= 3) lands within half a grid step of a kept offset whose gain
    agrees to 2% (copies hold one eigenvalue; Hill's truncation at J harmonics, whose
    window a copy shifts by l, moves it by far less).

    Returns
    -------
    dict
        ``copy``: bool array, shape (n,), the offsets that are copies; ``copy_of``: the
        kept offset each copy repeats, in offset order; ``gain``: the gain with each kept
        offset at the largest of its copies' (one eigenvalue; they differ in rounding),
        so the curve's peak stays the spectrum's peak gain.
    """
    q, g = np.asarray(offsets, float), np.nan_to_num(np.asarray(gain, float), nan=0.0)
    grows = g > 0
    copy = np.zeros(q.size, bool)
    copy_of = []
    if not grows.any():
        return {"copy": copy, "copy_of": copy_of, "gain": g}
    g = g.copy()
    step = float(np.min(np.diff(np.sort(q)))) if q.size > 1 else 1e-9
    edges = np.flatnonzero(np.diff(np.concatenate([[0], grows.astype(int), [0]])))
    bands = [np.arange(a, b) for a, b in zip(edges[::2], edges[1::2])]
    if own is not None:  # the fastest mode's own band first
        bands.sort(key=lambda idx: 0 if np.min(np.abs(q[idx] - own)) <= step / 2 else 1)
    # the kept offsets by bin of width ``step``: a copy's candidates are the kept offsets
    # in the one or two bins its window of half a step touches (the earliest kept wins, as
    # a scan of the kept list in order would give), so a ring of 10^6 sites with 10^4
    # unstable offsets costs 10^4 look-ups, not 10^8 comparisons
    order = {}  # kept index -> its rank in the kept list
    bins: dict[int, list] = {}
    for idx in bands:
        for i in idx:
            match = None
            for x in {_wrap(s * (q[i] - ell * k)) for s in (1, -1) for ell in range(-3, 4)}:
                for y in (x - 2 * math.pi, x, x + 2 * math.pi):
                    for b in range(math.floor((y - step / 2) / step) - 1,  # -1, +1:
                                   math.floor((y + step / 2) / step) + 2):  # rounding
                        for j in bins.get(b, ()):
                            if ((match is None or order[j] < order[match])
                                    and abs(g[i] - g[j]) <= 0.02 * max(g[i], g[j])
                                    and any(abs(_wrap(q[i] - s * q[j] - ell * k)) <= step / 2
                                            for s in (1, -1) for ell in range(-3, 4))):
                                match = j
            if match is None:
                order[i] = len(order)
                bins.setdefault(math.floor(q[i] / step), []).append(i)
            else:
                copy[i] = True
                copy_of.append((float(q[i]), float(q[match])))
                g[match] = max(g[match], g[i])
    copy_of.sort()
    return {"copy": copy, "copy_of": [list(c) for c in copy_of], "gain": g}


def exact_curve(spec, k, own=None) -> dict:
    """The exact lattice's curve over the ring's offsets, each mode at its own offset
    once: its copies (``hill_copies``) are left out of the curve and listed in
    ``copy_of`` as [copy offset, kept offset] pairs."""
    cp = hill_copies(spec.offsets, spec.gain, k, own)
    keep = ~cp["copy"]
    gain = np.where(np.isfinite(spec.gain), cp["gain"], np.nan)  # NaN stays unknown
    out = curve(np.asarray(spec.offsets)[keep], gain[keep])
    out["copy_of"] = cp["copy_of"]
    if cp["copy_of"]:
        out["note"] = (f"{len(cp['copy_of'])} unstable offset(s) left out: copies +-q + l k "
                       "of a mode shown at its own offset (copy_of: [copy, kept] pairs); "
                       "one Floquet mode, one rate")
    return out


def model_theory_curves(model, k, amplitude, branch, N, spec, fw, own=None) -> dict:
    """{theory: {"offset": [...], "curve": [...]}}: the semi-discrete NLS on a fine grid
    of its band, the exact lattice (``spec``, a HillSpectrum on the ring, may be None) and
    the four-wave theory (``fw``, a FourWave) at the ring's offsets. ``own``: the exact
    fastest mode's own Hill offset, whose band is kept where copies repeat it."""
    from energy import ModelError

    from ..models import nls

    out = {}
    try:
        r = nls(model, k, branch)
        if not r.undefined:
            q = np.linspace(0.0, math.pi, 801)[1:]
            if r.verdict == "MI":  # the band is O(a) wide: resolve it
                edge = r.band_edge(amplitude)
                q = np.unique(np.concatenate([q, np.linspace(0.0, min(edge, math.pi),
                                                             201)[1:]]))
            out["semi-discrete NLS"] = curve(q, r.gain(q, amplitude))
    except ModelError:
        pass  # at k = pi: no NLS, said in its row
    if spec is not None:
        out["exact lattice"] = exact_curve(spec, k, own)
    if not fw.undefined:
        rates = np.max(np.nan_to_num(fw.rates, nan=0.0), axis=1) if fw.rates.size else \
            np.zeros(fw.offsets.size)
        if fw.verdict != "MI":  # every rate below the theories' floor: its verdict, stable
            rates = np.zeros_like(rates)
        out["four-wave"] = curve(fw.offsets, rates)
    return out


def simulated_curve(runs, k) -> dict | None:
    """sigma(q) of seeded runs of the ring (``numerics.models.ModelRun``): the log-slope of
    every ring mode over each unstable run's linear stage (from where its fastest mode
    has grown 10x to its end, ``measure_growth``'s window), mean and spread over those
    runs; None where no run was unstable."""
    from ..lattice import growth_rates
    from ._point import offset_curve

    rates = []
    for run in runs:
        g = run.growth()
        if g.verdict != "unstable":
            continue
        half = run.N // 2 + 1
        spec = run.spectrum[:, :half]
        end = int(np.searchsorted(run.t, g.t_linear))
        end = min(max(end, 4), len(run.t) - 1)
        i = int(np.argmax(spec[end]))
        above = np.nonzero(spec[:end + 1, i] > 10 * max(spec[0, i], 1e-300))[0]
        first = int(above[0]) if above.size else 0
        first = max(min(first, end - 3), 0)
        rates.append(growth_rates(run.t, spec, (first, end)))
    if not rates:
        return None
    rates = np.array(rates)
    spread = rates.std(axis=0, ddof=1) if len(rates) > 1 else np.zeros(rates.shape[1])
    N = runs[0].N
    q = 2 * math.pi * np.arange(N // 2 + 1) / N
    sigma = rates.mean(axis=0)
    Q, by_offset, std = offset_curve(q, sigma, spread, k)
    return {"q": q.tolist(), "sigma": sigma.tolist(), "sigma_std": spread.tolist(),
            "offset": Q.tolist(), "sigma_by_offset": by_offset.tolist(),
            "std_by_offset": std.tolist(), "seeds": len(rates)}
