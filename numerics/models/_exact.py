"""The exact lattice theory of any model: the Hill (Floquet) spectrum of the sidebands of
its exact travelling plane wave (the wave by harmonic balance: ``_wave``).

Hill spectrum. A perturbation e^{lambda t} e^{i q n} sum_{|l| <= P} c_l e^{i l xi_n} turns
the linearised equations into a quadratic eigenproblem in lambda whose coefficients are the
Fourier coefficients of the cell Hessian along the wave (sampled from the generated
``cell_hessian_into``):

    m (lambda - i l omega)^2 c_l + sum_h [Hhat_{l-h}[:d] X_h(q)
                                          + e^{-i (l-h) k} Hhat_{l-h}[d:] Y_h(q)] = 0,

X_h = (c_h, e^{i (q + h k)} c_h), Y_h = (e^{-i (q + h k)} c_h, c_h). At a = 0 it reduces to
lambda = i (l omega +- omega_b(q + l k)) (checked in tests); the wave is unstable where
some Re lambda > 0. A physical mode of spatial wavenumber kappa appears at every q with
q + l k = kappa; only its copies centred at l = -1, 0 or 1 (which the scan over q reaches
for every kappa) with less than 1e-6 of their weight in the outer three harmonics are kept:
the copies near the truncation are artefacts (measured: rates up to 4e-4 on an FPUT chain
that is stable, at l = 18 of 20). The growth a simulation sees is the largest rate over
the kept modes; the mode is named by its wavenumber kappa = q + l k: sidebands of the
carrier (within pi/4 of +-k: the modulational instability) or a resonance elsewhere.

How it is computed (issue 41: at most a tenth of one run of the point). The wave: Gauss-
Newton on the collocation equations with their exact Jacobian, the DFT of the generated
cell Hessian along the wave (least squares with finite differences where Newton does not
settle). The spectrum: compiled (``_sidebands``) at P = min(H + 4, WORK_HARMONICS)
harmonics. Gershgorin discs about the roots i (l omega +- w) of each harmonic's own block,
with the roots' Krein signs, certify the offsets and frequencies where no mode can grow;
each cluster of discs that can hold a growing mode centred at l = -1, 0, 1 is solved by
Newton on its Schur complement, and the modes found are kept by the same weights as the
dense eigenproblem's (heaviest at |l| <= 1, a tie of harmonics centred at their mean:
``CENTRE_TIE``; < 1e-6 in the outer three harmonics). Where a
cluster is too large (strong coupling, or a flat branch: flexmm), or Newton does not
settle, the central harmonics' pencil at |l| <= P - 5 with the outer ones folded in, its
growing eigenvalues refined by Newton at P, fastest first (``_strong``: flexmm's offsets
at ~1/4 of the dense eigenproblem's cost; that pencil in real arithmetic where a diagonal
phase makes the Hill matrix real, every built-in model's wave: ``_real_gauge``, ~1/3 of
the complex eigensolver's cost); where that does not settle either, that
offset's dense eigenproblem at the same P. On a ring (k = 2 pi m / N) a one-field wave's
modes are found once, in the clusters that hold an l = 0 root, at every ring offset, and
moved to the offsets q - s k where they are centred at l = s (``_ring_copies``: about
half the clusters solved). The fastest mode is computed again
at P + PERSIST_STEP (the truncation persistence rule of CONVENTIONS.md;
``HillSpectrum.truncations`` names both); where it moves by more than 1e-6 relative, the
whole spectrum is the dense one at H + 4. tests/test_exact_gain_anchors.py holds the
implementation before this one (dense ``eig`` at H + 4 per offset) to 1e-6 relative.
Where the wave's second harmonic is large (``HARMONIC_CHECK``: every flexmm carrier) the
continuation from small amplitude (``_connected``) gives the wave, the harmonic balance
from the linear wave solved only where the continuation loses the branch. On the infinite
chain a band narrower than a sample step is found where two roots of opposite Krein signs
cross between quiet samples (``_crossings``).
"""

from __future__ import annotations

import dataclasses
import functools
import math
import numbers
from dataclasses import dataclass

import numpy as np

