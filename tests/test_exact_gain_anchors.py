"""Regression anchors of the exact lattice theory (``exact_gain``, ring and infinite chain).

Where the numbers come from: tests/anchors/exact_gain.json was written by
tests/anchors/make_exact_gain_anchors.py run on the implementation at commit ac52a2e (a
dense ``numpy.linalg.eig`` of the Hill matrix per offset at P = H + 4 harmonics, the
harmonic balance by least squares with a finite-difference Jacobian), before issue 41
made the theory fast. They are anchors, not physics: they say the fast theory gives what
the slow one gave, within 1e-6 relative (issue 41's bar), at 20 points of six built-in
models (one and two fields; stable and unstable; the flexmm point whose fastest mode is a
resonance at some offsets; a commensurate k = pi / 2; a weak wave's narrow band on the
infinite chain). The physics is checked in tests/test_models_exact.py.

Compared: the wave's omega; the growth rate at every offset (0 where the old code saw no
resolved growing mode); where a mode grows, the wavenumber q + l k its harmonic l names and
its sideband offset (nan for a resonance); on the infinite chain the offsets themselves
(the refined peak's included).

What round-off decides is left out, as the old code itself measured it: the generator ran
the old theory again from the wave moved by 1e-15 relative (four draws) and marks
(``fragile``) the offsets where a draw differs; where the refined peak moved, the infinite
chain is compared on its fixed grid. At a commensurate k a mode's copies tie (at k = pi / 2
the fastest may sit at q or at q + pi; at k = pi the harmonics 1 and -1 name one
wavenumber; at q = pi the harmonics l and -l name kappa and -kappa), and a rate within
~1e-9 omega of a double eigenvalue is the eigensolver's round-off (``GAIN_FLOOR``): rates
are compared to 1e-6 relative or 1e-9 omega absolute.
"""

import json
import math
from pathlib import Path

import numpy as np
import pytest

from energy import load_model
from numerics.models import exact_gain

ANCHORS = json.loads((Path(__file__).parent / "anchors" / "exact_gain.json").read_text())
RTOL = 1e-6
#: absolute tolerance on rates, relative to omega (the eigensolver's own round-off there)
ATOL_OMEGA = 1e-9
CHAIN_GRID = np.concatenate([np.geomspace(1e-5, np.pi / 400, 40, endpoint=False),
                             np.linspace(np.pi / 400, np.pi, 400)])


def _id(p):
    where = f"N{p['N']}" if p["N"] else "chain"
    par = ",".join(f"{n}={v:g}" for n, v in p["params"].items())
    return f"{p['model']}[{par}]-k{p['k']:.4g}-a{p['amplitude']:g}-b{p['branch']}-{where}"


def _on_grid(q):
    return np.isclose(q[:, None], CHAIN_GRID[None, :], rtol=1e-12, atol=0).any(axis=1)


@pytest.mark.parametrize("point", ANCHORS["points"], ids=[_id(p) for p in ANCHORS["points"]])
def test_exact_gain_equals_the_old_implementation(point):
    p = point
    model = load_model(p["model"])
    if p["params"]:
        model = model.with_params(**p["params"])
    spec = exact_gain(model, p["k"], p["amplitude"], p["branch"], N=p["N"])
    assert spec.wave.omega == pytest.approx(p["omega"], rel=RTOL)
    q_old, q_new = np.array(p["offsets"]), spec.offsets
    # the infinite chain's bands between its samples (numerics.models._crossings, after
    # the anchors): offsets the old grid lacked, each growing, and a peak at least the old
    found = ~_on_grid(q_new) & ~np.isin(q_new, q_old)
    if not p["N"] and found.sum() > 1:  # more than a refined peak that moved
        assert np.all(spec.gain[found] > 0)
        assert spec.peak_gain >= p["peak_gain"] * (1 - RTOL)
    else:
        assert spec.peak_gain == pytest.approx(p["peak_gain"], rel=RTOL)
    keep_old = np.ones(q_old.size, bool)
    keep_old[p["fragile"]] = False
    if p["refined_offset_fragile"] or found.sum() > 1:  # the chain's fixed grid only
        grid_old, grid_new = _on_grid(q_old), _on_grid(q_new)
        assert grid_old.sum() == grid_new.sum() == CHAIN_GRID.size
        sel_old = np.flatnonzero(grid_old & keep_old)
        sel_new = np.flatnonzero(grid_new)[keep_old[grid_old]]
    else:
        assert q_new.size == q_old.size
        sel_old = sel_new = np.flatnonzero(keep_old)
    np.testing.assert_allclose(q_new[sel_new], q_old[sel_old], rtol=RTOL, atol=0)
    gain = np.array(p["gain"])[sel_old]
    np.testing.assert_allclose(spec.gain[sel_new], gain, rtol=RTOL,
                               atol=ATOL_OMEGA * p["omega"])
    grows = gain > 0
    # the harmonic through the wavenumber kappa = q + l k it names; at q = pi the chain's
    # reflection maps l onto -l at the same offset (kappa onto -kappa): a tie, compared
    # up to the sign of kappa
    k = spec.wave.k
    kappa_new = np.exp(1j * (q_new[sel_new] + spec.harmonic[sel_new] * k))[grows]
    kappa_old = np.exp(1j * (q_old[sel_old] + np.array(p["harmonic"])[sel_old] * k))[grows]
    at_pi = np.isclose(q_old[sel_old][grows], np.pi, rtol=0, atol=1e-12)
    kappa_new[at_pi] = kappa_new[at_pi].real
    kappa_old[at_pi] = kappa_old[at_pi].real
    np.testing.assert_allclose(kappa_new, kappa_old, rtol=0, atol=1e-9)
    side = np.array([math.nan if x is None else x for x in p["sideband_offset"]])[sel_old]
    np.testing.assert_allclose(spec.sideband_offset[sel_new][grows], side[grows], rtol=RTOL,
                               atol=1e-12)
    if not p["fragile"] and not p["refined_offset_fragile"]:
        assert spec.mode == p["mode"]


