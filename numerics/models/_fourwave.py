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

import functools
import math
import numbers
from dataclasses import dataclass

import numpy as np

from energy import Model, ModelError

from ._exact import GAIN_FLOOR  # one floor for both theories' verdicts
from ._fourwave_kernel import _kernel
from ._linear import carrier, check_amplitude, check_model, scalar
from ._modes import _wrap, field_groups, own_offset, pair_kind, same_wave, wave_field, wave_sheets

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
    crossing_gain : float
        The fastest two-wave rate among the pairs left unrated at a crossing (0 if none):
        where it passes ``gain``, the rated pair may not be the fastest.
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
    crossing_gain: float = 0.0

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
        """The kind of pair (offset index i, branch pair j): by dispersion sheets
        (``sheet_pair_kind``), so a pair of the carrier's own waves across a crossing of
        uncoupled branches is its sidebands."""
        table = self._sheets
        if table[0] == "followed":  # the fields all coupled: the followed branch indices
            b1, b2 = self.pairs[j]
            q = float(self.offsets[i])  # a branch meeting the followed one is it (same_wave)
            on = (same_wave(self.model, self.k + q, b1, int(table[1][i]))
                  and same_wave(self.model, self.k - q, b2, int(table[2][i])))
            return pair_kind(self.branch, (self.branch,) * 2 if on else (-1, -1),
                             self.offsets[i])
        own, plus, minus = table
        b1, b2 = self.pairs[j]
        if plus[i][b1] != own or minus[i][b2] != own:
            return "parametric"
        return pair_kind(self.branch, (self.branch, self.branch), self.offsets[i])

    @functools.cached_property
    def _sheets(self):
        """(the carrier's sheet, every branch's sheet at k + q and at k - q per offset);
        where the fields are all linearly coupled ('followed', the carrier's branch
        followed through avoided crossings to k + q, to k - q: ``_sheet_track``)."""
        groups = field_groups(self.model)
        q = np.asarray(self.offsets, dtype=float)
        if len(set(groups)) == 1:
            from ._sheet_track import followed_branches

            both = followed_branches(self.model, self.k, self.branch,
                                     np.concatenate([self.k + q, self.k - q]))
            return ("followed", both[:q.size], both[q.size:])
        own = wave_sheets(self.model, self.k, groups)[self.branch]
        return (own, wave_sheets(self.model, _wrap(self.k + q), groups),
                wave_sheets(self.model, _wrap(self.k - q), groups))

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
        for j in range(len(self.pairs)):
            for i in np.flatnonzero(r[:, j] > 0):
                kind = self.kind_of(int(i), j)
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
                "kind_rates": self.kind_rates(), "crossing_gain": self.crossing_gain,
                "reason": self.undefined}


def pair_rates(model: Model, k: float, amplitude: float, branch=None, offsets=None):
    """Every pair's (rate, detuning, coupling), each shape (n, d^2), at the offsets q
    (shape (n,)), the branch pairs and the plane wave's (Carrier, Omega); a reason string
    where the expansion fails. The kernel of the module docstring, vectorised over q."""
    kernel = _kernel(model, k, float(amplitude), branch)
    if isinstance(kernel, str):
        return kernel
    rates, pairs, car, Omega = kernel
    return (*rates(offsets), pairs, car, Omega)


def _offset_grid(samples: int) -> np.ndarray:
    # log-spaced near q = 0 (sidebands) and q = pi (the backward pair k - pi +- Q): a weak
    # wave's bands there are O(a) wide, narrower than the uniform grid's step
    near = np.geomspace(1e-4, math.pi / samples, 24, endpoint=False)
    return np.unique(np.concatenate([near, np.linspace(math.pi / samples, math.pi, samples),
                                     math.pi - near]))


