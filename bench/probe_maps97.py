"""probe 97: maps of any model through the one map engine, interrupted and resumed.

What it tries (one line a try, ``!!`` where a bar is missed):

- ``interrupt``: a 12-cell fput map (N 64, 1 worker, then 2) run whole once, then run
  again and hit with SIGINT, SIGTERM or SIGKILL (of the whole process group) at a seeded
  random moment between 0.5 s and the whole run's time, then the same command once more.
  Bars: the interrupted command exits 130 / 143 (one line on stderr naming what is kept)
  or dies (-9); the rerun exits 0; the store equals the undisturbed one, every variable
  and attribute bit for bit; no lock is left behind.
- ``store``: the finished store opened with ``xr.open_zarr`` (dims named by the axes,
  coordinates with units, every fixed parameter in attrs, each variable's units), then a
  seeded byte flip, truncation, emptying or deletion of a random file of a copy and the
  same command again. Bars: a rerun exits 0 with the undisturbed store bit for bit and a
  store ``xr.open_zarr`` reads, or exits 2 with one line naming the damage and the
  remedy; never a traceback, never "checksums verified" over a store xarray cannot read.
- ``refuse``: the same --out resumed with one thing changed (a fixed parameter, an axis,
  N, the amplitude, seeds, --t-end, --block, the model file's energy, another model) and
  two maps started at once into one --out. Bars: exit 2, one line naming what changed and
  the remedy (``--overwrite`` or another --out; ``omit --block``); the second of two maps
  refused naming the lock's holder; the store left as it was.
- ``cells``: each cell of a simulated map (fput, a lossy Klein-Gordon file with a
  [dissipation] table, a two-field file) against ``flexmm point --json`` at its
  parameters (same verdicts; rates within 2%: point runs 4 seeds, the map 1, and a run's
  rate moves ~1% between seeds), the exact column against
  ``numerics.models.exact_gain`` (1e-12 relative: the same theory, called apart), and
  fput's g1 against the hand closed form -sin(k/2)/2 (1e-12).
- ``grids``: reversed and 1 x n axes, a parameter through a branch crossing (diatomic
  FPUT's mass ratio through 1, k at pi), the flexmm model with ``--start paper``, a
  paper-flag theory-only map. Bars: exit 0, coordinates ascending and the cells' values
  at the sorted coordinates, or one line naming the option.
- ``progress``: a 24-cell map with stderr a pipe, each line's time stamped. Bars: the
  first line within 5 s, a progress line within 10 s of the cluster's start, no
  "about 0 s left" while cells are left, the last line naming what was written where.

    OMP_NUM_THREADS=1 NUMBA_NUM_THREADS=1 python -m bench.probe_maps97 [--part NAME]
        [--tries N] [--seed S]

Run time on the 2-core VM shared with other sessions (load average 2-10), 2026-11-27,
``--tries 3``/``8``: interrupt ~5 min, store ~4 min, refuse ~2 min, cells ~4 min (12
``point --simulate`` calls), grids ~3 min, progress ~10 s idle (~70 s loaded).
Findings (fixed, tests/test_probe97_maps.py): a variable's lost ``.zattrs`` made the
resume a traceback; a flipped byte in ``.zmetadata`` was resumed as sound while
``xr.open_zarr`` failed; a progress line said "about 0 s left" 70 s before the end; a
lock file caught between its creation and its record was taken over by a second map; a
store set aside by a stopped rewrite was deleted by the next run; a one-value SPEC of
--k was no axis (no 1 x 1 map); a theory-only map's interrupt line counted 0 cells kept.
Left: SIGINT during the interpreter's exit, after the last line ("wrote ..."), ends the
process by the signal (exit -2, no line; the store complete), which the interrupt part
reports with ``!!``.
"""

from __future__ import annotations

import argparse
import json
import os
import random
import shutil
import signal
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
PY = sys.executable
ENV = {**os.environ, "OMP_NUM_THREADS": "1", "NUMBA_NUM_THREADS": "1"}
FPUT12 = ("--model fput --param alpha=1 --param beta=0.5:1.5:3 --k 1.0:2.8:4 "
          "--amplitude 0.1 --N 64").split()
