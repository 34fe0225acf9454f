"""Linear waves of any lattice model: dispersion matrix, branches, group velocity, g1.

For a model with Taylor tensor H of the cell energy W(u_n, u_{n+1}) at rest (blocks
H11, H12, H21, H22 over (u_n, u_{n+1})), a wave u_n = e exp(i(kappa n - Omega t)) solves

    D(kappa, Omega) e = 0,   D = K(kappa) - Omega^2 M,
    K(kappa) = H11 + H22 + H12 e^{i kappa} + H21 e^{-i kappa}          (Hermitian)

Branch b at kappa is the b-th eigenvalue (ascending) of M^{-1/2} K M^{-1/2}, omega_b^2.
"""

from __future__ import annotations

import math
import numbers
from dataclasses import dataclass

import numpy as np

from energy import MAX_VALUE, Model, ModelError

from ._args import check_harmonics, check_k, scalar, wavenumbers  # noqa: F401 (imported from here)


def blocks(H: np.ndarray, d: int):
    return H[:d, :d], H[:d, d:], H[d:, :d], H[d:, d:]


def dynamical_matrix(H: np.ndarray, kappa: float, order: int = 0) -> np.ndarray:
    """K(kappa) (order 0) or its ``order``-th derivative in kappa.

    Order 0 as K(0) + H12 (e^{i kappa} - 1) + H21 (e^{-i kappa} - 1), e^{i kappa} - 1 =
    2 i sin(kappa/2) e^{i kappa/2}: an acoustic branch's K(0) is exactly 0 (its bond's
    Hessian entries cancel), so omega^2 ~ kappa^2 keeps its relative precision as kappa
    -> 0 (the form H11 + H22 + H12 e^{i kappa} + H21 e^{-i kappa} loses it to
    cancellation: omega^2 = 0 at kappa = 1e-9 on an FPUT chain, g1 3x off at 1e-4)."""
    d = H.shape[0] // 2
    H11, H12, H21, H22 = blocks(H, d)
    if order == 0:
        dz = 2j * math.sin(kappa / 2) * np.exp(0.5j * kappa)  # e^{i kappa} - 1
        return (H11 + H22 + H12 + H21).astype(complex) + H12 * dz + H21 * np.conj(dz)
    z = np.exp(1j * kappa)
    return H12 * (1j) ** order * z + H21 * (-1j) ** order / z


@dataclass(frozen=True)
class Carrier:
    """The linear carrier wave of one branch at one k.

    Attributes
    ----------
    k, omega : float
        Wavenumber (rad/site) and frequency (1/time, lattice units).
    branch : int
        Branch index at k (0 = lowest frequency).
    field : int
        Index of the field whose first-harmonic amplitude is the wave's amplitude.
    e : ndarray, shape (d,), complex
        Polarisation, e[field] = 1.
    group_velocity, g1 : float
        d omega/dk and d^2 omega/dk^2 of the branch.
    gap : float
        Distance in omega to the nearest other branch at k (0: degenerate carrier).
    """

    k: float
    omega: float
    branch: int
    field: int
    e: np.ndarray
    group_velocity: float
    g1: float
    gap: float


def branches(model: Model, kappa) -> np.ndarray:
    """omega_b(kappa) of every branch, shape (..., d), ascending; NaN where omega^2 < 0."""
    H = model.code.taylor(model.p)[0]
    m = model.masses
    s = 1 / np.sqrt(m)
    kap = wavenumbers(kappa)
    out = np.empty(kap.shape + (len(m),))
    for idx in np.ndindex(kap.shape):
        A = s[:, None] * dynamical_matrix(H, float(kap[idx])) * s[None, :]
        lam = np.linalg.eigvalsh(A)
        out[idx] = np.where(lam >= 0, np.sqrt(np.abs(lam)), np.nan)
    return out


def rest_kink(model: Model) -> str | None:
    """Why there is no linear wave where the rest state is a kink of the energy (an
    ``Abs`` of a quantity that vanishes at rest, to the first power): the force jumps
    there, the Hessian (``Abs`` differentiated away from its kink) does not see it, and
    at small amplitude the jump outweighs every linear force. None for an energy whose
    force is continuous at rest (smooth, or ``Abs(x)**p`` with p > 1).

    Measured on the generated gradient: g(h e_i) - g(-h e_i) - 2 h H e_i at h = 1e-7 is
    O(h^2) (round-off ~1e-16) where the force is smooth, twice the jump where it is not."""
    key = (model.code, np.asarray(model.p, float).tobytes())  # one module per energy
    if key not in _KINKS:  # asked by every carrier: once per model and parameters
        if len(_KINKS) > 256:
            _KINKS.clear()
        _KINKS[key] = _rest_kink(model)
    return _KINKS[key]


