"""The Hill pencil's dense eigenproblem per offset: the reference the compiled path of
``_exact`` (``_sidebands``, ``_strong``) equals, and its fallback where that path does not
settle; and the sideband offset a kept mode names (its weights near the carrier's
copies). Split from ``_exact`` (its module docstring has the pencil)."""

from __future__ import annotations

import math

import numpy as np

from ._exact import GAIN_FLOOR, PERSIST_STEP, HillSpectrum, _centre, _hessian_harmonics
from ._wave import _wrap

#: sqrt(machine epsilon): how far eig splits a near-double eigenvalue, relative to the
#: matrix's scale (``_DensePencil.resolved``)
RESOLUTION = math.sqrt(np.finfo(float).eps)
#: a dense rate below that counts where it is this many times its first-order error
#: (``_DensePencil.resolved``: 2.2x for the artefact measured, 2.8e6x for the real rate)
COND_MARGIN = 10.0


def _sideband_offsets(q, l_, k, w_best):
    """``_sideband_offset`` of many offsets q (shape (m,)) at once, w_best (m, 2P + 1)."""
    kap = q[:, None] + l_[None, :] * k
    dist = np.minimum(_wrap(kap - k), _wrap(kap + k))
    near = dist <= np.pi / 4
    side = np.where(near, w_best, 0).sum(axis=1) >= 0.1 * w_best.sum(axis=1)
    j = np.argmax(np.where(near, w_best, -np.inf), axis=1)
    out = dist[np.arange(q.size), j]
    return np.where(side & near.any(axis=1), out, math.nan)


def _sideband_offset(q, l_, k, w_best):
    kap = q + l_ * k
    dist = np.minimum(_wrap(kap - k), _wrap(kap + k))
    near = dist <= np.pi / 4
    side = w_best[near].sum() >= 0.1 * w_best.sum()
    return float(dist[near][np.argmax(w_best[near])]) if side else math.nan


class _DensePencil:
    """What both dense paths build from the wave at truncation P: the harmonics, the
    masses, the rate floor, and per offset q the scaled-free stiffness L(q) (n x n, the
    cell Hessian's Fourier blocks: ``_exact``'s module docstring)."""

    def __init__(self, wave, P):
        model = wave.model
        self.d = d = model.n_fields
        self.k, self.omega = wave.k, wave.omega
        self.Hh = _hessian_harmonics(wave, P)
        self.l_ = l_ = np.arange(-P, P + 1)
        self.n = d * (2 * P + 1)
        self.m = np.tile(np.asarray(model.masses, float), 2 * P + 1)
        self.Minv = 1 / self.m
        self.ll = np.repeat(l_, d)
        self.floor = GAIN_FLOOR * max(self.omega, 1e-300)
        self._diff = l_[:, None] - l_[None, :] + 2 * P
        self._back = np.exp(-1j * (l_[:, None] - l_[None, :]) * self.k)[..., None, None]

    def resolved(self, A, lam, j, x=None, lu=None) -> bool:
        """Whether eig resolves the rate of eigenvalue ``lam[j]`` of the linearisation ``A``
        (its right eigenvector ``x`` and the LU of A - lam I shifted, ``_dense_growing``'s,
        where known): above the floor, and either above
        2 sqrt(eps) max |lambda| (eig splits a near-double eigenvalue by ~sqrt(eps) times
        the pencil's scale, however ill-conditioned) or above COND_MARGIN times its own
        first-order error eps ||A||_F kappa, kappa = |x| |y| / |y^H x| (y its left
        eigenvector, by inverse iteration on A^H).

        Probe 98: a diatomic-fput ring of 128 (m 2.58, alpha -0.29, beta 0.65, k 0.056,
        a 0.027, omega 0.018) went dense at P = 36 and read 2.85e-8 = 1.6e-6 omega at one
        offset, 5x the carrier-relative floor: kappa 1.9e7 (a pair colliding on the
        axis), its error estimate 1.3e-8, and 0 in an independent pencil. A real rate of
        the same size (m 2.58, alpha 0, beta 1, k 0.056, a 0.09: 4.97e-8, the compiled
        path's to 7 digits and ~a^2) has kappa 27, error 2e-14: kept (a cut at
        2 sqrt(eps) max |lambda| alone, 5e-8, dropped it: review of this change). Only the
        dense paths: the compiled ones solve small clusters by Newton."""
        rate = float(lam[j].real)
        if not rate > self.floor:
            return False
        if rate >= 2 * RESOLUTION * float(np.max(np.abs(lam))):
            return True
        from scipy.linalg import lu_factor, lu_solve

        size = A.shape[0]
        if lu is None:
            shift = lam[j] + 1e-13 * (abs(lam[j]) + self.omega)
            lu = lu_factor(A - shift * np.eye(size), check_finite=False)
        b = np.random.default_rng(1).standard_normal(size) + 0j
        if x is None:
            x = lu_solve(lu, b, check_finite=False)
            x = lu_solve(lu, x / np.max(np.abs(x)), check_finite=False)
        y = lu_solve(lu, b, trans=2, check_finite=False)
        y = lu_solve(lu, y / np.max(np.abs(y)), trans=2, check_finite=False)
        kappa = np.linalg.norm(x) * np.linalg.norm(y) / max(abs(np.vdot(y, x)), 1e-300)
        error = np.finfo(float).eps * float(np.linalg.norm(A)) * kappa
        return rate > COND_MARGIN * error

    def linearisation(self, q) -> np.ndarray:
        """The lossless pencil's first-order form at offset q, 2n x 2n: its eigenvalues
        are the Hill spectrum's."""
        n, omega, ll, m = self.n, self.omega, self.ll, self.m
        A = np.zeros((2 * n, 2 * n), complex)
        A[:n, n:] = np.eye(n)
        A[n:, :n] = -self.Minv[:, None] * (self.stiffness(q) - np.diag(ll**2 * omega**2 * m))
        A[n:, n:] = np.diag(2j * omega * ll)
        return A

    def stiffness(self, q):
        """L(q): block (l, h) = A + B e^{i th_h} + C e^{-i th_l} + D e^{-i (l - h) k}."""
        d, l_ = self.d, self.l_
        ph = np.exp(1j * (q + l_ * self.k))[None, :, None, None]  # per column harmonic h
        S = self.Hh[self._diff]                                     # (l, h, 2d, 2d)
        Sb = S * self._back
        blk = (S[..., :d, :d] + S[..., :d, d:] * ph + Sb[..., d:, :d] / ph
               + Sb[..., d:, d:])                                  # (l, h, d, d)
        return blk.transpose(0, 2, 1, 3).reshape(self.n, self.n)


