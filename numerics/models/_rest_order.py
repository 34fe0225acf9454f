"""Whether a model's nonlinearity at rest is the cubic one the NLS expands.

The NLS needs the energy's Taylor expansion at rest to fourth order: its third and fourth
derivatives (``model.code.taylor``). An odd power of ``Abs`` of a quantity that vanishes
at rest (``Abs(r)**3``, ``Abs(theta)*U**2``) has finite derivatives there, which the
derivation evaluates at 0, but its third derivatives jump across rest: the force holds a
term ``r |r|`` of second order that is odd, which no Taylor tensor carries. Its
frequency shift then grows like |a| instead of a^2 and the NLS read from the tensors
(Abs(r)**3: g2 = 0, "stable") describes another chain (the exact theory finds MI).

Measured on the generated gradient g along directions v: the odd part
(g(h v) - g(-h v)) / 2 - H h v - Q[v, v, v] h^3 / 6 is O(h^5) where the energy is smooth,
c h^2 where the third derivatives jump; seen at two steps, the h^2 law is the test.
"""

from __future__ import annotations

import functools
import itertools

import numpy as np

from energy import Model

#: the two steps along each direction (fields near rest: a weak wave's amplitude is
#: 1e-2 .. 1e-1); smooth, the residual over h^2 falls 1000x from the first to the second
STEPS = (1e-3, 1e-4)
#: the residual over h^2, relative to the Taylor tensors' size, that counts as a jump
#: (Abs(r)**3: 3; a smooth exp(100 r): ~0.1 against a scale 1e8)
JUMP = 1e-6

_ANSWERS: dict = {}


def rest_not_cubic(model: Model, taylor=None) -> str | None:
    """Why the model's nonlinearity at rest is not cubic (its third derivatives jump
    there), or None. Once per model and parameters; ``taylor``: ``model.code.taylor``'s
    (H, T, Q) where the caller has them (the NLS: ~0.1 ms a new parameter value)."""
    key = (model.code, np.asarray(model.p, float).tobytes())
    if key not in _ANSWERS:
        if len(_ANSWERS) > 256:
            _ANSWERS.clear()
        _ANSWERS[key] = _rest_not_cubic(model, taylor)
    return _ANSWERS[key]


@functools.lru_cache(maxsize=16)
def _directions(n: int) -> np.ndarray:
    """Unit vectors, pairwise sums (a product of fields) and one generic direction, as
    columns."""
    eye = np.eye(n)
    pairs = [eye[i] + eye[j] for i, j in itertools.combinations(range(n), 2)]
    generic = np.cos(np.arange(1, n + 1) * 1.234567)  # fixed: reproducible
    return np.column_stack([*eye, *pairs, generic]) if n > 1 else eye


def _rest_not_cubic(model: Model, taylor=None) -> str | None:
    H, T, Q = (np.asarray(a, float) for a in (taylor or model.code.taylor(model.p)))
    if not (np.all(np.isfinite(H)) and np.all(np.isfinite(T)) and np.all(np.isfinite(Q))):
        return None  # said by the NLS's own check (a power below 4)
    n = H.shape[0]
    V = _directions(n)
    scale = max(1.0, float(np.max(np.abs(H))), float(np.max(np.abs(T))),
                float(np.max(np.abs(Q))))
    ratio, kink = [], []
    # the cell's gradient at rest: zero where each cell's energy is at its minimum, not
    # where a precompressed bond's force cancels between neighbours (a Hertz contact
    # (2/5) (d0 - r)^(5/2): -d0^(3/2) per bond); the even part's constant, which is no kink
    G0 = np.zeros((n, 1))
    with np.errstate(all="ignore"):
        model.code.cell_gradient_into(np.zeros((V.shape[0], 1)), model.p, G0)
    for h in STEPS:
        X = np.hstack([h * V, -h * V])
        G = np.empty_like(X)
        with np.errstate(all="ignore"):
            model.code.cell_gradient_into(X, model.p, G)
        m = V.shape[1]
        odd = (G[:, :m] - G[:, m:]) / 2
        cubic = np.einsum("iabc,aj,bj,cj->ij", Q, V, V, V) * h**3 / 6
        ratio.append(np.abs(odd - H @ V * h - cubic) / h**2)
        # the even part is T[v, v] h^2 / 2 + O(h^4) where the energy is smooth; c |h|
        # where its second derivatives jump at rest (r*Abs(r), a bilinear spring)
        even = (G[:, :m] + G[:, m:]) / 2 - G0
        kink.append(np.abs(even - np.einsum("iab,aj,bj->ij", T, V, V) * h**2 / 2) / h)
    if not all(np.all(np.isfinite(r)) for r in ratio + kink):
        return None  # not real near rest: said elsewhere (energy_not_real)
    k1, k2 = kink
    # the |h| law at both steps; smooth, the residual over h falls 1000x (h^3 / h)
    jump2 = (k1 > JUMP * scale) & (k2 > 0.5 * k1)
    if np.any(jump2):
        i, j = np.unravel_index(int(np.argmax(np.where(jump2, k1, 0))), k1.shape)
        return (f"model {model.describe()}: the energy's second derivatives jump at rest "
                "(Abs of a quantity that vanishes there times it, as r*Abs(r): a bilinear "
                "spring): its force holds an even first-order term (size "
                f"{k1[i, j]:.3g} |h| in coordinate {i}), so its stiffness differs on the "
                "two sides of rest: the linear branches shown are the mean stiffness's, not "
                "the chain's small waves, whose frequency does not depend on their "
                "amplitude; there is no NLS; the exact theory (exact_gain) still applies")
    c1, c2 = ratio
    jump = (c1 > JUMP * scale) & (c2 > 0.5 * c1)  # the h^2 law at both steps
    if not np.any(jump):
        return None
    i, j = np.unravel_index(int(np.argmax(np.where(jump, c1, 0))), c1.shape)
    return (f"model {model.describe()}: the energy's third derivatives jump at rest (an odd "
            "power of Abs of a quantity that vanishes there, as Abs(r)**3): its force holds "
            f"an odd second-order term (size {c1[i, j]:.3g} h^2 in coordinate {i}), so the "
            "wave's frequency shift grows like |a|, not a^2, and there is no cubic NLS; "
            "the exact theory (exact_gain) still applies")
