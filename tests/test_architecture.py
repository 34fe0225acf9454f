"""The layers import one way: derivation -> generated -> numerics (lattice <- theory <- maps)
-> scenes -> cli, with the leaf `common` below all of them; and one vocabulary for a start and an
amplitude across the public API."""

from __future__ import annotations

import ast
from pathlib import Path

import numpy as np
import pytest

import numerics
from numerics import Material, initial_condition, simulate
from numerics.lattice import source_hash

ROOT = Path(__file__).resolve().parents[1]
PROJECT = ("cli", "common", "energy", "derivation", "generated", "numerics", "scenes")


def _unit(path: Path) -> str:
    """The import-graph node of a file: a top-level package, or numerics.<subpackage>."""
    rel = path.relative_to(ROOT).parts
    if rel[0] == "numerics" and len(rel) > 2:
        return f"numerics.{rel[1]}"
    return rel[0]


def _target(module: str) -> str | None:
    parts = module.split(".")
    if parts[0] not in PROJECT:
        return None
    if parts[0] == "numerics" and len(parts) > 1 and parts[1] in ("lattice", "theory", "maps", "models"):
        return f"numerics.{parts[1]}"
    return parts[0]


def import_graph() -> dict:
    """{unit: {units it imports}} over every source file of the project's packages."""
    graph: dict[str, set] = {}
    for pkg in PROJECT:
        for path in (ROOT / pkg).rglob("*.py"):
            me = _unit(path)
            deps = graph.setdefault(me, set())
            for node in ast.walk(ast.parse(path.read_text(), str(path))):
                if isinstance(node, ast.ImportFrom):
                    if node.level:
                        base = list(path.relative_to(ROOT).parent.parts)
                        base = base[:len(base) - (node.level - 1)]
                        mods = [".".join(base + ([node.module] if node.module else []))]
                        if node.module is None:  # from . import a, b
                            mods = [f"{mods[0]}.{a.name}" for a in node.names]
                    else:
                        mods = [node.module]
                elif isinstance(node, ast.Import):
                    mods = [a.name for a in node.names]
                else:
                    continue
                for m in mods:
                    t = _target(m)
                    if t is not None and t != me:
                        deps.add(t)
    return graph


GRAPH = import_graph()

ALLOWED = {
    "common": set(),
    "generated": set(),
    # energy.load_model derives a model it has not seen (the one lazy hop back: derivation
    # reads energy's Lattice, energy asks derivation to compile it; see the cycle test)
    "energy": {"common", "generated", "derivation"},
    "derivation": {"common", "energy"},
    "numerics.lattice": {"common", "generated"},
    "numerics.theory": {"common", "generated", "numerics.lattice"},
    # the one map engine takes any model (ModelMapParameters): models sit below it
    "numerics.maps": {"common", "generated", "energy", "numerics.lattice", "numerics.theory",
                      "numerics.models"},
    # the paper chain's models register the paper engine's theory of its eq. IC start
    # (numerics.models._extras): the paper chain's theory sits below any model's
    "numerics.models": {"common", "generated", "energy", "numerics.lattice", "numerics.theory"},
    "numerics": {"numerics.lattice", "numerics.theory", "numerics.maps"},
    # any model's figures (four-wave-pairs) read models from energy and numerics.models
    "scenes": {"common", "derivation", "generated", "energy", "numerics", "numerics.lattice",
               "numerics.theory", "numerics.maps", "numerics.models"},
    "cli": {"common", "energy", "derivation", "generated", "numerics", "numerics.lattice",
            "numerics.theory", "numerics.maps", "numerics.models", "scenes"},
}


@pytest.mark.parametrize("unit", sorted(ALLOWED))
def test_imports_run_one_way(unit):
    assert GRAPH[unit] <= ALLOWED[unit], (
        f"{unit} imports {sorted(GRAPH[unit] - ALLOWED[unit])}, against the layering")


def test_no_import_cycles():
    seen, stack = set(), set()

    def visit(u, path):
        assert u not in stack, f"import cycle: {' -> '.join(path + [u])}"
        if u in seen:
            return
        stack.add(u)
        for v in GRAPH.get(u, ()):
            if (u, v) == ("energy", "derivation"):  # the compile-on-first-use hop (ALLOWED)
                continue
            if v != "numerics" or u not in ("numerics.lattice", "numerics.theory",
                                             "numerics.maps"):
                visit(v, path + [u])
        stack.discard(u)
        seen.add(u)

    for u in GRAPH:
        visit(u, [])


