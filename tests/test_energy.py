"""The energy generates eq. `norm` exactly (symbolic proof), and the code computes it."""

import numpy as np
import pytest
import sympy as sp

from derivation._continuum import K_s, K_theta, alpha, lattice_accelerations
from numerics import LatticeState, Material, energy
from numerics.lattice import accel

NS = 5  # periodic chain long enough that no site is its own second neighbour


def _symbolic_energy(coupled):
    th = sp.symbols(f"th0:{NS}")
    U = sp.symbols(f"U0:{NS}") if coupled else (0,) * NS
    V = 0
    for n in range(NS):
        p = (n + 1) % NS
        e = U[p] - U[n] + 1 - (sp.cos(th[p]) + sp.cos(th[n])) / 2
        V += (2 * e**2 + K_s / 2 * (sp.sin(th[p]) - sp.sin(th[n])) ** 2
              + K_theta * ((th[p] + th[n]) ** 2 / 2 + th[n] ** 2))
    return th, U, V


@pytest.mark.parametrize("case", ["rotation", "coupled"])
def test_energy_generates_the_equations_of_motion(case):
    # Lagrangian L = 2 U_dot^2 + theta_dot^2/(2 alpha^2) - V: masses 4 and 1/alpha^2, so
    # U_n'' = -dV/dU_n / 4 and theta_n'' = -alpha^2 dV/dtheta_n must be eq. `norm`.
    coupled = case == "coupled"
    th, U, V = _symbolic_energy(coupled)
    for n in range(NS):
        p, m = (n + 1) % NS, (n - 1) % NS
        acc_U, acc_th = lattice_accelerations(U[m], U[n], U[p], th[m], th[n], th[p])
        assert sp.simplify(-alpha**2 * sp.diff(V, th[n]) - acc_th) == 0
        if coupled:
            assert sp.simplify(-sp.diff(V, U[n]) / 4 - acc_U) == 0


@pytest.mark.parametrize("case", ["rotation", "coupled"])
def test_energy_code_matches_symbolic_energy(case):
    coupled = case == "coupled"
    th, U, V = _symbolic_energy(coupled)
    rng = np.random.default_rng(3)
    mat = Material.paper("blue")
    vals = {alpha: mat.alpha, K_s: mat.K_s, K_theta: mat.K_theta}
    tv, wv = rng.normal(0, 0.5, NS), rng.normal(0, 0.5, NS)
    vals.update(dict(zip(th, tv)))
    kin = np.sum(wv**2) / (2 * mat.alpha**2)
    if coupled:
        Uv, Vv = rng.normal(0, 0.1, NS), rng.normal(0, 0.1, NS)
        vals.update(dict(zip(U, Uv)))
        kin += 2 * np.sum(Vv**2)
        state = LatticeState(Uv, Vv, tv, wv)
    else:
        state = LatticeState(None, None, tv, wv)
    want = float(V.subs(vals)) + kin
    assert energy(state, mat, case) == pytest.approx(want, rel=1e-13)


def test_compiled_force_matches_equations_as_written():
    # The kernel reorganises 1 - cos; it must still be eq. `norm` (to rounding, 1e-13).
    rng = np.random.default_rng(4)
    mat = Material(1.7, 0.03, 0.011)
    N = 9
    th, Uv = rng.normal(0, 0.8, N), rng.normal(0, 0.3, N)
    s, c, v, ath, aU = (np.empty(N) for _ in range(5))
    accel(th, Uv, True, mat.alpha**2, mat.K_s, mat.K_theta, s, c, v, ath, aU)
    for n in range(N):
        p, m = (n + 1) % N, (n - 1) % N
        fU, ft = lattice_accelerations(Uv[m], Uv[n], Uv[p], th[m], th[n], th[p])
        subs = {alpha: mat.alpha, K_s: mat.K_s, K_theta: mat.K_theta}
        assert ath[n] == pytest.approx(float(ft.subs(subs)), rel=1e-12, abs=1e-14)
        assert aU[n] == pytest.approx(float(fU), rel=1e-12, abs=1e-14)
