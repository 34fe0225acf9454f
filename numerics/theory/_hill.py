"""Linear stability of the exact plane waves: Hill's method.

Linearising about a wave of ``_plane_wave``, a perturbation
x_n = e^{lambda T} sum_p X_p e^{i (q n + p phi_n)} turns the lattice into
(lambda - i p Omega)^2 X_p = sum_m L_pm(q) X_m: constant coefficients in the harmonic
index p (Hill's method; the couplings L come from the generated Jacobian of eq. `norm`).
The sidebands k + q (p = 1) and k - q (p = -1, as its conjugate q - k) sit in the family
x: p odd, y: p even, which also holds the induced mean flow (y_0 at wavenumber q) and the
second harmonic of U. The growth rate is the largest real part of the eigenvalues of the
2n x 2n first-order form. The only approximation is the truncation |p| <= P, whose
convergence tests/test_hill.py shows.

References
----------
G. W. Hill, Acta Math. 8 (1886); B. Deconinck & J. N. Kutz, J. Comput. Phys. 219 (2006)
296 (Hill's method for periodic coefficients).
"""

from __future__ import annotations

import functools

import numpy as np

from common.threads import one_blas_thread, threaded_get
from generated import lattice_model as model

from ..lattice import Material, check_case, checks
from ._launched import STARTS, launched_state
from ._plane_wave import (
    HARMONICS,
    MAX_AMPLITUDE,
    PlaneWave,
    _check,
    _check_harmonics,
    _combine,
    _on_branch,
    _solve_plane_waves,
    _tables,
    plane_wave,
)
from ._quasiperiodic import (
    ROUNDOFF,
    GainSpectrum,
    _labels,
    coupling_coefficients,
    gain_spectrum_torus,
    hill_matrices,
    neutral_offsets,
    off_centre,
    sideband_shares,
    torus_of_wave,
)
from ._quasiperiodic import is_mi as _is_mi

#: offsets searched by stability_map: at amplitude 0.02 every band of the paper's
#: parameter range lies inside (0, 1.5]
MAP_OFFSETS = np.linspace(0.075, 1.5, 20)


def _coefficients(a, b, k, al, Ks, Kt, M):
    """Fourier coefficients c_l (index l mod M) of the linearised lattice's couplings.

    Batched over waves: a, b (B, H) harmonics, k, al, Ks, Kt (B,). Returns a dict name ->
    (B, 3, M) complex array over neighbour offsets j = -1, 0, +1 of
    d(acceleration)/d(field_{n+j}) at the wave, as functions of phi_n
    (``_quasiperiodic.coupling_coefficients`` on the wave's values at M phases).
    """
    phi = 2 * np.pi * np.arange(M) / M
    t = _tables(k, a.shape[1], phi, True)
    f = {}
    for s in (-1, 0, 1):
        f["theta", s] = _combine(a, t["cos", s])
        f["U", s] = _combine(b, t["sin", s])
    return coupling_coefficients(f, al[:, None], Ks[:, None], Kt[:, None], (1,))


def _hill_batch(a, b, k, W, al, Ks, Kt, q, P, coupled, C=None):
    """First-order Hill matrices of travelling waves, shape (B, nq, 2n, 2n), and the
    harmonic labels p (theta first): ``_quasiperiodic.hill_matrices`` on tori with no free
    phase. q has shape (nq,) (the same offsets for every wave) or (B, nq)."""
    px, py = _labels(P, 0, 0)
    if C is None:  # else: the couplings' coefficients, already computed (M > 4 P + 2)
        C = _coefficients(a, b, k, al, Ks, Kt, max(64, 4 * (2 * P + 2)))
    A, labels, _ = hill_matrices(C, k, W, np.zeros((k.size, 0)), q, px, py, coupled)
    return A, labels[:, 0]


def _sideband_share(vec, labels, a2):
    """Kinetic-energy share of the theta harmonics p = +1, -1 in each eigenvector
    (``_quasiperiodic.sideband_shares`` with the labels p of :func:`_hill_batch`)."""
    return sideband_shares(vec, labels[:, None], int(np.sum(labels % 2 == 1)), a2)