def _dense_growing(wave, offsets, P):
    """The compiled path's fallback: the dense eigenvalues (``eigvals``, no vectors) at
    each offset, then the eigenvectors of the growing ones only, fastest first (inverse
    iteration on the linearisation), until one is kept by the dense spectrum's rule: the
    same rate, harmonic and sideband offset at ~60% of ``eig``'s cost (flexmm, P = 10)."""
    from scipy.linalg import lu_factor, lu_solve

    pencil = _DensePencil(wave, P)
    d, k, omega, l_, n = pencil.d, pencil.k, pencil.omega, pencil.l_, pencil.n
    gains = np.zeros(offsets.size)
    modes = np.zeros(offsets.size, int)
    offs = np.full(offsets.size, math.nan)
    b = np.random.default_rng(0).standard_normal(2 * n) + 0j  # inverse iteration's start
    for i, q in enumerate(offsets):
        A = pencil.linearisation(q)
        lam = np.linalg.eigvals(A)
        for j in np.argsort(-lam.real):
            if not lam[j].real > pencil.floor:
                break
            # A - lam I is singular to round-off: two solves give its null vector
            shift = lam[j] + 1e-13 * (abs(lam[j]) + omega)
            lu = lu_factor(A - shift * np.eye(2 * n), check_finite=False)
            x = lu_solve(lu, b, check_finite=False)
            x = lu_solve(lu, x / np.max(np.abs(x)), check_finite=False)
            c = np.abs(x[:n]) ** 2
            per_l = (c / max(c.sum(), 1e-300)).reshape(2 * P + 1, d).sum(axis=1)
            centre, central = _centre(per_l, l_)
            if not central or per_l[:3].sum() + per_l[-3:].sum() >= 1e-6:
                continue
            if not pencil.resolved(A, lam, j, x, lu):
                continue  # round-off of a pair on the axis: the next one
            gains[i] = lam[j].real
            modes[i] = int(centre)
            offs[i] = _sideband_offset(q, l_, k, per_l)
            break
    return HillSpectrum(wave=wave, offsets=offsets, gain=gains, harmonic=modes,
                        sideband_offset=offs, truncations=(P,))


