"""Probe 100 of six leftovers a demanding user hit (tests/test_leftovers100.py), each
against physics or a measurement made here, one line a check (``!!`` on a problem):

1. ``point --simulate`` with the paper's flags: its ``estimate:`` line against the runs'
   wall time (``took ... after the estimate``), within 2x, at three points;
2. theory-only ``--exact`` model maps (fput, diatomic FPUT, flexmm; 8 x 8, N 256): the
   estimate line against the command's wall time, within 2x;
3. a ring's missed bands (a Lennard-Jones chain, newuser99's, at seeded k): the printed
   peak against the band's maximum on a grid 1/4000 of its width (1e-6);
4. lossy files at zero damping (flexmm-lossy, an FPUT file with bond and site damping):
   ``coefficients`` (JSON and text), ``point`` and a 2 x 2 map say the damping is zero, print
   no loss line and give the lossless file's numbers (bit for bit);
5. eq. IC that is not quasi-periodic: case I near pi names no U resonance and the
   counter-propagating wave's share |Omega_c - omega| / (Omega_c + omega) from eq.
   `continuum2` and `discrete2` written here (1e-2 of the printed digits); case II near the
   U resonance names 2 Omega = omega_U(2k) with the detuning by hand (1e-3);
6. the plane wave's frequency shift of both engines (``nls_summary``, ``ModelNLS``) against
   the exact wave's a^2 coefficient fitted at a = 0.01, 0.02 (1e-3), at seeded materials,
   both cases; the paper's continuum NLS is reported (its own approximation), not judged.

    OMP_NUM_THREADS=1 python -m bench.probe_leftovers100 [--part N]

(2-core VM shared with other sessions, 2026-11-27: see bench/README.md.)
"""

from __future__ import annotations

import argparse
import json
import math
import os
import re
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

PROBLEMS: list = []
RNG = np.random.default_rng(100)


def say(part, what, ok, detail=""):
    print(f"{'ok' if ok else '!!'} {part} {what}: {detail}", flush=True)
    if not ok:
        PROBLEMS.append(f"{part} {what}: {detail}")


def cli(*argv, timeout=600):
    t0 = time.perf_counter()
    p = subprocess.run([sys.executable, "-m", "cli", *argv], capture_output=True, text=True,
                       timeout=timeout, env=dict(os.environ))
    return p.returncode, p.stdout, p.stderr, time.perf_counter() - t0


def seconds(text):
    m = re.match(r"([\d.]+) (s|min|h)", text)
    return float(m.group(1)) * {"s": 1, "min": 60, "h": 3600}[m.group(2)]


def part1():
    for k, N, seeds, case in ((1.2, 500, 2, "coupled"), (0.8, 300, 3, "rotation"),
                              (2.0, 1000, 2, "coupled")):
        code, out, err, wall = cli("point", "--alpha", "2", "--K-s", "0.03", "--K-theta",
                                   "0.02", "--k", str(k), "--amplitude", "0.04", "--case",
                                   case, "--N", str(N), "--seeds", str(seeds), "--simulate")
        est = re.search(r"^estimate: about (\S+ \w+)", out, re.M)
        took = re.search(r"^took (\S+ \w+) after the estimate", out, re.M)
        if code or not est or not took:
            say(1, f"k {k} N {N}", False, f"exit {code}, no estimate/took line {err[-200:]}")
            continue
        e, t = seconds(est.group(1)), seconds(took.group(1))
        # the line rounds to 1 s: below 3 s compare with 1 s of slack
        ok = t <= 2 * max(e, 1) + 1 and e <= 2 * max(t, 1) + 1
        say(1, f"k {k} N {N} seeds {seeds} {case}", ok, f"estimated {e:g} s, took {t:g} s "
            f"(whole command {wall:.1f} s)")


MAPS = {"fput": ["--model", "fput", "--param", "alpha=0.5", "--param", "beta=0.5:2.0:8",
                 "--k", "0.5:3.0:8", "--amplitude", "0.1"],
        "diatomic-fput": ["--model", "diatomic-fput", "--param", "beta=0.5:2.0:8", "--k",
                          "0.5:3.0:8", "--amplitude", "0.1"],
        "flexmm": ["--model", "flexmm", "--param", "K_theta=0.01:0.02:8", "--k", "0.5:1.5:8",
                   "--amplitude", "0.02"]}


