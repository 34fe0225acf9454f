"""Probe 98 of the model simulator (``numerics.models.simulate_model`` /
``simulate_seeds``) at nine model files nobody had tried, against physics written by hand
(``bench._sim98_models``: each file's energy, Rayleigh function and dynamical matrix in
numpy, nothing of the code under test).

The models: ``pend`` (a cosine bond K (1 - cos r) with a harmonic site), ``morse`` (a Morse
bond with a quartic site), ``quartic`` (a quartic-only bond, mass 1.5: a flat linear
branch), ``toda`` (the Toda bond), ``grad`` (two fields u, v of masses 1, 2 coupled by a
gradient product g r_u r_v and a gradient-squared lam r_u^2 r_v^2 / 4), ``mim`` (a
mass-in-mass chain, inner mass 0.01 on a spring 36: its optical branch at 60.3, 30x the
acoustic top 2), ``tri`` (three fields), ``damped`` (FPUT with a site, site damping gamma
and bond damping eta) and ``damp2`` (two fields, site and bond damping).

Checks (one line each, ``ok`` or ``FAIL``; bars, each with its reason):

- ``conv``: a run's final state at dt, dt/2, dt/4, dt/8 against one at dt/64; the slope of
  log(error) on log(dt) is the method's order (srkn11b 6, rk4 4, verlet 2; lossy srkn
  runs are Strang-split: 2) within 0.3;
- ``energy``: E(T) - E(0) from the hand energy at the default dt over T = 200, below 1e-7
  relative (a symplectic method's energy error stays bounded at C (omega dt)^6, omega dt
  <= 0.57 at the default step; C grows with the nonlinearity: measured 3e-14 .. 3e-11,
  and 3.7e-8 on morse at b a = 0.45, its bonds 2.5x stiffer compressed) and falling at
  least 16x at dt/2 where above round-off (order >= 4 at the least); damped: E(t) monotone, and
  E(t) - E(0) + int 2R dt (Simpson over the hand R at 1/20 of the fastest period) below
  1e-6 of E(0) (the splitting's order 2 at the default dt, Simpson's h^4);
- ``reverse``: forward T = 20, velocities flipped, T again: back to the start within 1e-9
  (round-off 1e-16 per step over ~1e3 steps, times the growth of 20 time units of a
  noisy wave); rk4 is not symmetric: only said; ``shift``: the start shifted by one site
  gives the end shifted by one site within 1e-12 (the same arithmetic in another order);
- ``linear``: a plane wave of amplitude 1e-7 (frequency shift ~a^2 = 1e-14) on every
  branch at three k, launched in the hand mode shape: the phase of its ring mode, fitted
  over 60 radians, gives omega within 1e-6 of the hand omega(k);
- ``edge``: N 2, 3 (refused in one line), odd N, N = 65536 (time, memory), t_end tiny and
  huge, records 1 and huge, a Morse bond past its barrier (BlowUpError with its time),
  seeds 0, 1, many, the stiff mim at its default dt;
- ``rate``: ten seeded random points of the lossless models: the runs' median rate
  against ``exact_gain``'s ring rate over what a run can see (``visible_gain``) within
  10%, or the point's stated reason (its harmonics, an undetermined run).

    OMP_NUM_THREADS=1 NUMBA_NUM_THREADS=1 python -m bench.probe_sim98 [--part NAME]

(2-core VM, 2026-11-27: see bench/README.md for the time and the findings.)
"""

from __future__ import annotations

import argparse
import math
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

from bench import _sim98_models as H

FAILS: list = []


def say(part: str, what: str, ok: bool, detail: str) -> None:
    print(f"{'ok  ' if ok else 'FAIL'} {part:8s} {what:42s} {detail}", flush=True)
    if not ok:
        FAILS.append(f"{part} {what}: {detail}")


def models(folder: Path) -> dict:
    from energy import load_model

    out = {}
    for name, text in H.FILES.items():
        path = folder / f"{name}.toml"
        path.write_text(text)
        out[name] = load_model(str(path))
    return out


def run(model, k=1.0, a=0.3, **kw):
    from numerics.models import simulate_model

    kw.setdefault("records", 1)
    return simulate_model(model, k, a, **kw)


