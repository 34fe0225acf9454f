"""Probe 102's review: the lossy exact theory's net rate at t = 0
(``exact_amplification(...).initial_gain``, ``_losses_hill.mode_damping``) against the
damped ring's time-domain monodromy (``bench._floquet102_ref``, sharing only the energy
file), on lossy models probe 102 did not cover, and its amplification against seeded
damped runs.

Models (written here): ``cross2-lossy`` (two fields coupled across sites, a bond damping
between different fields eta (v_{n+1,t} - u_{n,t})^2 / 2 and a site damping of v),
``tri3-lossy`` (three masses, the third 10x the first, only it damped),
``diatom10-lossy`` (a diatomic chain of mass ratio 10, only the light field damped), and
the built-in ``flexmm-lossy`` at random (gamma_theta, gamma_U, k, a), and with theta
damped strongly and U not at all (``flexmm-theta``). Points seeded: rings of 8-24 sites
(8-14 for three fields), k = 2 pi m / N, the amplitude log-uniform in [top/4, top].

Checks, one line a point (``!!`` per disagreement):

- t = 0: ``initial_gain`` against the damped monodromy's fastest rate (where nothing grows
  without losses: the damped ring grows at no more than 1e-6 omega) (1e-6 relative or
  1e-9 omega, issue 41's bar: the same linear equations, the referee's own error ~1e-10),
  where either grows; and each growing offset's net rate is one of the monodromy's rates.
- runs (``--runs``; flexmm-lossy on 64 sites, 3 seeds, launched as ``point --simulate``,
  ``numerics.models.lossy_runs``, and with noise 1e-4): the theory's amplification against the
  median seed's max A(t) / A(0), in log, within the seeds' spread plus ln 3 (a run starts
  from noise, of which the growing mode holds a share; the theory from the mode itself).

Found (2026-11-27): (1) only the fastest lossless mode of an offset was continued to the
damped pencil: with theta damped and U not, a slower mode holding less theta outgrows it
(flexmm-lossy gamma_theta 0.0387, gamma_U 0, k 2 pi 5/13, a 0.474: initial_gain 0.0056
for the monodromy's 0.0547); fixed (every growing mode continued where it could pass).
(2) not fixed: a mode neutral without losses that the damping destabilises
(gamma_theta 0.0431, gamma_U 0, k 2 pi 7/16, a 0.169: initial_gain -0.096, the monodromy
+0.0178, rate proportional to the damping); tests/test_lossreview102.py's strict xfail.
(3) lossless: flexmm at k 2 pi/18, a 0.3733 (the point with gamma_U 0 read 'nothing grows
lossless', the damped ring 0.447): exact_gain stable where the ring grows at 0.566;
fixed in ``_exact._Sidebands.checked``.

    OMP_NUM_THREADS=1 python -m bench.probe_lossreview102 [--points 24] [--seed S]
        [--quick] [--runs]

``--quick``: 8 points (< 60 s). Exit 1 where any disagreement.
"""

from __future__ import annotations

import argparse
import math
import os
import sys
import tempfile
import time

import numpy as np

from energy import load_model
from numerics.models import exact_amplification, exact_gain, lossy_runs, simulate_seeds

from ._floquet102_ref import RingReferee, monodromy, wave_state
from .exact98_files import exact_where_a_wave_is
from .probe_floquet102 import MODELS as FLOQUET_MODELS
from .probe_floquet102 import model_text as floquet_text

SEED = 20261127
RTOL = 1e-6

