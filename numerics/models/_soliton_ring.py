"""Any model's envelope soliton on a ring: the prediction a run is launched from
(``ring_soliton``, ``RingSoliton``), split from ``_soliton_run`` (the run and its tracking).

The launch is the multiple-scales solution of ``_nls`` with the soliton's envelope E
(|E| = a/2 sech(xi/w) bright, a/2 tanh(xi/w) black; a = 2 eps |A|, xi = n - c - v_g t):

    u_n = (E e - i E_xi e' - E_xixi e''/2) e^{i theta} + E^2 v2 e^{2 i theta} + c.c.
          + |E|^2 w + sum_{m<n} s (|E|^2 + lam),

theta = k n - Omega t, e the carrier's polarisation (e' = de/dk: the packet's
wavenumbers k + p carry e(k + p)), v2 the second harmonic, w the optical
mean, s the acoustic mean strain per |E|^2 (its sum over the ring is the kink). A periodic
field has no net strain, so a uniform strain lam s with lam = -<|E|^2> (the ring average)
compensates the kink; the carrier feels it through the mean flow's part of g2, which
moves its frequency by -g2_meanflow lam (order width / N for a bright soliton; for a
black one the background's own strain). Velocities: the envelope moves at v_g and turns
at Omega (the soliton's frequency on this ring), the mean fields translate with it.
"""


from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from energy import Model, ModelError
from numerics.theory import ring_too_short, shortest_ring

from ._linear import blocks, dynamical_matrix
from ._nls import ModelNLS, ModelSoliton, acoustic_directions, nls
from ._soliton_measure import analytic_carrier

KINDS = ("bright", "dark")
#: below this width (sites) the envelope is too narrow for the weak-modulation ordering
#: (the paper chain's MIN_WIDTH)
MIN_WIDTH = 8.0
#: the longest run picked by itself (the paper chain's MAX_T_END)
MAX_T_END = 5e5
#: a sech^2 kink of width w keeps 99% of its spectrum below 4.5 / w: k w >= 9 separates it
#: (and the envelope) from the carrier's band-pass at k/2
SEPARATION = 9.0


def ring_wavenumber(k: float, N: int, kind: str = "bright") -> float:
    """The wavenumber nearest ``k`` on which a ring of ``N`` sites carries the soliton:
    2 pi m / N (bright), (2 m + 1) pi / N (black: the envelope changes sign across it)."""
    if kind not in KINDS:
        raise ModelError(f"kind must be one of {KINDS}, got {kind!r}")
    offset = 0.0 if kind == "bright" else math.pi
    m = round((k * N - offset) / (2 * math.pi))
    out = (2 * math.pi * m + offset) / N
    if not 0 < out < math.pi:
        why = ("its nearest is pi, where v_g = 0: the soliton stands still and travels no "
               f"widths; k <= {(2 * math.pi * (m - 1) + offset) / N:.6g} (or a larger N)"
               if out >= math.pi else
               f"its nearest is {out:.3g}: a larger N")
        raise ModelError(f"no ring wavenumber near k = {k:g} for N = {N} (a {kind} soliton): "
                         + why)
    return out


def default_ring(width: float) -> int:
    """A ring of at least 20 widths (and 256 sites): the tails (e^{-20}) never meet."""
    return int(max(256, 2 * math.ceil(10 * width)))


def soliton_ring(soliton: ModelSoliton) -> int:
    """:func:`default_ring` of ``soliton``'s width, or a ModelError naming the amplitude
    that fits the largest ring (``MAX_RING``): a soliton 8.5e8 sites wide (fput, k = 1,
    amplitude 1e-9) asked numpy for a ring of 1.7e10 sites ('Unable to allocate 127.
    GiB'), naming no argument."""
    from ._args import MAX_RING

    N = default_ring(soliton.width)
    if N > MAX_RING:
        # width ~ 1 / amplitude; 2 sites of slack for default_ring's rounding up, 0.6%
        # for the 3 digits printed (rounded to nearest: the advice refused itself)
        least = 1.006 * soliton.amplitude * soliton.width / ((MAX_RING - 2) / 20)
        raise ModelError(f"amplitude {soliton.amplitude:g}: the {soliton.kind} soliton is "
                         f"{soliton.width:.3g} sites wide, and its ring of 20 widths ({N} "
                         f"sites) exceeds the largest, {MAX_RING} sites; give amplitude >= "
                         f"{least:.3g} (a narrower soliton)")
    return N


