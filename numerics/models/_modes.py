"""What grows: the kind of an exact mode or a four-wave pair, and the bands a ring misses.

classify_mode   the fastest mode of an exact Hill spectrum as a four-wave pair: its kind
                ('sidebands', 'backward', 'parametric', 'resonance'), its two waves and its
                own offset (not a copy's at a commensurate k)
ring_misses     the infinite chain's unstable bands that no offset 2 pi j / N of a ring
                samples, with the ring size that would (where the band grows at half its
                peak: common.rings.advised_ring)
wave_field, pair_kind, own_offset   the naming rules, shared with ``_fourwave``
sheet_pair_kind, wave_sheet   pair_kind by dispersion sheets, where uncoupled branches cross
"""

from __future__ import annotations

import math

import numpy as np

from common.rings import advised_ring
from energy import Model


def _wrap(x):
    """x wrapped to (-pi, pi] (0 as +0.0: a pair's wave at k - q = 0 read '-0')."""
    return -((-np.asarray(x, dtype=float) + np.pi) % (2 * np.pi) - np.pi) + 0.0


def wave_field(model: Model, kappa: float, branch: int) -> str:
    """The field that carries most of the kinetic energy of the linear wave (kappa,
    branch): branch indices ascend in frequency at each wavenumber, so where branches
    cross the field says which wave it is."""
    from ._linear import _modes

    vecs = _modes(model, float(kappa))[1]
    return model.fields[int(np.argmax(np.abs(vecs[:, branch]) ** 2))]


def pair_kind(branch: int, pair, q: float) -> str:
    """'sidebands', 'backward' or 'parametric' for the pair (k + q on pair[0], k - q on
    pair[1]) of a carrier on ``branch``."""
    if pair[0] != branch or pair[1] != branch:
        return "parametric"
    return "sidebands" if abs(float(_wrap(q))) <= math.pi / 2 else "backward"


def field_groups(model: Model) -> tuple:
    """Per field, the label of its group of linearly coupled fields: fields that no term
    of the rest Hessian (the bond's and the site's) couples, directly or through others,
    are linearly independent waves, whose branches cross where their frequencies meet."""
    d = model.n_fields
    H = np.asarray(model.code.taylor(model.p)[0], dtype=float)
    big = float(np.max(np.abs(H))) or 1.0
    link = np.zeros((d, d), bool)
    for blk in (H[:d, :d], H[:d, d:], H[d:, :d], H[d:, d:]):
        link |= (np.abs(blk) > 1e-14 * big) | (np.abs(blk.T) > 1e-14 * big)
    label = list(range(d))
    for _ in range(d):  # propagate the smallest label through the links
        for i in range(d):
            for j in range(d):
                if link[i, j]:
                    label[i] = label[j] = min(label[i], label[j])
    return tuple(label)


def wave_sheet(model: Model, kappa: float, branch: int, groups=None) -> tuple:
    """The dispersion sheet of the linear wave (kappa, branch): (its group of linearly
    coupled fields, its rank by frequency within that group). Branch indices rank the
    waves of all fields together, so where the branches of two uncoupled groups cross
    (a field coupled to the others only through nonlinear terms) the indices swap while
    each wave stays on its own sheet; with one group the sheet is the branch index."""
    groups = field_groups(model) if groups is None else groups
    if len(set(groups)) == 1:
        return (groups[0], int(branch))
    return wave_sheets(model, kappa, groups)[branch]


def wave_sheets(model: Model, kappas, groups: tuple) -> list:
    """``wave_sheet`` of every branch at each of ``kappas`` (a float or a sequence; one
    small eigenproblem each, the rest Hessian taken once): a list per kappa."""
    from ._linear import dynamical_matrix

    H = model.code.taylor(model.p)[0]
    s = 1 / np.sqrt(model.masses)
    ks = np.atleast_1d(np.asarray(kappas, dtype=float))
    # the eigenvectors _modes takes (mass-weighted), as wave_field names a wave; stacked
    D = np.stack([s[:, None] * dynamical_matrix(H, float(x)) * s[None, :] for x in ks])
    heavy = np.argmax(np.abs(np.linalg.eigh(D)[1]) ** 2, axis=1)  # (n, branches)
    out = []
    for row in heavy:
        g = [groups[int(f)] for f in row]
        out.append([(g[b], sum(1 for c in range(b) if g[c] == g[b])) for b in range(len(g))])
    return out if np.ndim(kappas) else out[0]


