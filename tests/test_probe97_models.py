"""What probe 97 found with eight model files nobody had tried (bench/probe_models97.py
holds the model texts and reruns the probe's checks), each reproduced on its point:

- a Hertz contact with precompression written with ``Abs`` (so that it may open) had no
  NLS at any d0: SymPy's simplify split each third and fourth derivative at rest into a
  Piecewise with an infinite branch at d0 = 0, printed as nan;
- a bilinear spring (stiffness jumping at rest) read g2 = 0, "stable", where its exact
  theory grows at a rate independent of the amplitude;
- a run's length bounds (T >= 1000, <= 1e5, 5000 where nothing grows) were in the model's
  own time: a chain of stiffness 1e6 and mass 1e-3 ran 6e7 radians (an estimated 88 min
  on 64 sites), one of stiffness 1e-6 could not decide what the unit chain decides;
- a run was said to leave out offsets whose waves sit on harmonics far below its noise
  (the 8th and 10th), and its T was chosen as if nothing it can see grows.
"""

from __future__ import annotations

import math

import pytest

from bench.probe_models97 import MODELS, fput_g2
from energy import load_model, parse_model


def _model(name, **params):
    return load_model(parse_model(MODELS[name], f"{name}.toml")).with_params(**params)


@pytest.mark.parametrize("k", [0.7, 1.3, 2.5])
def test_a_hertz_contact_written_with_abs_has_its_closed_contacts_nls(k):
    """Below the contact's opening the bond is (2/(3 sqrt d0)) ((2/5) (d0 - r)^(5/2) - ...):
    FPUT with alpha = V'''/2 = -1/(4 d0), beta = V''''/6 = -1/(24 d0^2) (by hand), whose
    g2 is -12 beta s^3 + 8 alpha^2 s (1 + s^2). Before: 'undefined: the energy's third or
    fourth derivatives at rest are not finite'. 1e-9: both are closed forms, the code's
    g2 an eigenproblem's round-off from it (measured 2e-16)."""
    from numerics.models import nls

    for d0 in (0.5, 2.0):
        r = nls(_model("hertz-pre", d0=d0), k)
        assert not r.undefined, r.undefined
        want = fput_g2(-1 / (4 * d0), -1 / (24 * d0**2), k)
        assert r.g2 == pytest.approx(want, rel=1e-9)


def test_a_bilinear_spring_has_no_nls_and_says_why():
    """(k1 + k2) r^2/4 + (k2 - k1) r |r|/4: its stiffness is k1 on one side of rest, k2 on
    the other, so its energy is homogeneous of degree 2: no weakly nonlinear expansion, and
    the exact theory's rate does not depend on the amplitude (1e-8: the Hill solve's
    round-off; measured equal to the last digit). Before: g2 = 0, 'stable (g2 = 0)', and
    the four-wave row 'stable', beside an exact MI of 0.035."""
    from numerics.models import exact_gain, four_wave, nls

    model = _model("bilinear")
    n = nls(model, 1.0)
    assert n.undefined and "second derivatives jump" in n.undefined
    assert four_wave(model, 1.0, 0.1, N=64).undefined
    r1, r2 = (exact_gain(model, 1.0, a, N=64).peak_gain for a in (0.1, 0.003))
    assert r1 > 0.01
    assert r2 == pytest.approx(r1, rel=1e-8)


def test_a_run_length_is_in_the_models_time():
    """K = 1e6, m = 1e-3 is the unit chain in a time 1/s shorter, s = sqrt(K/m): its runs'
    bounds follow (T_MIN = 1000 became 1000 (10 / omega_max), not 1000 time units = 6e7
    radians); a chain of frequencies 0.1 .. 10 keeps them as they were."""
    from numerics.lattice import run_length
    from numerics.models import time_scale

    stiff = _model("stiff")
    s = math.sqrt(1e9)
    tau = time_scale(stiff)
    assert tau == pytest.approx(10 / (2 * s), rel=1e-12)  # omega_max = 2 s at k = pi
    assert run_length(0.01 * s, time_scale=tau).t_end * s == pytest.approx(5000, rel=1e-9)
    assert time_scale(_model("stiff", K=1.0, m=1.0)) == 1.0
    assert run_length(0.01).t_end == 1000.0  # unchanged where the scale is 1