def part2(tmp):
    for name, spec in MAPS.items():
        code, out, err, wall = cli("map", *spec, "--N", "256", "--theory-only", "--exact",
                                   "--out", str(tmp / f"map-{name}"), "--overwrite")
        est = re.search(r"^estimate: about (\S+ \w+)", out, re.M)
        if code or not est:
            say(2, name, False, f"exit {code} {err[-200:]}")
            continue
        e = seconds(est.group(1))
        load = os.getloadavg()[0]
        say(2, f"{name} 8 x 8 --exact", 0.5 <= wall / e <= 2, f"estimated {e:g} s, took "
            f"{wall:.1f} s (ratio {wall / e:.2f}; load average {load:.1f})")


def part3():
    from bench.probe_newuser99 import LJ  # the Lennard-Jones file's one copy
    from energy import load_model, parse_model
    from numerics.models import exact_gain, hill_spectrum, ring_misses, snap_ring

    model = load_model(parse_model(LJ))
    for k in [1.0, *RNG.uniform(0.9, 1.1, 2)]:
        kr = snap_ring(float(k), 128)[0]
        chain = exact_gain(model, kr, 0.01)
        for b in ring_misses(model, float(k), 0.01, N=128, chain=chain):
            lo, hi = b["band"]
            top = float(np.max(hill_spectrum(chain.wave, np.linspace(lo, hi, 4001)).gain))
            say(3, f"lj k {kr:.4f} band {lo:.5f}..{hi:.5f}", abs(b["peak_gain"] / top - 1)
                < 1e-6, f"printed {b['peak_gain']:.6g}, maximum {top:.6g}")


FPUT_LOSSY = """name = "fput-damped"
fields = ["u"]
[parameters]
beta = 1.0
gamma = 0.0
eta = 0.0
[energy]
kinetic = "u_t**2/2"
bond = "(u_next - u)**2/2 + beta*(u_next - u)**4/4"
[dissipation]
site = "gamma*u_t**2/2"
bond = "eta*(u_next_t - u_t)**2/2"
"""
FPUT_PLAIN = FPUT_LOSSY.split("[dissipation]")[0].replace("gamma = 0.0\neta = 0.0\n", "")


def part4(tmp):
    lossy, plain = tmp / "fput-damped.toml", tmp / "fput-plain.toml"
    lossy.write_text(FPUT_LOSSY)
    plain.write_text(FPUT_PLAIN)
    pairs = {"flexmm-lossy": (["--model", "flexmm-lossy", "--param", "gamma_theta=0",
                               "--param", "gamma_U=0", "--k", "1"],
                              ["--model", "flexmm", "--k", "1"]),
             "fput-damped": (["--model", str(lossy), "--k", "2.5", "--amplitude", "0.2"],
                             ["--model", str(plain), "--k", "2.5", "--amplitude", "0.2"])}
    for name, (zero, base) in pairs.items():
        _, z, _, _ = cli("coefficients", *zero, "--json")
        _, b, _, _ = cli("coefficients", *base, "--json")
        z, b = json.loads(z), json.loads(b)
        same = all(z[key] == b[key] for key in ("omega", "g1", "g2", "g"))
        say(4, f"{name} coefficients --json", same and "carrier_damping" not in z,
            f"keys of losses {sorted(k for k in z if 'damp' in k or 'ampl' in k)}")
        for command in ("coefficients", "point"):
            code, out, _, _ = cli(command, *zero, "--N", "64") if command == "point" else \
                cli(command, *zero)
            lines = [line for line in out.splitlines() if "with losses" in line
                     or "carrier damping" in line]
            say(4, f"{name} {command}", code == 0 and "damping:  zero" in out and not lines,
                f"exit {code}; loss lines {lines[:2]}")
        model = [a for a in zero if not a.startswith("--k") and a not in ("1", "2.5")]
        code, out, err, _ = cli("map", *model, "--param",
                                "beta=0.5:1.0:2" if "fput" in name else "K_theta=0.01:0.02:2",
                                "--k", "0.8:1.2:2", "--N", "64", "--theory-only", "--exact",
                                "--out", str(tmp / f"zero-{name}"))
        say(4, f"{name} map", code == 0 and "damping:  zero" in out and "observable" not in
            out, next((x for x in out.splitlines() if x.startswith("damping")), "")
            if code == 0 else f"exit {code}: {err.strip()[-150:]}")


