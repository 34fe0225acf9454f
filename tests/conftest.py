"""Fixtures shared by the test files: the paper's points and materials, random states, and
one quick run of every scene (module-independent: each test file passes alone)."""

from __future__ import annotations

import numpy as np
import pytest

from numerics import Material


def pytest_addoption(parser):
    parser.addoption("--update-golden", action="store_true",
                     help="rewrite tests/golden/*.json from this run instead of comparing")


@pytest.fixture(scope="session")
def blue():
    """Material of the paper's blue point (delta = +0.003)."""
    return Material.paper("blue")


@pytest.fixture(scope="session")
def green():
    """Material of the paper's green point (delta = -0.003)."""
    return Material.paper("green")


@pytest.fixture(scope="session")
def fput_lossy():
    """The text of a lossy FPUT model file (issue 42): the FPUT chain (quartic bonds, beta)
    with viscous damping of each site, R = gamma u_t^2 / 2 (the carrier decays at
    gamma / 2 on every k)."""
    return """name = "fput-lossy"
fields = ["u"]
[parameters]
beta = 1.0
gamma = 0.01
[energy]
kinetic = "u_t**2/2"
bond = "(u_next - u)**2/2 + beta*(u_next - u)**4/4"
[dissipation]
site = "gamma*u_t**2/2"
"""


@pytest.fixture
def rng():
    """A fresh, seeded generator per test (tests never share random state)."""
    return np.random.default_rng(20261122)


@pytest.fixture(scope="session")
def quick_scenes(tmp_path_factory):
    """Every registered scene run once in quick mode: (out folder, {name: summary})."""
    import scenes

    out = tmp_path_factory.mktemp("quick_scenes")
    return out, {name: scenes.run_scene(name, out, quick=True) for name in scenes.REGISTRY}


@pytest.fixture
def sigint_raises():
    """SIGINT raises KeyboardInterrupt during the test, whatever the process inherited: a
    non-interactive shell starts background jobs (``make test &``, nohup, batch systems)
    with SIGINT ignored, and Python then keeps it ignored. Tests that send themselves
    SIGINT install the handler they rely on."""
    import signal

    old = signal.signal(signal.SIGINT, signal.default_int_handler)
    try:
        yield
    finally:
        signal.signal(signal.SIGINT, old)