MODELS = {
    "cross2-lossy": FLOQUET_MODELS["cross2"].replace('"cross2"', '"cross2-lossy"').replace(
        "b = 0.5\n", "b = 0.5\neta = 1e-3\ngv = 1e-3\n") + """[dissipation]
bond = "eta*(v_next_t - u_t)**2/2"
site = "gv*v_t**2/2"
""",
    "tri3-lossy": FLOQUET_MODELS["tri3"].replace('"tri3"', '"tri3-lossy"').replace(
        "beta = 1.0\n", "beta = 1.0\ngw = 1e-3\n") + """[dissipation]
site = "gw*w_t**2/2"
""",
    "diatom10-lossy": FLOQUET_MODELS["diatom-site"].replace(
        '"diatom-site"', '"diatom10-lossy"').replace("w = 0.3\n", "w = 0.3\ngu = 1e-3\n") + """[dissipation]
site = "gu*u_t**2/2"
""",
}
#: point name -> (model file, parameter ranges, branches, the largest amplitude drawn)
SPACE = {
    "cross2-lossy": ("cross2-lossy", {"wu": (0.5, 1.2), "w0": (0.8, 1.8), "g": (-0.8, 0.8),
                                      "e": (-0.8, 0.8), "h": (-0.2, 0.2), "c": (0.1, 1.0),
                                      "eta": (0.0, 5e-3), "gv": (0.0, 2e-2)}, (0, 1), 0.4),
    "tri3-lossy": ("tri3-lossy", {"m2": (0.5, 3.0), "m3": (10.0, 10.0),
                                  "alpha": (-0.5, 0.5), "beta": (0.2, 1.5),
                                  "gw": (1e-4, 1e-2)}, (0, 1, 2), 0.3),
    "diatom10-lossy": ("diatom10-lossy", {"m": (10.0, 10.0), "a": (-0.6, 0.6),
                                          "b": (0.2, 1.5), "w": (0.0, 0.8),
                                          "gu": (1e-4, 1e-2)}, (0, 1), 0.3),
    "flexmm-lossy": ("flexmm-lossy", {"gamma_theta": (0.0, 1e-2), "gamma_U": (0.0, 1e-2)},
                     (0,), 0.3),
    "flexmm-theta": ("flexmm-lossy", {"gamma_theta": (5e-3, 6e-2), "gamma_U": (0.0, 0.0)},
                     (0,), 0.5),
}
#: runs: (gamma_theta = gamma_U, k, a) on 64 sites; the theory's 10.7x, 339x, 35.7x, 11.9x
#: (observable or near it) and 4.1x (not)
RUN_POINTS = [(0.001, 1.0, 0.1), (0.001, 1.0, 0.15), (0.0015, 1.0, 0.15), (0.002, 1.0, 0.15),
              (0.003, 1.0, 0.15)]


def model_text(name):
    return MODELS.get(name) or floquet_text(name)


