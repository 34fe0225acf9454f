"""Which ring modes a damped run's amplification reads (``numerics.models._growth``:
``harmonic_drift``, ``amplitude_series``): a carrier harmonic's mode counts by what it holds
beyond the most the wave's own content can put there.

Before, every mode h m (mod N), |h| <= H, was left out: on a small ring a high harmonic
aliases onto the fastest sidebands (kg-cubic on 64 sites, k = 2 pi 23 / 64, H = 16: 33
of the 64 modes, the sideband pair 21, 25 among them) and the run read 2e3 where its own
sideband grew e^14 and the exact theory says 4.5e6 (probe 98's left note)."""

from __future__ import annotations

import math
from types import SimpleNamespace

import numpy as np

from bench.probe_losses98 import model_of
from energy import load_model, parse_model
from numerics.models import exact_amplification, exact_gain, lossy_runs, simulate_model
from numerics.models._growth import OVER_DRIFT, amplitude_series, harmonic_drift


def test_the_drift_of_a_mode_is_twice_its_harmonics_content():
    """By hand: a two-field wave with H = 3 on a ring of 10, carrier mode 3: harmonic 2
    lands on 6 and 4, harmonic 3 on 9 and 1; the mean and the carrier's modes never read."""
    c = np.zeros((2, 7), complex)
    c[:, 3 + 2] = [3e-4, 4e-4]  # |c_2| = 5e-4 (the fields' norm)
    c[:, 3 - 2] = [0, 1e-4]
    c[:, 3 + 3] = [1e-6, 0]
    wave = SimpleNamespace(harmonics=3, coefficients=c)
    D = harmonic_drift(wave, 10, 2 * math.pi * 3 / 10)
    assert D[6] == 2 * 5e-4 and D[4] == 2 * 1e-4 and D[9] == 2e-6 and D[1] == 0.0
    assert np.isinf(D[[0, 3, 7]]).all() and (D[[2, 5, 8]] == 0).all()
    S = np.array([[1.0, 1e-9, 2e-9, 5.0, 3e-3, 1e-9, 9e-3, 5.0, 3e-9, 1e-9]])
    # read: 1, 2, 5, 8 as they are; 4 beyond 10 x its 2e-4, 6 beyond 10 x its 1e-3 (none),
    # 9 beyond 10 x 2e-6 (none); 0, 3, 7 never
    assert amplitude_series(S, D)[0] == 3e-3 - 2e-3
    S[0, 4] = 1.9e-3
    assert amplitude_series(S, D)[0] == 3e-9
    S[0, 6] = 1.5e-2  # a sideband on the harmonic's mode: what it holds beyond the drift
    assert amplitude_series(S, D)[0] == 1.5e-2 - 1e-2
    assert amplitude_series(S[0], D) == amplitude_series(S, D)[0]  # one record


def test_a_damped_run_on_a_small_ring_reads_its_fastest_sidebands():
    """kg-cubic (probe 98's file) at gamma 1.15e-3 on 64 sites: the run's amplification
    within 100x of the exact theory's (it read 2100x below; measured now 34x: the runs'
    usual 0.2-0.5x is not met here, left as a finding: the fastest mode grew e^14 from its
    own start, 0.27 of the theory's e^15.3, and started at 0.4 of the noise's largest
    mode, A(0)), and its largest mode a harmonic's alias whose drift bound is below 1e-12
    of it (the modes the old rule left out)."""
    m = model_of("kgcubic", gamma=0.0011488688502019468)
    k, a, N = 2.266, 0.4059, 64
    spec = exact_gain(m, k, a, N=N)
    ex = exact_amplification(m, k, a, N=N, first=spec)
    _, amp = lossy_runs(m, k, a, spec, N=N, seeds=1, peak_time=ex.amplification_time)
    ratio = amp["amplification_simulated"] / ex.amplification
    assert 1 / 100 < ratio < 2, (amp, ex.amplification)
    run = simulate_model(m, k, a, N=N, t_end=2000.0, records=200)
    D = harmonic_drift(run.wave, N, run.k)
    A = amplitude_series(run.spectrum, D)
    i = int(np.argmax(A))
    j = int(np.argmax(np.where(np.isfinite(D), run.spectrum[i] - OVER_DRIFT * D, 0)))
    assert 0 < D[j] < 1e-12 * A[i], (j, D[j], A[i])


def test_a_linear_start_reads_no_harmonic_mode():
    """A stable wave (a KG chain with a quartic site: probe 98's stable twin, undamped)
    started from the linear wave, not the exact one: its harmonics' modes deviate far
    above the noise (measured 22 |c_5| and 1000 |c_7|: combination tones of the wave and
    the free wave the start launched, off the wave's family, so no drift bound holds);
    none is read, and the run does not grow 20x (the new rule without the linear start's
    exception read 8600x)."""
    m = model_of("stabletwin", eta=0.0)
    run = simulate_model(m, 1.0, 0.3, N=32, t_end=600.0, start="linear", records=120)
    D = harmonic_drift(run.wave, 32, run.k)  # the exact start's bound, to show the drift
    S = run.spectrum
    noise = float(np.median(S[0, D == 0]))
    big = np.isfinite(D) & (D > 1e3 * noise)
    assert big.any()  # harmonics far above the noise: the drift that must not be read
    assert np.max(S[:, big]) > 1e3 * noise  # ...and their modes do deviate that much
    assert (np.max(S, axis=0) > 10 * D)[big].any()  # far past the exact start's bound
    assert np.isinf(harmonic_drift(run.wave, 32, run.k, False)[big]).all()
    assert run.amplification().amplification < 20


def test_fput_on_32_sites_sees_the_sidebands_on_its_harmonics(fput_lossy):
    """docs/models.md's case: the lossy FPUT chain (beta 1, gamma 0.002) at k 2.6, a 0.1
    on 32 sites. Its sidebands alias onto carrier harmonics; the run read 1.7x against
    the exact theory's 4800x (not observable against observable). Now within the runs'
    documented band of the theory, 0.1-2x (measured 0.23)."""
    m = load_model(parse_model(fput_lossy), gamma=0.002)
    k, a, N = 2.6, 0.1, 32
    spec = exact_gain(m, k, a, N=N)
    ex = exact_amplification(m, k, a, N=N, first=spec)
    _, amp = lossy_runs(m, k, a, spec, N=N, seeds=1, peak_time=ex.amplification_time)
    assert 0.1 < amp["amplification_simulated"] / ex.amplification < 2, (amp, ex)
    assert amp["observable_simulated"] == 1.0 and ex.observable


def test_a_given_initial_state_reads_no_harmonic_mode():
    """The review's case: the linear start's state given as ``initial`` (noise 0) is as far
    off the wave's family as start="linear" itself: the run says start "initial", keeps
    every harmonic's mode out, and reads what the linear start reads (it read 8571x
    through the exact start's drift bound)."""
    m = model_of("stabletwin", eta=0.0)
    lin = simulate_model(m, 1.0, 0.3, N=32, t_end=600.0, start="linear", records=120)
    u0, v0 = simulate_model(m, 1.0, 0.3, N=32, t_end=1e-9, start="linear", noise=0.0,
                            records=1).state
    given = simulate_model(m, 1.0, 0.3, N=32, t_end=600.0, initial=(u0, v0), noise=1e-8,
                           records=120)
    assert given.start == "initial"
    assert given.amplification().amplification < 20
    assert lin.amplification().amplification < 20
