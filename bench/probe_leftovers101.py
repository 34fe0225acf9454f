"""Probe 101: three leftovers of earlier probes, each reproduced and checked (one line a
check, ``ok`` or ``!!``; the list at the end, exit 1 where any).

- ``ring``: ``ring_misses``' advice (``flexmm point`` where a ring of N misses a band of
  the infinite chain) at seeded random points of the built-in models (klein-gordon with a
  cubic term, fput alpha-beta, sine-gordon, diatomic-fput) and probe 100's kgeven, rings
  of 64 and 128: the advised ring that keeps k has an offset where Hill's rate (the
  referee: the chain's spectrum at that offset) is at least half the band's peak, and no
  smaller such ring does; the old rule (any offset in the band) is counted where it
  advised a ring whose offsets grow at less than half the peak;
- ``nls``: the NLS band's note (a band below the ring's first offset): the advised N's
  first offset 2 pi / N grows at half the peak or more, by the NLS rate written here from
  g1 and g2 (|g1|/2 q sqrt(g a^2 - q^2), g = g2/g1), and N - 1's does not; the paper
  chain's note (README's material at a = 0.005) checked on its exact curve;
- ``names``: the exact row of ``point --json`` names its mode once (``mode`` agrees with
  ``mode_kind``; a resonance the four-wave row names a three-wave decay says so, as the
  notes do; the decay's waves sum to k by hand), and no page or module says 'parametric
  decay' for a parametric pair;
- ``lossless``: a simulated map of flexmm-lossy at zero damping (no damping axis) against
  flexmm's: every stored variable equal; the cells' cost through the lossy path (as the
  old tree ran them) against the lossless path, interleaved, best of 2.

    python -m bench.probe_leftovers101 [--part ring|nls|names|lossless] [--points N]

(2-core VM, 2026-11-27: see bench/README.md for the time and the findings.)
"""

from __future__ import annotations

import argparse
import json
import math
import re
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
FAILS: list = []
RNG = np.random.default_rng(101)


def say(part: str, ok: bool, detail: str) -> None:
    print(f"{'ok' if ok else '!!'}  {part:8s} {detail}", flush=True)
    if not ok:
        FAILS.append(f"{part} {detail}")


def _offsets_in(lo, hi, n):
    return 2 * math.pi * np.arange(math.ceil(lo * n / (2 * math.pi)),
                                   math.floor(hi * n / (2 * math.pi)) + 1) / n


def _ring_models():
    from bench._fourwave100_models import FILES
    from energy import load_model, parse_model

    return [("klein-gordon alpha 0.5", load_model("klein-gordon", alpha=0.5)),
            ("klein-gordon alpha 1", load_model("klein-gordon", alpha=1.0)),
            ("fput alpha 0.5", load_model("fput", alpha=0.5)),
            ("fput alpha 1", load_model("fput", alpha=1.0)),
            ("sine-gordon", load_model("sine-gordon")),
            ("diatomic-fput alpha 0.5", load_model("diatomic-fput", alpha=0.5)),
            ("kgeven", load_model(parse_model(FILES["kgeven"], "kgeven.toml")))]