#: rest_kink's answers by (generated module, parameters)
_KINKS: dict = {}


def _rest_kink(model: Model) -> str | None:
    d = model.n_fields
    H = model.code.taylor(model.p)[0]
    h = 1e-7
    X = np.hstack([h * np.eye(2 * d), -h * np.eye(2 * d)])
    G = np.empty((2 * d, 4 * d))
    with np.errstate(all="ignore"):
        model.code.cell_gradient_into(X, model.p, G)
    jump = np.abs(G[:, :2 * d] - G[:, 2 * d:] - 2 * h * H)
    if not np.all(np.isfinite(jump)):
        return None  # an infinite stiffness at rest: said by the derivation's own checks
    i = int(np.argmax(jump.max(axis=0)))
    size = float(jump[:, i].max()) / 2
    if size <= 1e-6 * max(1.0, float(np.max(np.abs(H)))):
        return None
    coord = model.fields[i % d] + ("_next" if i >= d else "")
    return (f"model {model.describe()}: the rest state is a kink of the energy: its force "
            f"jumps by {size:.3g} where {coord} crosses it (Abs of a quantity that vanishes "
            "at rest), so there is no linear wave and no small-amplitude theory; smooth "
            "the kink (e.g. sqrt(x**2 + eps**2)) or raise its power (Abs(x)**p, p >= 2)")


def check_rest_stable(model: Model, samples: int = 257):
    """Refuse a rest state whose energy is not real (or not finite) at the parameters'
    values, one that is not a minimum (omega^2 < 0 on some branch), or a kink of the
    energy (``rest_kink``)."""
    import warnings

    model = check_model(model)
    with warnings.catch_warnings(), np.errstate(all="ignore"):  # said below, in one line
        warnings.simplefilter("ignore")
        w0 = np.asarray(model.code.cell_energy(np.zeros(2 * model.n_fields), model.p))
        H = np.asarray(model.code.taylor(model.p)[0], dtype=float)
    if not (np.all(np.isfinite(w0)) and np.all(np.isfinite(H))):
        # sqrt(u**2 - c) or log(u**2 - c) at c > 0: NaN at rest (the symbolic checks of the
        # derivation hold for every parameter value, so they cannot see it)
        raise ModelError(f"model {model.describe()}: the energy is not real at the rest "
                         f"state (every field 0): bond + site there is {float(w0.ravel()[0]):g}"
                         + ("" if np.all(np.isfinite(H)) else ", its stiffness not finite")
                         + " (a division by zero, or a square root, log or fractional power "
                         "of a quantity that is negative at rest, at these parameter values?)")
    if why := rest_kink(model):
        raise ModelError(why)
    m = model.masses
    s = 1 / np.sqrt(m)
    scale = max(1.0, float(np.max(np.abs(H))) / float(np.min(m)))
    # every k at once (a map checks each of its parameter values: 4 ms -> 0.3 ms a value),
    # each K(kappa) formed as dynamical_matrix forms it
    kap = np.linspace(0, math.pi, samples)
    d = model.n_fields
    H11, H12, H21, H22 = blocks(H, d)
    dz = (2j * np.sin(kap / 2) * np.exp(0.5j * kap))[:, None, None]  # e^{i kappa} - 1
    K = (H11 + H22 + H12 + H21).astype(complex)[None] + H12 * dz + H21 * np.conj(dz)
    lowest = np.linalg.eigvalsh(s[:, None] * K * s[None, :])[:, 0]
    bad = np.flatnonzero(lowest < -1e-12 * scale)
    if bad.size:
        i = int(bad[np.argmin(lowest[bad])])  # the most negative (newuser99: the first)
        raise ModelError(f"model {model.describe()}: the rest state is not a minimum: "
                         f"branch 0 has omega^2 = {lowest[i]:.3g} < 0 at k = {kap[i]:.4g} "
                         "(its lowest); "
                         "the energy's quadratic part (bond + site to second order) must be "
                         "positive: check the signs of its stiffness terms and parameters")


