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
def toda():
    """The text of a Toda chain's model file (the energy exp(-b r) that stops being real
    at large strain: a = 2000 carries no wave), with parameters a and b."""
    return """
name = "toda"
fields = ["u"]
[parameters]
a = 1.0
b = 1.0
[energy]
kinetic = "u_t**2/2"
bond = "a/b*(exp(-b*(u_next - u)) - 1 + b*(u_next - u))"
"""


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


def _flexmm_points(seed, count, window=False):
    """``count`` seeded points (name, params, k, a) of flexmm and flexmm-stiff-hinge in turn,
    parameters drawn in their ranges (hinge K_theta 0.01-0.03, shear K_s 0.01-0.03, alpha
    1.5-3.5, the stiffening K_3 0-1), k over the rotation branch (0.3-pi), amplitude
    0.02-0.1. ``window``: (name, params, k, a, start), ``start`` an index in [1, 360)
    drawn after the parameters (a window of the infinite chain's offsets)."""
    rng = np.random.default_rng(seed)
    points = []
    for i in range(count):
        name = ("flexmm", "flexmm-stiff-hinge")[i % 2]
        params = {"K_theta": rng.uniform(0.01, 0.03), "K_s": rng.uniform(0.01, 0.03),
                  "alpha": rng.uniform(1.5, 3.5)}
        if name == "flexmm-stiff-hinge":
            params["K_3"] = rng.uniform(0.0, 1.0)
        start = int(rng.integers(1, 360)) if window else None
        point = (name, params, rng.uniform(0.3, np.pi), rng.uniform(0.02, 0.1))
        points.append((*point, start) if window else point)
    return points


@pytest.fixture(scope="session")
def flexmm_points():
    """``_flexmm_points(seed, count, window=False)``: seeded random points of the strongly
    coupled models (tests/test_exact_strong.py, tests/test_exact_between.py)."""
    return _flexmm_points


def _interrupt_map(out):
    """Marks the first cell of the map stored under ``out`` (its ``map.zarr``) not computed,
    as an interrupted map leaves it."""
    import zarr

    group = zarr.open_group(str(out / "map.zarr"), mode="r+", use_consolidated=False)
    done = group["done_predicted"][...]
    done[0, 0] = False
    group["done_predicted"][...] = done


@pytest.fixture(scope="session")
def interrupt_map():
    """``_interrupt_map(out)``: a finished map's store made one an interrupted run leaves
    (tests/test_model_walk.py's resumed maps)."""
    return _interrupt_map


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