def sheet_branches(model: Model, k: float, branch: int, kappas) -> np.ndarray:
    """The branch index of the carrier's sheet (``wave_sheet`` of (k, branch)) at each of
    ``kappas``: ``branch`` everywhere where the fields are all linearly coupled; across a
    crossing of uncoupled branches, the other index (flexmm-lossy at the blue point: the
    sideband at k - q = 0.07 is theta's on branch 1, where branch 0 is U, damped 25x
    less)."""
    kappas = np.atleast_1d(np.asarray(kappas, dtype=float))
    groups = field_groups(model)
    if len(set(groups)) == 1:
        return np.full(kappas.size, int(branch))
    own = wave_sheets(model, float(k), groups)[int(branch)]
    return np.array([row.index(own) for row in wave_sheets(model, kappas, groups)], int)


def same_wave(model: Model, kappa: float, b: int, b_on: int) -> bool:
    """Whether branch b at ``kappa`` is the followed branch b_on: the same index, or a
    branch of the same frequency there (to 1e-9), where two branches meet and the index
    is no label (a two-site cell of a monatomic chain folds its branch at pi with no gap:
    probe 100's nnn chain, a wave at kappa = pi on the ring of 128 was named 'parametric'
    by its index, 1, where the carrier's sheet at pi is branch 0 and 1 alike)."""
    if b == b_on:
        return True
    from ._linear import branches

    w = branches(model, [float(kappa)])[0]
    return bool(abs(w[b] - w[b_on]) <= 1e-9 * max(1.0, abs(w[b_on])))


def sheet_pair_kind(model: Model, k: float, branch: int, pair, q: float,
                    groups=None) -> str:
    """``pair_kind`` by dispersion sheets (``wave_sheet``) instead of branch indices: the
    pair (k + q on pair[0], k - q on pair[1]) is the carrier's sidebands (or backward pair)
    where both waves lie on the carrier's sheet, even where another group's branch crosses
    it between k and k +- q (there the indices swap). Where the fields are all linearly
    coupled, the carrier's branch followed by its eigenvector through avoided crossings
    (``_sheet_track``): ``pair_kind`` where none lies between k and k +- q."""
    groups = field_groups(model) if groups is None else groups
    if len(set(groups)) == 1:
        # one group: the sheet followed through avoided crossings by its eigenvector
        from ._sheet_track import followed_branches

        qw = float(_wrap(q))
        on = tuple(int(b) for b in followed_branches(model, k, branch, [k + qw, k - qw]))
        same = all(same_wave(model, kap, int(b), o)
                   for kap, b, o in zip((k + qw, k - qw), pair, on))
        return pair_kind(branch, (branch, branch) if same else (-1, -1), q)
    own = wave_sheet(model, k, branch, groups)
    on = (wave_sheet(model, float(_wrap(k + q)), pair[0], groups) == own
          and wave_sheet(model, float(_wrap(k - q)), pair[1], groups) == own)
    if not on:
        return "parametric"
    return "sidebands" if abs(float(_wrap(q))) <= math.pi / 2 else "backward"


def own_offset(kind: str, q: float) -> float:
    """A pair's own offset from its centre: |q| from k, or pi - |q| from k - pi
    (backward)."""
    q = abs(float(_wrap(q)))
    return math.pi - q if kind == "backward" else q


