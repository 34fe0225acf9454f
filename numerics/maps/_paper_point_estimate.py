"""How long a paper-chain point's runs will take (``flexmm point --simulate`` with the
paper's flags), said before them as a model point's are (``estimate_model_point``): one
short run of the ring measured here with the runs' own method and step, scaled to their
length and number."""

from __future__ import annotations

import time

from ..lattice import simulate as simulate_chain
from ._estimate import POINT_FIGURE_SECONDS, PROBE_STEPS, PointEstimate, load_slowdown


def estimate_paper_point(material, case: str, k: float, amplitude: float, *, N: int,
                         start: str, t_end: float, seeds: int, method: str, dt: float,
                         save_every: float, figure: bool = True) -> PointEstimate:
    """The wall time of ``seeds`` runs of ``t_end`` on the ring of ``N`` sites with
    ``method`` at ``dt`` (a simulated point's, ``point_step``), and its figure, slowed by
    the load: a run of a few steps loads the kernels, then PROBE_STEPS steps (at most a
    tenth of the run, at least 200) are timed (CPU seconds) and scaled to ``t_end`` (the
    run's cost is its steps)."""
    run = dict(material=material, case=case, N=N, k=k, amplitude=amplitude, seed=0,
               method=method, dt=dt, start=start, progress=False, store="spectrum",
               energy_tolerance=1.0)
    simulate_chain(**run, t_end=min(t_end, 4 * dt), save_every=min(t_end, 4 * dt))
    # at most a tenth of a run (not below 200 steps): a short run is not run twice
    probe_t = min(t_end, PROBE_STEPS * dt, max(t_end / 10, 200 * dt))
    t0 = time.process_time()
    simulate_chain(**run, t_end=probe_t, save_every=min(save_every, probe_t))
    one = (time.process_time() - t0) * t_end / probe_t
    slowdown, load, cores = load_slowdown(1)
    total = (seeds * one + (POINT_FIGURE_SECONDS if figure else 0.0)) * slowdown
    return PointEstimate(total, 0.0, one, int(seeds), float(t_end), slowdown, load, cores)


__all__ = ["estimate_paper_point"]
