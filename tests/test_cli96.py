"""Issue 96: the command line and the Python entry points at inputs nobody tried
(bench/probe_cli96.py). Each test names what the old tree did."""

from __future__ import annotations

import math

import numpy as np
import pytest

import energy
import numerics.models as nm
from energy import ModelError
from generated import soliton as closed


@pytest.mark.parametrize("k", [-1.0, 0.0, 4.0, 7.0, math.pi + 1e-12, -math.pi])
def test_carrier_takes_the_range_nls_takes(k):
    # before: carrier(fput, -1.0) returned a Carrier with k = -1 (omega 0.9589, v_g of the
    # wave at +1) and carrier(fput, 7.0) one with k = 7, where nls, exact_gain and
    # four_wave refuse k outside (0, pi]; carrier(fput, 0.0) talked of float64 resolution
    m = energy.load_model("fput", alpha=1, beta=1)
    with pytest.raises(ModelError, match=r"k must be in \(0, pi\].*got"):
        nm.carrier(m, k)
    with pytest.raises(ModelError, match=r"k must be in \(0, pi\]"):
        nm.nls(m, k)


def test_carrier_keeps_the_zone_boundary():
    # FPUT by hand: omega = 2 sin(k/2) = 2 at pi, v_g = cos(k/2) = 0, g1 = -sin(k/2)/2
    c = nm.carrier(energy.load_model("fput"), math.pi)
    assert c.omega == pytest.approx(2.0, rel=1e-14)
    assert c.group_velocity == 0.0
    assert c.g1 == pytest.approx(-0.5, rel=1e-10)  # lambda'' - 2 v_g^2: a few ulps of 1


G1, G2 = 0.02, 40.0  # bright: g = 2000; dark: g2 -> -G2


@pytest.mark.parametrize("a", [0.002, 0.01])
def test_soliton_forms_take_the_amplitude_by_its_size(a):
    # before: bright_width(-0.002, 0.02, 40) = -22.4 sites, dark_width and both kinks
    # negative too: a width is a length. The amplitude is the peak rotation 2|E| and
    # E -> -E solves the NLS when E does, so -a is the soliton of |a| (docs/solitons.md).
    # By hand, with a/2 = |E|: w = 1/((a/2) sqrt(g)), kink 2 mu (a/2)^2 w
    g, mu, phi = G2 / G1, -1.3, 0.4
    w_bright = 1 / (a / 2 * math.sqrt(g))
    w_dark = 1 / (a / 2 * math.cos(phi) * math.sqrt(g))
    for amp in (a, -a):
        assert closed.bright_width(amp, G1, G2) == pytest.approx(w_bright, rel=1e-14)
        assert closed.dark_width(amp, phi, G1, -G2) == pytest.approx(w_dark, rel=1e-14)
        assert closed.bright_kink(amp, G1, G2, mu) == pytest.approx(
            2 * mu * (a / 2) ** 2 * w_bright, rel=1e-14)
        assert closed.dark_kink(amp, phi, G1, -G2, mu) == pytest.approx(
            -2 * mu * (a / 2) ** 2 * math.cos(phi) ** 2 * w_dark, rel=1e-14)
        # V = g1 (a/2) sin(phi) sqrt(-g): the grey soliton of |a|, not the mirror one
        assert closed.dark_velocity(amp, phi, G1, -G2) == pytest.approx(
            G1 * a / 2 * math.sin(phi) * math.sqrt(g), rel=1e-14)
    xi, t = np.linspace(-3 * w_bright, 3 * w_bright, 41), 7.0
    np.testing.assert_array_equal(closed.bright_envelope(xi, t, -a, G1, G2),
                                  closed.bright_envelope(xi, t, a, G1, G2))
    np.testing.assert_array_equal(closed.dark_envelope(xi, t, -a, phi, G1, -G2),
                                  closed.dark_envelope(xi, t, a, phi, G1, -G2))