FPUT4 = ("--model fput --param alpha=1 --param beta=0.8,1.6 --k 2.6,2.8 --amplitude 0.1 "
         "--N 64 --workers 1").split()
KG_LOSSY = """name = "kg-lossy"
fields = ["u"]
[parameters]
C = 1.0
w0 = 1.0
lam = -1.0
gamma = 1e-4
[energy]
kinetic = "u_t**2/2"
bond = "C*(u_next - u)**2/2"
site = "w0**2*u**2/2 + lam*u**4/4"
[dissipation]
site = "gamma*u_t**2/2"
"""
ROTOR2 = """name = "rotor2"
fields = ["u", "v"]
branch = "u"
[parameters]
c = 1.0
mv = 1.5
kv = 2.0
g = 0.3
b = 1.0
[energy]
kinetic = "u_t**2/2 + mv*v_t**2/2"
bond = "c*(u_next - u)**2/2 + b*(u_next - u)**4/4"
site = "kv*v**2/2 + 0.1*(u - v)**2/2 + g*u**2*v"
"""
FOUND = []


def say(part, what, ok, detail=""):
    line = f"{'  ' if ok else '!!'} {part:9s} {what}: {detail}"
    print(line, flush=True)
    if not ok:
        FOUND.append(line)


def flexmm(args, timeout=600):
    t0 = time.perf_counter()
    p = subprocess.run([PY, "-m", "cli", *args], cwd=ROOT, env=ENV, capture_output=True,
                       text=True, timeout=timeout)
    return p, time.perf_counter() - t0


def same_store(a, b) -> list:
    """What differs between two stores: variables and attributes, bit for bit."""
    import xarray as xr

    A, B = xr.open_zarr(a, chunks=None), xr.open_zarr(b, chunks=None)
    out = [n for n in sorted(set(A.variables) | set(B.variables))
           if n not in A.variables or n not in B.variables
           or not np.array_equal(A[n].values, B[n].values,
                                 equal_nan=A[n].dtype.kind == "f")]
    out += [f"attr {k}" for k in sorted(set(A.attrs) | set(B.attrs))
            if str(A.attrs.get(k)) != str(B.attrs.get(k))]
    return out


def one_line_error(p, *needles) -> tuple[bool, str]:
    lines = p.stderr.strip().splitlines()
    last = lines[-1] if lines else ""
    ok = (p.returncode == 2 and "Traceback" not in p.stderr
          and all(n in last for n in needles))
    return ok, last[:200]


def part_interrupt(tmp, rng, tries):
    for workers in ("1", "2"):
        args = FPUT12 + ["--workers", workers]
        ref = tmp / f"ref{workers}"
        p, whole = flexmm(["map", *args, "--out", str(ref)])
        say("interrupt", f"reference, {workers} worker(s)", p.returncode == 0, f"{whole:.0f} s")
        for i in range(tries):
            sig = rng.choice([signal.SIGINT, signal.SIGTERM, signal.SIGKILL])
            at = rng.uniform(0.5, whole)
            out = tmp / f"int{workers}_{i}"
            q = subprocess.Popen([PY, "-m", "cli", "map", *args, "--out", str(out)], cwd=ROOT,
                                 env=ENV, stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                                 text=True, start_new_session=True)
            time.sleep(at)
            if q.poll() is None:
                (os.killpg if sig == signal.SIGKILL else os.kill)(q.pid, sig)
            _, err = q.communicate(timeout=180)
            want = {signal.SIGINT: 130, signal.SIGTERM: 143, signal.SIGKILL: -9}[sig]
            said = [t for t in err.strip().splitlines() if not t.startswith("map: ")]
            clean = q.returncode in (0, want) and (
                sig == signal.SIGKILL or q.returncode == 0
                or (len(said) == 1 and "Traceback" not in err))
            again, t = flexmm(["map", *args, "--out", str(out)])
            diff = same_store(ref / "map.zarr", out / "map.zarr") if again.returncode == 0 \
                else ["rerun failed: " + again.stderr.strip()[-150:]]
            left = (out / "map.zarr.lock").exists()
            say("interrupt", f"{workers}w {signal.Signals(sig).name} at {at:.1f} s",
                clean and not diff and not left,
                f"exit {q.returncode}; rerun {t:.0f} s; "
                + ("store bit for bit" if not diff else f"differs: {diff[:4]}")
                + ("; lock left" if left else ""))


