"""The symbolic pipeline against the paper's typed forms, and its generated code."""

import difflib
import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
import sympy as sp

from derivation import derive, derive_continuum, paper, paper_forms
from derivation._continuum import K_s, K_theta, alpha, k
from derivation._mi import A0, K, g
from derivation._report import TEST_POINTS
from generated import coefficients as co

ROOT = Path(__file__).resolve().parents[1]
GENERATED = ROOT / "generated"
GENERATED_FILES = ("coefficients.py", "lattice_coefficients.py", "lattice_model.py",
                   "soliton.py", "derivation.md", "models/__init__.py") + tuple(
    f"models/{p.stem.replace('-', '_')}.py"
    for p in sorted((Path(__file__).resolve().parents[1] / "energy" / "models").glob("*.toml")))


@pytest.fixture(scope="module")
def d():
    return derive()


def test_continuum_constants_from_lattice_taylor_expansion():
    cont = derive_continuum()
    for name in ("C1", "C2", "C3", "C4"):
        assert sp.simplify(cont.C[name] - getattr(paper_forms, name)) == 0, name


@pytest.mark.parametrize("name", list(paper_forms.FORMS))
def test_derived_minus_paper_is_exactly_zero(d, name):
    paper, _ = paper_forms.FORMS[name]
    derived = d.form(name).expr
    if name == "mi_growth_rate":
        derived = d.mi.growth_rate  # the paper's form holds inside the band
    assert sp.simplify(derived - paper) == 0


def test_both_cases_share_the_linear_part(d):
    rot, cpl = d.cases["rotation"], d.cases["coupled"]
    assert sp.simplify(rot.g1 - cpl.g1) == 0
    assert rot.u2_coefficient == 0  # no displacement in case (I)


def test_mi_branches_and_peak(d):
    mi = d.mi
    assert sp.simplify(mi.omega0 - (sp.Symbol("k0", real=True) ** 2 / 2 - g * A0**2)) == 0
    gp = sp.Symbol("gp", positive=True)
    assert sp.simplify(mi.peak_growth.subs(g, gp) - gp * A0**2) == 0


def _grid(n=400, seed=1):
    """Random material points away from the singular sets (|delta|, |k^2-omega^2| small)."""
    rng = np.random.default_rng(seed)
    kk = rng.uniform(0.05, 1.5, 4 * n)
    al = rng.uniform(0.5, 4.0, 4 * n)
    ks = rng.uniform(0.005, 0.05, 4 * n)
    kt = rng.uniform(0.005, 0.05, 4 * n)
    om2 = al**2 * ((ks - kt) * kk**2 + 6 * kt)
    ok = (np.abs(ks - kt) > 0.05 * ks) & (np.abs(kk**2 - om2) > 0.05 * kk**2)
    return kk[ok][:n], al[ok][:n], ks[ok][:n], kt[ok][:n]


MATERIAL_FUNCS = ["omega", "group_velocity", "g1", "g2_rotation", "g2_coupled",
                  "g_rotation", "g_coupled", "u2_coefficient"]


@pytest.mark.parametrize("name", MATERIAL_FUNCS)
def test_generated_equals_paper_numerically(name):
    # Both sides evaluate the same closed form arranged differently; away from the
    # singular sets the condition number is < 1e2, so agreement to 1e-12 relative is
    # what double precision allows (a wrong term would show at O(1)).
    paper = sp.lambdify((k, alpha, K_s, K_theta), paper_forms.FORMS[name][0], "numpy")
    args = _grid()
    got = getattr(co, name)(*args)
    want = paper(*args)
    assert got.shape == args[0].shape
    np.testing.assert_allclose(got, want, rtol=1e-12, atol=0)


def test_generated_mi_functions_equal_paper():
    rng = np.random.default_rng(2)
    gg = rng.uniform(0.1, 5e3, 300)
    aa = rng.uniform(0.1, 2.0, 300)
    for name in ("mi_cutoff", "mi_fastest"):
        paper = sp.lambdify((g, A0), paper_forms.FORMS[name][0], "numpy")
        np.testing.assert_allclose(getattr(co, name)(gg, aa), paper(gg, aa), rtol=1e-12)
    KK = rng.uniform(0, 1, 300) * co.mi_cutoff(gg, aa)  # inside the band
    paper = sp.lambdify((K, g, A0), paper_forms.mi_growth_rate, "numpy")
    np.testing.assert_allclose(co.mi_growth_rate(KK, gg, aa), paper(KK, gg, aa), rtol=1e-10)