def check_model(model) -> Model:
    """``model`` itself where it is an ``energy.Model``; a one-line error naming what it
    got otherwise (a name or a Lattice given where the loaded model belongs)."""
    if not isinstance(model, Model):
        raise ModelError(f"model must be an energy.Model (energy.load_model(name, file or "
                         f"Lattice)), got {type(model).__name__} {str(model)[:60]!r}")
    return model


def check_amplitude(amplitude, name: str = "amplitude") -> float:
    """A carrier's amplitude: a real number (not a bool or a string) in (0, MAX_VALUE]."""
    amplitude = scalar(amplitude)
    if isinstance(amplitude, (bool, np.bool_)) or not isinstance(amplitude, numbers.Real):
        raise ModelError(f"{name} must be a real number > 0, got "
                         f"{type(amplitude).__name__} {amplitude!r}")
    a = float(amplitude)
    if not (math.isfinite(a) and 0 < a <= MAX_VALUE):
        raise ModelError(f"{name} must be a finite number > 0 (at most {MAX_VALUE:g}), got "
                         f"{amplitude!r}")
    return a


def branch_index(model: Model, k: float, branch=None) -> int:
    """Branch index at k from an index, a field name (the branch that field dominates) or
    None (the model's default: its ``branch`` field, else 0)."""
    d = check_model(model).n_fields
    if branch is None:
        branch = model.lattice.branch if model.lattice.branch is not None else 0
    if isinstance(branch, (int, np.integer)) and not isinstance(branch, bool):
        if not 0 <= branch < d:
            raise ModelError(f"branch must be in 0..{d - 1} for model {model.name!r} "
                             f"({d} field(s)), got {branch}")
        return int(branch)
    if isinstance(branch, str):
        if branch.isdigit():
            return branch_index(model, k, int(branch))
        if branch not in model.fields:
            raise ModelError(f"branch {branch!r} is neither an index nor a field of model "
                             f"{model.name!r} (fields: {', '.join(model.fields)})")
        f = model.fields.index(branch)
        vecs = _modes(model, k)[1]
        weight = np.abs(vecs[f, :]) ** 2  # mass-weighted eigenvectors: columns normalised
        return int(np.argmax(weight))
    raise ModelError(f"branch must be an index or a field name, got {branch!r}")


def _modes(model: Model, k: float):
    H = model.code.taylor(model.p)[0]
    m = model.masses
    s = 1 / np.sqrt(m)
    lam, vecs = np.linalg.eigh(s[:, None] * dynamical_matrix(H, k) * s[None, :])
    return lam, vecs, H, s


#: float64's unit round-off: the rounding error of one operation, relative
_EPS = float(np.finfo(float).eps)


def _rounding_floor(H: np.ndarray, s: np.ndarray, k: float) -> float:
    """The rounding error of omega^2 at ``k`` from the mass-weighted dynamical matrix:
    its entries' (each K(0) + H12 (e^{ik} - 1) + H21 (e^{-ik} - 1), good to eps times the
    size of those terms: ``dynamical_matrix``) and, with more than one field, the
    Hermitian eigensolver's, backward stable to eps times the matrix's norm times its order
    (an acoustic omega^2 ~ k^2 of a diatomic chain keeps no digit below k ~ 1e-8: its
    eigenvalue is the small difference of the matrix's O(1) ones)."""
    d = len(s)
    H11, H12, H21, H22 = blocks(H, d)
    w = np.abs(s)[:, None] * np.abs(s)[None, :]
    # one field: omega^2 is the entry's real part, whose e^{ik} - 1 is -2 sin^2(k/2) (the
    # imaginary parts cancel exactly); more: the entries' imaginary parts count too
    dz = 2 * math.sin(k / 2) ** 2 if d == 1 else abs(2 * math.sin(k / 2))
    terms = w * (np.abs(H11 + H22 + H12 + H21) + (np.abs(H12) + np.abs(H21)) * dz)
    floor = _EPS * float(np.max(terms.sum(axis=1)))
    if d > 1:
        A = w * np.abs(dynamical_matrix(H, k))
        floor += d * _EPS * float(np.max(A.sum(axis=1)))
    # below the smallest normal number omega^2 underflows, losing its digits one by one
    return max(floor, float(np.finfo(float).tiny))


