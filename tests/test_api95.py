"""The public Python API as a notebook uses it (session api95): arguments a scientist may
pass by mistake get a one-line error naming them, and what the functions return is checked
against forms derived here by hand, not read from the code under test."""

from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np
import pytest

import energy
import numerics.models as nm
from energy import ModelError

ROOT = Path(__file__).resolve().parents[1]


@pytest.fixture(scope="module")
def fput():
    return energy.load_model("fput")


@pytest.fixture(scope="module")
def fput_wave(fput):
    # a = 0.05 at k = 2: weakly nonlinear (shift 3 a^2 sin^3(1) / omega ~ 4e-3)
    return nm.travelling_wave(fput, 2.0, 0.05)


def beta_fput_nls(k, a, beta=1.0):
    """The beta-FPUT chain's NLS by hand. u = a cos(k n - omega t) in the bond force
    V'(r) = r + beta r^3 (strain amplitude r = 2 a sin(k/2)) gives omega_nl^2 = omega^2
    (1 + 3 beta a^2 sin^2(k/2)), so the shift is 3 beta a^2 sin^3(k/2) = -g2 a^2 / 4, i.e.
    g2 = -12 beta sin^3(k/2); g1 = omega'' = -sin(k/2)/2. MI (g1 g2 > 0) at the fastest
    offset q_m = (a/2) sqrt(2 g2 / g1) grows at |g2| a^2 / 4."""
    s = math.sin(k / 2)
    g1, g2 = -s / 2, -12 * beta * s**3
    return g1, g2, a / 2 * math.sqrt(2 * g2 / g1), abs(g2) * a**2 / 4


@pytest.mark.parametrize("bad", [0, -1, 1.5, True, "8"])
def test_travelling_wave_refuses_a_bad_truncation(fput, bad):
    # before: 0 was read as the default 8 silently, -1 and 1.5 failed inside numpy
    with pytest.raises(ModelError, match="harmonics must be an integer >= 1"):
        nm.travelling_wave(fput, 2.0, 0.05, harmonics=bad)


@pytest.mark.parametrize("bad", ["abc", None, 1j, [0.1]])
def test_travelling_wave_names_a_bad_amplitude(fput, bad):
    # before: float(amplitude) raised ValueError/TypeError without the argument's name
    with pytest.raises(ModelError, match="amplitude must be a real number"):
        nm.travelling_wave(fput, 2.0, bad)


def test_travelling_wave_refuses_a_start_that_is_no_wave(fput):
    # before: AttributeError 'int' object has no attribute 'coefficients'
    with pytest.raises(ModelError, match="start must be a TravellingWave"):
        nm.travelling_wave(fput, 2.0, 0.05, start=3)


@pytest.mark.parametrize("bad", [0, 1, 2, 3, -1, True, 4.0])
def test_hill_spectrum_refuses_a_truncation_that_resolves_no_sideband(fput_wave, bad):
    # before: P <= 3 returned gain 0 (stable) on every wave: the outer three harmonics,
    # where a kept mode must hold < 1e-6 of its weight, then include l = +-1
    with pytest.raises(ModelError, match="harmonics must be an integer >= 4"):
        nm.hill_spectrum(fput_wave, [0.1], harmonics=bad)


def test_hill_spectrum_at_the_smallest_truncation_is_the_nls_rate(fput_wave):
    g1, g2, q_m, peak = beta_fput_nls(2.0, 0.05)
    default = nm.hill_spectrum(fput_wave, [q_m]).gain[0]
    for P in (4, 6):
        got = nm.hill_spectrum(fput_wave, [q_m], harmonics=P).gain[0]
        # the same Hill spectrum at another truncation: equal to the eigensolver's round-off
        assert got == pytest.approx(default, rel=1e-9)
    # the exact rate tends to the NLS's with a relative error O(a^2) (measured 0.9% at
    # a = 0.05; 3.5% at a = 0.1): 2% allows the NLS's next order, not a wrong rate
    assert default == pytest.approx(peak, rel=0.02)


def test_hill_spectrum_says_offsets_must_be_one_dimensional(fput_wave):
    # before: "offsets must be finite real numbers" for a finite 2-D array
    with pytest.raises(ModelError, match="1-D array.*shape \\(2, 2\\)"):
        nm.hill_spectrum(fput_wave, np.full((2, 2), 0.1))


