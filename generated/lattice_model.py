# -----------------------------------------------------------------------------
# GENERATED FILE - DO NOT EDIT BY HAND.
# Written by `make derive` (python -m derivation --out generated) from the
# SymPy derivation in derivation/ (SymPy 1.14.0). Regenerate, never edit.
# -----------------------------------------------------------------------------

"""Eq. `norm` of Demiquel, Achilleos, Theocharis & Tournat as NumPy functions.

Generated from the SymPy text of the discrete equations (derivation/_continuum.py,
``lattice_accelerations``): the accelerations of site n from its neighbourhood
(U_m, U_0, U_p) = (U_{n-1}, U_n, U_{n+1}), likewise theta; their Jacobian with respect
to the six neighbour values (by ``sympy.diff``); and the two branches of the linear
lattice (eqs. `discrete1`, `discrete2`), derived from the Jacobian at rest.
Arguments broadcast like NumPy; theta in rad, time in units of sqrt(m / k_l).
"""

import numpy

__all__ = ['acceleration_U', 'acceleration_theta', 'jacobian', 'omega_longitudinal', 'omega_rotation']


def _real(name, value):
    """``value`` as a float array; TypeError naming ``name`` unless it holds real numbers
    (a bool, a string or a complex number is refused, not cast)."""
    a = numpy.asarray(value)
    if a.dtype.kind not in "fiu":
        raise TypeError(f"{name} must hold real numbers, got {type(value).__name__} "
                        f"{value!r}"[:200])
    return a.astype(float, copy=False)


def acceleration_U(U_m, U_0, U_p, theta_m, theta_0, theta_p, alpha, K_s, K_theta):
    r"""d^2 U_n / dT^2 from the neighbourhood of site n.

    Paper: eq. `norm`. Derived closed form:

    .. math:: - 2 U_{0} + U_{m} + U_{p} + \frac{\cos{\left(\theta_{m} \right)}}{2} - \frac{\cos{\left(\theta_{p} \right)}}{2}

    Parameters are floats or arrays (NumPy broadcasting); singular points
    give inf/nan with NumPy's RuntimeWarning, never an exception.
    """
    U_m = _real('U_m', U_m)
    U_0 = _real('U_0', U_0)
    U_p = _real('U_p', U_p)
    theta_m = _real('theta_m', theta_m)
    theta_0 = _real('theta_0', theta_0)
    theta_p = _real('theta_p', theta_p)
    alpha = _real('alpha', alpha)
    K_s = _real('K_s', K_s)
    K_theta = _real('K_theta', K_theta)
    return -2*U_0 + U_m + U_p + (1/2)*numpy.cos(theta_m) - 1/2*numpy.cos(theta_p)


def acceleration_theta(U_m, U_0, U_p, theta_m, theta_0, theta_p, alpha, K_s, K_theta):
    r"""d^2 theta_n / dT^2 (alpha^2 included) from the neighbourhood of site n.

    Paper: eq. `norm`. Derived closed form:

    .. math:: \alpha^{2} \left(K_{s} \left(- 2 \sin{\left(\theta_{0} \right)} + \sin{\left(\theta_{m} \right)} + \sin{\left(\theta_{p} \right)}\right) \cos{\left(\theta_{0} \right)} - K_{\theta} \left(4 \theta_{0} + \theta_{m} + \theta_{p}\right) - \left(- 2 U_{m} + 2 U_{p} - 2 \cos{\left(\theta_{0} \right)} - \cos{\left(\theta_{m} \right)} - \cos{\left(\theta_{p} \right)} + 4\right) \sin{\left(\theta_{0} \right)}\right)

    Parameters are floats or arrays (NumPy broadcasting); singular points
    give inf/nan with NumPy's RuntimeWarning, never an exception.
    """
    U_m = _real('U_m', U_m)
    U_0 = _real('U_0', U_0)
    U_p = _real('U_p', U_p)
    theta_m = _real('theta_m', theta_m)
    theta_0 = _real('theta_0', theta_0)
    theta_p = _real('theta_p', theta_p)
    alpha = _real('alpha', alpha)
    K_s = _real('K_s', K_s)
    K_theta = _real('K_theta', K_theta)
    x0 = numpy.cos(theta_0)
    x1 = numpy.sin(theta_0)
    return alpha**2*(K_s*x0*(-2*x1 + numpy.sin(theta_m) + numpy.sin(theta_p)) - K_theta*(4*theta_0 + theta_m + theta_p) - x1*(-2*U_m + 2*U_p - 2*x0 - numpy.cos(theta_m) - numpy.cos(theta_p) + 4))


