"""The travelling wave's collocation equations (``_wave_solve._solve``), set up once per layout.

A damped point (issue 42) solves the wave of one carrier at several amplitudes, each from
a near start in two Newton steps: most of such a solve was its set-up (the carrier, the
acoustic directions, the grid's phase tables) and each call's assembly. Here the tables
that depend on the layout alone (fields, H, k, the carrier field, the acoustic
directions; not the amplitude, not the model's parameters) are built once and kept
(least recently used), and the residual and its Jacobian are ``_wave_solve._solve``'s,
operation for operation, with fewer calls. The solve keeps the start's Jacobian
(``chord_newton``: one Jacobian and its pseudo-inverse a wave instead of two Jacobians
and two least-squares solves): the same wave as ``_solve``'s to round-off (6e-14 of the
amplitude for flexmm, 1e-16 for one field; tests/test_models_exact.py), which may name
the other of two ring offsets that tie to round-off at a damped point (either is right:
tests/test_dissipation.py).
"""

from __future__ import annotations

import functools
import math

import numpy as np
from numba import njit


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
        # ``_wave_solve._solve``'s expressions, evaluated once
        self.E = np.exp(-1j * h[:, None] * xi[None, :]) / M
        self.B0 = np.exp(1j * h[:, None] * xi[None, :])
        self.Bp = self.B0 * np.exp(1j * h * k)[:, None]
        self.Bm = self.B0 * np.exp(-1j * h * k)[:, None]
        self.sidx = (h[:, None] - h[None, :]) % M
        self.ph = np.exp(1j * h * k)  # e^{i h k}, the Jacobian's phases
        # the free parts' (field, h - 1, Re/Im), in the order ``parts[free]`` reads them
        self.free_cols = np.argwhere(free).astype(np.int64)
        # a cell's fields at (n, n + 1) and at (n - 1, n) side by side, (2d, 2M): the cell
        # functions in one call each (elementwise: the same values as two calls)
        self.B_cell = np.concatenate([self.B0, self.Bm], axis=1)
        self.B_next = np.concatenate([self.Bp, self.B0], axis=1)
        for arr in (self.E, self.B0, self.Bp, self.Bm, self.sidx, self.ph, optical, free,
                    self.B_cell, self.B_next, self.free_cols):
            arr.flags.writeable = False

    def equations(self, model, masses, a, scale):
        """(residual(x), jacobian(x)) of ``_wave_solve._solve`` at amplitude a and ``scale``,
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
        m_col = masses[:, None]
        fixed = (a / 2, 0.0)
        # the Jacobian's layout (``_assemble``): its rows (the optical means, then Re and
        # Im of the harmonics 1..H) and unknowns (omega, the means, the free parts)
        n_rows, n_unknowns = n_opt + 2 * d * H, 1 + n_opt + self.free_cols.shape[0]
        free_cols = self.free_cols
        masses = np.ascontiguousarray(masses, dtype=float)

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
            out = np.empty((n_rows, n_unknowns))
            _assemble(F, sidx, ph, H, float(omega), masses, c, free_cols, optical,
                      float(scale), out)
            return out

        residual.last = None
        residual.at = at  # (x, its coefficients, its fields) of the last residual
        return residual, jacobian


@njit(cache=True, nogil=True, error_model="numpy", boundscheck=False)
def _assemble(F, sidx, ph, H, omega, masses, c, free_cols, optical, scale, out):
    """The collocation Jacobian (``_wave_solve._solve``'s, element for element) into ``out``
    (rows, unknowns), from F (2d, 2d, 2, M): the DFT / M of the cell Hessian along the
    grid at the cells (n, n + 1) [0] and (n - 1, n) [1]. dR_hat[l, j] / dc[h, b] is
    F[j, b, 0] + F[d + j, d + b, 1] + F[j, d + b, 0] e^{i h k} + F[d + j, b, 1] e^{-i h k}
    at l - h (mod M), less m_j (h omega)^2 on the diagonal; the unknowns are omega, the
    optical means and the free Re, Im of c[b, h], h = 1..H (c[-h] = conj c[h]); the rows
    the optical means (l = 0), then Re and Im of l = 1..H, each field's in turn, all over
    ``scale``. Only the rows l >= 0 are formed (numpy's version formed all 2H + 1 and
    dropped l < 0): ~10x faster on the small systems of a damped point's waves."""
    d = masses.size
    n_opt = optical.shape[1]
    nu = out.shape[1]
    X = np.empty((d, H + 1, nu), np.complex128)  # rows l = 0..H (index H..2H)
    w2 = omega**2
    for j in range(d):
        for li in range(H, 2 * H + 1):
            r = li - H
            X[j, li - H, 0] = -2 * omega * masses[j] * (r * r) * c[j, li]
            for o in range(n_opt):
                acc = 0j
                for b in range(d):
                    acc += _entry(F, sidx, ph, H, w2, masses, j, li, b, H) * optical[b, o]
                X[j, li - H, 1 + o] = acc
            for u in range(free_cols.shape[0]):
                b, hh, ri = free_cols[u, 0], free_cols[u, 1], free_cols[u, 2]
                jp = _entry(F, sidx, ph, H, w2, masses, j, li, b, H + 1 + hh)
                jm = _entry(F, sidx, ph, H, w2, masses, j, li, b, H - 1 - hh)
                X[j, li - H, 1 + n_opt + u] = jp + jm if ri == 0 else 1j * (jp - jm)
    row = 0
    for o in range(n_opt):
        for u in range(nu):
            acc = 0j
            for j in range(d):
                acc += optical[j, o] * X[j, 0, u]
            out[row, u] = acc.real / scale
        row += 1
    for part in range(2):
        for j in range(d):
            for li in range(1, H + 1):
                for u in range(nu):
                    v = X[j, li, u]
                    out[row, u] = (v.real if part == 0 else v.imag) / scale
                row += 1


@njit(cache=True, nogil=True, error_model="numpy", boundscheck=False, inline="always")
def _entry(F, sidx, ph, H, w2, masses, j, li, b, hi):
    """dR_hat[l, j] / dc[h, b] (``_assemble``), l and h by their indices li, hi."""
    d = masses.size
    s = sidx[li, hi]
    v = (F[j, b, 0, s] + F[d + j, d + b, 1, s]) + F[j, d + b, 0, s] * ph[hi] \
        + F[d + j, b, 1, s] / ph[hi]
    if li == hi and j == b:
        r = li - H
        v -= (r * r) * w2 * masses[j]
    return v


def chord_newton(residual, jacobian, x0, steps=12, progress=None, refresh=0, done=1e-14):
    """Newton's method with the start's Jacobian kept (the chord method): the lower
    amplitudes of a damped point start from the last wave scaled, ~1e-5 of their
    residual's scale away, where the chord converges linearly at a rate of that order, so
    one Jacobian and its pseudo-inverse serve every step (Newton took two Jacobians and
    two least-squares solves for the same round-off). Stops as ``_wave_solve._gauss_newton``:
    a residual below 1e-14, or one that no longer falls by 4 once below 1e-11 (round-off);
    None where it does not converge so (the caller solves by Gauss-Newton instead).
    ``progress``: a list that gets the last iterate whose residual fell by 4 or more
    against the one before (left empty where none did): where the chord gives up, Gauss-Newton
    goes on from it rather than from x0 (the continuation's steps of ``_wave._connected``:
    the chord took a flexmm wave's residual from ~1e-3 to ~1e-10 before it stalled, and
    Gauss-Newton then began again at 1e-3). ``refresh``: how many times at most the
    Jacobian is taken again at the latest iterate, where the chord's rate (now / before)
    says it would need more than ``REFRESH_AFTER`` further steps to reach 1e-14, or where
    a step fails to fall by 4 from the Jacobian of an earlier iterate (the continuation's
    last step: a rate of ~0.21 from 1e-2, 14 residuals before it stalled at 4e-11; with
    the Jacobian taken again at 5e-5 it converges in two more steps). Its fixed point does
    not depend on the Jacobian, so neither does the converged wave, beyond round-off.
    ``done``: the residual it stops at (1e-14; the continuation's steps before its last
    stop at 1e-11, as ``_wave_solve._gauss_newton``'s)."""
    x = x0.copy()
    r = residual(x)
    best = float(np.max(np.abs(r)))
    if not np.isfinite(best):
        return None
    if best < done:
        return x
    step = _least_squares_map(jacobian(x))  # the least-squares solution of each step
    fresh = True  # the step map is the current iterate's
    for _ in range(steps):
        xn = x - step @ r
        rn = residual(xn)
        now = float(np.max(np.abs(rn)))
        if not np.isfinite(now):
            return None
        if now < done:
            return xn
        if now >= best / 4:  # round-off, or too far for the chord
            if best < 1e-11 and now < 2 * best:
                return xn
            if refresh and fresh and now < 1e3 * best:
                # the current Jacobian's own step went up (Newton's overshoot far from the
                # root): taken, and the Jacobian with it, as Gauss-Newton would (which
                # otherwise starts again from x0 and takes this same step first)
                refresh -= 1
                x, r, best = xn, rn, now
                step = _least_squares_map(jacobian(x))
                continue
            if not refresh or fresh:
                return None
            # the Jacobian of an earlier iterate: taken again at the best one
            refresh -= 1
            step = _least_squares_map(jacobian(x))
            fresh = True
            continue
        rate = now / best
        x, r, best = xn, rn, now
        fresh = False
        if progress is not None:
            progress[:] = [x]
        if refresh and now > 1e-11 and math.log(1e-14 / now) / math.log(rate) > REFRESH_AFTER:
            refresh -= 1
            step = _least_squares_map(jacobian(x))
            fresh = True
    return None


#: ``chord_newton``'s steps at the current rate beyond which the Jacobian is taken again
#: (one Jacobian and its map cost ~3 residuals for flexmm at H = 16, measured)
REFRESH_AFTER = 4


def _least_squares_map(J):
    """An approximate pseudo-inverse B of J, the map r -> the step of ``chord_newton``.
    The chord needs B J = I on J's columns only to within its own contraction (its steps
    converge where |I - B J| is small, and its fixed point, where the residual vanishes,
    does not depend on B): the normal equations, B = (J^T J)^{-1} J^T (one 16 x 16 solve
    for a one-field wave, ~1/3 of a QR's cost), kept where |B J - I| <= 1e-8 (J
    conditioned to ~1e4 or better: cond(J) ~ 300 at Klein-Gordon a 0.4); else QR (R^{-1}
    Q^T where J is tall and R's diagonal within 1e10, ``_wave_solve._qr_step``'s rule), else
    ``pinv``. The converged wave differs by round-off, ~1e-16 of the amplitude."""
    m, n = J.shape
    if m >= n:
        with np.errstate(all="ignore"):
            try:
                B = np.linalg.solve(J.T @ J, J.T)
            except np.linalg.LinAlgError:
                B = None
        if B is not None and np.all(np.isfinite(B)):
            err = B @ J
            err[np.diag_indices(n)] -= 1.0
            if np.max(np.abs(err)) <= 1e-8:
                return B
        Q, R = np.linalg.qr(J)
        diag = np.abs(np.diagonal(R))
        if diag.size and diag.min() > 1e-10 * diag.max():
            out = np.linalg.solve(R, Q.T)
            if np.all(np.isfinite(out)):
                return out
    return np.linalg.pinv(J)


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
