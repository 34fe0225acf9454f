"""The four-wave theory's rates at a lower carrier amplitude, from its rates at a0
(issue 42, ``four_wave_amplification``).

In the four-wave kernel (``_fourwave_kernel``) the wave's harmonics scale exactly as x1 ~ a,
x2, x0 ~ a^2, its frequency as Omega = omega - g2 a^2 / 4, and the driven waves'
operators D_l do not depend on a (their frequencies are the pair's and the carrier's
linear ones). So the cross-phase shifts S_j and the couplings C_ij are ~ a^2, and with
s = (a / a0)^2 each pair's

    detuning  Delta'(s) = Delta_0 + s (Delta'(a0) - Delta_0),
    coupling  kappa12 kappa21 (s) = s^2 kappa12 kappa21 (a0),
    rate      sigma(s) = |Im sqrt(Delta'(s)^2 / 4 - kappa12 kappa21 (s))|,

Delta_0 = omega1 + omega2 - 2 omega the linear detuning: the kernel at a equals its
polynomial in a^2 to round-off, and no kernel is computed at the lower amplitudes. A
pair that is not resonant at a0 is not at a < a0 (the driven waves' sizes are ~ a).
"""

from __future__ import annotations

import numpy as np

#: kappa12 kappa21 is real and positive (|kappa|^2) where coupling^2 equals
#: sigma^2 + Delta'^2 / 4 to this share: the closed form holds (else the kernel per a)
REAL_COUPLING = 1e-8


def rates_at(model, first, rows, branch_pairs):
    """A function s -> the rates of the pairs (``first.offsets[rows]``, branch pairs
    ``branch_pairs`` (index into ``first.pairs``)) at s = (a / a0)^2; None where the
    pairs' coupling is not real and positive (then the kernel is needed at each a)."""
    from ._fourwave_kernel import FLOOR

    rate0 = np.asarray(first.rates, float)[rows, branch_pairs]
    det0 = np.asarray(first.detuning, float)[rows, branch_pairs]
    # a growing pair's kappa12 kappa21 = sigma^2 + Delta'^2 / 4 where it is real; checked
    # against the coupling where the pair clearly grows (a rate of round-off is no growth)
    kk0 = rate0**2 + det0**2 / 4
    grows = rate0 > 1e-6 * np.max(rate0, initial=0.0)
    coupling2 = np.asarray(first.coupling, float)[rows, branch_pairs] ** 2
    if not np.all(np.abs(kk0 - coupling2)[grows] <= REAL_COUPLING * kk0[grows]):
        return None
    q = np.asarray(first.offsets, float)[rows]
    pairs = np.asarray(first.pairs, int).reshape(-1, 2)[np.asarray(branch_pairs, int)]
    # both waves' frequencies in one batched call (each matrix's own eigenvalues: the same
    # numbers as two calls)
    both = _frequencies(model, np.concatenate([q + first.k, first.k - q]))
    w1 = both[np.arange(q.size), pairs[:, 0]]
    w2 = both[q.size + np.arange(q.size), pairs[:, 1]]
    lin = w1 + w2 - 2 * first.omega

    def at(s):
        delta = lin + s * (det0 - lin)
        kk = s * s * kk0
        disc = delta**2 / 4 - kk
        sig = np.sqrt(np.maximum(-disc, 0.0))
        # a pair at the edge of its band: the discriminant is round-off (``_rates``)
        sig[np.abs(disc) <= FLOOR * np.maximum(kk, delta**2 / 4)] = 0.0
        return sig

    return at


def _frequencies(model, kap):
    """omega_b(kappa) of every branch at each kappa, ascending (``_rates``' modes: one
    batched eigenvalue call)."""
    H = model.code.taylor(model.p)[0]
    m = np.asarray(model.masses, float)
    d = m.size
    s = 1 / np.sqrt(m)
    z = np.exp(1j * kap)[:, None, None]
    K = (H[:d, :d] + H[d:, d:]) + H[:d, d:] * z + H[d:, :d] / z
    A = s[None, :, None] * K * s[None, None, :]
    # one field: a 1 x 1 Hermitian matrix's eigenvalue is its diagonal's real part (what
    # LAPACK's zheevd returns for it, without the batched call)
    lam = np.real(A[:, :, 0]) if d == 1 else np.linalg.eigvalsh(A)
    with np.errstate(invalid="ignore"):
        return np.where(lam >= 0, np.sqrt(np.abs(lam)), np.nan)
