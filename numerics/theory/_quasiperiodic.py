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

from generated import lattice_model as model

from ..lattice import checks
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
    offset : ndarray, shape (nq,)
        Sideband offsets from the carrier (rad per site); the sidebands are k +- offset.
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

    offset: np.ndarray
    sigma: np.ndarray
    field: np.ndarray
    wavenumber: np.ndarray
    frequency: np.ndarray
    sideband: np.ndarray
    start: str

    def to_xarray(self, **inputs):
        """The spectrum as an ``xarray.Dataset`` over ``offset``, units in the variables'
        attrs; ``inputs`` (material, case, k, amplitude: what it was computed for) go
        into the attrs (a Material as alpha, K_s, K_theta).

        Returns
        -------
        xarray.Dataset
        """
        import xarray as xr

        attrs = {"start": self.start}
        for key, v in inputs.items():
            if hasattr(v, "alpha") and hasattr(v, "K_theta"):
                attrs.update(alpha=v.alpha, K_s=v.K_s, K_theta=v.K_theta)
            else:
                attrs[key] = v
        return xr.Dataset(
            {"sigma": ("offset", self.sigma, {"long_name": "growth rate",
                                              "units": "1/T (lattice time)"}),
             "field": ("offset", self.field.astype(str), {"long_name": "field that grows"}),
             "wavenumber": ("offset", self.wavenumber,
                            {"long_name": "dominant wavenumber of the growing mode "
                                          "(absolute, folded into [0, pi])",
                             "units": "rad per site"}),
             "frequency": ("offset", self.frequency, {"long_name": "its lab frequency",
                                                      "units": "1/T"}),
             "sideband": ("offset", self.sideband, {"long_name": "an MI (sideband) mode"})},
            coords={"offset": ("offset", self.offset,
                               {"long_name": "sideband offset from the carrier k",
                                "units": "rad per site"})}, attrs=attrs)


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


def coupling_coefficients(fields, alpha, K_s, K_theta, axes):
    """Fourier coefficients of the linearised lattice's couplings, from the state on a grid.

    ``fields[(name, s)]`` ("theta" or "U", neighbour s = -1, 0, 1) holds the field at site
    n + s on a grid of the state's phases (``axes``: the phase axes of those arrays, the
    carrier's first). Returns name -> coefficients, with the phase axes replaced by their
    harmonic indices and a neighbour axis (j = -1, 0, +1) in front of them: d(acceleration)
    / d(field_{n+j}) of the generated Jacobian of eq. `norm`
    (``generated.lattice_model.jacobian``): "tt" (theta on theta), "tU", "Ut"."""
    J = model.jacobian(fields["U", -1], fields["U", 0], fields["U", 1], fields["theta", -1],
                       fields["theta", 0], fields["theta", 1], alpha, K_s, K_theta)
    # J[row, col]: rows (U, theta), cols (U_{n-1}, U_n, U_{n+1}, theta_{n-1}, theta_n,
    # theta_{n+1}); blocks over the offsets j = -1, 0, +1
    blocks = {"tt": J[1, 3:], "tU": J[1, :3], "Ut": J[0, 3:]}
    size = int(np.prod([fields["theta", 0].shape[a] for a in axes]))
    # neighbour axis (0 of each block) next to the phase axes, which shift by one
    ax = tuple(a + 1 for a in axes)
    out = {}
    for name, b in blocks.items():
        b = np.moveaxis(b, 0, ax[0] - 1) if ax[0] > 1 else b
        out[name] = np.fft.fftn(b, axes=ax) / size
    return out


def _coefficients(torus, material, Mp):
    """Torus Fourier coefficients of the Jacobian blocks: name -> (3, Mp, Mf, ..)."""
    d = torus.nu.size
    phi = 2 * np.pi * np.arange(Mp) / Mp
    psi = 2 * np.pi * np.arange(FREE_GRID) / FREE_GRID
    f = {(fld, s): torus.on_grid(fld, phi, psi, s) for fld in ("theta", "U") for s in (-1, 0, 1)}
    return coupling_coefficients(f, material.alpha, material.K_s, material.K_theta,
                                 tuple(range(d + 1)))


