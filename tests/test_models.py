"""Any lattice from its energy: model files, derived equations, the NLS of any model.

Checks against physics and closed forms: the paper's chain derived from its energy equals
eq. `norm` and its NLS the closed forms of generated/lattice_coefficients.py; FPUT's NLS the
known coefficient with the mean flow (MI at k = pi iff 3 beta > 4 alpha^2); sine-Gordon's
g2 = omega0^2/(4 omega); g1 and v_g equal finite differences of omega(k).
"""

from __future__ import annotations

import math

import numpy as np
import pytest
import sympy as sp

from energy import BUILTIN, Lattice, ModelError, builtin, load_model, parse_model
from numerics.models import branches, carrier, check_rest_stable, nls

KG = """
name = "klein-gordon"
description = "phi^4 chain with a cubic term"
fields = ["u"]
[parameters]
C = 1.0
omega0 = 1.0
alpha = 0.0
beta = 1.0
[energy]
kinetic = "u_t**2/2"
bond = "C*(u_next - u)**2/2"
site = "omega0**2*u**2/2 + alpha*u**3/3 + beta*u**4/4"
"""


def test_the_issue_example_parses_and_equals_the_builtin():
    assert parse_model(KG).content_hash == builtin("klein-gordon").content_hash


def test_every_builtin_model_loads_with_a_stable_rest_state():
    for name in BUILTIN:
        m = load_model(name)
        check_rest_stable(m)
        assert np.all(m.masses > 0)


def test_flexmm_equations_from_the_energy_are_eq_norm():
    # the energy is the source of truth: Lagrange's equations of the built-in model equal
    # eq. `norm` as the derivation types it (derivation._continuum.lattice_accelerations)
    from derivation import equations_of_motion, model_energies
    from derivation._continuum import K_s, K_theta, alpha, lattice_accelerations

    e = model_energies(builtin("flexmm"))
    s = e.symbols
    acc_theta, acc_U = equations_of_motion(e)
    rename = {sp.Symbol(p.name, real=True): q for p, q in
              zip(s.params, (alpha, K_s, K_theta))}
    (tm, Um), (t0, U0), (tp, Up) = s.prev, s.here, s.next
    want_U, want_t = lattice_accelerations(Um, U0, Up, tm, t0, tp)
    assert sp.simplify(acc_U.subs(rename) - want_U) == 0
    assert sp.simplify(acc_theta.subs(rename) - want_t) == 0


@pytest.mark.parametrize("k", [0.3, 0.81681, 1.5, 2.5])
@pytest.mark.parametrize("mat", [(2.5, 0.01851, 0.01551), (2.0, 0.03, 0.02),
                                 (1.3, 0.05, 0.045), (2.5, 0.01851, 0.02151)])
def test_flexmm_nls_equals_the_closed_forms(k, mat):
    # Two independent derivations: the SymPy multiple-scales hierarchy of eq. `norm`
    # (generated/lattice_coefficients.py) and the general formulas from the energy's
    # Taylor tensors. Agreement to 1e-9 relative: both are closed forms evaluated in
    # double precision (observed 1e-15).
    from generated import lattice_coefficients as lc

    a, Ks, Kt = mat
    coupled = nls(load_model("flexmm", alpha=a, K_s=Ks, K_theta=Kt), k)
    rotation = nls(load_model("flexmm-rotation", alpha=a, K_s=Ks, K_theta=Kt), k)
    assert coupled.carrier.omega == pytest.approx(lc.omega(k, a, Ks, Kt), rel=1e-12)
    assert coupled.carrier.group_velocity == pytest.approx(lc.group_velocity(k, a, Ks, Kt),
                                                           rel=1e-9, abs=1e-14)
    assert coupled.g1 == pytest.approx(lc.g1(k, a, Ks, Kt), rel=1e-9, abs=1e-14)
    assert coupled.g2 == pytest.approx(lc.g2_coupled(k, a, Ks, Kt), rel=1e-9)
    assert rotation.g2 == pytest.approx(lc.g2_rotation(k, a, Ks, Kt), rel=1e-9)
    # U's second harmonic: |v2| is the generated |c| of u2 (per A^2)
    assert abs(coupled.second_harmonic[1]) == pytest.approx(
        abs(lc.u2_coefficient(k, a, Ks, Kt)), rel=1e-9)


