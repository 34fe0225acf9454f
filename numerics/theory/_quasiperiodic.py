"""Hill's method for a quasi-periodic state: the growth from the state a run starts in.

The launched state (``_launched``, ``_torus``) depends on the carrier phase
phi = k n - Omega T and on d free phases psi_j = -nu_j T. Linearising eq. `norm` about it,
a perturbation

    x_n(T) = e^{lambda T} sum_{p, m} X_{p,m} e^{i (q + p k) n} e^{-i (p Omega + m . nu) T}

turns the lattice into (lambda - i (p Omega + m . nu))^2 X_{p,m} = sum L X, constant
coefficients in the multi-index (p, m): Hill's method on the torus. The couplings are the
Fourier coefficients, over the torus, of the generated Jacobian of eq. `norm` evaluated on
the state; d = 0 is ``_hill``'s travelling-wave problem. The truncations (|p| <= P,
|m_j| <= R) are the approximations; tests/test_launched.py shows their convergence.
The state is odd in theta and even in U under phi -> phi + pi (a free wave at harmonic m k
sits at p = m), so, as in the periodic case, the sideband family holds theta at odd p and
U at even p, with any m.

References
----------
B. Deconinck & J. N. Kutz, J. Comput. Phys. 219 (2006) 296; quasi-periodic Floquet
theory: A. Jorba & C. Simo, J. Differ. Equ. 98 (1992) 111.
"""

from __future__ import annotations

import itertools
from dataclasses import dataclass

import numpy as np

from ..lattice import checks

from generated import lattice_model as model

from ._torus import Torus

#: a Hill mode is a sideband (MI) mode when the two sidebands p = +-1 hold more than
#: SIDEBAND_SHARE of its kinetic energy, each of them at least SIDEBAND_PRESENT
SIDEBAND_SHARE, SIDEBAND_PRESENT = 0.75, 0.05
#: growth rates below this fraction of Omega are round-off (the q = 0 Jordan block).
ROUNDOFF = 1e-8
#: torus grid points per free phase (the Jacobian is linear in the small free waves: few
#: harmonics); per carrier phase as in _hill
FREE_GRID = 8


@dataclass(frozen=True)
class GainSpectrum:
    """Growth rate per Bloch offset, with what grows.

    Attributes
    ----------
    q : ndarray, shape (nq,)
        Offsets from the carrier (rad per site); the sidebands are k + q and k - q.
    sigma : ndarray, shape (nq,)
        Largest growth rate (1/T) of the modes selected (``modes``), 0 where none grows.
    field : ndarray of str, shape (nq,)
        "theta" or "U": the field holding most of the kinetic energy of that mode ("" if
        none grows).
    wavenumber : ndarray, shape (nq,)
        Its dominant component's wavenumber |q + p k| folded into [0, pi] (rad per site).
    frequency : ndarray, shape (nq,)
        That component's lab frequency |Im lambda - (p Omega + m . nu)| (1/T).
    sideband : ndarray of bool, shape (nq,)
        Whether the mode is an MI mode (theta at k +- q holds most of its energy).
    start : str
    """

    q: np.ndarray
    sigma: np.ndarray
    field: np.ndarray
    wavenumber: np.ndarray
    frequency: np.ndarray
    sideband: np.ndarray
    start: str


def _multi_indices(R, d):
    """All m in Z^d with |m_j| <= R, shape (n, d) (one empty index when d = 0)."""
    combos = list(itertools.product(range(-R, R + 1), repeat=d))
    return np.array(combos, int).reshape(len(combos), d)


def _labels(P, R, d):
    """Basis multi-indices: theta (p odd, m) and U (p even, m), |m_j| <= R."""
    ms = _multi_indices(R, d)
    x, y = [], []
    for p in range(-(P + 1), P + 2):
        for m in ms:
            if p % 2 == 1 and abs(p) <= P:
                x.append((p, *m))
            elif p % 2 == 0:
                y.append((p, *m))
    return np.array(x, int).reshape(-1, d + 1), np.array(y, int).reshape(-1, d + 1)


def _coefficients(torus, material, Mp):
    """Torus Fourier coefficients of the Jacobian blocks: name -> (3, Mp, Mf, ..)."""
    d = torus.nu.size
    phi = 2 * np.pi * np.arange(Mp) / Mp
    psi = 2 * np.pi * np.arange(FREE_GRID) / FREE_GRID
    f = {(fld, s): torus.on_grid(fld, phi, psi, s) for fld in ("theta", "U") for s in (-1, 0, 1)}
    J = model.jacobian(f["U", -1], f["U", 0], f["U", 1], f["theta", -1], f["theta", 0],
                       f["theta", 1], material.alpha, material.K_s, material.K_theta)
    blocks = {"tt": J[1, 3:], "tU": J[1, :3], "Ut": J[0, 3:]}
    axes = tuple(range(1, d + 2))
    return {n: np.fft.fftn(b, axes=axes) / (Mp * FREE_GRID**d) for n, b in blocks.items()}


