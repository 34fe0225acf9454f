"""Exact MI maps from resonance conditions: where the bands are, then Hill's method there.

A sideband pair k + q, k - q grows when the two sidebands, dressed by the carrier, are in
resonance with it: omega_+(q) + omega_-(q) = 2 Omega (the lab frequencies of theta at
k + q and k - q, shifted by the carrier through the couplings of the Hill matrix, the U
modes folded in by a Schur complement). Near a resonance the 2 x 2 sideband problem gives,
in closed form (rotating-wave reduction of the Hill matrix at harmonics H = 1),

    sigma_red(q)^2 = L_+- L_-+ / (4 omega_+ omega_-) - (omega_+ + omega_- - 2 Omega)^2 / 4.

``resonance_map`` evaluates sigma_red on a fine offset grid for every cell at once (cheap:
closed form), takes each cell's peak, and there computes the exact growth rate of the
Hill matrix of ``_hill`` (10 x 10 in case II): Newton on its quadratic pencil from the
reduced pair (``_pencil``), the full eigenproblem where that has no start. A band is found
wherever the reduced problem has one, however narrow, so the verdict does not depend on a
sampling of q (tests/test_resonance.py refines the grid 4x and no cell changes); sampling
the exact Hill spectrum instead misses bands narrower than the sampling (the 20-offset
``stability_map`` misses 6% of the case II cells at amplitude 0.02).

From the paper's start (eq. `IC`, case II) the free U waves at 2k (frequency
omega_U(2k), amplitudes from ``_launched``) also pump rotational pairs with wavenumbers
summing to 2k: omega_+ + omega_- = omega_U(2k), at the rate
sigma_f = alpha^2 |c| |sin 2k| / sqrt(omega_+ omega_-) on resonance (leading order in the
free wave's amplitude c; the quasi-periodic Hill method of ``_quasiperiodic`` gives the
exact rate at a point, 8-14% lower at the three gain-theories points). The map adds these bands;
on the MI band it keeps the travelling wave's rate (eq. `IC` lowers it by 2-8% at the
paper's amplitude, which ``mi_gain(start="paper")`` computes point by point).
"""

from __future__ import annotations

import numpy as np
from numba import njit

from common.threads import one_blas_thread, threaded_get
from generated import lattice_model as model

from ..lattice import checks
from ._hill import _coefficients, _hill_batch, _is_mi, _sideband_share, map_grid
from ._pencil import pencil_eigenvalues
from ._plane_wave import _on_branch, _solve_plane_waves
from ._quasiperiodic import ROUNDOFF
from ._reduced import _growth, _reduced, _refine_roots

