"""Envelope solitons of the chain: the prediction (closed forms) and the ring's wavenumber.

The closed forms are derived in ``derivation/_soliton.py`` and read from
``generated/soliton.py`` (bright and dark solitons of the NLS, eq. `NLS`, in lattice units,
with the kink of U in case II); the NLS coefficients come from ``generated.coefficients``
(theory ``"paper NLS"``) or ``generated.lattice_coefficients`` (``"semi-discrete NLS"``,
the default: it is the one the lattice follows, see docs/solitons.md). The lattice launch
is in ``_soliton_launch``, the measurement of a run in ``_soliton_measure``.

Conventions: ``amplitude`` is the peak rotation (rad) of the carrier, 2|E| (the paper's
2 eps |B|); for a dark soliton that of the background. Widths in sites, |E| = a sech(xi/w)
(bright) or a tanh(xi/w) (black). Velocities in sites per T, frequencies in 1/T, the kink
height in lattice units of U.

A ring of N sites carries a bright soliton at k = 2 pi m / N, and a dark one only when the
carrier closes the envelope's phase jump: k N + (2 phi - pi) = 2 pi m (k = (2m + 1) pi / N
for a black soliton); :func:`ring_wavenumber` picks that k.
"""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass, field

from generated import soliton as closed

from ..lattice import Material, check_case, checks
from ._gain import nls_undefined
from ._records import PAPER_NLS, SEMIDISCRETE_NLS

KINDS = ("bright", "dark")
#: the NLS theories a soliton can be predicted from (names as in ``THEORIES``)
SOLITON_THEORIES = {t.label: t.closed_forms() for t in (SEMIDISCRETE_NLS, PAPER_NLS)}
#: below this width (sites) the envelope is too narrow for the weak-modulation ordering
#: (the convergence scene shows the error reaching tens of percent near 5 sites)
MIN_WIDTH = 8.0


class SolitonWarning(UserWarning):
    """The soliton asked for is too narrow for the envelope theory."""


@dataclass(frozen=True)
class Soliton:
    """A predicted envelope soliton of one material, case, carrier and theory.

    Attributes
    ----------
    kind : {"bright", "dark"}
    theory : {"semi-discrete NLS", "paper NLS"}
    material, case, k, amplitude, phi
        The inputs (k in rad/site, amplitude = peak rotation in rad; phi the greyness angle
        of a dark soliton, 0 = black).
    omega, v_g, g1, g2 : float
        The NLS at k (linear carrier frequency, group velocity, eq. `g_i`).
    width : float
        Sites: |E| = a sech(xi/w) (bright), a^2 - |E|^2 = a^2 cos^2(phi) sech^2(xi/w) (dark).
    velocity : float
        Sites per T: v_g (bright, black), v_g + V (grey).
    frequency : float
        The soliton's carrier frequency (1/T): omega minus the nonlinear shift.
    mu : float
        Mean-flow coefficient (case II), U_{n+1} - U_n = mu (|E|^2 - background); 0 in case I.
    kink_height : float
        U(+inf) - U(-inf) across the soliton (lattice units); 0 in case I.
    """

    kind: str
    theory: str
    material: Material
    case: str
    k: float
    amplitude: float
    phi: float
    omega: float
    v_g: float
    g1: float
    g2: float
    width: float
    velocity: float
    frequency: float
    mu: float
    kink_height: float
    u2: complex = field(repr=False, default=0j)

    @property
    def g(self) -> float:
        return self.g2 / self.g1

    def envelope(self, xi, t=0.0):
        """E at sites ``xi`` from the centre (frame moving with v_g), time ``t``."""
        if self.kind == "bright":
            return closed.bright_envelope(xi, t, self.amplitude, self.g1, self.g2)
        return closed.dark_envelope(xi, t, self.amplitude, self.phi, self.g1, self.g2)

    def summary(self) -> dict:
        """The five numbers the CLI prints and ``soliton.json`` stores."""
        return {"velocity": self.velocity, "width": self.width, "amplitude": self.amplitude,
                "frequency": self.frequency, "kink_height": self.kink_height}


def _kind_that_exists(g):
    return "bright" if g > 0 else "dark"


