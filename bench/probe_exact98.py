"""Probe 98 of the exact lattice theory's fast paths (``numerics.models.exact_gain``: the
Gershgorin clusters, the frozen central pencil, the anchors between them, the ring copies,
the crossings, the persistence check) at models nobody had tried, against two referees.

The models (TOML, ``bench.exact98_files``, written to a temporary folder and loaded with
``energy.load_model``): ``res2`` (a chain with a local resonator, a flat optical branch,
cubic cross terms of size 1), ``weak2`` (an acoustic u and a Klein-Gordon v with a tiny
spring, coupled by g (u_next - u) v^2), ``kgflat`` (one Klein-Gordon field, inter-site
spring 0.0005-0.02), ``cross2`` (an acoustic u and a flat v whose branches cross, cubic
cross term of size 1, a linear coupling 0-1e-2), ``tri-flat`` (three fields: a chain and
two resonators), ``kg2`` (two Klein-Gordon fields with tiny springs, cubic coupling both
ways), ``fput1`` (FPUT, alpha of either sign), ``rotor-flat`` (a pendulum chain with a
weak spring coupled to an acoustic field through cos), and the built-ins ``flexmm``
(K_theta 0.005-0.05, alpha 1.5-3.5), ``flexmm-stiff-hinge`` and ``diatomic-fput``. Points
are seeded: the parameters drawn, k uniform or near pi/2, near pi, near 0 (a band edge);
branch 0 or 1 (an optical carrier); the amplitude log-uniform in [0.01, a model's top],
halved until a travelling wave exists; rings of 32-512 sites (odd and even) or the chain.

Checks (each against physics the fast paths do not compute):

- the dense spectrum (``hill_spectrum(..., harmonics=P)``, ``_hill_dense``) of the same wave at the same
  offsets and truncation, with its kept-mode rule: the peak rate within 1e-6 relative
  (issue 41's bar), every offset's rate within 1e-6 of the peak, the same growing offsets
  (rates above 1e-9 omega where the other's is above 2x the 3e-7 omega floor: a rate at
  the floor may round either way) and the same fastest offset (or a tie within 1e-6);
- this probe's own Hill pencil (``exact98_files.own_rates``: the energy by hand, exact
  Hessians by hyper-dual numbers, numpy.linalg.eig) at the fastest offset, at the
  spectrum's truncation P (1e-6 relative) and at P + 4 (1e-6 relative where the theory says
  its peak persisted there);
- on the chain, ``four_wave``: a contradiction is four-wave 'stable' where the exact
  chain grows faster than 1e-3 omega; the ratio of their fastest rates and the kind are
  printed.

    OMP_NUM_THREADS=1 NUMBA_NUM_THREADS=1 python -m bench.probe_exact98 [--points 72] [--seed S]

Prints one line a point and the disagreements at the end (exit 1 where any). Run time on
the loaded 2-core VM (2026-11-27): ~10 min for the default 72 points; other seeds draw
waves near a harmonic's resonance with a flat branch (H = 32, P = 36: every offset dense)
at 2-4 min each. Found: a Gershgorin cluster's close pair refrozen between its roots was
a start only within 2x their gap, and a growing band (stiff-hinge, 2.4e-3) was certified
stable (fixed in ``_cluster_solve``), and a start of the frozen central pencil whose
vector, distorted by the frozen fold, was heaviest off centre was left where the mode
(weights 0.170 at l = -1 and at 4) is kept: stiff-hinge's chain at k 0.308, a 0.103 read
stable where it grows at 3.9e-3 (seed 98003, ``--only flexmm-stiff-hinge``; fixed after:
a start whose central harmonic weighs half its heaviest is refined, after the others,
``_frozen.SPREAD_SHARE``, at 1.5x the cost of flexmm's and stiff-hinge's rings); at q = k on
an FPUT ring a truncation artefact of the translation mode read 3e-6 (ring copies) against
5e-7 (dense at the same P), 0 at P + 4 (fixed after: slow offsets are checked at P + 4,
``_persist``; the dense referee at P still shows its 5e-7, below the probe's floor).
"""

from __future__ import annotations

import argparse
import dataclasses
import math
import os
import sys
import tempfile

import numpy as np

from energy import ModelError, load_model
from numerics.models import four_wave, hill_spectrum

from .exact98_files import MODELS, exact_where_a_wave_is, own_rates

SEED = 20261198
#: issue 41's bar: the fast paths equal the dense eigenproblem to 1e-6 relative
RTOL = 1e-6
#: the exact theory's rate floor (``_exact.GAIN_FLOOR``), in units of omega
FLOOR = 3e-7

