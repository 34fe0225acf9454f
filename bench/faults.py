"""The fault catalogue: bad inputs and faults, each with the exact outcome it must have.

Each entry is (name, action, expected): ``action()`` is called; ``expected`` is either
``("error", ExceptionType, regex)``: that exception, its message matching and naming the
parameter; or ``("ok", check)``: ``check(result)`` is true. ``run_catalogue()`` classifies
every entry as "clear error" (the expected error), "worked" (the expected result) or
"problem" (anything else, with what happened); ``tests/test_faults.py`` asserts each one
and ``make stress`` (bench/stress.py) counts them into stress.md. Faults that need a
process, a signal or a file system (resume after Ctrl-C, checkpoints, tampered cache
entries, partial files, the CLI) are tested in ``tests/test_faults.py`` itself.
"""

from __future__ import annotations

import math
import re
from pathlib import Path

import numpy as np

from bench._fault_helpers import BLUE, E, _integrate, _nan_spectrum, _sim, _smap
from numerics import LatticeState, Material, mi_gain, plane_wave

CATALOGUE = [
    # types: a wrong type names the parameter (TypeError)
    ("simulate: material None", lambda: _sim(material=None), (E, TypeError, "material")),
    ("simulate: initial is not a state", lambda: _sim(initial=[0.0] * 100),
     (E, TypeError, "initial")),
    ("integrate: state None", lambda: _integrate(state=None), (E, TypeError, "state")),
    ("integrate: material is a dict", lambda: _integrate(material={"alpha": 2.5}),
     (E, TypeError, "material")),
    ("Material: alpha None", lambda: Material(None, 0.01, 0.01), (E, TypeError, "alpha")),
    ("Material: K_s complex", lambda: Material(2.5, 0.01 + 1j, 0.01), (E, TypeError, "K_s")),
    ("LatticeState: complex theta", lambda: LatticeState(None, None, [1j, 0, 0], [0, 0, 0]),
     (E, TypeError, "theta")),
    ("LatticeState: theta None", lambda: LatticeState(None, None, None, [0, 0, 0]),
     (E, TypeError, "theta")),
    ("simulate: seed is a string", lambda: _sim(seed="1"), (E, TypeError, "seed")),
    ("simulate: seed is a float", lambda: _sim(seed=1.0), (E, TypeError, "seed")),
    ("simulate: N is a float", lambda: _sim(N=100.0), (E, TypeError, "N")),
    ("simulate: t_end is a string", lambda: _sim(t_end="10"), (E, TypeError, "t_end")),
    # values: a wrong value names the parameter and its range (ValueError)
    ("simulate: seed >= 2^64", lambda: _sim(seed=2**64), (E, ValueError, r"seed .*2\^63")),
    ("simulate: seed < 0", lambda: _sim(seed=-1), (E, ValueError, "seed")),
    ("simulate: max_energy_error NaN", lambda: _sim(max_energy_error=math.nan),
     (E, ValueError, "max_energy_error")),
    ("simulate: max_energy_error < 0", lambda: _sim(max_energy_error=-0.1),
     (E, ValueError, "max_energy_error")),
    ("simulate: energy_tolerance 0", lambda: _sim(energy_tolerance=0.0),
     (E, ValueError, "energy_tolerance")),
    ("simulate: noise NaN", lambda: _sim(noise=math.nan), (E, ValueError, "noise")),
    ("simulate: noise 2", lambda: _sim(noise=2.0), (E, ValueError, "noise")),
    ("simulate: omega_model unknown", lambda: _sim(omega_model="exact"),
     (E, ValueError, "omega_model")),
    ("simulate: tol and dt", lambda: _sim(tol=1e-6), (E, ValueError, "dt or tol")),
    ("simulate: tol 0", lambda: _sim(dt=None, tol=0.0), (E, ValueError, "tol")),
    ("simulate: k = 0", lambda: _sim(k=0.0), (E, ValueError, "k")),
    ("simulate: N absurd", lambda: _sim(N=10**9), (E, ValueError, "N")),
    # scipy methods: these hung before
    ("dop853: rtol NaN", lambda: _integrate(method="dop853", rtol=math.nan),
     (E, ValueError, "rtol")),
    ("dop853: rtol 0", lambda: _integrate(method="dop853", rtol=0.0), (E, ValueError, "rtol")),
    ("dop853: atol inf", lambda: _integrate(method="dop853", atol=math.inf),
     (E, ValueError, "atol")),
    ("rk45: atol 0", lambda: _integrate(method="rk45", atol=0.0), (E, ValueError, "atol")),
    # the exact theory
    ("mi_gain: wave of another k", lambda: mi_gain(
        BLUE, "coupled", 0.8, 0.02, [0.1], wave=plane_wave(BLUE, "coupled", 0.7, 0.02)),
     (E, ValueError, "wave does not match.*k")),
    ("mi_gain: rotation wave for case coupled", lambda: mi_gain(
        BLUE, "coupled", 0.8, 0.02, [0.1], wave=plane_wave(BLUE, "rotation", 0.8, 0.02)),
     (E, ValueError, "wave does not match.*case")),
    ("mi_gain: material None", lambda: mi_gain(None, "coupled", 0.8, 0.02, [0.1]),
     (E, TypeError, "material")),
    ("plane_wave: amplitude 5 rad", lambda: plane_wave(BLUE, "coupled", 0.8, 5.0),
     (E, ValueError, "amplitude")),
    ("stability_map: amplitude 5", lambda: _smap(amplitude=5.0), (E, ValueError, "amplitude")),
    ("stability_map: NaN in k", lambda: _smap(k=np.array([0.8, np.nan])),
     (E, ValueError, "finite")),
    ("stability_map: alpha < 0", lambda: _smap(alpha=-2.5), (E, ValueError, "alpha")),
    ("stability_map: shape mismatch", lambda: _smap(delta=np.zeros(3)),
     (E, ValueError, "shape")),
    ("stability_map: chunk 0", lambda: _smap(chunk=0), (E, ValueError, "chunk")),
    ("stability_map: k complex", lambda: _smap(k=np.array([0.8 + 1j, 0.9])),
     (E, TypeError, "k")),
    ("stability verdict of a NaN spectrum", _nan_spectrum, (E, ValueError, "not finite")),
    # things that must simply work
    ("simulate: numpy integer N and seed", lambda: _sim(N=np.int64(100), seed=np.uint32(3)),
     ("ok", lambda run: run.N == 100 and run.completed)),
    ("simulate: tol=1e-6 picks a method", lambda: _sim(dt=None, tol=1e-6),
     ("ok", lambda run: run.method == "srkn11b" and run.completed)),
    ("stability_map: scalar delta broadcasts", lambda: _smap(delta=0.003),
     ("ok", lambda g: g.shape == (2,) and np.all(np.isfinite(g)))),
    ("Material.from_physical", lambda: Material.from_physical(1.0, 0.1, 1.0, 1.0, 0.02, 0.005),
     ("ok", lambda m: m.alpha > 0)),
]


