"""One rule for the smallest amplitude float64 resolves (common.resolution): the paper
flags' check (cli._resolved) and a model's (ModelNLS.smallest_amplitude) give the same
number for the paper's chain written as a model, and each is the amplitude whose NLS
frequency shift |g2| a^2 / 4 equals eps omega."""

from __future__ import annotations

import math
import sys

import pytest

from common import paper
from common.resolution import smallest_resolved_amplitude


def test_the_shift_at_the_smallest_amplitude_is_omegas_rounding():
    for omega, g2 in ((1.0, 1.0), (0.3, -2e-3), (4e4, 7.5e9), (1e-6, 1e-12)):
        a = smallest_resolved_amplitude(omega, g2)
        # |g2| a^2 / 4 = eps omega to rounding (a few ulps of the square root's inputs)
        assert abs(g2) * a * a / 4 == pytest.approx(sys.float_info.epsilon * omega,
                                                    rel=1e-14)
    for omega, g2 in ((1.0, 0.0), (1.0, math.nan), (math.inf, 1.0), (-1.0, 1.0)):
        assert smallest_resolved_amplitude(omega, g2) == 0.0


def test_the_paper_flags_and_the_model_refuse_below_one_number():
    """The paper's blue point: the paper flags' check (the larger |g2| of the two cases:
    case II's, -36.25) and flexmm's model NLS (the same chain: its g2 is case II's to
    2e-15) refuse below one number, 1% either side of it."""
    from cli._resolved import check_paper_amplitude
    from energy import load_model
    from numerics import Material
    from numerics.models import nls

    blue = paper.POINTS["blue"]
    mat = Material(alpha=paper.ALPHA, K_s=paper.K_S, K_theta=blue["K_theta"])
    model = load_model("flexmm").with_params(alpha=paper.ALPHA, K_s=paper.K_S,
                                             K_theta=blue["K_theta"])
    least = nls(model, blue["k"]).smallest_amplitude()
    assert least > 0
    check_paper_amplitude(mat, blue["k"], 1.01 * least)
    with pytest.raises(ValueError, match="--amplitude"):
        check_paper_amplitude(mat, blue["k"], 0.99 * least)
