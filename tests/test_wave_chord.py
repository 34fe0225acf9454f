"""The collocation's chord method (``numerics/models/_collocation.py``, ``chord_newton``)
with its Jacobian taken again where it converges slowly (the wave's continuation, issue 41):
the same root as Newton's method, found where the chord on its first Jacobian alone gives
up, and in fewer residuals than that chord needs where it does converge."""

import numpy as np

from numerics.models._collocation import chord_newton


def _system(n=12, seed=3):
    """A smooth square system F(x) = A x + 0.3 x^3 - b (A well conditioned) whose root is
    known (b made from it), and its Jacobian; each residual call counted."""
    rng = np.random.default_rng(seed)
    A = np.eye(n) * 2 + 0.3 * rng.standard_normal((n, n))
    root = 0.8 * rng.standard_normal(n)
    b = A @ root + 0.3 * root**3
    calls = [0]

    def residual(x):
        calls[0] += 1
        return A @ x + 0.3 * x**3 - b

    def jacobian(x):
        return A + np.diag(0.9 * x**2)

    return residual, jacobian, root, calls


def test_the_refreshed_chord_finds_the_root_where_the_plain_chord_gives_up():
    residual, jacobian, root, _ = _system()
    x0 = root + 0.6  # far: the first Jacobian's steps contract too slowly
    assert chord_newton(residual, jacobian, x0) is None
    x = chord_newton(residual, jacobian, x0, refresh=6)
    assert x is not None
    # the root to round-off of its residual (1e-14 of an O(1) system)
    np.testing.assert_allclose(x, root, rtol=0, atol=1e-12)


def test_the_refreshed_chord_needs_fewer_residuals_where_the_chord_crawls():
    residual, jacobian, root, calls = _system()
    x0 = root + 0.05  # near enough for the plain chord, at a slow rate
    plain = chord_newton(residual, jacobian, x0, steps=60)
    n_plain, calls[0] = calls[0], 0
    fresh = chord_newton(residual, jacobian, x0, refresh=3)
    n_fresh = calls[0]
    assert plain is not None and fresh is not None
    np.testing.assert_allclose(fresh, plain, rtol=0, atol=1e-12)
    assert n_fresh < n_plain


def test_a_progress_list_holds_the_last_improving_iterate():
    residual, jacobian, root, _ = _system()
    progress = []
    x0 = root + 0.6
    assert chord_newton(residual, jacobian, x0, progress=progress) is None
    # where the chord gave up, its best iterate is nearer the root than the start
    assert progress and np.max(np.abs(residual(progress[0]))) < np.max(np.abs(residual(x0)))