def test_cli_above_scenes_above_numerics():
    """cli imports scenes and numerics; scenes imports numerics, never cli; nothing below
    scenes imports it or cli."""
    assert "scenes" in GRAPH["cli"] and "numerics" in GRAPH["scenes"]
    for unit, deps in GRAPH.items():
        if unit != "cli":
            assert "cli" not in deps, f"{unit} imports cli"
        if unit not in ("cli", "scenes"):
            assert "scenes" not in deps, f"{unit} imports scenes"


# --- private names stay in their package ------------------------------------------------------

#: a test that reaches into another package's private module or name, and why (what it
#: tests is that private piece itself, or a fault it injects there)
TEST_EXCEPTIONS = {
    "cli.map._agreement_text": "the map summary's wording, a sentence at a time",
    "cli._resolved": "the paper flags' resolution check against a model's, one rule",
    "cli._slow": "the slow step's note, its timer's threshold set to 0.05 s to fire it",
    "cli._model_point_args": "a model point's measure_point made slower to fire its note",
    "numerics.models._losses_hill": "each growing offset's damping against the damped ring's "
                                    "monodromy (probe 102's referee)",
    "derivation._continuum": "the continuum model's symbolic steps against the paper",
    "derivation._energy": "a Rayleigh function refused by the derivation (not quadratic)",
    "numerics.models._losses": "the damped NLS's pair integrator against solve_ivp, the "
                               "amplitude sampling against dense quadrature, its compiled "
                               "quadrature and restricted offsets against the array forms",
    "numerics.models._losses_fourwave": "the four-wave rates' exact scaling in a^2 against "
                                        "the kernel recomputed at each amplitude",
    "numerics.models._losses_sampling": "the exact theory's coarse-to-fine offsets: which "
                                        "columns a profile refines",
    "numerics.models._small_algebra": "the Hill kernel's LU that skips exact zeros against a "
                                  "dense solve, and its round-off threshold on the Hessian's "
                                  "harmonics; its L D L^* fold against a dense solve",
    "derivation._mi": "the MI band's derivation step",
    "derivation._pipeline": "the semi-discrete NLS derived afresh (the generated code's source)",
    "numerics.maps._integrity": "a garbled chunk found from its Blosc header, never decoded",
    "numerics.maps._model_point_curves": "a model point's Hill-copy rule against a plain scan",
    "derivation._report": "the derivation report's sections",
    "derivation._soliton": "the soliton's symbolic solution against the generated one",
    "numerics.lattice._analysis": "the spectrum bins' helpers, checked bin by bin",
    "numerics.lattice._cache": "the simulation cache's files, damaged on purpose",
    "numerics.lattice._integrate": "the stepper table (every method's stepper class)",
    "numerics.lattice._kernels": "the compiled kernels against the NumPy reference",
    "numerics.lattice._run": "the record grid of a run",
    "numerics.lattice._runcontrol": "an interrupt injected into the run loop",
    "numerics.lattice._simulate": "an interrupt injected into the run loop",
    "numerics.maps._store": "the map store's format and damage handling",
    "numerics.maps._progress": "the progress lines' timing and pace, on a clock of the test's",
    "numerics.maps._cluster": "the progress lines' clock started before the cluster (probe 97)",
    "cli.app._interrupted": "the interrupt line of a map whose every cell is done (probe 97)",
    "numerics.maps._devices": "a run stopped where the store's closing attributes are written",
    "numerics.maps._model_columns": "the mode kind's attributes, read beside a map cell",
    "numerics.maps._model_point_rows": "a point's note from rows built by hand (damped "
                                       "verdicts beside lossless rates)",
    "numerics.models._simulate": "the energy balance's interval rule, records and samples",
    "numerics.models._threewave": "the offsets the three-wave check is given (a spy)",
    "numerics.lattice._verdict": "the run-length bounds against the --help text and the API",
    "numerics.maps._estimate": "the map estimate's start-up and speed model, part by part",
    "numerics.maps._gpu": "the GPU cells' seed rule and launch, under the CUDA simulator",
    "scenes._plotting": "the map figure's cell edges, checked cell by cell",
    "numerics.theory._hill": "Hill's batched eigenproblems, the pencil's input",
    "numerics.theory._pencil": "the pencil eigenvalue solver",
    "numerics.models._exact": "the anchors' writer moves the wave exact_gain solves (its own "
                              "round-off spread, tests/anchors); the kept-mode rule's "
                              "centre of tied harmonics",
    "numerics.models._kept": "the compiled kept-mode rule against eigenvectors made by hand "
                             "(the centre of tied harmonics)",
    "numerics.models._collocation": "the wave's chord method with its Jacobian taken "
                                    "again, on a system whose root is known",
    "numerics.models._sidebands": "the compiled Hill kernel's early give-up where the "
                                  "central discs chain, against its own full pass",
    "numerics.models._cluster_solve": "the Hill kernel's fold on the axis against LU",
    "numerics.models._frozen_roots": "the Hill kernel's frozen roots against LAPACK",
    "numerics.models._ring_copies": "a one-field ring's spectrum from its modes' copies at "
                                    "l = 0 against the spectrum solved offset by offset",
    "numerics.models._real_gauge": "the phase that makes the Hill pencil real, and the "
                                   "frozen pencil's real eigenvalues against the complex ones",
    "numerics.lattice._bound": "the exponential bound's Python source against its "
                               "compiled host copy",
    "numerics.models._growth": "the drift bound of a carrier harmonic's ring mode and the "
                               "modes a damped run's amplification reads",
    "numerics.models._hill_dense": "the dense eigenproblem's resolution (sqrt(eps) of the "
                                   "pencil's scale)",
    "numerics.theory._plane_wave": "the batched plane-wave solver the exact map uses",
    "numerics.theory._quasiperiodic": "the torus gain spectrum of a launched state",
    "numerics.theory._resonance": "the exact-map engine's reduced determinant",
    "numerics.theory._response": "the linear response's internals",
    "numerics.theory._torus": "the torus integrator and its peak finder",
    "scenes._runner": "the scene runner's files, and a failure injected in a figure",
}
#: the bench reaches private code only to time its parts
BENCH_EXCEPTIONS = {
    "numerics.models._losses_hill": "bench/probe_lossreview102.py: each growing offset's "
                                    "damping against the damped ring's monodromy rates",
    "numerics.lattice._kernels": "bench/speed.py times the kernel's parts one by one "
                                 "(stencil, the libm variant, the vectorised loops)",
    "numerics.maps._cells": "bench/gpu.py takes a map's step (map_step) as a map does",
    "numerics.models._sidebands": "bench/hill_kernel_check.py swaps the compiled Hill kernel "
                                  "for another tree's copy, to compare their answers",
    "numerics.maps._gpu": "bench/gpu.py reports the device's name and whether it simulates",
    "numerics.maps._gpu_models": "bench/gpu.py times one launch of each model's kernel (its "
                                 "chains started as a map's are)",
}


