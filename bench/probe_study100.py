"""Probe 100: a designer's full study of a chain nobody had tried, through the command line.

The chain (``HINGE3`` below, written from its geometry): rigid units of half-length l = 1,
each with a rotation theta, an axial displacement U and a transverse displacement V,
joined at their tips by hinges with an axial spring k_l = 1, a shear spring K_s and a
bending spring K_b; mass 1, rotational inertia J. The hinge between units n and n + 1
spans the gap between the right tip of n and the left tip of n + 1:

    dx - h = U_{n+1} - U_n + 2 - cos(theta_n) - cos(theta_{n+1})
    dy     = V_{n+1} - V_n - sin(theta_n) - sin(theta_{n+1})
    W      = (dx - h)^2 / 2 + K_s dy^2 / 2 + K_b (theta_{n+1} - theta_n)^2 / 2

Linearised by hand (s = sin(k/2), c = cos(k/2)): U decouples, omega_U = 2 s; theta and V
couple through the shear spring, K = [[4 K_s s^2, 2 i K_s sin k], [., 4 K_s c^2 + 4 K_b s^2]]
with masses (1, J), so

    J w^4 - 4 w^2 (K_s c^2 + K_b s^2 + J K_s s^2) + 16 K_s K_b s^4 = 0,

an optical rotation branch (4 K_s / J at k = 0) and a flexural one (w ~ sqrt(K_b) k^2 / 2).
With hinge damping R = gamma theta_t^2 / 2 the theta-V block's symbol is
det(K - i w C - w^2 M) = J w^4 + i gamma w^3 - (B + J A) w^2 - i gamma A w + A B - X = 0
(A = 4 K_s s^2, B = 4 K_s c^2 + 4 K_b s^2, X = 16 K_s^2 s^2 c^2).

Parts (one line a check, ``!!`` where one disagrees; exit 1 if any):

1. ``disp``: the three branches against the hand roots (1e-9) at 20 seeded k; v_g and g1 of
   the theta carrier (``coefficients --json`` and ``numerics.models.carrier``) against
   central differences of the hand root (h = 1e-3: truncation ~h^2 w''' ~ 1e-7, bar 1e-6);
2. ``map``: a theory-only map K_s x k (5 x 15; g1 per cell against the hand differences;
   the theta carrier's branch index along k, 2 -> 1 -> 0 by hand, said by the map),
   an ``--exact`` map (3 x 5): every cell whose NLS verdict differs from the exact one must
   be explained by the map's printed output and by ``point``'s notes at that cell;
3. ``point``: three points simulated: the runs' rate against the exact ring rate (5%),
   the energy drift (1e-9), the printed estimate against the wall time;
4. ``soliton``: a bright soliton at k = 2.8 (g > 0 on the lowest, theta-dominated branch),
   simulated: velocity against the hand v_g, width against 2 / (a sqrt(g)), amplitude
   against a; the errors are the NLS's O(a^2): bars 3x the measured error at a = 0.025
   scaled by (a / 0.025)^2 are not a test, so: velocity 2%, amplitude 3%, width 3% at
   a = 0.025 and the width's error falling at least 2.5x from a = 0.05 to 0.025 (O(a^2)
   would give 4x);
5. ``loss``: the carrier's damping (``coefficients --json``) against the hand damped root
   (1e-8) at 10 k; a damped point simulated: dE/dt = -2R (1e-3), the run's observable
   against the exact theory's;
6. ``store``: the map's store opened with xarray, a figure drawn from it; a simulated map
   interrupted by SIGINT and resumed: the resumed store equal to an uninterrupted one.

    OMP_NUM_THREADS=1 python -m bench.probe_study100 [--part NAME]

(~5 min on the loaded 2-core VM, 2026-11-27; findings in bench/README.md.)
"""

from __future__ import annotations

import argparse
import json
import math
import os
import re
import signal
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

HINGE3 = '''name = "hinge3"
description = "rigid units joined by hinges with axial, shear and bending stiffness"
fields = ["theta", "U", "V"]
branch = "theta"
[parameters]
J = 0.5        # rotational inertia / (m l^2)
K_s = 0.2      # shear stiffness / axial stiffness
K_b = 0.05     # bending stiffness / (k_l l^2)
[energy]
kinetic = "J*theta_t**2/2 + U_t**2/2 + V_t**2/2"
bond = "(U_next - U + 2 - cos(theta) - cos(theta_next))**2/2 + K_s*(V_next - V - sin(theta) - sin(theta_next))**2/2 + K_b*(theta_next - theta)**2/2"
'''
LOSSY = (HINGE3.replace('name = "hinge3"', 'name = "hinge3-lossy"')
         .replace("K_b = 0.05 ", "gamma = 0.002\nK_b = 0.05 ")
         + '[dissipation]\nsite = "gamma*theta_t**2/2"\n')