def hill_matrices(C, k, W, nu, q, px, py, coupled):
    """First-order Hill matrices of B states on tori (the one builder: a travelling wave
    is the torus with no free phase, d = 0).

    Parameters
    ----------
    C : dict name -> ndarray, shape (B, 3, Mp, Mf, .. (d times))
        The couplings' Fourier coefficients (:func:`coupling_coefficients`), carrier
        harmonics mod Mp, free harmonics mod Mf.
    k, W : ndarray, shape (B,)
        Carrier wavenumber and frequency; ``nu`` (B, d) the free frequencies.
    q : ndarray, shape (nq,) (common offsets) or (B, nq)
    px, py : ndarray, shape (nx, 1 + d), (ny, 1 + d)
        Labels (p, m) of the theta and U components (:func:`_labels`).

    Returns
    -------
    A : ndarray, shape (B, nq, 2n, 2n)
        The first-order form of (lambda - i (p W + m . nu))^2 X = L X.
    labels : ndarray, shape (n, 1 + d); theta first
    freq : ndarray, shape (B, n): p W + m . nu of each label
    """
    d = px.shape[1] - 1
    if not coupled:
        py = py[:0]
    B = k.size
    q2 = np.broadcast_to(q, (B, np.shape(q)[-1]))
    nq = q2.shape[1]
    shape = C["tt"].shape[2:]  # (Mp, Mf, ...)
    jj = np.array([-1.0, 0.0, 1.0])

    def block(c, rows, cols):
        # block[r, c] = sum_j c_{j, r - c} e^{i (q + p_c k) j}
        diff = rows[:, None, :] - cols[None, :, :]  # (nr, nc, 1 + d)
        idx = tuple(diff[..., a] % shape[a] for a in range(d + 1))
        cj = c[(slice(None), slice(None)) + idx]  # (B, 3, nr, nc)
        wav = q2[:, :, None] + cols[None, None, :, 0] * k[:, None, None]  # (B, nq, nc)
        ph = np.exp(1j * jj[None, :, None, None] * wav[:, None])  # (B, 3, nq, nc)
        return np.einsum("bjrc,bjqc->bqrc", cj, ph)

    labels = np.concatenate([px, py])
    nx, n = len(px), len(labels)
    L = np.zeros((B, nq, n, n), complex)
    L[:, :, :nx, :nx] = block(C["tt"], px, px)
    if coupled and len(py):
        L[:, :, :nx, nx:] = block(C["tU"], px, py)
        L[:, :, nx:, :nx] = block(C["Ut"], py, px)
        lap = -model.omega_longitudinal(q2[:, :, None] + py[None, None, :, 0]
                                        * k[:, None, None]) ** 2
        L[:, :, nx:, nx:] = lap[..., None] * np.eye(len(py))
    freq = labels[None, :, 0] * W[:, None] + (nu @ labels[:, 1:].T if d else 0.0)
    D = 1j * freq[:, None, :]  # (B, 1, n)
    A = np.zeros((B, nq, 2 * n, 2 * n), complex)
    i = np.arange(n)
    A[:, :, i, i] = D
    A[:, :, i, n + i] = 1.0
    A[:, :, n:, :n] = L
    A[:, :, n + i, n + i] = D
    return A, labels, freq


def kinetic(vec, nx, a2):
    """Kinetic energy of each basis component of eigenvectors ``vec`` (..., 2n, 2n):
    (..., n, 2n), with eq. `norm`'s weights theta_dot^2 / (2 alpha^2) (the first ``nx``
    components), 2 U_dot^2; ``a2`` = alpha^2, broadcastable against vec's leading axes."""
    n = vec.shape[-2] // 2
    kin = np.abs(vec[..., n:, :]) ** 2  # the components' lab velocities
    a2 = np.asarray(a2, float)
    kin[..., :nx, :] /= 2 * a2.reshape(a2.shape + (1,) * (kin.ndim - a2.ndim))
    kin[..., nx:, :] *= 2
    return kin


def sideband_shares(vec, labels, nx, a2):
    """Kinetic-energy shares of the sidebands k + q (theta at p = +1, any m) and k - q
    (p = -1) in each eigenvector: (..., 2n, 2) for eigenvectors ``vec`` (..., 2n, 2n).
    A component (p, m) lives at wavenumber q + p k whatever m (the free phases are uniform
    in the carrier's frame), so a free wave pumping the sidebands shifts only their
    frequencies."""
    kin = kinetic(vec, nx, a2)
    total = kin.sum(axis=-2)
    theta = np.arange(labels.shape[0]) < nx
    with np.errstate(invalid="ignore", divide="ignore"):
        share = np.stack([kin[..., (labels[:, 0] == p) & theta, :].sum(axis=-2) / total
                          for p in (1, -1)], axis=-1)
    return np.nan_to_num(share)


