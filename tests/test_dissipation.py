"""Losses (issue 42): the [dissipation] table, damping rates, damped runs and theories."""

import numpy as np
import pytest

from energy import ModelError, builtin, load_model, parse_model

CHAIN = """name = "lossy-chain"
fields = ["u"]
[parameters]
beta = 1.0
gamma = 0.01
eta = 0.0
[energy]
kinetic = "u_t**2/2"
bond = "(u_next - u)**2/2 + beta*(u_next - u)**4/4"
[dissipation]
"""


def _chain(site="gamma*u_t**2/2", bond=None):
    text = CHAIN + (f'site = "{site}"\n' if site else "") + (f'bond = "{bond}"\n' if bond
                                                               else "")
    return parse_model(text, "chain.toml")


@pytest.fixture
def cache(tmp_path, monkeypatch):
    monkeypatch.setenv("FLEXMM_CACHE", str(tmp_path))
    return tmp_path


def test_lossless_hash_and_generated_code_unchanged():
    lat = builtin("flexmm")
    assert lat.dissipation is None and not lat.lossy
    assert "dissipation" not in lat.canonical()
    lossy = builtin("flexmm-lossy")
    assert lossy.lossy and lossy.content_hash != lat.content_hash
    m = load_model("flexmm")
    assert not hasattr(m.code, "damping_matrices")
    S, B = m.damping
    assert not S.any() and not B.any()


@pytest.mark.parametrize("site, bond, message", [
    ("gamma*u**2/2", None, "unknown symbol 'u'"),
    ("gamma*u_next_t**2/2", None, "u_next_t in dissipation.bond only"),
    ("gamma*u_t**2/2 + 1", None, "has no velocity"),
    ("__import__('os')", None, "unknown function"),
])
def test_dissipation_refused_in_one_line(site, bond, message):
    with pytest.raises(ModelError) as exc:
        _chain(site, bond)
    assert message in str(exc.value) and "\n" not in str(exc.value)
    assert "dissipation.site" in str(exc.value)


def test_dissipation_keys_checked():
    with pytest.raises(ModelError, match="unknown dissipation key"):
        parse_model(CHAIN + 'mass = "u_t**2"\n')
    with pytest.raises(ModelError, match="empty"):
        parse_model(CHAIN)


@pytest.mark.parametrize("site, message", [
    ("gamma*u_t**3", "not a quadratic form"),
    ("gamma*u_t**2 + u_t", "not a quadratic form"),
])
def test_not_quadratic_refused_by_the_derivation(site, message):
    from derivation._energy import energies

    with pytest.raises(ModelError, match=message):
        energies(_chain(site))


def test_not_positive_refused_at_the_values(cache):
    m = load_model(_chain("gamma*u_t**2/2", "eta*(u_next_t - u_t)**2/2"))
    S, B = m.damping
    assert S[0, 0] == 0.01 and B.shape == (2, 2)
    with pytest.raises(ModelError, match="not positive semi-definite"):
        m.with_params(gamma=-0.1)
    with pytest.raises(ModelError, match="dissipation.bond is not positive"):
        load_model(_chain("gamma*u_t**2/2", "eta*(u_next_t - u_t)**2/2"), eta=-1.0)
    with pytest.raises(ModelError, match="not positive"):  # indefinite, not just negative
        load_model(_chain(None, "eta*u_t*u_next_t"), eta=1.0)


def test_bond_damping_matrix(cache):
    m = load_model(_chain(None, "eta*(u_next_t - u_t)**2/2"), eta=0.5)
    S, B = m.damping
    assert np.allclose(B, 0.5 * np.array([[1, -1], [-1, 1]])) and not S.any()