#: model -> (parameter ranges, branches, the largest amplitude drawn)
SPACE = {
    "res2": ({"mr": (0.5, 3.0), "kr": (0.005, 0.3), "beta": (0.2, 1.5), "g": (-1.0, 1.0)},
             (0, 1), 0.4),
    "weak2": ({"c": (1e-4, 1e-2), "w0": (0.6, 1.6), "g": (-1.0, 1.0), "lam": (0.2, 1.5)},
              (0, 1), 0.4),
    "kgflat": ({"C": (5e-4, 2e-2), "alpha": (-0.8, 0.8), "beta": (0.5, 1.5)}, (0,), 0.4),
    "cross2": ({"wv": (0.6, 1.9), "g": (-1.0, 1.0), "eps": (0.0, 1e-2)}, (0, 1), 0.3),
    "tri-flat": ({"kv": (0.02, 0.3), "kw": (0.05, 0.5), "g": (-1.0, 1.0)}, (0, 1, 2), 0.3),
    "kg2": ({"C": (1e-3, 2e-2), "w2": (1.2, 2.0), "g": (-1.0, 1.0)}, (0, 1), 0.3),
    "fput1": ({"alpha": (-1.0, 1.0), "beta": (0.2, 2.0)}, (0,), 0.4),
    "rotor-flat": ({"C": (1e-3, 3e-2), "g": (-1.0, 1.0)}, (0, 1), 0.6),
    "flexmm": ({"K_theta": (0.005, 0.05), "alpha": (1.5, 3.5)}, (0,), 0.6),
    "flexmm-stiff-hinge": ({"K_theta": (0.005, 0.05), "alpha": (1.5, 3.5),
                            "K_3": (0.1, 1.0)}, (0,), 0.5),
    "diatomic-fput": ({"m": (0.3, 3.0), "alpha": (-0.5, 0.5), "beta": (0.2, 1.5)}, (0, 1),
                      0.3),
}
RINGS = (32, 33, 64, 65, 97, 128, 255, 256, 512)


def _model(name, folder):
    if name in MODELS:
        path = os.path.join(folder, f"{name}.toml")
        if not os.path.exists(path):
            with open(path, "w") as f:
                f.write(MODELS[name])
        return load_model(path)
    return load_model(name)


def points(count, seed=SEED):
    """The seeded points: (model, params, k, amplitude, branch, N or None)."""
    rng = np.random.default_rng(seed)
    names = list(SPACE)
    out = []
    for i in range(count):
        name = names[i % len(names)]
        ranges, branches, top = SPACE[name]
        params = {p: float(rng.uniform(*r)) for p, r in ranges.items()}
        where = rng.integers(4)
        k = [rng.uniform(0.05, 1.0) * math.pi, math.pi / 2 + rng.normal(0, 0.02),
             math.pi - abs(rng.normal(0, 0.02)), 0.03 + rng.uniform(0, 0.1)][where]
        a = float(math.exp(rng.uniform(math.log(0.01), math.log(top))))
        branch = int(branches[rng.integers(len(branches))])
        N = [None, int(RINGS[rng.integers(len(RINGS))])][int(rng.integers(3) > 0)]
        out.append((name, params, float(min(k, math.pi)), a, branch, N))
    return out


