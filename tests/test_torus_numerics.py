"""The torus' numerical building blocks: the uniform-grid phase tables and the NAFF peak."""

import numpy as np
import pytest

from numerics.theory._torus import PEAK_TOL, _peak, uniform_phases


@pytest.mark.parametrize("nt, t_end", [(201, 5000.0), (30001, 20000.0), (50, 10.0)])
def test_uniform_phases_equal_the_exponential(nt, t_end):
    rng = np.random.default_rng(3)
    t = np.linspace(0.0, t_end, nt)
    w = rng.normal(0.0, 2.0, 9)
    # the direct exponential is itself only as exact as its argument w t, whose rounding is
    # ~eps |w t| (up to ~1e5 rad here): 8 such roundings bound the difference
    bound = 8 * np.finfo(float).eps * np.abs(np.outer(t, w)).max() + 1e-15
    assert np.abs(uniform_phases(t, w) - np.exp(1j * np.outer(t, w))).max() < bound


def test_uniform_phases_on_a_nonuniform_grid_fall_back():
    t = np.sort(np.random.default_rng(1).uniform(0, 100, 300))
    w = np.array([0.3, -1.7])
    assert np.allclose(uniform_phases(t, w), np.exp(1j * np.outer(t, w)), rtol=0, atol=1e-13)


def test_peak_finds_the_windowed_maximum():
    """Two close quasi-periodic lines: the refined frequency is the true maximum of the
    windowed amplitude |S| (no neighbour a tolerance away is higher), near the stronger
    line (the window's leakage shifts it by far less than a resolution bin)."""
    T = 1500.0
    t = np.linspace(0.0, T, 12001)
    c = np.exp(-1j * 0.9318 * t) + 0.3 * np.exp(-1j * 0.9400 * t)
    window = np.sin(np.pi * t / T) ** 2
    span = 3 * 2 * np.pi / T
    nu = _peak(t, c, 0.93, window, span)
    S = lambda x: abs(np.exp(1j * x * t) @ (window * c))
    h = 100 * PEAK_TOL * span
    assert S(nu) >= S(nu - h) and S(nu) >= S(nu + h)
    assert abs(nu - 0.9318) < 0.1 * 2 * np.pi / T


def test_a_launched_state_of_many_free_waves_is_refused_at_once(tmp_path, capsys):
    """The paper chain's point at amplitude 1 rad (eq. `IC` launches 6 significant free
    waves: 5^6 = 15625 torus modes, more than the 12624 samples, ~2.5e13 flops) ran its torus
    fit for 8 minutes in one BLAS call that ignored Ctrl-C and SIGTERM; it is now the
    paper start's row undefined with the reason (no linear theory of sidebands: no carrier
    with small sidebands), the NLS rows still printed, exit 0, in seconds. At 0.05 rad (2
    free waves) the theory still answers."""
    from cli.app import main
    from numerics.lattice import Material
    from numerics.theory import PAPER_START, theory_gain

    with pytest.raises(ArithmeticError, match="6 significant free waves.*--start travelling"):
        theory_gain(PAPER_START, Material(2.0, 0.03, 0.02), "coupled", 1.1938,
                    offset=np.array([0.1]), eps=0.01, A0=50.0)
    assert main(["point", "--alpha", "2.0", "--K-s", "0.03", "--K-theta", "0.02", "--k", "1.2",
                 "--amplitude", "1.0", "--case", "coupled", "--out", str(tmp_path)]) == 0
    out = capsys.readouterr().out
    assert "exact lattice, paper start: start 'paper': the state eq. `IC` launches holds 6" in out
    assert "semi-discrete NLS           MI" in out
    g = theory_gain(PAPER_START, Material(2.0, 0.03, 0.02), "coupled", 1.1938,
                    offset=np.array([0.1]), eps=0.01, A0=2.5)
    assert np.all(np.isfinite(g))
