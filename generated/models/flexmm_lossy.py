# -----------------------------------------------------------------------------
# GENERATED FILE - DO NOT EDIT BY HAND.
# Written by `make derive` (python -m derivation) from the energy of model 'flexmm-lossy'
# (SymPy 1.14.0). Regenerate, never edit.
# -----------------------------------------------------------------------------

"""Derivatives of the cell energy W(u_n, u_{n+1}) of model 'flexmm-lossy'.

x = (u_n fields..., u_{n+1} fields...) (first axis), p = parameters in PARAMETERS
order. Every function works on floats (Numba) and on arrays of shape (2 d, ...)
(NumPy); the ``*_into`` forms write into ``out`` of shape (2 d[, 2 d], ...).
"""

import numpy

NAME = 'flexmm-lossy'
FIELDS = ('theta', 'U')
PARAMETERS = ('alpha', 'K_s', 'K_theta', 'gamma_theta', 'gamma_U')
MODEL_HASH = '89a2111936eed7fe59bfdeb4d1b92942135b7e85c2ed41bb1aee07090aae2783'


def masses(_p):
    """Masses m_i of the fields (kinetic energy sum_i m_i u_t**2/2)."""
    alpha = _p[0]
    K_s = _p[1]
    K_theta = _p[2]
    gamma_theta = _p[3]
    gamma_U = _p[4]
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
    gamma_theta = _p[3]
    gamma_U = _p[4]
    _w = (1/2)*K_s*(-numpy.sin(theta) + numpy.sin(theta_next))**2 + K_theta*theta**2 + (1/2)*K_theta*(theta + theta_next)**2 + 2*(-U + U_next - 1/2*numpy.cos(theta) - 1/2*numpy.cos(theta_next) + 1)**2
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
    gamma_theta = _p[3]
    gamma_U = _p[4]
    _c0 = 2*theta
    _c1 = (1/2)*K_theta*(_c0 + 2*theta_next)
    _c2 = numpy.cos(theta)
    _c3 = numpy.sin(theta)
    _c4 = numpy.sin(theta_next)
    _c5 = K_s*(-_c3 + _c4)
    _c6 = numpy.cos(theta_next)
    _c7 = -2*U + 2*U_next - _c2 - _c6 + 2
    _c8 = 4*U - 4*U_next + 2*_c2 + 2*_c6 - 4
    _out[0] = K_theta*_c0 + _c1 - _c2*_c5 + _c3*_c7
    _out[1] = _c8
    _out[2] = _c1 + _c4*_c7 + _c5*_c6
    _out[3] = -_c8


SITE_FUNCTIONS_ALL = 2


def site_functions_all(_u, _p, _F):
    """F[i, n] = the i-th elementary function of site n's fields, every site."""
    alpha = _p[0]
    K_s = _p[1]
    K_theta = _p[2]
    gamma_theta = _p[3]
    gamma_U = _p[4]
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
    gamma_theta = _p[3]
    gamma_U = _p[4]
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
    _c0 = _fl1 - _fn1
    _c1 = (1/2)*K_theta*(2*theta + 2*theta_next)
    _c2 = -2*U + 2*U_next - _fl0 - _fn0 + 2
    _w0 = K_s*_c0*_fn0 - _c1 - _c2*_fn1
    _w1 = -4*U + 4*U_next - 2*_fl0 - 2*_fn0 + 4
    _b0 = -K_s*_c0*_fl0 - _c1 - _c2*_fl1
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
        _c0 = _fl1 - _fn1
        _c1 = 2*theta
        _c2 = (1/2)*K_theta*(_c1 + 2*theta_next)
        _c3 = -2*U + 2*U_next - _fl0 - _fn0 + 2
        _h0 = K_s*_c0*_fn0 - _c2 - _c3*_fn1
        _h1 = -4*U + 4*U_next - 2*_fl0 - 2*_fn0 + 4
        _g0 = -K_s*_c0*_fl0 - _c2 - _c3*_fl1
        _s0 = -K_theta*_c1
        _out[0, _n] = (_b0 + _h0 + _s0)*_r0
        _out[1, _n] = (_h1 - _b1)*_r1
        _b0 = _g0
        _b1 = _h1
    theta = _u[0, _N - 1]
    _s0 = -2*K_theta*theta
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
    gamma_theta = _p[3]
    gamma_U = _p[4]
    _c0 = numpy.sin(theta)
    _c1 = numpy.cos(theta)
    _c2 = numpy.sin(theta_next)
    _c3 = K_s*(-_c0 + _c2)
    _c4 = numpy.cos(theta_next)
    _c5 = -2*U + 2*U_next - _c1 - _c4 + 2
    _c6 = 2*_c0
    _c7 = -_c6
    _c8 = -K_s*_c1*_c4 + K_theta + _c0*_c2
    _c9 = 2*_c2
    _c10 = -_c9
    _out[0, 0] = K_s*_c1**2 + 3*K_theta + _c0**2 + _c0*_c3 + _c1*_c5
    _out[0, 1] = _c7
    _out[0, 2] = _c8
    _out[0, 3] = _c6
    _out[1, 0] = _c7
    _out[1, 1] = 4
    _out[1, 2] = _c10
    _out[1, 3] = -4
    _out[2, 0] = _c8
    _out[2, 1] = _c10
    _out[2, 2] = K_s*_c4**2 + K_theta + _c2**2 - _c2*_c3 + _c4*_c5
    _out[2, 3] = _c9
    _out[3, 0] = _c6
    _out[3, 1] = -4
    _out[3, 2] = _c9
    _out[3, 3] = 4


def taylor(_p):
    """Derivatives of W at rest: H (order 2), T (3), Q (4), symmetric arrays."""
    alpha = _p[0]
    K_s = _p[1]
    K_theta = _p[2]
    gamma_theta = _p[3]
    gamma_U = _p[4]
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
        ('Q', (0, 0, 0, 0)): 3 - 4*K_s,
        ('Q', (0, 0, 0, 2)): K_s,
        ('Q', (0, 0, 2, 2)): 1,
        ('Q', (0, 2, 2, 2)): K_s,
        ('Q', (2, 2, 2, 2)): 3 - 4*K_s,
    }
    _arrays = {'H': _H, 'T': _T, 'Q': _Q}
    for (_name, _idx), _v in _vals.items():
        for _perm in _permutations(_idx):
            _arrays[_name][_perm] = _v
    return _H, _T, _Q


def _permutations(idx):
    import itertools
    return set(itertools.permutations(idx))



def damping_matrices(_p):
    """(C_site (d, d), C_bond (2 d, 2 d)): Hessians of the Rayleigh functions in the velocities."""
    alpha = _p[0]
    K_s = _p[1]
    K_theta = _p[2]
    gamma_theta = _p[3]
    gamma_U = _p[4]
    _S = numpy.zeros((2, 2))
    _B = numpy.zeros((4, 4))
    _S[0, 0] = gamma_theta
    _S[1, 1] = gamma_U
    return _S, _B
# BODY_SHA256 = 34bb2e9c224a204a1d9fc9e70d5442f1c5c1b3b819b8c324721df48e38c42559
