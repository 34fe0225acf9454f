"""The fused flexMM kernel as the registered fast force of the flexmm models: equal to the
force generated from their energy file, chosen by the energy's content (never by the name
alone), and a run on either force the same run to round-off."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

import energy
from energy import builtin, load_model, parse_model
from numerics.lattice import (
    ForceStepper,
    LatticeState,
    Material,
    Stepper,
    fast_force,
    fast_forces,
    get_method,
)
from numerics.models import energy_hash, lattice_force, run_force, simulate_model

#: parameter sets away from the defaults (alpha, K_s, K_theta): the mapping of the model's
#: values onto the kernel's (alpha^2, K_s, K_theta) is what is checked
PARAMS = [dict(), dict(alpha=1.3, K_s=0.05, K_theta=0.002),
          dict(alpha=3.7, K_s=0.2, K_theta=0.04), dict(alpha=0.8, K_s=0.0, K_theta=0.1)]
FLEXMM = ["flexmm", "flexmm-rotation", "flexmm-lossy"]


@pytest.mark.parametrize("name", FLEXMM)
@pytest.mark.parametrize("params", PARAMS)
def test_the_fused_force_equals_the_generated_force(name, params, rng):
    model = load_model(name, **params)
    force, p, rows, label = run_force(model)
    assert label.startswith("fast:")
    N = 48
    # small waves, the paper's amplitudes, large rotations, and |theta| beyond TRIG_LIMIT
    # (1e4: both forces hand over to libm's sin and cos there)
    for scale in (0.05, 0.3, 1.5, 3e4):
        u = scale * rng.standard_normal((model.n_fields, N))
        if model.n_fields == 2:
            u[1] *= 0.3  # sliding smaller than rotation, as on the chain
        fast = np.empty_like(u)
        force(u, p, fast, np.empty((rows, N)))
        generated = lattice_force(model, u)
        # relative to each field's largest acceleration: both sum the same O(1) terms in
        # another order (the generated loop forms 1 - (cos a + cos b)/2 by subtraction,
        # the kernel from versines), a few ulp of the largest term; 1e-12 leaves 1e3 room
        size = np.max(np.abs(generated), axis=1)
        err = np.max(np.abs(fast - generated), axis=1) / size
        assert np.all(err <= 1e-12), (name, params, scale, err)


def test_the_fast_force_is_chosen_by_the_energy_not_the_name():
    flexmm = builtin("flexmm")
    text = (Path(energy.__file__).with_name("models") / "flexmm.toml").read_text()
    assert fast_force(energy_hash(flexmm)).name == "flexmm"
    # another name, the same energy: the kernel is that energy's force
    renamed = parse_model(text.replace('name = "flexmm"', 'name = "my-chain"'), "my.toml")
    assert fast_force(energy_hash(renamed)).name == "flexmm"
    # the name flexmm with another energy (a stiffer hinge): its own generated force
    other = parse_model(text.replace('site = "K_theta*theta**2"',
                                     'site = "K_theta*theta**2 + theta**4"'), "flexmm.toml")
    assert other.name == "flexmm" and fast_force(energy_hash(other)) is None
    # fields in another order are another force layout
    swapped = parse_model(text.replace('fields = ["theta", "U"]', 'fields = ["U", "theta"]'),
                          "flexmm.toml")
    assert fast_force(energy_hash(swapped)) is None
    # the damping and its parameters are not the conservative force's
    assert energy_hash(builtin("flexmm-lossy")) == energy_hash(flexmm)
    assert set(fast_forces()) >= {"flexmm", "flexmm-rotation"}
    for name in ("fput", "flexmm-stiff-hinge", "sine-gordon"):
        assert run_force(load_model(name))[3] == "generated"


@pytest.mark.parametrize("name,method", [("flexmm", "srkn11b"), ("flexmm-rotation", "rk4"),
                                         ("flexmm-lossy", "srkn6b")])
def test_a_run_on_either_force_is_the_same_run(name, method):
    """A few hundred steps of the exact wave (k = 1, amplitude 0.1) with seeded noise, on
    the fused and on the generated force: the same states, energies and growth."""
    model = load_model(name, K_theta=0.012)
    kw = dict(N=64, t_end=150.0, records=5, seed=3, noise=1e-6, method=method)
    fast = simulate_model(model, 1.0, 0.1, **kw)
    ref = simulate_model(model, 1.0, 0.1, force="generated", **kw)
    assert fast.force.startswith("fast:") and ref.force == "generated"
    steps = round(150.0 / fast.dt)
    assert steps >= 300
    # the two forces differ by ~1e-16 of the force per evaluation; over n steps that
    # round-off adds up to at most ~n eps |u| (~1e-13 of the amplitude here), amplified by
    # at most the growth the run shows: 1e-10 of the amplitude bounds it 100-fold
    diff = max(np.max(np.abs(a - b)) for a, b in zip(fast.state, ref.state))
    growth = max(fast.growth().factor, 1.0)
    assert diff <= 1e-10 * 0.1 * growth, (diff, growth)
    assert fast.growth().factor == pytest.approx(ref.growth().factor, rel=1e-6)
    np.testing.assert_allclose(fast.energy, ref.energy, rtol=1e-12)


def test_force_is_checked():
    with pytest.raises(ValueError, match="force must be one of"):
        simulate_model(load_model("flexmm"), 1.0, 0.1, N=32, t_end=1.0, force="fused")


@pytest.mark.parametrize("name,case", [("flexmm", "coupled"), ("flexmm-rotation", "rotation")])
@pytest.mark.parametrize("method", ["verlet", "srkn11b"])
def test_the_model_path_steps_the_paper_engines_states_bit_for_bit(name, case, method):
    """The paper engine (``Stepper``: fused kick-drift passes) and the model path
    (``ForceStepper`` around the registered fused force) are one computation for an SRKN
    method: the same kicks and drifts, the same site formula. From one state, 2000 steps
    (long enough for any operation rounded differently to show) give the same states to
    the last bit. (RK4 sums its stages in another order in the two engines: not bit for
    bit, 1e-12 apart after 1000 steps.)"""
    params = dict(alpha=2.1, K_s=0.03, K_theta=0.012)
    model = load_model(name, **params)
    force, p, rows, label = run_force(model)
    assert label.startswith("fast:")
    rng = np.random.default_rng(4)
    N, coupled = 64, case == "coupled"
    th, w = 0.3 * rng.standard_normal(N), 0.05 * rng.standard_normal(N)
    U, V = (0.05 * rng.standard_normal(N), 0.01 * rng.standard_normal(N)) if coupled \
        else (None, None)
    paper = Stepper(LatticeState(U, V, th, w), Material(**params), case, get_method(method),
                    0.05)
    u = np.stack([th, U]) if coupled else th[None].copy()
    v = np.stack([w, V]) if coupled else w[None].copy()
    steps = ForceStepper(force, p, rows, u, v, get_method(method), 0.05)
    assert paper.advance(2000) == steps.advance(2000) == 2000
    end = paper.state()
    assert np.array_equal(steps.u[0], end.theta) and np.array_equal(steps.v[0], end.theta_dot)
    if coupled:
        assert np.array_equal(steps.u[1], end.U) and np.array_equal(steps.v[1], end.U_dot)
    assert np.max(np.abs(end.theta - th)) > 1e-2  # it moved: the comparison means something