def hill_matrix(torus, material, case, q, P, R):
    """First-order quasi-periodic Hill matrices (nq, 2n, 2n) and the basis labels
    (n, 1 + d): columns p, m_1 .. m_d; the first ``nx`` labels are theta."""
    d = torus.nu.size
    px, py = _labels(P, R, d)
    coupled = case == "coupled"
    if not coupled:
        py = py[:0]
    Mp = max(64, 4 * (2 * P + 2))
    C = _coefficients(torus, material, Mp)
    k, W, nu = torus.k, torus.omega, torus.nu
    jj = np.array([-1.0, 0.0, 1.0])
    q = np.asarray(q, float).ravel()

    def block(c, rows, cols):
        diff = rows[:, None, :] - cols[None, :, :]  # (nr, nc, 1 + d)
        idx = (diff[..., 0] % Mp,) + tuple(diff[..., 1 + j] % FREE_GRID for j in range(d))
        cj = c[(slice(None),) + idx]  # (3, nr, nc)
        wav = q[:, None] + cols[None, :, 0] * k  # (nq, nc)
        ph = np.exp(1j * jj[:, None, None] * wav[None])  # (3, nq, nc)
        return np.einsum("jrc,jqc->qrc", cj, ph)

    labels = np.concatenate([px, py])
    nx, n = len(px), len(labels)
    # A (nq, 2n, 2n) complex and eig's work arrays (about as large again)
    checks.memory("q, free_order", 2 * q.size * (2 * n) ** 2 * 16,
                  f"the quasi-periodic Hill matrices ({q.size} offsets of {2 * n} x {2 * n}, "
                  f"{d} free phases)")
    L = np.zeros((q.size, n, n), complex)
    L[:, :nx, :nx] = block(C["tt"], px, px)
    if coupled and len(py):
        L[:, :nx, nx:] = block(C["tU"], px, py)
        L[:, nx:, :nx] = block(C["Ut"], py, px)
        lap = -model.omega_longitudinal(q[:, None] + py[None, :, 0] * k) ** 2
        L[:, nx:, nx:] = lap[..., None] * np.eye(len(py))
    freq = labels[:, 0] * W + (labels[:, 1:] @ nu if d else 0.0)
    D = 1j * freq
    A = np.zeros((q.size, 2 * n, 2 * n), complex)
    i = np.arange(n)
    A[:, i, i] = D
    A[:, i, n + i] = 1.0
    A[:, n:, :n] = L
    A[:, n + i, n + i] = D
    return A, labels, nx, freq


def gain_spectrum_torus(torus, material, case, q, P, R, modes="sidebands", start=""):
    """Growth rates and labels of the modes of the quasi-periodic Hill matrices."""
    q = np.asarray(q, float).ravel()
    A, labels, nx, freq = hill_matrix(torus, material, case, q, P, R)
    lam, vec = np.linalg.eig(A)
    n = labels.shape[0]
    kin = np.abs(vec[:, n:, :]) ** 2  # velocities of each basis component, (nq, n, 2n)
    kin[:, :nx] /= 2 * material.alpha**2  # energy weights of eq. `norm`
    kin[:, nx:] *= 2
    total = kin.sum(axis=1)
    # a component (p, m) lives at wavenumber q + p k whatever m (the free phases are
    # uniform in the carrier's frame): theta at p = +1 and -1, any m, are the sidebands
    # k + q and k - q; a free wave pumping them shifts only their frequencies
    theta = np.arange(n) < nx
    with np.errstate(invalid="ignore", divide="ignore"):
        plus = kin[:, (labels[:, 0] == 1) & theta].sum(axis=1) / total
        minus = kin[:, (labels[:, 0] == -1) & theta].sum(axis=1) / total
    plus, minus = np.nan_to_num(plus), np.nan_to_num(minus)
    is_mi = ((plus + minus) > SIDEBAND_SHARE) & (np.minimum(plus, minus) > SIDEBAND_PRESENT)
    growth = lam.real if modes == "all" else np.where(is_mi, lam.real, 0.0)
    best = np.argmax(growth, axis=1)
    r = np.arange(q.size)
    sigma = growth[r, best]
    small = sigma < ROUNDOFF * torus.omega
    sigma = np.where(small, 0.0, sigma)
    dom = np.argmax(kin[r, :, best], axis=1)
    field = np.where(dom < nx, "theta", "U")
    wav = np.abs(np.mod(q + labels[dom, 0] * torus.k + np.pi, 2 * np.pi) - np.pi)
    fr = np.abs(lam[r, best].imag - freq[dom])
    field = np.where(small, "", field)
    zero_q = np.isclose(np.mod(q + np.pi, 2 * np.pi), np.pi, atol=1e-12, rtol=0)
    sigma[zero_q] = 0.0
    return GainSpectrum(q, sigma, field, wav, fr, is_mi[r, best] & ~small, start)


def torus_of_wave(wave) -> Torus:
    """A travelling wave as a torus with no free phase (d = 0): F[+-m] = c_m / 2 and its
    conjugate, c_m its complex harmonics."""
    P = 2 * wave.theta_harmonics.size
    F = {}
    for field, c in wave.complex_harmonics(P).items():
        F[field] = np.zeros((2 * P + 1, 1), complex)
        F[field][P + 1:, 0] = c / 2
        F[field][:P, 0] = np.conj(c[::-1]) / 2
    return Torus(wave.k, wave.omega, np.zeros(0), np.zeros((1, 0), int), F["theta"],
                 F["U"], 0.0, 0.0)
