# -----------------------------------------------------------------------------
# GENERATED FILE - DO NOT EDIT BY HAND.
# Written by `make derive` (python -m derivation) from the energy of model 'diatomic-fput'
# (SymPy 1.14.0). Regenerate, never edit.
# -----------------------------------------------------------------------------

"""Derivatives of the cell energy W(u_n, u_{n+1}) of model 'diatomic-fput'.

x = (u_n fields..., u_{n+1} fields...) (first axis), p = parameters in PARAMETERS
order. Every function works on floats (Numba) and on arrays of shape (2 d, ...)
(NumPy); the ``*_into`` forms write into ``out`` of shape (2 d[, 2 d], ...).
"""

import numpy

NAME = 'diatomic-fput'
FIELDS = ('u', 'v')
PARAMETERS = ('m', 'alpha', 'beta')
MODEL_HASH = '8b6daa83158d49fe5be4c3d4857eb800b2b5399b4776aded5f36b0b91665c09b'


def masses(_p):
    """Masses m_i of the fields (kinetic energy sum_i m_i u_t**2/2)."""
    m = _p[0]
    alpha = _p[1]
    beta = _p[2]
    return numpy.array([1, m], dtype=float)


def cell_energy(_x, _p):
    """W = bond + site of the cell (n, n + 1)."""
    u = _x[0]
    v = _x[1]
    u_next = _x[2]
    v_next = _x[3]
    m = _p[0]
    alpha = _p[1]
    beta = _p[2]
    _c0 = -v
    _c1 = -_c0 - u
    _c2 = _c0 + u_next
    _c3 = (1/3)*alpha
    _c4 = (1/4)*beta
    _w = _c1**4*_c4 + _c1**3*_c3 + (1/2)*_c1**2 + _c2**4*_c4 + _c2**3*_c3 + (1/2)*_c2**2
    return _w + 0.0 * _x[0]


def cell_gradient_into(_x, _p, _out):
    """out[a] = dW/dx_a."""
    u = _x[0]
    v = _x[1]
    u_next = _x[2]
    v_next = _x[3]
    m = _p[0]
    alpha = _p[1]
    beta = _p[2]
    _c0 = -v
    _c1 = -_c0 - u
    _c2 = _c1**2*alpha
    _c3 = _c1**3*beta
    _c4 = _c0 + u_next
    _c5 = _c4**3*beta + _c4**2*alpha
    _out[0] = -_c2 - _c3 + u - v
    _out[1] = _c2 + _c3 - _c5 - u - u_next + 2*v
    _out[2] = _c4 + _c5
    _out[3] = 0


SITE_FUNCTIONS_ALL = 0


def site_functions_all(_u, _p, _F):
    """F[i, n] = the i-th elementary function of site n's fields, every site."""
    m = _p[0]
    alpha = _p[1]
    beta = _p[2]
    for _n in range(_u.shape[1]):
        u = _u[0, _n]
        v = _u[1, _n]
        pass


def accelerations_into(_u, _F, _p, _out):
    """out[i, n] = d^2 u_{i,n}/dt^2 on a ring: the equations of motion, bond by bond (F from site_functions_all)."""
    _N = _u.shape[1]
    if _N == 0:
        return
    m = _p[0]
    alpha = _p[1]
    beta = _p[2]
    _r1 = m**(-1.0)
    v = _u[1, _N - 1]
    u_next = _u[0, 0]
    _c0 = u_next - v
    _c1 = _c0**3*beta + _c0**2*alpha + _c0
    _w1 = _c1
    _b0 = -_c1
    for _n in range(_N - 1):
        u = _u[0, _n]
        v = _u[1, _n]
        u_next = _u[0, _n + 1]
        _c0 = -v
        _c1 = _c0 + u_next
        _c2 = _c1**3*beta + _c1**2*alpha + _c1
        _c3 = -_c0 - u
        _c4 = _c3**3*beta + _c3**2*alpha - u + v
        _h1 = _c2
        _g0 = -_c2
        _s0 = _c4
        _s1 = -_c4
        _out[0, _n] = _b0 + _s0
        _out[1, _n] = (_h1 + _s1)*_r1
        _b0 = _g0
    u = _u[0, _N - 1]
    v = _u[1, _N - 1]
    _c0 = -u + v
    _c1 = _c0**3*beta + _c0**2*alpha - u + v
    _s0 = _c1
    _s1 = -_c1
    _out[0, _N - 1] = _b0 + _s0
    _out[1, _N - 1] = (_w1 + _s1)*_r1


