"""What probe 95's new user found with five lattices nobody had tried (bench/probe_newuser95.py
holds the model texts and reruns the probe), each reproduced on its point:

- branches of two linearly uncoupled fields cross (the paper's own chain: theta and U near
  k = 0.78), so branch indices swap between k and k +- q: a pair of the carrier's own
  waves across the crossing was named 'parametric' and the point said the NLS cannot see
  it, where the NLS gives its rate;
- a nearly flat branch put the NLS's band edge at 4.3 rad/site, its fastest offset at 3.06,
  without a word;
- a softening chain's MI drove the run past its barrier and ``point --simulate`` ended in
  an error (from its estimate's probe run), no table, where a map cell said MI.
"""

from __future__ import annotations

import json
import math

import pytest

from bench.probe_newuser95 import MODELS, omega_by_hand
from energy import load_model, parse_model


def _model(name):
    return load_model(parse_model(MODELS[name], f"{name}.toml"))


# ------------------------------------------------ crossing branches
def test_a_pair_across_an_exact_crossing_is_the_carriers_sidebands():
    """cross: u (omega = 2|sin(kappa/2)|) and v (omega = wv = 1) are coupled only by the
    cubic c (u_next - u) v^2, so their branches cross at kappa = pi/3. The u carrier at
    k = 2 pi 20/128 = 0.98 (branch 0) grows through u waves at 1.08 (branch 1: past the
    crossing) and 0.88 (branch 0): its own sidebands, whose NLS rate 0.00157 is the exact
    one (0.00150) to O(a^2). Before, both theories named the pair 'parametric' and the
    point noted that the NLS cannot see it."""
    from numerics.maps import ModelPointSpec, measure_point

    model = _model("cross")
    k, a = 2 * math.pi * 20 / 128, 0.1
    d = measure_point(ModelPointSpec(model, k, a, branch="u", N=128)).as_dict()
    ex, fw, nl = d["exact lattice"], d["four-wave"], d["semi-discrete NLS"]
    assert ex["mode_kind"] == fw["mode_kind"] == "sidebands", (ex, fw)
    # both waves are u waves, by the hand dispersion (not the code's field naming)
    for w in ex["mode_waves"]:
        assert w["frequency"] == pytest.approx(2 * abs(math.sin(w["wavenumber"] / 2)),
                                               abs=0.01)  # the pair's O(a^2) shift: 0.002
    assert {w["branch"] for w in ex["mode_waves"]} == {0, 1}  # across the crossing
    assert not any("not the carrier's sidebands" in n for n in d["notes"]), d["notes"]
    # the NLS's ring rate is the exact one within its O(a^2) error (measured 4.6%)
    assert nl["ring_peak_gain"] == pytest.approx(ex["peak_gain"], rel=0.10)


def test_a_genuinely_other_wave_pair_stays_parametric():
    """cross, carrier on the flat v branch at k = 2 (g1 = 0): the pair the four-wave theory
    rates is of v waves, on the carrier's sheet; a pair with a u wave would be parametric.
    The sheets are (group of linearly coupled fields, rank within it): u and v are two
    groups here, the paper chain's theta and U too, diatomic FPUT's u and v one."""
    from numerics.models import field_groups, four_wave, sheet_pair_kind

    model = _model("cross")
    assert field_groups(model) == (0, 1)
    assert field_groups(load_model("flexmm")) == (0, 1)
    assert field_groups(load_model("diatomic-fput")) == (0, 0)
    # at kappa = 1.5 the u branch (2 sin 0.75 = 1.36) is above v (1): branch 0 is v,
    # branch 1 is u; at kappa = 0.5 (u at 0.49) the other way round
    assert omega_by_hand("cross", model.params, 1.5)[0] == pytest.approx(1.0)
    k = 1.0  # u carrier (branch 0: 0.959 < 1)
    q = 0.5  # k + q = 1.5, k - q = 0.5
    assert sheet_pair_kind(model, k, 0, (1, 0), q) == "sidebands"   # u at both
    assert sheet_pair_kind(model, k, 0, (0, 0), q) == "parametric"  # v at 1.5, u at 0.5
    assert sheet_pair_kind(model, k, 0, (1, 1), q) == "parametric"  # u at 1.5, v at 0.5
    fw = four_wave(model, 2.0, 0.1, "v")
    assert {w["field"] for w in fw.row()["mode_waves"]} == {"v"}
    assert fw.mode_kind in ("sidebands", "backward")