def soliton(material: Material, case: str, k: float, amplitude: float, kind: str | None = None,
            *, theory: str = "semi-discrete NLS", phi: float = 0.0,
            N: int | None = None) -> Soliton:
    """The envelope soliton the NLS predicts at carrier ``k`` and peak rotation ``amplitude``.

    Parameters
    ----------
    material : Material
    case : {"rotation", "coupled"}
    k : float
        Carrier wavenumber, rad/site, in (0, pi).
    amplitude : float
        Peak rotation (rad): of the soliton (bright) or of its background (dark).
    kind : {"bright", "dark"}, optional
        Default: the one that exists (bright where g = g2/g1 > 0, dark where g < 0).
    theory : {"semi-discrete NLS", "paper NLS"}
    phi : float
        Greyness angle of a dark soliton, |phi| < pi/2 (0: black); 0 for bright ones.
    N : int, optional
        On a ring of N sites (case II, semi-discrete NLS): a periodic U has no net strain,
        so the mean strain under the soliton is compensated by a uniform one over the ring,
        which the carrier feels through the mean-flow part of g2 (a frequency shift of
        order width / N). Default: an infinite chain with no strain far away.

    Returns
    -------
    Soliton

    Raises
    ------
    ValueError
        A kind that does not exist here (the message names the one that does), or bad input.

    Warns
    -----
    SolitonWarning
        When the width is below ``MIN_WIDTH`` sites (the envelope theory does not hold).

    Examples
    --------
    >>> from numerics import Material
    >>> from numerics.theory import soliton
    >>> s = soliton(Material.paper("green"), "rotation", 0.92991, 0.002)
    >>> print(s.kind, f"{s.width:.1f} sites, v = {s.velocity:.5f}")
    bright 28.0 sites, v = -0.01689
    """
    checks.instance("material", material, Material)
    check_case(case)
    k = checks.real("k", k, 0.0, math.pi)
    amplitude = checks.positive("amplitude", amplitude)
    if amplitude >= 1.0:
        raise ValueError(f"amplitude must be a small peak rotation (< 1 rad), got {amplitude}")
    try:
        nls = SOLITON_THEORIES[theory]
    except (KeyError, TypeError):
        raise ValueError(f"theory must be one of {tuple(SOLITON_THEORIES)}, got "
                         f"{theory!r}") from None
    phi = checks.real("phi", phi, -math.pi / 2, math.pi / 2)
    p = (k, material.alpha, material.K_s, material.K_theta)
    why = nls_undefined(nls, material, case, k)
    if why is not None:
        raise ValueError(f"the {theory} has no soliton at k = {k:g}: {why}")
    omega, v_g, g1 = (float(f(*p)) for f in (nls.omega, nls.group_velocity, nls.g1))
    g2 = float(getattr(nls, f"g2_{case}")(*p))
    g = g2 / g1
    exists = _kind_that_exists(g)
    if kind is None:
        kind = exists
    if kind not in KINDS:
        raise ValueError(f"kind must be one of {KINDS}, got {kind!r}")
    if kind != exists:
        nature = "focusing" if g > 0 else "defocusing"
        raise ValueError(f"kind={kind!r}: the {theory} is {nature} here (g = g2/g1 = {g:.4g}, "
                         f"case {case}, k = {k:g}), so a {exists} soliton exists, not a {kind} "
                         "one")
    if kind == "bright" and phi != 0:
        raise ValueError(f"phi (greyness) applies to dark solitons only, got phi = {phi}")
    coupled = case == "coupled"
    mu = 0.0
    if coupled:
        mu = float(nls.mean_flow_coefficient(*p) if theory == SEMIDISCRETE_NLS.label
                   else closed.continuum_mean_flow_coefficient(*p))
    if N is not None:
        N = checks.integer("N", N, 3)
    # the mean-flow term of the semi-discrete NLS is g2_mf (F_X / mu) E with F_X = mu |E|^2
    # + c; a uniform strain c (no strain far away; on a ring, minus the soliton's mean)
    # turns E at g2_mf c / mu: the frequency moves by -g2_mf c / mu
    g2_mf = (float(closed.lattice_g2_mean_flow(*p))
             if coupled and theory == SEMIDISCRETE_NLS.label else 0.0)
    if kind == "bright":
        width = float(closed.bright_width(amplitude, g1, g2))
        velocity = v_g
        c_over_mu = 0.0 if N is None else -2 * (amplitude / 2) ** 2 * width / N
        frequency = (omega - float(closed.bright_frequency_shift(amplitude, g1, g2))
                     - g2_mf * c_over_mu)
        kink = float(closed.bright_kink(amplitude, g1, g2, mu))
    else:
        width = float(closed.dark_width(amplitude, phi, g1, g2))
        velocity = v_g + float(closed.dark_velocity(amplitude, phi, g1, g2))
        dip = 0.0 if N is None else 2 * width * math.cos(phi) ** 2 / N
        c_over_mu = -(amplitude / 2) ** 2 * (1 - dip)
        frequency = (omega - float(closed.dark_frequency_shift(amplitude, g2))
                     - g2_mf * c_over_mu)
        kink = float(closed.dark_kink(amplitude, phi, g1, g2, mu))
    if width < MIN_WIDTH:
        warnings.warn(f"the {kind} soliton is {width:.3g} sites wide (< {MIN_WIDTH:g}): the "
                      "envelope theory does not hold at this amplitude; lower the amplitude",
                      SolitonWarning, stacklevel=2)
    u2 = complex(nls.u2_coefficient(*p)) if coupled else 0j
    return Soliton(kind=kind, theory=theory, material=material, case=case, k=k,
                   amplitude=amplitude, phi=phi, omega=omega, v_g=v_g, g1=g1, g2=g2,
                   width=width, velocity=velocity, frequency=frequency, mu=mu,
                   kink_height=kink if coupled else 0.0, u2=u2)


def ring_wavenumber(k: float, N: int, kind: str = "bright", phi: float = 0.0) -> float:
    """The wavenumber nearest ``k`` on which a ring of ``N`` sites carries the soliton.

    Bright: 2 pi m / N. Dark: the envelope's phase jumps by 2 phi - pi across the soliton,
    so the carrier must close the ring with the opposite phase: k N + 2 phi - pi = 2 pi m.
    """
    N = checks.integer("N", N, 3)
    k = checks.real("k", k, 0.0, math.pi)
    if kind not in KINDS:
        raise ValueError(f"kind must be one of {KINDS}, got {kind!r}")
    offset = 0.0 if kind == "bright" else math.pi - 2 * phi
    m = round((k * N - offset) / (2 * math.pi))
    out = (2 * math.pi * m + offset) / N
    if not 0 < out < math.pi:
        raise ValueError(f"no ring wavenumber near k = {k:g} for N = {N}")
    return out


__all__ = ["KINDS", "SOLITON_THEORIES", "MIN_WIDTH", "SolitonWarning", "Soliton", "soliton",
           "ring_wavenumber"]