from common.threads import one_blas_thread
from energy import Model, ModelError

from ._args import ring_offsets  # noqa: F401 (here too, for its importers)
from ._linear import check_harmonics, scalar
from ._wave import TravellingWave, _wrap, continued_wave, travelling_wave  # noqa: F401 (here too)
from ._wave_solve import _grid

#: A growth rate below this fraction of omega is round-off of the eigensolver: at a
#: commensurate k (k = 2 pi p / r) a mode appears in several harmonics and its eigenvalues
#: are degenerate, which eig resolves only to sqrt(machine epsilon) (measured up to
#: 8e-8 omega on FPUT at k = pi / 2); a rate that small needs > 1e6 periods to show.
GAIN_FLOOR = 3e-7

#: Harmonics whose weights are within this (relative) of a mode's largest tie. A
#: four-wave pair holds its two waves in harmonics l and l - 2 with equal weight where the
#: waves mirror each other (README's fput at k = pi / 2: a backward pair, both waves at
#: k - pi, weighs 0.4954 at l = 0 and at l = 2 at q = pi / 2, equal to 1e-15; flexmm at
#: q = pi - k and q = k). The heaviest harmonic was then round-off's pick, and the mode
#: was kept or dropped by it: the merged-and-reverted sparse kernel of 2026-11-26 moved
#: that round-off and README's mode lost its name. A tie is centred at its harmonics'
#: mean: {0, 2} at 1 (kept), {1, 3} at 2 (not: its copy {-1, 1} two offsets over is).
#: 1e-6: above the weights' error (measured <= 2e-12 at such ties; the eigenvector's,
#: ~ eps |A| / rate, <= 1e-8 at the rate floor), below any difference that names one.
CENTRE_TIE = 1e-6


def _centre(per_l, l_):
    """Where each mode is centred: (harmonic, central), per row of ``per_l`` (weights
    over ``l_``, last axis). Its heaviest harmonic; where others tie with it
    (``CENTRE_TIE``), the tie's mean decides ``central`` (|mean| <= 1) and the tied
    harmonic nearest l = 0 is reported where the heaviest is not central."""
    per_l = np.asarray(per_l)
    heavy = l_[np.argmax(per_l, axis=-1)]
    tied = per_l >= (1 - CENTRE_TIE) * per_l.max(axis=-1, keepdims=True)
    mean = (tied * l_).sum(axis=-1) / tied.sum(axis=-1)
    central = np.abs(mean) <= 1
    near = l_[np.argmin(np.where(tied, np.abs(l_), np.inf), axis=-1)]
    return np.where(central & (np.abs(heavy) > 1), near, heavy), central