#: offsets of the reduced problem's grid, (0, pi]: fine enough that a band of the paper's
#: parameter range spans several points (the narrowest at amplitude 0.02 ~ 0.01 wide)
RESONANCE_GRID = 256
#: the exact rate is evaluated at up to this many resonances per cell (near a U resonance
#: the reduced detuning also changes sign through a pole; the exact matrix sorts it out)
CANDIDATES = 4
#: probes per root: WINDOW_POINTS offsets WINDOW apart (at amplitude 0.02; ~ a^2)
WINDOW_POINTS, WINDOW = 3, 0.005
#: sign changes examined per cell, and the detuning (relative to Omega) a true root
#: reaches after the secant steps
ROOTS_SEARCHED, ROOT_TOLERANCE = 8, 1e-6
#: U resonances (poles of the reduction) probed per U mode, when the pair's detuning there
#: is below POLE_WINDOW Omega
POLE_ROOTS, POLE_WINDOW = 2, 0.05
#: a root of the pair's detuning this close to a pole (|omega_U^2 - (nu - u Omega)^2| below
#: POLE_GUARD Omega^2) is probed as a pole, not as a root
POLE_GUARD = 0.05
#: ... and roots closer than POLE_NEAR Omega^2 get the window of probes
POLE_NEAR = 0.3
#: ... and at this many local maxima of the reduced rate
MAXIMA = 3
#: grid points on each side of a pole's root where the reduced rate is no guide (its
#: maxima there are left to the pole probes)
POLE_NEIGHBOURS = 2
#: the amplitude WINDOW is stated at (the narrowest bands scale as amplitude^2), and the
#: window's bounds at other amplitudes (below: finer than the secant's roots; above: a
#: band's width at the largest amplitudes the plane waves exist)
WINDOW_AMPLITUDE, WINDOW_LIMITS = 0.02, (1e-5, 0.05)
#: secant iterations on a root of the detuning from its interpolated position, their
#: finite-difference step (the detuning is smooth on 1e-6: its curvature scale is a band,
#: >= 1e-3), and the largest move per step (a root further away is another root's)
SECANT_STEPS, SECANT_STEP, SECANT_MOVE = 6, 1e-6, 0.02
#: offsets are kept in (0, pi]: q = 0 is the carrier itself (neutral), the zone ends at pi
Q_FLOOR = 1e-9
#: placeholder offset of a missing root or pole (its probe has no reduced rate, so it is
#: never evaluated)
NO_ROOT = 1.0
#: inverse iteration's shift off the eigenvalue: relative and absolute, so that the solve
#: is regular while the mode still dominates the others by ~1e10 per step
INVERSE_SHIFT = (1e-10, 1e-14)
#: real part of Newton's start where the reduced rate is smaller (relative to Omega): off
#: the imaginary axis, on which a pair's two roots meet at a band edge
NEWTON_START = 1e-3
#: Newton from the reduced pair is used up to this amplitude, where it was checked against
#: the full eigenproblem (0 differing cells: 12 materials, alpha 0.5-5, both cases and
#: starts); above, the reduction's start can lie nearer another root (at 0.15-0.2, 2-8 of
#: ~3 600 case II cells lost their band), so every probe gets the full eigenproblem
NEWTON_AMPLITUDE = 0.1
#: phase points of the plane waves' harmonic balance and of the couplings' Fourier
#: coefficients (H = 1 needs harmonics <= 4; aliasing from 16 - 4 is ~ a^12)
PHASES = 16


def _roots(q, detuning, n):
    """Offsets where each row of ``detuning`` (B, Q) changes sign (linear interpolation),
    at most n per row, (B, n), NaN where there are fewer."""
    out = np.full((detuning.shape[0], n), np.nan)
    _sign_changes(np.asarray(q, float), np.ascontiguousarray(detuning, dtype=float), out)
    return out


@njit(cache=True, nogil=True, error_model="numpy", boundscheck=False)
def _sign_changes(q, d, out):
    B, Q = d.shape
    n = out.shape[1]
    for r in range(B):
        slot = 0
        for c in range(Q - 1):
            if slot == n:
                break
            s0, s1 = np.sign(d[r, c]), np.sign(d[r, c + 1])
            if s0 * s1 < 0:
                t = d[r, c] / (d[r, c] - d[r, c + 1])
                out[r, slot] = q[c] + t * (q[c + 1] - q[c])
                slot += 1


def _refine(C, k, W, roots, coupled, pump, steps=SECANT_STEPS):
    """Secant steps on the detuning omega_+ + omega_- - pump from the interpolated roots;
    returns the roots and the reduced growth rate there, (B, n)."""
    x = _refine_roots(C, k, W, np.where(np.isfinite(roots), roots, NO_ROOT), coupled,
                      np.broadcast_to(pump, (k.size, 1))[:, 0], steps, SECANT_STEP,
                      SECANT_MOVE, Q_FLOOR)
    # a missing root's placeholder is refined too: where it settles on a root, that root's
    # reduced rate stands for a probe at NO_ROOT (a band found there, measured: dropping it
    # loses a few cells per 6 400 at the 20x threshold)
    wp, wm, c2, dens = _reduced(C, k, W, x, coupled, poles=True)
    pole = np.min(np.abs(dens), axis=0) if len(dens) else np.full(x.shape, np.inf)
    return np.where(np.isfinite(roots), x, np.nan), wp, wm, c2, pole


