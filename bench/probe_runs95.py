"""Probe 95's check: a run's measured growth rate against the exact lattice theory on the
run's own ring, at seeded random points of several models (one and two fields), by the
rule before probe 95 ("largest": the largest mode at the linear stage's end, fitted over
its stretch above 10x its start) and the rule now ("settled": every mode's settled slope,
read while the products of growing modes are below it; ``numerics.models._growth``).

Each point runs at the default length (``run_length`` of the exact rate a run can see,
``visible_gain``) and at 2x and 4x
it (the rate must converge as T grows: a longer run has a longer linear stage only where
the noise lets it, so these rows mostly show that the reading does not drift with T and
with the records' spacing). The table prints the exact rate (over the offsets a run
sees: one whose two waves sit on carrier harmonics is left out of a run's growth, as
``harmonic_note`` says on a point), both readings and their ratio to the exact one.

    OMP_NUM_THREADS=1 NUMBA_NUM_THREADS=1 python -m bench.probe_runs95 [--points 30]
        [--seed 95] [--lengths 1,2,4]
"""

from __future__ import annotations

import argparse
import math
import time

import numpy as np

#: per model: the text or built-in name, each parameter's random range, the branches
MODELS95 = {
    "fput": ("fput", dict(alpha=(-0.6, 0.6), beta=(0.3, 1.5)), (0,)),
    "klein-gordon": ("klein-gordon", dict(C=(0.3, 1.5), alpha=(-0.5, 0.5),
                                          beta=(-1.0, 1.0)), (0,)),
    "hertzish": ("probe94:hertzish", dict(a=(-0.6, 0.6), b=(0.05, 0.8)), (0,)),
    "diatomic-fput": ("diatomic-fput", dict(m=(1.5, 4.0), alpha=(-0.5, 0.5),
                                            beta=(0.3, 1.2)), (0, 1)),
    "rotor-cross": ("probe94:rotor-cross", dict(kt=(0.3, 1.2), w0=(0.3, 1.0),
                                                c=(-1.0, 1.0)), ("th",)),
}


def _model(source: str):
    from energy import load_model, parse_model

    if source.startswith("probe94:"):
        from bench.probe_models94 import MODELS

        return load_model(parse_model(MODELS[source.split(":")[1]], "probe94.toml"))
    return load_model(source)


def points(count: int, seed: int) -> list[dict]:
    """Seeded points: a third near k = pi/2 (the backward pairs), amplitude 0.05-0.25."""
    rng = np.random.default_rng(seed)
    names = list(MODELS95)
    out = []
    for i in range(count):
        name = names[i % len(names)]
        _, ranges, branches = MODELS95[name]
        params = {p: float(np.round(rng.uniform(*r), 3)) for p, r in ranges.items()}
        k = (math.pi / 2 + rng.uniform(-0.15, 0.15) if rng.uniform() < 1 / 3
             else rng.uniform(0.3, math.pi - 0.05))
        a = float(np.round(math.exp(rng.uniform(math.log(0.05), math.log(0.25))), 4))
        out.append(dict(index=i, model=name, params=params, k=float(np.round(k, 4)), a=a,
                        N=int(rng.choice([64, 128, 256])),
                        branch=branches[int(rng.integers(len(branches)))]))
    return out


def seen_rate(spec, run) -> float:
    """The exact ring theory's fastest rate over the offsets a run reads: offset j's
    waves are ring modes m + j and m - j; a run leaves out the carrier's harmonics whose
    phase drift could show (``read_modes``), and an offset with both its waves there is
    not seen (``numerics.maps._model_point_rows.harmonic_note`` says so on a point)."""
    from numerics.models import read_modes

    N = run.N
    keep = read_modes(run)
    read = {j for j in range(N) if keep[j] or keep[(N - j) % N]}
    gain = np.asarray(spec.gain, float)
    m = int(round(spec.wave.k * N / (2 * math.pi)))
    seen = [(m + i) % N in read or (m - i) % N in read for i in range(1, gain.size + 1)]
    return float(np.max(gain[np.array(seen)], initial=0.0))


def measure(pt: dict, lengths=(1, 2, 4)) -> list[dict]:
    """The point's exact ring rate and each length's run readings (seed 0)."""
    from numerics.lattice import run_length
    from numerics.models import exact_gain, measure_growth, simulate_model, visible_gain

    model = _model(MODELS95[pt["model"]][0]).with_params(**pt["params"])
    try:
        spec = exact_gain(model, pt["k"], pt["a"], pt["branch"], N=pt["N"])
    except Exception as exc:  # noqa: BLE001 (a point without a wave is reported, skipped)
        return [dict(pt, error=str(exc).splitlines()[0])]
    T0 = run_length(visible_gain(spec, pt["N"])).t_end
    rows = []
    for f in lengths:
        try:
            run = simulate_model(model, pt["k"], pt["a"], branch=pt["branch"], N=pt["N"],
                                 t_end=f * T0, wave=spec.wave, energy=False)
        except Exception as exc:  # noqa: BLE001
            rows.append(dict(pt, T=f * T0, exact=spec.peak_gain,
                             error=str(exc).splitlines()[0]))
            continue
        new, old = measure_growth(run), measure_growth(run, "largest")
        rows.append(dict(pt, T=f * T0, exact=seen_rate(spec, run), verdict=new.verdict,
                         new=new.rate, old=old.rate, t_linear=new.t_linear,
                         detectable=new.detectable))
    return rows