P = {"J": 0.5, "K_s": 0.2, "K_b": 0.05}
FAILS: list = []
ROOT = Path(__file__).resolve().parents[1]


def say(part: str, what: str, ok: bool, detail: str) -> None:
    print(f"{'ok' if ok else '!!'} {part:8s} {what:46s} {detail}", flush=True)
    if not ok:
        FAILS.append(f"{part} {what}: {detail}")


def cli(*args, timeout=600):
    """``python -m cli ARGS`` of this tree: (rc, stdout, stderr, wall seconds)."""
    env = dict(os.environ, PYTHONPATH=str(ROOT))
    t0 = time.perf_counter()
    p = subprocess.run([sys.executable, "-m", "cli", *map(str, args)], capture_output=True,
                       text=True, env=env, cwd=ROOT, timeout=timeout)
    return p.returncode, p.stdout, p.stderr, time.perf_counter() - t0


# ---- the chain by hand ------------------------------------------------------------------

def hand_omegas(k, J=0.5, K_s=0.2, K_b=0.05, gamma=None):
    """The three branches at k, ascending (the quadratic in w^2 and omega_U = 2 s)."""
    s, c = math.sin(k / 2), math.cos(k / 2)
    b = 4 * (K_s * c * c + K_b * s * s + J * K_s * s * s)
    d = math.sqrt(b * b - 4 * J * 16 * K_s * K_b * s ** 4)
    w2 = [(b - d) / (2 * J), (b + d) / (2 * J)]
    return sorted([math.sqrt(max(w, 0.0)) for w in w2] + [2 * abs(s)])


def hand_theta_root(k, near, **p):
    """The hand root nearest ``near`` (the carrier's branch followed by continuity)."""
    w = hand_omegas(k, **p)
    return min(w, key=lambda x: abs(x - near))


def hand_damping(k, w0, J=0.5, K_s=0.2, K_b=0.05, gamma=0.002):
    """-Im of the damped theta-V root nearest the lossless w0 (the quartic by hand)."""
    s, c = math.sin(k / 2), math.cos(k / 2)
    A, B, X = 4 * K_s * s * s, 4 * K_s * c * c + 4 * K_b * s * s, 16 * K_s ** 2 * s * s * c * c
    r = np.roots([J, 1j * gamma, -(B + J * A), -1j * gamma * A, A * B - X])
    r = r[np.argmin(np.abs(r - w0))]
    return -float(r.imag)


def fd(k, w0, h=1e-3):
    """v_g and g1 by central differences of the hand root followed from w0."""
    wp, wm = hand_theta_root(k + h, w0), hand_theta_root(k - h, w0)
    return (wp - wm) / (2 * h), (wp - 2 * w0 + wm) / h ** 2


# ---- parts ------------------------------------------------------------------------------

def part_disp(folder):
    from energy import load_model
    from numerics.models import branches, carrier

    m = load_model(str(folder / "hinge3.toml"))
    rng = np.random.default_rng(100)
    ks = rng.uniform(0.05, math.pi, 20)
    got = np.sort(np.asarray(branches(m, ks), float), axis=1)
    want = np.array([hand_omegas(k) for k in ks])
    err = float(np.max(np.abs(got - want) / np.maximum(want, 1e-3)))
    say("disp", "3 branches at 20 k vs hand roots", err < 1e-9, f"max rel err {err:.1e}")
    for k in rng.uniform(0.1, 3.0, 8):
        c = carrier(m, float(k), branch="theta")
        w = hand_theta_root(k, c.omega)
        vg, g1 = fd(k, w)
        e = max(abs(c.omega - w), abs(c.group_velocity - vg), abs(c.g1 - g1))
        say("disp", f"theta carrier k={k:.3f} (branch {c.branch}) w, v_g, g1",
            e < 1e-6, f"w {c.omega:.6f}, v_g {c.group_velocity:.6f} (fd {vg:.6f}), "
            f"g1 {c.g1:.6f} (fd {g1:.6f})")
    for k in (0.4, 2.8):
        rc, out, err_, _ = cli("coefficients", "--model", folder / "hinge3.toml", "--k", k,
                               "--amplitude", 0.05, "--json")
        d = json.loads(out)
        w = hand_theta_root(k, d["omega"])
        vg, g1 = fd(k, w)
        e = max(abs(d["omega"] - w), abs(d["group_velocity"] - vg), abs(d["g1"] - g1))
        say("disp", f"coefficients --json k={k}", rc == 0 and e < 1e-6,
            f"field {d['field']}, verdict {d['verdict']}, err {e:.1e}")


