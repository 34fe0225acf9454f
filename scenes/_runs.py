"""The paper's run, as the simulation scenes set it up (full and quick mode)."""

from __future__ import annotations

from common import paper
from numerics import Material

#: quick mode: the smallest N commensurate with the point's k (blue 13/100, green 37/250)
QUICK_N = {"blue": 200, "green": 250}


def run_parameters(ctx, point: str, quick_T: float, quick_N: int | None = None,
                   A0: float = paper.A0, **extra) -> dict:
    """Keyword arguments of ``numerics.simulate`` for the paper's run at a test point:
    eq. `IC` with the paper's noise and peak rotation 2 eps A0 (eps of the paper, ``A0``
    as in Fig. 9), RK4 at dt = 0.05, N = 500 and T = 5000 (quick mode: ``quick_N`` or
    QUICK_N, and ``quick_T``); ``extra`` overrides."""
    base = dict(material=Material.paper(point), k=paper.k(point),
                N=(quick_N or QUICK_N[point]) if ctx.quick else paper.N, amplitude=2 * paper.EPS * A0, noise=paper.NOISE, seed=ctx.seed,
                t_end=quick_T if ctx.quick else paper.T_END, dt=paper.DT, method="rk4")
    base.update(extra)
    return base


def plain_parameters(params: dict) -> dict:
    """The run parameters as plain values (material -> alpha, K_s, K_theta) for data.h5."""
    out = {k: v for k, v in params.items() if k not in ("material", "progress")}
    m = params["material"]
    out.update(alpha=m.alpha, K_s=m.K_s, K_theta=m.K_theta)
    return out


#: run length of the gain measurements at A0 = 1 (scaled by 1/A0^2): the unstable runs
#: leave their linear stage by then (blue grows faster than green)
GAIN_T = {"blue": 3000.0, "green": 5000.0}
#: seeds averaged per measured gain curve (full, quick)
GAIN_SEEDS = (4, 2)
#: time between spectrum records of a gain measurement (a fit needs >= 5 in its window)
GAIN_RECORD_DT = 5.0


def measured_gain(ctx, point, case, A0=paper.A0, t_end=None, quick_N=None, **extra):
    """sigma(q) measured at a test point (``numerics.measure_gain``), mean over seeds.

    Defaults: t_end = GAIN_T / A0^2, N = 500 (quick: QUICK_N), GAIN_SEEDS seeds from
    ``ctx.seed`` on; ``extra`` goes to the simulation (k, start, ...)."""
    from numerics.theory import measure_gain

    t_end = GAIN_T[point] / A0**2 if t_end is None else t_end
    params = run_parameters(ctx, point, t_end, quick_N, case=case, A0=A0, t_end=t_end,
                            save_every=GAIN_RECORD_DT, **extra)
    seeds = [ctx.seed + s for s in range(GAIN_SEEDS[ctx.quick])]
    return measure_gain(ctx.simulate, seeds, **params)
