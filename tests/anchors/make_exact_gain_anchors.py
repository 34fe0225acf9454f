"""Writes tests/anchors/exact_gain.json: regression anchors of ``exact_gain``.

The committed file was written by this script (the implementation's own round-off
spread: each point again from the wave moved by 1e-15) run on the implementation at commit
ac52a2e (dense ``numpy.linalg.eig`` per offset at P = H + 4 harmonics, least-squares
harmonic balance with a finite-difference Jacobian), before the fast exact theory of
issue 41 replaced it. It is not to be rewritten from a newer implementation: the anchors
say what the old, slow code gave, and tests/test_exact_gain_anchors.py checks the new code
against them (1e-6 relative). To reproduce them (the script came later than ac52a2e; it
uses ``exact_gain`` and, to move the wave, ``_exact.travelling_wave`` as exact_gain calls
it there):

    mkdir /tmp/old && git archive ac52a2e | tar -x -C /tmp/old
    cd /tmp/old && PYTHONPATH=/tmp/old python /path/to/make_exact_gain_anchors.py OUT.json
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


def _perturbed(travelling_wave, seed):
    """``travelling_wave`` whose coefficients are moved by 1e-15 relative (seeded)."""
    import dataclasses

    import numpy as np

    def wave(*args, **kwargs):
        w = travelling_wave(*args, **kwargs)
        r = np.random.default_rng(seed).standard_normal(w.coefficients.shape)
        return dataclasses.replace(w, coefficients=w.coefficients * (1 + 1e-15 * r))

    return wave


def _fixed(q):
    """Indices of the infinite chain's fixed grid (exact_gain's samples = 400) in q."""
    import numpy as np

    grid = np.concatenate([np.geomspace(1e-5, np.pi / 400, 40, endpoint=False),
                           np.linspace(np.pi / 400, np.pi, 400)])
    return np.flatnonzero(np.isclose(q[:, None], grid[None, :], rtol=1e-12, atol=0).any(1))


def _row(name, params, k, a, branch, N):
    import numpy as np

    from energy import load_model
    from numerics.models import _exact, exact_gain

    model = load_model(name).with_params(**params) if params else load_model(name)
    spec = exact_gain(model, k, a, branch, N=N)
    # the same theory from the wave moved by 1e-15, four times: what round-off alone
    # decides (at a commensurate k a mode's copies tie: which one is "fastest" or
    # "central"; measured: at k = pi / 2, q = pi / 2 the old rate is 0 or 0.0070 by the
    # draw of a 1e-16 perturbation)
    fragile = np.zeros(spec.gain.size, bool)
    same_grid = True
    plain = _exact.travelling_wave
    for seed in range(4):
        _exact.travelling_wave = _perturbed(plain, seed)
        try:
            moved = exact_gain(model, k, a, branch, N=N)
        finally:
            _exact.travelling_wave = plain
        if moved.offsets.size == spec.offsets.size and np.allclose(
                moved.offsets, spec.offsets, rtol=1e-6, atol=0):
            mine, theirs = np.arange(spec.offsets.size), np.arange(moved.offsets.size)
        else:  # the refined peak moved: compare the infinite chain's fixed grid
            same_grid = False
            mine, theirs = _fixed(spec.offsets), _fixed(moved.offsets)
        differ = ~np.isclose(moved.gain[theirs], spec.gain[mine], rtol=1e-6,
                             atol=1e-9 * spec.wave.omega)
        kap = np.exp(1j * (spec.offsets + spec.harmonic * spec.wave.k))[mine]
        kap_moved = np.exp(1j * (moved.offsets + moved.harmonic * spec.wave.k))[theirs]
        differ |= (spec.gain[mine] > 0) & (np.abs(kap - kap_moved) > 1e-9)
        fragile[mine[differ]] = True
    return {"fragile": np.flatnonzero(fragile).tolist(),
            "refined_offset_fragile": not same_grid, "model": name, "params": params, "k": k, "amplitude": a, "branch": branch, "N": N,
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