def test_load_model_reads_a_model_files_text(fput):
    # before: the text was taken for a path (it holds '/'): "<whole text>: no such model file"
    text = (ROOT / "energy" / "models" / "fput.toml").read_text()
    m = energy.load_model(text, beta=2.0)
    assert m.params == {"alpha": 0.0, "beta": 2.0}
    g1, g2, _, _ = beta_fput_nls(1.3, 0.05, beta=2.0)
    n = nm.nls(m, 1.3)
    # carrier and g2 by perturbation theory against the closed forms: round-off
    assert n.carrier.g1 == pytest.approx(g1, rel=1e-9)
    assert n.g2 == pytest.approx(g2, rel=1e-9)
    with pytest.raises(ModelError, match="model text: not valid TOML"):
        energy.load_model('name = "x"\nfields = [')


def _numpy_leaves(x, path=""):
    if isinstance(x, dict):
        return [p for k, v in x.items() for p in _numpy_leaves(v, f"{path}.{k}")]
    if isinstance(x, list):
        return [p for i, v in enumerate(x) for p in _numpy_leaves(v, f"{path}[{i}]")]
    return [path] if type(x).__module__ == "numpy" else []


@pytest.mark.parametrize("name", ["flexmm", "diatomic-fput", "flexmm-lossy"])
def test_model_coefficients_holds_plain_python_numbers(name):
    # before: g1 and the second harmonic of a model of several fields were numpy.float64
    d = nm.model_coefficients(energy.load_model(name), 1.0, 0.05)
    assert _numpy_leaves(d) == []
    assert type(d["g1"]) is float and type(d["group_velocity"]) is float
    assert json.loads(json.dumps(d, allow_nan=False)) == d


@pytest.mark.parametrize("module", ["coefficients", "lattice_coefficients"])
def test_band_edge_and_fastest_offset_are_even_in_the_amplitude(module):
    # before: 2 A0 sqrt(g) printed as typed gave K_c = -20 at A0 = -1 (g = 100): B -> -B
    # is a symmetry of the NLS, and eq. `kc` is |K_c| = 2 A0 sqrt(g) for A0 > 0
    import importlib

    co = importlib.import_module(f"generated.{module}")
    g, A0 = np.array([100.0, 3.0]), np.array([-1.0, -0.25])
    Kc, Km = co.mi_cutoff(g, A0), co.mi_fastest(g, A0)
    # by hand: Omega_I(K)^2 = K^2 (g A0^2 - K^2 / 4) vanishes at K^2 = 4 g A0^2 and peaks
    # at K^2 = 2 g A0^2, with Omega_I = g A0^2 there
    np.testing.assert_allclose(Kc, 2 * np.abs(A0) * np.sqrt(g), rtol=1e-15)
    np.testing.assert_allclose(Km, np.sqrt(2 * g) * np.abs(A0), rtol=1e-15)
    np.testing.assert_array_equal(Kc, co.mi_cutoff(g, -A0))
    np.testing.assert_allclose(co.mi_growth_rate(Km, g, A0), g * A0**2, rtol=1e-14)
    assert np.all(co.mi_growth_rate(Kc * (1 + 1e-12), g, A0) == 0)


@pytest.mark.parametrize("module", ["energy._model", "numerics.theory._response",
                                    "numerics.theory._launched", "numerics.theory._soliton",
                                    "numerics.maps._params", "numerics.maps._model_params",
                                    "numerics.lattice._simulate"])
def test_docstring_examples_run_as_written(module):
    # the modules whose public docstrings hold >>> examples (grep); before: launched_state's
    # example called s.mode("U", 2, t) with t undefined (NameError)
    import doctest
    import importlib

    result = doctest.testmod(importlib.import_module(module), verbose=False)
    assert result.attempted > 0 and result.failed == 0


UNSTABLE_REST = """name = "soft"
fields = ["u"]
[parameters]
b = 1.0
[energy]
kinetic = "u_t**2/2"
bond = "-(u_next - u)**2/2 + b*(u_next - u)**4/4"
site = "u**2"
"""