def _carrier_parts(model: Model, k: float, b: int):
    """(lam, vecs, H, s, lam1, lam2): omega^2 of every branch at ``k``, the modes, and
    d(omega_b^2)/dk, d^2(omega_b^2)/dk^2 of branch ``b`` (perturbation theory of the
    Hermitian eigenproblem); lam1, lam2 None where omega_b^2 <= 0."""
    lam, vecs, H, s = _modes(model, k)
    if lam[b] <= 0:
        return lam, vecs, H, s, None, None
    phi = vecs[:, b]
    A1 = s[:, None] * dynamical_matrix(H, k, 1) * s[None, :]
    A2 = s[:, None] * dynamical_matrix(H, k, 2) * s[None, :]
    lam1 = float(np.real(phi.conj() @ A1 @ phi))
    lam2 = float(np.real(phi.conj() @ A2 @ phi))
    for j in range(len(lam)):
        if j != b and abs(lam[j] - lam[b]) > 1e-13 * max(1.0, abs(lam[b])):
            lam2 += 2 * abs(vecs[:, j].conj() @ A1 @ phi) ** 2 / (lam[b] - lam[j])
    return lam, vecs, H, s, lam1, lam2


def _smallest_k(resolved, k: float) -> float | None:
    """The smallest wavenumber in [k, pi] where ``resolved(k)`` holds (bisection in log k:
    the rounding of a long wave's coefficients falls off as a power of k), or None where it
    does not hold at pi either."""
    if not resolved(math.pi):
        return None
    lo, hi = math.log(max(k, 1e-300)), math.log(math.pi)
    for _ in range(60):  # 60 halvings of [ln 1e-300, ln pi]: k to 1e-15 relative
        mid = (lo + hi) / 2
        lo, hi = (lo, mid) if resolved(math.exp(mid)) else (mid, hi)
    return math.exp(hi)


def g1_resolved(lam: float, lam1: float, lam2: float, floor: float) -> bool:
    """Whether g1's numerator lam2 - 2 v_g^2 (v_g^2 = lam1^2 / (4 lam)) is larger than its
    rounding: the subtraction's own, eps (|lam2| + 2 v_g^2), and v_g^2's through omega^2's
    (``floor`` / lam relative, which a long acoustic wave of several fields magnifies)."""
    vg2 = lam1 ** 2 / (4 * lam)
    return abs(lam2 - 2 * vg2) > _EPS * (abs(lam2) + 2 * vg2) + 2 * vg2 * floor / lam


def smallest_resolved_k(model: Model, k: float, branch=None, of: str = "omega") -> float:
    """The smallest k (>= ``k``) at which float64 resolves the carrier of ``branch``:
    ``of`` "omega": omega^2 above its rounding floor (``_rounding_floor``); "g1": also
    g1's two terms lam2 - 2 v_g^2, which cancel on a long acoustic wave (g1 ~ k while each
    term ~ c^2), not equal within their rounding eps (|lam2| + 2 v_g^2). NaN where it is
    not resolved even at pi."""
    b = branch_index(model, k, branch)

    def resolved(kk):
        lam, _, H, s, lam1, lam2 = _carrier_parts(model, kk, b)
        floor = _rounding_floor(H, s, kk)
        if lam[b] <= floor:
            return False
        return of == "omega" or g1_resolved(lam[b], lam1, lam2, floor)

    found = _smallest_k(resolved, k)
    return math.nan if found is None else found


