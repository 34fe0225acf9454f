"""The collocation solve of the travelling wave at one truncation H (``_wave``'s module
docstring states the equations), split from ``_wave``: the unknowns' layout, Gauss-Newton
with the exact Jacobian (``_solve``), the same equations from their linear maps by the
chord method (``_solve_fast``, ``_collocation``), and scipy's least squares where Newton
does not settle. Each returns (omega, coefficients, residual); ``_wave`` makes the wave.
"""

from __future__ import annotations

import math

import numpy as np

#: the largest collocation residual, relative to m omega^2 a, of a wave that is found
RESIDUAL_TOL = 1e-9


def _grid(M):
    return 2 * np.pi * np.arange(M) / M


def _pack_layout(d, H, field, acoustic):
    """Which unknowns are free: (complement basis of the acoustic directions, mask of the
    free Re/Im parts of c[j, h], h = 1..H)."""
    if acoustic.shape[1]:
        q, _ = np.linalg.qr(np.concatenate([acoustic, np.eye(d)], axis=1))
        optical = q[:, acoustic.shape[1]:d]
    else:
        optical = np.eye(d)
    free = np.ones((d, H, 2), bool)
    free[field, 0, :] = False  # c[f, 1] = a / 2, real: the amplitude and the phase
    return optical, free


def _least_squares(*args, **kwargs):
    """scipy's least_squares (Levenberg-Marquardt with the exact Jacobian, at most
    ``_lm_evaluations``), imported on the first call: the fallback where Newton does
    not settle (importing scipy.optimize costs ~0.8 s, in every process that finds a wave:
    each map worker)."""
    from scipy.optimize import least_squares

    return least_squares(*args, **kwargs)