def cell_hessian_into(_x, _p, _out):
    """out[a, b] = d^2 W/dx_a dx_b."""
    u = _x[0]
    v = _x[1]
    u_next = _x[2]
    v_next = _x[3]
    m = _p[0]
    alpha = _p[1]
    beta = _p[2]
    _c0 = -2*v
    _c1 = _c0 + 2*u
    _c2 = -v
    _c3 = 3*beta
    _c4 = _c3*(-_c2 - u)**2
    _c5 = _c4 + 1
    _c6 = -_c1*alpha + _c5
    _c7 = -_c1*alpha
    _c8 = _c0 + 2*u_next
    _c9 = _c8*alpha
    _c10 = _c3*(_c2 + u_next)**2
    _c11 = _c10 + 1
    _c12 = _c11 + _c8*alpha
    _out[0, 0] = _c6
    _out[0, 1] = -_c5 - _c7
    _out[0, 2] = 0
    _out[0, 3] = 0
    _out[1, 0] = -_c6
    _out[1, 1] = _c10 + _c4 + _c7 + _c9 + 2
    _out[1, 2] = -_c12
    _out[1, 3] = 0
    _out[2, 0] = 0
    _out[2, 1] = -_c11 - _c9
    _out[2, 2] = _c12
    _out[2, 3] = 0
    _out[3, 0] = 0
    _out[3, 1] = 0
    _out[3, 2] = 0
    _out[3, 3] = 0


def taylor(_p):
    """Derivatives of W at rest: H (order 2), T (3), Q (4), symmetric arrays."""
    m = _p[0]
    alpha = _p[1]
    beta = _p[2]
    _H = numpy.zeros((4, 4))
    _T = numpy.zeros((4, 4, 4))
    _Q = numpy.zeros((4, 4, 4, 4))
    _vals = {
        ('H', (0, 0)): 1,
        ('H', (0, 1)): -1,
        ('H', (1, 1)): 2,
        ('H', (1, 2)): -1,
        ('H', (2, 2)): 1,
        ('T', (0, 0, 0)): -2*alpha,
        ('T', (0, 0, 1)): 2*alpha,
        ('T', (0, 1, 1)): -2*alpha,
        ('T', (1, 1, 2)): 2*alpha,
        ('T', (1, 2, 2)): -2*alpha,
        ('T', (2, 2, 2)): 2*alpha,
        ('Q', (0, 0, 0, 0)): 6*beta,
        ('Q', (0, 0, 0, 1)): -6*beta,
        ('Q', (0, 0, 1, 1)): 6*beta,
        ('Q', (0, 1, 1, 1)): -6*beta,
        ('Q', (1, 1, 1, 1)): 12*beta,
        ('Q', (1, 1, 1, 2)): -6*beta,
        ('Q', (1, 1, 2, 2)): 6*beta,
        ('Q', (1, 2, 2, 2)): -6*beta,
        ('Q', (2, 2, 2, 2)): 6*beta,
    }
    _arrays = {'H': _H, 'T': _T, 'Q': _Q}
    for (_name, _idx), _v in _vals.items():
        for _perm in _permutations(_idx):
            _arrays[_name][_perm] = _v
    return _H, _T, _Q


def _permutations(idx):
    import itertools
    return set(itertools.permutations(idx))
# BODY_SHA256 = 2a8ac2bb3e570eb585ded85ce93adc44c69225bf8b80eadd6ce7becf6c1231ca