def test_a_lattice_unstable_at_rest_gets_no_nls_verdict():
    # by hand: omega^2(kappa) = 2 - 4 sin^2(kappa/2), < 0 beyond pi/2, down to -2 at pi:
    # the rest state itself grows at up to sqrt(2). Before: model_coefficients said "MI"
    # with the NLS's 7.6e-4 and no warning, and classify_mode of the exact spectrum raised
    # numpy's "All-NaN slice encountered" (branches are NaN where omega^2 < 0)
    m = energy.load_model(UNSTABLE_REST)
    assert 1.0 < math.pi / 2  # the carrier itself is a real wave
    assert nm.carrier(m, 1.0).omega == pytest.approx(math.sqrt(2 - 4 * math.sin(0.5)**2),
                                                      rel=1e-12)
    d = nm.model_coefficients(m, 1.0, 0.05)
    assert d["verdict"] == "undefined" and "not a minimum" in d["reason"]
    assert d["peak_gain"] is None and d["g2"] is not None
    spec = nm.exact_gain(m, 1.0, 0.05)
    # the exact theory sees the rest state's growth: sqrt(2) moved by the carrier's O(a^2)
    # (0.35% measured at a = 0.05)
    assert spec.peak_gain == pytest.approx(math.sqrt(2), rel=0.01)
    assert nm.classify_mode(spec)["mode_kind"] == "resonance"


def test_derivation_takes_a_model_by_name_model_or_text():
    # before: model_energies("fput"), model_energies(load_model("fput")),
    # equations_of_motion("fput") and model_module_text("fput") raised AttributeError
    import sympy as sp

    import derivation

    text = (ROOT / "energy" / "models" / "fput.toml").read_text()
    u, up, un, a, b = sp.symbols("u u_prev u_next alpha beta")

    def dV(r):  # the bond force V'(r) = r + alpha r^2 + beta r^3, by hand
        return r + a * r**2 + b * r**3

    hand = dV(un - u) - dV(u - up)  # u'' = V'(u_next - u) - V'(u - u_prev)
    for given in ("fput", energy.load_model("fput"), text):
        (acc,) = derivation.equations_of_motion(given)
        by_name = {str(x): x for x in acc.free_symbols}
        ours = hand.subs({x: by_name[str(x)] for x in (u, up, un, a, b)},
                         simultaneous=True)
        assert sp.expand(acc - ours) == 0
    assert derivation.model_module_text("fput") == derivation.model_module_text(
        energy.builtin("fput"))
    with pytest.raises(ModelError, match="model must be an energy.Lattice"):
        derivation.model_energies(3)


HALF_POWER = """name = "half-power"
fields = ["u"]
[energy]
kinetic = "u_t**2/2"
bond = "(u_next - u)**2/2 + (u_next - u)**2.5"
"""


def _within(seconds, f):
    """f(), or a failure after ``seconds`` (the old tree looped forever)."""
    import signal

    def stop(*_):
        raise TimeoutError(f"no answer within {seconds} s")

    old = signal.signal(signal.SIGALRM, stop)
    signal.alarm(seconds)
    try:
        return f()
    finally:
        signal.alarm(0)
        signal.signal(signal.SIGALRM, old)


def test_a_model_real_at_no_amplitude_is_said_not_looped_on():
    # r**(5/2) is real only for r >= 0 and every wave has r < 0 somewhere, so no amplitude
    # has a real energy (by hand). Before: amplitude_reach's bisection never ended (hi
    # underflowed to 5e-324, mid rounded to 0), and model_coefficients with it (> 13 min)
    m = energy.load_model(HALF_POWER)
    assert _within(60, lambda: nm.amplitude_reach(m, 1.0, 0.05)) == 0.0
    why = _within(60, lambda: nm.energy_not_real(m, 1.0, 0.05))
    assert "no amplitude tried had a real energy" in why
    d = _within(60, lambda: nm.model_coefficients(m, 1.0, 0.05))
    assert d["verdict"] == "undefined" and d["peak_gain"] is None


ABS_CUBE = """name = "abs-cube"
fields = ["u"]
[energy]
kinetic = "u_t**2/2"
bond = "(u_next - u)**2/2 + Abs(u_next - u)**3"
"""


