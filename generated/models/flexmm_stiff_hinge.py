# -----------------------------------------------------------------------------
# GENERATED FILE - DO NOT EDIT BY HAND.
# Written by `make derive` (python -m derivation) from the energy of model 'flexmm-stiff-hinge'
# (SymPy 1.14.0). Regenerate, never edit.
# -----------------------------------------------------------------------------

"""Derivatives of the cell energy W(u_n, u_{n+1}) of model 'flexmm-stiff-hinge'.

x = (u_n fields..., u_{n+1} fields...) (first axis), p = parameters in PARAMETERS
order. Every function works on floats (Numba) and on arrays of shape (2 d, ...)
(NumPy); the ``*_into`` forms write into ``out`` of shape (2 d[, 2 d], ...).
"""

import numpy

NAME = 'flexmm-stiff-hinge'
FIELDS = ('theta', 'U')
PARAMETERS = ('alpha', 'K_s', 'K_theta', 'K_3')
MODEL_HASH = '0f7b1f531fdc33b7c80bc19d11cc2eba15f0e7bb12c9fb73fc1949564fecf8c1'


def masses(_p):
    """Masses m_i of the fields (kinetic energy sum_i m_i u_t**2/2)."""
    alpha = _p[0]
    K_s = _p[1]
    K_theta = _p[2]
    K_3 = _p[3]
    return numpy.array([alpha**(-2.0), 4], dtype=float)


def cell_energy(_x, _p):
    """W = bond + site of the cell (n, n + 1)."""
    theta = _x[0]
    U = _x[1]
    theta_next = _x[2]
    U_next = _x[3]
    alpha = _p[0]
    K_s = _p[1]
    K_theta = _p[2]
    K_3 = _p[3]
    _c0 = theta + theta_next
    _w = (1/4)*K_3*_c0**4 + (1/2)*K_3*theta**4 + (1/2)*K_s*(-numpy.sin(theta) + numpy.sin(theta_next))**2 + (1/2)*K_theta*_c0**2 + K_theta*theta**2 + 2*(-U + U_next - 1/2*numpy.cos(theta) - 1/2*numpy.cos(theta_next) + 1)**2
    return _w + 0.0 * _x[0]


def cell_gradient_into(_x, _p, _out):
    """out[a] = dW/dx_a."""
    theta = _x[0]
    U = _x[1]
    theta_next = _x[2]
    U_next = _x[3]
    alpha = _p[0]
    K_s = _p[1]
    K_theta = _p[2]
    K_3 = _p[3]
    _c0 = 2*theta
    _c1 = numpy.sin(theta)
    _c2 = numpy.cos(theta)
    _c3 = numpy.cos(theta_next)
    _c4 = -2*U + 2*U_next - _c2 - _c3 + 2
    _c5 = numpy.sin(theta_next)
    _c6 = K_s*(-_c1 + _c5)
    _c7 = K_3*(theta + theta_next)**3 + (1/2)*K_theta*(_c0 + 2*theta_next)
    _c8 = 4*U - 4*U_next + 2*_c2 + 2*_c3 - 4
    _out[0] = 2*K_3*theta**3 + K_theta*_c0 + _c1*_c4 - _c2*_c6 + _c7
    _out[1] = _c8
    _out[2] = _c3*_c6 + _c4*_c5 + _c7
    _out[3] = -_c8


SITE_FUNCTIONS_ALL = 2


def site_functions_all(_u, _p, _F):
    """F[i, n] = the i-th elementary function of site n's fields, every site."""
    alpha = _p[0]
    K_s = _p[1]
    K_theta = _p[2]
    K_3 = _p[3]
    for _n in range(_u.shape[1]):
        theta = _u[0, _n]
        U = _u[1, _n]
        _F[0, _n] = numpy.cos(theta)
        _F[1, _n] = numpy.sin(theta)