def _off_centre(vec, labels, a2, P):
    """``_quasiperiodic.off_centre`` with the labels p of :func:`_hill_batch`."""
    return off_centre(vec, labels[:, None], int(np.sum(labels % 2 == 1)), a2, P)


def _hill_matrices(wave, material, q, P):
    """Hill matrices of one wave, shape (nq, 2n, 2n), and the harmonic labels."""
    A, labels = _hill_batch(wave.theta_harmonics[None], wave.U_harmonics[None],
                            np.array([wave.k]), np.array([wave.omega]),
                            np.array([material.alpha]), np.array([material.K_s]),
                            np.array([material.K_theta]), np.asarray(q, float).ravel(), P,
                            wave.case == "coupled")
    return A[0], labels


def hill_spectrum(wave: PlaneWave, material: Material, q, P: int):
    """Eigenvalues of the Hill matrices and the sideband share of each eigenvector.

    Returns ``(lam, share)``, shapes (nq, 2n) and (nq, 2n, 2): ``share[..., 0]`` and
    ``share[..., 1]`` are the fractions of the mode's kinetic energy (theta_dot^2 /
    (2 alpha^2) + 2 U_dot^2 per harmonic, eq. `norm`'s energy) carried by the theta
    harmonics p = +1 and p = -1, i.e. by the sidebands k + q and q - k.
    The Hill spectrum at q + 2k is that at q shifted by 2 i Omega (relabel p -> p - 2),
    so a growth rate shows up at many q in some eigenvector; the share picks the mode
    whose sidebands are k +- q, and leaves out modes that live in U (see ``modes``).
    """
    A, labels = _hill_matrices(wave, material, q, P)
    lam, vec = np.linalg.eig(A)
    return lam, _sideband_share(vec, labels, np.array(material.alpha**2))


def _check_wave(wave, material, case, k, amplitude, H):
    """A wave passed to mi_gain must be the one it is asked about."""
    checks.instance("wave", wave, PlaneWave)
    problems = [f"{name} {got!r} != {want!r}" for name, got, want in (
        ("case", wave.case, case), ("k", wave.k, k), ("amplitude", wave.amplitude, amplitude),
        ("harmonics", wave.theta_harmonics.size, H)) if got != want]
    w_lin = float(model.omega_rotation(k, material.alpha, material.K_s, material.K_theta))
    if not np.isclose(wave.omega_linear, w_lin, rtol=1e-12):
        problems.append("material (its linear frequency differs)")
    if problems:
        raise ValueError("wave does not match the arguments of mi_gain: " + "; ".join(problems)
                         + "; compute it with plane_wave(material, case, k, amplitude, "
                         "harmonics)")


