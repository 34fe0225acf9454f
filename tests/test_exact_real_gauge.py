"""The strong path's frozen pencil in real arithmetic (``numerics/models/_real_gauge.py``).

Where a diagonal phase G makes the Hill matrix real (R = G^* K G), the frozen pencil
(lambda - i Omega)^2 + K_CC - Sigma(0) becomes, with lambda = i mu, a real one: its
eigenvalues are solved by a real eigensolver at ~1/3 of the complex one's cost. Held here
to an independent NumPy construction of the complex frozen pencil (its companion matrix's
eigenvalues, the fold by ``numpy.linalg.solve``), and the gauge's own check to what it
must accept and refuse.
"""

import numpy as np
import pytest
from scipy.optimize import linear_sum_assignment
from scipy.sparse.csgraph import connected_components

from energy import load_model
from numerics.models import travelling_wave
from numerics.models._exact import _hessian_harmonics, _work_harmonics
from numerics.models._real_gauge import GAUGE_TOL, frozen_real, real_gauge
from numerics.models._small_algebra import _drop_roundoff


def _pencil(wave, q, drop=False):
    """K(q) of the Hill pencil scaled by M^{-1/2}, (Omega, K) in the harmonics' coordinates
    (field-major inside a harmonic), written out from the dense spectrum's formula.
    ``drop``: the Hessian's harmonics below round-off made exact zeros, as the compiled
    paths have them (a pencil that then splits: flexmm-stiff-hinge's)."""
    d = wave.model.n_fields
    P = _work_harmonics(wave)
    Hh = _hessian_harmonics(wave, P)
    if drop:
        Hh = _drop_roundoff(Hh)
    l_ = np.arange(-P, P + 1)
    S = Hh[l_[:, None] - l_[None, :] + 2 * P]
    ph = np.exp(1j * (q + l_ * wave.k))[None, :, None, None]
    back = np.exp(-1j * (l_[:, None] - l_[None, :]) * wave.k)[..., None, None]
    blk = S[..., :d, :d] + S[..., :d, d:] * ph + S[..., d:, :d] * back / ph \
        + S[..., d:, d:] * back
    n = d * l_.size
    sq = np.tile(1 / np.sqrt(np.asarray(wave.model.masses, float)), l_.size)
    K = blk.transpose(0, 2, 1, 3).reshape(n, n) * sq[:, None] * sq[None, :]
    return P, np.repeat(l_ * wave.omega, d), K


def _frozen_complex(K, Om, C):
    """The frozen pencil's eigenvalues, its fold and T_RR(0)^{-1} K_RC, in complex
    arithmetic: the companion matrix of (lambda - i Omega_C)^2 + K_CC - Sigma."""
    R = ~C
    X = np.linalg.solve(K[np.ix_(R, R)] - np.diag(Om[R] ** 2), K[np.ix_(R, C)])
    Sig = K[np.ix_(C, R)] @ X
    A = K[np.ix_(C, C)] - Sig
    rc = int(C.sum())
    L = np.zeros((2 * rc, 2 * rc), complex)
    L[:rc, rc:] = np.eye(rc)
    L[rc:, :rc] = -A + np.diag(Om[C] ** 2)
    L[rc:, rc:] = np.diag(2j * Om[C])
    return np.linalg.eigvals(L), Sig, X