def test_an_abs_cube_nonlinearity_gets_no_cubic_nls():
    # V(r) = r^2/2 + |r|^3: the force r + 3 r|r| on a strain r = R cos(phi), R = 2 a sin(k/2),
    # has the first harmonic R + 3 R^2 (1/pi) int |cos|^3 = R (1 + 8 R / pi) (by hand), so
    # omega_nl = omega (1 + 4 R / pi): a shift 16 a sin^2(k/2) / pi, linear in a. Before:
    # the Taylor tensors at rest (third derivative 0 there) gave g2 = 0 and "stable",
    # while the exact theory finds MI (rate 0.033 at a = 0.02, k = 2)
    m = energy.load_model(ABS_CUBE)
    k = 2.0
    n = nm.nls(m, k)
    assert n.verdict == "undefined" and "third derivatives jump" in n.undefined
    assert nm.model_coefficients(m, k, 0.02)["verdict"] == "undefined"
    a = 0.005
    shift = nm.travelling_wave(m, k, a).omega - nm.carrier(m, k).omega
    # next order O(R) relative: 4 R / pi = 0.9% at a = 0.005; 3% allows it
    assert shift == pytest.approx(16 * a * math.sin(k / 2)**2 / math.pi, rel=0.03)
    assert nm.exact_gain(m, k, 0.02).peak_gain > 0.01
    # the four-wave kernel reads the same tensors: before, 'stable' with gain 0
    fw = nm.four_wave(m, k, 0.02)
    assert fw.verdict == "undefined" and "third derivatives jump" in fw.undefined


@pytest.mark.parametrize("name", sorted(energy.BUILTIN))
def test_smooth_builtin_models_keep_their_nls(name):
    # the jump test must not fire on a smooth energy (a false "undefined" would hide MI)
    m = energy.load_model(name)
    for k in (0.5, 1.0, 2.0, 3.1):
        assert "third derivatives jump" not in nm.nls(m, k).undefined


def test_ring_soliton_names_the_kinds_for_an_unknown_one(fput):
    # before: "kind grey: the NLS at k = 2 has g = 16.99 (> 0), so only bright solitons"
    with pytest.raises(ModelError, match="kind must be one of .*'grey'"):
        nm.ring_soliton(fput, 2.0, 0.1, kind="grey")
    with pytest.raises(ModelError, match="so only bright solitons"):
        nm.ring_soliton(fput, 2.0, 0.1, kind="dark")  # g = 24 sin^2(1) > 0: focusing


def test_saturation_time_is_never_negative():
    # ln(SATURATION / noise) / rate: two noises differ by ln(n2 / n1) / rate (by hand)
    t1, t2 = nm.saturation_time(0.01, noise=1e-8), nm.saturation_time(0.01, noise=1e-6)
    assert t1 - t2 == pytest.approx(math.log(100) / 0.01, rel=1e-12)
    # noise of twice the amplitude is past any saturation share: no time to wait
    assert nm.saturation_time(0.01, noise=2.0) == 0.0  # before: -299.6
    assert nm.saturation_time(0.0) == math.inf


def test_with_energy_names_a_key_it_cannot_replace():
    lat = energy.builtin("klein-gordon")
    # before: TypeError "Lattice.__init__() got an unexpected keyword argument 'sit'"
    with pytest.raises(ModelError, match="cannot replace sit .*site"):
        lat.with_energy(sit="u**2/2")
    # and a replacement that works: C = 0 leaves omega = omega0 on every k (by hand)
    m = energy.load_model(lat.with_energy(bond="0*(u_next - u)**2"), omega0=1.5)
    assert nm.carrier(m, 2.0).omega == pytest.approx(1.5, rel=1e-12)


def test_nls_summary_gives_no_stability_where_g_is_undefined():
    from numerics import Material, nls_summary

    # delta = 0: C1 = alpha^2 delta = 0 and v_g = C1 k / omega = 0, so g1 = 0 (eq. g_i by
    # hand) and g = g2/g1 does not exist. Before: "stable": False, read as unstable
    s = nls_summary(Material(2.5, 0.02, 0.02), "coupled", 0.8, amplitude=0.02)
    assert s["g1"] == 0.0 and math.isnan(s["g"]) and "g1 = 0" in s["undefined"]
    assert s["stable"] is None
    blue = nls_summary(Material.paper("blue"), "coupled", 0.81681, amplitude=0.02)
    assert blue["stable"] is False and blue["g"] > 0  # the paper's MI point keeps its verdict