@one_blas_thread
def mi_gain(material: Material, case: str, k: float, amplitude: float, offset,
            harmonics: int = HARMONICS, wave: PlaneWave | None = None,
            modes: str = "sidebands", start: str = "travelling") -> np.ndarray:
    """Exact linear growth rate of the sidebands k + q and k - q of a lattice plane wave.

    Parameters
    ----------
    material : Material
    case : {"rotation", "coupled"}
    k : float
        Carrier wavenumber (rad per site).
    amplitude : float
        Peak rotation of the carrier, rad (2 eps A0 in the paper's eq. `IC`).
    offset : array_like
        Sideband offsets q = |sideband - k|, rad per site (not absolute wavenumbers).
    harmonics : int
        Truncation H: the wave keeps theta harmonics 1, 3, .., 2H - 1 and U harmonics
        2, .., 2H; the Hill matrix keeps theta harmonics |p| <= 2H - 1 and U harmonics
        |p| <= 2H of the perturbation (default 4: a 34 x 34 matrix in case II, 16 x 16 in case I).
    wave : PlaneWave, optional
        A wave already computed by :func:`plane_wave` (same material, case, k, amplitude).
    modes : {"sidebands", "all"}
        "sidebands": modes whose kinetic energy sits mostly (> 3/4) in theta at k + q
        and k - q, both present: the modulational instability. "all": every Hill
        mode at Bloch offset q centred on theta's p = +-1 or U's p = 0, +-2 (a copy
        relabelled to other harmonics is counted at its own offset; cut off at the
        truncation's edge it grew spuriously, ``_quasiperiodic.off_centre``), which
        also holds resonant instabilities living in U (pairs of longitudinal waves
        driven by the carrier, 2 Omega = omega_U(q) + omega_U(q - 2k)).
    start : {"travelling", "paper", "discrete"}
        The state whose stability is asked: the exact travelling wave of peak rotation
        ``amplitude`` (the default), or the state eq. `IC` launches with initial rotation
        ``amplitude`` ("paper": continuum frequency; "discrete": the lattice's linear
        one): travelling wave plus free waves (:func:`launched_state`), a quasi-periodic
        state whose Hill spectrum :func:`gain_spectrum` computes. ``wave`` is for
        "travelling" only.

    Returns
    -------
    ndarray, same shape as offset
        sigma(q) = max Re lambda >= 0, per unit of lattice time T. No long-wave or weak-
        modulation approximation: the truncation is the only one.
    """
    k, amplitude = _check(material, case, k, amplitude)
    H = _check_harmonics(harmonics)
    q_arr = checks.real_array("offset", offset)
    if not np.all(np.isfinite(q_arr)):
        raise ValueError("offset must be finite")
    checks.choice("start", start, STARTS)
    if start != "travelling":
        if wave is not None:
            raise ValueError("wave= describes a travelling wave; it cannot be used with "
                             f"start={start!r}")
        spec = gain_spectrum(material, case, k, amplitude, q_arr.ravel(), start=start,
                             modes=modes, harmonics=harmonics)
        return spec.sigma.reshape(q_arr.shape)
    if wave is None:
        wave = plane_wave(material, case, k, amplitude, H)
    else:
        _check_wave(wave, material, case, k, amplitude, H)
    if modes not in ("sidebands", "all"):
        raise ValueError(f"modes must be 'sidebands' or 'all', got {modes!r}")
    if modes == "all":  # every mode centred at |p| <= CENTRE (``off_centre``)
        A, labels = _hill_matrices(wave, material, q_arr.ravel(), 2 * H - 1)
        lam, vec = np.linalg.eig(A)
        growth = np.where(_off_centre(vec, labels, material.alpha**2, 2 * H - 1), 0.0,
                          lam.real)
    else:
        lam, share = hill_spectrum(wave, material, q_arr.ravel(), 2 * H - 1)
        growth = np.where(_is_mi(share), lam.real, 0.0)
    sigma = growth.max(axis=1)
    sigma[sigma < ROUNDOFF * wave.omega] = 0.0
    sigma[neutral_offsets(q_arr.ravel())] = 0.0
    return sigma.reshape(q_arr.shape)


def check_map_grid(case, alpha, K_s, amplitude, k, delta, q=None, axis="delta"):
    """The arguments every (k, delta) map shares, checked: returns alpha, K_s, amplitude
    and k, delta broadcast together (``q``, the offsets a map samples, checked finite).
    ``axis="K_theta"``: the second coordinate is K_theta itself, not K_s - K_theta."""
    check_case(case)
    alpha = checks.positive("alpha", alpha)
    K_s = checks.positive("K_s", K_s)
    amplitude = checks.real("amplitude (peak rotation, rad)", amplitude, 0.0, MAX_AMPLITUDE)
    k, delta = checks.real_array("k", k), checks.real_array(axis, delta)
    try:
        k, delta = np.broadcast_arrays(k, delta)
    except ValueError:
        raise ValueError(f"k and {axis} must have the same (or broadcastable) shapes, got "
                         f"{k.shape} and {delta.shape}") from None
    arrays = (k, delta) if q is None else (k, delta, q)
    if not all(np.all(np.isfinite(a)) for a in arrays):
        raise ValueError((f"k and {axis}" if q is None else f"k, {axis} and q")
                         + " must be finite")
    K_theta = K_s - delta if axis == "delta" else delta
    if np.any(K_theta <= 0) or np.any((k <= 0) | (k >= np.pi)):
        raise ValueError(("need K_theta = K_s - delta > 0" if axis == "delta" else
                          "need K_theta > 0") + " and 0 < k < pi on the whole grid")
    return alpha, K_s, amplitude, k, delta