@pytest.mark.parametrize("alpha,beta", [(0.0, 1.0), (1.0, 1.0), (0.5, 2.0), (0.7, 0.3)])
@pytest.mark.parametrize("k", [0.5, 1.5708, 2.8])
def test_fput_nls_has_its_mean_flow(alpha, beta, k):
    s = math.sin(k / 2)
    r = nls(load_model("fput", alpha=alpha, beta=beta), k)
    assert r.g2 == pytest.approx(-12 * beta * s**3 + 8 * alpha**2 * s * (1 + s**2), rel=1e-10)
    assert r.g1 == pytest.approx(-math.sin(k / 2) / 2, rel=1e-10)


@pytest.mark.parametrize("alpha", [0.6, 1.0])
def test_fput_zone_boundary_verdict_flips_at_3beta_4alpha2(alpha):
    k = math.pi - 1e-6  # the open interval's edge: the zone boundary itself
    beta_c = 4 * alpha**2 / 3
    assert nls(load_model("fput", alpha=alpha, beta=beta_c * 1.05), k).verdict == "MI"
    assert nls(load_model("fput", alpha=alpha, beta=beta_c * 0.95), k).verdict == "stable"


def test_pure_alpha_fput_is_stable_everywhere():
    m = load_model("fput", alpha=1.0, beta=0.0)
    assert all(nls(m, k).verdict == "stable" for k in np.linspace(0.1, 3.0, 15))


@pytest.mark.parametrize("k", [0.4, 1.3, 2.7])
def test_sine_gordon_g2(k):
    r = nls(load_model("sine-gordon", C=1.3, omega0=0.7), k)
    assert r.g2 == pytest.approx(0.7**2 / (4 * r.carrier.omega), rel=1e-12)


def test_klein_gordon_cubic_site_term_through_second_harmonic_and_mean():
    # KG with a cubic site term: g2 = (3 beta - 10 alpha^2 / 3 ...) has a closed form for
    # C = 0 (uncoupled oscillators): the Duffing-type frequency shift of one oscillator,
    # omega0^2 = 1: shift = (3 beta/8 - 5 alpha^2/12) a^2 (Landau & Lifshitz sec. 28) and
    # the NLS shift is -g2 a^2/4, so g2 = -(3 beta/2 - 5 alpha^2/3) at omega0 = 1.
    m = load_model("klein-gordon", C=1e-9, omega0=1.0, alpha=0.4, beta=0.9)
    r = nls(m, 1.0)
    assert r.g2 == pytest.approx(-(1.5 * 0.9 - 5 * 0.4**2 / 3), rel=1e-6)


@pytest.mark.parametrize("name,params,k", [("flexmm", {}, 0.9), ("diatomic-fput", {}, 0.7),
                                           ("klein-gordon", {"C": 0.4}, 2.0)])
def test_group_velocity_and_g1_are_derivatives_of_omega(name, params, k):
    m = load_model(name, **params)
    c = carrier(m, k)
    h = 1e-4
    w = [carrier(m, k + j * h, c.branch).omega for j in (-1, 0, 1)]
    # central differences: error h^2 omega''' ~ 1e-8; 1e-6 leaves room
    assert c.group_velocity == pytest.approx((w[2] - w[0]) / (2 * h), abs=1e-6)
    assert c.g1 == pytest.approx((w[2] - 2 * w[1] + w[0]) / h**2, abs=1e-5)