def classify_mode(spectrum) -> dict:
    """What the fastest mode of an exact Hill spectrum (``exact_gain``'s result) is.

    The mode e^{lambda t} e^{iqn} sum_l c_l e^{il xi} holds, in its harmonics l and l - 2,
    the waves (q + lk, l Omega - Im lambda) and (2k - q - lk, Im lambda - (l - 2) Omega)
    whose wavenumbers sum to 2k and frequencies to 2 Omega: a four-wave pair. The pair
    whose two waves lie nearest to linear waves (a branch each, by frequency) names the
    mode; its eigenvalue is found again at the fastest q. The harmonic that carries most
    of the mode's weight does not name it (an acoustic mean-flow harmonic can outweigh
    the pair), nor does a copy of it at a commensurate k.

    Returns
    -------
    dict
        ``mode_kind`` ('sidebands', 'backward', 'parametric', 'resonance' where a wave is
        no linear wave within max(2% Omega, 2 |Omega - omega(k)| + 3 rates), nor a linear wave moved by the
        carrier's own frequency shift Omega - omega(k) (as a pair locked to the carrier
        is) -- a harmonic resonant with a branch -- or 'none'), ``mode_waves`` [{branch, wavenumber, frequency, field}] x 2 and
        ``fastest_offset``, the pair's own offset (from k, or from k - pi for a backward
        pair), not a copy's.
    """
    from ._exact import hill_spectrum
    from ._linear import branches

    if spectrum.peak_gain <= 0:
        return {"mode_kind": "none", "mode_waves": [], "fastest_offset": None}
    wave = spectrum.wave
    model, k, Omega = wave.model, wave.k, wave.omega
    i = int(np.argmax(spectrum.gain))
    q = float(spectrum.offsets[i])
    _, lams = hill_spectrum(wave, [q], return_eigenvalues=True)
    # the pencil is Hamiltonian (T(lambda)^H = T(-conj lambda)): a kept decaying root
    # is its growing mirror's pair, with the same frequency; name the growing member
    lam = lams[0][int(np.argmax(np.abs(lams[0].real)))]
    lam = complex(abs(lam.real), lam.imag)
    vec = _mode_vector(wave, q, lam) if model.n_fields > 1 else None
    best = None
    # the carrier's own nonlinear frequency shift: a pair locked to it (sidebands, a
    # backward pair) sits that far off the linear branches, each wave by the same amount
    # (their frequencies sum to 2 Omega); fput alpha 1, beta 1.5 at k 2.45, a 0.1 on 64
    # sites: both waves 0.041 off, the shift 0.039 (2% of Omega), called a resonance before
    shift = Omega - float(branches(model, [k])[0][wave.carrier.branch])
    # the pair's harmonics l: both frequencies positive for l in (nu / Omega, nu / Omega + 2)
    l0 = int(math.floor(lam.imag / Omega)) if Omega > 0 else 0
    for l in range(l0 - 1, l0 + 4):
        phi, phi2 = l * Omega - lam.imag, lam.imag - (l - 2) * Omega
        if phi <= 0 or phi2 <= 0:
            continue
        kap, kap2 = float(_wrap(q + l * k)), float(_wrap(2 * k - q - l * k))
        w1, w2 = branches(model, [kap, kap2])
        if np.all(np.isnan(w1)) or np.all(np.isnan(w2)):
            # omega^2 < 0 on every branch there (a rest state that is no minimum): no
            # linear wave to name; before, nanargmin raised 'All-NaN slice encountered'
            continue
        # each wave's branch: the one its harmonic's eigenvector lies along (probe 96:
        # cross's v carrier at pi/2 holds only v in both harmonics, yet the u branch lay
        # nearer one wave's frequency); the nearest in frequency where it is not known
        own1 = _branch_along(model, kap, vec, l, conj=False)
        own2 = _branch_along(model, kap2, vec, l - 2, conj=True)
        miss, b1, b2 = min(
            (max(abs(w1[i] + s - phi), abs(w2[j] + s - phi2)), i, j)
            for s in (0.0, shift) if math.isfinite(s)
            for i in [own1 if own1 is not None else int(np.nanargmin(np.abs(w1 + s - phi)))]
            for j in [own2 if own2 is not None else int(np.nanargmin(np.abs(w2 + s - phi2)))])
        if not (math.isfinite(miss)):
            continue
        if best is None or miss < best[0]:
            best = (miss, kap, phi, b1, kap2, phi2, b2)
    if best is None:  # no pair of positive frequencies (a wave with Omega <= 0): unnamed
        return {"mode_kind": "resonance", "mode_waves": [],
                "fastest_offset": float(abs(_wrap(q)))}
    miss, kap, phi, b1, kap2, phi2, b2 = best
    # a pair's waves sit off their branches by their cross-phase shifts (about twice the
    # carrier's own, one of which the shift s above takes off) and their detuning (about
    # a rate at the fastest offset): probe 100 measured at most 2 |shift| in 53 of 54
    # pairs of seven models (the other, a ring offset on a band's flank, within 2% of
    # Omega), cross-0's flat v pair (test_fourwave96) 2 |shift| + 1 rate; a three-wave
    # decay read as a pair misses by O(1) (decay2: 0.43 off every branch, 6.9-56 rates),
    # and the former bound of 10 rates named decay2's decay at a 0.1 'sidebands'
    tol = max(0.02 * Omega, (2 * abs(shift) if math.isfinite(shift) else 0.0)
              + 3 * float(lam.real))
    waves = [{"branch": b1, "wavenumber": kap, "frequency": float(phi),
              "field": wave_field(model, kap, b1)},
             {"branch": b2, "wavenumber": kap2, "frequency": float(phi2),
              "field": wave_field(model, kap2, b2)}]
    if miss > tol:
        return {"mode_kind": "resonance", "mode_waves": waves,
                "fastest_offset": float(min(abs(_wrap(kap - k)), abs(_wrap(kap + k))))}
    kind = sheet_pair_kind(model, k, wave.carrier.branch, (b1, b2), kap - k)
    return {"mode_kind": kind, "mode_waves": waves,
            "fastest_offset": own_offset(kind, kap - k)}