def part_store(tmp, rng, tries):
    import xarray as xr

    ref = tmp / "store_ref"
    p, _ = flexmm(["map", *FPUT4, "--out", str(ref)])
    ds = xr.open_zarr(ref / "map.zarr")
    layout = (tuple(ds.sizes) == ("beta", "k") and ds["k"].attrs.get("units") == "rad per site"
              and "units" in ds["beta"].attrs and ds.attrs.get("param_alpha") == 1.0
              and all("units" in ds[n].attrs for n in ds.data_vars
                      if n.startswith(("peak_gain", "growth", "t_simulated"))))
    say("store", "xr.open_zarr layout", p.returncode == 0 and layout,
        f"dims {dict(ds.sizes)}, k units {ds['k'].attrs.get('units')!r}")
    files = sorted(str(f.relative_to(ref)) for f in (ref / "map.zarr").rglob("*")
                   if f.is_file())
    for i in range(tries):
        name, how = rng.choice(files), rng.choice(["flip", "flip", "truncate", "empty",
                                                   "delete"])
        out = tmp / f"damaged{i}"
        shutil.copytree(ref, out)
        f = out / name
        data = bytearray(f.read_bytes())
        if how == "flip" and data:
            data[rng.randrange(len(data))] ^= 1 << rng.randrange(8)
            f.write_bytes(bytes(data))
        elif how == "truncate":
            f.write_bytes(bytes(data[:rng.randrange(max(len(data), 1))]))
        elif how == "empty":
            f.write_bytes(b"")
        else:
            f.unlink()
        q, t = flexmm(["map", *FPUT4, "--out", str(out)])
        if q.returncode == 0:
            diff = same_store(ref / "map.zarr", out / "map.zarr")
            try:
                xr.open_zarr(out / "map.zarr").load()
                readable = True
            except Exception:  # noqa: BLE001 - any failure is the finding
                readable = False
            ok, detail = not diff and readable, ("bit for bit" if not diff else
                                                 f"differs: {diff[:3]}") + (
                "" if readable else "; xr.open_zarr fails")
        else:
            ok, detail = one_line_error(q, "--overwrite")
        say("store", f"{how} {name}", ok, f"{t:.0f} s, {detail}")


def part_refuse(tmp):
    ref = tmp / "refuse_ref"
    flexmm(["map", *FPUT4, "--out", str(ref)])
    model = tmp / "mine.toml"
    text, _ = flexmm(["models", "fput"])
    model.write_text(text.stdout)
    changes = {
        "alpha": ("--param alpha=1", "--param alpha=0.9"), "axis": ("beta=0.8,1.6",
                                                                   "beta=0.8,1.7"),
        "N": ("--N 64", "--N 65"), "amplitude": ("--amplitude 0.1", "--amplitude 0.11"),
        "seeds": ("--workers 1", "--workers 1 --seeds 2"),
        "t_end": ("--workers 1", "--workers 1 --t-end 500"),
        "block": ("--workers 1", "--workers 1 --block 2"),
        "model": ("--model fput", "--model klein-gordon"),
        "model file": ("--model fput", f"--model {model}"),
    }
    base = " ".join(FPUT4)
    for what, (a, b) in changes.items():
        out = tmp / f"refuse_{what.replace(' ', '_')}"
        shutil.copytree(ref, out)
        if what == "model file":  # the user's copy of fput with its energy changed
            model.write_text(text.stdout.replace("beta*(u_next - u)**4/4",
                                                 "beta*(u_next - u)**4/4.5"))
        p, _ = flexmm(["map", *base.replace(a, b).split(), "--out", str(out)])
        ok, last = one_line_error(p, "--overwrite")
        same = not same_store(ref / "map.zarr", out / "map.zarr")
        say("refuse", f"{what} changed", ok and same, last)
    out = tmp / "two"
    args = [PY, "-m", "cli", "map", *FPUT4, "--out", str(out)]
    first = subprocess.Popen(args, cwd=ROOT, env=ENV, stdout=subprocess.PIPE,
                             stderr=subprocess.PIPE, text=True)
    end = time.monotonic() + 120
    while not (out / "map.zarr.lock").exists() and time.monotonic() < end:
        time.sleep(0.05)
    p, _ = flexmm(args[3:])
    first.communicate(timeout=300)
    ok, last = one_line_error(p, "is being written by pid")
    same = first.returncode == 0 and not same_store(ref / "map.zarr", out / "map.zarr")
    say("refuse", "two maps into one --out", ok and same, last)


