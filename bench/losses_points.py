"""The theory rows of damped points against their lossless twins (issue 42's bar: a damped
point costs no more than 2x), on more points than ``bench.models.losses_cost``: the
cheap one-field models (Klein-Gordon, sine-Gordon, FPUT) with site and bond damping on
rings of 64-256 sites, where the damped theories' extra samples weigh most.

Per point: CPU seconds (``time.process_time``, one thread) of the NLS, four-wave and exact
rows on the point's ring, and of the same plus each theory's amplification along the
decaying carrier for the lossy twin; a fresh model object each round, the twins
alternating, best of ``reps``. ``--answers`` prints the lossy theories' answers
(amplification, time, offset) at full precision instead, to compare two trees.

    OMP_NUM_THREADS=1 python -m bench.losses_points [--reps 9] [--answers]
"""

from __future__ import annotations

import sys
import time

from energy import load_model, parse_model

_ONE_FIELD = """name = "{name}-lossy"
fields = ["u"]
[parameters]
{params}
gamma = 0.0
eta = 0.0
[energy]
kinetic = "u_t**2/2"
{energy}
[dissipation]
site = "gamma*u_t**2/2"
bond = "eta*(u_next_t - u_t)**2/2"
"""

#: each built-in model's energy and parameters, written as a model file with both kinds of
#: damping (one set to zero by the point)
_LOSSY = {
    "klein-gordon": _ONE_FIELD.format(
        name="kg", params="C = 1.0\nomega0 = 1.0\nalpha = 0.0\nbeta = 1.0",
        energy='bond = "C*(u_next - u)**2/2"\n'
               'site = "omega0**2*u**2/2 + alpha*u**3/3 + beta*u**4/4"'),
    "sine-gordon": _ONE_FIELD.format(
        name="sg", params="C = 1.0\nomega0 = 1.0",
        energy='bond = "C*(u_next - u)**2/2"\nsite = "omega0**2*(1 - cos(u))"'),
    "fput": _ONE_FIELD.format(
        name="fput", params="alpha = 0.0\nbeta = 1.0",
        energy='bond = "(u_next - u)**2/2 + alpha*(u_next - u)**3/3 + '
               'beta*(u_next - u)**4/4"'),
}

#: (label, built-in model, its parameters, damping, k, a, ring N): bench/README.md's
#: cheap points
POINTS = (
    ("KG site 0.001 (k 2, a 0.4, 256)", "klein-gordon", {}, dict(gamma=0.001), 2.0, 0.4, 256),
    ("KG site 0.004 (k 2, a 0.4, 128)", "klein-gordon", {}, dict(gamma=0.004), 2.0, 0.4, 128),
    ("KG site 0.004 (k 2, a 0.4, 64)", "klein-gordon", {}, dict(gamma=0.004), 2.0, 0.4, 64),
    ("KG bond 0.01 (k 2, a 0.4, 128)", "klein-gordon", {}, dict(eta=0.01), 2.0, 0.4, 128),
    ("KG bond 0.01 (k 2, a 0.4, 64)", "klein-gordon", {}, dict(eta=0.01), 2.0, 0.4, 64),
    ("SG site 0.002 (k 0.8, a 0.5, 256)", "sine-gordon", {}, dict(gamma=0.002), 0.8, 0.5, 256),
    ("SG site 0.002 (k 0.8, a 0.5, 128)", "sine-gordon", {}, dict(gamma=0.002), 0.8, 0.5, 128),
    ("SG site 0.002 (k 0.8, a 0.5, 64)", "sine-gordon", {}, dict(gamma=0.002), 0.8, 0.5, 64),
    ("SG bond 0.01 (k 0.8, a 0.6, 128)", "sine-gordon", {}, dict(eta=0.01), 0.8, 0.6, 128),
    ("SG bond 0.01 (k 0.8, a 0.6, 64)", "sine-gordon", {}, dict(eta=0.01), 0.8, 0.6, 64),
    ("fput beta 2, bond 0.02 (k 1.5, a 0.3, 128)", "fput", dict(beta=2.0), dict(eta=0.02),
     1.5, 0.3, 128),
    ("fput site 0.003 (k 2.5, a 0.2, 256)", "fput", {}, dict(gamma=0.003), 2.5, 0.2, 256),
    ("fput site 0.012 (k 2.5, a 0.2, 64)", "fput", {}, dict(gamma=0.012), 2.5, 0.2, 64),
)


def twins(name, params, damping):
    """(lossless built-in model, its lossy twin) at ``params``."""
    plain = load_model(name)
    lossy = load_model(parse_model(_LOSSY[name], f"{name}-lossy.toml"))
    return (plain.with_params(**params) if params else plain,
            lossy.with_params(**params, **damping))


def theories(m, k, a, N, lossy):
    """The point's theory rows (``bench.models.losses_cost``'s): exact, four-wave and NLS
    on the ring, and for the lossy twin the three amplifications; returns them."""
    from numerics.models import (
        exact_amplification,
        exact_gain,
        four_wave,
        four_wave_amplification,
        nls,
        nls_amplification,
    )

    e = exact_gain(m, k, a, N=N)
    f = four_wave(m, k, a, N=N)
    r = nls(m, k)
    if not lossy:
        return None
    return (exact_amplification(m, k, a, N=N, first=e),
            four_wave_amplification(m, k, a, N=N, first=f),
            nls_amplification(m, k, a, first=r))


def main(argv=None):
    argv = sys.argv[1:] if argv is None else argv
    reps = int(argv[argv.index("--reps") + 1]) if "--reps" in argv else 9
    for label, name, params, damping, k, a, N in POINTS:
        m0, m1 = twins(name, params, damping)
        if "--answers" in argv:
            rows = theories(m1, k, a, N, True)
            print(label, " ".join(f"{x.amplification!r} {x.amplification_time!r} "
                                  f"{x.offset!r}" for x in rows))
            continue
        best = {}
        for m, lossy in ((m0, False), (m1, True)):
            theories(m, k, a, N, lossy)  # warm-up: generated module, JIT
        for _ in range(reps):
            for m, lossy in ((m0, False), (m1, True)):
                m = m.with_params()  # fresh: nothing kept for the model carries over
                t0 = time.process_time()
                theories(m, k, a, N, lossy)
                dt = time.process_time() - t0
                best[lossy] = min(best.get(lossy, dt), dt)
        print(f"{label:44s} {best[False] * 1e3:7.2f} -> {best[True] * 1e3:7.2f} ms "
              f"{best[True] / best[False]:5.2f}x", flush=True)


if __name__ == "__main__":
    main()
