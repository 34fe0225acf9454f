"""The lattice's four-wave theory of a plane wave, from its energy (Zakharov's kernel on a
lattice), the labels of what grows, and the bands a ring misses.

A plane wave (k, branch b, amplitude a: the carrier field's first harmonic a cos(kn - Omega t))
pumps every pair of linear waves (k1, b1), (k2, b2) with k1 + k2 = 2k (mod 2 pi). Write
the pair as k +- q. In Hill's frame (the exact theory's, ``_exact.py``) the perturbation is
e^{lambda t} e^{iqn} sum_l c_l e^{il xi}, xi = kn - Omega t; the pair is l = +1 (the wave
(k1, omega1)) and l = -1 (the conjugate of (k2, omega2)). To O(a^2) the other harmonics are
driven: l = 0 (wavenumber k1 - k, frequency omega1 - Omega: for sidebands the mean flow),
l = +2 (k + k1, Omega + omega1) and l = -2 (the conjugate of (k + k2, Omega + omega2)).
Eliminating them (a Schur complement) leaves a 2 x 2 problem for the pair's amplitudes
(p, r), c_1 = p e1, c_{-1} = r conj(e2), e^H M e = 1:

    (omega1' - w1) p + kappa12 r = 0,   (omega2' - w2) r + kappa21 p = 0,
    w1 + w2 = 2 Omega,   omega_j' = omega_j + S_j / (2 omega_j),   kappa_ij = C_ij / (2 omega_i),

    S1  = e1^H [B11 - B10 D0^-1 B01 - B12 D2^-1 B21] e1                 (cross-phase shift)
    C12 = e1^H [B1,-1 - B10 D0^-1 B0,-1] conj(e2)                       (the coupling)

and S2, C21 alike with the harmonics mirrored, where B_lh = P(kappa_l) Hhat_{l-h}
X(kappa_h) (P(kappa) = [I, e^{-i kappa} I], X(kappa) = [I; e^{i kappa} I], kappa_l = q + lk)
maps harmonic h to the force at harmonic l through the Fourier coefficients of the cell
Hessian along the wave to O(a^2): Hhat_{+-1} = T(x1), Hhat_2 = T(x2) + Q(x1, x1)/2,
Hhat_0 - H = T(x0) + Q(x1, conj x1) (x1 = (a/2)(e, e^{ik} e), x2, x0 the second harmonic
and the optical mean of the wave), and D_l = K(kappa_l) - phi_l^2 M the driven waves'
linear operators (phi_l their frequencies). Omega = omega - (g2 without its mean flow) a^2/4
is the wave's own frequency (self-phase modulation; the plane wave has no mean strain).
With the nonlinear detuning Delta' = omega1' + omega2' - 2 Omega the pair grows at

    sigma = Im sqrt((Delta'/2)^2 - kappa12 kappa21)   (= sqrt(|kappa|^2 - (Delta'/2)^2)),

the standard four-wave rate. At q -> 0 (the sidebands) the l = 0 wave is the mean flow and
the rate is the semi-discrete NLS's, sigma = (|g1|/2) q sqrt(g a^2 - q^2) (tested); near
k - pi (q -> pi: the umklapp pair) and on other branches it sees what the NLS cannot.
docs/theory.md derives it and gives FPUT's closed form at k = pi/2.

Kinds of pair ("mode_kind"): ``sidebands`` (both on the carrier's branch, |q| <= pi/2: the
pair k +- q), ``backward`` (both on the carrier's branch, |q| > pi/2: the pair
k - pi +- Q, Q = pi - |q|, the lattice's umklapp), ``parametric`` (a wave on another branch,
frequencies summing to 2 Omega); for a mode of the exact theory, ``resonance`` where its
partner is no linear wave (a harmonic resonant with a branch).
"""

from __future__ import annotations

import math
import numbers
from dataclasses import dataclass

import numpy as np

from energy import Model, ModelError

from ._exact import GAIN_FLOOR  # one floor for both theories' verdicts
from ._linear import carrier, check_amplitude, check_model, dynamical_matrix
from ._modes import _wrap, own_offset, pair_kind, wave_field

