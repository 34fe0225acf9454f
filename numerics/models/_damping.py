"""The damping of a lossy model's runs (a Rayleigh function R beside the energy): the
exact flow of its linear part (the Strang splitting's half steps around a symplectic step,
``numerics.lattice.local_flow`` / ``band_flow``) and the power it takes, 2 R."""

from __future__ import annotations

import math

import numpy as np

from energy import Model


def damping_flow(model: Model, N: int, h: float):
    """The exact flow of dv/dt = -M^-1 C v over time h on a ring of N sites: where the
    damping is site-local, (None, E) with E = expm(-h M^-1 C) (d, d); else ((offs, K),
    None), the flow as a circulant convolution v_n <- sum_i K_i v_{n - offs_i}: K is the
    ring's inverse FFT of E_j = expm(-h M^-1 C(2 pi j / N)), kept where it exceeds 1e-15
    of its largest entry (exp of a banded matrix of small norm: a few sites each side)."""
    from scipy.linalg import expm

    from ._linear import damping_matrix

    S, Bd = model.damping
    d = model.n_fields
    minv = 1 / np.asarray(model.masses, float)
    if not (Bd[:d, d:].any() or Bd[d:, :d].any()):
        return None, expm(-h * minv[:, None] * (S + Bd[:d, :d] + Bd[d:, d:]))
    kap = 2 * math.pi * np.arange(N) / N
    E = np.array([expm(-h * minv[:, None] * damping_matrix(model, q)) for q in kap])
    K = np.real(np.fft.ifft(E, axis=0))  # K[r]: offset r mod N
    size = np.max(np.abs(K), axis=(1, 2))
    r = np.arange(N)
    dist = np.minimum(r, N - r)
    R = int(np.max(dist[size > 1e-15 * size.max()]))
    keep = dist <= R
    return (np.ascontiguousarray(r[keep].astype(np.int64)), np.ascontiguousarray(K[keep])), None


def rayleigh(model: Model, v: np.ndarray) -> float:
    """R of a ring's velocities (d, N): sum over cells of the site and bond functions."""
    S, Bd = model.damping
    vn = np.concatenate([v, np.roll(v, -1, axis=1)])
    return float(0.5 * (np.einsum("an,ab,bn->", v, S, v) + np.einsum("an,ab,bn->", vn, Bd,
                                                                      vn)))