def test_a_soft_chain_decides_what_the_unit_chain_decides():
    """K = 1e-6 (omega up to 2e-3): the same chain as K = 1 in a time 1000x longer, so its
    run's verdict must be the unit chain's and its rate 1/1000 of it (3%: a run's rate fit,
    measured 0.03%). Before: T = 5000 (the no-growth default, the growing offsets read as
    harmonics), 0.08 e-foldings: 'no growth within T'."""
    from numerics.models import exact_gain, simulate_seeds

    k, a, N = 2 * math.pi * 21 / 64, 0.12, 64
    out = []
    for K in (1.0, 1e-6):
        model = _model("stiff", K=K, m=1.0)
        spec = exact_gain(model, k, a, N=N)
        out.append(simulate_seeds(model, k, a, spec, N=N, seeds=1))
    assert out[0].verdict.word == out[1].verdict.word == "MI"
    assert out[1].rate * 1e3 == pytest.approx(out[0].rate, rel=0.03)


def test_offsets_on_harmonics_below_the_noise_are_visible_to_a_run():
    """FPUT alpha 0.5 at k = 2 pi 21/64, a 0.12 on 64 sites: the fastest offset j = 3 puts
    its waves on the 8th and 10th harmonics (|c_h| 1e-12 and 1e-15, far below the run's
    noise 1e-9), which a run reads (it measures the exact 0.01597). Before: visible rate 0
    and the note 'a run may measure ... 0 /time, not 0.016'."""
    from numerics.models import exact_gain, visible_gain

    spec = exact_gain(load_model("fput").with_params(alpha=0.5), 2 * math.pi * 21 / 64, 0.12,
                      N=64)
    assert visible_gain(spec, 64) == pytest.approx(spec.peak_gain, rel=1e-12)


def test_an_opened_hertz_contact_has_a_real_energy_and_force():
    """Past the opening (strain r > d0) the contact's bond is the preload's linear term
    alone: (2/(3 sqrt d0)) (-(2/5) d0^(5/2) + d0^(3/2) r), its force the constant
    (2/3) d0 (by hand). Before: the printed base d0/2 + u/2 - u_next/2 + |d0 + u -
    u_next|/2 rounded to -1.4e-17 on 41 of 512 cells of the wave at k 2, a 0.5: the energy
    nan there, and 'at amplitude 0.5 the energy is not real'. 1e-12: the hand forms'
    round-off at values of order 1."""
    import numpy as np

    from numerics.models import energy_not_real, lattice_force

    d0 = 0.5
    model = _model("hertz-pre", d0=d0)
    rng = np.random.default_rng(97)
    u = rng.uniform(-1, 1, 4096)
    r = rng.uniform(d0 + 1e-9, 3, 4096)
    x = np.vstack([u, u + r])
    grad = np.empty_like(x)
    energy = model.code.cell_energy(x, model.p)
    model.code.cell_gradient_into(x, model.p, grad)
    c = 2 / (3 * math.sqrt(d0))
    assert np.allclose(energy, c * (-0.4 * d0**2.5 + d0**1.5 * r), rtol=1e-12, atol=1e-12)
    assert np.allclose(grad[1], c * d0**1.5, rtol=1e-12)
    assert energy_not_real(model, 2.0, 0.5) is None
    # the compiled force on a ring whose every other bond is open: +-(2/3) d0 per open bond
    ring = np.array([[0.0, 0.8, 0.8 - 0.1, 1.5, 1.5 - 0.1, 2.2, 2.2 - 0.1, 2.9]]) - 1.45
    f = lattice_force(model, ring)
    assert np.all(np.isfinite(f))


def test_a_precompressed_bond_is_no_kink():
    """A Hertz bond (2/5) (d0 - r)^(5/2) written without its linear term: each cell's
    force at rest is -d0^(3/2) (it cancels between neighbours). The bilinear-spring check
    read that constant as an even first-order term (c |h| with c = 1e3 at h = 1e-3) and
    said "second derivatives jump at rest: no NLS" (test_model_walk's Hertz chain, first
    CI of probe 97). Smooth at rest: no reason, an NLS."""
    from numerics.models import nls

    text = MODELS["hertz-closed"].replace(
        "bond = \"(2/(3*sqrt(d0)))*((2/5)*(d0 - (u_next - u))**(5/2) - (2/5)*d0**(5/2) "
        "+ d0**(3/2)*(u_next - u))\"", "bond = \"(2/5)*(d0 - (u_next - u))**(5/2)\"")
    assert "(2/5)*(d0 - (u_next - u))**(5/2)\"" in text
    model = load_model(parse_model(text, "hertz-bare.toml"))
    r = nls(model, 1.0)
    assert not r.undefined and math.isfinite(r.g2) and r.g2 != 0