def private_imports(folder: str) -> dict:
    """{private target: [files]} for the imports in ``folder`` that reach another
    package's private module or name (``numerics.lattice._kernels``, ``cli.map._x``)."""
    out: dict[str, list] = {}
    for path in sorted((ROOT / folder).rglob("*.py")):
        me = _unit(path) if folder in PROJECT else folder
        for node in ast.walk(ast.parse(path.read_text(), str(path))):
            if isinstance(node, ast.ImportFrom):
                if node.level:
                    base = list(path.relative_to(ROOT).parent.parts)
                    base = base[:len(base) - (node.level - 1)]
                    module = ".".join(base + ([node.module] if node.module else []))
                else:
                    module = node.module
                pairs = [(module, a.name) for a in node.names]
            elif isinstance(node, ast.Import):
                pairs = [(a.name, None) for a in node.names]
            else:
                continue
            for module, name in pairs:
                target = _target(module)
                if target is None or target == me:
                    continue
                full = module.split(".") + ([name] if name else [])
                for i, part in enumerate(full):
                    if part.startswith("_") and not part.startswith("__"):
                        out.setdefault(".".join(full[:i + 1]), []).append(path.name)
                        break
    return out


@pytest.mark.parametrize("folder", PROJECT)
def test_the_library_imports_no_private_name_across_packages(folder):
    assert not private_imports(folder), private_imports(folder)


