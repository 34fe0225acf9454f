"""Exact MI maps from resonance conditions (numerics.resonance_map)."""

from __future__ import annotations

import numpy as np
import pytest

from common import paper
from numerics import Material, mi_gain, resonance_map, stability_map

#: the scenes' question: grows more than 20x within the paper's T = 5000
THRESHOLD = np.log(20.0) / paper.T_END


def _grid(n):
    k = np.linspace(0.02, np.pi - 0.02, n)
    d = np.linspace(-0.0149, 0.0149, n)
    return np.meshgrid(k, d)


@pytest.mark.parametrize("case,start", [("rotation", "travelling"), ("coupled", "travelling"),
                                        ("coupled", "paper")])
def test_verdict_does_not_depend_on_the_offset_grid(case, start):
    """The issue's test: refine the grid of offsets 4x, no cell's verdict changes."""
    K, D = _grid(30)
    coarse = resonance_map(K, D, case, paper.ALPHA, paper.K_S, 0.02, start=start)
    fine = resonance_map(K, D, case, paper.ALPHA, paper.K_S, 0.02, start=start, grid=1024)
    a, b = (np.nan_to_num(r["peak_gain"]) > THRESHOLD for r in (coarse, fine))
    assert np.array_equal(a, b)
    assert 0.2 < a.mean() < 0.8  # the map is not trivially all stable or all unstable


def test_case_I_matches_a_dense_hill_scan():
    """Case I's reduced problem is the whole H = 1 Hill problem up to the rotating-wave
    step: the peak agrees with a 2000-offset scan to the scan's resolution (2e-3)."""
    K, D = _grid(8)
    res = resonance_map(K, D, "rotation", paper.ALPHA, paper.K_S, 0.02)["peak_gain"]
    dense = stability_map(K, D, "rotation", paper.ALPHA, paper.K_S, 0.02,
                          offset=np.linspace(1e-3, np.pi, 2000))
    assert np.array_equal(res > 0, dense > 0)
    both = dense > 0
    assert np.max(np.abs(res[both] / dense[both] - 1)) < 2e-3


def test_case_II_finds_every_band_a_dense_scan_finds():
    """Where an 800-offset Hill scan finds a band clearly above the threshold, the map
    finds it. Its rate is Hill's at the reduced problem's resonance, not at the exact
    maximum: 14 of 15 cells within 0.1%, one wide asymmetric band at 86% (measured)."""
    K, D = _grid(14)
    res = resonance_map(K, D, "coupled", paper.ALPHA, paper.K_S, 0.02)["peak_gain"]
    dense = stability_map(K, D, "coupled", paper.ALPHA, paper.K_S, 0.02,
                          offset=np.linspace(1e-3, np.pi, 800))
    clear = np.nan_to_num(dense) > 2 * THRESHOLD
    assert clear.sum() >= 15
    ratio = np.nan_to_num(res[clear]) / dense[clear]
    assert np.all(ratio >= 0.8) and np.median(ratio) > 0.999


def test_paper_start_pumped_band_at_a_gain_theories_point():
    """delta = -0.0051, k = 2 pi 90/500: the travelling wave is stable, eq. `IC` grows
    (measured 2.46e-3, quasi-periodic Hill 2.47e-3; the map's leading-order rate for the
    band the free U waves pump is within 15%)."""
    k, d = 2 * np.pi * 90 / 500, -0.0051
    trav = resonance_map(k, d, "coupled", paper.ALPHA, paper.K_S, 0.02)
    pap = resonance_map(k, d, "coupled", paper.ALPHA, paper.K_S, 0.02, start="paper")
    assert trav["peak_gain"] < THRESHOLD
    assert pap["pumped"]
    exact = mi_gain(Material(paper.ALPHA, paper.K_S, paper.K_S - d), "coupled", k, 0.02,
                    np.linspace(1.98, 2.1, 25), harmonics=1, start="paper").max()
    assert abs(pap["peak_gain"] / exact - 1) < 0.15


def test_bad_inputs():
    with pytest.raises(ValueError, match="start"):
        resonance_map(1.0, 0.0, "coupled", 2.5, paper.K_S, 0.02, start="IC")
    with pytest.raises(ValueError, match="grid"):
        resonance_map(1.0, 0.0, "coupled", 2.5, paper.K_S, 0.02, grid=4)
    with pytest.raises(ValueError, match="0 < k < pi"):
        resonance_map(3.5, 0.0, "coupled", 2.5, paper.K_S, 0.02)
    with pytest.raises(ValueError, match="K_theta"):
        resonance_map(1.0, 0.05, "coupled", 2.5, paper.K_S, 0.02)
    with pytest.raises(ValueError, match="broadcastable"):
        resonance_map(np.ones(3), np.zeros(4), "coupled", 2.5, paper.K_S, 0.02)