def _mode_vector(wave, q: float, lam: complex):
    """The Hill mode (offset q, eigenvalue ``lam``) per harmonic: c_l, shape (2P + 1, d),
    row P + l harmonic l, in displacements (the dense pencil of ``hill_spectrum`` with
    ``return_eigenvalues``, P = H + 4; inverse iteration at ``lam``); None where it
    does not settle."""
    from scipy.linalg import lu_factor, lu_solve

    from ._hill_dense import _DensePencil

    P = wave.harmonics + 4
    pen = _DensePencil(wave, P)
    n, omega, ll, m = pen.n, pen.omega, pen.ll, pen.m
    A = np.zeros((2 * n, 2 * n), complex)
    A[:n, n:] = np.eye(n)
    A[n:, :n] = -(pen.stiffness(q) - np.diag(ll**2 * omega**2 * m)) / m[:, None]
    A[n:, n:] = np.diag(2j * omega * ll)
    shift = lam + 1e-13 * (abs(lam) + omega)  # A - lam I is singular to round-off
    with np.errstate(all="ignore"):
        lu = lu_factor(A - shift * np.eye(2 * n), check_finite=False)
        x = np.random.default_rng(0).standard_normal(2 * n) + 0j
        for _ in range(2):
            x = lu_solve(lu, x / np.max(np.abs(x)), check_finite=False)
    if not np.all(np.isfinite(x)):
        return None
    return x[:n].reshape(2 * P + 1, pen.d)


def _branch_along(model: Model, kappa: float, vec, l: int, conj: bool):
    """The branch whose linear eigenvector at ``kappa`` the mode's harmonic l (conjugated
    for the pair's second wave) overlaps most, in the mass inner product; None where the
    mode is not known or the harmonic holds < 1e-6 of its weight."""
    if vec is None:
        return None
    P = (vec.shape[0] - 1) // 2
    if abs(l) > P:
        return None
    m = np.asarray(model.masses, float)
    c = vec[P + l]
    w = m * np.abs(vec) ** 2
    if float(np.sum(m * np.abs(c) ** 2)) < 1e-6 * float(np.sum(w)):
        return None
    from ._linear import _modes

    y = _modes(model, float(kappa))[1]  # mass-weighted eigenvectors
    c = np.sqrt(m) * (np.conj(c) if conj else c)
    return int(np.argmax(np.abs(y.conj().T @ c)))