@pytest.mark.parametrize("name, params, k, a, branch", [
    ("fput", {"alpha": 0.3, "beta": 1.0}, 1.2, 0.12, None),
    ("klein-gordon", {"alpha": 0.3}, 2.0, 0.08, None),
    ("diatomic-fput", {"alpha": 0.2}, 2.0, 0.08, 1),
    ("flexmm-rotation", {}, 0.7, 0.1, None),
    # strongly nonlinear (H = 32): its only growing mode couples the harmonics 1 and 5,
    # dropped at P = 10 (found by random points against the dense spectrum)
    ("fput", {"alpha": 0.5118216247002567, "beta": 1.9108346533866836}, 0.704, 0.238, None),
])
def test_the_compiled_spectrum_is_the_dense_one(name, params, k, a, branch):
    """Points the anchors do not hold: the compiled spectrum (``hill_spectrum`` by default)
    against the dense eigenproblem at the old truncation H + 4 (``harmonics=``), and the
    truncations the verdict rests on. (144 random points of six models, amplitudes up to
    0.25, rings of 64, agreed to 1e-6 this way when the fast path was written, the
    strongly nonlinear one below excepted until P followed H.)"""
    from numerics.models import hill_spectrum, ring_offsets, travelling_wave

    model = load_model(name).with_params(**params)
    wave = travelling_wave(model, k, a, branch)
    q = ring_offsets(96)
    fast = hill_spectrum(wave, q)
    dense = hill_spectrum(wave, q, harmonics=wave.harmonics + 4)
    np.testing.assert_allclose(fast.gain, dense.gain, rtol=RTOL, atol=ATOL_OMEGA * wave.omega)
    grows = dense.gain > 0
    np.testing.assert_array_equal(fast.harmonic[grows], dense.harmonic[grows])
    assert dense.truncations == (wave.harmonics + 4,)
    assert fast.truncations[0] <= wave.harmonics + 4
    if fast.peak_gain > 0:  # the fastest mode checked at a second truncation
        assert len(fast.truncations) == 2 and fast.truncations[1] > fast.truncations[0]


@pytest.mark.slow
def test_the_compiled_spectrum_is_the_dense_one_at_random_points():
    """36 seeded random points of six models (amplitudes up to 0.25 for the one-field
    chains, 0.1 for flexmm), ring of 64: the compiled spectrum equals the dense one at the
    old truncation H + 4 (~15 s)."""
    from energy import ModelError
    from numerics.models import hill_spectrum, ring_offsets, travelling_wave

    rng = np.random.default_rng(41)
    models = [("fput", lambda: {"alpha": rng.uniform(0, 1), "beta": rng.uniform(0.2, 2)},
               0.25, [None]),
              ("klein-gordon", lambda: {"alpha": rng.uniform(-0.5, 0.5)}, 0.2, [None]),
              ("sine-gordon", dict, 0.4, [None]),
              ("diatomic-fput", lambda: {"alpha": rng.uniform(0, 0.5)}, 0.15, [0, 1]),
              ("flexmm-rotation", dict, 0.15, [None]),
              ("flexmm", lambda: {"K_theta": rng.uniform(0.01, 0.03)}, 0.1, [None])]
    q = ring_offsets(64)
    for i in range(36):
        name, params, top, branches = models[i % len(models)]
        model = load_model(name).with_params(**params())
        k, a = rng.uniform(0.3, 3.1), rng.uniform(0.02, top)
        branch = branches[rng.integers(len(branches))]
        try:
            wave = travelling_wave(model, k, a, branch)
        except ModelError:
            continue
        dense = hill_spectrum(wave, q, harmonics=wave.harmonics + 4)
        np.testing.assert_allclose(hill_spectrum(wave, q).gain, dense.gain, rtol=RTOL,
                                   atol=ATOL_OMEGA * wave.omega,
                                   err_msg=f"{name} {model.params} k={k} a={a} b={branch}")
