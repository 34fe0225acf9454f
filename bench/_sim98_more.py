"""Probe 98's edge inputs and rate points (``bench.probe_sim98``): ``part_edge(ms, folder,
say)`` and ``part_rate(ms, say)``, ``say(part, what, ok, detail)`` printing one line."""

from __future__ import annotations

import math
import resource
import subprocess
import sys
import time

import numpy as np

from bench import _sim98_models as H


def _try(call, *args, **kw):
    """(call(*args, **kw), None) or (None, the exception)."""
    try:
        return call(*args, **kw), None
    except Exception as exc:  # noqa: BLE001 - the probe reports whatever comes
        return None, exc


def _one_line(exc, *words) -> bool:
    msg = str(exc)
    return "\n" not in msg and all(w in msg for w in words)


def part_edge(ms: dict, folder, say) -> None:
    from energy import ModelError
    from numerics import BlowUpError
    from numerics.models import exact_gain, simulate_model, simulate_seeds

    pend, morse, mim = ms["pend"], ms["morse"], ms["mim"]
    for N in (2, 3):
        _, exc = _try(simulate_model, pend, 1.0, 0.3, N=N, t_end=10.0)
        say("edge", f"N = {N}", isinstance(exc, ModelError) and _one_line(exc, "N must be"),
            str(exc))
    for N in (9, 11, 33):
        r, exc = _try(simulate_model, pend, 1.0, 0.3, N=N, t_end=50.0, records=4)
        ok = exc is None and r.energy_drift < 1e-9 and r.N == N
        say("edge", f"odd N = {N}", ok, f"k {r.k:.4f}, drift {r.energy_drift:.1e}" if r
            else str(exc))
    t0, rss0 = time.time(), resource.getrusage(resource.RUSAGE_SELF).ru_maxrss
    r = simulate_model(pend, 1.0, 0.3, N=65536, t_end=20.0, records=10)
    took = time.time() - t0
    rss = (resource.getrusage(resource.RUSAGE_SELF).ru_maxrss - rss0) / 1024
    steps = round(r.t_end / r.dt)
    say("edge", "N = 65536, T = 20", r.energy_drift < 1e-9,
        f"{took:.1f} s ({took / steps / 65536 * 1e9:.0f} ns a site-step), +{rss:.0f} MB, "
        f"drift {r.energy_drift:.1e}")
    for T in (1e-12, 1e-300):
        r, exc = _try(simulate_model, pend, 1.0, 0.3, N=16, t_end=T)
        ok = exc is None and r.growth().verdict == "no growth within T"
        say("edge", f"t_end {T:g}", ok, r.growth().verdict if r else str(exc))
    t0 = time.time()
    _, exc = _try(simulate_model, pend, 1.0, 0.3, N=16, t_end=1e12)
    say("edge", "t_end 1e12", isinstance(exc, ModelError) and _one_line(exc, "steps"),
        f"{time.time() - t0:.1f} s: {exc}")
    for rec in (1, 10**9):
        r, exc = _try(simulate_model, pend, 1.0, 0.3, N=16, t_end=5.0, records=rec)
        steps = round(5.0 / r.dt) if r else 0
        ok = exc is None and len(r.t) == min(rec, steps) + 1
        say("edge", f"records {rec}", ok, f"{len(r.t)} records of {steps} steps" if r
            else str(exc))
    for dt in (5.0, 1e6):
        _, exc = _try(simulate_model, pend, 1.0, 0.3, N=16, t_end=50.0, dt=dt)
        say("edge", f"dt {dt:g} past the stability limit",
            isinstance(exc, ModelError) and _one_line(exc, "dt =", "stability limit"),
            str(exc))
    N = 16
    for a in (1.0, 1.5):
        x = np.where(np.arange(N) % 2 == 0, a, -a)[None, :]
        r, exc = _try(simulate_model, morse, math.pi, 0.1, N=N, t_end=50.0,
                                             initial=(x, np.zeros((1, N))), noise=0.0)
        if exc is None:
            E0 = H.energy("morse", x, np.zeros((1, N)))
            err = abs(H.energy("morse", *r.state) - E0) / E0
            say("edge", f"morse compressed start {a}", err < 1e-7,
                f"dt {r.dt:.3g}, hand energy error {err:.1e}")
        else:
            t = getattr(exc, "time", None)
            say("edge", f"morse compressed start {a}",
                isinstance(exc, (BlowUpError, ModelError)) and _one_line(exc),
                f"{type(exc).__name__} at t = {t}: {exc}")
    for a in (0.6, 2.0):  # past the soft bond's barrier r = 1: the energy falls to -inf
        x = np.where(np.arange(N) % 2 == 0, a, -a)[None, :]
        _, exc = _try(simulate_model, ms["soft"], math.pi, 0.05, N=N, t_end=100.0,
                      initial=(x, np.zeros((1, N))), noise=0.0)
        t = getattr(exc, "time", None)
        say("edge", f"soft bond past its barrier, r = {2 * a:g}",
            isinstance(exc, BlowUpError) and t is not None and 0 < t < 100
            and _one_line(exc, "blew up by t ="), f"{type(exc).__name__} at t = {t}: {exc}")
    r = simulate_model(mim, 1.0, 0.2, N=32, t_end=200.0, records=2)
    wopt = float(H.omega_hand("mim", math.pi)[1])
    say("edge", "stiff mim: step follows omega 60.3", r.dt * wopt < 0.2 * math.pi
        and r.energy_drift < 1e-9, f"omega dt {r.dt * wopt:.3f}, drift {r.energy_drift:.1e}")
    for gamma in (100.0, 1e4):  # overdamped: the step must follow the damping's rate
        for method in ("rk4", "srkn11b"):
            lossy = ms["damped"].with_params(gamma=gamma)
            r, exc = _try(simulate_model, lossy, 1.0, 0.2, N=16, t_end=20.0, records=4,
                          method=method)
            ok = exc is None and bool(np.all(np.diff(r.energy) <= 0))
            say("edge", f"damping gamma {gamma:g} {method}", ok,
                f"dt {r.dt:.3g}, E {r.energy[0]:.3g} -> {r.energy[-1]:.3g}, balance "
                f"{r.energy_balance():.1e}" if r else f"{type(exc).__name__}: {exc}")
    r, exc = _try(simulate_model, ms["damped"].with_params(gamma=1e4), 1.0, 0.2, N=16,
                  t_end=2.0, dt=0.2, records=1)
    say("edge", "damping flow exp(-1000) (given dt)", exc is None,
        "ran" if r else f"{type(exc).__name__}: {exc}")
    spec = exact_gain(pend, 1.0, 0.3, N=32)
    _, exc = _try(simulate_seeds, pend, 1.0, 0.3, spec, N=32, seeds=0, t_end=10.0)
    say("edge", "seeds 0", isinstance(exc, ModelError) and _one_line(exc, "seeds"), str(exc))
    for s in (1, 6):
        runs = simulate_seeds(pend, 1.0, 0.3, spec, N=32, seeds=s, t_end=50.0)
        distinct = len({float(x.state[0][0, 3]) for x in runs.runs}) == s
        say("edge", f"seeds {s}", len(runs.runs) == s and distinct,
            f"{runs.verdict.word}, {s} distinct runs")
    _cli(folder, say)