def ring_misses(model: Model, k: float, amplitude: float, branch=None, *, N: int,
                chain=None) -> list:
    """The infinite chain's unstable bands (exact theory) that a ring of ``N`` sites does
    not sample: none of its offsets 2 pi j / N falls in them.

    ``chain``: the infinite chain's ``exact_gain`` at the ring's k (computed if None). Its
    offset grid can step over a narrow band (a parametric pair's is ~ rate / |v1 - v2|
    wide), so the Hill spectrum is also sampled where the four-wave theory puts a band.
    Returns a list of dicts: ``band`` (lo, hi), the Hill offsets q (rad/site) where the
    chain grows, ``peak_gain`` there and ``N``, the smallest ring size above N with an
    offset where the band grows at least ``RESOLVED`` (half) of its peak (an offset at
    the band's edge grows at ~0: a run cannot show it), a multiple of the ring's own
    period of k where one up to 64 N has one (``same_k`` True: that ring carries this k,
    so this band), else any (its k snaps elsewhere, and the band moves with it); None
    where no ring up to 64 N has such an offset.
    """
    from ._exact import exact_gain
    from ._fourwave import four_wave
    from ._simulate import snap_ring

    k_ring, m_ring = snap_ring(k, N)
    if chain is None:
        chain = exact_gain(model, k_ring, amplitude, branch)
    from ._exact import hill_spectrum

    fw = four_wave(model, k_ring, amplitude, branch)
    q, g = chain.offsets, chain.gain
    if fw.verdict == "MI":
        # Hill offsets every 1e-3 (at most 40) across each band the four-wave theory finds
        # and 4e-3 beyond it, and 41 across the band and its width on either side: a
        # parametric band can be far narrower than 1e-3 (a Hertz chain's, 9e-5 wide at
        # q = 1.128, k = 0.98, a = 0.05, fell between them). A band: rates above the
        # verdicts' floor (the four-wave rates' round-off, ~1e-13, is positive elsewhere)
        from ._exact import GAIN_FLOOR

        floor = GAIN_FLOOR * fw.omega
        r4 = np.nan_to_num(fw.rates, nan=0.0).max(axis=1) > floor
        e4 = np.flatnonzero(np.diff(np.concatenate([[0], r4.astype(int), [0]])))
        bands = [(fw.offsets[a], fw.offsets[b - 1]) for a, b in zip(e4[::2], e4[1::2])]
        extra = np.concatenate(
            [np.linspace(lo - 4e-3, hi + 4e-3, min(40, int((hi - lo + 8e-3) / 1e-3) + 2))
             for lo, hi in bands]
            + [np.linspace(lo - w, hi + w, 41) for lo, hi in bands
               for w in [max(hi - lo, 1e-5)]] + [np.empty(0)])
        extra = extra[(extra > 0) & (extra <= math.pi)]
        if extra.size:
            more = hill_spectrum(chain.wave, extra)
            q, g = np.concatenate([q, extra]), np.concatenate([g, more.gain])
            order = np.argsort(q)
            q, g = q[order], g[order]
    grows = g > 0
    out, sampled = [], []
    edges = np.flatnonzero(np.diff(np.concatenate([[0], grows.astype(int), [0]])))
    for start, stop in zip(edges[::2], edges[1::2]):
        lo = _edge(chain.wave, q[start], q[start - 1] if start > 0 else None)
        hi = _edge(chain.wave, q[stop - 1], q[stop] if stop < q.size else None)
        j = np.arange(math.ceil(lo * N / (2 * math.pi)), math.floor(hi * N / (2 * math.pi)) + 1)
        if j.size:
            sampled.append((lo, hi))
            continue
        # a mode shows at Hill offsets q + l k too (its copies): one band per mode
        mid = (lo + hi) / 2
        if any(_same_mode(mid, (b["band"][0] + b["band"][1]) / 2, k_ring, hi - lo)
               for b in out):
            continue
        # the band's own peak, not its sampled offsets' (probe 100: 10% low on a 1e-3
        # wide band of a Lennard-Jones chain)
        peak, at = _band_peak(chain.wave, lo, hi, float(np.max(g[start:stop])),
                              float(q[start + int(np.argmax(g[start:stop]))]))
        # the ring advised has an offset where the band grows at >= RESOLVED of its peak:
        # an offset at the band's edge grows at ~0 and a run shows nothing there
        # (leftovers101: kgeven at k 0.393, a 0.175, N = 128 was told N = 256, whose only
        # offset in the band 0.4148-0.4173, 0.41724, grows at 1.5e-4 of a peak 6.3e-4)
        rlo, rhi = _resolved_span(chain.wave, lo, hi, at, RESOLVED * peak)
        n, same = advised_ring(rlo, rhi, N, m_ring)
        out.append({"band": (lo, hi), "peak_gain": peak, "N": n, "same_k": same})
    # Hill's spectrum at +-q + l k is the one at q: a piece between two ring offsets of a
    # band that is a copy of a band the ring samples is that band's mode, which the ring
    # shows (at k = pi on 64 sites the sidebands' copies near pi - q read as 13 bands)
    return [b for b in out if not any(_copy_inside(b["band"], s, k_ring) for s in sampled)]