# ------------------------------------------------ a nearly flat branch
def test_an_nls_band_wider_than_half_the_zone_is_warned(tmp_path, capsys):
    """flat-kg (C 1e-3): at k = 2.5 g1 = C cos k / omega - ... = -8.0e-4 and g2 = -3 lambda
    / (2 omega) = -1.497, so the band edge a sqrt(g2/g1) = 4.33 at a = 0.1: past pi/2 (and
    the zone), where the lattice's pairs are backward ones (exact 0.0030, NLS 0.0037). At
    a = 0.03 the edge is 1.30: no warning. The file's name and description are unicode."""
    from cli import main

    path = tmp_path / "flat_\u00dcn\u00efcode.toml"
    path.write_text(MODELS["flat-kg"], encoding="utf-8")
    p = {"C_tiny_2": 1e-3, "Omega_0": 1.0, "lambda_4": 1.0}
    # by hand: omega^2 = Omega0^2 + 2 C (1 - cos k), so omega' = C sin k / omega and
    # g1 = omega'' = (C cos k - omega'^2) / omega (second differences of omega ~ 1 keep
    # only 1e-5 of a g1 ~ 1e-3)
    C, k = p["C_tiny_2"], 2.5
    om = omega_by_hand("flat-kg", p, k)[0]
    g1 = (C * math.cos(k) - (C * math.sin(k) / om) ** 2) / om
    g2 = -1.5 / om
    for a, wide in ((0.1, True), (0.03, False)):
        assert main(["coefficients", "--model", str(path), "--k", "2.5", "--amplitude",
                     str(a), "--json"]) == 0
        co = json.loads(capsys.readouterr().out)
        assert co["band_edge"] == pytest.approx(a * math.sqrt(g2 / g1), rel=1e-6)
        said = [x for x in co["warnings"] if "beyond pi/2" in x]
        assert bool(said) == wide, co["warnings"]


# ------------------------------------------------ a softening chain past its barrier
def test_a_point_whose_run_blows_up_after_growing_still_answers(capsys, tmp_path):
    """soft-pi (r^2/2 + 0.3 r^3/3 - r^4/4) at k = pi, a = 0.3 on 64 sites: the exact
    lattice grows at 0.0630; a full run blows up at t ~ 272, after its sidebands have
    grown (ln(1e8) / 0.063 = 290). The point ended in 'error: the run blew up' (exit 2,
    no table) while a map cell of the same (k, a) said MI at 0.0619. Now the point's runs
    stop where the map cell's do, once the sidebands saturate, with a note."""
    from cli import main
    from numerics.models import map_cells

    path = tmp_path / "soft-pi.toml"
    path.write_text(MODELS["soft-pi"])
    assert main(["point", "--model", str(path), "--k", str(math.pi), "--amplitude", "0.3",
                 "--N", "64", "--simulate", "--seeds", "1", "--json"]) == 0
    d = json.loads(capsys.readouterr().out)
    ex, sim = d["exact lattice"], d["simulated"]
    assert ex["verdict"] == sim["verdict"] == "MI"
    assert sim["peak_gain"] == pytest.approx(ex["peak_gain"], rel=0.10)  # measured -1.8%
    assert "blew up" in sim["note"]
    cell = map_cells(load_model(str(path)), [({}, math.pi)], 0.3, simulate=True, N=64)[0]
    assert cell["verdict_simulated"] == "MI"
    assert cell["peak_gain_simulated"] == pytest.approx(sim["peak_gain"], rel=1e-9)