def _cli(folder, say) -> None:
    """``flexmm point --model F --simulate`` at the edges: one line, exit 2, or a run."""
    cases = [("--N 3", 2, "--N"), ("--t-end 1e30", 2, "--t-end"), ("--seeds 0", 2, "--seeds"),
             ("--N 11 --t-end 20", 0, "simulated"), ("--t-end 1e-9", 0, "simulated")]
    for extra, code, word in cases:
        cmd = [sys.executable, "-m", "cli", "point", "--model", str(folder / "pend.toml"),
               "--k", "1", "--amplitude", "0.3", "--simulate", *extra.split()]
        p = subprocess.run(cmd, capture_output=True, text=True, timeout=300)
        err = p.stderr.strip().splitlines()
        ok = p.returncode == code and "Traceback" not in p.stderr and (
            word in (p.stdout if code == 0 else err[-1] if err else ""))
        say("cli", f"point {extra}", ok, f"exit {p.returncode}: "
            + (err[-1] if code else p.stdout.strip().splitlines()[-1])[:120])


#: (model, amplitude range) of the rate points: lossless models, amplitudes where the
#: exact wave exists and grows on rings of 64-128
RATE_MODELS = {"pend": (0.1, 0.4), "morse": (0.05, 0.15), "toda": (0.1, 0.3),
               "grad": (0.1, 0.3), "mim": (0.05, 0.2), "tri": (0.1, 0.3),
               "quartic": (0.2, 0.5), "soft": (0.05, 0.2)}


def part_rate(ms: dict, say, points: int = 10, seed: int = 98) -> None:
    from numerics.models import exact_gain, simulate_seeds, visible_gain

    rng = np.random.default_rng(seed)
    names = sorted(RATE_MODELS)
    done = 0
    while done < points:
        name = names[int(rng.integers(len(names)))]
        lo, hi = RATE_MODELS[name]
        k, a, N = float(rng.uniform(0.3, 3.0)), float(rng.uniform(lo, hi)), int(
            rng.choice([64, 128]))
        spec, exc = _try(exact_gain, ms[name], k, a, N=N)
        if exc is not None:
            say("rate", f"{name} k {k:.3f} a {a:.3f} N {N}", True,
                f"no exact wave: {str(exc)[:80]}")
            continue
        done += 1
        want = visible_gain(spec, N)
        t0 = time.time()
        runs = simulate_seeds(ms[name], k, a, spec, N=N, seeds=1)
        got, word = runs.rate, runs.verdict.word
        if want > 0 and word == "MI":
            ok, detail = abs(got / want - 1) <= 0.10, f"run {got:.5g}, exact {want:.5g}, " \
                f"ratio {got / want:.3f}"
        else:
            ok = word != "MI" or want > 0
            detail = f"run {word}, exact {want:.3g} (T = {runs.t_end:g})"
        say("rate", f"{name} k {k:.3f} a {a:.3f} N {N}", ok,
            detail + f", {time.time() - t0:.0f} s")