def _candidates(q, sigma, n):
    """The n largest local maxima of each row of sigma (B, Q), refined by a parabola
    through their three points: offsets and values, (B, n) (value 0: no maximum)."""
    B, Q = sigma.shape
    pad = np.pad(sigma, ((0, 0), (1, 1)), constant_values=-1.0)
    is_max = (sigma > pad[:, :-2]) & (sigma >= pad[:, 2:]) & (sigma > 0)
    score = np.where(is_max, sigma, -1.0)
    j = np.argsort(-score, axis=1)[:, :n]
    r = np.arange(B)[:, None]
    val = np.maximum(score[r, j], 0.0)
    jc = np.clip(j, 1, Q - 2)
    y0, y1, y2 = sigma[r, jc - 1], sigma[r, jc], sigma[r, jc + 1]
    den = y0 - 2 * y1 + y2
    with np.errstate(divide="ignore", invalid="ignore"):
        shift = np.where(den < 0, 0.5 * (y0 - y2) / den, 0.0)
    return q[jc] + np.clip(shift, -1, 1) * (q[1] - q[0]), val


@one_blas_thread
def resonance_map(k, delta=None, case: str | None = None, alpha: float | None = None,
                  K_s: float | None = None, amplitude: float | None = None,
                  start: str = "travelling", grid: int = RESONANCE_GRID, chunk: int = 1000, *,
                  material=None, K_theta=None):
    """Peak sideband growth rate over a grid of (k, delta), from the resonance conditions.

    Parameters
    ----------
    k, delta : array_like, same (or broadcastable) shapes
        Carrier wavenumbers in (0, pi) and delta = K_s - K_theta (K_theta > 0).
    case : {"rotation", "coupled"}
    material : Material
        The material (keyword): its alpha and K_s; the grid's K_theta is K_s - delta (the
        material's own K_theta is not used). ``alpha, K_s`` (floats) instead are the
        earlier form: ``resonance_map(k, delta, case, alpha, K_s, amplitude)``.
    amplitude : float
        Peak rotation of the travelling wave, or the initial rotation of eq. `IC`.
    start : {"travelling", "paper"}
        The travelling wave, or the state eq. `IC` launches (case II: plus the bands its
        free U waves pump; case I: the same as "travelling", no U).
    grid : int
        Points of the reduced problem's offset grid in (0, pi].
    K_theta : array_like, optional
        The grid's second axis as K_theta itself instead of delta (keyword; no K_s - delta
        round trip): give delta or K_theta.

    Returns
    -------
    dict of ndarray, shape of k
        ``peak_gain`` (1/T; 0 where stable, NaN where no plane wave exists), ``q_peak``
        (its offset) and ``pumped`` (bool: the peak is a band pumped by the free U waves).
    """
    checks.choice("start", start, ("travelling", "paper"))
    # grid x chunk offsets are evaluated at once (8 bytes each, a few arrays): 1e6 points
    # resolve a band 3e-6 wide and stay within a few hundred MB at the default chunk
    grid = checks.integer("grid", grid, 16, 10**6 + 1)
    chunk = checks.integer("chunk", chunk, 1)
    alpha, K_s, amplitude, k, K_theta = map_grid(k, delta, case, alpha, K_s, amplitude,
                                                 material, K_theta)
    q = np.linspace(np.pi / grid, np.pi, grid)
    coupled = case == "coupled"
    kf, Ktf = k.ravel().astype(float), K_theta.ravel().astype(float)
    out = {"peak_gain": np.zeros(kf.size), "q_peak": np.full(kf.size, np.nan),
           "pumped": np.zeros(kf.size, bool)}
    slices = [slice(s, s + chunk) for s in range(0, kf.size, chunk)]
    import dask  # here: importing the theory (`flexmm coefficients`) needs no Dask

    tasks = [dask.delayed(_chunk)(kf[sl], Ktf[sl], float(alpha), float(K_s),
                                  float(amplitude), q, coupled, start == "paper" and coupled)
             for sl in slices]
    # chunks on the machine's cores: NumPy, LAPACK and the compiled loops release the GIL
    # (1.9x on 2 cores against one thread, chunks of 1000 cells, measured once)
    for sl, res in zip(slices, dask.compute(*tasks, scheduler=threaded_get())):
        for name in out:
            out[name][sl] = res[name]
    return {name: v.reshape(k.shape) for name, v in out.items()}