@dataclass(frozen=True)
class HillSpectrum:
    """Growth rates of the sidebands of a travelling wave.

    Attributes
    ----------
    wave : TravellingWave
    offsets : ndarray
        Perturbation wavenumbers q (rad/site), as asked.
    gain : ndarray
        Largest Re lambda over the resolved modes at each q (1/time, >= 0).
    harmonic : ndarray of int
        The harmonic l (-1, 0 or 1: only modes centred there are kept, which every mode is
        at some q) that carries most of the fastest mode's weight at each q.
    sideband_offset : ndarray
        Where the fastest mode at q holds >= 10% of its weight within pi/4 of the carrier's
        +-k (a modulational mode: at k = pi a sideband pair with the mean flow), its
        heaviest such component's distance from +-k (rad/site); else nan. Where no mode
        grows (gain 0): harmonic 0 and nan.
    truncations : tuple of int
        The truncations P (harmonics l = -P..P) the verdict rests on: the spectrum's,
        then the one the fastest mode was checked to persist at (CONVENTIONS.md: a mode
        counts when it persists at the same q across truncations).
    """

    wave: TravellingWave
    offsets: np.ndarray
    gain: np.ndarray
    harmonic: np.ndarray
    sideband_offset: np.ndarray
    truncations: tuple = ()

    peak_gain = property(lambda self: float(np.max(self.gain)) if self.gain.size else 0.0)

    def to_xarray(self):
        """The spectrum as an ``xarray.Dataset`` over ``offset`` (q): ``gain``, the kept
        mode's ``harmonic`` and ``sideband_offset``; the model, its parameters, k,
        amplitude, omega and the verdict in attrs."""
        import xarray as xr

        w = self.wave
        attrs = {"model": w.model.name, "k": w.k, "amplitude": w.amplitude, "omega": w.omega,
                 "omega_linear": w.carrier.omega, "branch": w.carrier.branch,
                 "verdict": self.verdict, "peak_gain": self.peak_gain, "mode": self.mode,
                 "truncations": list(self.truncations),
                 "units": "lattice units: time as in the model file, wavenumbers rad/site"}
        attrs.update({f"param_{n}": v for n, v in w.model.params.items()})
        return xr.Dataset(
            {"gain": ("offset", self.gain, {"long_name": "growth rate of the fastest kept "
                                                         "mode", "units": "1/time"}),
             "harmonic": ("offset", self.harmonic, {"long_name": "its dominant harmonic l"}),
             "sideband_offset": ("offset", self.sideband_offset,
                                 {"long_name": "its sideband component's distance from "
                                               "+-k (nan: a resonance)",
                                  "units": "rad/site"})},
            coords={"offset": ("offset", self.offsets,
                               {"long_name": "perturbation wavenumber q", "units": "rad/site"})},
            attrs=attrs)

    @property
    def modulational_gain(self) -> float:
        """The fastest rate among the sideband modes only (what the NLS describes); the
        peak_gain may be a resonance's, far from the carrier."""
        side = np.isfinite(self.sideband_offset) & (self.gain > 0)
        return float(np.max(self.gain[side])) if side.any() else 0.0

    @property
    def fastest_wavenumber(self) -> float:
        """The spatial wavenumber kappa = q + l k (wrapped to (-pi, pi]) of the fastest
        mode's dominant harmonic."""
        if not self.gain.size or self.peak_gain <= 0:
            return math.nan
        i = int(np.argmax(self.gain))
        kap = self.offsets[i] + self.harmonic[i] * self.wave.k
        return float((kap + np.pi) % (2 * np.pi) - np.pi)

    @property
    def fastest_offset(self) -> float:
        """The fastest mode's sideband offset from the carrier's +-k (rad/site); for a
        resonance (no sideband component), the distance of its wavenumber from +-k."""
        if not self.gain.size or self.peak_gain <= 0:
            return math.nan
        off = self.sideband_offset[int(np.argmax(self.gain))]
        if math.isfinite(off):
            return float(off)
        kap, k = self.fastest_wavenumber, self.wave.k
        return float(min(_wrap(kap - k), _wrap(kap + k)))

    @property
    def verdict(self) -> str:  # 'MI' where a sideband grows, else 'stable'
        return "MI" if self.peak_gain > 0 else "stable"

    @property
    def mode(self) -> str:
        """Where the fastest mode lies: 'sidebands k +- q' (it has sideband components near
        the carrier) or 'resonance at wavenumber kappa' (none: its dominant harmonic's
        wavenumber). Its kind (a backward or parametric pair, a three-wave decay) is
        ``classify_mode``'s, which ``point``'s row names it by."""
        if self.peak_gain <= 0:
            return "none"
        if math.isfinite(self.sideband_offset[int(np.argmax(self.gain))]):
            return "sidebands k +- q"
        return f"resonance at wavenumber {self.fastest_wavenumber:.4g}"


def _hessian_harmonics(wave: TravellingWave, P: int):
    """Hhat_s, s = -2P..2P, of the cell Hessian along the wave: shape (4P + 1, 2d, 2d)."""
    model = wave.model
    d = model.n_fields
    M, here, there, E = _hessian_bases(wave.harmonics, P, wave.k)
    c = wave.coefficients
    # the wave's profile at xi and xi + k (``TravellingWave.profile``'s arithmetic: its
    # tensordot over the harmonics is this dot)
    x = np.concatenate([np.real(np.dot(c, here)), np.real(np.dot(c, there))])
    Hs = np.empty((2 * d, 2 * d, M))
    model.code.cell_hessian_into(x, model.p, Hs)
    return np.einsum("abm,sm->sab", Hs, E) / M


