"""The vectorised force kernel and fused loops against libm and the reference loops; the
accuracy controls (AccuracyWarning, tol=)."""

import warnings

import numpy as np
import pytest

from common import paper
from numerics import AccuracyWarning, Material, choose_step, initial_condition, integrate, simulate
from numerics.lattice import _kernels as kernels

ULP = np.spacing


def _poly(x):
    s, c, v = (np.empty_like(x) for _ in range(3))
    kernels.sincosvers(x, s, c, v)
    return s, c, v


def test_polynomial_sin_cos_within_2_ulp_of_libm():
    # dense grid and random points over |theta| <= 100 (the range), tiny angles,
    # and random points up to TRIG_LIMIT, where the loops still use the polynomial
    rng = np.random.default_rng(1)
    x = np.concatenate([np.linspace(-100, 100, 400_001), rng.uniform(-100, 100, 200_000),
                        np.geomspace(1e-300, 1, 2000), -np.geomspace(1e-300, 1, 2000),
                        rng.uniform(-kernels.TRIG_LIMIT, kernels.TRIG_LIMIT, 100_000),
                        [0.0, -0.0, np.pi / 4, np.pi / 2, np.pi, 100.0, -100.0]])
    s, c, _ = _poly(x)
    assert np.max(np.abs(s - np.sin(x)) / ULP(np.abs(np.sin(x)))) <= 2
    assert np.max(np.abs(c - np.cos(x)) / ULP(np.abs(np.cos(x)))) <= 2


@pytest.mark.skipif(np.finfo(np.longdouble).eps > 1e-18, reason="needs 80-bit long double")
def test_polynomial_versine_without_cancellation():
    # 1 - cos against 2 sin^2(x/2) in extended precision: relative accuracy everywhere,
    # also where 1 - cos(x) computed naively loses every digit (x ~ 1e-8)
    rng = np.random.default_rng(2)
    x = np.concatenate([rng.uniform(-100, 100, 200_000), np.geomspace(1e-150, 1, 3000)])
    _, _, v = _poly(x)
    exact = (2 * np.sin(x.astype(np.longdouble) / 2) ** 2).astype(float)
    assert np.max(np.abs(v - exact) / ULP(exact)) <= 4  # measured 3.3 ulp


@pytest.mark.parametrize("coupled", [True, False], ids=["coupled", "rotation"])
@pytest.mark.parametrize("scale", [1e-4, 0.05, 1.0, 30.0])
def test_kernel_equals_the_libm_kernel(coupled, scale, rng, blue):
    # sin/cos differ by <= 1 ulp, the versine by a few: accelerations agree to 1e-15 of
    # the force scale (alpha^2 times the largest term)
    N = 301
    th, U = rng.normal(0, scale, N), rng.normal(0, scale / 10, N)
    U = U if coupled else np.zeros(0)
    out = []
    for fn in (kernels.accel, kernels.accel_libm):
        s, c, v, ath = (np.empty(N) for _ in range(4))
        aU = np.empty(N if coupled else 0)
        fn(th, U, coupled, blue.alpha**2, blue.K_s, blue.K_theta, s, c, v, ath, aU)
        out.append((ath, aU))
    force = blue.alpha**2 * (4 + 6 * blue.K_theta * np.max(np.abs(th))) * min(1.0, 4 * scale)
    assert np.max(np.abs(out[0][0] - out[1][0])) <= 1e-15 * force
    if coupled:
        assert np.max(np.abs(out[0][1] - out[1][1])) <= 1e-15 * (1 + np.max(np.abs(U)))


def _loops(state, mat, coupled, method, nsteps, dt, expect_done=None):
    """(fused, libm) final (theta, U, accelerations) after nsteps from the same state;
    each loop must report ``expect_done`` steps done (default all)."""
    from numerics.lattice import get_method

    m = get_method(method)
    res = []
    for fast in (True, False):
        th, w = state.theta.copy(), state.theta_dot.copy()
        U = state.U.copy() if coupled else np.zeros(0)
        V = state.U_dot.copy() if coupled else np.zeros(0)
        N, nU = th.size, th.size if coupled else 0
        p = (mat.alpha**2, mat.K_s, mat.K_theta)
        s, c, v, ath, aU = np.empty(N), np.empty(N), np.empty(N), np.empty(N), np.empty(nU)
        if m.kind == "rk4":
            done = (kernels.rk4_steps(th, w, U, V, coupled, *p, dt, nsteps, np.empty((11, N)),
                                      np.empty((5, nU))) if fast else
                    kernels.rk4_steps_libm(th, w, U, V, coupled, *p, dt, nsteps, s, c, v,
                                           np.empty((10, N))))
        else:
            kernels.accel_libm(th, U, coupled, *p, s, c, v, ath, aU)
            a, b = np.array(m.a), np.array(m.b)
            done = (kernels.srkn_steps(th, w, U, V, ath, aU, coupled, *p, a, b, dt, nsteps,
                                       np.empty((8, N)), np.empty((2, nU))) if fast else
                    kernels.srkn_steps_libm(th, w, U, V, ath, aU, coupled, *p, a, b, dt, nsteps,
                                            s, c, v))
        assert done == (nsteps if expect_done is None else expect_done[not fast])
        res.append((th, U, ath))
    return res