@dataclass(frozen=True)
class RingSoliton:
    """The predicted soliton on a ring of N sites.

    Attributes
    ----------
    nls : ModelNLS
        The NLS at the ring's k.
    soliton : ModelSoliton
        On an infinite chain (kind, amplitude, width, velocity, kink per field).
    N : int
    frequency : float
        The soliton's carrier frequency on this ring (1/time): ``soliton.frequency`` moved
        by the ring's compensating strain.
    ring_strain : float
        lam = -<|E|^2>: the uniform strain lam s that closes the ring.
    """

    nls: ModelNLS
    soliton: ModelSoliton
    N: int
    frequency: float
    ring_strain: float

    @property
    def k(self) -> float:
        return self.nls.carrier.k

    @property
    def kind(self) -> str:
        return self.soliton.kind

    @property
    def width(self) -> float:
        return self.soliton.width

    @property
    def velocity(self) -> float:
        return self.soliton.velocity

    def kink_fields(self) -> list:
        """Indices of the fields that carry a kink (acoustic, nonzero mean strain)."""
        s = np.abs(self.nls.strain)
        return [int(i) for i in np.nonzero(s > 1e-12 * max(1.0, float(s.max())))[0]]

    def summary(self, fields) -> dict:
        """velocity, width, amplitude, frequency and kink_<field> for the kink fields."""
        s = self.soliton
        out = {"velocity": s.velocity, "width": s.width, "amplitude": s.amplitude,
               "frequency": self.frequency}
        for i in self.kink_fields():
            out[f"kink_{fields[i]}"] = float(s.kink[i])
        return out

    def notes(self) -> list:
        """Sentences on where the envelope theory or its measurement is strained here."""
        out = []
        if self.width < MIN_WIDTH:
            out.append(f"note: {self.width:.3g} sites is too narrow for the envelope theory; "
                       "lower the amplitude")
        if self.k * self.width < SEPARATION:
            out.append(f"warning: the envelope spans k x width = {self.k * self.width:.2g} rad "
                       f"of carrier phase (< {SEPARATION:g}): the envelope and the kink "
                       "overlap the mean and the second harmonic in wavenumber, so their "
                       "measurement (band and low pass at k/2) is not clean; a smaller "
                       "amplitude (a wider envelope) or a larger k separates them")
        from ._summary import harmonic_resonance_note

        # the envelope carries the NLS's second harmonic (``state``): near its resonance
        # the launch and the width both rest on a harmonic that is neither small nor slaved
        note = harmonic_resonance_note(self.nls.model, self.nls.carrier,
                                       self.soliton.amplitude, "the soliton's NLS")
        if note:
            out.append(f"warning: {note}")
        return out

    def carrier_signal(self, u, v) -> np.ndarray:
        """The carrier field's band-passed analytic signal 2 E e^{i theta} in the state
        (u, v) (``_soliton_measure.analytic_carrier``), shape (N,), complex."""
        return analytic_carrier(u, v, self)

    def envelope(self, xi) -> np.ndarray:
        """|E| at distances ``xi`` (sites) from the centre (real: sech or tanh)."""
        a, w = self.soliton.amplitude, self.width
        xi = np.asarray(xi, dtype=float)
        return a / 2 / np.cosh(xi / w) if self.kind == "bright" else a / 2 * np.tanh(xi / w)

    def state(self, centre: float | None = None) -> tuple:
        """(u, v), each shape (d, N): the soliton centred at site ``centre`` (N/2), t = 0."""
        N, nl = self.N, self.nls
        n = np.arange(N, dtype=float)
        c = N / 2 if centre is None else float(centre)
        xi = (n - c + N / 2) % N - N / 2
        w, vg, Om = self.width, self.velocity, self.frequency
        E = self.envelope(xi)
        h = 1e-4 * w  # central difference: relative error (h / w)^2 = 1e-8
        dE = (self.envelope(xi + h) - self.envelope(xi - h)) / (2 * h)
        carrier = np.exp(1j * self.k * n)[None, :]
        e = nl.carrier.e[:, None]
        v2 = nl.second_harmonic[:, None]
        u = 2 * np.real(E * e * carrier) + 2 * np.real(E**2 * v2 * carrier**2)
        v = (2 * np.real((-vg * dE - 1j * Om * E) * e * carrier)
             + 2 * np.real((-2 * vg * E * dE - 2j * Om * E**2) * v2 * carrier**2))
        # a packet's polarisation follows its wavenumbers: e(k + p) = e + p e' + p^2 e''/2
        # acts on the carrier field's envelopes (p -> -i d/dxi) as e - i e' d - e''/2 d^2
        # (no part in the carrier field: e[field] = 1); without it a two-field packet
        # sheds the other branch (diatomic FPUT, 13 sites: a width ripple of 1.4%, 0.1%
        # with e' alone, < 5e-5 with e'' too)
        d1, d2 = (x[:, None] for x in _polarisation_slope(nl))
        h2, h3 = 1e-3 * w, 1e-2 * w  # stencils: (h/w)^2 relative, on 1/w^2 and 1/w^3 terms
        E2 = (self.envelope(xi + h2) - 2 * E + self.envelope(xi - h2)) / h2**2
        E3 = (self.envelope(xi + 2 * h3) - 2 * self.envelope(xi + h3)
              + 2 * self.envelope(xi - h3) - self.envelope(xi - 2 * h3)) / (2 * h3**3)
        V1, V2 = -vg * E2 - 1j * Om * dE, -vg * E3 - 1j * Om * E2  # d/dxi of the velocity
        u = u + 2 * np.real((-1j * d1 * dE - d2 / 2 * E2) * carrier)
        v = v + 2 * np.real((-1j * d1 * V1 - d2 / 2 * V2) * carrier)
        u = u + nl.mean[:, None] * E**2
        v = v - vg * nl.mean[:, None] * 2 * E * dE
        s = nl.strain[:, None]
        if np.any(s != 0):
            mid = self.envelope(xi + 0.5) ** 2 + self.ring_strain  # between n and n + 1
            strain = s * mid
            U = np.concatenate([np.zeros((len(s), 1)), np.cumsum(strain, axis=1)[:, :-1]],
                               axis=1)
            u = u + U - U.mean(axis=1, keepdims=True) + _optical_per_strain(nl) * \
                self.ring_strain
            v = v - vg * (strain + np.roll(strain, 1, axis=1)) / 2
        return np.ascontiguousarray(u), np.ascontiguousarray(v)


