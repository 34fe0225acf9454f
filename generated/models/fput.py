# -----------------------------------------------------------------------------
# GENERATED FILE - DO NOT EDIT BY HAND.
# Written by `make derive` (python -m derivation) from the energy of model 'fput'
# (SymPy 1.14.0). Regenerate, never edit.
# -----------------------------------------------------------------------------

"""Derivatives of the cell energy W(u_n, u_{n+1}) of model 'fput'.

Fermi-Pasta-Ulam-Tsingou alpha-beta chain: bond V(r) = r^2/2 + alpha r^3/3 + beta r^4/4

x = (u_n fields..., u_{n+1} fields...) (first axis), p = parameters in PARAMETERS
order. Every function works on floats (Numba) and on arrays of shape (2 d, ...)
(NumPy); the ``*_into`` forms write into ``out`` of shape (2 d[, 2 d], ...).
"""

import numpy

NAME = 'fput'
FIELDS = ('u',)
PARAMETERS = ('alpha', 'beta')
MODEL_HASH = 'fef35be8a26880c67c0ca296363dd13c36fe912d9d66a3ba3c604c3f4cafb6ff'


def masses(p):
    """Masses m_i of the fields (kinetic energy sum_i m_i u_t**2/2)."""
    alpha = p[0]
    beta = p[1]
    return numpy.array([1], dtype=float)


def cell_energy(x, p):
    """W = bond + site of the cell (n, n + 1)."""
    u = x[0]
    u_next = x[1]
    alpha = p[0]
    beta = p[1]
    _c0 = -u + u_next
    _w = (1/4)*_c0**4*beta + (1/3)*_c0**3*alpha + (1/2)*_c0**2
    return _w + 0.0 * x[0]


def cell_gradient_into(x, p, out):
    """out[a] = dW/dx_a."""
    u = x[0]
    u_next = x[1]
    alpha = p[0]
    beta = p[1]
    _c0 = -u + u_next
    _c1 = _c0**3*beta + _c0**2*alpha - u + u_next
    out[0] = -_c1
    out[1] = _c1


def cell_hessian_into(x, p, out):
    """out[a, b] = d^2 W/dx_a dx_b."""
    u = x[0]
    u_next = x[1]
    alpha = p[0]
    beta = p[1]
    _c0 = 2*u - 2*u_next
    _c1 = 3*beta*(-u + u_next)**2 + 1
    _c2 = -_c0*alpha + _c1
    _c3 = -_c0*alpha + _c1
    out[0, 0] = _c2
    out[0, 1] = -_c3
    out[1, 0] = -_c2
    out[1, 1] = _c3


def taylor(p):
    """Derivatives of W at rest: H (order 2), T (3), Q (4), symmetric arrays."""
    alpha = p[0]
    beta = p[1]
    H = numpy.zeros((2, 2))
    T = numpy.zeros((2, 2, 2))
    Q = numpy.zeros((2, 2, 2, 2))
    vals = {
        ('H', (0, 0)): 1,
        ('H', (0, 1)): -1,
        ('H', (1, 1)): 1,
        ('T', (0, 0, 0)): -2*alpha,
        ('T', (0, 0, 1)): 2*alpha,
        ('T', (0, 1, 1)): -2*alpha,
        ('T', (1, 1, 1)): 2*alpha,
        ('Q', (0, 0, 0, 0)): 6*beta,
        ('Q', (0, 0, 0, 1)): -6*beta,
        ('Q', (0, 0, 1, 1)): 6*beta,
        ('Q', (0, 1, 1, 1)): -6*beta,
        ('Q', (1, 1, 1, 1)): 6*beta,
    }
    arrays = {'H': H, 'T': T, 'Q': Q}
    for (name, idx), v in vals.items():
        for perm in _permutations(idx):
            arrays[name][perm] = v
    return H, T, Q


def _permutations(idx):
    import itertools
    return set(itertools.permutations(idx))