def _copy_inside(band, other, k) -> bool:
    """Whether a copy +-q + l k (mod 2 pi) of ``band``'s centre lies in the band ``other``
    (offsets |q| in [0, pi]), within half of ``band``'s width."""
    mid, half = (band[0] + band[1]) / 2, (band[1] - band[0]) / 2
    for l in range(-3, 4):
        m = abs(float(_wrap(mid - l * k)))
        if other[0] - half <= m <= other[1] + half:
            return True
    return False


def _same_mode(q1, q2, k, width):
    """Whether Hill offsets q1, q2 are copies of one mode: q1 = +-q2 + l k (mod 2 pi)."""
    for sign in (1, -1):
        for l in range(-3, 4):
            if abs(float(_wrap(q1 - sign * q2 - l * k))) <= max(width, 1e-9):
                return True
    return False


def _edge(wave, inside: float, outside, steps: int = 12) -> float:
    """The band edge between an unstable offset and a stable one (bisection on Hill's
    rate); ``inside`` where there is no stable neighbour."""
    from ._exact import hill_spectrum

    if outside is None:
        return float(inside)
    a, b = float(inside), float(outside)
    for _ in range(steps):
        m = (a + b) / 2
        if hill_spectrum(wave, [m]).gain[0] > 0:
            a = m
        else:
            b = m
    return a


#: offsets across a missed band where its peak is looked for before it is refined
PEAK_SAMPLES = 33


def _band_peak(wave, lo: float, hi: float, sampled: float, at: float) -> tuple:
    """The largest Hill rate over the offsets [lo, hi] of a band and where: PEAK_SAMPLES
    across it, then Brent's bounded search between the best sample's neighbours (to 1e-4
    of the band's width); never below ``sampled``, the rate already seen inside it (at the
    offset ``at``). Returns (rate, offset)."""
    from scipy.optimize import minimize_scalar

    from ._exact import hill_spectrum

    if not hi > lo:
        return sampled, at
    q = np.linspace(lo, hi, PEAK_SAMPLES)
    g = np.nan_to_num(hill_spectrum(wave, q).gain, nan=0.0)
    i = int(np.argmax(g))
    a, b = q[max(i - 1, 0)], q[min(i + 1, q.size - 1)]
    best = minimize_scalar(lambda x: -float(np.nan_to_num(hill_spectrum(wave, [x]).gain[0])),
                           bounds=(a, b), method="bounded",
                           options={"xatol": 1e-4 * (hi - lo)})
    return max((sampled, at), (float(g[i]), float(q[i])), (-float(best.fun), float(best.x)))


#: the share of a band's peak rate that an advised ring's offset must grow at: a run
#: resolves a mode at half the peak within twice the peak's e-folding time
RESOLVED = 0.5


def _resolved_span(wave, lo: float, hi: float, at: float, rate: float,
                   steps: int = 14) -> tuple:
    """The offsets about ``at`` (the band's peak) where Hill's rate is at least ``rate``:
    bisection between the peak and each edge of [lo, hi] (2^-14 of the band's width)."""
    from ._exact import hill_spectrum

    def above(x):
        return float(np.nan_to_num(hill_spectrum(wave, [x]).gain[0])) >= rate

    ends = []
    for edge in (lo, hi):
        a, b = at, edge  # a: at least rate; b: below, or the edge itself
        if above(b):
            ends.append(b)
            continue
        for _ in range(steps):
            m = (a + b) / 2
            a, b = (m, b) if above(m) else (a, m)
        ends.append(a)
    return ends[0], ends[1]
