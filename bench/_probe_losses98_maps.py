"""probe_losses98's sections (4), maps against points, interrupted and resumed, and (5),
the edge inputs (the model files written by ``probe_losses98``)."""

from __future__ import annotations

import json
import math
import os
import signal
import subprocess
import sys
import time

import numpy as np


def _rel(a, b):
    if a is None or b is None:
        return 0.0 if a is None and b is None else math.inf
    a, b = float(a), float(b)
    if a == b or (math.isnan(a) and math.isnan(b)):
        return 0.0
    return abs(a - b) / max(abs(a), abs(b))


#: a map cell's verdict code, as the store writes it (cli/_map_shares)
_THEORIES = {"semidiscrete": "semi-discrete NLS", "exact": "exact lattice",
             "fourwave": "four-wave"}


def _point(cli, path, params, k, a, N, extra=()):
    args = ["point", "--model", str(path), "--k", repr(k), "--amplitude", repr(a), "--N",
            str(N), "--json", *extra]
    for name, v in params.items():
        args += ["--param", f"{name}={v!r}"]
    r = cli(args)
    if r.returncode:
        raise RuntimeError(r.stderr.strip().splitlines()[-1])
    return json.loads(r.stdout)


def _theory_map(out, cli, tmp, name, axis, values, k, a):
    import xarray as xr

    path = tmp / f"{name}.toml"
    store = tmp / f"map3-{name}"
    r = cli(["map", "--model", str(path), "--param", f"{axis}={','.join(map(repr, values))}",
             "--k", ",".join(map(repr, k)), "--amplitude", repr(a), "--N", "64",
             "--theory-only", "--exact", "--workers", "1", "--out", str(store)])
    if r.returncode:
        out(f"(4) FAIL {name} 3 x 3 map: {r.stderr.strip()[-300:]}")
        return
    ds = xr.open_zarr(store / "map.zarr")
    worst, bad = 0.0, []
    for i, g in enumerate(ds[axis].values):
        for j, kk in enumerate(ds["k"].values):
            ks = float(ds["k_simulated"].values[i, j]) if "k_simulated" in ds else float(kk)
            pt = _point(cli, path, {axis: float(g)}, ks, a, 64)
            for col, key in _THEORIES.items():
                got = pt[key]
                amp = float(ds[f"amplification_{col}"].values[i, j])
                if got.get("amplification") is None and math.isinf(amp):
                    continue  # JSON null: unbounded
                worst = max(worst, _rel(amp, got.get("amplification")))
                verdict = {1: "MI", 0: "stable"}.get(int(ds[f"verdict_{col}"].values[i, j]),
                                                     "undefined")
                if verdict != got["verdict"]:
                    bad.append(f"{col} {axis} {g:g} k {ks:.4g}: map {verdict}, point "
                               f"{got['verdict']}")
    # every float variable says its unit (flags carry flag_values, the checksum none)
    units = [v for v in ds.data_vars if ds[v].dtype.kind == "f" and "units" not in ds[v].attrs]
    ok = worst <= 1e-9 and not bad and not units
    out(f"(4) {'ok  ' if ok else 'FAIL'} {name} 3 x 3 theory-only --exact map against point "
        f"--json: worst amplification {worst:.1e} (bar 1e-9), verdicts differing "
        f"{bad or 'none'}; variables without units {units or 'none'}; attrs "
        f"{sorted(a for a in ds.attrs if a.startswith('param_'))}, axis {axis} units "
        f"{ds[axis].attrs.get('units')!r}")


def _simulated_map(cli, tmp, name, axis, values, k, a, store, interrupt=None, t_end=400):
    args = ["map", "--model", str(tmp / f"{name}.toml"), "--param",
            f"{axis}={','.join(map(repr, values))}", "--k", ",".join(map(repr, k)),
            "--amplitude", repr(a), "--N", "64", "--t-end", repr(t_end), "--workers", "1",
            "--block", "1", "--out", str(store)]
    if interrupt is None:
        return cli(args)
    env = {**os.environ, "OMP_NUM_THREADS": "1"}
    p = subprocess.Popen([sys.executable, "-m", "cli", *args], stdout=subprocess.PIPE,
                         stderr=subprocess.PIPE, text=True, env=env)
    # SIGINT ``interrupt`` seconds after the store appears (the cells under way)
    while p.poll() is None and not (store / "map.zarr").exists():
        time.sleep(0.2)
    time.sleep(interrupt)
    p.send_signal(signal.SIGINT)
    first = p.communicate(timeout=300)
    return p.returncode, first, cli(args)