@functools.lru_cache(maxsize=64)
def _hessian_bases(H: int, P: int, k: float):
    """(M, e^{i h xi}, e^{i h (xi + k)}, e^{-i s xi}) of ``_hessian_harmonics``: they do
    not depend on the amplitude, so a damped point's waves at its lower amplitudes share
    them (kept, read only, the 64 latest: thread safe)."""
    M = max(128, 8 * P + 8, 4 * H + 8)
    xi = _grid(M)
    h = np.arange(-H, H + 1)
    s = np.arange(-2 * P, 2 * P + 1)
    out = (np.exp(1j * h[:, None] * xi), np.exp(1j * h[:, None] * (xi + k)),
           np.exp(-1j * s[:, None] * xi[None, :]))
    for arr in out:
        arr.flags.writeable = False
    return (M, *out)


@one_blas_thread
def hill_spectrum(wave: TravellingWave, offsets, *, harmonics: int | None = None,
                  return_eigenvalues: bool = False):
    """The growth rate of the fastest resolved sideband mode at each offset q.

    ``harmonics`` P: the perturbation's harmonics l = -P..P (default: the wave's H + 4;
    an integer >= 4: below, no sideband mode is resolved and every gain would read 0).
    With ``return_eigenvalues``, also the lambdas at each q (list of arrays). On one BLAS
    thread (``common.threads``).
    """
    if not isinstance(wave, TravellingWave):
        raise ModelError(f"wave must be a TravellingWave (numerics.models.travelling_wave), "
                         f"got {type(wave).__name__}")
    q = np.atleast_1d(np.asarray(offsets))
    if q.ndim != 1:
        raise ModelError(f"offsets must be a number or a 1-D array of offsets q (rad/site), "
                         f"got an array of shape {q.shape}: pass offsets.ravel() and "
                         f"reshape the gain")
    if q.dtype.kind not in "fiu" or not np.all(np.isfinite(q)):
        raise ModelError(f"offsets must be finite real numbers (rad/site), got {offsets!r}")
    # below P = 4 the outer three harmonics, where a kept mode must hold < 1e-6 of its
    # weight, include l = +-1 where every sideband mode sits: each would be dropped and
    # the gain read 0 (stable) whatever the wave
    harmonics = check_harmonics(harmonics, 4, "a sideband mode sits at l = +-1, and a "
                                "mode counts only with < 1e-6 of its weight in the outer "
                                "three harmonics")
    return _hill_spectrum(wave, q.astype(float), harmonics, return_eigenvalues)


#: The fast path's truncation: harmonics l = -P..P with P = min(H + 4, WORK_HARMONICS)
#: (H + 4 for a strongly nonlinear wave, ``_work_harmonics``).
#: A kept mode is centred at |l| <= 1 with < 1e-6 of its weight in the outer three
#: harmonics; its tail falls faster than geometrically (the gaps grow as (l omega)^2).
#: Measured against the dense spectrum at P = H + 4 (20 for flexmm): the anchors
#: (tests/test_exact_gain_anchors.py) and 144 random points of six models pass at P = 10;
#: P = 8 passes the anchors too and 36 of the random points (it would halve flexmm's
#: cost), 10 is kept as the margin; at P = 6 modes are dropped (the weight filter reaches
#: them). Every spectrum's fastest mode is checked at P + PERSIST_STEP.
WORK_HARMONICS = 10
#: the second truncation the fastest mode is checked at: P + PERSIST_STEP
PERSIST_STEP = 4
#: growing modes per offset the compiled path reports at most, and the largest cluster of
#: roots (coordinates) it solves; beyond either, that offset's dense eigenproblem
MAX_MODES, MAX_CLUSTER = 12, 6


def _work_harmonics(wave) -> int:
    """The compiled path's truncation: min(H + 4, WORK_HARMONICS) for a wave whose
    harmonics fell below 1e-13 of its amplitude by H = 16; H + 4 (the dense path's) for a
    strongly nonlinear one (measured: fput alpha 0.51, beta 1.91, k 0.70, a 0.24 has
    H = 32 and a growing mode at q = 0.196 made of the harmonics 1 and 5, which at P = 10
    holds more than 1e-6 of its weight in the outer three and is dropped)."""
    H = wave.harmonics
    return H + 4 if H > 16 else min(H + 4, WORK_HARMONICS)