@pytest.mark.parametrize("folder,exceptions", [("bench", BENCH_EXCEPTIONS),
                                               ("tests", TEST_EXCEPTIONS)])
def test_bench_and_tests_reach_private_names_only_where_listed(folder, exceptions):
    found = private_imports(folder)
    assert set(found) <= set(exceptions), sorted(set(found) - set(exceptions))
    assert set(exceptions) <= set(found), f"no longer needed: {set(exceptions) - set(found)}"


def test_facade_is_small_and_every_name_resolves():
    assert len(numerics.__all__) <= 30
    for sub in (numerics.lattice, numerics.theory, numerics.maps):
        for name in sub.__all__:
            assert getattr(sub, name) is getattr(numerics, name)
    with pytest.raises(AttributeError, match="no attribute 'nonsense'"):
        numerics.nonsense


def test_source_hash_covers_new_and_changed_files(tmp_path):
    pkg = tmp_path / "pkg"
    (pkg / "sub").mkdir(parents=True)
    (pkg / "a.py").write_text("x = 1\n")
    h0 = source_hash(pkg)
    (pkg / "sub" / "b.py").write_text("y = 2\n")  # a module nobody listed
    h1 = source_hash(pkg)
    (pkg / "sub" / "b.py").write_text("y = 3\n")
    h2 = source_hash(pkg)
    assert len({h0, h1, h2}) == 3
    assert source_hash(pkg) == h2  # and nothing else (no times, no paths) enters it


# --- one vocabulary ---------------------------------------------------------------------------

BLUE = Material.paper("blue")
K = 2 * np.pi * 8 / 64


@pytest.mark.parametrize("start,legacy", [("paper", "continuum"), ("discrete", "discrete"),
                                          ("travelling", "travelling")])
def test_start_names_and_their_earlier_spelling_give_the_same_state(start, legacy):
    a = initial_condition(BLUE, "coupled", 64, K, 0.02, seed=1, start=start)
    b = initial_condition(BLUE, "coupled", 64, K, seed=1, eps=0.01, A0=1.0, omega_model=legacy)
    for f in ("theta", "theta_dot", "U", "U_dot"):
        np.testing.assert_array_equal(getattr(a, f), getattr(b, f))  # bit for bit


def test_amplitude_is_the_peak_rotation():
    st = initial_condition(BLUE, "rotation", 64, K, amplitude=0.05, noise=0.0)
    assert abs(np.max(np.abs(st.theta)) - 0.05) < 1e-15
    run = simulate(BLUE, "rotation", 64, K, amplitude=0.05, t_end=1.0, dt=0.05)
    assert run.amplitude == 0.05 and run.start == "paper"
    assert "amplitude=0.05" in repr(run) and len(repr(run)) < 400  # no arrays in the repr


def test_amplitude_given_two_ways_is_refused():
    with pytest.raises(TypeError, match="not both"):
        simulate(BLUE, "rotation", 64, K, amplitude=0.02, eps=0.01, t_end=1.0)
    with pytest.raises(ValueError, match="start"):
        simulate(BLUE, "rotation", 64, K, start="continuum", t_end=1.0)


# --- one theory, one spelling per layer -----------------------------------------------------