def _dense_spectrum(wave, offsets, P, return_eigenvalues):
    """The Hill pencil's whole spectrum per offset (numpy.linalg.eig of its 2 n x 2 n
    linearisation): the reference the compiled path equals, and its fallback."""
    pencil = _DensePencil(wave, P)
    d, k, omega, l_, n = pencil.d, pencil.k, pencil.omega, pencil.l_, pencil.n
    m, Minv, ll = pencil.m, pencil.Minv, pencil.ll
    gains, modes, lams, offs = [], [], [], []
    outer = np.zeros((2 * P + 1, d), bool)
    outer[:3] = outer[-3:] = True
    outer = outer.ravel()
    for q in offsets:
        L = pencil.stiffness(q)
        K0 = L - np.diag(ll**2 * omega**2 * m)
        B = np.diag(-2j * omega * ll * m)
        A = np.zeros((2 * n, 2 * n), complex)
        A[:n, n:] = np.eye(n)
        A[n:, :n] = -Minv[:, None] * K0
        A[n:, n:] = -Minv[:, None] * B
        lam, vec = np.linalg.eig(A)
        c = np.abs(vec[:n]) ** 2
        weight = c / np.maximum(c.sum(axis=0), 1e-300)
        per_l = weight.reshape(2 * P + 1, d, -1).sum(axis=1)
        centre, central = _centre(per_l.T, l_)
        resolved = central & (weight[outer].sum(axis=0) < 1e-6)
        re = np.where(resolved, lam.real, -np.inf)
        # the fastest kept mode eig resolves (``_DensePencil.resolved``); where none, 0
        for j in np.argsort(-re):
            if not re[j] > pencil.floor or pencil.resolved(A, lam, j, vec[:, j]):
                break
            re[j] = -np.inf  # round-off of a pair on the axis
        best = int(np.argmax(re))
        gains.append(float(re[best]) if re[best] > pencil.floor else 0.0)
        modes.append(int(centre[best]))
        kap = q + l_ * k
        dist = np.minimum(_wrap(kap - k), _wrap(kap + k))
        near = dist <= np.pi / 4
        w_best = per_l[:, best]
        side = w_best[near].sum() >= 0.1 * w_best.sum()
        offs.append(float(dist[near][np.argmax(w_best[near])]) if side else math.nan)
        if return_eigenvalues:
            lams.append(lam[resolved])
    spec = HillSpectrum(wave=wave, offsets=offsets, gain=np.array(gains),
                        harmonic=np.array(modes, int), sideband_offset=np.array(offs),
                        truncations=(P,))
    return (spec, lams) if return_eigenvalues else spec


def not_converged(spec: HillSpectrum) -> str | None:
    """A sentence where ``spec``'s fastest mode moves with the Hill truncation, else None
    (CONVENTIONS.md: a mode counts when it persists at the same q across truncations).

    ``exact_gain`` checks the compiled path's peak at P + PERSIST_STEP; where it moves, the
    spectrum is the dense one at the wave's H + 4, named by that one truncation. That
    peak is checked here at H + 4 + PERSIST_STEP (one dense offset): where it moves by
    more than 1e-6 relative, the rate is not converged. Measured: a Hertz contact past its
    opening (probe 97, k 2 pi 20 / 64, a 0.5: a force with a kink, whose Hessian's
    harmonics fall as 1 / l) gave 1.4e-3, 6.8e-4, 4.8e-4, 5.5e-4 at 20, 36, 40, 80
    harmonics, its run 1.4e-3."""
    if spec.peak_gain <= 0 or len(spec.truncations) != 1:
        return None
    P = spec.truncations[0]
    i = int(np.argmax(spec.gain))
    again = _dense_spectrum(spec.wave, spec.offsets[i:i + 1], P + PERSIST_STEP, False)
    if abs(again.gain[0] - spec.gain[i]) <= 1e-6 * spec.gain[i]:
        return None
    return (f"the exact lattice theory's fastest mode moves with the Hill truncation (rate "
            f"{spec.gain[i]:.4g} at {P} harmonics, {again.gain[0]:.4g} at "
            f"{P + PERSIST_STEP}): its rate is not converged (a force with a kink, such as "
            "a contact that opens, converges slowly); a run decides")
