# -----------------------------------------------------------------------------
# GENERATED FILE - DO NOT EDIT BY HAND.
# Written by `make derive` (python -m derivation) from the energy of model 'fput'
# (SymPy 1.14.0). Regenerate, never edit.
# -----------------------------------------------------------------------------

"""Derivatives of the cell energy W(u_n, u_{n+1}) of model 'fput'.

x = (u_n fields..., u_{n+1} fields...) (first axis), p = parameters in PARAMETERS
order. Every function works on floats (Numba) and on arrays of shape (2 d, ...)
(NumPy); the ``*_into`` forms write into ``out`` of shape (2 d[, 2 d], ...).
"""

import numpy

NAME = 'fput'
FIELDS = ('u',)
PARAMETERS = ('alpha', 'beta')
MODEL_HASH = 'fef35be8a26880c67c0ca296363dd13c36fe912d9d66a3ba3c604c3f4cafb6ff'


def masses(_p):
    """Masses m_i of the fields (kinetic energy sum_i m_i u_t**2/2)."""
    alpha = _p[0]
    beta = _p[1]
    return numpy.array([1], dtype=float)


def cell_energy(_x, _p):
    """W = bond + site of the cell (n, n + 1)."""
    u = _x[0]
    u_next = _x[1]
    alpha = _p[0]
    beta = _p[1]
    _c0 = -u + u_next
    _w = (1/4)*_c0**4*beta + (1/3)*_c0**3*alpha + (1/2)*_c0**2
    return _w + 0.0 * _x[0]


def cell_gradient_into(_x, _p, _out):
    """out[a] = dW/dx_a."""
    u = _x[0]
    u_next = _x[1]
    alpha = _p[0]
    beta = _p[1]
    _c0 = -u + u_next
    _c1 = _c0**3*beta + _c0**2*alpha - u + u_next
    _out[0] = -_c1
    _out[1] = _c1


SITE_FUNCTIONS_ALL = 0


def site_functions_all(_u, _p, _F):
    """F[i, n] = the i-th elementary function of site n's fields, every site."""
    alpha = _p[0]
    beta = _p[1]
    for _n in range(_u.shape[1]):
        u = _u[0, _n]
        pass


def accelerations_into(_u, _F, _p, _out):
    """out[i, n] = d^2 u_{i,n}/dt^2 on a ring: the equations of motion, bond by bond (F from site_functions_all)."""
    _N = _u.shape[1]
    if _N == 0:
        return
    alpha = _p[0]
    beta = _p[1]
    u = _u[0, _N - 1]
    u_next = _u[0, 0]
    _c0 = -u + u_next
    _w0 = _c0**3*beta + _c0**2*alpha - u + u_next
    _b0 = _w0
    for _n in range(_N - 1):
        u = _u[0, _n]
        u_next = _u[0, _n + 1]
        _c0 = -u + u_next
        _h0 = _c0**3*beta + _c0**2*alpha - u + u_next
        _out[0, _n] = _h0 - _b0
        _b0 = _h0
    _out[0, _N - 1] = _w0 - _b0


def cell_hessian_into(_x, _p, _out):
    """out[a, b] = d^2 W/dx_a dx_b."""
    u = _x[0]
    u_next = _x[1]
    alpha = _p[0]
    beta = _p[1]
    _c0 = 2*u - 2*u_next
    _c1 = 3*beta*(-u + u_next)**2 + 1
    _c2 = -_c0*alpha + _c1
    _c3 = -_c0*alpha + _c1
    _out[0, 0] = _c2
    _out[0, 1] = -_c3
    _out[1, 0] = -_c2
    _out[1, 1] = _c3


def taylor(_p):
    """Derivatives of W at rest: H (order 2), T (3), Q (4), symmetric arrays."""
    alpha = _p[0]
    beta = _p[1]
    _H = numpy.zeros((2, 2))
    _T = numpy.zeros((2, 2, 2))
    _Q = numpy.zeros((2, 2, 2, 2))
    _vals = {
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
    _arrays = {'H': _H, 'T': _T, 'Q': _Q}
    for (_name, _idx), _v in _vals.items():
        for _perm in _permutations(_idx):
            _arrays[_name][_perm] = _v
    return _H, _T, _Q


def _permutations(idx):
    import itertools
    return set(itertools.permutations(idx))
# BODY_SHA256 = 28f98c8f75188932a690ce515ce956eebd3514779754b242f6e8933f4936e3d8