def part_sanity(ms: dict) -> None:
    """The hand files are the project's: E(0) and the branches agree (1e-12: round-off)."""
    from numerics.models import branches

    for name, m in ms.items():
        r = run(m, N=16, t_end=0.01, noise=1e-2)
        u0, v0 = r.state
        # the hand energy at the end state against the project's record there
        e = abs(H.energy(name, u0, v0) - r.energy[-1]) / abs(r.energy[-1])
        ks = np.linspace(0.1, math.pi, 7)
        w = np.asarray(branches(m, ks), float).reshape(len(ks), -1)
        hw = np.array([H.omega_hand(name, k) for k in ks]).reshape(len(ks), -1)
        d = float(np.max(np.abs(np.sort(w, axis=1) - hw) / hw))
        say("sanity", f"{name} hand energy, branches", e < 1e-12 and d < 1e-12,
            f"energy {e:.1e}, omega {d:.1e}")


def _slope(model, method, dt0, T=10.0, lossy=False):
    ref = run(model, N=16, t_end=T, dt=dt0 / 64, method=method, noise=1e-2).state[0]
    dts, errs = [], []
    for j in range(4):
        r = run(model, N=16, t_end=T, dt=dt0 / 2**j, method=method, noise=1e-2)
        dts.append(r.dt)
        errs.append(float(np.max(np.abs(r.state[0] - ref))))
    return float(np.polyfit(np.log(dts), np.log(errs), 1)[0]), errs


def part_conv(ms: dict) -> None:
    from numerics.lattice import get_method

    for name, m in ms.items():
        wmax = float(np.max(H.omega_hand(name, math.pi))) + 1.5
        for method in (("srkn11b", "rk4") if name in ("damped", "damp2", "mim", "grad")
                       else ("srkn11b",)) + (("verlet",) if name == "pend" else ()):
            order = get_method(method).order
            if m.lossy and method != "rk4":
                order = 2  # the Strang splitting
            # dt0 where the error is well above round-off and the method well inside its
            # stability limit; order 6 needs a larger dt0 than order 2 to stay off round-off
            frac = {2: 0.1, 4: 0.25, 6: 0.5}[order]
            dt0 = frac * get_method(method).stability_limit() / wmax
            p, errs = _slope(m, method, dt0)
            while errs[0] > 1e-5 and dt0 > 1e-3:  # before the asymptotic range: halve
                dt0 /= 2
                p, errs = _slope(m, method, dt0)
            say("conv", f"{name} {method} order {order}", abs(p - order) <= 0.3,
                f"slope {p:.2f}, errors {errs[0]:.1e} .. {errs[-1]:.1e}")


def part_energy(ms: dict) -> None:
    for name, m in ms.items():
        if m.lossy:
            continue
        drifts = []
        for half in (1, 2):
            r0 = run(m, N=32, t_end=10.0, noise=1e-2)  # the default dt (snapped to 10)
            dt = r0.dt / half
            r = run(m, N=32, t_end=200.0, noise=1e-2, dt=dt)
            u, v = r.state
            drifts.append(abs(H.energy(name, u, v) - r.energy[0]) / abs(r.energy[0]))
        falls = drifts[0] < 1e-13 or drifts[0] / max(drifts[1], 1e-300) >= 16
        say("energy", f"{name} default dt {r0.dt:.3g}", drifts[0] < 1e-7 and falls,
            f"|dE|/E {drifts[0]:.1e}, at dt/2 {drifts[1]:.1e}")
    for name in ("damped", "damp2"):
        m = ms[name]
        for method in ("srkn11b", "rk4"):
            first = run(m, N=32, t_end=0.01, noise=1e-2, method=method)
            u, v = first.state
            wmax = float(np.max(H.omega_hand(name, math.pi)))
            h = 2 * math.pi / wmax / 20
            E, P = [H.energy(name, u, v)], [2 * H.rayleigh(name, v)]
            for _ in range(400):  # 400 h: ~20 fastest periods
                r = run(m, N=32, t_end=h, noise=0.0, method=method, initial=(u, v),
                        dt=first.dt)
                u, v = r.state
                E.append(H.energy(name, u, v))
                P.append(2 * H.rayleigh(name, v))
            E, P = np.array(E), np.array(P)
            lost = np.concatenate([[0.0], np.cumsum(h * (P[:-1] + P[1:]) / 2)])
            # Simpson on pairs of intervals
            simpson = np.array([h / 3 * (P[j] + 4 * P[j + 1] + P[j + 2])
                                for j in range(0, len(P) - 2, 2)])
            lost2 = np.concatenate([[0.0], np.cumsum(simpson)])
            bal = float(np.max(np.abs(E[::2] - E[0] + lost2)) / E[0])
            mono = bool(np.all(np.diff(E) <= 1e-13 * E[0]))
            say("energy", f"{name} {method} dE/dt = -2R", bal < 1e-6 and mono,
                f"balance {bal:.1e} (trapezoid {np.max(np.abs(E - E[0] + lost)) / E[0]:.1e})"
                f", monotone {mono}, lost {lost[-1] / E[0]:.2e} of E(0)")