def test_model_map_refuses_k_given_twice(fput):
    # before: k = 1.0 beside a 'k' axis was dropped without a word
    with pytest.raises(ModelError, match="k = 1 given and 'k' is a map axis"):
        nm.model_map(fput, ("k", [0.5]), ("beta", [1.0]), 0.05, k=1.0)
    # before: "needs finite values" for a finite 2-D list
    with pytest.raises(ModelError, match="1-D list of values, got an array of shape \\(1, 2\\)"):
        nm.model_map(fput, ("k", [[0.5, 1.0]]), ("beta", [1.0]), 0.05)
    ds = nm.model_map(fput, ("k", [0.5, 2.0]), ("beta", [0.5, 1.0]), 0.05)
    # beta-FPUT NLS rate 3 beta a^2 sin^3(k/2) by hand (beta_fput_nls): the map's cells
    want = [[beta_fput_nls(k, 0.05, beta)[3] for k in (0.5, 2.0)] for beta in (0.5, 1.0)]
    np.testing.assert_allclose(ds["peak_gain_semidiscrete"].values, want, rtol=1e-9)


def test_simulate_model_refuses_a_wave_of_another_point(fput):
    # before: a wave of another amplitude, model or k was run silently, from its own
    # state (a k = 2 wave on a 32-site ring that carries k = 1.9635 only: not periodic)
    N = 32
    kr = nm.snap_ring(2.0, N)[0]
    assert kr == pytest.approx(2 * math.pi * 10 / N)  # 2 pi m / N, m = 10 (by hand)
    right = nm.travelling_wave(fput, kr, 0.1)
    for wave, words in ((nm.travelling_wave(fput, kr, 0.2), "amplitude 0.1 \\(wave: 0.2\\)"),
                        (nm.travelling_wave(fput, 2.0, 0.1), "k on the ring"),
                        (nm.travelling_wave(fput.with_params(beta=2.0), kr, 0.1), "model"),
                        (3, "wave must be a TravellingWave")):
        with pytest.raises(ModelError, match=words):
            nm.simulate_model(fput, 2.0, 0.1, N=N, t_end=10.0, wave=wave)
    run = nm.simulate_model(fput, 2.0, 0.1, N=N, t_end=10.0, wave=right, records=2)
    e = run.energy  # symplectic step: energy kept to round-off over 10 time units
    assert abs(e[-1] - e[0]) < 1e-12 * abs(e[0])


def test_lossy_amplification_checks_its_sampling_options():
    m = energy.load_model("flexmm-lossy")
    # the carrier's decay rate by hand: R = gamma theta_t^2/2 on a mass 1/alpha^2 damps the
    # amplitude at gamma alpha^2 / 2 = 0.001 * 6.25 / 2
    assert nm.carrier_damping(m, 1.0) == pytest.approx(0.001 * 2.5**2 / 2, rel=1e-12)
    # before: ZeroDivisionError (offsets, steps = 0), 'math domain error' (ratio -1),
    # 'amplitude must be > 0' (ratio 0), most = 0 accepted
    for kw, words in ((dict(offsets=0), "offsets must be an integer >= 1"),
                      (dict(steps=0), "steps must be an integer >= 1")):
        with pytest.raises(ModelError, match=words):
            nm.nls_amplification(m, 1.0, 0.05, **kw)
    for kw, words in ((dict(ratio=-1.0), "ratio .* must be in \\(0, 1\\)"),
                      (dict(ratio=0.0), "ratio"), (dict(ratio=2.0), "ratio"),
                      (dict(most=0), "most must be an integer >= 1")):
        for f in (nm.exact_amplification, nm.four_wave_amplification):
            with pytest.raises(ModelError, match=words):
                f(m, 1.0, 0.05, **kw)