def _point(args):
    p, _ = flexmm(["point", *args, "--json"])
    return json.loads(p.stdout) if p.returncode == 0 else {"error": p.stderr[-200:]}


def part_cells(tmp):
    import xarray as xr

    from energy import load_model
    from numerics.models import exact_gain

    (tmp / "kg-lossy.toml").write_text(KG_LOSSY)
    (tmp / "rotor2.toml").write_text(ROTOR2)
    maps = {
        "fput": (FPUT4, {"alpha": 1.0}),
        "kg-lossy": (f"--model {tmp / 'kg-lossy.toml'} --param gamma=1e-5,1e-3 --k 0.6,1.2 "
                     "--amplitude 0.2 --N 64 --workers 1".split(), {}),
        "rotor2": (f"--model {tmp / 'rotor2.toml'} --param g=0.3,0.6 --k 1.0,2.0 "
                   "--amplitude 0.1 --N 64 --workers 1".split(), {}),
    }
    for name, (args, fixed) in maps.items():
        out = tmp / f"cells_{name}"
        p, t = flexmm(["map", *args, "--out", str(out)])
        if p.returncode != 0:
            say("cells", f"{name} map", False, p.stderr.strip()[-200:])
            continue
        ds = xr.open_zarr(out / "map.zarr", chunks=None)
        rows, cols = ds.attrs["axes"].split()
        model_arg = args[args.index("--model") + 1]
        for r in ds[rows].values:
            for c in ds[cols].values:
                cell = ds.sel({rows: r, cols: c})
                params = {**fixed, rows: float(r)} if rows != "k" else {**fixed}
                k = float(c) if cols == "k" else float(ds.attrs["k"])
                pargs = ["--model", model_arg, "--k", repr(k), "--amplitude",
                         str(ds.attrs["amplitude"]), "--N", str(ds.attrs["N"]), "--simulate"]
                for n, v in params.items():
                    pargs += ["--param", f"{n}={v!r}"]
                pt = _point(pargs)
                theories = pt.get("theories", pt)
                sim = theories.get("simulated", {}) if isinstance(theories, dict) else {}
                words = {1: "MI", 0: "stable", -1: "undetermined"}
                mine = words[int(cell["verdict_simulated"])]
                theirs = str(sim.get("verdict", "?"))
                rate_m, rate_p = float(cell["peak_gain_simulated"]), sim.get("peak_gain")
                agree = (mine == "MI") == theirs.startswith("MI") and (
                    mine != "MI" or rate_p is None
                    or abs(rate_m / float(rate_p) - 1) < 0.02)
                model = load_model(model_arg if name == "fput" else model_arg,
                                   **{n: v for n, v in params.items()})
                ex = exact_gain(model, k, float(ds.attrs["amplitude"]), N=int(ds.attrs["N"]))
                stored = float(cell["peak_gain_exact"])
                same_exact = (stored == ex.peak_gain
                              or abs(stored - ex.peak_gain) <= 1e-12 * abs(ex.peak_gain))
                say("cells", f"{name} {rows}={r:g} {cols}={c:g}", agree and same_exact,
                    f"map {mine} {rate_m:.4g} / point {theirs} {rate_p}; exact {stored:.6g} "
                    f"/ exact_gain {ex.peak_gain:.6g}")
        if name == "fput":  # g1 = omega''(k), omega = 2 sin(k/2): by hand
            ks = ds["k_simulated"].values
            hand = -np.sin(ks / 2) / 2
            err = float(np.max(np.abs(ds["g1"].values - hand) / np.abs(hand)))
            say("cells", "fput g1 against -sin(k/2)/2", err < 1e-12, f"{err:.1e}")