def test_each_theory_has_one_spelling_per_layer_from_its_record():
    """The API's labels, the generated modules, the coefficients table's columns, the
    soliton command's --theory values, a map store's variables and point.json's theory keys
    all come from ``numerics.theory.THEORY_RECORDS``."""
    from cli.app import build_parser
    from numerics.maps import MapParameters, measure_point, theory_columns
    from numerics.theory import (
        MAP_COLUMNS,
        NLS_THEORIES,
        PAPER_START,
        SOLITON_THEORIES,
        THEORIES,
        THEORY_RECORDS,
        nls_coefficients,
    )

    labels = [t.label for t in THEORY_RECORDS]
    assert len(set(labels)) == len(labels)
    assert set(THEORIES) | {PAPER_START} <= set(labels)
    # the generated modules and the NLS theories' API names
    for t in NLS_THEORIES:
        assert t.closed_forms().__name__ == f"generated.{t.module}"
        assert SOLITON_THEORIES[t.label] is t.closed_forms()
    assert set(nls_coefficients(BLUE, 0.8)) == {t.column for t in NLS_THEORIES}
    # the CLI: the soliton command's --theory takes the records' cli names
    sub = next(a for a in build_parser()._actions if a.dest == "cmd")  # argparse's own tree
    theory = next(a for a in sub.choices["soliton"]._actions if a.dest == "theory")
    assert set(theory.choices) == {t.cli for t in NLS_THEORIES}
    # the store: verdict_<key> and peak_gain_<key> for every map column but the predicted one
    params = MapParameters(case="coupled", alpha=2.5, K_s=0.01851, delta=(0.003,), k=(0.8,),
                           amplitude=0.02, N=64, t_end=500.0, seeds=1, start="travelling",
                           theory_only=True)
    stored = set(theory_columns(params))
    for key in MAP_COLUMNS:
        if key != "predicted":  # filled per cell by predict_cell, not by theory_columns
            assert {f"verdict_{key}", f"peak_gain_{key}"} <= stored, key
    assert {n.removeprefix("verdict_") for n in stored if n.startswith("verdict_")} \
        <= set(MAP_COLUMNS)
    # point.json: the theories by their labels
    point = measure_point(BLUE, "coupled", 0.81681, start="travelling", N=64).as_dict()
    assert list(point["theories"]) == list(THEORIES)


def test_one_map_engine():
    """Every `flexmm map`, the paper flags' and any model's, runs through
    ``numerics.maps.run_map`` into OUT/map.zarr: no command keeps cells of its own (a loop
    over cells, a journal, a second file format)."""
    for name in ("map.py", "model_map.py"):
        tree = ast.parse((ROOT / "cli" / name).read_text())
        imported = {(node.module, a.name) for node in ast.walk(tree)
                    if isinstance(node, ast.ImportFrom) for a in node.names}
        assert ("numerics.maps", "run_map") in imported, name
        called = {n.func.id if isinstance(n.func, ast.Name) else getattr(n.func, "attr", None)
                  for n in ast.walk(tree) if isinstance(n, ast.Call)}
        assert not called & {"model_map", "map_cells", "simulated_cell", "to_netcdf"}, name
        strings = {n.value for n in ast.walk(tree) if isinstance(n, ast.Constant)
                   and isinstance(n.value, str)}
        assert not any(".jsonl" in s or s.endswith(".nc") for s in strings), name
    # a model's map answers what the engine asks, as the paper chain's does
    from numerics.maps import MapParameters, ModelMapParameters

    asked = ("grid_shape", "dims", "axis_values", "store_coords", "theory_names",
             "flag_columns", "new_dataset", "task", "block_cost", "estimated_seconds",
             "attrs", "identity", "other_map")
    for cls in (MapParameters, ModelMapParameters):
        assert all(hasattr(cls, a) for a in asked), cls


# --- one point path ---------------------------------------------------------------------------

#: the cli modules of `flexmm point` (the command, a model point's checks, text and figure)
POINT_MODULES = ("point.py", "_model_point_args.py", "_model_point_text.py", "model_figure.py")
#: what a model point computes, in numerics.models: the numbers of its rows and curves
MODEL_THEORY = {"exact_gain", "exact_gain_checked", "four_wave", "nls", "simulate_seeds",
                "simulate_model", "model_coefficients", "ring_misses", "ring_offsets",
                "classify_mode", "extra_theories", "nls_amplification",
                "exact_amplification", "four_wave_amplification", "growth_rates"}


def _tree(path: Path):
    return ast.parse(path.read_text(), str(path))