def part_ring(points: int) -> None:
    from numerics.models import exact_gain, hill_spectrum, ring_misses, snap_ring

    models = _ring_models()
    # the two reproducers first: the built-in one this probe found, probe 100's kgeven
    cases = [(models[0], 2.3687, 0.0587, 64), (models[-1], 0.393, 0.175, 128)]
    cases += [(models[int(RNG.integers(len(models)))], float(RNG.uniform(0.2, 3.0)),
               float(RNG.uniform(0.05, 0.3)), int(RNG.choice([64, 128])))
              for _ in range(points)]
    old_short = bands = 0
    for (name, model), k, a, N in cases:
        kr, m = snap_ring(k, N)
        try:
            misses = ring_misses(model, k, a, N=N)
        except Exception as exc:  # a point with no travelling wave: nothing to advise
            print(f"    {name} k {k:.4f} a {a:.4f} N {N}: {type(exc).__name__}")
            continue
        wave = exact_gain(model, kr, a).wave if misses else None
        for b in misses:
            lo, hi = b["band"]
            n, peak = b["N"], b["peak_gain"]
            where = f"{name} k {k:.4f} a {a:.4f} N {N} band {lo:.5g}-{hi:.5g}"

            def best(n_, lo=lo, hi=hi, wave=wave):
                q = _offsets_in(lo, hi, n_)
                return float(np.max(hill_spectrum(wave, q).gain)) if q.size else 0.0
            step = N // math.gcd(m, N)
            # the old rule: the first multiple of the ring's period with any offset inside
            old = next((n_ for n_ in range(N + step, 64 * N + 1, step)
                        if _offsets_in(lo, hi, n_).size), None)
            bands += 1
            if old is not None and best(old) < 0.5 * peak:
                old_short += 1
            if n is None:
                # the rule says none up to 64 N: every ring keeping k below 8 N checked
                worst = max((best(n_) for n_ in range(N + step, 8 * N + 1, step)),
                            default=0.0)
                say("ring", worst < 0.5 * peak, f"{where}: no ring advised; rings of this "
                    f"k up to {8 * N} reach {worst / peak:.2f} of the peak (< 0.5)")
                continue
            if not b["same_k"]:
                print(f"    {where}: N {n} of another k (its band moves: not refereed)")
                continue
            got = best(n)
            smaller = max((best(n_) for n_ in range(N + step, n, step)), default=0.0)
            say("ring", got >= 0.5 * peak and smaller < 0.5 * peak,
                f"{where}: advised N {n} reaches {got / peak:.2f} of the peak {peak:.3g}, "
                f"smaller rings of this k {smaller / peak:.2f} (old advice N {old}: "
                f"{best(old) / peak if old else float('nan'):.2f})")
    print(f"    the old rule advised a ring below half the peak for {old_short} of {bands} "
          "bands")


def _cli(*argv, timeout=300) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, "-m", "cli", *argv], cwd=ROOT, capture_output=True,
                          text=True, timeout=timeout)


