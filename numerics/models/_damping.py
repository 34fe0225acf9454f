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

    from ._linear import dynamical_matrix

    S, Bd = model.damping
    d = model.n_fields
    minv = 1 / np.asarray(model.masses, float)
    if not (Bd[:d, d:].any() or Bd[d:, :d].any()):
        return None, expm(-h * minv[:, None] * (S + Bd[:d, :d] + Bd[d:, d:]))
    kap = 2 * math.pi * np.arange(N) / N
    # C(kappa) of ``damping_matrix`` from one read of the (checked) matrices, every
    # exponential in one batched call (the same as one call each)
    C = np.array([S.astype(complex) + dynamical_matrix(Bd, q) for q in kap])
    E = expm(-h * minv[None, :, None] * C)
    K = np.real(np.fft.ifft(E, axis=0))  # K[r]: offset r mod N
    size = np.max(np.abs(K), axis=(1, 2))
    r = np.arange(N)
    dist = np.minimum(r, N - r)
    kept = size > 1e-15 * size.max()
    # a damping whose flow over h underflows to 0 everywhere (gamma h ~ 1e3: the velocities
    # are gone by the half step) keeps offset 0 alone, zeros (probe 98: gamma 1e4 raised
    # numpy's 'zero-size array to reduction operation maximum')
    R = int(np.max(dist[kept])) if kept.any() else 0
    keep = dist <= R
    return (np.ascontiguousarray(r[keep].astype(np.int64)), np.ascontiguousarray(K[keep])), None


def rayleigh(model: Model, v: np.ndarray, matrices=None) -> float:
    """R of a ring's velocities (d, N): sum over cells of the site and bond functions.
    ``matrices``: ``model.damping`` where already read (a run's records: reading it
    checks them again, an eigenvalue problem each)."""
    S, Bd = model.damping if matrices is None else matrices
    vn = np.concatenate([v, np.roll(v, -1, axis=1)])
    return float(0.5 * (np.einsum("an,ab,bn->", v, S, v) + np.einsum("an,ab,bn->", vn, Bd,
                                                                      vn)))


#: a damped run's samples of 2R (``simulate_model``'s energy balance) are at most
#: LOSS_DECAY / (the damping's fastest rate) apart, besides ``LOSS_SAMPLE`` radians of the
#: carrier: a strong damping's 2R falls as a sum of exponentials (an overdamped pair: two
#: rates), which one exponential through two samples far apart misreads. Probe 96, balance
#: errors from samples 8 radians apart, then at most 0.1 / rate apart (a sample every step
#: where that is shorter than the step): Klein-Gordon gamma 0.5, 5.0e-3 -> 1.8e-4; gamma 3
#: (overdamped at k 1) 0.099 -> 0.011 (0.72 -> 0.01 on a point's T = 5000); FPUT bond
#: damping eta 1, 0.16 -> 0.012; a mass-in-mass dashpot c 1, 0.046 -> 0.020 (the last
#: three limited by the step: dt 0.01-0.02 reads 2e-4). A rate below ~omega / 80 keeps
#: the 8 radians (every run of the tests and docs).
LOSS_DECAY = 0.1


def loss_spacing(model: Model, N: int) -> float:
    """The most time between two samples of 2R: LOSS_DECAY over the fastest rate of the
    damping alone, the largest eigenvalue of M^-1/2 C(kappa) M^-1/2 over the ring's
    wavenumbers (inf where nothing is damped)."""
    from ._linear import damping_matrices

    s = 1 / np.sqrt(np.asarray(model.masses, float))
    C = damping_matrices(model, 2 * math.pi * np.arange(N) / N)
    top = float(np.max(np.linalg.eigvalsh(C * s[None, :, None] * s[None, None, :])))
    return LOSS_DECAY / top if top > 0 else math.inf