#: A driven wave whose operator has a singular value below this share of the largest is
#: resonant with a branch: the four-wave ordering fails there (a three-wave process).
RESONANT = 1e-8
#: A driven wave this large (the square root of its energy, y^H K y + phi^2 y^H M y,
#: against the pair's, omega1^2 + omega2^2: a long acoustic wave's displacement is large
#: for a small strain, its energy is not) is no longer slaved to the pair: it is a free
#: wave in a three-wave resonance with the carrier and the pair, which the four-wave
#: ordering does not treat (its rate is left nan).
DRIVEN_MAX = 0.5

#: A discriminant (Delta'/2)^2 - kappa12 kappa21 this small against its terms is round-off.
FLOOR = 1e-10

KINDS = ("sidebands", "backward", "parametric", "resonance")


@dataclass(frozen=True)
class FourWave:
    """The four-wave theory of one plane wave: every pair's rate and the fastest pair.

    Attributes
    ----------
    model : Model
    k, amplitude : float
        The carrier's wavenumber (rad/site) and first-harmonic amplitude a.
    branch : int
        The carrier's branch.
    omega, frequency : float
        Its linear frequency and its own nonlinear one Omega (self-phase modulation).
    offsets : ndarray, shape (n,)
        The pairs' offsets q in (0, pi]: waves k + q and k - q (wrapped).
    pairs : tuple of (int, int)
        Branch pairs (b1, b2) of the waves k + q and k - q, shape (m,) (every ordered pair).
    rates : ndarray, shape (n, m)
        Growth rate of each pair (1/time, >= 0; nan where a driven wave is resonant with a
        branch -- a three-wave process this ordering does not treat -- or a wave has zero
        frequency).
    detuning : ndarray, shape (n, m)
        Delta' = omega1' + omega2' - 2 Omega, the nonlinear detuning (1/time).
    coupling : ndarray, shape (n, m)
        sqrt|kappa12 kappa21|, the pair's coupling (1/time).
    undefined : str
        Why there is no theory (empty when there is one).
    """

    model: Model
    k: float
    amplitude: float
    branch: int
    omega: float
    frequency: float
    offsets: np.ndarray
    pairs: tuple
    rates: np.ndarray
    detuning: np.ndarray
    coupling: np.ndarray
    undefined: str = ""

    @property
    def gain(self) -> float:
        """The fastest pair's growth rate (1/time); nan where undefined."""
        if self.undefined:
            return math.nan
        r = np.nan_to_num(self.rates, nan=0.0)
        best = float(np.max(r)) if r.size else 0.0
        # the exact theory's floor: a rate below 3e-7 omega needs > 1e6 periods to show
        return best if best > GAIN_FLOOR * self.omega else 0.0

    @property
    def verdict(self) -> str:
        """'MI' where a pair grows, else 'stable' ('undefined' with a reason)."""
        if self.undefined:
            return "undefined"
        return "MI" if self.gain > 0 else "stable"

    def _best(self):
        r = np.nan_to_num(self.rates, nan=0.0)
        i, j = np.unravel_index(int(np.argmax(r)), r.shape)
        return int(i), int(j)

    def kind_of(self, i: int, j: int) -> str:
        """The kind of pair (offset index i, branch pair j)."""
        return pair_kind(self.branch, self.pairs[j], self.offsets[i])

    @property
    def mode_kind(self) -> str:
        """What grows fastest: 'sidebands', 'backward' or 'parametric' ('none' if stable)."""
        if self.verdict != "MI":
            return "none"
        return self.kind_of(*self._best())

    @property
    def mode_waves(self) -> tuple:
        """The fastest pair's waves ((b1, k1), (b2, k2)), wavenumbers in (-pi, pi]."""
        if self.verdict != "MI":
            return ()
        i, j = self._best()
        q = self.offsets[i]
        b1, b2 = self.pairs[j]
        return ((b1, float(_wrap(self.k + q))), (b2, float(_wrap(self.k - q))))

    @property
    def offset(self) -> float:
        """The fastest pair's own offset: q from k (sidebands, parametric) or Q = pi - q
        from k - pi (backward)."""
        if self.verdict != "MI":
            return math.nan
        i, j = self._best()
        return own_offset(self.kind_of(i, j), self.offsets[i])

    def kind_rates(self) -> dict:
        """The fastest rate of each kind of pair: {'sidebands': ..., 'backward': ...,
        'parametric': ...} (0 where none grows)."""
        out = {kind: 0.0 for kind in KINDS[:3]}
        r = np.nan_to_num(self.rates, nan=0.0)
        for j, pair in enumerate(self.pairs):
            for i in np.flatnonzero(r[:, j] > 0):
                kind = pair_kind(self.branch, pair, self.offsets[i])
                out[kind] = max(out[kind], float(r[i, j]))
        return out

    def row(self) -> dict:
        """The JSON-ready theory row: verdict, peak_gain, fastest_offset (the pair's own),
        mode_kind, mode_waves, frequency and the fastest rate of each kind."""
        return {"verdict": self.verdict,
                "peak_gain": None if self.undefined else self.gain,
                "fastest_offset": None if not math.isfinite(self.offset) else self.offset,
                "mode_kind": self.mode_kind,
                "mode_waves": [{"branch": b, "wavenumber": kap,
                                "field": wave_field(self.model, kap, b)}
                               for b, kap in self.mode_waves],
                "frequency": self.frequency if math.isfinite(self.frequency) else None,
                "kind_rates": self.kind_rates(),
                "reason": self.undefined}