@pytest.mark.parametrize("method", ["rk4", "verlet", "srkn11b"])
@pytest.mark.parametrize("case", ["coupled", "rotation"])
def test_fused_loops_equal_the_reference_loops(method, case, blue):
    # 200 steps of the paper's noisy wave (amplitude 0.3 rad: strongly nonlinear):
    # the loops differ only by the trig round-off, which stays at 1e-13 of the state
    coupled = case == "coupled"
    s0 = initial_condition(blue, case, 64, 2 * np.pi * 8 / 64, eps=0.15, noise=0.1)
    (th_f, U_f, a_f), (th_l, U_l, a_l) = _loops(s0, blue, coupled, method, 200, 0.1)
    scale = np.max(np.abs(th_l))
    assert np.max(np.abs(th_f - th_l)) <= 1e-13 * scale
    if coupled:
        assert np.max(np.abs(U_f - U_l)) <= 1e-13 * scale
    if method != "rk4":  # first same as last: accelerations of the final state on exit
        assert np.max(np.abs(a_f - a_l)) <= 1e-12 * np.max(np.abs(a_l))


def test_beyond_the_polynomial_range_the_libm_path_takes_over(blue):
    N = 16
    th = np.full(N, 2 * kernels.TRIG_LIMIT) + np.linspace(0, 1, N)
    s0 = type(initial_condition(blue, "rotation", N, 2 * np.pi / N))(None, None, th,
                                                                      np.zeros(N))
    # the fused loop refuses the state (0 steps done); integrate hands it to libm
    _, libm = _loops(s0, blue, False, "rk4", 20, 0.01, expect_done=(0, 20))
    end = integrate(s0, blue, "rotation", 0.2, 0.01)
    assert np.array_equal(end.theta, libm[0])


@pytest.mark.parametrize("coupled", [True, False], ids=["coupled", "rotation"])
def test_the_site_loops_are_vectorised(coupled):
    # the point of the polynomial: LLVM turns the site loops into SIMD code
    found = kernels.vectorised_loops(coupled)
    assert all(found.values()), found


def test_accuracy_warning_at_a_too_large_step_and_not_at_the_papers(blue):
    # the example: blue point, case II, dt = 0.5 "completed" with a 37% energy
    # error; dt = 0.05 (the paper's) conserves the energy to 1e-5
    kw = dict(material=blue, case="coupled", N=200, k=paper.k("blue"), t_end=2000.0,
              store="energy")
    with pytest.warns(AccuracyWarning, match=r"energy error 0\.\d+ exceeds .* dt <= "):
        run = simulate(dt=0.5, **kw)
    assert run.energy_error > 0.1
    msg_dt = None
    with warnings.catch_warnings(record=True) as w:
        warnings.simplefilter("always")
        simulate(dt=0.5, **kw)
        msg_dt = float(str(w[0].message).split("dt <= ")[1].split(",")[0])
    with warnings.catch_warnings():
        warnings.simplefilter("error", AccuracyWarning)
        assert simulate(dt=0.05, **kw).energy_error < 1e-3
        # the suggested step meets the tolerance
        assert simulate(dt=msg_dt, **kw).energy_error < 1e-3


@pytest.mark.parametrize("point, case", [("blue", "coupled"), ("green", "rotation")])
def test_tol_reaches_about_tol_against_a_tight_reference(point, case):
    # T = 200 (before MI amplifies errors); the reference is srkn11b at dt = 0.005
    # (error ~1e-13). The model's constants are the largest of its calibration points, so
    # the error lands at or below tol: measured 0.37 tol (blue) and 0.07 tol (green)
    mat = Material.paper(point)
    s0 = initial_condition(mat, case, 500, paper.k(point))
    ref = integrate(s0, mat, case, 200.0, 0.005, "srkn11b")
    for tol in (1e-5, 1e-7):
        end = integrate(s0, mat, case, 200.0, tol=tol)
        err = np.max(np.abs(end.theta - ref.theta))
        if case == "coupled":
            err = max(err, np.max(np.abs(end.U - ref.U)))
        err /= np.max(np.abs(ref.theta))
        assert tol / 30 < err <= 1.5 * tol, (tol, err)


def test_tol_chooses_a_method_and_rejects_nonsense(blue):
    s0 = initial_condition(blue, "coupled", 100, 2 * np.pi * 13 / 100)
    method, dt = choose_step(s0, blue, "coupled", 200.0, 1e-6)
    assert method == "srkn11b" and 0 < dt < 2.0
    run = simulate(blue, "coupled", 100, 2 * np.pi * 13 / 100, t_end=10.0, tol=1e-6)
    assert run.method == "srkn11b"
    with pytest.raises(ValueError, match="dt or tol"):
        integrate(s0, blue, "coupled", 1.0, 0.05, tol=1e-6)
    with pytest.raises(ValueError, match="tol must be in"):
        integrate(s0, blue, "coupled", 1.0, tol=float("nan"))
    with pytest.raises(ValueError, match="adaptive"):
        integrate(s0, blue, "coupled", 1.0, method="dop853", tol=1e-6)
    with pytest.raises(ValueError, match="energy_tolerance"):
        integrate(s0, blue, "coupled", 1.0, 0.05, energy_tolerance=-1)