def part_nls(points: int) -> None:
    cases = [("sine-gordon", ["C=1.901", "omega0=1.092"], 0.335, 0.05, 128),
             ("klein-gordon", ["alpha=0.5"], 2.3687, 0.0587, 64)]
    cases += [("sine-gordon", ["C=1.901", "omega0=1.092"], float(RNG.uniform(0.2, 0.6)),
               float(RNG.uniform(0.02, 0.06)), 64) for _ in range(max(1, points // 8))]
    for name, params, k, a, N in cases:
        args = ["--model", name, *sum((["--param", p] for p in params), []), "--k", str(k),
                "--amplitude", str(a), "--N", str(N)]
        r = _cli("point", *args, "--json")
        if r.returncode:
            say("nls", False, f"{name} k {k:.4f}: point exited {r.returncode}: "
                f"{r.stderr.strip()[-200:]}")
            continue
        out = json.loads(r.stdout)
        row = out["semi-discrete NLS"]
        note = next((n for n in out["notes"] if "semi-discrete NLS's band" in n), None)
        if note is None:
            print(f"    {name} k {k:.4f} a {a}: the NLS band fits the ring (no note)")
            continue
        n = int(re.search(r"--N (\d+) or more", note).group(1))
        g1, g2 = row["g1"], row["g2"]
        g = g2 / g1

        def rate(q, g1=g1, g=g, a=a):  # the NLS's rate written here (docs/models.md)
            return abs(g1) / 2 * q * math.sqrt(max(g * a * a - q * q, 0.0))
        peak = abs(g2) * a * a / 4
        at, before = rate(2 * math.pi / n), rate(2 * math.pi / (n - 1))
        say("nls", at >= 0.5 * peak * (1 - 1e-9) and before < 0.5 * peak,
            f"{name} k {k:.4f} a {a} N {N}: --N {n}: first offset at {at / peak:.3f} of "
            f"the peak, N - 1's {before / peak:.3f} (old advice 'above "
            f"{math.ceil(2 * math.pi / math.sqrt(g) / a)}': "
            f"{rate(2 * math.pi / math.ceil(2 * math.pi / math.sqrt(g) / a)) / peak:.3f})")
    # the paper chain's note (README's material, a = 0.005 on 64 sites): its point.json
    with tempfile.TemporaryDirectory() as tmp:
        r = _cli("point", "--alpha", "2.0", "--K-s", "0.03", "--K-theta", "0.02",
                 "--amplitude", "0.005", "--case", "coupled", "--start", "travelling", "--k",
                 "1.2", "--N", "64", "--out", tmp)
        out = json.loads((Path(tmp) / "point.json").read_text()) if not r.returncode else {}
    note = next((n for n in r.stdout.splitlines() if "holds no offset 2 pi j / N" in n), None)
    ex = out.get("theories", {}).get("exact lattice")
    if note is None or not ex or "curve" not in ex:
        say("nls", False, "paper chain, a 0.005 on 64 sites: no unsampled-band note or exact "
            f"curve (exit {r.returncode})")
        return
    n = int(re.search(r"N = (\d+)", note.split("samples it")[0].split(";")[-1]).group(1))
    Q, c = np.asarray(ex["offset"], float), np.nan_to_num(np.asarray(ex["curve"], float))
    ring = 2 * math.pi * np.arange(1, n // 2 + 1) / n
    got = float(np.max(np.interp(ring, Q, c)))
    say("nls", got >= 0.5 * c.max(), f"paper chain a 0.005 N 64: advised N {n}: its best "
        f"offset on the exact curve {got / c.max():.2f} of the peak")


def part_names(points: int) -> None:
    from bench._fourwave100_models import FILES

    with tempfile.TemporaryDirectory() as tmp:
        path = Path(tmp) / "decay2.toml"
        path.write_text(FILES["decay2"])
        cases = [(["--model", str(path), "--branch", "u"], float(k), a)
                 for k in RNG.uniform(0.8, 3.0, max(2, points // 6)) for a in (0.03, 0.1)]
        cases += [(["--model", "fput", "--param", "alpha=0.5", "--param", "beta=1"],
                   math.pi / 2, 0.1)]
        for argv, k, a in cases:
            r = _cli("point", *argv, "--k", str(k), "--amplitude", str(a), "--N", "128",
                     "--json")
            out = json.loads(r.stdout)
            ex, fw = out["exact lattice"], out["four-wave"]
            kind, mode = ex.get("mode_kind"), ex.get("mode", "")
            decay = re.search(r"three-wave decay of the carrier into branch \d+ at "
                              r"(-?[\d.]+) and branch \d+ at (-?[\d.]+)", fw.get("reason") or "")
            said = any("three-wave decay" in n for n in out["notes"])
            where = f"{Path(argv[1]).stem} k {k:.4f} a {a}"
            if decay and kind == "resonance":
                k1, k3 = float(decay.group(1)), float(decay.group(2))
                dk = abs((k1 + k3 - out["k"] + math.pi) % (2 * math.pi) - math.pi)
                say("names", mode.startswith("three-wave decay") and said and dk < 2e-3,
                    f"{where}: mode {mode!r}, notes say three-wave decay: {said}; "
                    f"k1 + k3 - k = {dk:.1e}")
            else:
                want = {"sidebands": "sidebands", "backward": "backward pair",
                        "parametric": "parametric pair", "resonance": "resonance",
                        "none": "none"}.get(kind, "?")
                say("names", mode.startswith(want), f"{where}: mode_kind {kind}, mode {mode!r}")
    bad = [f"{p.relative_to(ROOT)}:{i}" for p in [*ROOT.glob("docs/*.md"),
                                                  *ROOT.glob("cli/*.py"),
                                                  *ROOT.glob("numerics/models/*.py")]
           for i, line in enumerate(p.read_text().splitlines(), 1)
           if re.search(r"parametric decay", line)]
    say("names", not bad, f"'parametric decay' for a parametric pair: {bad or 'nowhere'}")


def _map(out: Path, name: str, extra: list) -> float:
    t0 = time.perf_counter()
    r = _cli("map", "--model", name, *extra, "--param", "alpha=2:3:2", "--k", "1.0,1.3",
             "--amplitude", "0.06", "--N", "64", "--workers", "1", "--out", str(out),
             "--overwrite", "--yes", timeout=600)
    if r.returncode:
        raise RuntimeError(r.stderr.strip()[-300:])
    return time.perf_counter() - t0


def part_lossless(points: int) -> None:
    import xarray as xr

    from energy import load_model
    from numerics.models import map_cells

    zero = ["--param", "gamma_theta=0", "--param", "gamma_U=0"]
    with tempfile.TemporaryDirectory() as tmp:
        t_lossy = _map(Path(tmp) / "lossy", "flexmm-lossy", zero)
        t_plain = _map(Path(tmp) / "plain", "flexmm", [])
        a = xr.open_zarr(Path(tmp) / "lossy" / "map.zarr")
        b = xr.open_zarr(Path(tmp) / "plain" / "map.zarr")
        differ = [v for v in b.data_vars if v not in a.data_vars
                  or not np.array_equal(a[v].values, b[v].values,
                                        equal_nan=a[v].dtype.kind == "f")]
        say("lossless", not differ and set(a.data_vars) == set(b.data_vars),
            f"flexmm-lossy at gamma 0 against flexmm, 2 x 2 simulated map: variables that "
            f"differ {differ or 'none'} (wall {t_lossy:.1f} s against {t_plain:.1f} s, "
            "cluster start included)")
    # the cells' cost: the lossy path (what the old tree ran) against the lossless one
    model = load_model("flexmm-lossy", gamma_theta=0.0, gamma_U=0.0)
    cells = [({"alpha": al}, k) for al in (2.0, 3.0) for k in (1.0, 1.3)]
    best = {True: math.inf, False: math.inf}
    rows = {}
    for _ in range(2):
        for lossy in (True, False):
            t0 = time.process_time()
            rows[lossy] = map_cells(model, cells, 0.06, exact=True, simulate=True, N=64,
                                    lossy=lossy)
            best[lossy] = min(best[lossy], time.process_time() - t0)
    plain = map_cells(load_model("flexmm"), cells, 0.06, exact=True, simulate=True, N=64)
    same = all(json.dumps(x, sort_keys=True, default=str) ==
               json.dumps(y, sort_keys=True, default=str) for x, y in zip(rows[False], plain))
    say("lossless", same, f"4 cells through the lossless path equal flexmm's cells: {same}; "
        f"CPU {best[True]:.2f} s through the lossy path, {best[False]:.2f} s lossless "
        f"({best[True] / best[False]:.2f}x; best of 2, interleaved)")


PARTS = {"ring": part_ring, "nls": part_nls, "names": part_names, "lossless": part_lossless}


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--part", choices=sorted(PARTS), action="append")
    ap.add_argument("--points", type=int, default=24, help="random points of 'ring'")
    args = ap.parse_args(argv)
    t0 = time.time()
    for name in args.part or PARTS:
        print(f"# {name}", flush=True)
        PARTS[name](args.points)
    print(f"\n{len(FAILS)} disagreements, {time.time() - t0:.0f} s")
    for f in FAILS:
        print(f"!! {f}")
    return 1 if FAILS else 0


if __name__ == "__main__":
    sys.exit(main())