def map_grid(k, delta, case, alpha, K_s, amplitude, material=None, K_theta=None, q=None):
    """The inputs of a (k, delta) map in either form, checked: the material as ``material``
    (a Material: its alpha and K_s; the grid gives K_theta) or as ``alpha, K_s``; the grid's
    second axis as ``delta`` or as ``K_theta`` itself. Returns alpha, K_s, amplitude, and k
    and the grid's K_theta broadcast together (K_s - delta, or K_theta as given)."""
    if material is not None:
        checks.instance("material", material, Material)
        if alpha is not None or K_s is not None:
            raise TypeError("give the material as material= or as alpha and K_s, not both")
        alpha, K_s = material.alpha, material.K_s
    for name, value in (("case", case), ("alpha", alpha), ("K_s", K_s),
                        ("amplitude", amplitude)):
        if value is None:
            raise TypeError(f"missing {name}" + (" (or material=, a Material)"
                                                 if name in ("alpha", "K_s") else ""))
    if (delta is None) == (K_theta is None):
        raise TypeError("give the grid's second axis as delta or as K_theta=, one of them")
    if K_theta is None:
        alpha, K_s, amplitude, k, delta = check_map_grid(case, alpha, K_s, amplitude, k, delta,
                                                         q)
        return alpha, K_s, amplitude, k, K_s - delta
    return check_map_grid(case, alpha, K_s, amplitude, k, K_theta, q, axis="K_theta")


@one_blas_thread
def stability_map(k, delta=None, case: str | None = None, alpha: float | None = None,
                  K_s: float | None = None, amplitude: float | None = None, offset=None,
                  harmonics: int = 1, chunk: int = 2000, modes: str = "sidebands", *,
                  material: Material | None = None, K_theta=None):
    """Peak sideband growth rate max_q sigma(q) over a grid of (k, delta), batched.

    Parameters
    ----------
    k, delta : array_like, same (or broadcastable) shapes
        Carrier wavenumbers and delta = K_s - K_theta (K_theta must stay > 0).
    case, amplitude : as in :func:`mi_gain`.
    material : Material
        The material (keyword): its alpha and K_s; the grid's K_theta is K_s - delta (the
        material's own K_theta is not used). ``alpha, K_s`` (floats) instead are the
        earlier form: ``stability_map(k, delta, case, alpha, K_s, amplitude)``.
    K_theta : array_like, optional
        The grid's second axis as K_theta itself instead of delta (keyword; no K_s - delta
        round trip): give delta or K_theta.
    offset : array_like, optional
        Sideband offsets searched (default 20 values in (0, 1.5]: at amplitude 0.02 every
        sideband band of the paper's parameter range lies inside).
    harmonics : int
        Truncation H (default 1: theta at k +- q, U at 0 and +-2: the mean flow and the
        second harmonic; the peak gain is converged to ~a^2 relative, see the tests).
    modes : {"sidebands", "all"}
        As in :func:`mi_gain`: MI modes only, or every growing Hill mode.

    Returns
    -------
    ndarray, shape of k
        Peak growth rate; 0 where the plane wave is stable (to the q grid).
    """
    chunk = checks.integer("chunk", chunk, 1)
    q = MAP_OFFSETS if offset is None else checks.real_array("offset", offset).ravel()
    if q.size == 0 or not np.all(np.isfinite(q)):
        raise ValueError(f"offset must hold at least one finite offset, got {q.size} values"
                         + ("" if q.size == 0 else " with a non-finite one"))
    H = _check_harmonics(harmonics)
    checks.choice("modes", modes, ("sidebands", "all"))
    alpha, K_s, amplitude, k, K_theta = map_grid(k, delta, case, alpha, K_s, amplitude,
                                                 material, K_theta, q)
    kf, Ktf = k.ravel(), K_theta.ravel()
    out = np.zeros(kf.size)
    starts = range(0, kf.size, chunk)
    import dask  # here: importing the theory (`flexmm coefficients`) needs no Dask

    tasks = [dask.delayed(_stability_chunk)(kf[s:s + chunk], Ktf[s:s + chunk], float(alpha),
                                            float(K_s), float(amplitude), q, H,
                                            case == "coupled", modes) for s in starts]
    # chunks on the machine's cores (LAPACK on one BLAS thread releases the GIL), by the
    # threaded scheduler itself (``threaded_get``: no client lookup)
    for s, g in zip(starts, dask.compute(*tasks, scheduler=threaded_get())):
        out[s:s + chunk] = g
    return out.reshape(k.shape)