def test_lattice_force_and_energy_refuse_a_state_of_the_wrong_shape(fput):
    u = np.array([[0.1, -0.2, 0.05, 0.3, -0.1]])
    # by hand: F_n = V'(r_n) - V'(r_{n-1}), r_n = u_{n+1} - u_n on the ring, V'(r) = r + r^3
    r = np.roll(u, -1, axis=1) - u
    np.testing.assert_allclose(nm.lattice_force(fput, u), (r + r**3) - np.roll(r + r**3, 1, 1),
                               rtol=1e-13, atol=1e-16)
    assert nm.lattice_energy(fput, u, 0 * u) == pytest.approx(np.sum(r**2 / 2 + r**4 / 4),
                                                                rel=1e-13)
    # before: a (1, N) state of the two-field flexmm returned NaN forces after reading and
    # writing past the array (a segmentation fault or LLVM assertion later in the
    # process); a 1-D state raised IndexError; u and v of different N read past v
    flexmm = energy.load_model("flexmm")
    with pytest.raises(ModelError, match="shape \\(d, N\\) = \\(2, N >= 3\\).*\\(1, 5\\)"):
        nm.lattice_force(flexmm, u)
    with pytest.raises(ModelError, match="got shape \\(5,\\)"):
        nm.lattice_force(fput, u[0])
    with pytest.raises(ModelError, match="same shape"):
        nm.lattice_energy(fput, u, np.zeros((1, 3)))
    with pytest.raises(ModelError, match="real numbers"):
        nm.lattice_force(fput, u + 0j)


def test_simulate_model_names_an_initial_state_of_the_wrong_shape(fput):
    # before: numpy's "cannot reshape array of size 64 into shape (1,32)"
    with pytest.raises(ModelError, match="initial must be a pair \\(u, v\\), each of shape "
                                         "\\(d, N\\) = \\(1, 32\\)"):
        nm.simulate_model(fput, 2.0, 0.1, N=32, t_end=5.0,
                          initial=(np.zeros((2, 32)), np.zeros((2, 32))))
    # the rest state stays at rest: energy 0 (noise 0)
    run = nm.simulate_model(fput, 2.0, 0.1, N=32, t_end=5.0, records=2, noise=0.0,
                            initial=(np.zeros((1, 32)), np.zeros((1, 32))))
    assert np.all(run.energy == 0.0)


def test_simulated_verdict_and_run_length_check_their_arguments():
    from numerics.lattice import run_length, simulated_verdict

    # the rule as documented: most seeds past 20x is MI, a median below sqrt(20) no growth
    assert simulated_verdict([100.0, 100.0, 1.0], 1000.0).word == "MI"
    assert simulated_verdict([1.0], 1000.0).word == "no growth within T"
    assert simulated_verdict([10.0], 1000.0).word == "undetermined"
    # before: "MI (grew 100x within T = -1)", "math domain error", "'float' object is not
    # iterable", "no growth" for a negative factor, and run_length(cap=-1) gave T = -1
    with pytest.raises(ValueError, match="t_end must be finite and > 0"):
        simulated_verdict([100.0], -1.0)
    with pytest.raises(ValueError, match="threshold must be in \\(1, inf\\)"):
        simulated_verdict([2.0], 100.0, threshold=0.0)
    with pytest.raises(TypeError, match="growth must be a sequence"):
        simulated_verdict(100.0, 100.0)
    with pytest.raises(ValueError, match="amplitude ratios"):
        simulated_verdict([-5.0], 100.0)
    with pytest.raises(ValueError, match="cap must be finite and > 0"):
        run_length(0.01, cap=-1.0)


def test_a_spec_or_wave_of_the_same_model_from_its_file_is_accepted(fput):
    # before: the built-in fput and energy/models/fput.toml differ only in Lattice.source,
    # and simulate_seeds refused the spec as "model fput (...) (spec: fput (...))"
    same = energy.load_model(str(ROOT / "energy" / "models" / "fput.toml"))
    assert same.lattice.source != fput.lattice.source
    spec = nm.exact_gain(fput, 2.0, 0.1, N=32)
    runs = nm.simulate_seeds(same, 2.0, 0.1, spec, N=32, seeds=1, t_end=20.0)
    assert len(runs.runs) == 1 and runs.t_end == 20.0
    nm.simulate_model(same, 2.0, 0.1, N=32, t_end=5.0, wave=spec.wave, records=2)
    with pytest.raises(ModelError, match="model"):  # another beta is another model
        nm.simulate_seeds(fput.with_params(beta=2.0), 2.0, 0.1, spec, N=32, t_end=20.0)