def accelerations_into(_u, _F, _p, _out):
    """out[i, n] = d^2 u_{i,n}/dt^2 on a ring: the equations of motion, bond by bond (F from site_functions_all)."""
    _N = _u.shape[1]
    if _N == 0:
        return
    alpha = _p[0]
    K_s = _p[1]
    K_theta = _p[2]
    K_3 = _p[3]
    _r0 = alpha**2
    _r1 = 1/4
    theta = _u[0, _N - 1]
    U = _u[1, _N - 1]
    _fn0 = _F[0, _N - 1]
    _fn1 = _F[1, _N - 1]
    theta_next = _u[0, 0]
    U_next = _u[1, 0]
    _fl0 = _F[0, 0]
    _fl1 = _F[1, 0]
    _c0 = -2*U + 2*U_next - _fl0 - _fn0 + 2
    _c1 = _fl1 - _fn1
    _c2 = K_3*(theta + theta_next)**3 + (1/2)*K_theta*(2*theta + 2*theta_next)
    _w0 = K_s*_c1*_fn0 - _c0*_fn1 - _c2
    _w1 = -4*U + 4*U_next - 2*_fl0 - 2*_fn0 + 4
    _b0 = -K_s*_c1*_fl0 - _c0*_fl1 - _c2
    _b1 = _w1
    for _n in range(_N - 1):
        theta = _u[0, _n]
        U = _u[1, _n]
        _fn0 = _F[0, _n]
        _fn1 = _F[1, _n]
        theta_next = _u[0, _n + 1]
        U_next = _u[1, _n + 1]
        _fl0 = _F[0, _n + 1]
        _fl1 = _F[1, _n + 1]
        _c0 = -2*U + 2*U_next - _fl0 - _fn0 + 2
        _c1 = _fl1 - _fn1
        _c2 = 2*theta
        _c3 = K_3*(theta + theta_next)**3 + (1/2)*K_theta*(_c2 + 2*theta_next)
        _h0 = K_s*_c1*_fn0 - _c0*_fn1 - _c3
        _h1 = -4*U + 4*U_next - 2*_fl0 - 2*_fn0 + 4
        _g0 = -K_s*_c1*_fl0 - _c0*_fl1 - _c3
        _s0 = -2*K_3*theta**3 - K_theta*_c2
        _out[0, _n] = (_b0 + _h0 + _s0)*_r0
        _out[1, _n] = (_h1 - _b1)*_r1
        _b0 = _g0
        _b1 = _h1
    theta = _u[0, _N - 1]
    _s0 = -2*K_3*theta**3 - 2*K_theta*theta
    _out[0, _N - 1] = (_b0 + _w0 + _s0)*_r0
    _out[1, _N - 1] = (_w1 - _b1)*_r1


def cell_hessian_into(_x, _p, _out):
    """out[a, b] = d^2 W/dx_a dx_b."""
    theta = _x[0]
    U = _x[1]
    theta_next = _x[2]
    U_next = _x[3]
    alpha = _p[0]
    K_s = _p[1]
    K_theta = _p[2]
    K_3 = _p[3]
    _c0 = numpy.sin(theta)
    _c1 = numpy.cos(theta)
    _c2 = 3*K_3*(theta + theta_next)**2
    _c3 = numpy.sin(theta_next)
    _c4 = K_s*(-_c0 + _c3)
    _c5 = numpy.cos(theta_next)
    _c6 = -2*U + 2*U_next - _c1 - _c5 + 2
    _c7 = 2*_c0
    _c8 = -_c7
    _c9 = K_theta + _c2
    _c10 = -K_s*_c1*_c5 + _c0*_c3 + _c9
    _c11 = 2*_c3
    _c12 = -_c11
    _out[0, 0] = 6*K_3*theta**2 + K_s*_c1**2 + 3*K_theta + _c0**2 + _c0*_c4 + _c1*_c6 + _c2
    _out[0, 1] = _c8
    _out[0, 2] = _c10
    _out[0, 3] = _c7
    _out[1, 0] = _c8
    _out[1, 1] = 4
    _out[1, 2] = _c12
    _out[1, 3] = -4
    _out[2, 0] = _c10
    _out[2, 1] = _c12
    _out[2, 2] = K_s*_c5**2 + _c3**2 - _c3*_c4 + _c5*_c6 + _c9
    _out[2, 3] = _c11
    _out[3, 0] = _c7
    _out[3, 1] = -4
    _out[3, 2] = _c11
    _out[3, 3] = 4


def taylor(_p):
    """Derivatives of W at rest: H (order 2), T (3), Q (4), symmetric arrays."""
    alpha = _p[0]
    K_s = _p[1]
    K_theta = _p[2]
    K_3 = _p[3]
    _H = numpy.zeros((4, 4))
    _T = numpy.zeros((4, 4, 4))
    _Q = numpy.zeros((4, 4, 4, 4))
    _vals = {
        ('H', (0, 0)): K_s + 3*K_theta,
        ('H', (0, 2)): -K_s + K_theta,
        ('H', (1, 1)): 4,
        ('H', (1, 3)): -4,
        ('H', (2, 2)): K_s + K_theta,
        ('H', (3, 3)): 4,
        ('T', (0, 0, 1)): -2,
        ('T', (0, 0, 3)): 2,
        ('T', (1, 2, 2)): -2,
        ('T', (2, 2, 3)): 2,
        ('Q', (0, 0, 0, 0)): 18*K_3 - 4*K_s + 3,
        ('Q', (0, 0, 0, 2)): 6*K_3 + K_s,
        ('Q', (0, 0, 2, 2)): 6*K_3 + 1,
        ('Q', (0, 2, 2, 2)): 6*K_3 + K_s,
        ('Q', (2, 2, 2, 2)): 6*K_3 - 4*K_s + 3,
    }
    _arrays = {'H': _H, 'T': _T, 'Q': _Q}
    for (_name, _idx), _v in _vals.items():
        for _perm in _permutations(_idx):
            _arrays[_name][_perm] = _v
    return _H, _T, _Q


def _permutations(idx):
    import itertools
    return set(itertools.permutations(idx))
# BODY_SHA256 = bcd9e9d1f632f66bc497027a4b61729d85e882335f9006169d3320a0c322717f
