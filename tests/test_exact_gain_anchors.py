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
resolved growing mode); where a mode grows, its harmonic l and its sideband offset (nan for
a resonance); on the infinite chain the offsets themselves (the refined peak's included).
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


def _id(p):
    where = f"N{p['N']}" if p["N"] else "chain"
    par = ",".join(f"{n}={v:g}" for n, v in p["params"].items())
    return f"{p['model']}[{par}]-k{p['k']:.4g}-a{p['amplitude']:g}-b{p['branch']}-{where}"


@pytest.mark.parametrize("point", ANCHORS["points"], ids=[_id(p) for p in ANCHORS["points"]])
def test_exact_gain_equals_the_old_implementation(point):
    p = point
    model = load_model(p["model"])
    if p["params"]:
        model = model.with_params(**p["params"])
    spec = exact_gain(model, p["k"], p["amplitude"], p["branch"], N=p["N"])
    assert spec.wave.omega == pytest.approx(p["omega"], rel=RTOL)
    np.testing.assert_allclose(spec.offsets, p["offsets"], rtol=RTOL, atol=0)
    gain = np.array(p["gain"])
    np.testing.assert_allclose(spec.gain, gain, rtol=RTOL, atol=0)
    assert spec.peak_gain == pytest.approx(p["peak_gain"], rel=RTOL)
    grows = gain > 0
    np.testing.assert_array_equal(spec.harmonic[grows], np.array(p["harmonic"])[grows])
    side = np.array([math.nan if x is None else x for x in p["sideband_offset"]])
    np.testing.assert_allclose(spec.sideband_offset[grows], side[grows], rtol=RTOL, atol=1e-12)
    assert spec.mode == p["mode"]
