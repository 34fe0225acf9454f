"""The compiled Hill kernel's early give-up (``numerics/models/_chaining.py``): where the
discs of the central harmonics alone already chain into a cluster the kernel cannot solve,
it gives the offset up without its full pass. That is a claim of exactness (a subset of the
same discs, computed to the same bits), so it is held here to the full pass itself: the same
offsets given up and the same modes everywhere else, at random points of models that chain
(flexmm, flexmm-stiff-hinge) and of models that do not."""

import numpy as np
import pytest

from energy import ModelError, load_model
from numerics.models import ring_offsets, travelling_wave
from numerics.models._exact import MAX_CLUSTER, MAX_MODES, _Sidebands
from numerics.models._sidebands import sideband_modes


def _points(seed, count):
    """Seeded points: the strongly coupled flexmm models (parameters in their ranges, as
    tests/test_exact_strong.py draws them) and three models whose clusters stay small."""
    rng = np.random.default_rng(seed)
    points = []
    for i in range(count):
        name = ("flexmm", "flexmm-stiff-hinge", "fput", "diatomic-fput", "sine-gordon")[i % 5]
        params = {}
        if name.startswith("flexmm"):
            params = {"K_theta": rng.uniform(0.01, 0.03), "K_s": rng.uniform(0.01, 0.03),
                      "alpha": rng.uniform(1.5, 3.5)}
        points.append((name, params, rng.uniform(0.3, np.pi), rng.uniform(0.02, 0.12)))
    return points


#: bench/models.py's flexmm points (EXACT_POINTS), where every ring offset chains: the
#: early give-up is exercised there, not only allowed (at some random flexmm draws the
#: clusters stay small: k 0.75, a 0.048)
BENCH = [("flexmm", {"K_theta": 0.016}, 2 * np.pi * 36 / 256, 0.1),
         ("flexmm-stiff-hinge", {}, 1.0, 0.1)]


@pytest.mark.parametrize("name, params, k, a", BENCH + _points(41, 10))
def test_the_early_give_up_is_the_full_pass(name, params, k, a):
    model = load_model(name).with_params(**params) if params else load_model(name)
    try:
        wave = travelling_wave(model, k, a)
    except ModelError:  # no wave there (said in one line): nothing to compare
        pytest.skip("no travelling wave at this draw")
    engine = _Sidebands(wave)
    # a ring's offsets and random ones (the infinite chain's grid is any q)
    q = np.concatenate([ring_offsets(64), np.random.default_rng(7).uniform(0, np.pi, 24)])
    args = (engine.Hh, engine.masses, wave.k, wave.omega, engine.P, q, engine.floor,
            MAX_MODES, MAX_CLUSTER)
    lam_fast, vec_fast, count_fast = sideband_modes(*args, True)
    lam_full, vec_full, count_full = sideband_modes(*args, False)
    np.testing.assert_array_equal(count_fast, count_full)
    # where the offset was solved the pass is the same code: the same bits
    np.testing.assert_array_equal(lam_fast, lam_full)
    np.testing.assert_array_equal(vec_fast, vec_full)
    if (name, params, k, a) in BENCH:
        assert np.all(count_full < 0)