def _hill_spectrum(wave, offsets, harmonics=None, return_eigenvalues=False):
    offsets = np.atleast_1d(np.asarray(offsets, dtype=float))
    if harmonics or return_eigenvalues:
        from ._hill_dense import _dense_spectrum

        return _dense_spectrum(wave, offsets, harmonics or wave.harmonics + 4,
                               return_eigenvalues)
    return _Sidebands(wave).checked(offsets)


class _Sidebands:
    """The compiled Hill spectrum of one wave at truncation P (``_sidebands``): the cell
    Hessian's harmonics computed once for every offset asked."""

    def __init__(self, wave, P=None, Hh=None):
        self.wave = wave
        self.P = P or _work_harmonics(wave)
        self.Hh = _hessian_harmonics(wave, self.P) if Hh is None else Hh  # a caller's
        self.edge = False  # a mode grown into the outer harmonics (``_keep``, ``checked``)
        self.masses = np.asarray(wave.model.masses, float)
        self.floor = GAIN_FLOOR * max(wave.omega, 1e-300)

    def spectrum(self, offsets, gains_only=False, eigenvalues=None) -> HillSpectrum:
        """The spectrum at ``offsets``; ``gains_only``: the rates alone (harmonic 0 and
        sideband offset nan where the compiled path keeps a mode: a damped point's lower
        amplitudes, ``_losses_sampling``). ``eigenvalues``: the fastest kept mode's lambda
        (2-D, (offsets, MAX_MODES): every kept growing one's) where a compiled path found
        it (``_losses_hill``)."""
        from ._sidebands import sideband_modes
        from ._strong import CENTRAL_MARGIN, strong_modes

        wave, P = self.wave, self.P
        offsets = np.atleast_1d(np.asarray(offsets, dtype=float))
        gains = np.zeros(offsets.size)
        modes = np.zeros(offsets.size, int)
        offs = np.full(offsets.size, math.nan)
        # every argument given (numba's specialisation without the defaults: 3-15% slower)
        lam, vec, count = sideband_modes(self.Hh, self.masses, wave.k, wave.omega, P, offsets,
                                         self.floor, MAX_MODES, MAX_CLUSTER, True, False)
        self._keep(offsets, lam, vec, count, gains, modes, offs, gains_only, eigenvalues)
        dense = np.flatnonzero(count < 0)
        Pc = P - CENTRAL_MARGIN
        if dense.size and 2 <= Pc and P <= WORK_HARMONICS + PERSIST_STEP:
            # the clusters chain (strong coupling): the central pencil, the rest folded in
            # (it refines ~1.6 modes an offset, 4 at most at the bench points: more than
            # MAX_MODES, that offset's dense eigenproblem)
            lam, vec, count = strong_modes(self.Hh, self.masses, wave.k, wave.omega, P, Pc,
                                           offsets[dense], self.floor, MAX_MODES)
            sub = (gains[dense], modes[dense], offs[dense],
                   None if eigenvalues is None else eigenvalues[dense])
            self._keep(offsets[dense], lam, vec, count, *sub[:3], eigenvalues=sub[3])
            gains[dense], modes[dense], offs[dense] = sub[:3]
            if eigenvalues is not None:
                eigenvalues[dense] = sub[3]
            dense = dense[count < 0]
        if dense.size:
            from ._hill_dense import _dense_growing

            sub = _dense_growing(wave, offsets[dense], P)
            gains[dense], modes[dense] = sub.gain, sub.harmonic
            offs[dense] = sub.sideband_offset
        return HillSpectrum(wave=wave, offsets=offsets, gain=gains, harmonic=modes,
                            sideband_offset=offs, truncations=(P,))

    def _keep(self, offsets, lam, vec, count, gains, modes, offs, gains_only=False,
              eigenvalues=None):
        """The kept modes' rate, harmonic and sideband offset (and lambda: ``eigenvalues``)
        into gains, modes, offs at the offsets with count >= 0 (the dense spectrum's rule:
        heaviest at |l| <= 1 or a tie centred there, < 1e-6 of it in the outer three)."""
        P, k, d = self.P, self.wave.k, self.wave.model.n_fields
        if gains_only:  # the rates alone: the same rule, compiled (``_kept``)
            from ._kept import kept_gains

            kept_gains(lam, vec, count, P, d, self.floor, gains, CENTRE_TIE)
            return
        l_ = np.arange(-P, P + 1)
        # only the offsets that hold a mode (a stable chain's 440: none; the same values)
        rows = np.flatnonzero(count > 0)
        if not rows.size:
            return
        offsets, lam, vec, count = offsets[rows], lam[rows], vec[rows], count[rows]
        # the slots that hold a mode anywhere (flexmm: <= 4 of MAX_MODES): the same values
        width = max(int(count.max(initial=0)), 1)
        lam, vec = lam[:, :width], vec[:, :width]
        c = np.abs(vec) ** 2                                         # (Q, modes, n)
        weight = c / np.maximum(c.sum(axis=-1, keepdims=True), 1e-300)
        per_l = weight.reshape(offsets.size, width, 2 * P + 1, d).sum(axis=-1)
        centre, central = _centre(per_l, l_)
        outer = per_l[..., :3].sum(axis=-1) + per_l[..., -3:].sum(axis=-1)
        have = np.arange(width)[None, :] < count[:, None]
        re = np.where(have & central & (outer < 1e-6), lam.real, -np.inf)
        best = np.argmax(re, axis=1)
        # a central mode grown into the outer harmonics faster than the kept (``checked``)
        cut = np.where(have & central & (outer >= 1e-6), lam.real, -np.inf).max(axis=1)
        self.edge = self.edge or bool(np.any(
            cut > np.maximum(re[np.arange(offsets.size), best], self.floor)))
        grows = np.flatnonzero(re[np.arange(offsets.size), best] > self.floor)
        at = rows[grows]
        gains[at] = re[grows, best[grows]]
        if eigenvalues is not None:  # the fastest's, or every kept growing one's (2-D)
            two = eigenvalues.ndim == 2
            eigenvalues[(at[:, None], np.arange(width)) if two else at] = np.where(
                re[grows] > self.floor, lam[grows], np.nan) if two else lam[grows, best[grows]]
        w_best = per_l[grows, best[grows]]                           # (grows, 2P + 1)
        modes[at] = centre[grows, best[grows]]
        from ._hill_dense import _sideband_offsets

        offs[at] = _sideband_offsets(offsets[grows], l_, k, w_best)

    def checked(self, offsets, ring=None) -> HillSpectrum:
        """``spectrum``, its fastest mode checked at P + PERSIST_STEP harmonics (moved by >
        1e-6 relative: the whole densely at H + 4); where a central mode grew into the outer
        harmonics faster than the kept (``edge``; review 102: flexmm, k 2 pi/24, a 0.2 read
        stable, grows at 0.25), all at P + PERSIST_STEP (twice at most). ``ring``: (N, m),
        a one-field wave: from the modes' copies at l = 0 (``_ring_copies``)."""
        if ring is None:
            spec = self.spectrum(offsets)
        else:
            from ._ring_copies import ring_copies

            spec = ring_copies(self, *ring)
        if self.edge and self.P < self.wave.harmonics + 3 * PERSIST_STEP:
            return _Sidebands(self.wave, self.P + PERSIST_STEP).checked(offsets, ring)
        if spec.peak_gain <= 0:
            return spec
        i = int(np.argmax(spec.gain))
        finer = _Sidebands(self.wave, self.P + PERSIST_STEP)
        again = finer.spectrum(offsets[i:i + 1])
        P2 = self.P + PERSIST_STEP
        if abs(again.gain[0] - spec.gain[i]) <= 1e-6 * spec.gain[i]:
            from ._persist import slow_offsets_persist

            spec = slow_offsets_persist(spec, finer.spectrum)
            return dataclasses.replace(spec, truncations=(self.P, P2))
        from ._hill_dense import _dense_spectrum

        P = self.wave.harmonics + 4
        return dataclasses.replace(_dense_spectrum(self.wave, offsets, P, False),
                                   truncations=(P,))


