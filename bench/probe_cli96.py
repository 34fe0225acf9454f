"""probe 96: the command line and the Python entry points as a new user meets them,
at inputs nobody tried (odd numbers, bad files, hostile output folders).

Every try runs in a fresh process with a 60 s limit (a try past it is a finding). A failure
must be one line on stderr, exit 2, no traceback, naming the option (or argument); a
success exits 0 and, where it writes files, says so on its last line; a failure leaves no
new file in the output folder. Python tries: a clear ModelError / ValueError / TypeError
naming the argument, never a silent NaN, a hang or a crash.

    OMP_NUM_THREADS=1 NUMBA_NUM_THREADS=1 python -m bench.probe_cli96 [--only WORD]
        [--part all|cli|python] [--json OUT.json]

Seeded (numpy's default_rng(96)) where it draws; the tries themselves are listed below.
"""

from __future__ import annotations

import argparse
import json
import os
import shlex
import stat
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

LIMIT = 60.0
ROOT = Path(__file__).resolve().parents[1]
PY = sys.executable
RNG = np.random.default_rng(96)

FPUT = "--model fput --param alpha=1 --param beta=1"
FPUT1 = "--model fput --param alpha=1"
PAPER = "--alpha 2.5 --K-s 0.01851 --K-theta 0.01551"


def _files(folder: Path) -> set:
    return {str(p.relative_to(folder)) for p in folder.rglob("*")} if folder.exists() else set()


def run_cli(args: str, tmp: Path, expect: str, needle: str | None = None,
            out: Path | None = None, stdin: bytes | None = None) -> dict:
    """One `flexmm` call. expect: 'ok' (exit 0), 'bad' (exit 2, one line naming ``needle``)."""
    argv = [PY, "-m", "cli", *shlex.split(args.replace("{tmp}", str(tmp)))]
    before = _files(out) if out is not None else None
    t0 = time.perf_counter()
    env = {**os.environ, "OMP_NUM_THREADS": "1", "NUMBA_NUM_THREADS": "1"}
    try:
        p = subprocess.run(argv, cwd=tmp, capture_output=True, timeout=LIMIT, env=env,
                           input=stdin)
    except subprocess.TimeoutExpired:
        return {"try": args, "finding": f"no answer within {LIMIT:.0f} s"}
    dt = time.perf_counter() - t0
    err = p.stderr.decode(errors="replace").strip()
    so = p.stdout.decode(errors="replace").strip()
    problems = []
    if "Traceback" in err or "Traceback" in so:
        problems.append("traceback")
    if expect == "bad":
        if p.returncode != 2:
            problems.append(f"exit {p.returncode}, not 2")
        lines = [ln for ln in err.splitlines() if ln.strip()]
        last = lines[-1] if lines else ""
        if not last.startswith(("flexmm", "usage")) and "error" not in last:
            problems.append("no error line")
        errors = [ln for ln in lines if "error" in ln]
        if len(errors) != 1:
            problems.append(f"{len(errors)} error lines")
        if needle and needle.lower() not in err.lower():
            problems.append(f"error does not name {needle!r}")
        if out is not None and _files(out) != before:
            problems.append(f"left files: {sorted(_files(out) - before)[:4]}")
    elif expect == "ok":
        if p.returncode != 0:
            problems.append(f"exit {p.returncode}")
        if needle and needle not in (so.splitlines() or [""])[-1]:
            problems.append(f"last line lacks {needle!r}")
    tail = ((err.splitlines() or [""])[-1] if expect == "bad" or p.returncode
            else (so.splitlines() or [""])[-1])
    return {"try": args, "rc": p.returncode, "seconds": round(dt, 2), "said": tail[:220],
            **({"finding": "; ".join(problems)} if problems else {})}