def part_map(folder):
    import xarray as xr

    out = folder / "map-th"
    rc, so, se, wall = cli("map", "--model", folder / "hinge3.toml", "--param", "K_s=0.1:0.3:5",
                           "--k", "0.2:3.0:15", "--amplitude", 0.1, "--N", 128, "--theory-only",
                           "--workers", 1, "--out", out, "--overwrite")
    say("map", "theory-only 5 x 15 map", rc == 0, f"{wall:.1f} s; {so.splitlines()[-2]}")
    # the theta carrier is the optical root (index 2) at small k, below U from k ~ 1.3
    # (index 1), the lowest root near pi (4 K_b / J < 4 K_s there): the map must say so
    # (per row since newuser 101: the file's K_s = 0.2 row)
    jump = re.search(r"changes along k: .*?at K_s = 0.2: (.*?);", so + se)
    say("map", "the theta branch's index changes said", bool(jump) and re.findall(
        r"index (\d)", jump[1]) == ["2", "1", "0"], jump[1][:100] if jump else "not said")
    with xr.open_zarr(out / "map.zarr") as ds:
        worst = 0.0
        for i, Ks in enumerate(ds["K_s"].values):
            for j in range(ds["k"].size):
                kk = float(ds["k_simulated"].values[i, j])
                g1 = float(ds["g1"].values[i, j])
                c = dict(P, K_s=float(Ks))
                # the store has no omega: the carrier's root is the hand root whose g1 agrees
                g1s = [(hand_g1(kk, x, c)) for x in hand_omegas(kk, **c)]
                worst = max(worst, min(abs(g1 - x) for x in g1s))
        say("map", "store g1 vs hand differences (75 cells)", worst < 1e-6, f"max {worst:.1e}")
        # --help (since probe 100): a --model --theory-only map without --exact takes k as
        # given (the infinite chain's NLS; before, the help said every k is snapped)
        same = bool(np.all(ds["k_simulated"].values == ds["k"].values[None, :]))
        say("map", "theory-only --N 128: k as given (as --help says)", same,
            "k_simulated equal to the asked k" if same else "k snapped")
    out = folder / "map-ex"
    rc, so, se, wall = cli("map", "--model", folder / "hinge3.toml", "--param", "K_s=0.1:0.3:3",
                           "--k", "0.3:2.9:5", "--amplitude", 0.1, "--N", 128, "--theory-only",
                           "--exact", "--workers", 1, "--out", out, "--overwrite")
    say("map", "--exact 3 x 5 map", rc == 0, f"{wall:.1f} s")
    with xr.open_zarr(out / "map.zarr") as ds:
        vs, ve = ds["verdict_semidiscrete"].values, ds["verdict_exact"].values
        diff = [(float(ds["K_s"].values[i]), float(ds["k_simulated"].values[i, j]))
                for i in range(vs.shape[0]) for j in range(vs.shape[1]) if vs[i, j] != ve[i, j]]
    explained = re.search(r"(three-wave|not the sidebands|differ)", so + se)
    say("map", f"NLS != exact in {len(diff)} of 15 cells: said by the map",
        not diff or bool(explained), "explained" if explained else
        "the map prints the shares only: nothing says why the exact theory differs")
    for Ks, k in diff[:3]:
        rc, so, se, _ = cli("point", "--model", folder / "hinge3.toml", "--param", f"K_s={Ks}",
                            "--k", k, "--amplitude", 0.1, "--N", 128, "--json")
        d = json.loads(so)
        notes = " ".join(d.get("notes", []))
        ok = bool(re.search(r"three-wave|not the carrier's sidebands|NLS cannot|neither", notes))
        say("map", f"point K_s={Ks} k={k:.3f}: the difference in notes", ok,
            f"NLS {d['semi-discrete NLS']['verdict']}, exact {d['exact lattice']['verdict']} "
            f"({d['exact lattice'].get('mode_kind')}): {notes[:90]}")


