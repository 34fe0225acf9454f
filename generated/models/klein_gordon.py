# -----------------------------------------------------------------------------
# GENERATED FILE - DO NOT EDIT BY HAND.
# Written by `make derive` (python -m derivation) from the energy of model 'klein-gordon'
# (SymPy 1.14.0). Regenerate, never edit.
# -----------------------------------------------------------------------------

"""Derivatives of the cell energy W(u_n, u_{n+1}) of model 'klein-gordon'.

phi^4 chain with a cubic term: site omega0^2 u^2/2 + alpha u^3/3 + beta u^4/4

x = (u_n fields..., u_{n+1} fields...) (first axis), p = parameters in PARAMETERS
order. Every function works on floats (Numba) and on arrays of shape (2 d, ...)
(NumPy); the ``*_into`` forms write into ``out`` of shape (2 d[, 2 d], ...).
"""

import numpy

NAME = 'klein-gordon'
FIELDS = ('u',)
PARAMETERS = ('C', 'omega0', 'alpha', 'beta')
MODEL_HASH = '9b1f4255b3436544833b4e6d2f15799d018732400dfc6b9a8d1385dca3346df3'


def masses(p):
    """Masses m_i of the fields (kinetic energy sum_i m_i u_t**2/2)."""
    C = p[0]
    omega0 = p[1]
    alpha = p[2]
    beta = p[3]
    return numpy.array([1], dtype=float)


def cell_energy(x, p):
    """W = bond + site of the cell (n, n + 1)."""
    u = x[0]
    u_next = x[1]
    C = p[0]
    omega0 = p[1]
    alpha = p[2]
    beta = p[3]
    _w = (1/2)*C*(-u + u_next)**2 + (1/3)*alpha*u**3 + (1/4)*beta*u**4 + (1/2)*omega0**2*u**2
    return _w + 0.0 * x[0]


def cell_gradient_into(x, p, out):
    """out[a] = dW/dx_a."""
    u = x[0]
    u_next = x[1]
    C = p[0]
    omega0 = p[1]
    alpha = p[2]
    beta = p[3]
    _c0 = 2*u - 2*u_next
    _c1 = (1/2)*C
    out[0] = _c0*_c1 + alpha*u**2 + beta*u**3 + omega0**2*u
    out[1] = -_c0*_c1


def cell_hessian_into(x, p, out):
    """out[a, b] = d^2 W/dx_a dx_b."""
    u = x[0]
    u_next = x[1]
    C = p[0]
    omega0 = p[1]
    alpha = p[2]
    beta = p[3]
    _c0 = -C
    out[0, 0] = C + 2*alpha*u + 3*beta*u**2 + omega0**2
    out[0, 1] = _c0
    out[1, 0] = _c0
    out[1, 1] = C


def taylor(p):
    """Derivatives of W at rest: H (order 2), T (3), Q (4), symmetric arrays."""
    C = p[0]
    omega0 = p[1]
    alpha = p[2]
    beta = p[3]
    H = numpy.zeros((2, 2))
    T = numpy.zeros((2, 2, 2))
    Q = numpy.zeros((2, 2, 2, 2))
    vals = {
        ('H', (0, 0)): C + omega0**2,
        ('H', (0, 1)): -C,
        ('H', (1, 1)): C,
        ('T', (0, 0, 0)): 2*alpha,
        ('Q', (0, 0, 0, 0)): 6*beta,
    }
    arrays = {'H': H, 'T': T, 'Q': Q}
    for (name, idx), v in vals.items():
        for perm in _permutations(idx):
            arrays[name][perm] = v
    return H, T, Q


def _permutations(idx):
    import itertools
    return set(itertools.permutations(idx))