def test_growth_rate_band_structure():
    g_, a_ = 2.0, 0.7
    Kc, Km = co.mi_cutoff(g_, a_), co.mi_fastest(g_, a_)
    KK = np.linspace(-2 * Kc, 2 * Kc, 2001)
    rate = co.mi_growth_rate(KK, g_, a_)
    assert np.all(rate[np.abs(KK) >= Kc] == 0)
    assert np.all(rate[(np.abs(KK) < Kc) & (KK != 0)] > 0)
    assert co.mi_growth_rate(Km, g_, a_) == pytest.approx(g_ * a_**2, rel=1e-14)
    assert co.mi_growth_rate(Km, g_, a_) >= rate.max()
    # defocusing: no band at all
    assert np.all(co.mi_growth_rate(KK, -g_, a_) == 0)
    with np.errstate(invalid="ignore"):
        assert np.isnan(co.mi_cutoff(-g_, a_)) and np.isnan(co.mi_fastest(-g_, a_))


def test_broadcasting():
    kk = np.linspace(0.1, 1.0, 7)[:, None]
    kt = np.linspace(0.01, 0.03, 5)[None, :]
    out = co.g_coupled(kk, paper.ALPHA, paper.K_S + 0.0013, kt)
    assert out.shape == (7, 5)
    # every entry is the scalar evaluation at its own (k, K_theta), bit for bit
    each = [[co.g_coupled(float(a), paper.ALPHA, paper.K_S + 0.0013, float(b))
             for b in kt.ravel()] for a in kk.ravel()]
    assert np.array_equal(out, np.array(each))


@pytest.mark.parametrize("point", list(TEST_POINTS))
def test_group_velocity_and_g1_are_derivatives_of_omega(point):
    p = dict(TEST_POINTS[point])
    k0 = p.pop("k")
    h = 1e-4  # central differences: truncation h^2 |w'''| ~ 1e-10, rounding 1e-16/h^2 ~ 1e-8
    w = lambda x: co.omega(x, **p)
    vg_fd = (w(k0 + h) - w(k0 - h)) / (2 * h)
    g1_fd = (w(k0 + h) - 2 * w(k0) + w(k0 - h)) / h**2
    assert co.group_velocity(k0, **p) == pytest.approx(vg_fd, rel=1e-7)
    assert co.g1(k0, **p) == pytest.approx(g1_fd, rel=1e-5)


def test_paper_test_points_have_the_papers_signs():
    blue, green = TEST_POINTS["blue"], TEST_POINTS["green"]
    assert co.g_rotation(**blue) < 0  # blue, case (I): defocusing, stable (Fig. 5)
    assert co.g_coupled(**blue) > 0  # blue, case (II): focusing, MI (Fig. 6)
    assert co.g_rotation(**green) > 0  # green, case (I): focusing, MI (Fig. 7)
    assert co.g_coupled(**green) < 0  # green, case (II): defocusing (erratum 1), stable


def test_case_one_sign_is_minus_sign_of_delta():
    # Fig. 3(a): "for case (I) the sign of g solely depends on the sign of delta"
    kk = np.linspace(0.01, 2.0, 50)[:, None]  # omega^2 > 0 on the whole grid
    dl = np.linspace(-0.01, 0.01, 40)
    dl = dl[np.abs(dl) > 1e-6][None, :]
    kt = 0.015
    gr = co.g_rotation(kk, 2.5, kt + dl, kt)
    assert np.all(np.sign(gr) == -np.sign(dl))


def test_singular_points_follow_numpy_semantics():
    # delta = 0: g1 = 0 and g = g2/g1 diverges
    with np.errstate(divide="ignore", invalid="ignore"):
        assert co.g1(0.5, 2.5, 0.02, 0.02) == 0.0
        assert np.isinf(co.g_rotation(0.5, 2.5, 0.02, 0.02))
        assert not np.isfinite(co.g_coupled(0.5, 2.5, 0.02, 0.02))
    # resonance k^2 = omega^2 (alpha = 1, delta = 1/4, K_theta = 1/8, k = 1; exact floats)
    res = dict(k=1.0, alpha=1.0, K_s=0.375, K_theta=0.125)
    assert co.omega(**res) == 1.0
    with np.errstate(divide="ignore", invalid="ignore"):
        assert not np.isfinite(co.u2_coefficient(**res))
        assert not np.isfinite(co.g2_coupled(**res))
        assert not np.isfinite(co.g_coupled(**res))
    with pytest.warns(RuntimeWarning):
        co.g_rotation(0.5, 2.5, 0.02, 0.02)


def _diff(a: Path, b: Path) -> str:
    return "".join(difflib.unified_diff(
        a.read_text().splitlines(True), b.read_text().splitlines(True),
        fromfile=str(a), tofile=str(b)))