def test_one_point_path():
    """Every `flexmm point`, the paper flags' and any model's, is one command (``run_point``
    in cli/point.py) over one entry point, ``numerics.maps.measure_point``, which takes each
    kind of point by its type: the numbers are numerics', the cli checks, prints, writes."""
    defining = sorted(p.name for p in (ROOT / "cli").glob("*.py")
                      if any(isinstance(n, ast.FunctionDef) and n.name == "run_point"
                             for n in ast.walk(_tree(p))))
    assert defining == ["point.py"], defining
    for name in POINT_MODULES:
        tree = _tree(ROOT / "cli" / name)
        imported = {(n.module, a.name) for n in ast.walk(tree)
                    if isinstance(n, ast.ImportFrom) for a in n.names}
        # a model's start names are a registry look-up (the option's check), not a theory
        from_models = {a for m, a in imported if m == "numerics.models"} - {"extra_starts"}
        assert not from_models, (name, from_models)
        called = {n.func.id if isinstance(n.func, ast.Name) else getattr(n.func, "attr", None)
                  for n in ast.walk(tree) if isinstance(n, ast.Call)}
        assert not called & MODEL_THEORY, (name, called & MODEL_THEORY)
    point = _tree(ROOT / "cli" / "point.py")
    assert ("numerics.maps", "measure_point") in {
        (n.module, a.name) for n in ast.walk(point) if isinstance(n, ast.ImportFrom)
        for a in n.names}
    # app.py sends every point to that one function
    app = _tree(ROOT / "cli" / "app.py")
    assert not any(isinstance(n, ast.ImportFrom) and any("model_point" in a.name
                                                         for a in n.names)
                   for n in ast.walk(app))
    # each kind of point answers measure_point, as each kind of map answers run_map
    from numerics.maps import POINT_KINDS, ModelPoint, ModelPointSpec, PointResult

    assert {Material, ModelPointSpec} <= set(POINT_KINDS)
    assert all(hasattr(cls, "as_dict") for cls in (PointResult, ModelPoint))

# --- one stepper ------------------------------------------------------------------------------

def _compiled_functions(path: Path):
    """The functions of a file that Numba compiles by decorator (njit or jit, in any
    spelling: ``@njit``, ``@numba.njit(...)``; nested ones too)."""
    tree = ast.parse(path.read_text(), str(path))
    jit = {"njit", "jit"}

    def is_jit(node):
        f = node.func if isinstance(node, ast.Call) else node
        return (isinstance(f, ast.Name) and f.id in jit) or (
            isinstance(f, ast.Attribute) and f.attr in jit)

    for node in ast.walk(tree):
        if isinstance(node, ast.FunctionDef) and any(is_jit(d) for d in node.decorator_list):
            yield node


def test_one_stepper():
    """Every model's run steps in numerics.lattice (``ForceStepper``: the one SRKN and RK4
    implementation for a compiled force): no compiled function in numerics/models takes a
    time step or a number of steps, and the integrators' coefficients are written once,
    in numerics/lattice/_integrators.py."""
    from numerics.lattice import METHODS, get_method

    # not a lattice: the damped NLS's sideband pair propagated exactly over piecewise-
    # constant coefficients (cosh/sinh of each interval; a theory, no force, no state), and
    # the trapezoid quadrature of a rate along the decaying carrier (along_decay: a sum);
    # "step" is one interval's exponential of that pair, shared by its two loops
    theory = {("_losses_pairs.py", "pairs_top"), ("_losses_pairs.py", "pairs_all"),
              ("_losses_pairs.py", "step"), ("_losses.py", "integrate")}
    for path in sorted((ROOT / "numerics" / "models").rglob("*.py")):
        for fn in _compiled_functions(path):
            if (path.name, fn.name) in theory:
                continue
            args = {a.arg for a in fn.args.args}
            assert not args & {"dt", "h", "nsteps", "steps"}, (
                f"{path.name}: {fn.name}({', '.join(sorted(args))}) is a stepping loop: "
                "steps live in numerics.lattice (ForceStepper)")
    tree = ast.parse((ROOT / "numerics" / "models" / "_simulate.py").read_text())
    imported = {a.name for node in ast.walk(tree) if isinstance(node, ast.ImportFrom)
                and node.module == "numerics.lattice" for a in node.names}
    assert "ForceStepper" in imported
    # every SRKN coefficient other than 0, 1/2 and 1 appears in one file of the project
    coefficients = {float(c) for m in METHODS for c in get_method(m).a + get_method(m).b
                    if float(c) not in (0.0, 0.5, 1.0)}
    shown = {c: f"{c!r}"[:12] for c in coefficients}  # 10 digits: no accidental match
    owners = {}
    for pkg in PROJECT:
        for path in (ROOT / pkg).rglob("*.py"):
            text = path.read_text()
            for c, s in shown.items():
                if s.lstrip("-") in text:
                    owners.setdefault(c, set()).add(path.relative_to(ROOT).as_posix())
    literal = {p for files in owners.values() for p in files}
    assert literal == {"numerics/lattice/_integrators.py"}, sorted(literal)
