"""Probe 98 of losses (bench/probe_losses98.py): the cases that found bugs, each against
physics computed here (the damped pencil's roots by numpy, a continuation in the damping)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from bench.probe_losses98 import FILES
from energy import load_model, parse_model
from numerics.models import (
    carrier,
    damping_rates,
    exact_amplification,
    four_wave_amplification,
    nls_amplification,
)

# the probe's own files (bench/probe_losses98.py), one text each
RESONATOR = FILES["resonator"]
KG_CUBIC = FILES["kgcubic"]


def _resonator_roots(gamma, k, p=(0.7, 0.4, 0.5)):
    """omega of det(K - i omega C - omega^2 M) = 0, the resonator's pencil by hand: K from
    (u_next - u)^2/2 + kc (v - u)^2/2 + kg v^2/2, M = diag(1, m2), C = diag(0, gamma)."""
    m2, kc, kg = p
    s2 = 4 * math.sin(k / 2) ** 2
    K = np.array([[s2 + kc, -kc], [-kc, kc + kg]])
    Minv = np.diag([1.0, 1 / m2])
    A = np.block([[np.zeros((2, 2)), np.eye(2)],
                  [-Minv @ K, -Minv @ np.diag([0.0, gamma])]])
    return 1j * np.linalg.eigvals(A)  # e^{lambda t} = e^{-i omega t}


def test_overdamped_resonator_keeps_the_carriers_oscillating_root():
    """gamma 3 on the resonator at k 0.3: the carrier's rate is that of the root continued
    from the lossless carrier as gamma rises from 0 (steps of 3/2000: the roots move by
    ~1e-3 a step, far less than their ~0.1 spacing). Before: 0.210, the resonator's slow
    relaxation (Re omega = 0), where the continued root decays at 0.055 (a jump from 0.066
    at gamma 2.5)."""
    model = load_model(parse_model(RESONATOR), gamma=3.0)
    c = carrier(model, 0.3)
    w = complex(c.omega)
    for g in np.linspace(0.0, 3.0, 2001)[1:]:
        r = _resonator_roots(g, c.k)
        w = r[np.argmin(np.abs(r - w))]
    assert w.real > 0.5  # it still oscillates
    # 1e-8: two eigenvalue solvers of the same 4 x 4 pencil (round-off ~1e-15)
    assert float(damping_rates(model, c.k)[c.branch]) == pytest.approx(-w.imag, rel=1e-8)


@pytest.mark.parametrize("gamma", [1e3, 1e8])
def test_overdamped_carrier_grows_nothing(gamma):
    """A Klein-Gordon carrier (k 2, a 0.4) damped past critical does not oscillate: its
    root omega = -i (gamma/2 - sqrt(gamma^2/4 - omega0^2 - 4 sin^2 1)) is imaginary
    (closed form here), a relaxation. Before: the theories took its slow rate
    (~omega^2/gamma, 3.8e-8 at 1e8) for a nearly undamped carrier: MI, amplification e^700,
    observable (3.6x, the NLS's, at 1e3)."""
    model = load_model(parse_model(KG_CUBIC), gamma=gamma)
    w2 = 1.0 + 4 * math.sin(1.0) ** 2
    assert gamma / 2 > math.sqrt(w2)  # overdamped, by hand
    for f in (nls_amplification, lambda m, k, a: exact_amplification(m, k, a, N=64),
              lambda m, k, a: four_wave_amplification(m, k, a, N=64)):
        a = f(model, 2.0, 0.4)
        assert a.amplification == 1.0 and not a.observable
        assert a.damped_verdict("MI")["verdict"] == "stable"


def test_damped_run_does_not_stop_at_a_first_band_before_the_theorys_peak():
    """kg-cubic (a3 0.5), k 2.266, a 0.4059, gamma 1.15e-3 on 64 sites: the near-carrier
    band peaks at ~86x at t ~ 561 and halves, while the band of offset ~1.96 (the exact
    theory's, peak at t ~ 1516) grows on: an unstopped run reaches 2540x by t 2500. Before,
    the run stopped at the first halving (t 680) and read 86x at t 561; now not before the
    theory's peak time. Bar 1000: between the first band's 86 and the later band's 2540
    (seed 0 as the cell's)."""
    from numerics.models import exact_gain, lossy_runs

    model = load_model(parse_model(KG_CUBIC), gamma=0.00115)
    k, a, N = 2.266, 0.4059, 64
    spec = exact_gain(model, k, a, N=N)
    peak = exact_amplification(model, k, a, N=N, first=spec).amplification_time
    sim, amp = lossy_runs(model, k, a, spec, N=N, seeds=1, peak_time=peak)
    assert sim.runs[0].t[-1] >= peak
    assert amp["amplification_simulated"] > 1000


def test_point_names_an_overdamped_carrier_in_its_stable_note(tmp_path, capsys):
    """After the theories answer 1x for an overdamped carrier, ``point``'s note read 'no
    sideband outgrows its damping at t = 0 (net rate at best 0 /time)': a sideband balanced
    by its damping, where there is no wave at all. It now says the carrier is damped past
    critical (gamma 1e3 > 2 omega, by hand in test_overdamped_carrier_grows_nothing)."""
    from cli.app import main

    path = tmp_path / "kg-cubic-damped.toml"
    path.write_text(KG_CUBIC)
    assert main(["point", "--model", str(path), "--param", "gamma=1e3", "--k", "2",
                 "--amplitude", "0.4", "--N", "64"]) == 0
    out = capsys.readouterr().out
    assert "damped past critical" in out and "net rate at best" not in out