@pytest.mark.parametrize("k", [1e-9, 1e-5, 1e-4, 1e-2])
def test_acoustic_branch_keeps_its_precision_at_long_waves(k):
    """FPUT's omega = 2 sin(k/2), g1 = -sin(k/2)/2. omega^2 as 2 - 2 cos k lost its digits
    to cancellation: omega^2 = 0 at k = 1e-9 (the carrier refused), g1 3x off at 1e-4.
    omega to 1e-12 relative (a few ulps of the sin form); g1 = (lambda'' - 2 v_g^2) /
    (2 omega) still cancels two O(1) terms, absolute error ~ eps / omega: 1e-4 relative
    where that is below it (k >= 1e-5), its sign and size where it is not (k = 1e-9)."""
    c = carrier(load_model("fput"), k)
    assert c.omega == pytest.approx(2 * math.sin(k / 2), rel=1e-12)
    assert c.group_velocity == pytest.approx(math.cos(k / 2), rel=1e-12)
    if k >= 1e-5:
        assert c.g1 == pytest.approx(-math.sin(k / 2) / 2, rel=1e-4)
    # with a cubic term the mean flow resonates at long waves (v_g -> the sound speed 1):
    # no NLS, said why; beta-FPUT has no mean stress, so nothing resonates (probe 97)
    if k <= 1e-5:
        assert "sound speed" in nls(load_model("fput", alpha=1.0), k).undefined


def test_diatomic_branches_acoustic_and_optical():
    m = load_model("diatomic-fput", m=2.0)
    w = branches(m, np.array([1e-9, math.pi]))
    # closed form: omega^2 = (1 + 1/m) -+ sqrt((1 + 1/m)^2 - 4 sin^2(k/2)/m)
    mu = 1 + 1 / 2.0
    assert w[0, 0] == pytest.approx(0, abs=1e-8)
    assert w[0, 1] == pytest.approx(math.sqrt(2 * mu), rel=1e-12)
    assert w[1, 0] == pytest.approx(math.sqrt(mu - math.sqrt(mu**2 - 2)), rel=1e-12)
    assert w[1, 1] == pytest.approx(math.sqrt(mu + math.sqrt(mu**2 - 2)), rel=1e-12)
    # by field name: u (mass 1) dominates the optical branch at the zone boundary for m=2
    assert carrier(m, 3.0, "v").branch == 0 and carrier(m, 3.0, "u").branch == 1


def test_diatomic_acoustic_nls_has_a_mean_flow_along_the_translation():
    r = nls(load_model("diatomic-fput", alpha=0.5, beta=1.0), 0.8, branch=0)
    assert r.verdict in ("MI", "stable") and r.parts["mean flow"] != 0
    # the mean strain is a translation of both fields together: equal strains
    assert r.strain[0] == pytest.approx(r.strain[1], rel=1e-9)


def test_undefined_nls_says_why():
    # a second harmonic resonant with the carrier's own branch: KG with C = 0 is a
    # flat band; choose omega(2k) = 2 omega(k) on a diatomic chain instead
    m = load_model("diatomic-fput", m=1.0, alpha=1.0)
    ks = np.linspace(0.05, 3.0, 600)
    found = [nls(m, k, branch=0) for k in ks]
    assert all(r.verdict in ("MI", "stable", "undefined") for r in found)
    und = [r for r in found if r.undefined]
    for r in und:
        assert math.isnan(r.g2) and ("resonant" in r.undefined or "sound speed" in
                                     r.undefined or "degenerate" in r.undefined)


# ---------------------------------------------------------------- bad models, one line each
BAD = {
    "syntax": ('bond = "(u_next - u**2/2"', "syntax error"),
    "unknown symbol": ('bond = "K*(u_next - u)**2/2"', "unknown symbol 'K'"),
    "beyond nearest": ('bond = "(u_next2 - u)**2/2"', "beyond the nearest neighbour"),
    "velocity in bond": ('bond = "u_t*(u_next - u)**2/2"', "velocities are allowed in "
                         "energy.kinetic and [dissipation] only"),
    "xor power": ('bond = "(u_next - u)^2/2"', "write '**'"),
    "attribute": ('bond = "__import__(\'os\').system(\'true\')"', "attribute is not allowed"),
    "call": ('bond = "exec(u)"', "unknown function 'exec'"),
    "lambda": ('bond = "(lambda: 1)()"', "not allowed"),
    "string": ('bond = "\'a\'"', "not a real number"),
}