def hand_g1(k, w, c, h=1e-3):
    wp = min(hand_omegas(k + h, **c), key=lambda x: abs(x - w))
    wm = min(hand_omegas(k - h, **c), key=lambda x: abs(x - w))
    return (wp - 2 * w + wm) / h ** 2


def _estimate(se):
    m = re.search(r"estimate: about ([\d.]+) (s|min)", se)
    return None if m is None else float(m.group(1)) * (60 if m.group(2) == "min" else 1)


def part_point(folder):
    for Ks, k, a, N in ((0.2, 2.8, 0.1, 128), (0.2, 0.4, 0.05, 128), (0.1, 2.2, 0.1, 128)):
        rc, so, se, wall = cli("point", "--model", folder / "hinge3.toml", "--param",
                               f"K_s={Ks}", "--k", k, "--amplitude", a, "--N", N,
                               "--simulate", "--seeds", 2, "--json")
        if rc:
            say("point", f"K_s={Ks} k={k} a={a}", False, se.strip()[-200:])
            continue
        d = json.loads(so)
        ex, sim = d["exact lattice"], d["simulated"]
        r = sim["peak_gain"] / ex["peak_gain"] if ex["peak_gain"] else math.nan
        say("point", f"K_s={Ks} k={k} a={a}: run / exact ring rate", abs(r - 1) < 0.05,
            f"{sim['peak_gain']:.5g} / {ex['peak_gain']:.5g} = {r:.4f} ({ex.get('mode_kind')})")
        say("point", f"K_s={Ks} k={k} a={a}: energy drift", abs(sim["energy_drift"]) < 1e-9,
            f"{sim['energy_drift']:.1e}")
        print(f"   timing: estimate {_estimate(se)} s for the runs, command {wall:.1f} s")


def part_soliton(folder):
    res = {}
    for a in (0.05, 0.025):
        rc, so, se, wall = cli("soliton", "--model", folder / "hinge3.toml", "--k", 2.8,
                               "--amplitude", a, "--simulate", "--json")
        d = json.loads(so)
        res[a] = d
        print(f"   soliton a={a}: {wall:.1f} s, estimate {_estimate(se)} s")
    for a, d in res.items():
        meas, pred = d["measured"], d["predicted"]
        k = d["run"]["k_ring"]  # the ring's k, where the soliton was launched
        w = hand_theta_root(k, pred["frequency"])
        vg, g1 = fd(k, w)
        g = d["g2"] / g1
        width = 2 / (a * math.sqrt(g))
        ev = abs(meas["velocity"] / vg - 1)
        ew = abs(meas["width"] / width - 1)
        ea = abs(meas["amplitude"] / a - 1)
        res[a]["_ew"] = ew
        say("soliton", f"a={a} velocity vs hand v_g", ev < 0.02, f"{meas['velocity']:.5g} vs "
            f"{vg:.5g} ({ev:.2%}); predicted {pred['velocity']:.5g}")
        say("soliton", f"a={a} amplitude", ea < 0.03, f"{meas['amplitude']:.5g} ({ea:.2%})")
        if a == 0.025:
            say("soliton", f"a={a} width vs 2/(a sqrt g)", ew < 0.03,
                f"{meas['width']:.4g} vs {width:.4g} ({ew:.2%})")
        say("soliton", f"a={a} energy drift", abs(meas["energy_drift"]) < 1e-9,
            f"{meas['energy_drift']:.1e}")
    ratio = res[0.05]["_ew"] / max(res[0.025]["_ew"], 1e-12)
    say("soliton", "width error falls with a (O(a^2): 4x)", ratio > 2.5, f"{ratio:.2f}x")


def part_loss(folder):
    f = folder / "hinge3-lossy.toml"
    for k in np.linspace(0.3, 3.0, 10):
        rc, so, se, _ = cli("coefficients", "--model", f, "--k", k, "--amplitude", 0.05, "--json")
        d = json.loads(so)
        want = hand_damping(float(k), d["omega"])
        e = abs(d["carrier_damping"] - want) / want
        say("loss", f"carrier damping k={k:.2f} (branch {d['branch']})", e < 1e-8,
            f"{d['carrier_damping']:.8g} vs hand {want:.8g} ({e:.1e})")
    rc, so, se, wall = cli("point", "--model", f, "--k", 2.8, "--amplitude", 0.1, "--N", 128,
                           "--simulate", "--seeds", 1, "--json")
    if rc:
        say("loss", "damped point", False, se.strip()[-200:])
        return
    d = json.loads(so)
    sim, ex = d["simulated"], d["exact lattice"]
    bal = sim.get("energy_balance")
    say("loss", "damped point: dE/dt = -2R", bal is not None and abs(bal) < 1e-3, f"{bal}")
    say("loss", "damped point: run's observable = exact's",
        sim.get("observable") == ex.get("observable"),
        f"run {sim.get('amplification')} at {sim.get('amplification_time')}, exact "
        f"{ex.get('amplification')} at {ex.get('amplification_time')}")
    print(f"   timing: estimate {_estimate(se)} s for the runs, command {wall:.1f} s")