def check_point(model, name, params, k, a, branch, N, fourwave=True):
    """One point's comparisons: (line, disagreements, record)."""
    bad = []
    # the largest amplitude (of a halved draw) where a wave exists
    spec, a, wall, why = exact_where_a_wave_is(model, k, a, branch, N)
    if spec is None:
        return f"{name:18s} no wave ({why[:80]})", [], None
    wave, P = spec.wave, spec.truncations[0]
    omega = wave.omega
    if P > 20 and wave.model.n_fields > 1:
        # every offset is the dense eigenproblem already (the strong path stops at 14
        # harmonics): the referee at the growing offsets and every 8th one (a resonant
        # wave's H = 32 costs ~0.7 s an offset on the loaded VM)
        keep = (spec.gain > 0) | (np.arange(spec.offsets.size) % 8 == 0)
        spec = dataclasses.replace(spec, offsets=spec.offsets[keep], gain=spec.gain[keep],
                                   harmonic=spec.harmonic[keep],
                                   sideband_offset=spec.sideband_offset[keep])
    # the dense eigenproblem at P (``hill_spectrum`` with harmonics given: ``_hill_dense``)
    dense = hill_spectrum(wave, spec.offsets, harmonics=P)
    peak, dpeak = spec.peak_gain, dense.peak_gain
    top = max(peak, dpeak)
    # rates within 2x the floor of the floor may round either way (eig resolves a
    # degenerate eigenvalue to ~sqrt(eps): ``_exact.GAIN_FLOOR``'s comment)
    near_floor = 2 * FLOOR * omega
    if abs(peak - dpeak) > RTOL * top and top > near_floor:
        bad.append(f"peak {peak:.10g} vs dense {dpeak:.10g}")
    if top > near_floor:
        diff = np.abs(spec.gain - dense.gain)
        diff[np.maximum(spec.gain, dense.gain) <= near_floor] = 0
        worst = float(np.max(diff))
        # 1e-9 omega: the resolution the bar asks for (rates above it count as growing);
        # below it, eig's round-off between two solvers (probe: 2.8e-12 at a 4.3e-8 rate)
        if worst > RTOL * top + 1e-9 * omega:
            j = int(np.argmax(diff))
            again, _ = own_rates(name, params, wave, spec.offsets[j], P + 4)
            why = " (truncation artefact: 0 at P + 4)" if again == 0 else ""
            bad.append(f"curve off by {worst:.3g} at q {spec.offsets[j]:.6g} "
                       f"({spec.gain[j]:.6g} vs dense {dense.gain[j]:.6g}){why}")
        grow_f = spec.gain > 1e-9 * omega
        grow_d = dense.gain > 1e-9 * omega
        sure = np.maximum(spec.gain, dense.gain) > 2 * FLOOR * omega
        if np.any((grow_f != grow_d) & sure):
            bad.append(f"growing offsets differ at q "
                       f"{spec.offsets[(grow_f != grow_d) & sure][:4]}")
        i, j = int(np.argmax(spec.gain)), int(np.argmax(dense.gain))
        if i != j and abs(dense.gain[i] - dense.gain[j]) > RTOL * top:
            bad.append(f"fastest offset {spec.offsets[i]:.6g} vs dense {spec.offsets[j]:.6g}")
        own, _ = own_rates(name, params, wave, spec.offsets[j], P)
        if abs(own - dense.gain[j]) > RTOL * top and top > near_floor:
            bad.append(f"own pencil at P {P}: {own:.10g} vs dense {dense.gain[j]:.10g}")
        own4, _ = own_rates(name, params, wave, spec.offsets[i], P + 4)
        if (len(spec.truncations) == 2 and abs(own4 - peak) > RTOL * top
                and top > near_floor):
            bad.append(f"own pencil at P + 4: {own4:.10g} vs peak {peak:.10g}")
    else:
        own = own4 = 0.0
    fw_txt = ""
    if fourwave and N is None:
        try:
            fw = four_wave(model, k, a, branch)
            fw_txt = f" 4w {fw.verdict}"
            if fw.verdict == "MI" and peak > 0:
                fw_txt += f" {fw.gain / peak:.3f}x {fw.mode_kind}"
            if fw.verdict == "stable" and peak > 1e-3 * omega:
                bad.append(f"four-wave stable where exact grows at {peak / omega:.3g} omega")
        except ModelError as e:
            fw_txt = f" 4w error: {str(e)[:60]}"
    ring = f"N {N}" if N else "chain"
    line = (f"{name:18s} b{branch} k {wave.k:.4f} a {a:.4g} {ring:6s} P {spec.truncations} "
            f"peak {peak:.6g} dense {dpeak:.6g} own {own:.6g}/{own4:.6g} "
            f"{wall:.2f}s{fw_txt}")
    return line, bad, (peak, wall)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--points", type=int, default=72)
    ap.add_argument("--seed", type=int, default=SEED)
    ap.add_argument("--only", default="", help="comma-separated model names")
    args = ap.parse_args(argv)
    only = set(filter(None, args.only.split(",")))
    found = []
    with tempfile.TemporaryDirectory() as folder:
        for n, (name, params, k, a, branch, N) in enumerate(points(args.points, args.seed)):
            if only and name not in only:
                continue
            model = _model(name, folder).with_params(**params)
            try:
                line, bad, _ = check_point(model, name, dict(model.params), k, a, branch, N)
            except ModelError as e:
                line, bad = f"{name:18s} refused: {str(e)[:100]}", []
            print(f"{n:3d} {line}", flush=True)
            for b in bad:
                print(f"    !! {b}", flush=True)
                found.append(f"point {n} {name} {params} k {k:.6g} a {a:.4g} b{branch} "
                             f"N {N}: {b}")
    print(f"\n{len(found)} disagreements", file=sys.stderr)
    for f in found:
        print("  " + f, file=sys.stderr)
    return 1 if found else 0


if __name__ == "__main__":
    sys.exit(main())
