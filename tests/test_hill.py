"""Exact lattice plane waves (harmonic balance) and their stability (Hill's method)."""

import numpy as np
import pytest

from common import paper
from numerics import LatticeState, Material, integrate, mi_gain, plane_wave, simulate
from numerics.lattice import _analysis as an
from numerics.lattice import discrete_omega_longitudinal, discrete_omega_rotation
from numerics.theory import hill_spectrum

ALPHA, K_S = paper.ALPHA, paper.K_S
BLUE, GREEN = Material.paper("blue"), Material.paper("green")
K_BLUE, K_GREEN = paper.k("blue"), paper.k("green")
AMP = 0.02  # 2 eps A0 of the paper's runs


@pytest.mark.parametrize("mat,case,k", [(BLUE, "coupled", K_BLUE), (GREEN, "rotation", K_GREEN)])
def test_plane_wave_frequency_shift_is_quadratic(mat, case, k):
    # Omega - omega_lin = c a^2 (1 + O(a^2)): halving a divides the shift by 4. The
    # O(a^2) correction is ~5% at a = 0.02 near the U second-harmonic resonance (blue),
    # so take a = 0.004 (correction ~0.2%, tolerance 1%).
    a = AMP / 5
    s1 = plane_wave(mat, case, k, a).omega - discrete_omega_rotation(k, mat)
    s2 = plane_wave(mat, case, k, a / 2).omega - discrete_omega_rotation(k, mat)
    assert s1 / s2 == pytest.approx(4.0, rel=1e-2)


@pytest.mark.parametrize("mat,case,k", [(BLUE, "coupled", K_BLUE), (GREEN, "coupled", K_GREEN),
                                        (GREEN, "rotation", K_GREEN)])
def test_plane_wave_travels_unchanged_on_the_lattice(mat, case, k):
    # an independent check of the harmonic balance: the simulator (RK4, dt = 0.01, error
    # ~ 1e-10 over T = 50) carries the wave into its own shifted copy
    N = 40
    m = round(k * N / (2 * np.pi))
    kk = 2 * np.pi * m / N
    w = plane_wave(mat, case, kk, AMP)
    n = np.arange(N)
    th, thd, U, Ud = w.fields(n)
    st = LatticeState(U, Ud, th, thd) if case == "coupled" else LatticeState(None, None, th, thd)
    T = 50.0
    end = integrate(st, mat, case, T, 0.01, method="srkn11b")
    th_T, _, U_T, _ = w.fields(n, T)
    assert np.max(np.abs(end.theta - th_T)) < 1e-9 * AMP / 1e-2
    if case == "coupled":
        assert np.max(np.abs(end.U - U_T)) < 1e-9
    # the frequency is not the linear one: a wave at omega_lin would be off by ~T dOmega a
    assert abs(w.omega - w.omega_linear) * T * AMP > 1e-4


def test_hill_small_amplitude_spectrum_is_the_linear_lattice():
    # amplitude -> 0: eigenvalues i (p Omega +- omega(q + p k)), theta odd p, U even p
    w = plane_wave(BLUE, "coupled", K_BLUE, 1e-7)
    q = 0.3
    lam, _ = hill_spectrum(w, BLUE, [q], 5)
    expect = []
    for p in range(-5, 6, 2):
        wr = discrete_omega_rotation(q + p * K_BLUE, BLUE)
        expect += [p * w.omega + wr, p * w.omega - wr]
    for p in range(-6, 7, 2):
        wl = discrete_omega_longitudinal(q + p * K_BLUE)
        expect += [p * w.omega + wl, p * w.omega - wl]
    assert np.max(np.abs(lam.real)) < 1e-10
    assert np.allclose(np.sort(lam.imag[0]), np.sort(expect), atol=1e-9)


@pytest.mark.parametrize("mat,case,k", [(BLUE, "coupled", K_BLUE), (GREEN, "rotation", K_GREEN)])
def test_truncation_converges(mat, case, k):
    q = np.linspace(0.05, 1.0, 40)
    curves = [mi_gain(mat, case, k, AMP, q, harmonics=h) for h in (1, 2, 3, 4)]
    d = [np.max(np.abs(a - b)) for a, b in zip(curves, curves[1:])]
    peak = curves[-1].max()
    assert peak > 0
    # each added harmonic costs a factor ~ a^2 ~ 4e-4: spectral convergence
    assert d[1] < 1e-3 * peak and d[2] < 1e-6 * peak
    assert d[2] < d[1]