def _solve(model, car, a, masses, acoustic, H, c0, omega0, least_squares):
    """The collocation equations at H harmonics: Gauss-Newton with their exact Jacobian
    (from the generated cell Hessian), Levenberg-Marquardt with the same Jacobian
    (scipy's "lm") where Newton does not settle. Both solve the same equations; Newton
    needs ~5 steps of one Hessian evaluation and a small least-squares solve each."""
    d = model.n_fields
    M = max(64, 4 * H + 8)
    xi = _grid(M)
    optical, free = _pack_layout(d, H, car.field, acoustic)
    h = np.arange(-H, H + 1)
    E = np.exp(-1j * h[:, None] * xi[None, :]) / M  # projection onto e^{i h xi}
    scale = float(np.max(masses)) * omega0**2 * a
    n_opt = optical.shape[1]

    def unpack(x):
        omega = x[0]
        mean = optical @ x[1:1 + n_opt]
        parts = np.zeros((d, H, 2))
        parts[free] = x[1 + n_opt:]
        parts[car.field, 0] = (a / 2, 0.0)
        c = np.zeros((d, 2 * H + 1), complex)
        c[:, H] = mean
        c[:, H + 1:] = parts[..., 0] + 1j * parts[..., 1]
        c[:, :H] = np.conj(c[:, H + 1:][:, ::-1])
        return omega, c

    # e^{i h xi}, e^{i h (xi + k)}, e^{i h (xi - k)} on the grid, once per solve
    B0 = np.exp(1j * h[:, None] * xi[None, :])
    Bp = B0 * np.exp(1j * h * car.k)[:, None]
    Bm = B0 * np.exp(-1j * h * car.k)[:, None]

    def equations(R_hat):
        """The real equations of R_hat, shape (d, 2H + 1[, ncols])."""
        eqs = [np.real(np.tensordot(optical.T, R_hat[:, H], axes=1))]
        pos = R_hat[:, H + 1:]
        rest = pos.shape[2:]
        eqs += [np.real(pos).reshape((-1,) + rest), np.imag(pos).reshape((-1,) + rest)]
        return np.concatenate(eqs) / scale

    def residual(x):
        omega, c = unpack(x)
        U0, Up, Um = np.real(c @ B0), np.real(c @ Bp), np.real(c @ Bm)
        g_here = np.empty((2 * d, M))
        g_back = np.empty((2 * d, M))
        model.code.cell_gradient_into(np.concatenate([U0, Up]), model.p, g_here)
        model.code.cell_gradient_into(np.concatenate([Um, U0]), model.p, g_back)
        R = (masses[:, None] * omega**2 * np.real((c * (-(h**2))) @ B0)
             + g_here[:d] + g_back[d:])
        return equations(R @ E.T)

    def jacobian(x):
        omega, c = unpack(x)
        U0 = np.real(c @ B0)
        Hf = np.empty((2 * d, 2 * d, M))
        Hb = np.empty((2 * d, 2 * d, M))
        model.code.cell_hessian_into(np.concatenate([U0, np.real(c @ Bp)]), model.p, Hf)
        model.code.cell_hessian_into(np.concatenate([np.real(c @ Bm), U0]), model.p, Hb)
        # dR_hat[l, j] / dc[h, b] (c[h] and c[-h] independent): the DFT of the force's
        # derivative at l - h, the same grid as the residual (exact for the discrete system)
        sidx = (h[:, None] - h[None, :]) % M
        Ff, Fb = np.fft.fft(Hf, axis=-1) / M, np.fft.fft(Hb, axis=-1) / M
        ph = np.exp(1j * h * car.k)[None, :, None, None]
        J = (Ff[:d, :d][..., sidx] + Fb[d:, d:][..., sidx]).transpose(2, 3, 0, 1) \
            + Ff[:d, d:][..., sidx].transpose(2, 3, 0, 1) * ph \
            + Fb[d:, :d][..., sidx].transpose(2, 3, 0, 1) / ph   # (l, h, j, b)
        J[np.arange(2 * H + 1), np.arange(2 * H + 1)] -= (
            (h**2 * omega**2)[:, None, None] * np.diag(masses)[None])
        J = J.transpose(2, 0, 3, 1)                               # (j, l, b, h)
        # the unknowns: omega, the optical means, Re and Im of c[b, 1..H] where free
        # (c[-h] = conj c[h]), in the order unpack reads them
        Jp, Jm = J[..., H + 1:], J[..., H - 1::-1]
        parts = np.stack([Jp + Jm, 1j * (Jp - Jm)], axis=-1)[:, :, free]  # (j, l, n_free)
        cols = [equations(-2 * omega * masses[:, None] * h**2 * c)[:, None]]
        if n_opt:
            cols.append(equations(np.tensordot(J[:, :, :, H], optical, axes=1)))
        cols.append(equations(parts))
        return np.concatenate(cols, axis=1)

    x0 = [omega0, *(optical.T @ np.real(c0[:, H]))]
    parts0 = np.stack([np.real(c0[:, H + 1:]), np.imag(c0[:, H + 1:])], axis=-1)
    x0 = np.array(x0 + list(parts0[free]))
    x = _gauss_newton(residual, jacobian, x0)
    if x is None:
        sol = least_squares(residual, x0, jac=jacobian, method="lm", xtol=1e-15,
                            ftol=1e-15, gtol=1e-15, max_nfev=_lm_evaluations(x0.size))
        x = sol.x
    omega, c = unpack(x)
    res = float(np.max(np.abs(residual(x)))) if np.all(np.isfinite(x)) else math.inf
    return float(omega), c, res


