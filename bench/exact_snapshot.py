"""``exact_gain``'s answers at seeded random points, saved by one tree and compared by
another: the check to run before and after each change to the exact theory (its wave, its
Hill kernel, its chain search), whose results must stay within 1e-6 relative (issue 41).

60 points, seeded (the same on every tree): fput (alpha in [0, 1], beta in [0.2, 2]),
diatomic-fput (branch 0), klein-gordon and sine-gordon in turn, k in [0.05, 1] pi,
amplitude in [0.02, 0.3], a ring of 64, 128 or 256 sites or the infinite chain. Saved per
point: the peak gain, the offsets and the gain, harmonic and sideband offset at each, the
truncations, the mode's name and the fastest offset (or the one-line error). Compared: the
peak gain (1e-6 relative, the issue's bar), the truncations, the mode's name, the fastest
offset (1e-6 relative), and on a ring the set of growing offsets, their harmonics and the
whole gain curve (1e-6 of the peak). Prints each point that differs and the worst peak
change. JSON, so a saved file is read without running code.

    python -m bench.exact_snapshot save /tmp/before.json      (on the tree before)
    python -m bench.exact_snapshot compare /tmp/before.json   (on the tree after)
"""

from __future__ import annotations

import json
import math
import sys

import numpy as np

from energy import load_model
from numerics.models import exact_gain

POINTS, SEED = 60, 20261126
MODELS = ("fput", "diatomic-fput", "klein-gordon", "sine-gordon")
#: the issue's bar: results within 1e-6 relative of the tree before
RTOL = 1e-6


def points():
    """The seeded points: (model, params, k, amplitude, branch, N or None)."""
    rng = np.random.default_rng(SEED)
    out = []
    for i in range(POINTS):
        name = MODELS[i % len(MODELS)]
        params = {}
        if name == "fput":
            params = dict(alpha=float(rng.uniform(0, 1)), beta=float(rng.uniform(0.2, 2)))
        k = float(rng.uniform(0.05, 1.0) * np.pi)
        a = float(rng.uniform(0.02, 0.3))
        N = (64, 128, 256, None)[int(rng.integers(0, 4))]
        out.append((name, params, k, a, 0 if name == "diatomic-fput" else None, N))
    return out


def _floats(x):
    return [None if not math.isfinite(v) else float(v) for v in np.asarray(x, float)]


def answers():
    """``exact_gain`` at every point, as JSON-ready dicts."""
    rows = []
    for name, params, k, a, branch, N in points():
        row = {"point": [name, params, k, a, branch, N]}
        model = load_model(name).with_params(**params) if params else load_model(name)
        try:
            s = exact_gain(model, k, a, branch, N=N)
        except Exception as exc:  # noqa: BLE001 (a point's error is part of its answer)
            row["error"] = f"{type(exc).__name__}: {exc}"
        else:
            row.update(peak=s.peak_gain, offsets=_floats(s.offsets), gain=_floats(s.gain),
                       harmonic=[int(h) for h in s.harmonic],
                       sideband_offset=_floats(s.sideband_offset),
                       truncations=list(s.truncations), mode=s.mode,
                       fastest_offset=_floats([s.fastest_offset])[0])
        rows.append(row)
    return rows


def differences(before, now):
    """What differs between two saved answers of one point (empty: within the bar)."""
    if "error" in before or "error" in now:
        same = before.get("error") == now.get("error")
        return [] if same else [f"error {before.get('error')!r} -> {now.get('error')!r}"]
    out = []
    p0, p1 = before["peak"], now["peak"]
    if abs(p1 - p0) > RTOL * abs(p0) + (0.0 if p0 else 1e-300):
        out.append(f"peak {p0:.9g} -> {p1:.9g}")
    if before["truncations"] != now["truncations"]:
        out.append(f"truncations {before['truncations']} -> {now['truncations']}")
    if before["mode"] != now["mode"]:
        out.append(f"mode {before['mode']!r} -> {now['mode']!r}")
    f0, f1 = before["fastest_offset"], now["fastest_offset"]
    if (f0 is None) != (f1 is None) or (f0 is not None and abs(f1 - f0) > RTOL * abs(f0)):
        out.append(f"fastest offset {f0} -> {f1}")
    if before["point"][5] is not None:  # a ring: the same offsets, curve by curve
        g0, g1 = np.array(before["gain"]), np.array(now["gain"])
        grows = g0 > 0
        if not np.array_equal(grows, g1 > 0):
            out.append(f"growing offsets differ at {np.flatnonzero(grows ^ (g1 > 0)).tolist()}")
            return out
        if p0 and np.max(np.abs(g1 - g0)) > RTOL * p0:
            out.append(f"gain curve moved by {np.max(np.abs(g1 - g0)) / p0:.2e} of the peak")
        h0, h1 = np.array(before["harmonic"]), np.array(now["harmonic"])
        if not np.array_equal(h0[grows], h1[grows]):
            out.append("harmonics of the growing offsets differ")
    return out


def main(argv=None):
    argv = sys.argv[1:] if argv is None else argv
    if len(argv) != 2 or argv[0] not in ("save", "compare"):
        raise SystemExit("usage: python -m bench.exact_snapshot save|compare FILE.json")
    what, path = argv
    rows = answers()
    if what == "save":
        with open(path, "w") as f:
            json.dump(rows, f)
        print(f"saved {len(rows)} points ({sum('error' in r for r in rows)} errors) to {path}")
        return
    with open(path) as f:
        before = json.load(f)
    bad, worst = 0, 0.0
    for b, r in zip(before, rows, strict=True):
        if "peak" in b and "peak" in r and b["peak"]:
            worst = max(worst, abs(r["peak"] - b["peak"]) / b["peak"])
        diff = differences(b, r)
        if diff:
            bad += 1
            print("DIFFERS", b["point"], "; ".join(diff))
    print(f"compared {len(rows)} points with {path}: {bad} differ; worst peak change "
          f"{worst:.2e} relative (bar {RTOL:g})")


if __name__ == "__main__":
    main()