def _contract(T, x):
    return np.einsum("ijm,m->ij", T, x)


def _harmonic_ratio(H, M, k, w, e, v2) -> float:
    """sqrt of the energy of the second harmonic's response v2 over the carrier's e."""
    K1, K2 = dynamical_matrix(H, k), dynamical_matrix(H, 2 * k)
    e1 = np.real(e.conj() @ K1 @ e + w**2 * e.conj() @ M @ e)
    e2 = np.real(v2.conj() @ K2 @ v2 + (2 * w) ** 2 * v2.conj() @ M @ v2)
    return math.sqrt(abs(e2) / e1) if e1 > 0 else math.inf


def second_harmonic_size(model: Model, k: float, a: float, branch=None, car=None) -> float:
    """The carrier's second harmonic at amplitude a, to O(a^2), against its first
    harmonic (square root of their energies' ratio; inf at a resonance): small for a
    weakly nonlinear wave, O(1) where 2 omega(k) meets a branch at 2k. ``car``: the
    carrier ``carrier(model, k, branch)`` where the caller has it (``travelling_wave``:
    ~0.07 ms of its ~1.3 for fput)."""
    H, T, _ = model.code.taylor(model.p)
    d = model.n_fields
    M = np.diag(np.asarray(model.masses, float))
    c = carrier(model, k, branch) if car is None else car
    X1 = np.concatenate([c.e, np.exp(1j * k) * c.e])
    P2 = np.hstack([np.eye(d), np.eye(d) * np.exp(-2j * k)])
    D2 = dynamical_matrix(H, 2 * k) - (2 * c.omega) ** 2 * M
    f2 = -P2 @ np.einsum("ibc,b,c->i", T, X1, X1) / 2
    try:
        v2 = np.linalg.solve(D2, f2)
    except np.linalg.LinAlgError:
        return math.inf
    return a / 2 * _harmonic_ratio(H, M, k, c.omega, c.e, v2)