def check_maps(out, tmp, cli):
    import xarray as xr

    _theory_map(out, cli, tmp, "bondsite", "eta", [0.001, 0.003, 0.01], [2.2, 2.5, 2.8], 0.15)
    _theory_map(out, cli, tmp, "kgcubic", "gamma", [0.001, 0.004, 0.02], [1.6, 2.2, 2.8], 0.4)
    for name, axis, values, k, a in (("resonator", "gamma", [0.01, 0.1], [2.3, 2.7], 0.15),
                                     ("kgcubic", "gamma", [0.002, 0.02], [1.8, 2.6], 0.4)):
        store = tmp / f"sim-{name}"
        r = _simulated_map(cli, tmp, name, axis, values, k, a, store)
        if r.returncode:
            out(f"(4) FAIL {name} simulated map: {r.stderr.strip()[-300:]}")
            continue
        ds = xr.open_zarr(store / "map.zarr")
        worst, bad = 0.0, []
        for i, g in enumerate(ds[axis].values):
            for j in range(ds["k"].size):
                ks = float(ds["k_simulated"].values[i, j])
                pt = _point(cli, tmp / f"{name}.toml", {axis: float(g)}, ks, a, 64,
                            ("--simulate", "--seeds", "1", "--t-end", "400"))
                sim = pt["simulated"]
                amp = float(ds["amplification_simulated"].values[i, j])
                worst = max(worst, _rel(amp, sim.get("amplification")))
                obs = int(ds["observable_simulated"].values[i, j])
                if bool(obs == 1) != bool(sim.get("observable")):
                    bad.append(f"{axis} {g:g} k {ks:.4g}")
        ok = worst <= 0.02 and not bad
        out(f"(4) {'ok  ' if ok else 'FAIL'} {name} 2 x 2 simulated map against point "
            f"--simulate: worst run amplification {worst:.1e} (bar 2%), observable "
            f"differing {bad or 'none'}")
        # interrupted (SIGINT 2 s after its store appears, cells of T 3000 under way) and
        # resumed, against the same map run once
        ref = _simulated_map(cli, tmp, name, axis, values, k, a, tmp / f"ref-{name}",
                             t_end=3000)
        ds = xr.open_zarr(tmp / f"ref-{name}" / "map.zarr")
        rc, first, again = _simulated_map(cli, tmp, name, axis, values, k, a,
                                          tmp / f"int-{name}", interrupt=2, t_end=3000)
        d1 = xr.open_zarr(tmp / f"int-{name}" / "map.zarr")
        diff = [v for v in ds.data_vars if not np.array_equal(
            ds[v].values, d1[v].values, equal_nan=ds[v].dtype.kind == "f")]
        tb = "Traceback" in first[1]
        ok = ref.returncode == 0 and again.returncode == 0 and not diff and not tb and rc
        out(f"(4) {'ok  ' if ok else 'FAIL'} {name} simulated map interrupted (SIGINT 2 s "
            f"after its store appeared: exit {rc}, traceback {tb}, last line {first[1].strip()[-120:]!r}) and "
            f"resumed (exit {again.returncode}): variables differing from the one run "
            f"{diff or 'none'}")


#: (what, the edit of the kgcubic file or its --param, what is expected)
EDGES = [
    ("gamma negative", None, {"gamma": -0.01}, "refused"),
    ("gamma nan", None, {"gamma": math.nan}, "refused"),
    ("gamma inf", None, {"gamma": math.inf}, "refused"),
    ("gamma 1e300", None, {"gamma": 1e300}, "refused"),
    ("gamma 1e3 (past critical)", None, {"gamma": 1e3}, "stable"),
    ("gamma 1e8 (past critical)", None, {"gamma": 1e8}, "stable"),
    ("a field the model lacks", "gamma*w_t**2/2", {}, "refused"),
    ("a symbol that is no parameter", "zeta*u_t**2/2", {}, "refused"),
    ("time-dependent", "gamma*cos(t)*u_t**2/2", {}, "refused"),
    ("position-dependent", "gamma*u**2*u_t**2/2", {}, "refused"),
    ("quartic in the velocity", "gamma*u_t**4/4", {}, "refused"),
    ("nonlinear in the velocity", "gamma*exp(u_t)*u_t**2/2", {}, "refused"),
    ("linear in the velocity", "gamma*u_t", {}, "refused"),
    ("indefinite (negative coefficient)", "-gamma*u_t**2/2", {}, "refused"),
]


def check_edges(out, tmp, cli):
    from bench.probe_losses98 import FILES

    base = FILES["kgcubic"]
    for what, expr, params, expect in EDGES:
        path = tmp / "edge.toml"
        path.write_text(base if expr is None else base.replace('"gamma*u_t**2/2"',
                                                                f'"{expr}"'))
        args = ["point", "--model", str(path), "--k", "2", "--amplitude", "0.4", "--N", "64"]
        for name, v in params.items():
            args += ["--param", f"{name}={v!r}"]
        r = cli([*args, "--json"])
        err = r.stderr.strip().splitlines()
        if expect == "refused":
            ok = r.returncode == 2 and len(err) == 1 and "Traceback" not in r.stderr
            got = f"exit {r.returncode}: {err[-1][:160] if err else ''}"
        else:
            try:
                pt = json.loads(r.stdout)
            except ValueError:
                pt = {}
            rows = [pt.get(t, {}) for t in _THEORIES.values()]
            ok = r.returncode == 0 and all(x.get("verdict") == "stable" and x.get(
                "amplification") == 1.0 for x in rows)
            got = "; ".join(f"{x.get('verdict')} {x.get('amplification')}" for x in rows)
        out(f"(5) {'ok  ' if ok else 'FAIL'} {what}: expected {expect}; {got}")
