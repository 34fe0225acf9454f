"""Writes tests/anchors/exact_gain.json: regression anchors of ``exact_gain``.

The committed file was written by this script run on the implementation at commit
ac52a2e (dense ``numpy.linalg.eig`` per offset at P = H + 4 harmonics, least-squares
harmonic balance with a finite-difference Jacobian), before the fast exact theory of
issue 41 replaced it. It is not to be rewritten from a newer implementation: the anchors
say what the old, slow code gave, and tests/test_exact_gain_anchors.py checks the new code
against them (1e-6 relative). To reproduce them:

    git worktree add /tmp/old ac52a2e && cd /tmp/old && python tests/anchors/make_exact_gain_anchors.py OUT.json

(the script itself came later; it uses only ``exact_gain``'s public result).
"""

from __future__ import annotations

import json
import math
import sys

POINTS = [
    # name, params, k, amplitude, branch, N (None: the infinite chain)
    ("fput", {"alpha": 0.5, "beta": 1.0}, 2 * math.pi * 66 / 256, 0.1, None, 256),
    ("fput", {"alpha": 0.0, "beta": 1.0}, 2.0, 0.1, None, 128),
    ("fput", {"alpha": 0.8, "beta": 1.0}, math.pi, 0.1, None, 128),
    ("fput", {"alpha": 0.5, "beta": 1.0}, math.pi / 2, 0.1, None, 128),
    ("fput", {"alpha": 1.0, "beta": 0.0}, 2.0, 0.1, None, 128),
    ("klein-gordon", {"alpha": 0.5}, 2.5, 0.05, None, 128),
    ("klein-gordon", {}, 1.0, 0.1, None, 128),
    ("sine-gordon", {}, 1.0, 0.3, None, 128),
    ("diatomic-fput", {}, 1.0, 0.1, 0, 128),
    ("diatomic-fput", {}, 1.0, 0.1, 1, 128),
    ("flexmm", {"K_theta": 0.016}, 2 * math.pi * 18 / 128, 0.1, None, 128),
    ("flexmm-rotation", {}, 1.0, 0.1, None, 128),
    ("flexmm", {}, 1.0, 0.1, None, 256),
    ("fput", {"alpha": 0.5, "beta": 1.0}, 2 * math.pi * 66 / 256, 0.1, None, None),
    ("fput", {"alpha": 0.5, "beta": 1.0}, 1.5, 0.002, None, None),
    ("fput", {"alpha": 0.5, "beta": 1.0}, math.pi / 2, 0.005, None, None),
    ("klein-gordon", {"alpha": 0.5}, 2.5, 0.05, None, None),
    ("sine-gordon", {}, 1.0, 0.3, None, None),
    ("diatomic-fput", {}, 1.0, 0.1, 0, None),
    ("flexmm", {"K_theta": 0.016}, 2 * math.pi * 18 / 128, 0.1, None, None),
]


def _row(name, params, k, a, branch, N):
    from energy import load_model
    from numerics.models import exact_gain

    model = load_model(name).with_params(**params) if params else load_model(name)
    spec = exact_gain(model, k, a, branch, N=N)
    return {"model": name, "params": params, "k": k, "amplitude": a, "branch": branch, "N": N,
            "omega": spec.wave.omega, "peak_gain": spec.peak_gain, "mode": spec.mode,
            "offsets": spec.offsets.tolist(), "gain": spec.gain.tolist(),
            "harmonic": spec.harmonic.tolist(),
            "sideband_offset": [None if math.isnan(x) else x
                                for x in spec.sideband_offset.tolist()]}


def main(path):
    rows = []
    for pt in POINTS:
        rows.append(_row(*pt))
        print(pt[0], pt[-1], rows[-1]["peak_gain"], flush=True)
    doc = {"written_by": "tests/anchors/make_exact_gain_anchors.py",
           "implementation": "ac52a2e (numerics/models/_exact.py before issue 41)",
           "points": rows}
    with open(path, "w") as f:  # one point a line
        f.write("{\n" + f'"written_by": {json.dumps(doc["written_by"])},\n'
                + f'"implementation": {json.dumps(doc["implementation"])},\n"points": [\n')
        f.write(",\n".join(json.dumps(r, separators=(",", ":")) for r in rows))
        f.write("\n]}\n")


if __name__ == "__main__":
    main(sys.argv[1])