def _polarisation_slope(nl: ModelNLS) -> tuple:
    """(de/dk, d^2e/dk^2) of the carrier's polarisation (e[field] = 1), each shape (d,),
    by central differences (step 1e-4: truncation 1e-8, round-off 1e-8 relative)."""
    from ._linear import carrier

    c = nl.carrier
    h = min(1e-4, c.k / 3, (math.pi - c.k) / 3)
    ep, em = (carrier(nl.model, c.k + s, c.branch).e for s in (h, -h))
    ep, em = ep / ep[c.field], em / em[c.field]
    return (ep - em) / (2 * h), (ep - 2 * c.e + em) / h**2


def _optical_per_strain(nl: ModelNLS) -> np.ndarray:
    """Optical mean displacement per unit lam of the uniform strain lam s, shape (d, 1):
    -K(0)^+ (H12 + H22) N s_N (``_nls``: the optical fields' response to a strain)."""
    model = nl.model
    H = model.code.taylor(model.p)[0]
    d = model.n_fields
    _, H12, _, H22 = blocks(H, d)
    Nd = acoustic_directions(model)
    if not Nd.shape[1]:
        return np.zeros((d, 1))
    K0p = np.linalg.pinv(np.real(dynamical_matrix(H, 0.0)), rcond=1e-10, hermitian=True)
    return (-K0p @ (H12 + H22) @ Nd @ (Nd.T @ nl.strain))[:, None]