def jacobian(U_m, U_0, U_p, theta_m, theta_0, theta_p, alpha, K_s, K_theta):
    r"""Jacobian of (acceleration_U, acceleration_theta) with respect to (U_m, U_0, U_p, theta_m, theta_0, theta_p): shape (2, 6) + the broadcast shape of the arguments.

    Paper: eq. `norm`. Derived closed form:

    .. math:: \left[\begin{matrix}1 & -2 & 1 & - \frac{\sin{\left(\theta_{m} \right)}}{2} & 0 & \frac{\sin{\left(\theta_{p} \right)}}{2}\\2 \alpha^{2} \sin{\left(\theta_{0} \right)} & 0 & - 2 \alpha^{2} \sin{\left(\theta_{0} \right)} & \alpha^{2} \left(K_{s} \cos{\left(\theta_{0} \right)} \cos{\left(\theta_{m} \right)} - K_{\theta} - \sin{\left(\theta_{0} \right)} \sin{\left(\theta_{m} \right)}\right) & \alpha^{2} \left(- K_{s} \left(- 2 \sin{\left(\theta_{0} \right)} + \sin{\left(\theta_{m} \right)} + \sin{\left(\theta_{p} \right)}\right) \sin{\left(\theta_{0} \right)} - 2 K_{s} \cos^{2}{\left(\theta_{0} \right)} - 4 K_{\theta} - \left(- 2 U_{m} + 2 U_{p} - 2 \cos{\left(\theta_{0} \right)} - \cos{\left(\theta_{m} \right)} - \cos{\left(\theta_{p} \right)} + 4\right) \cos{\left(\theta_{0} \right)} - 2 \sin^{2}{\left(\theta_{0} \right)}\right) & \alpha^{2} \left(K_{s} \cos{\left(\theta_{0} \right)} \cos{\left(\theta_{p} \right)} - K_{\theta} - \sin{\left(\theta_{0} \right)} \sin{\left(\theta_{p} \right)}\right)\end{matrix}\right]

    Parameters are floats or arrays (NumPy broadcasting); singular points
    give inf/nan with NumPy's RuntimeWarning, never an exception.
    """
    U_m = _real('U_m', U_m)
    U_0 = _real('U_0', U_0)
    U_p = _real('U_p', U_p)
    theta_m = _real('theta_m', theta_m)
    theta_0 = _real('theta_0', theta_0)
    theta_p = _real('theta_p', theta_p)
    alpha = _real('alpha', alpha)
    K_s = _real('K_s', K_s)
    K_theta = _real('K_theta', K_theta)
    x0 = numpy.sin(theta_m)
    x1 = numpy.sin(theta_p)
    x2 = alpha**2
    x3 = numpy.sin(theta_0)
    x4 = 2*x3
    x5 = x2*x4
    x6 = numpy.cos(theta_0)
    x7 = numpy.cos(theta_m)
    x8 = numpy.cos(theta_p)
    entries = numpy.broadcast_arrays(U_m, U_0, U_p, theta_m, theta_0, theta_p, alpha, K_s, K_theta, 1, -2, 1, -1/2*x0, 0, (1/2)*x1, x5, 0, -x5, x2*(K_s*x6*x7 - K_theta - x0*x3), x2*(-K_s*x3*(x0 + x1 - x4) - 2*K_s*x6**2 - 4*K_theta - 2*x3**2 - x6*(-2*U_m + 2*U_p - 2*x6 - x7 - x8 + 4)), x2*(K_s*x6*x8 - K_theta - x1*x3))[9:]
    return numpy.stack(entries).reshape((2, 6) + entries[0].shape)


def omega_longitudinal(q):
    r"""Longitudinal branch of the linear lattice, omega_U(q) >= 0.

    Paper: eq. `discrete1`. Derived closed form:

    .. math:: 2 \left|{\sin{\left(\frac{q}{2} \right)}}\right|

    Parameters are floats or arrays (NumPy broadcasting); singular points
    give inf/nan with NumPy's RuntimeWarning, never an exception.
    """
    q = _real('q', q)
    return 2*numpy.abs(numpy.sin((1/2)*q))


def omega_rotation(q, alpha, K_s, K_theta):
    r"""Rotational branch of the linear lattice, omega_theta(q) > 0.

    Paper: eq. `discrete2`. Derived closed form:

    .. math:: \sqrt{6 K_{\theta} \alpha^{2} + \left(4 K_{s} \alpha^{2} - 4 K_{\theta} \alpha^{2}\right) \sin^{2}{\left(\frac{q}{2} \right)}}

    Parameters are floats or arrays (NumPy broadcasting); singular points
    give inf/nan with NumPy's RuntimeWarning, never an exception.
    """
    q = _real('q', q)
    alpha = _real('alpha', alpha)
    K_s = _real('K_s', K_s)
    K_theta = _real('K_theta', K_theta)
    x0 = alpha**2
    x1 = 4*x0
    return numpy.sqrt(6*K_theta*x0 + (K_s*x1 - K_theta*x1)*numpy.sin((1/2)*q)**2)