@one_blas_thread
def exact_gain(model: Model, k: float, amplitude: float, branch=None, *, N: int | None = None,
               samples: int = 400) -> HillSpectrum:
    """The exact lattice theory at one point: the travelling wave and its Hill spectrum on
    a ring of ``N`` sites (k snapped to 2 pi m / N, the offsets the ring carries) or, N
    None, on the infinite chain (``samples`` offsets in [pi / samples, pi] and 40
    log-spaced below, the peak refined between them). On one BLAS thread
    (``common.threads``: a multithreaded BLAS only adds synchronisation to small dense
    algebra, and on a busy machine its threads spin against the work)."""
    from ._simulate import MAX_RING, check_count, check_ring, snap_ring

    if N is not None:
        N = check_ring(N)  # N = 0 is a bad ring, not the infinite chain
        k, m = snap_ring(k, N)
    else:  # the ring's snap checks k; the chain's as four_wave and nls do
        k = scalar(k)
        if isinstance(k, (bool, np.bool_)) or not isinstance(k, numbers.Real):
            raise ModelError(f"k must be a real number in (0, pi], got {type(k).__name__} "
                             f"{k!r}")
        if not (math.isfinite(k) and 0 < k <= math.pi):
            raise ModelError(f"k must be in (0, pi], got {k!r}")
        k = float(k)
    # at most the offsets of the largest ring (a finer grid only costs: 10**8 was a
    # MemoryError naming no argument; 65536 takes ~3 s for fput)
    samples = check_count("samples", samples, least=8, most=MAX_RING // 2,
                          why=f"the offsets of the largest ring, N = {MAX_RING}")
    from ._nls import check_resolved_amplitude

    check_resolved_amplitude(model, k, amplitude, branch)  # no rates from rounding
    wave = travelling_wave(model, k, amplitude, branch)  # the branch checked (_connected)
    engine = _Sidebands(wave)
    if N:
        one = wave.model.n_fields == 1
        return engine.checked(ring_offsets(N), ring=(N, m) if one else None)
    # small offsets log-spaced below the uniform grid's first point: a weak wave's band is
    # O(a) wide (a = 0.002: edge 0.005, inside the first uniform step pi / 400)
    q = np.concatenate([np.geomspace(1e-5, np.pi / samples, 40, endpoint=False),
                        np.linspace(np.pi / samples, np.pi, samples)])
    # a band narrower than a step between two samples that hold no growing mode: at the
    # crossings of opposite-sign roots there (``_crossings``), kept where they grow
    from ._crossings import band_bracket, merged, with_crossings

    for attempt in range(3):  # at P + PERSIST_STEP where a mode grew into the edge
        spec = with_crossings(engine, engine.spectrum(q))
        if not engine.edge or attempt == 2:
            break
        engine = _Sidebands(wave, engine.P + PERSIST_STEP)
    q = spec.offsets
    if spec.peak_gain <= 0:
        return spec
    # the infinite chain's peak between the samples (bounded scalar search of the rate)
    from scipy.optimize import minimize_scalar

    i = int(np.argmax(spec.gain))
    rate = lambda x: engine.spectrum([x], gains_only=True).gain[0]  # noqa: E731
    lo, hi = band_bracket(rate, q, spec.gain, i)
    best = minimize_scalar(lambda x: -rate(x), bounds=(lo, hi),
                           method="bounded", options={"xatol": 1e-6 * (hi - lo)})
    extra = engine.checked(np.array([best.x]))
    if len(extra.truncations) != 2:  # the peak did not persist: the old dense way
        from ._hill_dense import _dense_spectrum

        spec = _dense_spectrum(wave, q, wave.harmonics + 4, False)
        extra = _dense_spectrum(wave, extra.offsets, wave.harmonics + 4, False)
    return dataclasses.replace(merged(spec, extra), truncations=extra.truncations)