def _plane_wave(model: Model, k: float, a: float, branch):
    """The carrier to O(a^2): (Carrier, Omega, x1, x2, x0) with x_h the cell's (u_n,
    u_{n+1}) harmonic h; or a reason string where the expansion fails."""
    H, T, Q = model.code.taylor(model.p)
    d = model.n_fields
    M = np.diag(np.asarray(model.masses, float))
    c = carrier(model, k, branch)
    e, w = c.e, c.omega
    if c.gap < 1e-7 * max(w, 1e-300):
        return f"degenerate carrier: another branch has the frequency {w:.6g} at k = {k:.6g}"
    z = np.exp(1j * k)
    X1 = np.concatenate([e, z * e])
    scale = max(1.0, float(np.max(np.abs(H))))

    def P(kap):
        return np.hstack([np.eye(d), np.eye(d) * np.exp(-1j * kap)])

    D2 = dynamical_matrix(H, 2 * k) - (2 * w) ** 2 * M
    f2 = -P(2 * k) @ np.einsum("ibc,b,c->i", T, X1, X1) / 2
    sv = np.linalg.svd(D2, compute_uv=False)
    if sv[-1] < RESONANT * max(sv[0], scale) and np.linalg.norm(f2) > RESONANT * scale:
        return f"second harmonic resonant with a branch at 2k = {2 * k:.6g}"
    v2 = np.linalg.lstsq(D2, f2, rcond=None)[0]
    # near (not at) that resonance the second harmonic is no longer slaved: its energy
    # against the first harmonic's, as DRIVEN_MAX measures a pair's driven waves
    size = a / 2 * _harmonic_ratio(H, M, k, w, e, v2)
    if size > DRIVEN_MAX:
        return (f"second harmonic near resonance with a branch at 2k = {2 * k:.6g}: its energy "
                f"{size**2:.3g} x the carrier's at amplitude {a:.6g}; the four-wave ordering "
                "fails there (a three-wave process; the exact theory holds)")
    K0 = np.real(dynamical_matrix(H, 0.0))
    f0 = -np.real(P(0.0) @ np.einsum("ibc,b,c->i", T, X1, X1.conj()))
    w0 = np.linalg.pinv(K0, rcond=1e-10, hermitian=True) @ f0  # optical mean: no strain
    X2 = np.concatenate([v2, z**2 * v2])
    X0 = np.concatenate([w0, w0]).astype(complex)
    F1 = -P(k) @ (np.einsum("ibc,b,c->i", T, X0, X1) + np.einsum("ibc,b,c->i", T, X2, X1.conj())
                  + np.einsum("ibcd,b,c,d->i", Q, X1, X1, X1.conj()) / 2)
    g2_wave = float(np.real(e.conj() @ F1)) / (2 * w * float(np.real(e.conj() @ M @ e)))
    Omega = w - g2_wave * a**2 / 4
    return c, Omega, a / 2 * X1, a**2 / 4 * X2, a**2 / 4 * X0


def pair_rates(model: Model, k: float, amplitude: float, branch=None, offsets=None):
    """Every pair's (rate, detuning, coupling), each shape (n, d^2), at the offsets q
    (shape (n,)), the branch pairs and the plane wave's (Carrier, Omega); a reason string
    where the expansion fails. The kernel of the module docstring, vectorised over q."""
    kernel = _kernel(model, k, float(amplitude), branch)
    if isinstance(kernel, str):
        return kernel
    rates, pairs, car, Omega = kernel
    return (*rates(offsets), pairs, car, Omega)


def _kernel(model: Model, k: float, a: float, branch):
    """(rates, pairs, carrier, Omega): rates(q) -> (rate, detuning, coupling) of every
    branch pair at the offsets q; or the reason the expansion fails."""
    wave = _plane_wave(model, k, a, branch)
    if isinstance(wave, str):
        return wave
    car, Omega, x1, x2, x0 = wave
    H, T, Q = model.code.taylor(model.p)
    d = model.n_fields
    pairs = [(b1, b2) for b1 in range(d) for b2 in range(d)]
    Hh = {1: _contract(T, x1), -1: _contract(T, x1.conj()),
          2: _contract(T, x2) + np.einsum("ijmn,m,n->ij", Q, x1, x1) / 2}
    Hh[-2] = Hh[2].conj()
    Hh[0] = _contract(T, x0) + np.einsum("ijmn,m,n->ij", Q, x1, x1.conj())
    return (lambda offsets: _rates(model, k, car, Omega, Hh, pairs, offsets)), pairs, car, Omega