def _solve_fast(model, car, a, masses, acoustic, H, c0, omega0, least_squares, qr=False,
                done=1e-14, kept=None, refresh=0):
    """``_solve``'s equations from their linear maps (``_collocation``: no per-call
    assembly), by the chord method (``chord_newton``: the start's Jacobian kept; Gauss-
    Newton where it does not converge), the converged residual not computed again: the
    same wave to round-off (tests/test_models_exact.py). ``qr``, ``done``: the Gauss-Newton
    fallback's (``_gauss_newton``). ``kept``: a dict of one carrier's calls (the layout
    and its ``Collocation`` per H, built once: a damped point's lower amplitudes).
    ``refresh``: the chord's Jacobian taken again up to that many times where it
    converges slowly (``chord_newton``; the continuation's steps)."""
    from ._collocation import chord_newton, collocation

    d = model.n_fields
    layout = None if kept is None else kept.get(H)
    if layout is None:
        optical, free = _pack_layout(d, H, car.field, acoustic)
        layout = (optical, free, collocation(d, H, car.k, car.field, optical, free),
                  float(np.max(masses)))
        if kept is not None:
            kept[H] = layout
    optical, free, coll, m_max = layout
    scale = m_max * omega0**2 * a
    n_opt = optical.shape[1]
    residual, jacobian = coll.equations(model, masses, a, scale)
    # Re and Im of c0[:, 1..H] side by side (a complex array's float view: the values of
    # np.stack([Re, Im], axis=-1)), the free ones in ``parts[free]``'s order
    parts0 = np.ascontiguousarray(c0[:, H + 1:]).view(float).reshape(d, H, 2)
    x0 = np.concatenate([[omega0], optical.T @ np.real(c0[:, H]), parts0[free]])
    progress = []
    x = chord_newton(residual, jacobian, x0, progress=progress, refresh=refresh, done=done)
    if x is None and progress:
        # Gauss-Newton from where the chord got to (its residual fell by 4 a step until
        # then: the same root's basin), from x0 where that does not settle
        x = _gauss_newton(residual, jacobian, progress[0], qr=qr, done=done)
    if x is None:
        x = _gauss_newton(residual, jacobian, x0, qr=qr, done=done)
    if x is None:
        x = least_squares(residual, x0, jac=jacobian, method="lm", xtol=1e-15, ftol=1e-15,
                          gtol=1e-15, max_nfev=_lm_evaluations(x0.size)).x
        residual(x)
    last = getattr(residual, "at", (None,))
    if last[0] is not None and np.array_equal(last[0], x):
        c = last[1]  # x's coefficients, unpacked by its residual (the same arithmetic)
    else:
        parts = np.zeros((d, H, 2))
        parts[free] = x[1 + n_opt:]
        parts[car.field, 0] = (a / 2, 0.0)
        c = np.zeros((d, 2 * H + 1), complex)
        c[:, H] = optical @ x[1:1 + n_opt]
        c[:, H + 1:] = parts[..., 0] + 1j * parts[..., 1]
        c[:, :H] = np.conj(c[:, H + 1:][:, ::-1])
    # the residual of x is the last one computed (Newton's, or the line above's)
    res = float(np.max(np.abs(residual.last))) if np.all(np.isfinite(x)) else math.inf
    return float(x[0]), c, res


def _lm_evaluations(n: int) -> int:
    """The least-squares fallback's evaluations at most, for n unknowns. With the exact
    Jacobian each is one iteration; the fallback settled in 11-155 where it settles at all
    (the test suite's waves). 200 (n + 1) with a finite-difference Jacobian (n residuals
    an iteration) took 120-340 s to refuse a Morse wave past its range (probe 98: a 2 at
    k pi, 16 184 Jacobians)."""
    return 100 + 4 * n


def _gauss_newton(residual, jacobian, x0, steps=40, qr=False, done=1e-14):
    """Gauss-Newton until the residual is round-off (None where it does not settle: the
    caller falls back to scipy's least squares). ``qr``: each step's least squares by
    Householder QR (~1/4 of ``lstsq``'s SVD on the 64 x 63 systems of H = 16), the SVD
    where R is near singular (a fold: lstsq's cut-off then matters); the same solution,
    other round-off: used by the continuation's checks (``_connected``). ``done``: the
    residual it stops at (round-off by default; the continuation's steps before the
    last stop at 1e-11, 100x below RESIDUAL_TOL: each is only the next one's start)."""
    x = x0.copy()
    r = residual(x)
    start = best = np.max(np.abs(r))
    for _ in range(steps):
        if not (np.isfinite(best) and best < 1e6 * max(start, 1e-3)):
            return None
        if best < done:
            return x
        J = jacobian(x)
        step = _qr_step(J, r) if qr else None
        if step is None:
            step = np.linalg.lstsq(J, -r, rcond=None)[0]
        x = x + step
        r = residual(x)
        now = np.max(np.abs(r))
        if best < 1e-11 and now >= best / 4:
            return x if now < 2 * best else None  # round-off: the last step changed nothing
        best = now
    return x if best < RESIDUAL_TOL else None


def _qr_step(J, r):
    """The least-squares step -J^+ r by QR (J of full column rank), or None where R's
    diagonal spans more than 1e10 (near rank-deficient: ``lstsq`` decides)."""
    Q, R = np.linalg.qr(J)
    diag = np.abs(np.diagonal(R))
    if not diag.size or not diag.min() > 1e-10 * diag.max():
        return None
    step = np.linalg.solve(R, -(Q.T @ r))
    return step if np.all(np.isfinite(step)) else None