def carrier(model: Model, k: float, branch=None) -> Carrier:
    """The carrier of ``branch`` at ``k`` with its group velocity and g1 (perturbation
    theory of the Hermitian eigenproblem; checked against finite differences in tests)."""
    check_k(k)
    b = branch_index(model, k, branch)
    if why := rest_kink(model):
        raise ModelError(why)
    lam, vecs, H, s, lam1, lam2 = _carrier_parts(model, k, b)
    floor = _rounding_floor(H, s, k)
    if abs(lam[b]) <= floor:  # lost to rounding (or an underflow): neither > 0 nor < 0
        least = smallest_resolved_k(model, k, b)
        if least == least:
            raise ModelError(
                f"k = {k:.6g} is below what float64 resolves on branch {b} of model "
                f"{model.describe()}: omega^2 = {lam[b]:.3g} is within its rounding error "
                f"{floor:.2g} or underflows (not a missing carrier); give k (--k) >= {least:.3g}")
    if lam[b] <= 0:
        # a branch that carries a wave there, named (probe 99: a field in no energy is a
        # zero branch, the lowest, and the default; the error said no more)
        waves = [j for j in range(len(lam)) if lam[j] > floor]
        raise ModelError(f"model {model.describe()}: branch {b} has omega^2 = {lam[b]:.3g} "
                         f"<= 0 at k = {k:.6g}: no carrier wave there"
                         + (f"; branch {waves[0]} carries one: give branch (--branch) "
                            f"{waves[0]}" if waves else ""))
    omega = math.sqrt(lam[b])
    phi = vecs[:, b]
    others = [j for j in range(len(lam)) if j != b]
    gap = min((abs(math.sqrt(max(lam[j], 0)) - omega) for j in others), default=math.inf)
    # omega(pi + q) = omega(pi - q) (time reversal and the 2 pi period): v_g is 0 at the
    # zone boundary, not sin(pi)'s round-off (6e-17 printed as a soliton's velocity)
    vg = 0.0 if k == math.pi else lam1 / (2 * omega)
    g1 = (lam2 - 2 * vg**2) / (2 * omega)
    e = s * phi  # back from mass-weighted coordinates
    f = field_of(model, e, branch if isinstance(branch, str) and not branch.isdigit() else None)
    e = e / e[f]
    return Carrier(k=float(k), omega=omega, branch=b, field=f, e=e, group_velocity=float(vg),
                   g1=float(g1), gap=gap)


def field_of(model: Model, e: np.ndarray, name: str | None = None) -> int:
    """The field that carries the wave's amplitude: the field that named the branch (or the
    model's branch field) if it moves, else the field with most of the wave's kinetic
    energy m_f |e_f|^2 -- the weight ``branch_index`` names a branch by, so that
    ``--branch INDEX`` and ``--branch FIELD`` give one field for one branch (a heavy field
    can carry most of the energy with the smaller displacement)."""
    name = name or model.lattice.branch
    if name is not None:
        f = model.fields.index(name)
        if abs(e[f]) > 1e-8 * np.max(np.abs(e)):
            return f
    return int(np.argmax(np.asarray(model.masses, float) * np.abs(e) ** 2))


def field_rule(model: Model, branch=None, field: int | None = None) -> str:
    """Why the amplitude a measures the field it does (``field``, ``carrier``'s): a line
    for the outputs."""
    name = branch if isinstance(branch, str) and not branch.isdigit() else None
    named = name or model.lattice.branch
    if named is not None and (field is None or model.fields[field] == named):
        return (f"--branch {name} names the field" if name else
                f"the model's branch field {named}")
    if model.n_fields == 1:
        return "the model's only field"
    return "the field with most of the wave's kinetic energy m |e|^2"


def damping_matrix(model: Model, kappa: float) -> np.ndarray:
    """C(kappa) = C_site + B11 + B22 + B12 e^{i kappa} + B21 e^{-i kappa}: the damping
    force -C(kappa) v on a wave v_n = v e^{i kappa n} (zeros without [dissipation])."""
    S, B = model.damping
    return S.astype(complex) + dynamical_matrix(B, kappa)


def damping_matrices(model: Model, kappas) -> np.ndarray:
    """``damping_matrix`` at every kappa of a 1-d array, shape (n, d, d)."""
    S, B = model.damping
    d = S.shape[0]
    z = np.exp(1j * np.asarray(kappas, float))[:, None, None]
    return S + B[:d, :d] + B[d:, d:] + B[:d, d:] * z + B[d:, :d] / z


def damped_frequencies(model: Model, kappa: float) -> np.ndarray:
    """Complex omega_b(kappa) of every branch, ascending in Re omega: the roots of
    det(K - i omega C - omega^2 M) = 0 with Re omega >= 0 (a wave e^{i(kappa n - omega t)}
    decays as e^{Im(omega) t}). Companion linearisation in mass-weighted coordinates."""
    return _damped_many(model, np.array([float(kappa)]))[0]


# (weak reference to the model, its ``_damped_setup``): the last model's, one tuple (read
# and replaced whole, safe across threads)
_SETUP = [None]


def _damped_setup(model: Model):
    """The kappa-independent parts of ``_damped_many`` (the Taylor and damping blocks, the
    mass weights): computed once per model object, since a damped point's theories ask
    its rates several times (the same arrays, so the same numbers)."""
    import weakref

    last = _SETUP[0]
    if last is not None and last[0]() is model:
        return last[1]
    H = model.code.taylor(model.p)[0]
    S, B = model.damping
    m = model.masses
    s = 1 / np.sqrt(m)
    d = len(m)
    Hb = blocks(H, d)
    Bb = blocks(B, d)
    setup = (d, (Hb[0] + Hb[3]).astype(complex), Hb[1], Hb[2],
             (S + Bb[0] + Bb[3]).astype(complex), Bb[1], Bb[2],
             s[None, :, None] * s[None, None, :], np.eye(d))
    _SETUP[0] = (weakref.ref(model), setup)
    return setup


