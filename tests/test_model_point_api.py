"""A model's point without the command line: ``numerics.maps.measure_point`` of a
``ModelPointSpec`` (the one entry point the paper chain's Material also takes), what it
refuses, and that `flexmm point --model --json` prints its numbers."""

from __future__ import annotations

import json
import math

import pytest

from energy import load_model
from numerics.maps import ModelPoint, ModelPointSpec, PointInputError, measure_point


def test_a_model_point_measures_the_models_own_theories():
    from numerics.models import exact_gain_checked, nls, snap_ring

    model = load_model("fput").with_params(alpha=0.0, beta=1.0)
    point = measure_point(ModelPointSpec(model, 2.0, 0.1, N=64))
    assert isinstance(point, ModelPoint)
    k, _ = snap_ring(2.0, 64)
    assert point.spec.k_ring == k
    rows = point.as_dict()
    assert rows["k"] == k and rows["k_requested"] == 2.0 and rows["N"] == 64
    # the rows are the model layer's theories, computed here independently
    hill = exact_gain_checked(model, k, 0.1, None, N=64)
    assert rows["exact lattice"]["peak_gain"] == hill.peak_gain
    assert rows["semi-discrete NLS"]["verdict"] == nls(model, k, None).verdict
    assert "simulated" not in rows and point.estimate is None
    # as_dict is a new dict each time: a caller's units do not leak into the point
    rows["units"] = {}
    assert "units" not in point.as_dict()


def test_the_command_prints_what_measure_point_returns(capsys):
    from cli import main

    model = load_model("fput").with_params(alpha=0.0, beta=1.0)
    rows = measure_point(ModelPointSpec(model, 2.0, 0.1, N=64)).as_dict()
    assert main(["point", "--model", "fput", "--param", "alpha=0", "--param", "beta=1",
                 "--k", "2", "--amplitude", "0.1", "--N", "64", "--json"]) == 0
    printed = json.loads(capsys.readouterr().out)
    for name in ("exact lattice", "four-wave", "semi-discrete NLS"):
        for key, value in rows[name].items():
            if isinstance(value, float) and not math.isfinite(value):
                value = None  # strict JSON
            assert printed[name][key] == value, (name, key)


@pytest.mark.parametrize("kwargs, field", [
    ({"N": 4}, "N"),                                  # below the smallest ring
    ({"amplitude": 1e-300, "k": 0.5}, "amplitude"),   # its nonlinearity is rounding
    ({"start": "paper"}, "start"),                    # the paper chain's energy only
])
def test_a_refused_point_names_its_field(kwargs, field):
    model = load_model("fput")
    spec = {"k": 1.0, "amplitude": 0.1, "N": 32, **kwargs}
    with pytest.raises(PointInputError) as err:
        ModelPointSpec(model, spec.pop("k"), spec.pop("amplitude"), **spec)
    assert err.value.field == field
    assert str(err.value).startswith(field)  # one line, named as the API spells it
    assert "\n" not in str(err.value)


def test_a_models_name_is_not_a_model():
    with pytest.raises(TypeError, match="model must be a Model"):
        ModelPointSpec("fput", 1.0, 0.1, N=32)