def table(rows) -> str:
    head = (f"{'#':>3} {'model':<14} {'k':>6} {'a':>6} {'N':>4} {'T':>7} {'exact':>9} "
            f"{'old':>9} {'new':>9} {'old/ex':>7} {'new/ex':>7} verdict")
    out = [head]
    for r in rows:
        if "error" in r:
            out.append(f"{r['index']:>3} {r['model']:<14} {r['k']:>6.3f} {r['a']:>6.3f} "
                       f"{r['N']:>4} -- {r['error'][:60]}")
            continue

        def ratio(x, r=r):
            return (f"{x / r['exact']:7.3f}" if r["exact"] > 0 and math.isfinite(x)
                    else "      -")
        out.append(f"{r['index']:>3} {r['model']:<14} {r['k']:>6.3f} {r['a']:>6.3f} "
                   f"{r['N']:>4} {r['T']:>7.0f} {r['exact']:>9.3e} {r['old']:>9.3e} "
                   f"{r['new']:>9.3e} {ratio(r['old'])} {ratio(r['new'])} {r['verdict']}")
    return "\n".join(out)


def summary(rows) -> str:
    ok = [r for r in rows if "error" not in r and r["exact"] > 0 and r["verdict"] == "unstable"]
    if not ok:
        return "no unstable run"
    lines = []
    for key in ("old", "new"):
        e = np.array([abs(r[key] / r["exact"] - 1) for r in ok])
        lines.append(f"{key}: {len(e)} unstable runs, |rate/exact - 1| median {np.median(e):.2%}"
                     f", 90th percentile {np.quantile(e, 0.9):.2%}, max {e.max():.2%}, "
                     f"within 5%: {np.mean(e <= 0.05):.0%}")
    return "\n".join(lines)


def paper_maps(quick: bool = True) -> str:
    """The paper's Fig. 3 map by simulation (``scenes.fig3_simulated``'s grid, both cases):
    each cell's run (``cell_records``), its verdict by the factor as read (a map cell's,
    unchanged: MI once it passed 20x) and by exponential growth only (a point's run verdict
    since probe 95: MI once the exponential reading of the records so far passed 20x, as
    an early stop under that rule would decide). Cells where they differ are listed."""
    from common import paper
    from numerics import Material
    from numerics.lattice import GROWTH_THRESHOLD
    from numerics.maps import cell_records, growth_of
    from scenes.fig3_simulated import grid

    k, delta, g = grid(quick)
    lines, cells, differ = [], 0, 0
    for case in ("rotation", "coupled"):
        for d in delta:
            mat = Material(paper.ALPHA, paper.K_S, paper.K_S - float(d))
            for kk in k:
                rec = cell_records(mat, case, float(kk), g["N"], g["t_end"],
                                   amplitude=paper.AMPLITUDE, early_stop=False)
                t, th, U, m = rec["t"], rec["theta_hat"], rec["U_hat"], rec["m"]

                def reading(j, t=t, th=th, U=U, m=m):
                    return growth_of(t[:j + 1], th[:j + 1], None if U is None else U[:j + 1],
                                     m, g["N"], g["t_end"])

                # the map's early stop: the first record where the factor as read passed
                # 20x (its verdict MI); under the exponential rule, the first where the
                # exponential reading also passed, else the whole run's
                first = next((j for j in range(1, len(t))
                              if reading(j)["growth"] > GROWTH_THRESHOLD), None)
                read = first is not None
                expo = next((True for j in range(first or len(t), len(t))
                             if reading(j)["growth_exponential"] > GROWTH_THRESHOLD), False)
                cells += 1
                if read != expo:
                    differ += 1
                    last = reading(len(t) - 1)
                    lines.append(f"  {case} delta {d:+.4f} k {kk:.4f}: read "
                                 f"{last['growth']:.3g}x, exponential "
                                 f"{last['growth_exponential']:.3g}x over T")
    return "\n".join([f"Fig. 3 grid ({'quick' if quick else 'full'}: N {g['N']}, T "
                      f"{g['t_end']:g}): {cells} cells, {differ} whose verdict differs "
                      "(read vs exponential)"] + lines)


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--points", type=int, default=30)
    ap.add_argument("--seed", type=int, default=95)
    ap.add_argument("--lengths", default="1,2,4")
    ap.add_argument("--maps", choices=("quick", "full"),
                    help="instead: the paper's Fig. 3 grid, verdicts read vs exponential")
    args = ap.parse_args(argv)
    if args.maps:
        print(paper_maps(args.maps == "quick"))
        return 0
    lengths = tuple(float(x) for x in args.lengths.split(","))
    t0 = time.time()
    rows = []
    for pt in points(args.points, args.seed):
        rows += measure(pt, lengths)
        print(table(rows[-len(lengths):]).splitlines()[-1], flush=True)
    print(table(rows))
    print(summary(rows))
    print(f"({time.time() - t0:.0f} s)")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