@pytest.mark.parametrize("name, params, k, a, drop", [
    ("flexmm", {"K_theta": 0.016}, 2 * np.pi * 36 / 256, 0.1, False),
    ("flexmm-stiff-hinge", {"K_3": 0.7, "alpha": 3.0}, 2.3, 0.06, False),
    ("diatomic-fput", {}, 1.0, 0.1, False),
    # the pencils the strong path solves (round-off dropped): stiff-hinge's splits in two
    # halves, whose eigenvalues ``frozen_real`` finds block by block
    ("flexmm-stiff-hinge", {"K_3": 0.7, "alpha": 3.0}, 2.3, 0.06, True),
    ("flexmm-stiff-hinge", {}, 1.0, 0.1, True),
    ("flexmm", {"K_theta": 0.016}, 2 * np.pi * 36 / 256, 0.1, True),
])
def test_the_real_frozen_pencil_is_the_complex_one(name, params, k, a, drop):
    model = load_model(name).with_params(**params) if params else load_model(name)
    wave = travelling_wave(model, k, a)
    for q in (1e-5, 0.37, 1.9, np.pi):
        P, Om, K = _pencil(wave, q, drop)
        if drop and name == "flexmm-stiff-hinge":  # the split path is exercised
            assert connected_components(np.abs(K) > 0)[0] == 2
        g = np.empty(K.shape[0], complex)
        assert real_gauge(K, g)  # a reflection-symmetric wave: every built-in model's
        R = np.conj(g)[:, None] * K * g[None, :]
        assert np.abs(R.imag).max() <= GAUGE_TOL * np.abs(K).max()
        C = np.repeat(np.abs(np.arange(-P, P + 1)) <= P - 5, model.n_fields)
        cidx, ridx = np.flatnonzero(C), np.flatnonzero(~C)
        X = np.empty((ridx.size, cidx.size), complex)
        Sig = np.empty((cidx.size, cidx.size), complex)
        lam, ok = frozen_real(K, Om, cidx, ridx, g, X, Sig)
        ref, Sig_ref, X_ref = _frozen_complex(K, Om, C)
        assert ok
        scale = np.abs(ref).max()
        # each eigenvalue matched one to one (the nearest assignment); the tolerance:
        # eigenvalues of a 44 x 44 nonsymmetric matrix, ~1e-13 of its largest measured,
        # with a margin of 100 for the conditioning of near pairs
        i, j = linear_sum_assignment(np.abs(lam[:, None] - ref[None, :]))
        np.testing.assert_allclose(lam[i], ref[j], rtol=0, atol=1e-10 * scale)
        # the fold and X back in the pencil's coordinates: linear algebra to round-off
        np.testing.assert_allclose(Sig, Sig_ref, rtol=0, atol=1e-12 * np.abs(Sig_ref).max())
        np.testing.assert_allclose(X, X_ref, rtol=0, atol=1e-12 * np.abs(X_ref).max())
        # what grows is the same (the strong path's starts: rates over 1e-9 omega); a rate
        # of a near-double eigenvalue is as sensitive as its eigenvalue (diatomic-fput:
        # 3.4e-7, the two within 2e-11), hence the eigenvalues' absolute tolerance
        grows = np.sort(lam.real[lam.real > 1e-9 * wave.omega])
        np.testing.assert_allclose(grows, np.sort(ref.real[ref.real > 1e-9 * wave.omega]),
                                   rtol=0, atol=1e-10 * scale)
        # in real arithmetic each growing eigenvalue's mirror -conj(lambda) is exact
        mirror = -np.conj(lam[lam.real > 1e-9 * wave.omega])
        assert all(np.min(np.abs(lam - z)) == 0.0 for z in mirror)


def test_the_gauge_is_found_where_it_exists_and_refused_where_not():
    rng = np.random.default_rng(41)
    n = 12
    Rs = rng.standard_normal((n, n))
    Rs = Rs + Rs.T
    Rs[3, :] = Rs[:, 3] = 0  # a zero row: a component of its own
    Rs[3, 3] = 1.0
    G = np.exp(1j * rng.uniform(0, 2 * np.pi, n))
    K = G[:, None] * Rs * np.conj(G)[None, :]  # real up to a diagonal phase
    g = np.empty(n, complex)
    assert real_gauge(K, g)
    R = np.conj(g)[:, None] * K * g[None, :]
    assert np.abs(R.imag).max() <= 1e-15 * np.abs(K).max() * n
    # the gauge is unique up to a sign per entry: |R| = |Rs| entry by entry
    np.testing.assert_allclose(np.abs(R), np.abs(Rs), rtol=1e-14, atol=0)
    # a phase around a loop (a flux) that no diagonal phase removes
    H = rng.standard_normal((n, n)) + 1j * rng.standard_normal((n, n))
    assert not real_gauge(H + H.conj().T, np.empty(n, complex))
    # nearly gauge-real: just over the tolerance is refused, just under accepted
    E = np.zeros((n, n), complex)
    E[0, 1], E[1, 0] = 1j, -1j
    big = np.abs(K).max()
    for factor, accepted in ((10.0, False), (0.1, True)):
        Kp = K + factor * GAUGE_TOL * big * (G[:, None] * E * np.conj(G)[None, :])
        assert real_gauge(Kp, np.empty(n, complex)) == accepted
