"""The exact lattice theory says when its rate is not converged in the Hill truncation
(CONVENTIONS.md: a mode counts when it persists at the same q across truncations).

A Hertz contact with precompression that opens (probe 97's ``hertz-pre`` at a 0.5, past
its opening) has a force with a kink: the Hessian along the wave jumps, its harmonics
fall as 1/l, and the Hill spectrum converges slowly. Before, the compiled path's peak
failed its check at P + 4 and the dense fallback at H + 4 was returned unchecked, one
truncation named and nothing said: `point` printed its rate as any other. Now that peak
is checked at H + 4 + 4 as the compiled path's is (``numerics.models.not_converged``):
where the rate moves, the point's exact row and notes say it is not converged.
"""

from __future__ import annotations

import numpy as np

from bench.probe_models97 import MODELS
from energy import load_model, parse_model
from numerics.models import exact_gain, hill_spectrum, not_converged, travelling_wave

#: 24 sites, k = 2 pi 8 / 24 (~1 s: the dense pencil at 36 harmonics, 12 offsets)
N, M, A = 24, 8, 0.5


def _hertz():
    return load_model(parse_model(MODELS["hertz-pre"], "hertz-pre.toml"))


def test_a_rate_the_truncation_moves_is_named_not_converged():
    model = _hertz()
    spec = exact_gain(model, 2 * np.pi * M / N, A, N=N)
    assert spec.peak_gain > 0 and len(spec.truncations) == 1
    P = spec.truncations[0]
    # independently of the fast path: the dense Hill spectrum at the fastest offset moves
    # by far more than the 1e-6 persistence bar between P and P + 4 harmonics (measured
    # 0.56% here; 6.8e-4 vs 4.8e-4 at k = 2 pi 20 / 64): 1e-3, 1000x the bar
    wave = travelling_wave(model, 2 * np.pi * M / N, A)
    q = spec.offsets[np.argmax(spec.gain)]
    r1, r2 = (hill_spectrum(wave, [q], harmonics=h).gain[0] for h in (P, P + 4))
    assert abs(r2 - r1) > 1e-3 * r1
    why = not_converged(spec)
    assert why and "not converged" in why and f"at {P} harmonics" in why


def test_the_point_says_so_on_the_exact_row():
    from numerics.maps import ModelPointSpec, measure_point

    spec = ModelPointSpec(_hertz(), 2 * np.pi * M / N, A, N=N)
    row = measure_point(spec).rows
    assert row["exact lattice"]["truncations"] == [36]
    assert "not converged" in row["exact lattice"]["not_converged"]
    assert any("not converged" in n for n in row["notes"])


def test_a_smooth_models_rate_persists_and_says_nothing():
    """FPUT (alpha 0.5, beta 1) at the bench point: the compiled path's peak persists at
    P and P + 4 (two truncations), no sentence."""
    model = load_model("fput").with_params(alpha=0.5, beta=1.0)
    spec = exact_gain(model, 2 * np.pi * 66 / 256, 0.1, N=256)
    assert len(spec.truncations) == 2 and not_converged(spec) is None