def points(count, seed=SEED):
    rng = np.random.default_rng(seed)
    names = list(SPACE)
    out = []
    for i in range(count):
        name = names[i % len(names)]
        file, ranges, branches, top = SPACE[name]
        params = {p: float(rng.uniform(*r)) for p, r in ranges.items()}
        N = int(rng.integers(8, (14 if name.startswith("tri3") else 24) + 1))
        m = int(rng.integers(1, N // 2 + 1))
        a = float(math.exp(rng.uniform(math.log(top / 4), math.log(top))))
        out.append((file, params, m, N, a, int(branches[rng.integers(len(branches))])))
    return out


def check_point(file, params, m, N, a, branch, folder):
    """(line, disagreements) at t = 0."""
    from numerics.models._losses_hill import mode_damping

    path = os.path.join(folder, f"{file}.toml")
    with open(path, "w") as f:
        f.write(model_text(file))
    k = 2 * math.pi * m / N
    model = load_model(path, **params)
    spec, a, _, _ = exact_where_a_wave_is(model, k, a, branch, N)
    if spec is None:
        return f"{file:16s} N {N} m {m} b{branch}: no wave", []
    omega = spec.wave.omega
    net = exact_amplification(model, k, a, branch, N=N, first=spec).initial_gain
    ref = RingReferee(model_text(file), params, N)
    mu, _, T, back = monodromy(ref, wave_state(spec.wave, N), omega)
    rates = np.log(np.abs(mu)) / T
    damped = float(rates.max())
    if spec.peak_gain <= 0:  # nothing grows without losses: nor with them?
        line = (f"{file:16s} N {N:2d} m {m:2d} b{branch} a {a:.4g}: nothing grows "
                f"lossless; the damped monodromy {damped:.3g}")
        # the theory's floor, 3e-7 omega, and the referee's error: nothing grows there
        return line, ([f"the damped ring grows at {damped:.6g} where nothing grows "
                       "lossless"] if damped > 1e-6 * omega else [])
    bar = RTOL * max(abs(damped), spec.peak_gain) + 1e-9 * omega
    bad = []
    if (damped > 0 or net > 0) and abs(damped - net) > bar:
        bad.append(f"initial_gain {net:.8g} vs the damped monodromy's {damped:.8g}")
    grow = np.flatnonzero(spec.gain > 0)
    each = spec.gain[grow] - mode_damping(spec, model, grow)
    miss = max(float(np.min(np.abs(rates - x))) for x in each)
    if miss > bar:
        bad.append(f"a growing offset's net rate is no rate of the damped ring ({miss:.2g})")
    params_s = " ".join(f"{p} {v:.4g}" for p, v in params.items())
    return (f"{file:16s} N {N:2d} m {m:2d} b{branch} a {a:.4g} [{params_s}] peak "
            f"{spec.peak_gain:.6g} net {net:.8g} monodromy {damped:.8g}"), bad


def _median_log(runs):
    """(median ln amplification, spread of ln over the seeds, the seeds' 'amp@t')."""
    amps = [r.amplification() for r in runs]
    logs = np.log([x.amplification for x in amps])
    return (float(np.median(logs)), float(logs.max() - logs.min()),
            [f"{x.amplification:.3g}@{x.amplification_time:.0f}" for x in amps])


def check_runs(gamma, k, a, N=64, seeds=3):
    """(line, disagreements): the theory's amplification against seeded damped runs,
    launched as ``point --simulate`` (``numerics.models.lossy_runs``) and with noise 1e-4 (the
    launch's default noise, A(0) ~3.5e-10, sits below a deterministic departure of the
    damped carrier from the lossless wave family, ~7e-8 in harmonic 8's mode by t 20 at
    gamma 0.003, k 1, a 0.15, whatever the noise: 1e-4 puts it at 2% of A(0))."""
    model = load_model("flexmm-lossy", gamma_theta=gamma, gamma_U=gamma)
    spec = exact_gain(model, k, a, 0, N=N)
    th = exact_amplification(model, k, a, 0, N=N, first=spec)
    sim, _ = lossy_runs(model, k, a, spec, branch=0, N=N, seeds=seeds,
                        peak_time=th.amplification_time)
    loud = simulate_seeds(model, k, a, spec, branch=0, N=N, seeds=seeds,
                          t_end=2.5 * th.amplification_time, noise_on="carrier", noise=1e-4)
    bad = []
    line = (f"flexmm-lossy gamma {gamma} k {k} a {a} N {N}: theory "
            f"{th.amplification:.4g}@{th.amplification_time:.0f}")
    for name, runs in (("launched as point", sim.runs), ("noise 1e-4", loud.runs)):
        med, spread, seen = _median_log(runs)
        line += f"; {name} {seen}"
        if abs(math.log(th.amplification) - med) > spread + math.log(3):
            bad.append(f"amplification {th.amplification:.4g} vs the runs ({name}) "
                       f"{math.exp(med):.4g}")
    return line, bad


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--points", type=int, default=24)
    ap.add_argument("--seed", type=int, default=SEED)
    ap.add_argument("--quick", action="store_true", help="8 points")
    ap.add_argument("--runs", action="store_true", help="the damped runs too (~1 min)")
    args = ap.parse_args(argv)
    found = []
    with tempfile.TemporaryDirectory() as folder:
        for i, p in enumerate(points(8 if args.quick else args.points, args.seed)):
            t0 = time.perf_counter()
            line, bad = check_point(*p, folder)
            print(f"{i:3d} {line} [{time.perf_counter() - t0:.1f}s]", flush=True)
            for b in bad:
                print(f"    !! {b}", flush=True)
                found.append(f"point {i} ({p[0]}, {p[1]}, m {p[2]}, N {p[3]}, a {p[4]:.4g}): {b}")
    if args.runs:
        for p in RUN_POINTS:
            line, bad = check_runs(*p)
            print(line, flush=True)
            for b in bad:
                print(f"    !! {b}", flush=True)
                found.append(f"runs {p}: {b}")
    print(f"\n{len(found)} disagreements")
    for f in found:
        print("  " + f)
    return 1 if found else 0


if __name__ == "__main__":
    sys.exit(main())