def _stability_chunk(kk, Kt, alpha, K_s, amplitude, q, H, coupled, modes):
    """Peak rate of one chunk of cells (``stability_map``); NaN where no plane wave."""
    B = kk.size
    al, Ks = np.full(B, alpha), np.full(B, K_s)
    x, res = _solve_plane_waves(kk, np.full(B, amplitude), al, Ks, Kt, coupled, H)
    ok = _on_branch(x, res, amplitude)
    A, labels = _hill_batch(x[:, :H], x[:, H:2 * H], kk, x[:, -1], al, Ks, Kt, q,
                            2 * H - 1, coupled)
    # eigenvalues everywhere, eigenvectors (to tell sideband modes) only where needed
    lam = np.linalg.eigvals(A)
    grow = lam.real.max(axis=-1) > ROUNDOFF * x[:, -1:]
    gq = np.zeros(grow.shape)
    if modes == "all" and H == 1:  # every harmonic is |p| <= CENTRE: nothing to drop
        gq = np.where(grow, lam.real.max(axis=-1), 0.0)
    elif modes == "all" and np.any(grow):
        lam_u, vec = np.linalg.eig(A[grow])
        a2 = np.broadcast_to(al[:, None] ** 2, grow.shape)[grow]
        off = _off_centre(vec, labels, a2, 2 * H - 1)
        gq[grow] = np.where(off, 0.0, lam_u.real).max(axis=-1)
    elif np.any(grow) and modes != "all":
        lam_u, vec = np.linalg.eig(A[grow])
        share = _sideband_share(vec, labels, np.broadcast_to(al[:, None] ** 2,
                                                             grow.shape)[grow])
        gq[grow] = np.where(_is_mi(share), lam_u.real, 0.0).max(axis=-1)
    g = gq.max(axis=1)
    g[g < ROUNDOFF * x[:, -1]] = 0.0
    return np.where(ok, g, np.nan)  # nan: no plane wave (resonance)


#: a launched state is quasi-periodic when its torus describes the reduced trajectory to
#: this relative misfit (1e-3 at the paper's points; the misfit jumps to O(1) where the
#: state exchanges energy resonantly, e.g. 2 Omega near omega_U(2k))
TORUS_TOLERANCE = 2e-2
#: free-phase truncation |m_j| <= FREE_ORDER of the quasi-periodic Hill matrices (the
#: peak gain at the paper's points changes by < 1e-7 relative from 1 to 2)
FREE_ORDER = 1


