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
PROJECT = ("cli", "common", "derivation", "generated", "numerics", "scenes")


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
    if parts[0] == "numerics" and len(parts) > 1 and parts[1] in ("lattice", "theory", "maps"):
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
    "derivation": {"common"},
    "numerics.lattice": {"common", "generated"},
    "numerics.theory": {"common", "generated", "numerics.lattice"},
    "numerics.maps": {"common", "generated", "numerics.lattice", "numerics.theory"},
    "numerics": {"numerics.lattice", "numerics.theory", "numerics.maps"},
    "scenes": {"common", "derivation", "generated", "numerics", "numerics.lattice",
               "numerics.theory", "numerics.maps"},
    "cli": {"common", "derivation", "generated", "numerics", "numerics.lattice",
            "numerics.theory", "numerics.maps", "scenes"},
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
            if v != "numerics" or u not in ("numerics.lattice", "numerics.theory",
                                             "numerics.maps"):
                visit(v, path + [u])
        stack.discard(u)
        seen.add(u)

    for u in GRAPH:
        visit(u, [])


def test_scenes_use_public_names_only():
    bad = []
    for path in (ROOT / "scenes").rglob("*.py"):
        for node in ast.walk(ast.parse(path.read_text())):
            if isinstance(node, ast.ImportFrom) and node.module and \
                    node.module.startswith("numerics"):
                private = [p for p in node.module.split(".") if p.startswith("_")]
                private += [a.name for a in node.names if a.name.startswith("_")]
                if private:
                    bad.append(f"{path.name}: from {node.module} import {private}")
    assert not bad, bad


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
                           amplitude=0.02, N=64, t_end=100.0, seeds=1, start="travelling",
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
