"""generated/lattice_model.py (eq. `norm` printed from SymPy) against the hand-tuned Numba
kernel, finite differences, and the linear lattice."""

import numpy as np
import pytest

from generated import lattice_model as lm
from numerics import Material, discrete_omega_rotation
from numerics.lattice import accel, numpy_accel


def _kernel(th, U, mat, coupled):
    n = th.size
    s, c, v, ath, aU = (np.empty(n) for _ in range(5))
    accel(th, U if coupled else np.zeros(0), coupled, mat.alpha**2, mat.K_s, mat.K_theta,
          s, c, v, ath, aU if coupled else np.zeros(0))
    return ath, (aU if coupled else None)


@pytest.mark.parametrize("coupled", [True, False], ids=["coupled", "rotation"])
@pytest.mark.parametrize("scale", [1e-3, 0.3, 2.0])
def test_numba_kernel_equals_the_generated_model(coupled, scale, rng, blue):
    # random states from tiny to large rotations; the kernel forms 1 - cos as
    # sin^2/(1 + cos) and the generated code as written, so they agree to round-off of the
    # largest term (alpha^2 * 4 |sin th|, ~ 1e-15 relative to the force scale)
    N = 257
    th, U = rng.normal(0, scale, N), rng.normal(0, scale / 10, N)
    ath, aU = _kernel(th, U, blue, coupled)
    ref_t, ref_U = numpy_accel(th, U, blue, coupled)
    force_scale = blue.alpha**2 * (4 * np.max(np.abs(np.sin(th))) + 6 * blue.K_theta * scale)
    assert np.max(np.abs(ath - ref_t)) <= 1e-14 * force_scale
    if coupled:
        assert np.max(np.abs(aU - ref_U)) <= 1e-14 * (1 + np.max(np.abs(U)))


def test_jacobian_matches_central_differences(rng):
    x = rng.normal(0, 0.5, 6)
    mat = (2.1, 0.03, 0.012)
    J = lm.jacobian(*x, *mat)
    assert J.shape == (2, 6)
    h = 1e-6
    for j in range(6):
        xp, xm = x.copy(), x.copy()
        xp[j] += h
        xm[j] -= h
        for i, f in enumerate((lm.acceleration_U, lm.acceleration_theta)):
            fd = (f(*xp, *mat) - f(*xm, *mat)) / (2 * h)
            assert J[i, j] == pytest.approx(fd, rel=1e-7, abs=1e-9)  # O(h^2) = 1e-12


def test_jacobian_broadcasts_constant_entries():
    th = np.linspace(-1, 1, 7)
    J = lm.jacobian(0.0, 0.0, 0.0, th, 2 * th, -th, 2.5, 0.02, 0.01)
    assert J.shape == (2, 6, 7)
    assert np.all(J[0, 1] == -2) and np.all(J[0, 0] == 1)  # the U Laplacian


def test_dispersion_is_the_jacobian_at_rest_and_the_papers_discrete2():
    q = np.linspace(-np.pi, np.pi, 101)
    mat = Material(2.5, 0.01851, 0.02151)
    J = lm.jacobian(0, 0, 0, 0, 0, 0, mat.alpha, mat.K_s, mat.K_theta)
    shifts = np.exp(1j * np.outer(q, [-1, 0, 1]))
    w2_t = -(shifts @ J[1, 3:]).real
    w2_U = -(shifts @ J[0, :3]).real
    np.testing.assert_allclose(lm.omega_rotation(q, mat.alpha, mat.K_s, mat.K_theta) ** 2,
                               w2_t, rtol=1e-13)
    np.testing.assert_allclose(lm.omega_longitudinal(q) ** 2, w2_U, atol=1e-13)
    # the paper's eq. `discrete2`, typed: alpha^2 (4 delta sin^2(q/2) + 6 K_theta)
    typed = mat.alpha * np.sqrt(4 * mat.delta * np.sin(q / 2) ** 2 + 6 * mat.K_theta)
    np.testing.assert_allclose(discrete_omega_rotation(q, mat), typed, rtol=1e-14)
    # eq. `discrete1`: 2 |sin(q/2)|, accurate (no cancellation) at tiny q
    assert lm.omega_longitudinal(1e-9) == pytest.approx(1e-9, rel=1e-12)
