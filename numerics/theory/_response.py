"""What a run measures, predicted: the linear response of its actual initial state.

The simulated verdict of a map cell (``numerics.maps.simulate_cell``) reads the Fourier
spectrum of the run: the largest non-carrier, non-harmonic component relative to the
carrier, and how much it grows (theta from T = 0, U from its level at 5% of the run). A
growth *rate* answers another question. This module answers the simulation's:

1. The run starts in ``initial_condition(seed)`` = the noise-free start + delta. The
   noise-free start is the launched state (``launched_state``: the exact travelling
   wave, or, for eq. `IC`, the quasi-periodic torus of carrier plus free waves).
2. delta is linear data on that state. Split by Bloch offset: the components of delta at
   the wavenumbers q + p k (theta at odd p, U at even p) form one family, which Hill's
   matrices about the state (``_quasiperiodic.hill_matrix``; the travelling wave is its
   d = 0 case) evolve exactly, up to the truncation |p| <= P, |m| <= R.
3. Each family's data are projected on its Hill modes (the rows of V^-1 are the left
   eigenvectors, biorthogonal to the right ones V), every mode is advanced by its
   exponent e^{lambda T}, and the components are reassembled at the lattice's Fourier
   bins, e^{-i (p Omega + m . nu) T} restoring the lab frame.
4. Bins no family reaches (far from the carrier when k is small: |p| > P) hold free
   linear waves; their forward and backward parts beat at the linear frequency.
5. The spectrum is read as the simulation reads it: same bins, same masks
   (``non_carrier_bins``), same ratio to the carrier (whose amplitude the launched state
   gives over time), same records (t_end / records apart), same reference levels.

The families' Hill problems live in ``_families`` (``Families``); this module reads their
response as the simulation reads its spectrum.

A family's response is linear in the noise, so the Hill work is done once per cell and
each seed (or draw of the noise law for the expectation) costs one projection.

The prediction is the linear response. Where a predicted component reaches the carrier's
amplitude the run has left the linear stage: the verdict is MI either way, the predicted
growth factor is then an upper bound of what a saturating run shows (``linear`` False).
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass

import numpy as np

from common.threads import one_blas_thread
from generated import lattice_model as model

from ..lattice import (
    GROWTH_THRESHOLD,
    Material,
    check_case,
    check_start,
    checks,
    initial_condition,
    noise_field,
    non_carrier_bins,
    snap_wavenumber,
    spectrum_growth,
)
from ._families import Families
from ._launched import forward_backward
from ._plane_wave import HARMONICS, _check_harmonics, plane_wave
from ._quasiperiodic import torus_of_wave
from ._torus import uniform_phases

#: draws of the noise law for the expected growth factor (its Monte-Carlo error on the
#: mean is std / sqrt(DRAWS), ~ 10% of the spread between seeds)
DRAWS = 32
#: the chains a prediction takes, [low, high) sites (below 8 no sideband pair and its
#: neighbours fit beside the carrier's harmonics; a map's cells need it too)
SITES = (8, 10**6)
#: bytes of one chunk of evolved families (and its temporaries): the spectra stay the
#: largest arrays (the result does not depend on it, tests/test_response.py)
CHUNK_BYTES = 2**27
#: the linear stage ends where a predicted component reaches this fraction of the carrier
LINEAR_LIMIT = 1.0
#: free-phase truncation of the eq. `IC` torus' Hill matrices (|m_j| <= free_order):
#: 0 keeps the free waves' mean effect (frequency shifts) only, 1 also their pumping,
#: which decides cells near 2 Omega = omega_U(2k). Measured on the fig3 grid, case II: 3 of
#: 62 cells (all MI, 500-1800x) need 1; elsewhere 0 and 1 agree within a few %. 1 costs
#: (2 + 1)^3 = 27x the eigenproblems (seconds per cell, > 10 s on a loaded 2-core machine
#: near k = pi): the default is 0; ask for 1 at single points
FREE_ORDER = 0
#: free phases given their own Fourier index when free_order >= 1: the strongest ones
#: (by their torus coefficients); the others enter by their mean
FREE_PHASES = 1
#: with free_order >= 1, torus misfit up to which a prediction is still made
#: (``_hill.TORUS_TOLERANCE`` bounds the misfit for a growth *rate*); between the two the
#: prediction is ``approximate``: the growth factor read at 20x tolerates a rate error a
#: gain does not (measured: the two fig3 case II cells with misfit 0.08-0.09 both grew
#: > 1000x, predicted 50x and 5e4x at free_order 1; at 0 they are predicted stable)
RESPONSE_TORUS_TOLERANCE = 0.1


@dataclass(frozen=True)
class GrowthPrediction:
    """The predicted spectrum growth of one run, read as the simulation reads it.

    Attributes
    ----------
    t : ndarray, shape (nt,)
        Record times (lattice time units), 0 .. t_end.
    ratio : dict of str -> ndarray, shape (nt,)
        Per field ("theta"; "U" in case II): the largest non-carrier, non-harmonic
        component over the carrier, per record.
    spectrum : dict of str -> ndarray, shape (nt, N // 2 + 1)
        Per field: the predicted perturbation's Fourier amplitudes |rfft| 2 / N (the
        simulation's ``theta_hat``/``U_hat`` less the noise-free state), every bin.
    growth : float
        The simulation's measure: the largest growth factor of ``ratio`` over the run
        (theta from T = 0, U from its level at 5% of t_end: ``spectrum_growth``), over the fields.
    growth_field : str
        The field carrying it.
    growth_q : float
        The wavenumber (rad per site) of the component at the record where it peaks.
    verdict : bool
        growth > GROWTH_THRESHOLD (20x within t_end): the simulation's question.
    rate : float
        The largest growth rate Re lambda over every family (1/T), for reference.
    linear : bool
        False where a predicted component reaches the carrier's amplitude within t_end
        (the run saturates: verdict MI either way, growth an upper bound).
    torus_misfit : float
        Relative misfit of the launched state's torus (0 for the travelling wave); above
        ``_hill.TORUS_TOLERANCE`` the prediction is approximate.
    expected_growth : float
        The mean growth factor over DRAWS draws of the noise law (same parameters, seeds
        seed + 1 .. seed + draws); ``growth_quantiles`` its 10%, 50% and 90% quantiles,
        ``growth_draws`` every draw's growth factor.
    k, start, N, seed, t_end : the experiment
    exponential : ndarray, shape (1 + draws,)
        The growth factors (seed, then each draw) that exponential growth accounts for
        (``spectrum_growth(exponential=True)``: algebraic growth does not count), as a
        point's run verdict reads them.
    """

    t: np.ndarray
    ratio: dict
    spectrum: dict
    growth: float
    growth_field: str
    growth_q: float
    verdict: bool
    rate: float
    linear: bool
    torus_misfit: float
    expected_growth: float
    growth_quantiles: tuple
    growth_draws: np.ndarray
    k: float
    start: str
    N: int
    seed: int
    t_end: float
    exponential: np.ndarray | None = None

    @property
    def approximate(self) -> bool:
        """The launched state's torus misfits more than a growth rate tolerates
        (``_hill.TORUS_TOLERANCE``): the growth factor is approximate."""
        from ._hill import TORUS_TOLERANCE

        return self.torus_misfit > TORUS_TOLERANCE

    def growth_at(self, t: float) -> float:
        """The growth factor the simulation reads when it stops at time ``t`` (the
        records up to t; the map cells stop early once the verdict is certain)."""
        n = int(np.searchsorted(self.t, t * (1 + 1e-12), side="right"))
        if n < 2:
            return 1.0
        bins = {f: np.zeros(1, int) for f in self.ratio}
        g, _, _ = spectrum_growth(self.t[:n], {f: r[None, :n, None]
                                               for f, r in self.ratio.items()}, bins, self.N,
                                  t_end=self.t_end)
        return float(g[0])


def _strongest_phases(torus, keep: int):
    """The torus with only its ``keep`` strongest free phases (by the sum of their first
    Fourier coefficients over both fields); the others averaged out (modes with m_j = 0)."""
    d = torus.nu.size
    if d <= keep:
        return torus
    single = np.abs(torus.modes).sum(axis=1) == 1
    strength = [np.abs(torus.theta[:, single & (torus.modes[:, j] != 0)]).sum()
                + np.abs(torus.U[:, single & (torus.modes[:, j] != 0)]).sum()
                for j in range(d)]
    kept = np.sort(np.argsort(strength)[::-1][:keep])
    dropped = np.setdiff1d(np.arange(d), kept)
    rows = np.all(torus.modes[:, dropped] == 0, axis=1)
    return dataclasses.replace(torus, nu=torus.nu[kept], modes=torus.modes[rows][:, kept],
                               theta=torus.theta[:, rows], U=torus.U[:, rows])


def _free_waves(material, N, delta, field, covered, t):
    """Bins no family reaches: free linear waves of the branch, |f e^{-iwt} + b e^{iwt}|."""
    rest = np.array(sorted(set(range(N)) - covered), int)
    if rest.size == 0:
        return rest, np.zeros((t.size, delta[0].shape[0], 0), complex)
    qq = 2 * np.pi * rest / N
    w = (model.omega_rotation(qq, material.alpha, material.K_s, material.K_theta)
         if field == 0 else model.omega_longitudinal(qq))
    w = np.where(w > 0, w, 1.0)  # the uniform U mode is a rigid shift: no beating
    f, b = forward_backward(delta[2 * field][:, rest], delta[2 * field + 1][:, rest], w)
    ph = uniform_phases(t, -w)  # (nt, nb)
    return rest, f[None] * ph[:, None] + b[None] * np.conj(ph)[:, None]


@one_blas_thread
def predict_growth(material: Material, case: str, k: float, amplitude: float = 0.02, *,
                   start: str = "paper", N: int = 500, t_end: float = 5000.0,
                   seed: int = 0, noise: float = 1e-3, records: int = 200,
                   draws: int = DRAWS, harmonics: int = HARMONICS,
                   free_order: int = FREE_ORDER) -> GrowthPrediction:
    """The growth factor a simulation of this experiment measures, from linear response.

    Parameters
    ----------
    material, case, k, amplitude, start, N, noise, seed :
        The experiment, as :func:`numerics.simulate` takes it; k is snapped to the
        nearest 2 pi m / N, as ``flexmm map`` and ``point`` do before they simulate
        (``simulate`` itself takes only such a k, and names the nearest one otherwise).
    t_end : float
        Length of the run (lattice time).
    records : int
        Spectra recorded over the run (t_end / records apart: the map cells record 200).
    draws : int
        Draws of the noise law (seeds seed + 1 ..) for ``expected_growth``; 0 skips it.
    harmonics : int
        Truncation H of the state (as :func:`plane_wave`); the Hill matrices keep
        |p| <= 2H - 1 (theta) and 2H (U).
    free_order : int
        |m_j| <= free_order for the free phases of eq. `IC`'s torus.

    Returns
    -------
    GrowthPrediction

    Raises
    ------
    ValueError
        For bad input, or where no plane wave of that amplitude exists.
    ArithmeticError
        Where the launched state is not quasi-periodic (no linear theory applies).

    Examples
    --------
    >>> p = predict_growth(Material.paper("blue"), "coupled", 0.8168, 0.02, t_end=2000)
    >>> p.growth, p.verdict                                 # doctest: +SKIP
    """
    checks.instance("material", material, Material)
    case = check_case(case)
    start = check_start(start)
    N = checks.integer("N", N, *SITES)
    noise = checks.real("noise", noise, 0.0, 1.0, low_open=False, high_open=True)
    seed = checks.seed(seed)
    t_end = checks.positive("t_end", t_end)
    records = checks.integer("records", records, 2, 10**5)
    draws = checks.integer("draws", draws, 0, 10**4)
    free_order = checks.integer("free_order", free_order, 0, 3)
    H = _check_harmonics(harmonics)
    k_run, m0 = snap_wavenumber(k, N, return_index=True)
    if 2 * m0 >= N:
        raise ValueError(f"k = {k:g} snaps to pi on N = {N} sites: no sidebands")
    # the state the run starts in (imported here: _launched imports _hill's torus cache)
    from ._hill import _launched
    if start == "travelling":
        wave = plane_wave(material, case, k_run, amplitude, H)
        tor, R, launched = torus_of_wave(wave), 0, None
    else:
        launched = _launched(material, case, k_run, amplitude, start, H)
        tor = launched.torus if free_order == 0 else _strongest_phases(launched.torus,
                                                                      FREE_PHASES)
        R = free_order
        from ._hill import TORUS_TOLERANCE
        if tor.residual > (RESPONSE_TORUS_TOLERANCE if free_order else TORUS_TOLERANCE):
            raise ArithmeticError(
                f"the state eq. `IC` launches at k = {k_run:.6g}, amplitude {amplitude:g} is "
                f"not quasi-periodic (torus misfit {tor.residual:.2g}): no linear response "
                "applies; simulate it")
    fam = Families(tor, material, case, m0, N, 2 * H - 1, R)
    t = np.linspace(0.0, t_end, records + 1)

    # every start multiplies its fields by (1 + b0) (``numerics.lattice.noise_field``):
    # delta = b0 x the noise-free start, per seed
    seeds = [seed] + [seed + 1 + i for i in range(draws)]
    clean = initial_condition(material, case, N, k_run, amplitude, 0.0, 0, start)
    b0 = np.array([noise_field(N, noise, s) for s in seeds])  # (draws + 1, N)
    delta = [np.fft.fft(b0 * x, axis=1) / N if x is not None else np.zeros((len(seeds), N))
             for x in (clean.theta, clean.theta_dot, clean.U, clean.U_dot)]
    X0 = fam.initial(delta)
    fields = ("theta", "U") if case == "coupled" else ("theta",)
    # the spectra of every field at every record (complex), kept while the families are
    # evolved a chunk at a time: a chunk's amplitudes (nt, chunk, n, draws) are deposited at
    # their bins and dropped (all at once they are ~ n / 2 x the spectra: 20 GB at N = 10^4)
    checks.memory("N", 16.0 * t.size * len(seeds) * N * (len(fields) + 1),
                  f"the predicted spectra of {N} sites at {t.size} records for "
                  f"{len(seeds)} seed(s)")
    fulls = [np.zeros((t.size, len(seeds), N), complex) for _ in fields]
    chunk = max(1, int(CHUNK_BYTES // (16 * t.size * fam.n * len(seeds) * 4)))
    for f0 in range(0, fam.j.size, chunk):
        sl = slice(f0, min(f0 + chunk, fam.j.size))
        amp = fam.evolve(X0[sl], t, sl)  # (nt, chunk, n, draws)
        for f, full in enumerate(fulls):
            for i, row in zip(*np.nonzero(fam.direct[sl] & (fam.field == f)[None, :])):
                full[:, :, fam.b[f0 + i, row] % N] += amp[:, i, row, :]
            for i, row in zip(*np.nonzero(fam.conj_owner[sl] & (fam.field == f)[None, :])):
                full[:, :, -fam.b[f0 + i, row] % N] += np.conj(amp[:, i, row, :])
        del amp

    # the carrier's amplitude per record, as the simulation reads bin m0
    if launched is None:
        carrier = np.full(t.size, abs(wave.theta_harmonics[0]))
    else:
        carrier = np.abs(launched.mode("theta", 1, t))
    ratio, bins_of, perturbation = {}, {}, {}
    linear = True
    for f, name in enumerate(fields):
        full = fulls[f]
        rest, free = _free_waves(material, N, delta, f, fam.covered[f], t)
        full[:, :, rest] += free
        mask = non_carrier_bins(m0, N, name)
        perturbation[name] = 2 * np.abs(full[:, 0, : N // 2 + 1])
        if not mask.any():  # every bin of this field is a harmonic (small N): nothing to read
            continue
        spec = 2 * np.abs(full[:, :, : N // 2 + 1][:, :, mask])  # (nt, draws, nbins)
        linear &= bool(np.all(spec[:, 0].max(axis=1) < LINEAR_LIMIT * carrier))
        ratio[name] = np.transpose(spec / carrier[:, None, None], (1, 0, 2))
        bins_of[name] = np.flatnonzero(mask)
    growth, field, where = spectrum_growth(t, ratio, bins_of, N)
    exponential, _, _ = spectrum_growth(t, ratio, bins_of, N, exponential=True)
    g = float(growth[0])
    expected = float(np.mean(growth[1:])) if draws else float("nan")
    quant = tuple(float(x) for x in np.quantile(growth[1:], (0.1, 0.5, 0.9))) if draws \
        else (float("nan"),) * 3
    return GrowthPrediction(
        t=t, ratio={n: r[0].max(axis=1) for n, r in ratio.items()}, spectrum=perturbation,
        growth=g,
        growth_field=str(field[0]), growth_q=float(where[0]),
        verdict=bool(g > GROWTH_THRESHOLD), rate=fam.rate, linear=linear,
        torus_misfit=float(tor.residual if launched is not None else 0.0),
        expected_growth=expected, growth_quantiles=quant, growth_draws=growth[1:].copy(),
        k=float(k_run), start=start, N=N,
        seed=seed, t_end=float(t_end), exponential=exponential.copy())


__all__ = ["GrowthPrediction", "predict_growth"]
