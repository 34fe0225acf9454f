"""Shared pieces of the fault catalogue (``bench/faults.py``, ``bench/faults_maps.py``)."""

from __future__ import annotations

import numpy as np

from common import paper
from numerics import (
    Material,
    initial_condition,
    integrate,
    simulate,
    stability_map,
    stability_verdict,
)

E = "error"
BLUE = Material.paper("blue")
K13 = 2 * np.pi * 13 / 100  # commensurate with N = 100


def _sim(**kw):
    args = dict(material=BLUE, case="coupled", N=100, k=K13, t_end=1.0, dt=0.05)
    args.update(kw)
    return simulate(**args)


def _state(case="coupled", N=16):
    return initial_condition(BLUE, case, N, 2 * np.pi * 2 / N)


def _integrate(**kw):
    args = dict(state=_state(), material=BLUE, case="coupled", t_end=1.0, dt=0.05)
    args.update(kw)
    return integrate(**args)


def _smap(**kw):
    args = dict(k=np.array([0.8, 0.9]), delta=np.array([0.003, -0.003]), case="coupled",
                alpha=2.5, K_s=paper.K_S, amplitude=0.02)
    args.update(kw)
    return stability_map(**args)


def _nan_spectrum():
    spec = np.ones((3, 51))
    spec[:, 5] = np.nan
    return stability_verdict(spec, 13, 100)