def _resonances(det, q, detuning=None, steps: int = 4):
    """Offsets where a pair's nonlinear detuning crosses zero between grid points (the
    centre of its band, however narrow), any branch pair: linear interpolation, then
    ``steps`` of regula falsi (Illinois) on ``detuning(qs)`` (the detunings at offsets
    ``qs``, shape (len(qs), pairs)) where given: a band is ~ its rate wide in detuning
    (fput k 1.5, a 0.002: 2.5e-5 in q, where the interpolation of a step of 0.025 landed
    4.4e-5 away in detuning, outside it)."""
    found = []
    for j in range(det.shape[1]):
        dj = det[:, j]
        ok = np.isfinite(dj[:-1]) & np.isfinite(dj[1:])
        i = np.flatnonzero(ok & (np.sign(dj[:-1]) * np.sign(dj[1:]) < 0))
        found += [(j, q[m], q[m + 1], dj[m], dj[m + 1]) for m in i]
    if not found:
        return np.zeros(0)
    j, a, b, fa, fb = (np.array(x) for x in zip(*found))
    x = a + (b - a) * fa / (fa - fb)
    for _ in range(steps if detuning is not None else 0):
        fx = detuning(x)[np.arange(x.size), j]
        if not np.all(np.isfinite(fx)):
            break
        left = np.sign(fx) == np.sign(fa)  # the root lies in [x, b]
        side_a = np.where(left, fa, fa / 2)  # Illinois: halve the end that stays
        side_b = np.where(left, fb / 2, fb)
        a, fa = np.where(left, x, a), np.where(left, fx, side_a)
        b, fb = np.where(left, b, x), np.where(left, side_b, fx)
        x = a + (b - a) * fa / (fa - fb)
    return np.unique(x)


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
    from ._simulate import MAX_RING, check_count, check_ring, snap_ring

    check_model(model)
    a = check_amplitude(amplitude)
    if N is not None:  # N = 0 is a bad ring, not the infinite chain (as exact_gain's)

        N = check_ring(N)
        k = snap_ring(k, N)[0]
        q = 2 * np.pi * np.arange(1, N // 2 + 1) / N
    else:
        k = scalar(k)
        if isinstance(k, (bool, np.bool_)) or not isinstance(k, numbers.Real):
            raise ModelError(f"k must be a real number in (0, pi], got {type(k).__name__} "
                             f"{k!r}")
        k = float(k)
        if not (math.isfinite(k) and 0 < k <= math.pi):
            raise ModelError(f"k must be in (0, pi], got {k!r}")
        # exact_gain's rule: at most the offsets of the largest ring (10**8 ran > 60 s)
        q = _offset_grid(check_count("samples", samples, least=8, most=MAX_RING // 2,
                                     why=f"the offsets of the largest ring, N = {MAX_RING}"))
    from ._nls import check_resolved_amplitude
    from ._reach import energy_not_real
    from ._rest_order import rest_not_cubic

    check_resolved_amplitude(model, k, a, branch)  # no rates from rounding
    # a wave the model cannot carry (its energy not real along it) has no four-wave rates:
    # the kernel's Taylor coefficients at rest would rate it as if it existed
    # nor where its nonlinearity at rest is not cubic (Abs(r)**3): the kernel's tensors
    # read 0 there, and 'stable' while the exact theory finds MI
    kernel = (energy_not_real(model, k, a, branch) or rest_not_cubic(model)
              or _kernel(model, k, a, branch))
    d = model.n_fields
    if isinstance(kernel, str):
        car = carrier(model, k, branch)
        nan = np.full((q.size, d * d), np.nan)
        return FourWave(model, k, a, car.branch, car.omega, math.nan, q,
                        tuple((i, j) for i in range(d) for j in range(d)), nan, nan, nan,
                        kernel)
    pair_rates_, pairs, car, Omega = kernel

    lost = [0.0]  # the fastest rate of the pairs ``_isolated`` leaves unrated

    def rates(qs):
        r, dt, cp = pair_rates_(qs)
        out = _isolated(model, k, qs, pairs, r, dt, cp)
        gone = np.isnan(out[0]) & np.isfinite(r)
        lost[0] = max(lost[0], float(np.max(r[gone], initial=0.0)))
        return out

    rate, det, coup = rates(q)
    if not N:
        extra_q = _resonances(det, q, lambda qs: rates(qs)[1])
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
    best = float(np.nanmax(np.nan_to_num(rate, nan=0.0), initial=0.0))
    # the pairs ``_isolated`` left unrated (a wave near another branch) are no driven wave
    # too large to be slaved (newuser 101: a two-field chain with its v decoupled, eta 0,
    # at k 2.8 read so; the 'lost' reason below is theirs)
    mixed = np.isnan(_isolated(model, k, q, pairs, np.ones_like(rate), det, coup)[0])
    if not best > GAIN_FLOOR * car.omega:
        why = _untreated(q, pairs, rate, det, mixed)
        if not why and lost[0] > GAIN_FLOOR * car.omega:
            why = (f"no rated pair grows, but a pair with a wave at a crossing (another "
                   f"branch at its wavenumber within {_ISOLATED_PAIR:g} couplings) would "
                   f"grow at about {lost[0]:.3g} /time in the two-wave reduction, which "
                   "does not hold there; the exact theory holds")
    decay = _decay(model, k, a, branch, N, samples)
    if (not why and best > GAIN_FLOOR * car.omega and (decay is None or decay[0] <= best)
            and _untreated(q, pairs, rate, det, mixed)):
        # a pair resonant through a driven wave too large to be slaved (its rate nan)
        # beside a rated one: the rated pair is the fastest only where that process is
        # slower. Probe 98: res2's optical carrier (k 0.120, a 0.0221) decays into two
        # resonator waves at 3.9e-3 (exact, ~ a), its l = 2 harmonic 4.7e-4 from the
        # optical branch (not isolated), and the theory named a pair at 5.3e-5
        loose = _decay(model, k, a, branch, N, samples, isolated_only=False)
        if loose is not None and loose[0] > best:
            rate3, (b1, k1), (b3, k3) = loose
            why = (f"a three-wave decay of the carrier into branch {b1} at {k1:.4g} and "
                   f"branch {b3} at {k3:.4g}, with another harmonic near a branch (not "
                   f"isolated), grows at about {rate3:.3g} /time in its two-wave "
                   f"reduction, faster than any rated four-wave pair ({best:.3g}): "
                   "neither ordering treats it; the exact theory holds")
    if decay is not None and decay[0] > max(best, GAIN_FLOOR * car.omega):
        rate3, (b1, k1), (b3, k3) = decay
        why = (f"a three-wave decay of the carrier into branch {b1} at {k1:.4g} and branch "
               f"{b3} at {k3:.4g} grows at about {rate3:.3g} /time, faster than any "
               f"four-wave pair ({best:.3g}): a process of order a that the four-wave "
               "ordering does not rate; the exact theory holds")
    if not why and not best > GAIN_FLOOR * car.omega:
        # a decay the carrier's own shift could bring into resonance: 'stable' is not
        # known at this order (probe 96: opt at pi/2, exact 6.3e-3, four-wave 'stable')
        near = _decay(model, k, a, branch, N, samples, margin=True)
        if near is not None and near[0] > GAIN_FLOOR * car.omega:
            rate3, (b1, k1), (b3, k3) = near
            why = (f"a three-wave decay of the carrier into branch {b1} at {k1:.4g} and "
                   f"branch {b3} at {k3:.4g} is detuned by less than the carrier's own "
                   f"frequency shift: it grows (at up to {rate3:.3g} /time) or not at the "
                   "next order, which the four-wave ordering does not rate; the exact "
                   "theory holds")
    return FourWave(model, k, a, car.branch, car.omega, float(Omega), q, tuple(pairs),
                    rate, det, coup, why, lost[0])


#: a pair whose wave has another branch at its own wavenumber nearer than this many
#: couplings is not a two-wave problem (the three-wave check's ``ISOLATED``)
_ISOLATED_PAIR = 4.0


def _isolated(model, k, q, pairs, rate, det, coup):
    """The pairs' rates with nan where a wave lies within ``_ISOLATED_PAIR`` couplings of
    another branch at its own wavenumber: there both linear waves answer the pump (near a
    crossing the 2 x 2 reduction picks one mixed wave). Probe 96: cross + 1e-3 (u_next -
    u) v (bench/probe_fourwave96.py), the v carrier at k 0.288, a 0.115: a pair with a
    wave at the avoided crossing pi/3 (gap 1e-3) read 2.21e-3 against the exact 1.69e-3,
    which is the u pair at 1.355, -0.779 (four-wave 1.72e-3 there, as at eps = 0)."""
    from ._linear import branches

    d = model.n_fields
    if d < 2 or not q.size:
        return rate, det, coup
    gaps = []
    for kap in (k + q, k - q):
        w = branches(model, _wrap(kap))  # (n, d) ascending
        g = np.full(w.shape, np.inf)
        with np.errstate(invalid="ignore"):
            g[:, 1:] = np.minimum(g[:, 1:], np.abs(np.diff(w, axis=1)))
            g[:, :-1] = np.minimum(g[:, :-1], np.abs(np.diff(w, axis=1)))
        gaps.append(g)
    b1 = np.array([p[0] for p in pairs])
    b2 = np.array([p[1] for p in pairs])
    gap = np.minimum(gaps[0][:, b1], gaps[1][:, b2])  # (n, pairs)
    with np.errstate(invalid="ignore"):
        mixed = gap < _ISOLATED_PAIR * np.abs(coup)
    return np.where(mixed, np.nan, rate), det, coup


def _decay(model, k, a, branch, N, samples, margin=False, isolated_only=True):
    """The fastest isolated three-wave decay (``_threewave.fastest_decay``, ``margin``
    its) over the ring's offsets of both signs, or a grid of the chain's; None where none
    grows."""
    from ._fourwave_kernel import _plane_wave
    from ._threewave import fastest_decay, fastest_near_decay

    wave = _plane_wave(model, k, a, branch)
    if N:
        j = np.arange(-((N - 1) // 2), N // 2 + 1)  # every ring offset, N odd too
        q = 2 * np.pi * j[j != 0] / N
    else:
        q = np.linspace(-np.pi, np.pi, 2 * samples + 1)[1:]
        q = q[q != 0]
    if margin:
        return fastest_near_decay(model, k, wave, q, refine=not N)
    return fastest_decay(model, k, wave, q, refine=not N, isolated_only=isolated_only)


def _untreated(q, pairs, rate, det, mixed=None) -> str:
    """Why 'stable' cannot be said: a pair resonant (its detuning through zero) where its
    rate is nan -- a driven wave not slaved, a three-wave process this ordering does not
    rate -- or '' where every resonant pair was rated. ``mixed``: where the nan is
    ``_isolated``'s (a wave near another branch), not the kernel's."""
    for j, pair in enumerate(pairs):
        d, r = det[:, j], rate[:, j]
        if mixed is not None:
            r = np.where(mixed[:, j], 0.0, r)
        i = np.flatnonzero(np.isfinite(d[:-1]) & np.isfinite(d[1:])
                           & (np.sign(d[:-1]) * np.sign(d[1:]) < 0)
                           & (np.isnan(r[:-1]) | np.isnan(r[1:])))
        if i.size:
            return (f"no rated pair grows, but the pair of branches {pair} is resonant at "
                    f"offset {q[i[0]]:.4g} through a driven wave too large to be slaved (a "
                    "three-wave process the four-wave ordering does not rate; the exact "
                    "theory holds)")
    return ""