@one_blas_thread
def gain_spectrum(material: Material, case: str, k: float, amplitude: float, offset,
                  start: str = "travelling", modes: str = "sidebands",
                  harmonics: int = HARMONICS, free_order: int = FREE_ORDER) -> GainSpectrum:
    """Growth rate per Bloch offset q, and which field and wavenumber grow.

    Parameters are those of :func:`mi_gain`; ``free_order`` truncates the free phases of a
    launched state (|m_j| <= free_order). For ``start="travelling"`` sigma equals
    :func:`mi_gain`'s (same Hill matrices).

    Returns
    -------
    GainSpectrum
        ``sigma`` (nq,), and per q the growing mode's dominant ``field``, ``wavenumber``
        (folded into [0, pi]), lab ``frequency`` and whether it is a ``sideband`` mode.
    """
    k, amplitude = _check(material, case, k, amplitude)
    H = _check_harmonics(harmonics)
    checks.choice("start", start, STARTS)
    checks.choice("modes", modes, ("sidebands", "all"))
    # the Hill matrices grow as (2 free_order + 1)^(free phases): 4 is already far beyond
    # the converged 1 (the peak gain changes by < 1e-7 from 1 to 2)
    free_order = checks.integer("free_order", free_order, 0, 5)
    q = checks.real_array("offset", offset).ravel()
    if not np.all(np.isfinite(q)):
        raise ValueError("offset must be finite")
    if start == "travelling":
        tor, R = torus_of_wave(plane_wave(material, case, k, amplitude, H)), 0
    else:
        tor, R = _launched(material, case, k, amplitude, start, H).torus, free_order
        if tor.residual > TORUS_TOLERANCE:
            raise ArithmeticError(
                f"the state eq. `IC` launches at k = {k:.6g}, amplitude {amplitude:g} is not "
                f"quasi-periodic (torus misfit {tor.residual:.2g} over T = "
                f"{tor.duration:.0f} > {TORUS_TOLERANCE}): {_exchange(material, case, k, amplitude, start)}"
                ", so no linear theory of its sidebands applies; simulate it (flexmm point "
                "--simulate)")
    return gain_spectrum_torus(tor, material, case, q, 2 * H - 1, R, modes, start)


#: a counter-propagating wave a start launches is named from this share of the carrier on
#: (case I, k 2.5: 1.8% and quasi-periodic; k 2.98: 3.3%, misfit 0.064)
COUNTER_WAVE = 0.01


def _exchange(material, case, k, amplitude, start) -> str:
    """What a launched state that is not quasi-periodic exchanges energy with, computed
    at this material, case and k (probe 100: case I near pi was told of '2 Omega =
    omega_U(2k)', a resonance of U, which case I freezes, and far from it anyway): the
    start's own frequency against the lattice's (a frequency other than omega(k) launches
    a counter-propagating wave at -k beside the carrier) and the nearest harmonic
    resonance of the case's fields (3 Omega = omega_theta(3k); case II also 2 Omega =
    omega_U(2k), U's second harmonic)."""
    from ..lattice import initial_condition

    W = float(model.omega_rotation(k, material.alpha, material.K_s, material.K_theta))
    # the start's frequency: theta_dot = a Omega_start sin(k n) on a noiseless ring
    n = np.arange(64)
    state = initial_condition(material, case, n.size, k, amplitude, 0.0, 0, start)
    s = np.sin(k * n)
    Ws = float(state.theta_dot @ s / (amplitude * (s @ s))) if s @ s > 1e-9 else W
    near = [(abs(3 * W - float(model.omega_rotation(3 * k, material.alpha, material.K_s,
                                                       material.K_theta))) / (3 * W),
             "3 Omega = omega_theta(3k)")]
    if case == "coupled":
        near.append((abs(2 * W - float(model.omega_longitudinal(2 * k))) / (2 * W),
                     "2 Omega = omega_U(2k)"))
    detuning, name = min(near)
    counter = abs(Ws - W) / (Ws + W)
    case_name = "case II" if case == "coupled" else "case I"
    return ("its carrier exchanges energy with "
            + (f"the wave at -k its start launches beside it ({counter:.2g} of its amplitude: "
               f"theta_dot set by the frequency {Ws:.4g}, not the lattice's omega(k) = "
               f"{W:.4g}; the travelling start launches none) or " if counter > COUNTER_WAVE
               else "")
            + f"its own harmonics (the nearest resonance of {case_name}, {name}, "
            f"{detuning:.1%} off)")


@functools.lru_cache(maxsize=64)
def _launched(material, case, k, amplitude, start, harmonics):
    # the torus costs ~1 s; scenes ask for the same state at many q
    return launched_state(material, case, k, amplitude, start=start, harmonics=harmonics)