def part_store(folder):
    import matplotlib
    import xarray as xr

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    with xr.open_zarr(folder / "map-th" / "map.zarr") as ds:
        fig, ax = plt.subplots(figsize=(5, 3))
        (ds["g2"] / ds["g1"]).plot(ax=ax, x="k", y="K_s", cmap="RdBu_r", center=0)
        ax.set_title("g = g2/g1 (theta carrier)")
        fig.savefig(folder / "g.png")
        plt.close(fig)
    say("store", "figure from the store", (folder / "g.png").stat().st_size > 1000, "g.png")
    args = ["map", "--model", folder / "hinge3.toml", "--param", "K_s=0.15,0.2", "--k",
            "2.6,2.8,3.0", "--amplitude", 0.1, "--N", 64, "--t-end", 1500, "--workers", 1,
            "--block", 1]
    t0 = time.perf_counter()
    rc, so, se, full = cli(*args, "--out", folder / "sim-full", "--overwrite")
    say("store", "simulated 2 x 3 map", rc == 0,
        f"{full:.1f} s; estimate {_estimate(so + se)} s")
    env = dict(os.environ, PYTHONPATH=str(ROOT))
    p = subprocess.Popen([sys.executable, "-m", "cli", *map(str, args), "--out",
                          folder / "sim-int", "--overwrite"], env=env, cwd=ROOT,
                         stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    end = time.perf_counter() + 3 * full
    while time.perf_counter() < end and p.poll() is None:  # until 2 cells are kept
        time.sleep(0.3)
        try:
            with xr.open_zarr(folder / "sim-int" / "map.zarr") as ds:
                if int(ds["done"].values.sum()) >= 2:
                    break
        except Exception:  # noqa: BLE001 - the store not written yet, or mid-write
            continue
    p.send_signal(signal.SIGINT)
    so, se = p.communicate(timeout=120)
    with xr.open_zarr(folder / "sim-int" / "map.zarr") as ds:
        done = int(ds["done"].values.sum())
    say("store", "SIGINT: exits, keeps its finished cells",
        p.returncode != 0 and 0 < done < 6,
        f"rc {p.returncode}, {done} of 6 done; {se.strip().splitlines()[-1][:80] if se else ''}")
    rc, so, se, _ = cli(*args, "--out", folder / "sim-int")
    with xr.open_zarr(folder / "sim-int" / "map.zarr") as a, \
            xr.open_zarr(folder / "sim-full" / "map.zarr") as b:
        same = all(np.array_equal(a[v].values, b[v].values, equal_nan=True)
                   for v in ("verdict_simulated", "peak_gain_simulated", "growth"))
    say("store", "resumed map equals the uninterrupted one", rc == 0 and same,
        f"rc {rc}; {[ln for ln in (so + se).splitlines() if 'resum' in ln.lower()][:1]}")
    del t0


PARTS = {"disp": part_disp, "map": part_map, "point": part_point, "soliton": part_soliton,
         "loss": part_loss, "store": part_store}


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--part", choices=sorted(PARTS), action="append")
    a = ap.parse_args(argv)
    t0 = time.perf_counter()
    with tempfile.TemporaryDirectory() as tmp:
        folder = Path(tmp)
        (folder / "hinge3.toml").write_text(HINGE3)
        (folder / "hinge3-lossy.toml").write_text(LOSSY)
        for name in a.part or PARTS:
            if name == "store" and not (folder / "map-th").exists():
                part_map(folder)
            PARTS[name](folder)
    print(f"{len(FAILS)} disagreement(s) in {time.perf_counter() - t0:.0f} s")
    for f in FAILS:
        print("  !!", f)
    return 1 if FAILS else 0


if __name__ == "__main__":
    sys.exit(main())