from bench.faults_maps import MAP_CATALOGUE, C  # the second half

CATALOGUE += MAP_CATALOGUE




def _where(exc: BaseException) -> str:
    """The last three frames an exception passed, innermost last (a rare failure, seen
    once in CI, then says where it came from)."""
    import traceback

    frames = traceback.extract_tb(exc.__traceback__)[-3:]
    return " <- ".join(f"{Path(f.filename).name}:{f.lineno} {f.name}"
                       for f in reversed(frames)) or "?"


def run_one(action, expected):
    """("clear error" | "worked" | "problem", what happened). ``("cli", code, regex)``: the
    action returns (exit code, stderr) of a CLI call; a clear error is that code and one
    stderr line matching regex, no traceback."""
    if expected[0] == C:
        try:
            code, err = action()
        except BaseException as exc:  # a CLI must not raise
            return "problem", f"raised {type(exc).__name__}: {exc}"
        lines = err.strip().splitlines()
        if code == expected[1] and len(lines) == 1 and re.search(expected[2], lines[0]) \
                and "Traceback" not in err:
            return "clear error", lines[0]
        return "problem", f"exit {code}, stderr: {err.strip()[:300]}"
    try:
        result = action()
    except Exception as exc:  # classifying is the point
        if expected[0] == E and isinstance(exc, expected[1]) and \
                re.search(expected[2], str(exc)):
            return "clear error", f"{type(exc).__name__}: {exc}"
        return "problem", f"{type(exc).__name__}: {exc} (raised at {_where(exc)})"
    if expected[0] == "ok" and expected[1](result):
        return "worked", "as expected"
    return "problem", f"returned {type(result).__name__} (expected {expected[0]})"


def run_catalogue():
    """[(name, outcome, detail)] for every entry."""
    return [(name, *run_one(action, expected)) for name, action, expected in CATALOGUE]