def ring_soliton(model: Model, k: float, amplitude: float, N: int | None = None,
                 kind: str | None = None, branch=None) -> RingSoliton:
    """The soliton of ``model``'s NLS at the ring wavenumber nearest ``k`` on N sites
    (default :func:`default_ring` of its width).

    Raises
    ------
    ModelError
        No NLS at k, a kind that does not exist there (the message names the one that does),
        or a ring shorter than 12 widths.
    """
    if kind is not None and kind not in KINDS:  # before: 'kind grey: ... only bright'
        raise ModelError(f"kind must be one of {KINDS}, got {kind!r}")
    probe = nls(model, k, branch)
    if probe.undefined:
        raise ModelError(f"no soliton at k = {k:.6g}: {probe.undefined}")
    exists = probe.soliton(amplitude).kind
    if N is None:
        N = soliton_ring(probe.soliton(amplitude))
    if kind is not None and kind != exists:
        raise ModelError(f"kind {kind}: the NLS at k = {k:.6g} has g = g2/g1 = {probe.g:.4g} "
                         f"({'> 0' if probe.g > 0 else '< 0'}), so only {exists} solitons")
    kr = ring_wavenumber(k, N, exists)
    nl = nls(model, kr, probe.carrier.branch)
    if nl.undefined:
        raise ModelError(f"no soliton at the ring's k = {kr:.6g}: {nl.undefined}")

    def width_at(ring: int) -> float:
        kn = ring_wavenumber(k, ring, exists)
        near = nls(model, kn, probe.carrier.branch)
        if near.undefined:
            raise ModelError(near.undefined)
        sn = near.soliton(amplitude)
        if sn.kind != exists:
            raise ModelError("g changes sign")
        return sn.width

    s = nl.soliton(amplitude)
    if s.kind != exists:
        fits = shortest_ring(width_at, N + 1, ModelError)
        raise ModelError(f"the ring's k = {kr:.6g} (N = {N}) has a {s.kind} soliton, k = "
                         f"{k:.6g} a {exists} one (g changes sign between): a longer ring"
                         + (f"; N = {fits} holds one of 12 widths at its own k" if fits
                            else ""))
    if 12 * s.width > N:
        raise ModelError(ring_too_short(N, s.width, kr, shortest_ring(width_at, N, ModelError)))
    n = np.arange(N, dtype=float)
    a, w = s.amplitude, s.width
    xi = n + 0.5 - N / 2
    E2 = (a / 2 / np.cosh(xi / w)) ** 2 if s.kind == "bright" else (a / 2 * np.tanh(
        xi / w)) ** 2
    lam = -float(E2.mean()) if np.any(nl.strain != 0) else 0.0
    # the soliton's own turn (e^{i shift t}), and the ring's uniform strain through the
    # mean flow's part of g2 (ModelSoliton: the black one's background has no strain)
    shift = nl.g2 * a**2 / 8 if s.kind == "bright" else nl.g2 * a**2 / 4
    frequency = nl.carrier.omega - shift - nl.parts["mean flow"] * lam
    return RingSoliton(nls=nl, soliton=s, N=int(N), frequency=float(frequency),
                       ring_strain=lam)