def _model(bond='bond = "(u_next - u)**2/2"', kinetic='kinetic = "u_t**2/2"', extra=""):
    return (f'name = "t"\nfields = ["u"]\n{extra}\n[parameters]\nb = 1.0\n[energy]\n'
            f'{kinetic}\n{bond}\n')


@pytest.mark.parametrize("case", sorted(BAD))
def test_bad_energy_is_one_clear_line(case):
    line, words = BAD[case]
    with pytest.raises(ModelError) as err:
        parse_model(_model(bond=line), "my.toml")
    msg = str(err.value)
    assert words in msg and "\n" not in msg and msg.startswith("my.toml")


@pytest.mark.parametrize("kinetic,words", [
    # a position in the kinetic energy is refused when read; a cubic velocity term reads
    # as a mass that depends on the state
    ('kinetic = "u_t**2/2 + u*u_t**2"', "unknown symbol 'u'"),
    ('kinetic = "u_t**3"', "depends on the state"),
    ('kinetic = "u_t**2/2 + b*u_t"', "not a quadratic form"),
])
def test_kinetic_energy_must_be_diagonal_quadratic(kinetic, words):
    from derivation import model_energies

    with pytest.raises(ModelError, match=words):
        model_energies(parse_model(_model(kinetic=kinetic)))


def test_coupled_velocities_refused():
    text = ('name = "t"\nfields = ["u", "v"]\n[energy]\nkinetic = "(u_t + v_t)**2/2"\n'
            'bond = "(u_next - u)**2/2 + (v_next - v)**2/2"\n')
    with pytest.raises(ModelError, match="diagonal"):
        parse_model(text)


def test_rest_state_not_an_equilibrium_refused():
    from derivation import model_energies

    with pytest.raises(ModelError, match="not an equilibrium"):
        model_energies(parse_model(_model(bond='bond = "(u_next - u)**2/2 + b*u"')))


def test_rest_state_not_a_minimum_names_branch_and_k(tmp_path, monkeypatch):
    monkeypatch.setenv("FLEXMM_CACHE", str(tmp_path))
    check_rest_stable(load_model("klein-gordon", omega0=0.0, C=1.0))  # marginal: allowed
    f = tmp_path / "upside_down.toml"
    f.write_text(KG.replace("omega0**2*u**2/2", "-omega0**2*u**2/2"))
    with pytest.raises(ModelError, match=r"branch 0 has omega\^2 = .* < 0 at k = 0"):
        check_rest_stable(load_model(str(f)))


@pytest.mark.parametrize("params,words", [({"beta": "2"}, "must be a real number"),
                                           ({"beta": True}, "must be a real number"),
                                           ({"beta": math.nan}, "must be finite"),
                                           ({"gamma": 1.0}, "has no parameter 'gamma'")])
def test_parameter_values_checked(params, words):
    with pytest.raises(ModelError, match=words):
        load_model("fput", **params)


def test_unknown_model_lists_the_builtins():
    with pytest.raises(ModelError, match="built-in: .*fput"):
        load_model("fpu")


def test_missing_field_and_file():
    with pytest.raises(ModelError, match="missing key 'fields'"):
        parse_model('name = "t"\n[energy]\nkinetic = "u_t**2/2"\nbond = "0"\n')
    with pytest.raises(ModelError, match="no such model file"):
        load_model("/nonexistent/chain.toml")
    with pytest.raises(ModelError, match="has no velocity"):
        parse_model(_model(kinetic='kinetic = "u_t**2/2 + b*1"'))
    with pytest.raises(ModelError, match="no term for field.*v"):
        parse_model('name = "t"\nfields = ["u", "v"]\n[energy]\nkinetic = "u_t**2/2"\n'
                    'bond = "(u_next - u)**2/2"\n')