def _damped_many(model: Model, kappas: np.ndarray) -> np.ndarray:
    """damped_frequencies at every kappa of a 1-d array, shape (n, d): one batched
    eigenvalue call."""
    d, K0, K12, K21, C0, C12, C21, w2, eye = _damped_setup(model)
    z = np.exp(1j * kappas)[:, None, None]
    K = K0 + K12 * z + K21 / z
    C = C0 + C12 * z + C21 / z
    if d == 1:
        return _one_field_roots(K[:, 0, 0] * w2[0, 0, 0], -1j * C[:, 0, 0] * w2[0, 0, 0])
    L = np.zeros((kappas.size, 2 * d, 2 * d), complex)
    L[:, :d, d:] = eye
    L[:, d:, :d] = K * w2
    L[:, d:, d:] = -1j * C * w2
    w = np.linalg.eigvals(L)
    # the d roots of the forward waves: the largest real parts (an overdamped pair has
    # Re omega = 0: the slower-decaying root of the pair), every kappa at once
    order = np.lexsort((np.imag(w), np.round(np.real(w), 12)), axis=-1)[:, ::-1][:, :d]
    wi = np.take_along_axis(w, order, axis=-1)
    from ._damped_order import lossless_order  # each root to the branch it continues

    return lossless_order(K, C, w2, np.take_along_axis(wi, np.argsort(np.real(wi), axis=-1),
                                                       axis=-1))


def _one_field_roots(a, b) -> np.ndarray:
    """The forward root of one field's damped symbol, shape (n, 1): the companion matrix
    [[0, 1], [a, b]] (a = K / m, b = -i C / m) has the eigenvalues omega of
    omega^2 - b omega - a = 0, in closed form (no eigenvalue call: ~40x cheaper for a
    damped point's few hundred wavenumbers). The larger root without cancellation,
    (b + s) / 2 with s = +-sqrt(b^2 + 4a) of Re(conj(b) s) >= 0, the other from the
    product of the roots, -a; then ``_damped_many``'s choice: the larger real part
    (rounded to 1e-12), the larger imaginary part where they tie. Equal to LAPACK's to
    ~1e-15 of |omega| (tests/test_dissipation.py)."""
    s = np.sqrt(b * b + 4 * a)
    s = np.where(np.real(np.conj(b) * s) >= 0, s, -s)
    big = (b + s) / 2
    small = np.where(big != 0, -a / np.where(big != 0, big, 1.0), big)
    r1, r2 = np.round(np.real(big), 12), np.round(np.real(small), 12)
    first = (r1 > r2) | ((r1 == r2) & (np.imag(big) >= np.imag(small)))
    return np.where(first, big, small)[:, None]


def damping_rates(model: Model, kappa) -> np.ndarray:
    """Gamma_b(kappa) = -Im omega_b: each branch's amplitude decay rate (1/time), shape
    (..., d), ascending branches as :func:`branches`; zeros without [dissipation]."""
    kap = wavenumbers(kappa)  # a NaN was numpy's LinAlgError 'Array must not contain infs'
    out = np.zeros(kap.shape + (model.n_fields,))
    if not model.lossy:
        return out
    w = _damped_many(model, kap.ravel())
    flat = -np.imag(w)
    # zero damping (a lossy model at gamma = 0) leaves round-off of ~1e-16 omega in Im w,
    # which would read as a finite damping and an amplification of 1e304, not unbounded:
    # a rate below 1e-12 of the frequency (10^12 periods to decay) is none
    flat = np.where(np.abs(flat) <= 1e-12 * np.maximum(np.abs(np.real(w)), 1e-300), 0.0,
                    flat)
    return flat.reshape(kap.shape + (model.n_fields,))


def carrier_damping(model: Model, k: float, branch=None) -> float:
    """Gamma of the carrier's branch at k (0 without [dissipation]); k in (0, pi] as for
    :func:`carrier`."""
    check_k(k)
    if not model.lossy:
        return 0.0
    return float(damping_rates(model, k)[branch_index(model, k, branch)])