def part_reverse(ms: dict) -> None:
    for name, m in ms.items():
        r0 = run(m, N=32, t_end=0.01, noise=1e-2)
        u0, v0 = r0.state
        meth = "rk4" if m.lossy else "srkn11b"
        if not m.lossy:
            f = run(m, N=32, t_end=20.0, noise=0.0, initial=(u0, v0), dt=r0.dt)
            u, v = f.state
            b = run(m, N=32, t_end=20.0, noise=0.0, initial=(u, -v), dt=r0.dt)
            err = float(max(np.max(np.abs(b.state[0] - u0)), np.max(np.abs(b.state[1] + v0))))
            say("reverse", f"{name} T 20 and back", err < 1e-9, f"{err:.1e}")
        f = run(m, N=32, t_end=20.0, noise=0.0, initial=(u0, v0), method=meth)
        s = run(m, N=32, t_end=20.0, noise=0.0, method=meth,
                initial=(np.roll(u0, 1, axis=1), np.roll(v0, 1, axis=1)))
        err = float(np.max(np.abs(s.state[0] - np.roll(f.state[0], 1, axis=1))))
        say("shift", f"{name} one site", err < 1e-12, f"{err:.1e}")


def part_linear(ms: dict) -> None:
    N, a = 32, 1e-7
    for name, m in ms.items():
        if m.lossy:
            continue
        d = m.n_fields
        for j in (3, 8, 16):
            k = 2 * math.pi * j / N
            for b in range(d):
                w = float(H.omega_hand(name, k)[b])
                X = H.mode_shape(name, k, b)
                ph = np.exp(1j * k * np.arange(N))
                u = a * np.real(X[:, None] * ph)
                v = a * np.real(-1j * w * X[:, None] * ph)
                M = np.diag(H.linear(name, k)[0]).real
                T = 60.0 / w if w > 0 else 60.0
                pieces = 40  # 1.5 radians a piece: the phase unwraps
                phases = [0.0]
                def amp(uu, vv, X=X, M=M, w=w, ph=ph):  # the mode's a X e^{-i w t}
                    return np.conj(X) @ (M[:, None] * (uu + 1j * vv / w)
                                         * np.conj(ph)).sum(axis=1)
                prev = amp(u, v)
                uu, vv = u, v
                for _ in range(pieces):
                    r = run(m, k=k, a=a, N=N, t_end=T / pieces, noise=0.0,
                            initial=(uu, vv))
                    uu, vv = r.state
                    c = amp(uu, vv)
                    phases.append(phases[-1] + float(np.angle(c / prev)))
                    prev = c
                ts = np.linspace(0, T, pieces + 1)
                fit = -np.polyfit(ts, phases, 1)[0]
                rel = abs(fit - w) / w
                say("linear", f"{name} k {k:.3f} branch {b}", rel < 1e-6,
                    f"omega hand {w:.10f}, run {fit:.10f}, rel {rel:.1e}")


PARTS = {"sanity": part_sanity, "conv": part_conv, "energy": part_energy,
         "reverse": part_reverse, "linear": part_linear}


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--part", choices=[*PARTS, "edge", "rate"], action="append")
    args = ap.parse_args(argv)
    t0 = time.time()
    with tempfile.TemporaryDirectory() as tmp:
        ms = models(Path(tmp))
        from bench import _sim98_more as more

        parts = dict(PARTS, edge=lambda ms: more.part_edge(ms, Path(tmp), say),
                     rate=lambda ms: more.part_rate(ms, say))
        for name in args.part or parts:
            parts[name](ms)
    print(f"{len(FAILS)} failures, {time.time() - t0:.0f} s", flush=True)
    for f in FAILS:
        print("  " + f, file=sys.stderr)
    return 1 if FAILS else 0


if __name__ == "__main__":
    sys.exit(main())