def test_user_model_derived_once_and_cached(tmp_path, monkeypatch):
    monkeypatch.setenv("FLEXMM_CACHE", str(tmp_path / "cache"))
    f = tmp_path / "kg.toml"
    f.write_text(KG.replace('name = "klein-gordon"', 'name = "my-kg"'))
    m = load_model(str(f), beta=2.0)
    files = list((tmp_path / "cache").glob("model_*.py"))
    assert len(files) == 1 and m.params["beta"] == 2.0
    r = nls(m, 1.0)
    assert r.g2 == pytest.approx(nls(load_model("klein-gordon", beta=2.0), 1.0).g2, rel=1e-14)


def test_python_lattice_equals_its_file():
    lat = Lattice(name="klein-gordon", fields=("u",),
                  parameters={"C": 1.0, "omega0": 1.0, "alpha": 0.0, "beta": 1.0},
                  kinetic="u_t**2/2", bond="C*(u_next - u)**2/2",
                  site="omega0**2*u**2/2 + alpha*u**3/3 + beta*u**4/4")
    assert lat.content_hash == builtin("klein-gordon").content_hash


@pytest.mark.parametrize("K_theta,k,amplitude", [(0.02151, 0.92991, 0.002),
                                                 (0.01551, 0.81681, 0.004), (0.03, 0.7, 0.009)])
def test_flexmm_soliton_equals_the_paper_chains_prediction(K_theta, k, amplitude):
    # generated/soliton.py (SymPy closed forms, bright/dark, kink of U) against the general
    # soliton of the model's NLS; 1e-9: both are closed forms in double precision
    from numerics import Material
    from numerics.theory import soliton

    mat = Material(2.5 if K_theta != 0.03 else 3.0, 0.01851 if K_theta != 0.03 else 0.05,
                   K_theta)
    want = soliton(mat, "coupled", k, amplitude)
    got = nls(load_model("flexmm", alpha=mat.alpha, K_s=mat.K_s, K_theta=K_theta),
              k).soliton(amplitude)
    assert got.kind == want.kind
    assert got.width == pytest.approx(want.width, rel=1e-9)
    assert got.frequency == pytest.approx(want.frequency, rel=1e-12)
    assert got.kink[1] == pytest.approx(want.kink_height, rel=1e-9)
    assert got.kink[0] == 0  # theta is optical: no kink


def test_with_params_keeps_the_other_values():
    m = load_model("fput", alpha=1.0).with_params(beta=3.0)
    assert dict(m.params) == {"alpha": 1.0, "beta": 3.0}


def test_fput_map_over_k_and_beta_has_the_zone_boundary_line():
    from numerics.models import model_map

    m = load_model("fput", alpha=1.0)
    betas = np.array([1.2, 1.3, 1.37, 1.45])
    ds = model_map(m, ("k", [3.1]), ("beta", betas), 0.1)
    # near k = pi the verdict flips at beta = 4 alpha^2 / 3 (1.333; at k = 3.1, where
    # s^2 = 0.9996, the edge moves by ~1e-3)
    assert list(ds.verdict_semidiscrete.values[:, 0]) == ["stable", "stable", "MI", "MI"]
    assert ds.attrs["param_alpha"] == 1.0


def _flexmm(*argv):
    import json
    import subprocess
    import sys

    proc = subprocess.run([sys.executable, "-m", "cli", *argv], capture_output=True,
                          text=True)
    return proc.returncode, proc.stdout, proc.stderr, (
        json.loads(proc.stdout) if "--json" in argv and proc.returncode == 0 else None)


