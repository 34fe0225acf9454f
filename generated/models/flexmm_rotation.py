# -----------------------------------------------------------------------------
# GENERATED FILE - DO NOT EDIT BY HAND.
# Written by `make derive` (python -m derivation) from the energy of model 'flexmm-rotation'
# (SymPy 1.14.0). Regenerate, never edit.
# -----------------------------------------------------------------------------

"""Derivatives of the cell energy W(u_n, u_{n+1}) of model 'flexmm-rotation'.

the paper's chain, case I (rotation): sliding frozen (U = 0), eq. norm

x = (u_n fields..., u_{n+1} fields...) (first axis), p = parameters in PARAMETERS
order. Every function works on floats (Numba) and on arrays of shape (2 d, ...)
(NumPy); the ``*_into`` forms write into ``out`` of shape (2 d[, 2 d], ...).
"""

import numpy

NAME = 'flexmm-rotation'
FIELDS = ('theta',)
PARAMETERS = ('alpha', 'K_s', 'K_theta')
MODEL_HASH = 'e16837568b3ece3752c731874e57f3865b77f41acd8188d2326c593bd2afad5e'


def masses(p):
    """Masses m_i of the fields (kinetic energy sum_i m_i u_t**2/2)."""
    alpha = p[0]
    K_s = p[1]
    K_theta = p[2]
    return numpy.array([alpha**(-2.0)], dtype=float)


def cell_energy(x, p):
    """W = bond + site of the cell (n, n + 1)."""
    theta = x[0]
    theta_next = x[1]
    alpha = p[0]
    K_s = p[1]
    K_theta = p[2]
    _w = (1/2)*K_s*(-numpy.sin(theta) + numpy.sin(theta_next))**2 + K_theta*theta**2 + (1/2)*K_theta*(theta + theta_next)**2 + 2*(-1/2*numpy.cos(theta) - 1/2*numpy.cos(theta_next) + 1)**2
    return _w + 0.0 * x[0]


def cell_gradient_into(x, p, out):
    """out[a] = dW/dx_a."""
    theta = x[0]
    theta_next = x[1]
    alpha = p[0]
    K_s = p[1]
    K_theta = p[2]
    _c0 = 2*theta
    _c1 = (1/2)*K_theta*(_c0 + 2*theta_next)
    _c2 = numpy.cos(theta)
    _c3 = numpy.sin(theta)
    _c4 = numpy.sin(theta_next)
    _c5 = K_s*(-_c3 + _c4)
    _c6 = numpy.cos(theta_next)
    _c7 = -_c2 - _c6 + 2
    out[0] = K_theta*_c0 + _c1 - _c2*_c5 + _c3*_c7
    out[1] = _c1 + _c4*_c7 + _c5*_c6


def cell_hessian_into(x, p, out):
    """out[a, b] = d^2 W/dx_a dx_b."""
    theta = x[0]
    theta_next = x[1]
    alpha = p[0]
    K_s = p[1]
    K_theta = p[2]
    _c0 = numpy.sin(theta)
    _c1 = numpy.cos(theta)
    _c2 = numpy.sin(theta_next)
    _c3 = K_s*(-_c0 + _c2)
    _c4 = numpy.cos(theta_next)
    _c5 = -_c1 - _c4 + 2
    _c6 = -K_s*_c1*_c4 + K_theta + _c0*_c2
    out[0, 0] = K_s*_c1**2 + 3*K_theta + _c0**2 + _c0*_c3 + _c1*_c5
    out[0, 1] = _c6
    out[1, 0] = _c6
    out[1, 1] = K_s*_c4**2 + K_theta + _c2**2 - _c2*_c3 + _c4*_c5


def taylor(p):
    """Derivatives of W at rest: H (order 2), T (3), Q (4), symmetric arrays."""
    alpha = p[0]
    K_s = p[1]
    K_theta = p[2]
    H = numpy.zeros((2, 2))
    T = numpy.zeros((2, 2, 2))
    Q = numpy.zeros((2, 2, 2, 2))
    vals = {
        ('H', (0, 0)): K_s + 3*K_theta,
        ('H', (0, 1)): -K_s + K_theta,
        ('H', (1, 1)): K_s + K_theta,
        ('Q', (0, 0, 0, 0)): 3 - 4*K_s,
        ('Q', (0, 0, 0, 1)): K_s,
        ('Q', (0, 0, 1, 1)): 1,
        ('Q', (0, 1, 1, 1)): K_s,
        ('Q', (1, 1, 1, 1)): 3 - 4*K_s,
    }
    arrays = {'H': H, 'T': T, 'Q': Q}
    for (name, idx), v in vals.items():
        for perm in _permutations(idx):
            arrays[name][perm] = v
    return H, T, Q


def _permutations(idx):
    import itertools
    return set(itertools.permutations(idx))