def test_generated_is_what_make_derive_writes(tmp_path):
    from derivation.__main__ import write_outputs

    written = write_outputs(tmp_path)
    assert sorted(str(p.relative_to(tmp_path)) for p in written) == sorted(GENERATED_FILES)
    mask = os.umask(0)
    os.umask(mask)
    for p in written:  # plain files (0644 under the usual umask), not mkstemp's 0600
        assert p.stat().st_mode & 0o777 == 0o666 & ~mask, p
    assert not list(tmp_path.glob(".*.tmp")), "temporary files left behind"
    problems = []
    for fresh in written:
        committed = GENERATED / fresh.relative_to(tmp_path)
        if not committed.exists():
            problems.append(f"{committed} is missing")
        elif committed.read_bytes() != fresh.read_bytes():
            problems.append(_diff(committed, fresh))
    assert not problems, ("generated/ is stale; run `make derive` and commit.\n"
                          + "\n".join(problems))


def test_derive_is_deterministic_across_hash_seeds(tmp_path):
    # one fresh process with another hash seed against the committed files (which the
    # in-process test above regenerates too): set iteration order must not leak out
    env = dict(os.environ, PYTHONHASHSEED="4242")
    subprocess.run([sys.executable, "-m", "derivation", "--out", str(tmp_path)], check=True,
                   cwd=ROOT, env=env, capture_output=True)
    for name in GENERATED_FILES:
        assert (tmp_path / name).read_bytes() == (GENERATED / name).read_bytes(), name


def test_importing_coefficients_does_not_import_sympy():
    code = ("import sys, generated.coefficients as c, generated.lattice_model, "
            "common.paper; "
            "assert 'sympy' not in sys.modules, 'sympy imported'; "
            "assert c.omega(0.5, 2.5, 0.02, 0.01) > 0")
    subprocess.run([sys.executable, "-c", code], check=True, cwd=ROOT)


def test_generated_files_carry_the_banner():
    for name in GENERATED_FILES:
        head = (GENERATED / name).read_text().splitlines()[:5]
        assert any("DO NOT EDIT BY HAND" in line for line in head), name
        text = (GENERATED / name).read_text()
        assert str(ROOT) not in text  # no machine paths


def test_every_erratum_is_in_the_readme():
    """Each erratum is written out in the errata page the README's 'Errata' section links."""
    from derivation import ERRATA

    readme = (ROOT / "README.md").read_text()
    assert "## Errata" in readme and "docs/reliability.md#errata" in readme
    errata = (ROOT / "docs" / "reliability.md").read_text()
    for e in ERRATA:
        assert e["where"] in errata, e["where"]


def test_the_derivation_stamp_lists_what_derivation_imports_and_is_current():
    """`make run` re-derives when generated/SOURCES.sha256 differs from the sources' hashes:
    it must list every common/ module derivation imports (else a change there is missed),
    only those (else a change elsewhere re-derives a fresh clone for nothing), and be the
    committed hashes of those files (else a fresh clone re-derives and dirties the tree)."""
    import ast
    import hashlib

    root = Path(__file__).resolve().parents[1]
    imported = {"common/__init__.py"}
    for f in (root / "derivation").glob("*.py"):
        for node in ast.walk(ast.parse(f.read_text())):
            if isinstance(node, ast.ImportFrom) and node.module and (
                    node.module == "common" or node.module.startswith("common.")):
                parts = node.module.split(".")[1:]
                if parts:
                    imported.add(f"common/{parts[0]}.py")
                else:  # from common import paper
                    imported.update(f"common/{a.name}.py" for a in node.names)
    makefile = (root / "Makefile").read_text()
    listed = set(next(line for line in makefile.splitlines()
                      if line.startswith("DERIVATION_COMMON :=")).split(":=")[1].split())
    assert listed == imported
    stamp = {}
    for line in (root / "generated" / "SOURCES.sha256").read_text().splitlines():
        if "  " in line:
            digest, name = line.split("  ", 1)
            stamp[name] = digest
    expected = sorted(str(p.relative_to(root)) for p in (root / "derivation").glob("*.py"))
    expected += [str(p.relative_to(root)) for p in (root / "energy").glob("*.py")]
    expected += [str(p.relative_to(root)) for p in (root / "energy" / "models").glob("*.toml")]
    assert set(stamp) == set(expected) | listed
    for name, digest in stamp.items():
        assert hashlib.sha256((root / name).read_bytes()).hexdigest() == digest, (
            f"{name} changed since generated/SOURCES.sha256: run `make derive`")
