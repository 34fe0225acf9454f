"""The travelling wave's collocation equations (``_wave._solve``), set up once per layout.

A damped point (issue 42) solves the wave of one carrier at several amplitudes, each from
a near start in two Newton steps: most of such a solve was its set-up (the carrier, the
acoustic directions, the grid's phase tables) and each call's assembly. Here the tables
that depend on the layout alone (fields, H, k, the carrier field, the acoustic
directions; not the amplitude, not the model's parameters) are built once and kept
(least recently used), and the residual and its Jacobian are ``_wave._solve``'s,
operation for operation, with fewer calls. The solve keeps the start's Jacobian
(``chord_newton``: one Jacobian and its pseudo-inverse a wave instead of two Jacobians
and two least-squares solves): the same wave as ``_solve``'s to round-off (6e-14 of the
amplitude for flexmm, 1e-16 for one field; tests/test_models_exact.py), which may name
the other of two ring offsets that tie to round-off at a damped point (either is right:
tests/test_dissipation.py).
"""

from __future__ import annotations

import functools

import numpy as np


class Collocation:
    """The phase tables of one layout (module docstring): the grid xi (M points), the
    harmonics h = -H..H, E = e^{-i h xi} / M (the projection), B0 = e^{i h xi} and Bp, Bm
    at xi +- k, the DFT's index table of the Jacobian and its phases e^{i h k}."""

    def __init__(self, d, H, k, field, optical, free):
        M = max(64, 4 * H + 8)
        xi = 2 * np.pi * np.arange(M) / M
        h = np.arange(-H, H + 1)
        self.d, self.H, self.M, self.k, self.field = d, H, M, k, field
        self.optical, self.free, self.n_opt, self.h = optical, free, optical.shape[1], h
        # ``_wave._solve``'s expressions, evaluated once
        self.E = np.exp(-1j * h[:, None] * xi[None, :]) / M
        self.B0 = np.exp(1j * h[:, None] * xi[None, :])
        self.Bp = self.B0 * np.exp(1j * h * k)[:, None]
        self.Bm = self.B0 * np.exp(-1j * h * k)[:, None]
        self.sidx = (h[:, None] - h[None, :]) % M
        self.ph = np.exp(1j * h * k)[None, :, None, None]
        # a cell's fields at (n, n + 1) and at (n - 1, n) side by side, (2d, 2M): the cell
        # functions in one call each (elementwise: the same values as two calls)
        self.B_cell = np.concatenate([self.B0, self.Bm], axis=1)
        self.B_next = np.concatenate([self.Bp, self.B0], axis=1)
        for arr in (self.E, self.B0, self.Bp, self.Bm, self.sidx, self.ph, optical, free,
                    self.B_cell, self.B_next):
            arr.flags.writeable = False

    def equations(self, model, masses, a, scale):
        """(residual(x), jacobian(x)) of ``_wave._solve`` at amplitude a and ``scale``,
        the same values. ``residual`` keeps its last value in ``last`` (the caller's check
        of a converged x reads it instead of computing it again)."""
        d, M, H, h = self.d, self.M, self.H, self.h
        optical, n_opt, free, field = self.optical, self.n_opt, self.free, self.field
        B0, E, sidx, ph = self.B0, self.E, self.sidx, self.ph
        B_cell, B_next = self.B_cell, self.B_next
        code, p = model.code, model.p
        g = np.empty((2 * d, 2 * M))
        Hc = np.empty((2 * d, 2 * d, 2 * M))
        m2 = -(h**2)
        h2 = h**2
        diag = np.arange(2 * H + 1)
        mdiag = np.diag(masses)[None]
        m_col = masses[:, None]
        fixed = (a / 2, 0.0)

        def unpack(x):
            parts = np.zeros((d, H, 2))
            parts[free] = x[1 + n_opt:]
            parts[field, 0] = fixed
            c = np.zeros((d, 2 * H + 1), complex)
            c[:, H] = optical @ x[1:1 + n_opt]
            c[:, H + 1:] = parts[..., 0] + 1j * parts[..., 1]
            c[:, :H] = np.conj(c[:, H + 1:][:, ::-1])
            return c

        # np.tensordot(optical.T, X, axes=1) is this dot (numpy's own reshapes), without
        # its argument handling
        opt_t = optical.T.reshape(n_opt, d)

        def mean_rows(X):
            # the optical means' equations (none without optical directions: no call)
            if not n_opt:
                return []
            return [np.real(np.dot(opt_t, X.reshape(d, -1)).reshape((n_opt,) + X.shape[1:]))]

        # Newton asks the Jacobian at the x whose residual it just computed: the
        # coefficients and fields of that x are kept for it (the same values)
        at = [None, None, None]

        def fields(c):
            # columns :M the cell (n, n + 1), M: the cell (n - 1, n), on the grid
            return np.concatenate([np.real(c @ B_cell), np.real(c @ B_next)])

        def residual(x):
            omega, c = x[0], unpack(x)
            U = fields(c)
            at[:] = [x.copy(), c, U]
            code.cell_gradient_into(U, p, g)
            R = m_col * omega**2 * np.real((c * m2) @ B0) + g[:d, :M] + g[d:, M:]
            R_hat = R @ E.T
            pos = R_hat[:, H + 1:]
            out = np.concatenate(mean_rows(R_hat[:, H]) + [np.real(pos).reshape(-1),
                                                           np.imag(pos).reshape(-1)]) / scale
            residual.last = out
            return out

        def jacobian(x):
            omega = x[0]
            if at[0] is not None and np.array_equal(at[0], x):
                c, U = at[1:]
            else:
                c = unpack(x)
                U = fields(c)
            code.cell_hessian_into(U, p, Hc)
            F = np.fft.fft(Hc.reshape(2 * d, 2 * d, 2, M), axis=-1) / M
            Ff, Fb = F[:, :, 0], F[:, :, 1]
            Fs, Bs = Ff[..., sidx], Fb[..., sidx]                   # (2d, 2d, l, h)
            J = (Fs[:d, :d] + Bs[d:, d:]).transpose(2, 3, 0, 1) \
                + Fs[:d, d:].transpose(2, 3, 0, 1) * ph \
                + Bs[d:, :d].transpose(2, 3, 0, 1) / ph                # (l, h, j, b)
            J[diag, diag] -= (h2 * omega**2)[:, None, None] * mdiag
            J = J.transpose(2, 0, 3, 1)                               # (j, l, b, h)
            Jp, Jm = J[..., H + 1:], J[..., H - 1::-1]
            parts = np.stack([Jp + Jm, 1j * (Jp - Jm)], axis=-1)[:, :, free]
            dw = -2 * omega * m_col * h2 * c                          # d/d omega
            blocks = [dw[..., None]]
            if n_opt:
                Jh = J[:, :, :, H]                                    # (j, l, b)
                blocks.append(np.dot(Jh.reshape(-1, d), optical).reshape(
                    Jh.shape[:2] + (n_opt,)))  # np.tensordot(Jh, optical, axes=1)
            blocks.append(parts)
            X = np.concatenate(blocks, axis=-1)                       # (j, l, unknowns)
            pos = X[:, H + 1:]
            rows = [np.real(pos).reshape(-1, X.shape[-1]), np.imag(pos).reshape(-1, X.shape[-1])]
            if n_opt:  # each block's means as ``_solve`` forms them
                rows.insert(0, np.concatenate(
                    [mean_rows(dw[:, H])[0][:, None]]
                    + [mean_rows(b[:, H])[0] for b in blocks[1:]], axis=1))
            return np.concatenate(rows) / scale

        residual.last = None
        return residual, jacobian


