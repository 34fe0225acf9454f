"""Hill's method with modes="all" counts no relabelled copy cut off at the truncation's
edge (probe 99, ``numerics.theory._quasiperiodic.off_centre``).

The Hill spectrum at offset q + j k is the one at q relabelled (p -> p - j, shifted by
i j Omega), so the rate at q = -(P - 1) k (mod 2 pi), where the outermost theta harmonic
p = P lands on the carrier's own wavenumber, is the rate at q = 0: a shift of the wave's
phase or amplitude, neutral. Before, modes="all" read a growth there (the carrier's
neutral pair copied to p = P - 2, P and cut off beyond P) at the blue point, case I:
2.7e-5 at a = 0.02, 3.1e-3 at a = 0.1, 1.7e-2 at a = 0.2, the same at every truncation,
where the lattice (a run of eq. `norm` below) and the model engine's exact theory show
nothing growing.
"""

import math

import numpy as np
import pytest

from numerics import Material
from numerics.theory import gain_spectrum, mi_gain, plane_wave, stability_map

BLUE = Material.paper("blue")
K_BLUE = 2 * np.pi * 13 / 100  # 0.8168, the blue carrier on a ring of 100 sites


def _wrap(q):
    return abs((q + np.pi) % (2 * np.pi) - np.pi)


@pytest.mark.parametrize("H", [2, 4, 6])
@pytest.mark.parametrize("amplitude", [0.02, 0.1, 0.2])
def test_no_growth_at_the_relabelled_neutral_offset(H, amplitude):
    P = 2 * H - 1
    q0 = _wrap(-(P - 1) * K_BLUE)
    # the copy's band was ~7e-3 wide around q0 (a = 0.02) and wider at larger a
    q = q0 + np.linspace(-0.02, 0.02, 81)
    sigma = mi_gain(BLUE, "rotation", K_BLUE, amplitude, q, modes="all", harmonics=H)
    assert sigma.max() == 0.0, (H, amplitude, sigma.max())
    # the same physical offset at q -> 0 (p = +-1): neutral in both readings
    near0 = mi_gain(BLUE, "rotation", K_BLUE, amplitude, q - q0 + 1e-3, modes="all",
                    harmonics=H)
    assert near0.max() == 0.0
    spec = gain_spectrum(BLUE, "rotation", K_BLUE, amplitude, q, modes="all", harmonics=H)
    assert spec.sigma.max() == 0.0


def test_stability_map_all_modes_no_edge_copy():
    # stability_map's batched path, harmonics 2 (P = 3): the copy sat at q = -2 k
    q = np.linspace(0.005, np.pi, 400)
    for a in (0.05, 0.1, 0.2):
        g = stability_map(np.array([K_BLUE]), np.array([BLUE.delta]), "rotation", BLUE.alpha,
                          BLUE.K_s, a, offset=q, modes="all", harmonics=2)
        assert g[0] == 0.0, (a, g)


def test_green_coupled_u_pairs_still_found():
    # the U pairs of green II (docs/theory.md: 2 Omega = omega_U(q) + omega_U(q - 2k))
    # are centred at U's p = 0, -2: kept. Their band is narrow; a fine grid about it
    mat, k = Material.paper("green"), 0.92991
    q = np.linspace(0.1145, 0.1205, 601)
    g = mi_gain(mat, "coupled", k, 0.02, q, modes="all")
    # 1.59e-3 before and after (the sideband modes: none, as the paper's run shows)
    assert 1.5e-3 < g.max() < 1.7e-3
    assert mi_gain(mat, "coupled", k, 0.02, q).max() == 0.0


def _norm_rotation(th, alpha, K_s, K_theta):
    """theta'' of eq. `norm` with U = 0 (case I), periodic, written here."""
    ct, st = np.cos(th), np.sin(th)
    return alpha**2 * (-K_theta * (np.roll(th, -1) + 4 * th + np.roll(th, 1))
                       + K_s * ct * (np.roll(st, -1) + np.roll(st, 1) - 2 * st)
                       - st * (4 - 2 * ct - np.roll(ct, -1) - np.roll(ct, 1)))


def test_the_lattice_agrees_nothing_grows():
    """A run of eq. `norm` (RK4 here, dt 0.05) from the exact wave at a = 0.2 plus noise
    1e-6 a: the old reading, 1.7e-2, would have grown the carrier's own mode 2.4e4x over
    T = 600 (the noise to 2.4e-2 a); it moves by < 1e-3 a, and no other mode grows."""
    N, a = 100, 0.2
    pw = plane_wave(BLUE, "rotation", K_BLUE, a)
    phase = K_BLUE * np.arange(N)
    orders = 2 * np.arange(pw.theta_harmonics.size) + 1
    th = sum(c * np.cos(j * phase) for c, j in zip(pw.theta_harmonics, orders))
    v = sum(c * j * pw.omega * np.sin(j * phase) for c, j in zip(pw.theta_harmonics, orders))
    rng = np.random.default_rng(99)
    th = th + 1e-6 * a * rng.standard_normal(N)
    v = v + 1e-6 * a * pw.omega * rng.standard_normal(N)
    f = lambda th_: _norm_rotation(th_, BLUE.alpha, BLUE.K_s, BLUE.K_theta)  # noqa: E731
    dt, steps = 0.05, 12000
    start = np.abs(np.fft.rfft(th)) * 2 / N
    worst = 0.0
    for s in range(steps):
        k1x, k1v = v, f(th)
        k2x, k2v = v + dt / 2 * k1v, f(th + dt / 2 * k1x)
        k3x, k3v = v + dt / 2 * k2v, f(th + dt / 2 * k2x)
        k4x, k4v = v + dt * k3v, f(th + dt * k3x)
        th = th + dt / 6 * (k1x + 2 * k2x + 2 * k3x + k4x)
        v = v + dt / 6 * (k1v + 2 * k2v + 2 * k3v + k4v)
        if s % 600 == 599:
            worst = max(worst, float(np.max(np.abs(np.abs(np.fft.rfft(th)) * 2 / N - start))))
    assert worst < 1e-3 * a, worst
    # and the theory now says what the run shows
    q = np.linspace(0.005, math.pi, 400)
    assert mi_gain(BLUE, "rotation", K_BLUE, a, q, modes="all").max() == 0.0