def _cli_tries(tmp: Path):
    """(args, expect, needle, out) for `flexmm`."""
    d = tmp / "files"
    d.mkdir(exist_ok=True)
    (d / "empty.toml").write_text("")
    (d / "binary.toml").write_bytes(bytes(RNG.integers(0, 256, 300, dtype=np.uint8)))
    (d / "syntax.toml").write_text('name = "x"\nfields = [\n')
    (d / "nofields.toml").write_text('name = "x"\n[energy]\nkinetic = "u_t**2/2"\n')
    (d / "evil.toml").write_text('name = "x"\nfields = ["u"]\n[energy]\nkinetic = "u_t**2/2"\n'
                                 'bond = "__import__(\'os\').system(\'echo hi\')"\n')
    (d / "ok.toml").write_text('name = "mine"\nfields = ["u"]\n[parameters]\nbeta = 1.0\n'
                               '[energy]\nkinetic = "u_t**2/2"\n'
                               'bond = "(u_next - u)**2/2 + beta*(u_next - u)**4/4"\n')
    (d / "afile").write_text("x")
    ro = tmp / "readonly"
    ro.mkdir(exist_ok=True)
    os.chmod(ro, stat.S_IRUSR | stat.S_IXUSR)
    yield from [
        # every --help, and the bare command
        ("--help", "ok", None, None),
        ("", "bad", "COMMAND", None),
        *[(f"{c} --help", "ok", None, None) for c in
          ("coefficients", "table", "scenes", "scene", "run", "point", "map", "soliton",
           "models")],
        ("nonsense", "bad", "nonsense", None),
        # coefficients: k at and past its boundaries
        (f"coefficients {PAPER} --k 0", "bad", "--k", None),
        (f"coefficients {PAPER} --k -1", "bad", "--k", None),
        (f"coefficients {PAPER} --k nan", "bad", "--k", None),
        (f"coefficients {PAPER} --k inf", "bad", "--k", None),
        (f"coefficients {PAPER} --k -inf", "bad", "--k", None),
        (f"coefficients {PAPER} --k 1e308", "bad", "--k", None),
        (f"coefficients {PAPER} --k ''", "bad", "--k", None),
        (f"coefficients {PAPER} --k one", "bad", "--k", None),
        (f"coefficients {PAPER} --k 3.141592653589793", "bad", "--k", None),
        (f"coefficients {PAPER} --k 0x1p0", "bad", "--k", None),
        (f"coefficients {PAPER} --k 1 --k 2", "bad", "--k", None),
        (f"coefficients {FPUT} --k 3.141592653589793 --amplitude 0.1", "ok", None, None),
        (f"coefficients {FPUT} --k 3.1415926535897936 --amplitude 0.1", "bad", "--k", None),
        (f"coefficients {FPUT} --k 1e-300 --amplitude 0.1", "bad", "--k", None),
        (f"coefficients {FPUT} --k 1.0 --amplitude 0", "bad", "--amplitude", None),
        (f"coefficients {FPUT} --k 1.0 --amplitude -0.1", "bad", "--amplitude", None),
        (f"coefficients {FPUT} --k 1.0 --amplitude nan", "bad", "--amplitude", None),
        (f"coefficients {FPUT} --k 1.0 --amplitude 1e300", "bad", "--amplitude", None),
        (f"coefficients {PAPER} --k 1.0 --amplitude 5", "bad", "--amplitude", None),
        ("coefficients --alpha 0 --K-s 0.01 --K-theta 0.01 --k 1", "bad", "--alpha", None),
        ("coefficients --alpha -2 --K-s 0.01 --K-theta 0.01 --k 1", "bad", "--alpha", None),
        ("coefficients --alpha nan --K-s 0.01 --K-theta 0.01 --k 1", "bad", "--alpha", None),
        ("coefficients --alpha 2 --K-s -0.01 --K-theta 0.01 --k 1", "bad", "--K-s", None),
        ("coefficients --alpha 2 --K-s 0.01 --K-theta inf --k 1", "bad", "--K-theta", None),
        ("coefficients --alpha 2 --K-s 0.01 --k 1", "bad", "--K-theta", None),
        ("coefficients --k 1", "bad", "--alpha", None),
        ("coefficients --alpha 2 --K-s 0.02 --K-theta 0.02 --k 1", "ok", None, None),
        ("coefficients --physical 1,2,3 --k 1", "bad", "--physical", None),
        ("coefficients --physical 0.01,2e-6,0.02,1e4,185,-1 --k 1", "bad", "--physical", None),
        ("coefficients --physical 0.01,2e-6,0.02,1e4,185,nan --k 1", "bad", "--physical", None),
        ("coefficients --physical a,b,c,d,e,f --k 1", "bad", "--physical", None),
        (f"coefficients --physical 0.01,2e-6,0.02,1e4,185,1 {PAPER} --k 1", "bad", None, None),
        # models and their files
        ("coefficients --model nosuch --k 1", "bad", "nosuch", None),
        ("coefficients --model '' --k 1", "bad", "built-in", None),
        ("coefficients --model {tmp}/files/missing.toml --k 1", "bad", "missing.toml", None),
        ("coefficients --model {tmp}/files --k 1", "bad", "not a regular file", None),
        ("coefficients --model {tmp}/files/empty.toml --k 1", "bad", "empty.toml", None),
        ("coefficients --model {tmp}/files/binary.toml --k 1", "bad", "binary.toml", None),
        ("coefficients --model {tmp}/files/syntax.toml --k 1", "bad", "syntax.toml", None),
        ("coefficients --model {tmp}/files/nofields.toml --k 1", "bad", "nofields.toml", None),
        ("coefficients --model {tmp}/files/evil.toml --k 1", "bad", "evil.toml", None),
        ("coefficients --model {tmp}/files/ok.toml --k 1 --amplitude 0.1", "ok", None, None),
        ("coefficients --model {tmp}/files/ok.toml --k 1 --param gamma=1", "bad", "gamma", None),
        ("coefficients --model {tmp}/files/ok.toml --k 1 --param beta=", "bad", "beta", None),
        ("coefficients --model {tmp}/files/ok.toml --k 1 --param beta=nan", "bad", "beta", None),
        ("coefficients --model {tmp}/files/ok.toml --k 1 --param beta", "bad", "--param", None),
        ("coefficients --model {tmp}/files/ok.toml --k 1 --param =1", "bad", "--param", None),
        ("coefficients --model fput --k 1 --param beta=1 --param beta=2", "bad", "beta", None),
        ("coefficients --model fput --k 1 --param beta=1e308 --amplitude 0.1", "bad", "beta", None),
        ("coefficients --model fput --k 1 --branch 1", "bad", "--branch", None),
        ("coefficients --model fput --k 1 --branch -1", "bad", "--branch", None),
        ("coefficients --model fput --k 1 --branch v", "bad", "--branch", None),
        ("coefficients --model fput --k 1 --time-unit 0", "bad", "--time-unit", None),
        ("coefficients --model fput --k 1 --time-unit -1", "bad", "--time-unit", None),
        ("coefficients --model fput --k 1 --length-unit nan", "bad", "--length-unit", None),
        (f"coefficients {PAPER} --k 1 --time-unit 1", "bad", "--time-unit", None),
        (f"coefficients {PAPER} --k 1 --model fput", "bad", "--model", None),
        ("coefficients --model fput --k 1 --json --amplitude 0.1", "ok", None, None),
        ("models nosuch", "bad", "nosuch", None),
        ("models fput", "ok", None, None),
        ("models --json", "ok", None, None),
        # table
        ("table --A0 0", "bad", "--A0", None),
        ("table --A0 -1", "bad", "--A0", None),
        ("table --A0 nan", "bad", "--A0", None),
        ("table --A0 1e200", "bad", "--A0", None),
        ("table --A0 1.4", "ok", None, None),
        # scene
        ("scene nosuch --quick --out {tmp}/sc", "bad", "nosuch", tmp / "sc"),
        ("scene fig2-dispersion --quick --out {tmp}/files/afile", "bad", "--out", None),
        ("scene fig2-dispersion --quick --out {tmp}/files/afile/x", "bad", "--out", ro),
        ("scene fig2-dispersion --replot --out {tmp}/noreplot", "bad", "--replot",
         tmp / "noreplot"),
        ("scene fig2-dispersion --quick --seed -1 --out {tmp}/sc2", "bad", "--seed", None),
        ("run --quick --out {tmp}/files/afile", "bad", "--out", None),
        # point
        (f"point {PAPER} --k 0.81681 --case coupled --N 2", "bad", "--N", None),
        (f"point {PAPER} --k 0.81681 --case coupled --N 0", "bad", "--N", None),
        (f"point {PAPER} --k 0.81681 --case coupled --N -5", "bad", "--N", None),
        (f"point {PAPER} --k 0.81681 --case coupled --N 1e9", "bad", "--N", None),
        (f"point {PAPER} --k 0.81681 --case coupled --N 500.5", "bad", "--N", None),
        (f"point {PAPER} --k 0.81681 --case coupled --N 99999999999", "bad", "--N", None),
        (f"point {PAPER} --k 0.81681 --case nosuch", "bad", "--case", None),
        (f"point {PAPER} --k 0.81681 --case coupled --t-end 0 --simulate", "bad", "--t-end",
         None),
        (f"point {PAPER} --k 0.81681 --case coupled --t-end nan --simulate", "bad", "--t-end",
         None),
        (f"point {PAPER} --k 0.81681 --case coupled --seeds 0 --simulate", "bad", "--seeds",
         None),
        (f"point {PAPER} --k 0.81681 --case coupled --seeds 100000 --simulate", "bad",
         "--seeds", None),
        (f"point {PAPER} --k 0.81681 --case coupled --out {{tmp}}/files/afile", "bad", "--out",
         None),
        (f"point {PAPER} --k 0.81681 --case coupled --out {{tmp}}/files/afile/p", "bad", "--out",
         ro),
        (f"point {PAPER} --k 0.81681 --case coupled --start linear", "bad", "--start", None),
        (f"point {FPUT} --k 2.5 --amplitude 0.1 --N 3", "bad", "--N", None),
        (f"point {FPUT} --k 2.5 --amplitude 0.1 --N 4 --out {{tmp}}/p4", "bad", "--N", tmp / "p4"),
        (f"point {FPUT} --k 2.5 --amplitude 0.1 --N 64 --t-end 1e300 --simulate", "bad",
         "--t-end", None),
        (f"point {FPUT} --k 2.5 --amplitude 0.1 --N 64 --start paper", "bad", "--start", None),
        (f"point {FPUT} --k 2.5 --amplitude 0.1 --N 64 --out ''", "ok", "wrote", None),
        # the epilog examples, as written (small sizes are theirs already)
        ("point --model fput --param alpha=1 --param beta=1.5 --k 2.5 --amplitude 0.1 --N 64 "
         "--out out/point", "ok", "wrote", None),
        ("point --alpha 2.5 --K-s 0.01851 --K-theta 0.01551 --k 0.81681 --case coupled",
         "ok", None, None),
        ("soliton --model fput --param alpha=1 --param beta=1 --k 1.0 --amplitude 0.05",
         "ok", None, None),
        ("soliton --alpha 2.5 --K-s 0.01851 --K-theta 0.02151 --k 0.92991 --amplitude 0.002 "
         "--case rotation", "ok", None, None),
        ("map --model fput --param alpha=1 --param beta=0.5:1.5:3 --k 0.5:3:4 --amplitude 0.1 "
         "--theory-only --out out/fput-map", "ok", "wrote", None),
        ("map --alpha 2.5 --K-s 0.01851 --delta -0.01:0.01:5 --k 0.3:2.9:6 --case rotation "
         "--theory-only --out out/map", "ok", "wrote", None),
        ("coefficients --model fput --param alpha=1 --param beta=1 --k 1.57 --amplitude 0.1",
         "ok", None, None),
        ("scenes", "ok", None, None),
        ("point --model fput --param alpha=1 --param beta=1.5 --k 3.1 --amplitude 0.1 --N 64 "
         "--simulate --seeds 2 --out out/point", "ok", "wrote", None),
        ("point --physical 0.01,2e-6,0.02,1e4,185,1 --k 1.0 --case rotation --simulate "
         "--seeds 2 --out out/point", "ok", "wrote", None),
        ("soliton --model fput --param alpha=0.5 --k 1.6 --amplitude 0.1 --simulate --travel 5 "
         "--out out/soliton", "ok", "wrote", None),
        ("soliton --alpha 3 --K-s 0.05 --K-theta 0.03 --k 0.7 --amplitude 0.009 --kind dark "
         "--simulate --travel 5 --out out/soliton", "ok", "wrote", None),
        ("scene fig2-dispersion --quick --out out", "ok", "wrote", None),
        ("table --A0 1.4", "ok", None, None),
        ("models", "ok", None, None),
        # `flexmm run --quick --out out` (every scene, ~2 min) is left to make run / CI
        # soliton
        (f"soliton {FPUT} --k 1.0 --amplitude 0.05 --kind nosuch", "bad", "--kind", None),
        (f"soliton {FPUT} --k 1.0 --amplitude 0.05 --travel 0 --simulate", "bad", "--travel",
         None),
        (f"soliton {FPUT} --k 1.0 --amplitude 0.05 --travel nan --simulate", "bad",
         "--travel", None),
        (f"soliton {FPUT} --k 1.0 --amplitude 0.05 --travel 1e9 --simulate", "bad",
         "--travel", None),
        (f"soliton {FPUT} --k 1.0 --amplitude 0.05 --N 3 --simulate", "bad", "--N", None),
        (f"soliton {FPUT} --k 1.0 --amplitude 0.05 --kind bright", "bad", "--kind", None),
        (f"soliton {FPUT} --k 1.0 --amplitude 0.05 --theory paper", "bad", "--theory", None),
        (f"soliton {FPUT} --k 1.0 --amplitude 0.05 --out {{tmp}}/files/afile", "bad", "--out",
         None),
        (f"soliton {FPUT} --k 1.0 --amplitude 1e-200", "ok", None, None),
        (f"soliton {FPUT} --k 1.0 --amplitude 0.5", "ok", None, None),
        # map
        (f"map {FPUT1} --param beta=1:1:1 --k 0.5:1:2 --theory-only --out {{tmp}}/m1", "ok",
         "wrote", None),
        (f"map {FPUT1} --param beta=2:1:3 --k 0.5:1:2 --theory-only --out {{tmp}}/m2", "ok",
         "wrote", None),
        (f"map {FPUT1} --param beta=1:2:0 --k 0.5:1:2 --theory-only --out {{tmp}}/m3", "bad",
         "beta", tmp / "m3"),
        (f"map {FPUT1} --param beta=1:2:-3 --k 0.5:1:2 --theory-only --out {{tmp}}/m4", "bad",
         "beta", tmp / "m4"),
        (f"map {FPUT1} --param beta=1:2:2.5 --k 0.5:1:2 --theory-only --out {{tmp}}/m5", "bad",
         "beta", tmp / "m5"),
        (f"map {FPUT1} --param beta=1:nan:2 --k 0.5:1:2 --theory-only --out {{tmp}}/m6", "bad",
         "beta", tmp / "m6"),
        (f"map {FPUT1} --param beta=1,1,1 --k 0.5:1:2 --theory-only --out {{tmp}}/m7", "bad",
         "beta", tmp / "m7"),
        (f"map {FPUT1} --param beta=1:2:3 --k 0.5:4:2 --theory-only --out {{tmp}}/m8", "bad",
         "--k", tmp / "m8"),
        (f"map {FPUT1} --param beta=1:2:3 --k 0:1:2 --theory-only --out {{tmp}}/m9", "bad",
         "--k", tmp / "m9"),
        (f"map {FPUT1} --param beta=1:2:3 --k '' --theory-only --out {{tmp}}/m10", "bad",
         "--k", tmp / "m10"),
        (f"map {FPUT1} --param beta=1:2:3 --k 1,, --theory-only --out {{tmp}}/m11", "bad",
         "--k", tmp / "m11"),
        (f"map {FPUT1} --param beta=1:2:3 --k 0.5:1:100000000 --theory-only --out {{tmp}}/m12",
         "bad", "--k", tmp / "m12"),
        (f"map {FPUT1} --param beta=1:2:3 --k 0.5:1:2 --theory-only --out {{tmp}}/files/afile",
         "bad", "--out", None),
        (f"map {FPUT1} --param beta=1:2:3 --k 0.5:1:2 --theory-only --out /proc/96/m",
         "bad", "--out", ro),
        (f"map {FPUT1} --param beta=1:2:3 --k 0.5:1:2 --theory-only --workers 0 "
         "--out {tmp}/m13", "bad", "--workers", tmp / "m13"),
        (f"map {FPUT1} --param beta=1:2:3 --k 0.5:1:2 --theory-only --workers -1 "
         "--out {tmp}/m14", "bad", "--workers", tmp / "m14"),
        (f"map {FPUT1} --param beta=1:2:3 --k 0.5:1:2 --theory-only --block 0 "
         "--out {tmp}/m15", "bad", "--block", tmp / "m15"),
        (f"map {FPUT1} --param beta=1:2:3 --k 0.5:1:2 --theory-only --timeout -1 "
         "--scheduler tcp://127.0.0.1:1 --out {tmp}/m16", "bad", "--timeout", tmp / "m16"),
        (f"map {FPUT1} --param beta=1:2:3 --k 0.5:1:2 --theory-only --scheduler nonsense "
         "--out {tmp}/m17", "bad", "--scheduler", tmp / "m17"),
        (f"map {FPUT1} --param beta=1:2:3 --k 0.5:1:2 --theory-only --scheduler "
         "tcp://127.0.0.1:1 --timeout 1 --out {tmp}/m18", "bad", "--scheduler", tmp / "m18"),
        (f"map {FPUT1} --param beta=1:2:3 --param alpha=1:2:2 --k 0.5:1:2 --theory-only "
         "--out {tmp}/m19", "bad", None, tmp / "m19"),
        (f"map {FPUT1} --param beta=1:2:3 --k 1 --theory-only --out {{tmp}}/m20", "bad", "--k",
         tmp / "m20"),
        (f"map {FPUT1} --param beta=1:2:3 --k 0.5:1:2 --theory-only --device gpu "
         "--out {tmp}/m21", "bad", "--device", tmp / "m21"),
        (f"map {FPUT1} --param beta=1:2:3 --k 0.5:1:2 --theory-only --amplitude 0.1:0.2:2 "
         "--out {tmp}/m22", "bad", "--amplitude", tmp / "m22"),
        (f"map {FPUT1} --param beta=1:2:3 --k 0.5:1:2 --t-end -5 --out {{tmp}}/m23", "bad",
         "--t-end", tmp / "m23"),
        (f"map {PAPER} --delta 0.01 --k 1 --case rotation --theory-only --out {{tmp}}/m24",
         "bad", None, tmp / "m24"),
        ("map --alpha 2.5 --K-s 0.01851 --delta -0.01:0.01:2 --k 1:2:2 --case rotation "
         "--theory-only --N 2 --out {tmp}/m25", "bad", "--N", tmp / "m25"),
        ("map --alpha 2.5 --K-s 0.01851 --delta 0.01:-0.01:2 --k 2:1:2 --case rotation "
         "--theory-only --out {tmp}/m26", "ok", "wrote", None),
        ("map --alpha 2.5 --K-s 0.01851 --delta 0.02 --k 1:2:2 --case rotation "
         "--theory-only --out {tmp}/m27", "bad", "--delta", tmp / "m27"),
    ]