def _rates(model, k, car, Omega, Hh, pairs, offsets):
    H = model.code.taylor(model.p)[0]
    d = model.n_fields
    m = np.asarray(model.masses, float)
    s = 1 / np.sqrt(m)
    q = np.atleast_1d(np.asarray(offsets, dtype=float))
    n = q.size
    eye = np.eye(d)

    def Pm(kap):  # (n, d, 2d)
        ph = np.exp(-1j * kap)[:, None, None]
        return np.concatenate([np.broadcast_to(eye, (kap.size, d, d)), eye * ph], axis=2)

    def Xm(kap):  # (n, 2d, d)
        ph = np.exp(1j * kap)[:, None, None]
        return np.concatenate([np.broadcast_to(eye, (kap.size, d, d)), eye * ph], axis=1)

    kap = {l: q + l * k for l in (-2, -1, 0, 1, 2)}
    P_ = {l: Pm(kap[l]) for l in kap}
    X_ = {l: Xm(kap[l]) for l in kap}

    def B(l, h):
        return P_[l] @ Hh[l - h] @ X_[h]

    def K(kp):  # (n, d, d)
        z = np.exp(1j * kp)[:, None, None]
        return (H[:d, :d] + H[d:, d:]) + H[:d, d:] * z + H[d:, :d] / z

    def modes(kp):
        A = s[None, :, None] * K(kp) * s[None, None, :]
        lam, phi = np.linalg.eigh(A)
        om = np.where(lam >= 0, np.sqrt(np.abs(lam)), np.nan)
        return om, s[None, :, None] * phi  # e^H M e = 1

    om1, E1 = modes(q + k)
    om2, E2 = modes(k - q)
    Bs = {(l, h): B(l, h) for l, h in ((1, 1), (-1, -1), (1, -1), (-1, 1), (1, 0), (0, 1),
                                        (0, -1), (-1, 0), (1, 2), (2, 1), (-1, -2), (-2, -1))}
    Kd = {l: K(kap[l]) for l in (0, 2, -2)}
    M = np.diag(m)
    # the driven second harmonics at the carrier's linear 2 omega, as the carrier's own
    # (_plane_wave): the same denominator at q -> 0, where the pair is the carrier
    w = car.omega
    rate = np.full((n, len(pairs)), np.nan)
    det = np.full_like(rate, np.nan)
    coup = np.full_like(rate, np.nan)

    def mv(A, v):
        return np.einsum("nij,nj->ni", A, v)

    def solve(D, f):
        # a nearly singular D shows as a driven wave too large to be slaved (DRIVEN_MAX);
        # an exactly singular one (rare) is found by the SVD
        try:
            y = np.linalg.solve(D, f[..., None])[..., 0]
            return y, ~np.all(np.isfinite(y), axis=1)
        except np.linalg.LinAlgError:
            sv = np.linalg.svd(D, compute_uv=False)
            bad = sv[:, -1] < RESONANT * np.maximum(sv[:, 0], 1.0)
            Dr = np.where(bad[:, None, None], np.eye(d), D)
            return np.linalg.solve(Dr, f[..., None])[..., 0], bad

    # nan where a wave has zero frequency, or its coupling overflows (a branch at 1e150)
    with np.errstate(invalid="ignore", divide="ignore", over="ignore"):
        for j, (b1, b2) in enumerate(pairs):
            w1, w2 = om1[:, b1], om2[:, b2]
            e1, e2c = E1[:, :, b1], E2[:, :, b2].conj()
            t1 = Omega + (w1 - w2) / 2  # the pair's frequencies, summing to 2 Omega
            t2 = Omega + (w2 - w1) / 2
            D0 = Kd[0] - ((t1 - Omega) ** 2)[:, None, None] * M
            D2 = Kd[2] - ((t1 - Omega + 2 * w) ** 2)[:, None, None] * M
            Dm2 = Kd[-2] - ((t2 - Omega + 2 * w) ** 2)[:, None, None] * M
            y01, r0 = solve(D0, mv(Bs[0, 1], e1))
            y0m, _ = solve(D0, mv(Bs[0, -1], e2c))
            y2, r2 = solve(D2, mv(Bs[2, 1], e1))
            ym2, rm2 = solve(Dm2, mv(Bs[-2, -1], e2c))
            f1 = mv(Bs[1, 1], e1) - mv(Bs[1, 0], y01) - mv(Bs[1, 2], y2)
            c12 = mv(Bs[1, -1], e2c) - mv(Bs[1, 0], y0m)
            fm = mv(Bs[-1, -1], e2c) - mv(Bs[-1, 0], y0m) - mv(Bs[-1, -2], ym2)
            c21 = mv(Bs[-1, 1], e1) - mv(Bs[-1, 0], y01)
            S1 = np.real(np.einsum("ni,ni->n", e1.conj(), f1))
            S2 = np.real(np.einsum("ni,ni->n", e2c.conj(), fm))
            C12 = np.einsum("ni,ni->n", e1.conj(), c12)
            C21 = np.einsum("ni,ni->n", e2c.conj(), c21)
            kk = C12 * C21 / (4 * w1 * w2)
            delta = w1 + S1 / (2 * w1) + w2 + S2 / (2 * w2) - 2 * Omega
            disc = delta**2 / 4 - kk
            sig = np.abs(np.imag(np.sqrt(disc + 0j)))
            # a pair at the edge of its band: the discriminant is round-off, not growth
            sig[np.abs(disc) <= FLOOR * np.maximum(np.abs(kk), delta**2 / 4)] = 0.0
            size = np.max([np.sqrt(np.abs(_energy(Kd[l], m, y, f)) / (w1**2 + w2**2))
                           for l, y, f in ((0, y01, t1 - Omega), (0, y0m, t1 - Omega),
                                           (2, y2, t1 - Omega + 2 * w), (-2, ym2, t2 - Omega + 2 * w))],
                           axis=0)
            resonant = r0 | r2 | rm2 | (size > DRIVEN_MAX)
            # a zero-frequency wave (a uniform translation, kappa = 0) is no wave
            still = ~(np.minimum(w1, w2) > 1e-9 * max(car.omega, 1e-300))
            rate[:, j] = np.where(resonant | still | ~np.isfinite(sig), np.nan, sig)
            det[:, j] = delta
            coup[:, j] = np.sqrt(np.abs(kk))
    return rate, det, coup


