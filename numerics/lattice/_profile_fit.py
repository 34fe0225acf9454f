"""The sech^2 fit of a soliton's intensity profile on a ring: the one fit behind the paper
chain's soliton measurement (``numerics.theory.measure_state``) and any model's
(``numerics.models.simulate_soliton``)."""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

#: half-width (in fitted soliton widths) of the window counted as the soliton: the
#: intensity off the fitted profile beyond it is radiation, inside it shape misfit
RADIATION_WINDOW = 6.0
#: half-width (in widths) of the window a kink's strain is summed over: sech^2's share
#: beyond it is 1 - tanh(8) = 2e-7
KINK_WINDOW = 8.0


def kink_window(width: float, N: int) -> float:
    """Half-width (sites) of the window a kink is summed over on a ring of ``N`` sites:
    ``KINK_WINDOW`` widths, but at most one width short of the antipode, so that a ring
    of 12-16 widths (launched: 12 is the least) keeps a strip to read the background
    strain from. Without it the window covered the whole ring, where a periodic strain
    sums to zero: the kink read 0 (-100%; fput alpha 0.5, k 1.6, a 0.1 on N = 100, 12.5
    widths). The share lost on a 12-width ring: 1 - tanh(5) = 9e-5."""
    return min(KINK_WINDOW * width, N / 2 - width)

_KINDS = ("bright", "dark")


@dataclass(frozen=True)
class ProfileFit:
    """A soliton's intensity profile fitted on a ring (:func:`fit_soliton_profile`).

    Attributes
    ----------
    kind : {"bright", "dark"}
        The profile fitted: a^2 sech^2 (bright) or a^2 (1 - D sech^2) (dark).
    centre : float
        Fitted centre (site), ``centre_guess`` plus the fitted offset: not wrapped onto the
        ring, so a tracked centre stays continuous across the seam.
    amplitude : float
        a: the square root of the peak intensity (bright) or of the background (dark).
    width : float
        w of sech^2((n - centre) / w), > 0.
    dip : float
        D of the dark profile: the share of the background intensity missing at the
        centre (1: black, < 1: grey); 0.0 for a bright soliton. See also :attr:`depth`.
    radiation : float
        The intensity off the fitted profile farther than RADIATION_WINDOW widths from the
        centre, scaled to the whole ring (divided by the share of the ring outside the
        window: radiation spread evenly counts as much as if the window were empty),
        relative to the soliton's own intensity (the sum of the profile, bright; of the dip
        below the background, dark). NaN when the window covers the whole ring.
    shape_misfit : float
        The same inside the window, unscaled: how far the profile is from sech^2.
    """

    kind: str
    centre: float
    amplitude: float
    width: float
    dip: float
    radiation: float
    shape_misfit: float

    @property
    def depth(self) -> float:
        """The other depth convention: 1 - D, the intensity at the centre over the
        background's (dark; 0: black, 1: no dip); 0.0 for a bright soliton."""
        return 0.0 if self.kind == "bright" else 1 - self.dip


def ring_distance(n, c, N):
    """Signed distance from c to the sites n on a ring of N sites, in [-N/2, N/2)."""
    return (n - c + N / 2) % N - N / 2


def fit_soliton_profile(intensity, kind: str, centre_guess: float, width_guess: float
                        ) -> ProfileFit:
    """Least-squares fit of a soliton's intensity |2E|^2 on a ring by a^2 sech^2 (bright) or
    a^2 (1 - D sech^2) (dark), near a guessed centre and width.

    The fit uses the sites within 6 (bright) or 8 (dark) guessed widths of the guess; a
    dark soliton's starting background is the median intensity beyond 8 guessed widths.

    Parameters
    ----------
    intensity : ndarray, shape (N,)
        The intensity at each site of the ring (the squared modulus of the carrier's
        analytic signal, 2 E e^{i theta}).
    kind : {"bright", "dark"}
    centre_guess : float
        The centre to start from (site; any real number, taken modulo N).
    width_guess : float
        The width to start from (sites), > 0: the predicted one.

    Returns
    -------
    ProfileFit
        Centre, amplitude, width, depth in both conventions (``dip`` D, ``depth`` 1 - D),
        radiation and shape misfit.

    Raises
    ------
    ValueError
        A kind other than "bright" or "dark", an intensity that is not a 1-d array, a
        width_guess that is not > 0, or a fit that cannot start (a non-finite intensity
        near the guess: scipy's ``least_squares``).
    """
    from scipy.optimize import least_squares

    if kind not in _KINDS:
        raise ValueError(f"kind must be 'bright' or 'dark', got {kind!r}")
    amp2 = np.asarray(intensity, dtype=float)
    if amp2.ndim != 1:
        raise ValueError(f"intensity must be a 1-d array (one value a site), got shape "
                         f"{amp2.shape}")
    if not width_guess > 0:
        raise ValueError(f"width_guess must be > 0, got {width_guess}")
    N = amp2.size
    c0, w0 = centre_guess, width_guess
    n = np.arange(N, dtype=float)
    d = ring_distance(n, c0, N)
    win = np.abs(d) < (6 if kind == "bright" else 8) * w0
    scale = float(np.max(amp2))  # O(1) numbers: least_squares' tolerances are absolute
    x, y = d[win], amp2[win] / scale
    if kind == "bright":
        def model(p):
            return p[1] ** 2 / np.cosh((x - p[0]) / p[2]) ** 2
        p0 = [x[np.argmax(y)], math.sqrt(y.max()), w0]
    else:
        def model(p):
            return p[1] ** 2 * (1 - p[3] / np.cosh((x - p[0]) / p[2]) ** 2)
        far = np.abs(d) > 8 * w0
        bg = math.sqrt(np.median(amp2[far] / scale)) if far.any() else 1.0
        p0 = [x[np.argmin(y)], bg, w0, 1.0 - y.min() / bg**2]
    p = least_squares(lambda p: model(p) - y, p0, xtol=1e-12, ftol=1e-12, gtol=1e-12).x
    amp, width = abs(float(p[1])) * math.sqrt(scale), abs(float(p[2]))
    centre = c0 + float(p[0])
    dd = ring_distance(n, centre, N)
    if kind == "bright":
        full = amp**2 / np.cosh(dd / width) ** 2
        own = full
    else:
        full = amp**2 * (1 - p[3] / np.cosh(dd / width) ** 2)
        own = amp**2 - full
    off = np.abs(amp2 - full)
    core = np.abs(dd) <= RADIATION_WINDOW * width
    content = float(np.sum(np.abs(own)))
    share = max(1 - core.mean(), 1e-12)  # the part of the ring outside the window
    radiation = float(np.sum(off[~core]) / content / share) if (~core).any() else math.nan
    misfit = float(np.sum(off[core]) / content)
    dip = 0.0 if kind == "bright" else float(p[3])
    return ProfileFit(kind, float(centre), amp, width, dip, radiation, misfit)