def part_grids(tmp):
    import xarray as xr

    tries = {
        "reversed axes": FPUT4[:4] + ["--param", "beta=1.6,0.8", "--k", "2.8:2.6:3",
                                      "--amplitude", "0.1", "--N", "64", "--theory-only"],
        "1 x n": FPUT4[:4] + ["--param", "beta=1:1:1", "--k", "2.6,2.7", "--amplitude",
                              "0.1", "--N", "64", "--theory-only", "--exact"],
        "repeated value": FPUT4[:4] + ["--param", "beta=1,1", "--k", "2.6,2.7",
                                       "--theory-only"],
        "branch crossing": "--model diatomic-fput --param m=0.5,1,2 --k 2.0,3.14159 "
                           "--amplitude 0.05 --N 64 --theory-only --exact".split(),
        "flexmm --start paper": "--model flexmm --start paper --param K_theta=0.0155,0.02 "
                                "--k 0.8,1.2 --amplitude 0.02 --N 64 --theory-only "
                                "--exact".split(),
        "paper flags": "--alpha 2.5 --K-s 0.01851 --delta=-0.003,0.003 --k 0.5:1.2:3 "
                       "--case coupled --theory-only --N 100".split(),
    }
    for what, args in tries.items():
        out = tmp / f"grid_{what.replace(' ', '_')}"
        p, t = flexmm(["map", *args, "--workers", "1", "--out", str(out)])
        if p.returncode == 2:
            ok, last = one_line_error(p)
            say("grids", what, ok and "--" in last, f"refused: {last}")
            continue
        ok = p.returncode == 0 and "wrote" in p.stdout.strip().splitlines()[-1]
        detail = f"exit {p.returncode}, {t:.0f} s"
        if ok:
            ds = xr.open_zarr(out / "map.zarr", chunks=None)
            ascending = all(np.all(np.diff(ds[d].values) > 0) for d in ds.dims)
            ok = ascending
            detail += f"; dims {dict(ds.sizes)}, ascending {ascending}"
        say("grids", what, ok, detail)


def part_progress(tmp):
    out = tmp / "progress"
    args = [PY, "-m", "cli", "map", "--model", "fput", "--param", "alpha=1", "--param",
            "beta=0.5:1.5:4", "--k", "1.0:2.8:6", "--amplitude", "0.1", "--N", "128",
            "--workers", "2", "--out", str(out)]
    t0 = time.perf_counter()
    p = subprocess.Popen(args, cwd=ROOT, env=ENV, stdout=subprocess.PIPE,
                         stderr=subprocess.STDOUT, text=True, bufsize=1)
    stamped = [(time.perf_counter() - t0, line.rstrip()) for line in p.stdout]
    p.wait()
    first = stamped[0][0] if stamped else float("inf")
    est = next((t for t, s in stamped if s.startswith("estimate: about")), None)
    prog = [(t, s) for t, s in stamped if s.startswith("map: ")]
    zero = [s for _, s in prog if "about 0 s left" in s]
    say("progress", "first line", first < 5, f"{first:.1f} s")
    say("progress", "a progress line", bool(prog) or stamped[-1][0] - (est or 0) < 15,
        f"{[f'{t:.0f} s' for t, _ in prog]} after an estimate at {est}")
    say("progress", "no 'about 0 s left'", not zero, str(zero[:1]))
    last = stamped[-1][1] if stamped else ""
    say("progress", "last line", p.returncode == 0 and last.startswith("wrote ")
        and str(out) in last, last[:120])


PARTS = {"interrupt": part_interrupt, "store": part_store, "refuse": part_refuse,
         "cells": part_cells, "grids": part_grids, "progress": part_progress}


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--part", choices=["all", *PARTS], default="all")
    ap.add_argument("--tries", type=int, default=6, help="interrupt/damage tries per part")
    ap.add_argument("--seed", type=int, default=97)
    a = ap.parse_args(argv)
    rng = random.Random(a.seed)
    with tempfile.TemporaryDirectory(prefix="probe97-") as d:
        for name, fn in PARTS.items():
            if a.part in ("all", name):
                sub = Path(d) / name
                sub.mkdir()
                if name in ("interrupt", "store"):
                    fn(sub, rng, a.tries)
                else:
                    fn(sub)
    print(f"{len(FOUND)} finding(s)" + "".join("\n" + f for f in FOUND))
    return 1 if FOUND else 0


if __name__ == "__main__":
    sys.exit(main())