def _energy(K, m, y, phi):
    return (np.einsum("ni,nij,nj->n", y.conj(), K, y)
            + phi**2 * np.einsum("ni,i,ni->n", y.conj(), m, y)).real


def _offset_grid(samples: int) -> np.ndarray:
    # log-spaced near q = 0 (sidebands) and q = pi (the backward pair k - pi +- Q): a weak
    # wave's bands there are O(a) wide, narrower than the uniform grid's step
    near = np.geomspace(1e-4, math.pi / samples, 24, endpoint=False)
    return np.unique(np.concatenate([near, np.linspace(math.pi / samples, math.pi, samples),
                                     math.pi - near]))


def _resonances(det, q):
    """Offsets where a pair's nonlinear detuning crosses zero between grid points (the
    centre of its band, however narrow; linear interpolation), any branch pair."""
    out = []
    for j in range(det.shape[1]):
        dj = det[:, j]
        ok = np.isfinite(dj[:-1]) & np.isfinite(dj[1:])
        i = np.flatnonzero(ok & (np.sign(dj[:-1]) * np.sign(dj[1:]) < 0))
        out.append(q[i] + (q[i + 1] - q[i]) * dj[i] / (dj[i] - dj[i + 1]))
    return np.unique(np.concatenate(out)) if out else np.zeros(0)


def _merge(q, arrays, q2, arrays2):
    qq = np.concatenate([q, q2])
    order = np.argsort(qq, kind="stable")
    return (qq[order], *(np.concatenate([x, y])[order] for x, y in zip(arrays, arrays2)))


