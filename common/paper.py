"""The paper's numbers, in one place: material, test points, initial condition, run length.

Every layer reads them from here (derivation report, scenes, tests, benchmarks), so a
number the paper states is typed exactly once. Pure Python: importing this module costs
nothing (no SymPy, no NumPy, no Numba).

Sources in the paper (LaTeX labels): K_s, Fig. 2's caption (Figs. 3-4 state no K_s:
their maps take the test points' K_s, K_theta = K_s - delta); alpha = 2.5, Figs. 2 and 4
and Sec. 'Numerical simulations of the flexMM' (Fig. 3 adds 1.5 and 3.5); the blue and
green points, Fig. 4's caption and Figs. 5-8; eps, the noise b0 and the periodic chain of
N = 500 sites integrated by RK4, the same section (eq. `IC`). The paper states no time
step and no run length: T = 5000 is what its figures imply (Fig. 9's green run is shown
at t = 5000; Fig. 5's stable run lasts 'more than 500 oscillations', T > 4076), dt = 0.05
is this project's choice.
"""

from __future__ import annotations

from types import MappingProxyType

#: Inertial parameter alpha (normalised, below eq. `norm`; Figs. 3-9 use 2.5).
ALPHA = 2.5
#: Shear stiffness K_s = k_s / k_l of the test points.
K_S = 0.01851
#: The two test points of Figs. 4-9: carrier wavenumber k (rad per site) and K_theta;
#: delta = K_s - K_theta is +0.003 (blue) and -0.003 (green).
POINTS = MappingProxyType({
    "blue": MappingProxyType({"k": 0.81681, "K_theta": 0.01551}),
    "green": MappingProxyType({"k": 0.92991, "K_theta": 0.02151}),
})
#: Small parameter of the multiple-scales expansion; the initial rotation is 2 eps A0.
EPS = 0.01
#: Envelope amplitude of the plane wave in eq. `IC` (Figs. 5-8; Fig. 9 also 0.8, 1.4).
A0 = 1.0
#: Peak rotation of the carrier in eq. `IC`: 2 eps A0 (the one conversion from the paper's
#: (eps, A0) to the amplitude every public function takes).
AMPLITUDE = 2 * EPS * A0
#: Relative amplitude of the uniform noise b0 in eq. `IC` (b0 in [-NOISE, NOISE]).
NOISE = 1e-3
#: Number of sites of the periodic chain.
N = 500
#: Duration and time step of the RK4 runs of Figs. 5-9 (neither stated in the paper: T from
#: Fig. 9's t = 5000 and Fig. 5's 'more than 500 oscillations'; dt our choice).
T_END = 5000.0
DT = 0.05
#: Times at which Fig. 9 shows the spectra, by (point, A0) (caption; erratum 2).
FIG9_TIMES = MappingProxyType({("blue", 0.8): 2500.0, ("blue", 1.4): 1100.0,
                               ("green", 0.8): 5000.0, ("green", 1.4): 1700.0})
#: The two unstable runs the paper shows MI for: (point, case).
MI_RUNS = (("blue", "coupled"), ("green", "rotation"))


def _point(point: str):
    try:
        return POINTS[point]
    except (KeyError, TypeError):
        raise ValueError(f"unknown test point {point!r}; choose one of "
                         f"{', '.join(POINTS)}") from None


def k(point: str) -> float:
    """Carrier wavenumber of a test point (rad per site)."""
    return _point(point)["k"]


def K_theta(point: str) -> float:
    """Bending stiffness K_theta of a test point."""
    return _point(point)["K_theta"]


def delta(point: str) -> float:
    """delta = K_s - K_theta of a test point."""
    return K_S - _point(point)["K_theta"]


def parameters(point: str) -> dict:
    """``{"k", "alpha", "K_s", "K_theta"}`` of a test point: the arguments of every
    generated coefficient function (``co.g1(**parameters("blue"))``)."""
    p = _point(point)
    return {"k": p["k"], "alpha": ALPHA, "K_s": K_S, "K_theta": p["K_theta"]}
