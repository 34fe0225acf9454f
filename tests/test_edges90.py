"""Edges (issue 90): a theory-only model map's simulated verdict says no run was made; tiny
k and amplitudes are refused with their bound; an exact spectrum of another ring is
refused; a simulated model map's cells too slow for T say so; summary.json echoes inputs."""

import numpy as np
import pytest

from numerics.maps import ModelMapParameters


def _fput_map(**options):
    return ModelMapParameters.from_model("fput", ("beta", [0.8, 1.6]), ("k", [2.6, 2.8]),
                                         0.1, params={"alpha": 1.0}, **options)


def test_a_theory_only_model_store_says_its_simulated_verdict_holds_no_run():
    ds = _fput_map(theory_only=True).new_dataset()
    attrs = ds["verdict_simulated"].attrs
    said = " ".join(str(v) for v in attrs.values())
    assert "a run grew" not in attrs["long_name"]
    assert "not simulated" in attrs["long_name"] and "no run" in attrs["long_name"]
    assert attrs["undetermined"] == "not simulated: no run made"
    # every cell holds -1, the code the words give for "not simulated"
    assert (ds["verdict_simulated"].values == -1).all() and "-1" in said


def test_a_simulated_model_store_names_not_simulated_beside_a_run_that_grew_too_little():
    attrs = _fput_map(N=64, t_end=100.0).new_dataset()["verdict_simulated"].attrs
    assert "not simulated yet where done is False" in attrs["undetermined"]
    assert "a run grew, but less than the threshold" in attrs["verdict_words"]
    assert np.int8(-1) in attrs["flag_values"]