def four_wave(model: Model, k: float, amplitude: float, branch=None, *, N: int | None = None,
              samples: int = 128) -> FourWave:
    """The four-wave theory of the plane wave (k, ``branch``, ``amplitude``) of ``model``.

    Parameters
    ----------
    model : Model
    k : float
        Carrier wavenumber in (0, pi] (rad/site); on a ring of ``N`` sites snapped to
        2 pi m / N, as ``exact_gain`` does.
    amplitude : float
        a: the carrier field's first harmonic is a cos(k n - Omega t).
    branch : int or str, optional
        The carrier's branch (index or field name; default the model's).
    N : int, optional
        A ring of N sites: the pairs are its modes, q = 2 pi j / N. None: the infinite
        chain (``samples`` offsets in [pi / samples, pi], 24 log-spaced below, the
        fastest refined between its neighbours).

    Returns
    -------
    FourWave
        Every pair's rate; ``gain``, ``verdict``, ``mode_kind``, ``mode_waves`` and
        ``offset`` of the fastest. ``undefined`` (with nan rates) where the carrier's
        expansion fails (a resonant second harmonic, a degenerate carrier) or the model's
        energy is not real along the wave (``energy_not_real``).
    """
    from ._simulate import check_count, check_ring, snap_ring

    check_model(model)
    a = check_amplitude(amplitude)
    if N is not None:  # N = 0 is a bad ring, not the infinite chain (as exact_gain's)

        N = check_ring(N)
        k = snap_ring(k, N)[0]
        q = 2 * np.pi * np.arange(1, N // 2 + 1) / N
    else:
        if isinstance(k, (bool, np.bool_)) or not isinstance(k, numbers.Real):
            raise ModelError(f"k must be a real number in (0, pi], got {type(k).__name__} "
                             f"{k!r}")
        k = float(k)
        if not (math.isfinite(k) and 0 < k <= math.pi):
            raise ModelError(f"k must be in (0, pi], got {k!r}")
        q = _offset_grid(check_count("samples", samples, least=8))  # exact_gain's rule
    from ._nls import check_resolved_amplitude
    from ._reach import energy_not_real

    check_resolved_amplitude(model, k, a, branch)  # no rates from rounding
    # a wave the model cannot carry (its energy not real along it) has no four-wave rates:
    # the kernel's Taylor coefficients at rest would rate it as if it existed
    kernel = energy_not_real(model, k, a, branch) or _kernel(model, k, a, branch)
    d = model.n_fields
    if isinstance(kernel, str):
        car = carrier(model, k, branch)
        nan = np.full((q.size, d * d), np.nan)
        return FourWave(model, k, a, car.branch, car.omega, math.nan, q,
                        tuple((i, j) for i in range(d) for j in range(d)), nan, nan, nan,
                        kernel)
    rates, pairs, car, Omega = kernel
    rate, det, coup = rates(q)
    if not N:
        extra_q = _resonances(det, q)
        if extra_q.size:
            q, rate, det, coup = _merge(q, (rate, det, coup), extra_q, rates(extra_q))
        # the infinite chain's fastest pair between the samples: two finer local grids
        for _ in range(2):
            r = np.nan_to_num(rate, nan=0.0)
            if not np.max(r) > 0:
                break
            i = int(np.unravel_index(int(np.argmax(r)), r.shape)[0])
            fine = np.linspace(q[max(i - 1, 0)], q[min(i + 1, q.size - 1)], 35)[1:-1]
            q, rate, det, coup = _merge(q, (rate, det, coup), fine, rates(fine))
    why = ""
    if not np.nanmax(np.nan_to_num(rate, nan=0.0), initial=0.0) > GAIN_FLOOR * car.omega:
        why = _untreated(q, pairs, rate, det)
    return FourWave(model, k, a, car.branch, car.omega, float(Omega), q, tuple(pairs),
                    rate, det, coup, why)


def _untreated(q, pairs, rate, det) -> str:
    """Why 'stable' cannot be said: a pair resonant (its detuning through zero) where its
    rate is nan -- a driven wave not slaved, a three-wave process this ordering does not
    rate -- or '' where every resonant pair was rated."""
    for j, pair in enumerate(pairs):
        d, r = det[:, j], rate[:, j]
        i = np.flatnonzero(np.isfinite(d[:-1]) & np.isfinite(d[1:])
                           & (np.sign(d[:-1]) * np.sign(d[1:]) < 0)
                           & (np.isnan(r[:-1]) | np.isnan(r[1:])))
        if i.size:
            return (f"no rated pair grows, but the pair of branches {pair} is resonant at "
                    f"offset {q[i[0]]:.4g} through a driven wave too large to be slaved (a "
                    "three-wave process the four-wave ordering does not rate; the exact "
                    "theory holds)")
    return ""