def test_stable_runs_have_no_sideband_gain_and_unstable_ones_do():
    q = np.linspace(0, np.pi, 300)
    assert mi_gain(BLUE, "rotation", K_BLUE, AMP, q).max() == 0.0
    assert mi_gain(GREEN, "coupled", K_GREEN, AMP, q).max() == 0.0
    assert mi_gain(BLUE, "coupled", K_BLUE, AMP, q).max() > 1e-3
    assert mi_gain(GREEN, "rotation", K_GREEN, AMP, q).max() > 1e-3


def test_gain_is_even_in_q_and_zero_at_q_zero():
    q = np.linspace(0.0, 1.0, 21)
    a = mi_gain(GREEN, "rotation", K_GREEN, AMP, q)
    b = mi_gain(GREEN, "rotation", K_GREEN, AMP, -q)
    assert a[0] == 0.0
    assert np.allclose(a, b, rtol=1e-8, atol=1e-12)


def test_green_coupled_hides_a_resonant_U_pair_instability():
    # "all" modes: 2 Omega = omega_U(q) + omega_U(q - 2k), growing in U, not in theta
    q = np.linspace(1.0, 1.2, 201)
    side = mi_gain(GREEN, "coupled", K_GREEN, AMP, q)
    every = mi_gain(GREEN, "coupled", K_GREEN, AMP, q, modes="all")
    assert side.max() == 0.0 and every.max() > 5e-4
    qm = q[every.argmax()]
    w = plane_wave(GREEN, "coupled", K_GREEN, AMP)
    res = discrete_omega_longitudinal(qm) + discrete_omega_longitudinal(qm - 2 * K_GREEN)
    assert res == pytest.approx(2 * w.omega, abs=0.01)


def test_quick_simulation_obeys_the_exact_gain():
    # green point, case I, N = 250, from the travelling wave: measured sigma(q) at the
    # peak and the half-gain edge within 5% (the goal; measured: < 1%)
    rates = []
    for seed in (0, 1):
        run = simulate(GREEN, "rotation", 250, K_GREEN, t_end=4000.0, save_every=5.0,
                       store="spectrum", start="travelling", seed=seed)
        win = an.linear_stage(run.theta_hat, run.m, run.N)
        assert win is not None
        rates.append(an.growth_rates(run.t, run.theta_hat, win))
    sigma = np.mean(rates, axis=0)
    meas = an.band_summary(run.wavenumbers, sigma, run.k)
    qf = np.linspace(0, np.pi, 2001)
    th = an.band_summary(qf, mi_gain(GREEN, "rotation", run.k, AMP, qf - run.k), run.k)
    assert meas["peak_gain"] == pytest.approx(th["peak_gain"], rel=0.05)
    assert meas["band_edge"] == pytest.approx(th["band_edge"], rel=0.05)


def test_speed_is_not_asserted_but_500_q_work():
    assert mi_gain(BLUE, "coupled", K_BLUE, AMP, np.linspace(0, 3, 500)).shape == (500,)


@pytest.mark.parametrize("kw,msg", [
    (dict(k=0.0), "k must be"), (dict(k=np.nan), "k must be"), (dict(amplitude=-1), "amplitude"),
    (dict(amplitude=2.0), "amplitude"), (dict(case="shear"), "case"),
    (dict(harmonics=0), "harmonics"), (dict(offset=[np.inf]), "offset must be finite"),
    (dict(modes="some"), "modes")])
def test_bad_input(kw, msg):
    args = dict(material=BLUE, case="coupled", k=K_BLUE, amplitude=AMP, offset=[0.1])
    args.update(kw)
    with pytest.raises(ValueError, match=msg):
        mi_gain(**args)


def test_exact_wave_survives_the_second_harmonic_resonance():
    # sin^2 k = omega^2: the NLS's u2 ~ 1/(sin^2 k - omega^2) diverges, but the exact wave
    # exists: its own frequency shift detunes the resonance and the U harmonic scales
    # as a (not a^2): b/a ~ 0.18 for a = 1e-3 .. 5e-2 (away from resonance b/a^2 = const)
    mat = Material(1.0, 0.5, 0.05)
    ks = np.linspace(0.3, 1.5, 2000)
    f = np.sin(ks) ** 2 - discrete_omega_rotation(ks, mat) ** 2
    k_res = float(ks[np.argmin(np.abs(f))])
    ratios = [abs(plane_wave(mat, "coupled", k_res, a).U_harmonics[0]) / a
              for a in (1e-3, 1e-2, 5e-2)]
    assert max(ratios) / min(ratios) < 1.2 and min(ratios) > 0.1
    off = [abs(plane_wave(mat, "coupled", k_res + 0.3, a).U_harmonics[0]) / a**2
           for a in (1e-3, 1e-2)]
    assert off[0] == pytest.approx(off[1], rel=0.02)