def test_cli_point_json_per_theory_and_the_fput_flip():
    # at k near pi the semi-discrete verdict flips at 3 beta = 4 alpha^2 (alpha = 1: 1.333)
    for beta, want in ((1.2, "stable"), (1.5, "MI")):
        code, _, err, data = _flexmm("point", "--model", "fput", "--param", "alpha=1",
                                     "--param", f"beta={beta}", "--k", "3.1", "--amplitude",
                                     "0.05", "--json")
        assert code == 0, err
        assert data["semi-discrete NLS"]["verdict"] == want
        assert data["exact lattice"]["verdict"] == want
        # k snapped to the ring point's theories and runs use (N = 500): 2 pi 247 / 500
        assert data["k_requested"] == 3.1 and data["k"] == pytest.approx(2 * math.pi * 247 / 500)
        assert data["parameters"]["beta"] == beta
    code, _, _, data = _flexmm("point", "--model", "flexmm", "--k", "0.81681", "--json")
    assert set(data) >= {"continuum NLS", "semi-discrete NLS"}  # the paper's chain only


def test_cli_model_errors_are_one_line():
    for argv, words in ((("coefficients", "--model", "fput", "--alpha", "2", "--k", "1"),
                         "--param NAME=VALUE"),
                        (("coefficients", "--model", "nope", "--k", "1"), "built-in:"),
                        (("coefficients", "--model", "fput", "--param", "gamma=1", "--k", "1"),
                         "no parameter 'gamma'")):
        code, out, err, _ = _flexmm(*argv)
        assert code == 2 and words in err and len(err.strip().splitlines()) == 1, err


_LIGHT_SITE = """name = "light-site"
fields = ["u", "v"]
[parameters]
m = 0.1
alpha = 0.0
beta = 1.0
kappa = 0.3
lam = 1.0
[energy]
kinetic = "u_t**2/2 + m*v_t**2/2"
bond = "(u_next - u)**2/2 + alpha*(u_next - u)**3/3 + beta*(u_next - u)**4/4"
site = "kappa*(v - u)**2/2 + lam*(v - u)**4/4"
"""


def test_branch_by_index_and_by_field_name_one_field(tmp_path):
    """A light site mass (m = 0.1) on an FPUT chain, no branch field: at k = 1 the lower
    branch's v displacement is the larger (|e_v| 1.26 |e_u|) but u carries 84% of its
    kinetic energy, the weight --branch u names a branch by. --branch 0 and --branch u
    must then be one carrier: the same field measured by a, the same g2 (walkthrough of
    issue 44: they said field v, g2 -5.2 and field u, g2 -7.1 for one branch)."""
    path = tmp_path / "light.toml"
    path.write_text(_LIGHT_SITE)
    rows = {}
    for b in ("0", "1", "u", "v"):
        code, _, err, data = _flexmm("coefficients", "--model", str(path), "--k", "1.0",
                                     "--amplitude", "0.1", "--branch", b, "--json")
        assert code == 0, err
        rows[b] = data
    for index in ("0", "1"):
        field = rows[index]["field"]
        named = rows[field]
        assert named["branch"] == int(index)
        assert named["g2"] == pytest.approx(rows[index]["g2"], rel=1e-12)
        assert "kinetic energy" in rows[index]["field_rule"]
        assert named["field_rule"] == f"--branch {field} names the field"
    assert rows["0"]["field"] == "u" and rows["1"]["field"] == "v"
    # the kinetic shares themselves, from the eigenvector (independent of the rule)
    m = load_model(str(path))
    e = carrier(m, 1.0, 0).e
    assert m.masses[0] * abs(e[0]) ** 2 > m.masses[1] * abs(e[1]) ** 2
    assert abs(e[1]) > abs(e[0])