def _chunk(kk, Kt, alpha, K_s, amplitude, q, coupled, pumped):
    """One chunk of cells: plane waves, the reduced problem on the offset grid, its
    candidates, the exact rate there, and (eq. `IC`, case II) the pumped bands."""
    B = kk.size
    al, Ks = np.full(B, alpha), np.full(B, K_s)
    x, res = _solve_plane_waves(kk, np.full(B, amplitude), al, Ks, Kt, coupled, 1,
                                points=PHASES)
    ok = _on_branch(x, res, amplitude)
    a, b, W = x[:, :1], x[:, 1:2], x[:, -1]
    C = _coefficients(a, b, kk, al, Ks, Kt, PHASES)
    wp, wm, c2, dens = _reduced(C, kk, W, q, coupled, poles=True)
    detuning = (wp + wm).real - 2 * W[:, None]
    probes, s_red = _root_probes(C, kk, W, q, detuning, coupled, amplitude)
    pole_probes, pole_red, near = _pole_probes(q, detuning, dens, W)
    # ... and the peaks of the reduced rate away from the poles: bands whose detuning
    # only dips towards zero (no root, the coupling bridges it: wide bands)
    sig = np.where(near, 0.0, np.nan_to_num(_growth(c2, wp, wm, 2 * W[:, None])))
    q_max, s_max = _candidates(q, sig, MAXIMA)
    eig_only = np.concatenate([np.zeros(p.shape[1], bool) for p in probes]
                              + [np.ones(p.shape[1], bool) for p in pole_probes]
                              + [np.zeros(q_max.shape[1], bool)])
    probes = np.concatenate(probes + pole_probes + [q_max], axis=1)
    s_red = np.concatenate(s_red + pole_red + [s_max], axis=1)
    gq = _exact_rates(a, b, kk, W, al, Ks, Kt, C, probes, s_red, coupled,
                      eig_only | (amplitude > NEWTON_AMPLITUDE))
    best = np.argmax(gq, axis=1)
    gain = gq[np.arange(B), best]
    gain[gain < ROUNDOFF * W] = 0.0
    q_peak = np.where(gain > 0, probes[np.arange(B), best], np.nan)
    is_pumped = np.zeros(B, bool)
    if pumped:
        s_f, q_f = _pumped_bands(C, kk, W, b, q, wp, wm, coupled, alpha)
        is_pumped = s_f > gain
        gain = np.maximum(gain, s_f)
        q_peak = np.where(is_pumped, q_f, q_peak)
    gain = np.where(ok, gain, np.nan)
    return {"peak_gain": gain, "q_peak": q_peak, "pumped": is_pumped & ok}


