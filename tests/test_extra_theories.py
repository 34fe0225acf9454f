"""Theories only some models have (issue 40 item 4): registered by the model's energy in
one place (``numerics.models.extra_theories``), asked by the commands, never named there."""

from __future__ import annotations

from pathlib import Path

import pytest

import energy


def _flexmm_text() -> str:
    return (Path(energy.__file__).parent / "models" / "flexmm.toml").read_text()


def test_the_paper_chain_models_have_the_paper_nls_and_no_other_does(tmp_path):
    """flexmm and flexmm-rotation (and a copy of flexmm's file under another name) have
    the paper's continuum NLS; a model with losses, another energy or another model none."""
    from energy import load_model
    from numerics.models import extra_theories

    renamed = tmp_path / "my-chain.toml"
    renamed.write_text(_flexmm_text().replace('name = "flexmm"', 'name = "my-chain"', 1))
    assert [e.column for e in extra_theories(load_model(str(renamed)))] == ["paper"]
    for name in ("flexmm", "flexmm-rotation"):
        assert [(e.column, e.label) for e in extra_theories(load_model(name))] == [
            ("paper", "continuum NLS")]
    for name in ("flexmm-lossy", "flexmm-stiff-hinge", "fput", "diatomic-fput"):
        assert extra_theories(load_model(name)) == (), name


@pytest.mark.parametrize("name, case", [("flexmm", "coupled"), ("flexmm-rotation", "rotation")])
def test_the_paper_nls_row_is_eq_g_i(name, case):
    """The row is the paper's NLS of eq. g_i (the forms typed from the paper,
    derivation.paper_forms: g1, g2; MI where g2/g1 > 0, peak gain |g2| a^2 / 4), at the
    model's parameters; 1e-10: the generated code against the typed form, round-off."""
    import sympy as sp

    from derivation import paper_forms as pf
    from derivation._continuum import K_s, K_theta, alpha
    from derivation._continuum import k as k_
    from energy import load_model
    from numerics.models import extra_theories

    args = (k_, alpha, K_s, K_theta)
    forms = {"g1": sp.lambdify(args, pf.g1), "g2": sp.lambdify(args, getattr(pf, f"g2_{case}"))}

    model = load_model(name, K_theta=0.012)
    (extra,) = extra_theories(model)
    p = model.params
    for k in (0.3, 0.9, 2.0):
        row = extra.row(model, k, 0.05)
        g1 = forms["g1"](k, p["alpha"], p["K_s"], p["K_theta"])
        g2 = forms["g2"](k, p["alpha"], p["K_s"], p["K_theta"])
        assert row["g1"] == pytest.approx(g1, rel=1e-10)
        assert row["g2"] == pytest.approx(g2, rel=1e-10)
        assert row["verdict"] == ("MI" if g2 / g1 > 0 else "stable")
        assert row["peak_gain"] == pytest.approx(abs(g2) * 0.05**2 / 4 if g2 / g1 > 0 else 0)


def test_a_flexmm_model_map_stores_the_paper_columns(tmp_path):
    """A model map of flexmm has verdict_paper and peak_gain_paper per cell (the point's
    continuum NLS row at each cell's K_theta and k); an fput map has none."""
    from energy import load_model
    from numerics.maps import ModelMapParameters, run_map
    from numerics.models import extra_theories

    p = ModelMapParameters.from_model("flexmm", ("K_theta", [0.008, 0.016]), ("k", [0.6, 1.8]),
                                      0.05, theory_only=True, block=1)
    ds = run_map(p, tmp_path / "a", workers=1, progress=False, log=lambda *a: None)
    assert "paper" in ds.attrs["theories"].split()
    model = load_model("flexmm")
    (extra,) = extra_theories(model)
    for i, Kt in enumerate([0.008, 0.016]):
        for j, k in enumerate([0.6, 1.8]):
            row = extra.row(model.with_params(K_theta=Kt), k, 0.05)
            assert ds["verdict_paper"].values[i, j] == {"MI": 1, "stable": 0}[row["verdict"]]
            assert ds["peak_gain_paper"].values[i, j] == pytest.approx(row["peak_gain"],
                                                                       rel=1e-12)
    q = ModelMapParameters.from_model("fput", ("beta", [0.5, 1.0]), ("k", [1.0, 2.0]), 0.1,
                                      theory_only=True, block=1)
    ds = run_map(q, tmp_path / "b", workers=1, progress=False, log=lambda *a: None)
    assert not any("paper" in v for v in ds.data_vars)
    assert "paper" not in ds.attrs["theories"].split()


def test_registering_a_bad_column_is_refused():
    from numerics.models import register_extra_theory

    with pytest.raises(ValueError, match="lower-case identifier"):
        register_extra_theory("Paper NLS", "x", lambda: "", lambda m, k, a: {})


def test_no_command_branches_on_a_model_name():
    """The commands (cli/) compare no value with a built-in model's name and key no table
    by one: what a model has is asked of the model (extra theories, fast forces)."""
    import ast

    names = set(energy.BUILTIN)
    root = Path(__file__).resolve().parents[1] / "cli"
    found = []
    for path in sorted(root.glob("*.py")):
        for node in ast.walk(ast.parse(path.read_text())):
            consts = []
            if isinstance(node, ast.Compare):
                consts = [node.left, *node.comparators]
            elif isinstance(node, ast.Dict):
                consts = [key for key in node.keys if key is not None]
            for c in consts:
                for sub in ast.walk(c):
                    if isinstance(sub, ast.Constant) and sub.value in names:
                        found.append(f"{path.name}:{node.lineno}: {sub.value!r}")
    assert not found, found
