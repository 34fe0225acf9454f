"""Probe 100 (every claim of the docs): what it found in the code."""

from __future__ import annotations

import pytest

from numerics.maps import parse_spec


@pytest.mark.parametrize("spec,count", [("0.1:3:1000000000", 1000000000),
                                        ("0.1:3:100001", 100001)])
def test_a_too_long_axis_is_refused_with_the_count_it_asks_for(spec, count):
    # the refusal named linspace's capped count (100001) for any longer range: a SPEC of
    # 1e9 values read "asks for 100001 values" (bench/stress.md's 1e9 row)
    with pytest.raises(ValueError) as err:
        parse_spec(spec, "--k")
    assert f"asks for {count} values; at most 100000 per axis" in str(err.value)


def test_a_long_list_is_refused_with_its_own_count():
    spec = ",".join(str(i) for i in range(100_001))
    with pytest.raises(ValueError, match="asks for 100001 values; at most 100000"):
        parse_spec(spec, "--k")