#: Python tries: (label, statement, expected exception names ('' = returns), needle)
PY_SETUP = ("import math, numpy as np, energy, derivation, numerics.models as nm, "
            "numerics.maps as mp; from generated import soliton as closed; "
            "m = energy.load_model('fput', alpha=1, beta=1); "
            "lossy = energy.load_model('flexmm-lossy')")
PY_TRIES = [
    ("carrier k < 0", "nm.carrier(m, -1.0)", "ModelError", "(0, pi]"),
    ("carrier k > pi", "nm.carrier(m, 7.0)", "ModelError", "(0, pi]"),
    ("carrier k = 0", "nm.carrier(m, 0.0)", "ModelError", "(0, pi]"),
    ("carrier k = pi", "print(nm.carrier(m, math.pi).omega)", "", None),
    ("carrier k nan", "nm.carrier(m, math.nan)", "ModelError", "k must"),
    ("carrier k array", "nm.carrier(m, np.array(1.0))", "ModelError", "k must"),
    ("carrier branch 5", "nm.carrier(m, 1.0, 5)", "ModelError", "branch"),
    ("carrier branch 1.5", "nm.carrier(m, 1.0, 1.5)", "ModelError", "branch"),
    ("nls k 4", "nm.nls(m, 4.0)", "ModelError", "(0, pi]"),
    ("nls gain nan", "nm.nls(m, 2.5).gain(math.nan, 0.1)", "ModelError", "offset"),
    ("nls peak_gain -0.1", "nm.nls(m, 2.5).peak_gain(-0.1)", "ModelError", "amplitude"),
    ("nls soliton 0", "nm.nls(m, 1.0).soliton(0.0)", "ModelError", "amplitude"),
    ("branches nan", "nm.branches(m, math.nan)", "ModelError", "kappa"),
    ("branches '1'", "nm.branches(m, '1')", "ModelError", "kappa"),
    ("damping_rates nan", "nm.damping_rates(lossy, math.nan)", "ModelError", "kappa"),
    ("carrier_damping k 7", "nm.carrier_damping(lossy, 7.0)", "ModelError", "(0, pi]"),
    ("model_coefficients amp 0", "nm.model_coefficients(m, 1.0, 0.0)", "ModelError",
     "amplitude"),
    ("travelling_wave amp 10", "nm.travelling_wave(m, 1.0, 10.0)", "ModelError", "amplitude"),
    ("travelling_wave harmonics 0", "nm.travelling_wave(m, 1.0, 0.1, harmonics=0)",
     "ModelError", "harmonics"),
    ("travelling_wave harmonics 10**6", "nm.travelling_wave(m, 1.0, 0.1, harmonics=10**6)",
     "ModelError", "harmonics"),
    ("exact_gain N 2", "nm.exact_gain(m, 1.0, 0.1, N=2)", "ModelError", "N must"),
    ("exact_gain N 3.5", "nm.exact_gain(m, 1.0, 0.1, N=3.5)", "ModelError", "N must"),
    ("exact_gain samples 1", "nm.exact_gain(m, 1.0, 0.1, samples=1)", "ModelError", "samples"),
    ("exact_gain samples 10**8", "nm.exact_gain(m, 1.0, 0.1, samples=10**8)", "ModelError",
     "samples"),
    ("four_wave samples 1", "nm.four_wave(m, 1.0, 0.1, samples=1)", "ModelError", "samples"),
    ("four_wave samples 10**8", "nm.four_wave(m, 2.5, 0.1, samples=10**8)", "ModelError",
     "samples"),
    ("hill_spectrum None", "nm.hill_spectrum(None, [0.1])", "ModelError", "wave"),
    ("hill_spectrum nan", "nm.hill_spectrum(nm.travelling_wave(m, 1.0, 0.1), [math.nan])",
     "ModelError", "offsets"),
    ("ring_offsets 0", "nm.ring_offsets(0)", "ModelError", "N must"),
    ("ring_offsets 2.5", "nm.ring_offsets(2.5)", "ModelError", "N must"),
    ("simulate_model t_end 0", "nm.simulate_model(m, 1.0, 0.1, N=16, t_end=0)", "ModelError",
     "t_end"),
    ("simulate_model dt 0", "nm.simulate_model(m, 1.0, 0.1, N=16, t_end=10, dt=0)",
     "ModelError", "dt"),
    ("simulate_model noise nan",
     "nm.simulate_model(m, 1.0, 0.1, N=16, t_end=10, noise=math.nan)", "ModelError", "noise"),
    ("simulate_model method x", "nm.simulate_model(m, 1.0, 0.1, N=16, t_end=10, method='x')",
     "ValueError", "method"),
    ("simulate_seeds seeds 0", "nm.simulate_seeds(m, 1.0, 0.1, None, N=16, seeds=0, t_end=10)",
     "ModelError", "seeds"),
    ("simulate_soliton travel nan", "nm.simulate_soliton(m, 1.0, 0.05, travel=math.nan)",
     "ModelError", "travel"),
    ("ring_soliton kind x", "nm.ring_soliton(m, 1.0, 0.05, kind='x')", "ModelError", "kind"),
    ("with_params beta nan", "m.with_params(beta=math.nan)", "ModelError", "beta"),
    ("load_model 42", "energy.load_model(42)", "ModelError", "model"),
    ("bright_width -a", "w = closed.bright_width(-0.002, 0.02, 40.0); assert w > 0, w", "", None),
    ("dark_width -a", "w = closed.dark_width(-0.1, 0.2, 1.0, -4.0); assert w > 0, w", "", None),
    ("parse_spec 1:2:0", "mp.parse_spec('1:2:0', 'x')", "ValueError", "SPEC"),
    ("parse_spec 1:2:1e9", "mp.parse_spec('1:2:1000000000', 'x')", "ValueError", "at most"),
    ("snap_carrier nan", "mp.snap_carrier(math.nan, 64)", "ValueError", "k must"),
    ("run_map None", "mp.run_map(None, 'x')", "TypeError", "params"),
    ("damping_parameters 'x'", "mp.damping_parameters('x')", "ValueError TypeError ModelError",
     "lattice"),
    ("ModelMapParameters N 3", "mp.ModelMapParameters.from_model('fput', ('beta', [1.0, 2.0]), "
     "('k', [1.0, 2.0]), 0.02, N=3, theory_only=True)", "ValueError ModelError", "N"),
    ("solve_case nonsense", "derivation.solve_case('nonsense')", "ValueError", "case"),
    ("model_energies None", "derivation.model_energies(None)", "ModelError", "model"),
    ("compile_model folder", "import tempfile; derivation.compile_model(energy.builtin('fput'), "
     "tempfile.mkdtemp())", "ValueError", "folder"),
    ("compile_model None", "derivation.compile_model(energy.builtin('fput'), None)",
     "TypeError", "path"),
]