#: the harmonics |p| a kept mode of modes="all" is centred on (``off_centre``): theta's
#: sidebands p = +-1, U's mean and second harmonic p = 0, +-2
CENTRE = 2
#: and the most of its kinetic energy it may hold in the truncation's outermost
#: harmonics (theta |p| = P, U |p| = P + 1): a cut-off copy holds 1/2 there, a mode
#: centred at |p| <= 1 O(a^(P - 1))
EDGE_SHARE = 0.25


def off_centre(vec, labels, nx, a2, P):
    """Eigenvectors whose kinetic energy peaks at a harmonic |p| > CENTRE, or holds more
    than EDGE_SHARE at the truncation's edge (for P >= 3; at P = 1 the edge is the
    sidebands themselves): (..., 2n) bool for ``vec`` (..., 2n, 2n). Such a mode is a
    relabelled copy (q -> q - j k, p -> p + j) of one centred at |p| <= CENTRE, which lies
    at another offset of (0, pi] (sigma(-q) = sigma(q)), so no physical mode is lost; near
    the edge the copy is cut off on one side and wrong: the carrier's neutral pair
    (p = -1, 1 at q = 0) copied to (P - 2, P) at q = -(P - 1) k read a growth of 3.1e-3 at
    the blue point, case I, a = 0.1, at every truncation P, where q = 0 is neutral and a
    run of the wave stays flat (probe 99; the model engine keeps modes centred at
    |l| <= 1 alike)."""
    kin = kinetic(vec, nx, a2)
    p = np.abs(labels[:, 0])
    out = p[np.argmax(kin, axis=-2)] > CENTRE
    if P >= 3:
        edge = np.where(np.arange(p.size) < nx, p == P, p == P + 1)
        with np.errstate(invalid="ignore", divide="ignore"):
            share = np.nan_to_num(kin[..., edge, :].sum(axis=-2) / kin.sum(axis=-2))
        out |= share > EDGE_SHARE
    return out


def is_mi(share):
    """MI modes hold nearly all their energy in the two sidebands, both present (the
    relabelled copy of a mode at q - 2k holds about half, in p = -1 and p = -3 only)."""
    return (share.sum(axis=-1) > SIDEBAND_SHARE) & (share.min(axis=-1) > SIDEBAND_PRESENT)


def neutral_offsets(q):
    """q = 0 (mod 2 pi): a shift of the state's phase, amplitude or U, neutral; a Jordan
    block whose eigenvalues round-off splits by ~sqrt(machine eps), so no growth."""
    return np.isclose(np.mod(np.asarray(q) + np.pi, 2 * np.pi), np.pi, atol=1e-12, rtol=0)


def hill_matrix(torus, material, case, q, P, R):
    """First-order quasi-periodic Hill matrices (nq, 2n, 2n) and the basis labels
    (n, 1 + d): columns p, m_1 .. m_d; the first ``nx`` labels are theta."""
    d = torus.nu.size
    px, py = _labels(P, R, d)
    q = np.asarray(q, float).ravel()
    n = len(px) + (len(py) if case == "coupled" else 0)
    # A (nq, 2n, 2n) complex and eig's work arrays (about as large again)
    checks.memory("q, free_order", 2 * q.size * (2 * n) ** 2 * 16,
                  f"the quasi-periodic Hill matrices ({q.size} offsets of {2 * n} x {2 * n}, "
                  f"{d} free phases)")
    C = _coefficients(torus, material, max(64, 4 * (2 * P + 2)))
    A, labels, freq = hill_matrices({n: c[None] for n, c in C.items()}, np.array([torus.k]),
                                    np.array([torus.omega]), np.asarray(torus.nu)[None],
                                    q, px, py, case == "coupled")
    return A[0], labels, len(px), freq[0]


def gain_spectrum_torus(torus, material, case, q, P, R, modes="sidebands", start=""):
    """Growth rates and labels of the modes of the quasi-periodic Hill matrices."""
    q = np.asarray(q, float).ravel()
    A, labels, nx, freq = hill_matrix(torus, material, case, q, P, R)
    lam, vec = np.linalg.eig(A)
    kin = kinetic(vec, nx, material.alpha**2)  # (nq, n, 2n)
    mi = is_mi(sideband_shares(vec, labels, nx, material.alpha**2))
    if modes == "all":  # every mode centred at |p| <= CENTRE (``off_centre``)
        growth = np.where(off_centre(vec, labels, nx, material.alpha**2, P), 0.0,
                          lam.real)
    else:
        growth = np.where(mi, lam.real, 0.0)
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
    sigma[neutral_offsets(q)] = 0.0
    return GainSpectrum(q, sigma, field, wav, fr, mi[r, best] & ~small, start)


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
