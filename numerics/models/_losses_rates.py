"""The sidebands' and the carrier's damping rates of a damped point (issue 42), kept per
wavenumber: a point's theories (the damped NLS, the four-wave and the exact theory along
the decaying carrier) ask the rates at their offsets k +- q and at the carrier's k; each
wavenumber's rates are computed once, in one ``damping_rates`` call per new set (a row
depends on its wavenumber alone: the same numbers as one call over all of them).
"""

from __future__ import annotations

import numpy as np

from energy import Model, ModelError


def sideband_damping(model: Model, k: float, q, branch: int) -> np.ndarray:
    """G_q: the mean amplitude decay rate of the sidebands k + q and k - q on the carrier's
    branch, followed as a dispersion sheet (``sheet_branches``) where the branches of
    linearly uncoupled fields cross between k and k +- q (by index, a theta sideband of the
    paper chain below the theta-U crossing was damped at U's rate)."""
    from ._modes import sheet_branches

    up, down = side_rates(model, k, q)
    q = np.atleast_1d(np.asarray(q, float))
    rows = np.arange(q.size)
    return 0.5 * (up[rows, sheet_branches(model, k, branch, k + q)]
                  + down[rows, sheet_branches(model, k, branch, k - q)])


# (weak reference to the model, kappas kept (ascending, unique), their rows): the rates a
# point's theories asked, one tuple (read and replaced whole, safe across threads): the
# NLS's, the four-wave's and the exact theory's offsets each computed once, in one call
# per new set
_SIDE = [None]
#: the most rates kept for one model
SIDE_KEPT = 4096


def side_rates(model: Model, k: float, q) -> tuple[np.ndarray, np.ndarray]:
    """(Gamma_b(k + q), Gamma_b(k - q)), each (len(q), d): one ``damping_rates`` call for
    the wavenumbers not asked before, the carrier's k among them (a row depends on its
    wavenumber alone: the same numbers as one call for all)."""
    q = np.atleast_1d(np.asarray(q, float))
    both = _rates_at(model, np.concatenate([[float(k)], k + q, k - q]))[1:]
    return both[:q.size], both[q.size:]


def _rates_at(model: Model, kappas) -> np.ndarray:
    """``damping_rates(model, kappas)``, shape (len(kappas), d), from the rates kept (a
    wavenumber is found by equality, as a dict key: 0.0 and -0.0 are one)."""
    import weakref

    from ._linear import damping_rates

    kap = np.asarray(kappas, float).ravel()
    if not np.all(np.isfinite(kap)):  # nan is no key: asked as it is
        return damping_rates(model, kap).reshape(kap.size, model.n_fields)
    last = _SIDE[0]
    keys, rows = (last[1], last[2]) if last is not None and last[0]() is model else \
        (np.zeros(0), np.zeros((0, model.n_fields)))
    at = np.minimum(np.searchsorted(keys, kap), max(keys.size - 1, 0))
    hit = keys[at] == kap if keys.size else np.zeros(kap.size, bool)
    if not hit.all():
        missing = np.unique(kap[~hit])
        if not keys.size or keys.size + missing.size > SIDE_KEPT:
            # afresh (none kept, or too many): this call's wavenumbers alone, already
            # sorted and unique (``missing``: every one)
            keys = missing if not keys.size else np.unique(kap)
            rows = damping_rates(model, keys)
        else:
            keys = np.concatenate([keys, missing])
            rows = np.concatenate([rows, damping_rates(model, missing)])
            order = np.argsort(keys, kind="stable")
            keys, rows = keys[order], rows[order]
        _SIDE[0] = (weakref.ref(model), keys, rows)
        at = np.searchsorted(keys, kap)
    return rows[at].reshape(kap.size, model.n_fields)


def rates_once(model: Model, k: float, q, branch: int) -> tuple[np.ndarray, float]:
    """(G_q, Gamma): ``sideband_damping`` and the carrier's rate from one
    ``damping_rates`` call, nothing kept: a theory's own offsets that no other asks (the
    damped NLS's), where merging them into the kept rates costs as much as the rates
    (the same numbers: a row depends on its wavenumber alone)."""
    from ._linear import branch_index, damping_rates
    from ._modes import sheet_branches

    q = np.atleast_1d(np.asarray(q, float))
    rows = damping_rates(model, np.concatenate([[float(k)], k + q, k - q]))
    b = branch_index(model, k, branch)
    n = np.arange(q.size)
    return (0.5 * (rows[1:q.size + 1][n, sheet_branches(model, k, b, k + q)]
                   + rows[q.size + 1:][n, sheet_branches(model, k, b, k - q)]),
            float(rows[0, b]))


def _carrier_damping(model: Model, k: float, branch) -> float:
    """``carrier_damping(model, k, branch)`` (Gamma of the carrier's branch) from the
    rates kept: a point's theories ask it after their sidebands' rates, which hold it."""
    from ._linear import branch_index

    if not model.lossy:
        return 0.0
    return float(_rates_at(model, [float(k)])[0][branch_index(model, k, branch)])


def _sampling(ratio, most) -> tuple[float, int]:
    """``along_decay``'s ratio in (0, 1) and most >= 1 (before: ratio -1 'math domain
    error', 0 'amplitude must be > 0', most 0 accepted)."""
    from ._simulate import check_count

    if isinstance(ratio, bool) or not isinstance(ratio, (int, float, np.floating)) \
            or not 0 < ratio < 1:
        raise ModelError(f"ratio (of the squared amplitudes sampled along the decay) must "
                         f"be in (0, 1), got {ratio!r}")
    return float(ratio), check_count("most", most)


def carrier_overdamped(model: Model, k: float, branch) -> bool:
    """Whether the carrier's damped root does not oscillate (Re omega = 0: damped past
    critical, a relaxation, not a wave). Probe 98: a Klein-Gordon chain with on-site
    damping gamma 1e8 (k 2, a 0.4) has its carrier's root at -i omega^2 / gamma, a rate of
    3.8e-8, and every theory read it as a nearly undamped carrier: MI, amplification
    e^700 at t ~ 1e7, observable (2.2x at gamma 1e3, cubic a3 0.8), where a chain that stiff in its
    damping only relaxes. Re omega below 1e-9 |omega| is LAPACK's round-off of zero."""
    from ._linear import branch_index, damped_frequencies

    if not model.lossy:
        return False
    w = complex(damped_frequencies(model, k)[branch_index(model, k, branch)])
    return bool(abs(w) > 0 and w.real <= 1e-9 * abs(w))


def overdamped_answer(model: Model, k: float, branch, Gamma: float):
    """A theory's answer where the carrier is overdamped (``carrier_overdamped``): nothing
    oscillates to pump a sideband, so nothing grows: (amplification 1 at t = 0, not
    observable, net gain 0, the ``damped_verdict`` 'stable' where the lossless chain
    says MI); None where the carrier oscillates."""
    from ._losses import Amplified

    if Gamma <= 0 or not carrier_overdamped(model, k, branch):
        return None
    return Amplified(Gamma, 1.0, 0.0, float("nan"), False, 0.0, overdamped=True)