def _root_probes(C, kk, W, q, detuning, coupled, amplitude):
    """Band centres: roots of the detuning omega_+ + omega_- - 2 Omega (a sign change on
    the grid; a band whose two edges fall within one grid step is a tangency, marginal),
    refined; the CANDIDATES fastest by the reduced rate, with a window of probes where a
    root sits near a pole. Returns lists of probe offsets and reduced rates, (B, n) each
    (rate 0: not a candidate)."""
    B = kk.size
    # a sign change through a pole of the reduction is no root: the secant steps do not
    # converge there, and it is dropped
    roots = _roots(q, detuning, ROOTS_SEARCHED)
    x, wp_r, wm_r, c2_r, pole = _refine(C, kk, W, roots, coupled, 2 * W[:, None])
    # roots next to a pole are left to the pole probes (there the reduction's rate is
    # meaningless and would crowd out the real bands)
    true_root = ((np.abs((wp_r + wm_r).real - 2 * W[:, None]) < ROOT_TOLERANCE * W[:, None])
                 & (pole > POLE_GUARD * W[:, None] ** 2))
    s_root = np.where(true_root, np.nan_to_num(_growth(c2_r, wp_r, wm_r, 2 * W[:, None])), 0.0)
    top = np.argsort(-s_root, axis=1)[:, :CANDIDATES]
    r = np.arange(B)[:, None]
    # the reduction places a narrow band next to a U resonance up to about its own width
    # off: probe a small window around each root (h ~ half the narrowest band, ~ a^2)
    h = np.clip(WINDOW * (amplitude / WINDOW_AMPLITUDE) ** 2, *WINDOW_LIMITS)
    probes, s_red = [], []
    near_pole = pole[r, top] < POLE_NEAR * W[:, None] ** 2
    for off in np.arange(-(WINDOW_POINTS // 2), WINDOW_POINTS // 2 + 1) * h:
        probes.append(np.clip(np.nan_to_num(x[r, top], nan=NO_ROOT) + off, Q_FLOOR, np.pi))
        # away from the poles the reduction is accurate: the root itself suffices
        s_red.append(s_root[r, top] * (near_pole | (off == 0)))
    return probes, s_red


def _pole_probes(q, detuning, dens, W):
    """Where a U mode meets the pair near its resonance (a pole of the reduction), a hybrid
    band may open: its resonance condition is a root of that pole's detuning. Returns the
    probes, their flags (1: probe), and the grid points next to a pole (B, Q)."""
    r = np.arange(detuning.shape[0])[:, None]
    probes, flags = [], []
    near = np.zeros(detuning.shape, bool)
    for den in dens:
        pr = _roots(q, den, POLE_ROOTS)
        j = np.clip(np.searchsorted(q, np.nan_to_num(pr, nan=0.0)), 0, q.size - 1)
        close = np.isfinite(pr) & (np.abs(detuning[r, j]) < POLE_WINDOW * W[:, None])
        probes.append(np.nan_to_num(pr, nan=NO_ROOT))
        flags.append(close.astype(float))
        for d in range(-POLE_NEIGHBOURS, POLE_NEIGHBOURS + 1):  # no guide next to a pole
            near[r, np.clip(j + d, 0, q.size - 1)] |= np.isfinite(pr)
    return probes, flags, near


def _exact_rates(a, b, kk, W, al, Ks, Kt, C, probes, s_red, coupled, eig_only):
    """The exact rate (Hill, H = 1, sideband modes) at every probe with a reduced rate,
    (B, n); 0 elsewhere and where no sideband mode grows. Columns ``eig_only`` (n,) (the
    pole probes: there the reduction gives no start) go to the full eigenproblem; the rest
    to Newton on the pencil from the reduced pair (``_pencil``), and to the eigenproblem
    where Newton does not settle on a growing-or-neutral root."""
    gq = np.zeros(probes.shape)
    rows, cols = np.nonzero(s_red > 0)  # only the (cell, offset) pairs that are candidates
    if rows.size == 0:
        return gq
    g = np.zeros(rows.size)
    full = eig_only[cols].copy()
    if not full.all():  # (above NEWTON_AMPLITUDE every probe is eig_only)
        nr, nc = rows[~full], cols[~full]
        Wr = W[nr]
        wp, wm, _ = _reduced(C, kk, W, probes, coupled)
        lam0 = 0.5j * (wm - wp).real[nr, nc] + np.maximum(s_red[nr, nc], NEWTON_START * Wr)
        lam, share, settled = pencil_eigenvalues(C, kk, W, al, probes[nr, nc], nr, lam0,
                                                 coupled)
        g[~full] = np.where(_is_mi(share) & (lam.real > ROUNDOFF * Wr), lam.real, 0.0)
        full[~full] = ~settled | (lam.real < -ROUNDOFF * Wr)
    if np.any(full):
        g[full] = _eig_rates(a, b, kk, W, al, Ks, Kt, C, probes, rows[full], cols[full],
                             coupled)
    gq[rows, cols] = g
    return gq


def _eig_rates(a, b, kk, W, al, Ks, Kt, C, probes, rows, cols, coupled):
    """The exact rate at the probes (rows, cols) from the Hill matrix's full spectrum: its
    fastest mode if that is a sideband pair, else the fastest sideband mode; (P,)."""
    g = np.zeros(rows.size)
    A, labels = _hill_batch(a[rows], b[rows], kk[rows], W[rows], al[rows], Ks[rows],
                            Kt[rows], probes[rows, cols][:, None], 1, coupled,
                            C={name: c[rows] for name, c in C.items()})
    A = A[:, 0]
    lam = np.linalg.eigvals(A)
    top = lam[np.arange(lam.shape[0]), np.argmax(lam.real, axis=-1)]
    grow = top.real > ROUNDOFF * W[rows]
    if not np.any(grow):
        return g
    # is the fastest mode a sideband pair? its eigenvector by two steps of inverse
    # iteration (a 10 x 10 solve each, 10x cheaper than a full eig) ...
    Ag, lg = A[grow], top[grow]
    rel, absolute = INVERSE_SHIFT
    shift = Ag - (lg * (1 + rel) + absolute)[:, None, None] * np.eye(Ag.shape[-1])
    v = np.ones(Ag.shape[:2], complex)
    for _ in range(2):
        v = np.linalg.solve(shift, v[..., None])[..., 0]
        v /= np.linalg.norm(v, axis=-1, keepdims=True)
    mi = _is_mi(_sideband_share(v[..., None], labels, al[rows][grow] ** 2)[:, 0])
    gg = np.where(mi, lg.real, 0.0)
    # ... and where it is not, a slower sideband mode may still grow: full eig
    if np.any(~mi):
        lam_u, vec = np.linalg.eig(Ag[~mi])
        share = _sideband_share(vec, labels, al[rows][grow][~mi] ** 2)
        gg[~mi] = np.where(_is_mi(share), lam_u.real, 0.0).max(axis=-1)
    g[grow] = gg
    return g


def _pumped_bands(C, kk, W, b, q, wp, wm, coupled, alpha):
    """Free U waves of eq. `IC` at 2k: forward and backward amplitudes cancelling the forced
    harmonic b_2 at T = 0 (``_launched``), each pumping rotational pairs at omega_U(2k), on
    resonance at rate G / (4 sqrt(omega_+ omega_-)). Returns the rate and offset, (B,)."""
    B = kk.size
    w2 = model.omega_longitudinal(2 * kk)
    r = 2 * W / w2
    roots = _roots(q, (wp + wm).real - w2[:, None], ROOTS_SEARCHED)
    q_r, wp_r, wm_r, _, pole = _refine(C, kk, W, roots, coupled, w2[:, None])
    true_root = ((np.abs((wp_r + wm_r).real - w2[:, None]) < ROOT_TOLERANCE * W[:, None])
                 & (pole > POLE_GUARD * W[:, None] ** 2))
    inv = np.where(true_root, np.nan_to_num(1 / np.sqrt(wp_r * wm_r).real), 0.0)
    c_max = np.abs(b[:, 0]) * np.maximum(1 + r, np.abs(r - 1)) / 2
    G = 4 * alpha**2 * c_max * np.abs(np.sin(2 * kk))
    j = np.argmax(inv, axis=1)
    return G / 4 * inv[np.arange(B), j], q_r[np.arange(B), j]