def run_py(label: str, stmt: str, expect: str, needle: str | None) -> dict:
    """One Python try in a fresh interpreter (a hang or a crash is a finding)."""
    code = (f"{PY_SETUP}\ntry:\n    {stmt}\nexcept Exception as e:\n"
            "    print('RAISED', type(e).__name__, '|', str(e)[:300])\nelse:\n"
            "    print('RETURNED')\n")
    env = {**os.environ, "OMP_NUM_THREADS": "1", "NUMBA_NUM_THREADS": "1"}
    t0 = time.perf_counter()
    try:
        p = subprocess.run([PY, "-c", code], cwd=ROOT, capture_output=True, timeout=LIMIT,
                           env=env)
    except subprocess.TimeoutExpired:
        return {"try": label, "finding": f"no answer within {LIMIT:.0f} s"}
    out = p.stdout.decode(errors="replace").strip().splitlines()
    said = out[-1] if out else p.stderr.decode(errors="replace").strip()[-200:]
    problems = []
    if p.returncode != 0:
        problems.append(f"interpreter exit {p.returncode}")
    elif expect and not said.startswith("RAISED"):
        problems.append("returned, no error")
    elif expect and said.split()[1] not in expect.split():
        problems.append(f"raised {said.split()[1]}, not {expect}")
    elif not expect and not said.startswith("RETURNED"):
        problems.append("raised")
    if expect and needle and needle.lower() not in said.lower():
        problems.append(f"error does not name {needle!r}")
    return {"try": label, "rc": p.returncode, "seconds": round(time.perf_counter() - t0, 2),
            "said": said[:220], **({"finding": "; ".join(problems)} if problems else {})}


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--only", help="run only the tries whose text holds this")
    ap.add_argument("--json", help="write every try's outcome here")
    ap.add_argument("--part", choices=("all", "cli", "python"), default="all")
    a = ap.parse_args(argv)
    results = []
    with tempfile.TemporaryDirectory() as t:
        tmp = Path(t)
        try:
            for args, expect, needle, out in _cli_tries(tmp):
                if a.part == "python" or a.only and a.only not in args:
                    continue
                r = run_cli(args, tmp, expect, needle, out)
                results.append(r)
                mark = "FINDING" if "finding" in r else "ok"
                print(f"[{mark}] flexmm {args}\n    -> rc {r.get('rc')} "
                      f"({r.get('seconds')} s): {r.get('said', '')}"
                      + (f"\n    !! {r['finding']}" if "finding" in r else ""), flush=True)
        finally:
            os.chmod(tmp / "readonly", stat.S_IRWXU)
    for label, stmt, expect, needle in PY_TRIES:
        if a.part == "cli" or a.only and a.only not in label:
            continue
        r = run_py(label, stmt, expect, needle)
        results.append(r)
        mark = "FINDING" if "finding" in r else "ok"
        print(f"[{mark}] python: {label}\n    -> {r.get('said', '')}"
              + (f"\n    !! {r['finding']}" if "finding" in r else ""), flush=True)
    n = sum("finding" in r for r in results)
    print(f"{len(results)} tries, {n} findings")
    if a.json:
        Path(a.json).write_text(json.dumps(results, indent=1))
    return 0


if __name__ == "__main__":
    sys.exit(main())