def chord_newton(residual, jacobian, x0, steps=12):
    """Newton's method with the start's Jacobian kept (the chord method): the lower
    amplitudes of a damped point start from the last wave scaled, ~1e-5 of their
    residual's scale away, where the chord converges linearly at a rate of that order, so
    one Jacobian and its pseudo-inverse serve every step (Newton took two Jacobians and
    two least-squares solves for the same round-off). Stops as ``_wave._gauss_newton``:
    a residual below 1e-14, or one that no longer falls by 4 once below 1e-11 (round-off);
    None where it does not converge so (the caller solves by Gauss-Newton instead)."""
    x = x0.copy()
    r = residual(x)
    best = float(np.max(np.abs(r)))
    if not np.isfinite(best):
        return None
    if best < 1e-14:
        return x
    step = np.linalg.pinv(jacobian(x))  # the least-squares solution of each step
    for _ in range(steps):
        x = x - step @ r
        r = residual(x)
        now = float(np.max(np.abs(r)))
        if not np.isfinite(now):
            return None
        if now < 1e-14:
            return x
        if now >= best / 4:  # round-off, or too far for the chord
            return x if best < 1e-11 and now < 2 * best else None
        best = now
    return None


@functools.lru_cache(maxsize=64)
def _cached(d, H, k, field, optical_bytes, n_opt, free_bytes):
    optical = np.frombuffer(optical_bytes).reshape(d, n_opt).copy()
    free = np.frombuffer(free_bytes, dtype=bool).reshape(d, H, 2).copy()
    return Collocation(d, H, k, field, optical, free)


def collocation(d, H, k, field, optical, free) -> Collocation:
    """The layout's ``Collocation``, built once (the 64 latest kept; lru_cache is thread
    safe, and a kept one is read only)."""
    optical = np.ascontiguousarray(optical, dtype=float)
    free = np.ascontiguousarray(free, dtype=bool)
    return _cached(int(d), int(H), float(k), int(field), optical.tobytes(),
                   int(optical.shape[1]), free.tobytes())