def omega_theta(k, alpha, K_s, K_theta):
    return alpha * math.sqrt(4 * K_s * math.sin(k / 2)**2 + 4 * K_theta * math.cos(k / 2)**2
                             + 2 * K_theta)


def part5():
    mat = (2.5, 0.01851, 0.01551)
    flags = ["--alpha", "2.5", "--K-s", "0.01851", "--K-theta", "0.01551", "--start",
             "paper", "--N", "200", "--amplitude", "0.05"]
    for case, k in (("rotation", 2.98), ("rotation", 3.1), ("coupled", 0.97)):
        code, out, err, _ = cli("point", *flags, "--case", case, "--k", str(k))
        line = next((x for x in out.splitlines()
                     if x.startswith("exact lattice, paper start: the state")), "")
        kk = 2 * math.pi * round(k * 200 / (2 * math.pi)) / 200
        w = omega_theta(kk, *mat)
        if case == "rotation":
            wc = mat[0] * math.sqrt(6 * mat[2] + (mat[1] - mat[2]) * kk**2)
            m = re.search(r"\(([\d.]+) of its amplitude", line)
            share = float(m.group(1)) if m else math.nan
            say(5, f"case I k {kk:.4f}", bool(line) and "omega_U" not in line
                and abs(share / (abs(wc - w) / (wc + w)) - 1) < 2e-2,
                f"share {share} against {abs(wc - w) / (wc + w):.4g} by hand")
        else:
            m = re.search(r"omega_U\(2k\), ([\d.]+)% off", line)
            off = float(m.group(1)) / 100 if m else math.nan
            hand = abs(2 * w - 2 * math.sin(kk)) / (2 * w)
            say(5, f"case II k {kk:.4f}", abs(off - hand) < 1e-3,
                f"detuning {off} against {hand:.4g} by hand")


def part6():
    from energy import load_model
    from generated import lattice_coefficients
    from numerics import Material
    from numerics.models import nls, travelling_wave
    from numerics.theory import nls_summary, plane_wave

    for _ in range(4):
        alpha, K_s, K_theta = RNG.uniform(1.5, 3.5), *RNG.uniform(0.01, 0.04, 2)
        k = float(RNG.uniform(0.3, 2.6))
        mat = Material(alpha, K_s, K_theta)
        for case, name in (("rotation", "flexmm-rotation"), ("coupled", "flexmm")):
            try:
                w0 = plane_wave(mat, case, k, 1e-6).omega
                d1, d2 = ((plane_wave(mat, case, k, a).omega - w0) / a**2 for a in (0.01, 0.02))
            except ArithmeticError as exc:
                print(f"   6 {case} k {k:.3f}: no exact wave ({str(exc)[:60]})")
                continue
            c = (4 * d1 - d2) / 3
            paper = nls_summary(mat, case, k, amplitude=1.0, nls=lattice_coefficients)
            model = load_model(name, alpha=alpha, K_s=K_s, K_theta=K_theta)
            m0 = travelling_wave(model, k, 1e-6).omega
            e1, e2 = ((travelling_wave(model, k, a).omega - m0) / a**2 for a in (0.01, 0.02))
            cm = (4 * e1 - e2) / 3
            mine = nls(model, k).frequency_shift(1.0)
            cont = nls_summary(mat, case, k, amplitude=1.0)["frequency_shift"]
            say(6, f"{case} alpha {alpha:.2f} K_s {K_s:.4f} K_theta {K_theta:.4f} k {k:.3f}",
                abs(paper["frequency_shift"] / c - 1) < 1e-3 and abs(mine / cm - 1) < 1e-3,
                f"exact {c:+.5g}: nls_summary {paper['frequency_shift']:+.5g}, model "
                f"{mine:+.5g} (its exact {cm:+.5g}); paper NLS {cont:+.5g} ({cont / c:.3f})")


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--part", type=int, action="append", help="only these parts (1-6)")
    parts = set(ap.parse_args().part or range(1, 7))
    with tempfile.TemporaryDirectory() as folder:
        tmp = Path(folder)
        for n, run in ((1, part1), (2, lambda: part2(tmp)), (3, part3),
                       (4, lambda: part4(tmp)), (5, part5), (6, part6)):
            if n in parts:
                run()
    print(f"\n{len(PROBLEMS)} problem(s)" + "".join(f"\n  {p}" for p in PROBLEMS))
    return 1 if PROBLEMS else 0


if __name__ == "__main__":
    sys.exit(main())