def _reduced_reference(C, k, W, q, coupled):
    """The reduced sideband problem in NumPy, as the map's docstring states it (the
    formulas the compiled ``_reduced`` evaluates): L[a, b] = sum_j c_{j, a - b}
    e^{i (q + b k) j}; U modes u = -2, 0, 2 folded in by a Schur complement with the
    pair's common exponent lam0 = i (omega_- - omega_+) / 2."""
    from generated import lattice_model as model

    M = C["tt"].shape[-1]
    eq = np.exp(1j * q)[None, :]
    E = {p: eq * np.exp(1j * p * k)[:, None] for p in (-2, -1, 0, 1, 2)}

    def entry(name, l, p):
        c = C[name][:, :, l % M]
        return c[:, 0, None] * E[p].conj() + c[:, 1, None] + c[:, 2, None] * E[p]

    L = {(a, b): entry("tt", a - b, b) for a in (1, -1) for b in (1, -1)}
    dens = []
    if coupled:
        lam0 = 0.5j * (np.sqrt(-L[-1, -1]) - np.sqrt(-L[1, 1]))
        for u in (-2, 0, 2):
            den = (lam0 - 1j * u * W[:, None]) ** 2 + model.omega_longitudinal(
                q + u * k[:, None]) ** 2
            dens.append(den.real)
            for a in (1, -1):
                for b in (1, -1):
                    L[a, b] = L[a, b] + entry("tU", a - u, u) / den * entry("Ut", u - b, b)
    return np.sqrt(-L[1, 1]), np.sqrt(-L[-1, -1]), L[1, -1] * L[-1, 1], np.array(dens)


@pytest.mark.parametrize("case", ["rotation", "coupled"])
def test_compiled_reduced_problem_matches_its_numpy_form(case):
    """The compiled reduced problem evaluates the documented formulas: equal to their
    NumPy form to rounding (1e-11 relative: ~20 complex operations in a different order,
    and the pole's 1 / den amplifies rounding near a U resonance by |L| / |den| <~ 1e3)."""
    from numerics.theory._hill import _coefficients
    from numerics.theory._plane_wave import _solve_plane_waves
    from numerics.theory._resonance import _reduced

    B = 40
    k = np.linspace(0.1, 3.0, B)
    Kt = paper.K_S - np.linspace(-0.012, 0.012, B)
    al, Ks = np.full(B, paper.ALPHA), np.full(B, paper.K_S)
    coupled = case == "coupled"
    x, _ = _solve_plane_waves(k, np.full(B, 0.02), al, Ks, Kt, coupled, 1, points=16)
    C = _coefficients(x[:, :1], x[:, 1:2], k, al, Ks, Kt, 16)
    q = np.linspace(np.pi / 256, np.pi, 256)
    got = _reduced(C, k, x[:, -1], q, coupled, poles=True)
    want = _reduced_reference(C, k, x[:, -1], q, coupled)
    # omega_+- compared squared: where -L is a negative real (no real frequency), the sign
    # of its rounding-level imaginary part picks the branch of the square root
    for g, w in zip(got[:2], want[:2]):
        np.testing.assert_allclose(g**2, w**2, rtol=1e-11, atol=1e-15)
    np.testing.assert_allclose(got[2], want[2], rtol=1e-11, atol=1e-15)
    assert len(got[3]) == len(want[3]) == (3 if coupled else 0)
    if coupled:
        np.testing.assert_allclose(got[3], want[3], rtol=1e-11, atol=1e-15)


# --- a material, as every other public function takes it ---------------------------------------

@pytest.mark.parametrize("case,start", [("rotation", "travelling"), ("coupled", "paper")])
def test_material_form_gives_the_positional_forms_arrays(case, start):
    # material= (its alpha and K_s; its own K_theta unused: the grid's is K_s - delta) is
    # the same map as (alpha, K_s), bit for bit; K_theta= instead of delta too
    K, D = _grid(6)
    mat = Material(paper.ALPHA, paper.K_S, 0.5)  # K_theta 0.5: not the grid's, not used
    old = resonance_map(K, D, case, paper.ALPHA, paper.K_S, 0.02, start=start)
    new = resonance_map(K, D, case, material=mat, amplitude=0.02, start=start)
    by_K_theta = resonance_map(K, case=case, material=mat, amplitude=0.02, start=start,
                               K_theta=paper.K_S - D)
    for name in ("peak_gain", "q_peak", "pumped"):
        assert new[name].tobytes() == old[name].tobytes() == by_K_theta[name].tobytes(), name
    old = stability_map(K, D, case, paper.ALPHA, paper.K_S, 0.02)
    assert stability_map(K, D, case, material=mat, amplitude=0.02).tobytes() == old.tobytes()
    assert stability_map(K, case=case, material=mat, amplitude=0.02,
                         K_theta=paper.K_S - D).tobytes() == old.tobytes()


def test_map_material_and_axis_are_given_once():
    mat = Material.paper("blue")
    with pytest.raises(TypeError, match="not both"):
        resonance_map(1.0, 0.0, "coupled", 2.5, paper.K_S, 0.02, material=mat)
    with pytest.raises(TypeError, match="delta or as K_theta"):
        resonance_map(1.0, 0.0, "coupled", material=mat, amplitude=0.02, K_theta=0.01)
    with pytest.raises(TypeError, match="delta or as K_theta"):
        stability_map(1.0, case="coupled", material=mat, amplitude=0.02)
    with pytest.raises(TypeError, match="missing amplitude"):
        resonance_map(1.0, 0.0, "coupled", material=mat)
    with pytest.raises(TypeError, match="material"):
        stability_map(1.0, 0.0, "coupled", material={"alpha": 2.5}, amplitude=0.02)
    with pytest.raises(ValueError, match="need K_theta > 0"):
        resonance_map(1.0, case="coupled", material=mat, amplitude=0.02, K_theta=-0.01)