def test_model_map_counts_nls_bands_no_ring_offset_samples(tmp_path):
    """A model map set the infinite chain's NLS verdict beside the ring's: where the NLS
    band 0 < q < a sqrt(g2/g1) is narrower than the ring's smallest offset 2 pi / N, no
    ring offset samples it. The map counts those cells (walkthrough of issue 44: 78% MI
    semi-discrete against 44% exact, unexplained); the count is checked against the NLS's
    own band edge per cell."""
    N, a = 64, 0.2
    code, _, err, data = _flexmm("map", "--model", "fput", "--param", "alpha=0", "--param",
                                 "beta=1:1.5:2", "--k", "0.2:1.2:2", "--amplitude", str(a),
                                 "--N", str(N), "--theory-only", "--exact", "--workers", "1",
                                 "--out", str(tmp_path / "m"), "--json")
    assert code == 0, err
    u = data["nls_band_unsampled"]
    assert u["ring_smallest_offset"] == pytest.approx(2 * math.pi / N)
    want = 0
    for beta in data["axes"]["beta"]:
        m = load_model("fput", alpha=0.0, beta=beta)
        for k in data["axes"]["k"]:
            r = nls(m, k)
            want += r.verdict == "MI" and r.band_edge(a) <= 2 * math.pi / N
    assert want >= 1  # k = 0.2: the band edge is ~0.07 < 0.098
    assert u["cells"] == want and u["of"] == 4
    assert set(u["ring_not_MI"]) == {"exact", "fourwave"}
    # the store carries it: the count in its attributes, which cells in a variable
    import xarray as xr

    ds = xr.open_zarr(tmp_path / "m" / "map.zarr")
    assert ds.attrs["nls_band_unsampled_cells"] == want
    assert f"{want} of 4 cells" in ds.attrs["nls_band_unsampled_note"]
    flag = ds["nls_band_unsampled"]
    assert int((flag == 1).sum()) == want and not (flag < 0).any()
    assert flag.attrs["ring_not_MI_exact"] == u["ring_not_MI"]["exact"]


def test_point_names_only_bands_the_ring_misses_in_its_own_units(capsys, monkeypatch):
    """At k = pi on 64 sites the ring samples the sidebands (offsets 0.1-0.39); their Hill
    copies near pi - q, between ring offsets, are that mode, not 13 missed bands (as
    point printed before). A band the ring does miss (a weak sine-Gordon wave's, offsets
    below 0.022 on 128 sites) is said in the model's units (/time, not the paper chain's
    /T); past 3 such bands the text gives the fastest 3 and counts the rest; a bad --N is
    named."""
    import json

    import numerics.models
    from cli.app import main as cli

    argv = ["point", "--model", "fput", "--k", "3.14159265", "--N", "64", "--amplitude",
            "0.1", "--json"]
    assert cli(argv) == 0
    res = json.loads(capsys.readouterr().out)
    assert res["exact lattice"]["verdict"] == "MI" and res["ring_misses"] == []
    sg = ["point", "--model", "sine-gordon", "--param", "C=1.901", "--param", "omega0=1.092",
          "--k", "0.335", "--amplitude", "0.05", "--N", "128"]
    assert cli(sg) == 0
    notes = [ln for ln in capsys.readouterr().out.splitlines()
             if ln.startswith("note: the infinite chain grows")]
    assert len(notes) == 1 and "/time in the band of offsets" in notes[0]
    fake = [{"band": (0.1 * i, 0.1 * i + 0.01), "peak_gain": 0.001 * i, "N": 100 + i}
            for i in range(1, 6)]
    monkeypatch.setattr(numerics.models, "ring_misses", lambda *a, **k: fake)
    assert cli(sg) == 0
    out = capsys.readouterr().out
    assert out.count("note: the infinite chain grows") == 3 and "at 0.005 /time" in out
    assert "note: 2 more such bands, growing at up to 0.002 /time" in out
    assert "N = 101 samples one" in out
    assert cli(["point", "--model", "fput", "--k", "1", "--N", "4"]) == 2
    err = capsys.readouterr().err
    assert err.startswith("flexmm: error: --N: N must be an integer in [8, ")


@pytest.mark.parametrize("k", ["0:2:2", "3.2", "0.5,4"])
def test_model_map_names_k_out_of_range(k, tmp_path, capsys):
    """A theory-only map has no ring to snap k on: its --k is still checked, named as the
    option, before anything is written."""
    from cli.app import main as cli

    assert cli(["map", "--model", "fput", "--param", "beta=1:2:2", "--k", k,
                "--theory-only", "--out", str(tmp_path / "m")]) == 2
    err = capsys.readouterr().err
    assert err == f"flexmm: error: --k must be in (0, pi], got {k!r}\n"
    assert not (tmp_path / "m").exists()