# ------------------------------------------------ names a new user tries
def test_a_unicode_bare_key_is_named_in_the_toml_error(tmp_path, capsys):
    """``ω0 = 1.0`` is no TOML (a bare key is ASCII); the error said only 'Invalid
    statement (at line 4, column 1)'. Now it names the key and the remedy; the quoted key
    ``"ω0"`` reaches the name check, which says the same. The flat-kg file's unicode and
    quotes in its description, its integer parameter and its odd names load as they are."""
    from cli import main

    text = MODELS["flat-kg"].replace("Omega_0", "\u03a90")
    path = tmp_path / "bare.toml"
    path.write_text(text, encoding="utf-8")
    assert main(["coefficients", "--model", str(path), "--k", "1", "--amplitude", "0.1"]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "not valid TOML" in err[0]
    assert "'\u03a90' is not ASCII" in err[0] and "spell a Greek letter out" in err[0], err
    lat = parse_model(MODELS["flat-kg"], "flat.toml")
    assert lat.parameters == {"C_tiny_2": 1e-3, "Omega_0": 1.0, "lambda_4": 1}
    assert "\u03c9 \u2248 \u03a9\u2080" in lat.description and '"almost no"' in lat.description


def test_a_map_of_a_flat_branch_points_to_the_exact_theory(tmp_path, capsys):
    """cross's v branch is flat (omega = wv at every k: g1 = 0), so no cell has an NLS
    verdict and a --theory-only map is refused; the exact lattice and four-wave theories
    have verdicts there (exact MI at k = 2 pi 15/64 for both c), which the message did not
    say: it offered only other axes, k, amplitudes or branches."""
    from cli import main

    path = tmp_path / "cross.toml"
    path.write_text(MODELS["cross"])
    argv = ["map", "--model", str(path), "--branch", "v", "--param", "c=0.2,0.5", "--k",
            "1.5,2.5", "--amplitude", "0.1", "--theory-only", "--workers", "1", "--N", "64",
            "--out", str(tmp_path / "m")]
    assert main(argv) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "every cell of the map is undefined" in err[0], err
    assert "add --exact" in err[0]
    assert main([*argv, "--exact"]) == 0
    import xarray as xr

    ds = xr.open_zarr(tmp_path / "m" / "map.zarr")
    assert (ds["verdict_semidiscrete"].values == -1).all()
    assert ds["verdict_exact"].values[:, 0].tolist() == [1, 1]


def test_a_parameter_named_k_is_not_swept_as_the_carrier(tmp_path, capsys):
    """A model whose parameter is named k (valid, as E, N or amplitude are): ``map --param
    k=0.3,0.6 --amplitude 0.1,0.2 --k 1`` swept the carrier over 0.3, 0.6 (g1 0.84 and
    0.51: the carrier's dispersion, by hand (C cos k w^2 - C^2 sin^2 k) / w^3 = 0.838 at
    0.3) at the parameter's default, and ignored --k 1; with --k 1,2 it said the two axes
    'must differ'. Now both are refused in one line, as a parameter named amplitude is;
    the Python model_map too."""
    from cli import main
    from numerics.models import model_map

    text = MODELS["fk-cubic"].replace("w0", "k")
    path = tmp_path / "pk.toml"
    path.write_text(text)
    for axes in (["--param", "k=0.3,0.6", "--amplitude", "0.1,0.2", "--k", "1"],
                 ["--param", "k=0.3,0.6", "--k", "1,2", "--amplitude", "0.1"]):
        assert main(["map", "--model", str(path), *axes, "--theory-only", "--workers", "1",
                     "--out", str(tmp_path / "m")]) == 2
        err = capsys.readouterr().err.strip().splitlines()
        assert len(err) == 1 and "map axis 'k' is ambiguous" in err[0], err
        assert not (tmp_path / "m").exists()
    from energy import ModelError

    with pytest.raises(ModelError, match="ambiguous"):
        model_map(load_model(str(path)), ("k", [0.3, 0.6]), ("alpha", [0.1, 0.2]), 0.1)
    # a fixed carrier with the parameter k on no axis still maps
    assert main(["map", "--model", str(path), "--param", "alpha=0.1,0.2", "--param",
                 "beta=0.3,0.4", "--k", "1", "--amplitude", "0.1", "--theory-only",
                 "--workers", "1", "--out", str(tmp_path / "ok")]) == 0


@pytest.mark.parametrize("c", [0.2, 0.5, 0.8])
def test_the_exact_theory_is_mathieus_rate_for_the_flat_oscillators_decay(c):
    """cross at k = 2 pi 29/64 (u at 1.98 ~ 2 wv): the bond term c (u_next - u) v^2 makes
    each site's v a Mathieu oscillator, v'' + (wv^2 - 4 c a s sin(phi_n - Omega t)) v = 0
    (s = sin(k/2)), pumped at the carrier's Omega = 2 s + 3 b s^3 a^2 (its own quartic
    shift, by hand): rate sqrt((c a s / wv)^2 - (Omega/2 - wv)^2), the same at every q
    (v is flat). The exact Hill theory of the ring gives it within 1% (measured 0.05%,
    0.03%, 0.2%; the Mathieu rate's next order is (h/4)^2 ~ 0.6% at h = 4 c a s / wv^2
    = 0.32), and the four-wave theory says it is a three-wave decay it does not rate."""
    from numerics.models import exact_gain, four_wave

    model = _model("cross").with_params(c=c)
    k, a = 2 * math.pi * 29 / 64, 0.1
    s, b, wv = math.sin(k / 2), model.params["b"], model.params["wv"]
    Omega = 2 * s + 3 * b * s**3 * a**2
    want = math.sqrt((c * a * s / wv) ** 2 - (Omega / 2 - wv) ** 2)
    ex = exact_gain(model, k, a, "u", N=64)
    assert ex.peak_gain == pytest.approx(want, rel=0.01)
    assert ex.wave.omega == pytest.approx(Omega, rel=1e-4)  # O(a^4) beyond: 2e-5 measured
    fw = four_wave(model, k, a, "u", N=64)
    assert fw.verdict == "undefined" and "three-wave decay" in fw.undefined


def test_a_pair_wave_at_zero_wavenumber_is_not_minus_zero():
    """flat-kg at k = pi/2 (a = 0.05, 64 sites): the fastest four-wave pair is at k + q =
    pi and k - q = 0, which the point printed as 'branch 0 (q_1) at -0' (the wrap of
    k - q gave -0.0, and the JSON held -0.0)."""
    from numerics.models import four_wave

    fw = four_wave(_model("flat-kg"), math.pi / 2, 0.05, N=64)
    waves = [w["wavenumber"] for w in fw.row()["mode_waves"]]
    assert 0.0 in waves and all(math.copysign(1.0, w) > 0 for w in waves if w == 0), waves
    assert "-0" not in json.dumps(fw.row()["mode_waves"])


# ------------------------------------------------ losses across a crossing
def test_a_sideband_past_an_uncoupled_crossing_is_damped_as_its_own_field():
    """flexmm-lossy: theta and U are linearly uncoupled and cross near k = 0.78; on the
    theta sheet the damping is gamma_theta alpha^2 / 2 everywhere (pure rotation), U's is
    25x smaller at gamma_theta = gamma_U. The sidebands' damping took the carrier's branch
    index at k +- q, so a theta sideband past the crossing was damped at U's rate:

    - the damped NLS at k = 1 (rates a^2 f(q/a), one damping on the whole sheet) must give
      one amplification for one a^2 / gamma_theta, at times 4x apart for a 2x a: a 0.05,
      gammas 5e-4, against a 0.1, gamma_theta 2e-3, gamma_U 0 gave 4.79 and 4.88 (U's
      damping, different in the two), now equal to round-off;
    - the exact theory at the paper's blue point (gamma 1e-4) said 2165x, twice the
      four-wave theory's 1030x, which damps each pair's own two waves; now 1030 both."""
    from numerics.models import (
        exact_amplification,
        four_wave_amplification,
        nls_amplification,
        sheet_branches,
    )

    m = load_model("flexmm-lossy")
    assert sheet_branches(m, 0.81681, 0, [0.07, 1.55]).tolist() == [1, 0]  # theta's
    one = nls_amplification(load_model("flexmm-lossy", gamma_theta=5e-4, gamma_U=5e-4),
                            1.0, 0.05)
    two = nls_amplification(load_model("flexmm-lossy", gamma_theta=2e-3, gamma_U=0.0),
                            1.0, 0.1)
    assert one.amplification == pytest.approx(two.amplification, rel=1e-9)  # measured 1e-15
    assert one.amplification_time == pytest.approx(4 * two.amplification_time, rel=1e-9)
    blue = load_model("flexmm-lossy", gamma_theta=1e-4, gamma_U=1e-4)
    ex = exact_amplification(blue, 0.81681, 0.028, N=256)
    fw = four_wave_amplification(blue, 0.81681, 0.028, N=256)
    # the four-wave rates are O(a^2) accurate (the lossless blue point: 0.0065 against the
    # exact 0.0055); along the decaying carrier the two agree to 0.1% here, bar 10%
    assert ex.amplification == pytest.approx(fw.amplification, rel=0.10)


def test_a_lossy_run_that_never_passes_its_noise_floor_says_so():
    """lossy-res (gr 5e-4) at k 1.18, a 0.2 on 64 sites: the exact theory's sidebands grow
    9.6x along the decaying carrier (peak at t ~ 1300), the run printed 'the sidebands grew
    1x by t = 0': A(t) is measured from the largest of 64 noisy modes, ~25x above the
    growing one's own start (the lossless run at the same point: 414x measured where its
    rate gives 1.0e4x), so it never passed A(0). The row now says that 1x is no
    measurement; a run that did pass it (gr 1e-3 at k 0.98: 1.67x at t 161) has no such
    note."""
    from numerics.maps import ModelPointSpec, measure_point

    model = _model("lossy-res")
    d = measure_point(ModelPointSpec(model.with_params(gr=5e-4), 1.2, 0.2, N=64,
                                     simulate=True, seeds=1)).as_dict()
    ex, sim = d["exact lattice"], d["simulated"]
    assert ex["amplification"] > 5 and sim["amplification"] == pytest.approx(1.0)
    assert "never passed A(0)" in sim.get("note", ""), sim
    d = measure_point(ModelPointSpec(model.with_params(gr=1e-3), 1.0, 0.2, N=64,
                                     simulate=True, seeds=1)).as_dict()
    assert d["simulated"]["amplification"] > 1.2
    assert "never passed A(0)" not in d["simulated"].get("note", "")


def test_fk_cubic_is_even_under_u_to_minus_u_with_alpha_to_minus_alpha():
    """The fk-cubic energy is unchanged by u -> -u together with alpha -> -alpha (the
    on-site 1 - cos u and the quartic bond are even), so every theory's rate is even in
    alpha: the NLS's g2 (its alpha enters as alpha^2 through the second harmonic) and the
    exact ring's peak rate, to round-off (measured 4e-15 for the exact one)."""
    from numerics.models import exact_gain, model_coefficients

    plus, minus = (_model("fk-cubic").with_params(alpha=s * 0.6) for s in (1, -1))
    k = 2 * math.pi * 20 / 64
    assert model_coefficients(plus, k, 0.15)["g2"] == pytest.approx(
        model_coefficients(minus, k, 0.15)["g2"], rel=1e-12)
    assert exact_gain(plus, k, 0.15, N=64).peak_gain == pytest.approx(
        exact_gain(minus, k, 0.15, N=64).peak_gain, rel=1e-9)
