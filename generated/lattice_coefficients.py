# -----------------------------------------------------------------------------
# GENERATED FILE - DO NOT EDIT BY HAND.
# Written by `make derive` (python -m derivation --out generated) from the
# SymPy derivation in derivation/ (SymPy 1.14.0). Regenerate, never edit.
# -----------------------------------------------------------------------------

"""Semi-discrete NLS coefficients: the multiple-scales derivation repeated on the lattice.

Same functions and arguments as `generated.coefficients`, derived from the discrete
eq. `norm` of Demiquel, Achilleos, Theocharis & Tournat instead of its continuum limit:
the carrier is exact on the lattice (eq. `discrete2`), the cubic terms are the lattice's,
the second harmonic of U has the lattice dispersion (eq. `discrete1` at 2k), and case (II)
includes the induced mean flow (`mean_flow_coefficient`), which the paper sets to zero.
Each tends to the paper's form as k -> 0 (the mean-flow part of g2_coupled excepted).
"""

import numpy

__all__ = ['omega', 'group_velocity', 'g1', 'g2_rotation', 'g2_coupled', 'g_rotation', 'g_coupled', 'u2_coefficient', 'mean_flow_coefficient', 'mi_cutoff', 'mi_fastest', 'mi_growth_rate']


def _real(name, value):
    """``value`` as a float array; TypeError naming ``name`` unless it holds real numbers
    (a bool, a string or a complex number is refused, not cast)."""
    a = numpy.asarray(value)
    if a.dtype.kind not in "fiu":
        raise TypeError(f"{name} must hold real numbers, got {type(value).__name__} "
                        f"{value!r}"[:200])
    return a.astype(float, copy=False)


def omega(k, alpha, K_s, K_theta):
    r"""Carrier frequency, the lattice's rotational branch. Semi-discrete: derived from eq. `norm` itself (exact carrier on the lattice).

    Paper: eq. `discrete2`. Derived closed form:

    .. math:: \sqrt{2} \alpha \sqrt{- K_{s} \cos{\left(k \right)} + K_{s} + K_{\theta} \cos{\left(k \right)} + 2 K_{\theta}}

    Parameters are floats or arrays (NumPy broadcasting); singular points
    give inf/nan with NumPy's RuntimeWarning, never an exception.
    """
    k = _real('k', k)
    alpha = _real('alpha', alpha)
    K_s = _real('K_s', K_s)
    K_theta = _real('K_theta', K_theta)
    x0 = numpy.cos(k)
    return numpy.sqrt(2)*alpha*numpy.sqrt(-K_s*x0 + K_s + K_theta*x0 + 2*K_theta)


def group_velocity(k, alpha, K_s, K_theta):
    r"""Group velocity d omega/dk of the lattice branch. Semi-discrete: derived from eq. `norm` itself (exact carrier on the lattice).

    Paper: eq. `solvability_condition`. Derived closed form:

    .. math:: \frac{\sqrt{2} \alpha \left(K_{s} - K_{\theta}\right) \sin{\left(k \right)}}{2 \sqrt{- K_{s} \cos{\left(k \right)} + K_{s} + K_{\theta} \cos{\left(k \right)} + 2 K_{\theta}}}

    Parameters are floats or arrays (NumPy broadcasting); singular points
    give inf/nan with NumPy's RuntimeWarning, never an exception.
    """
    k = _real('k', k)
    alpha = _real('alpha', alpha)
    K_s = _real('K_s', K_s)
    K_theta = _real('K_theta', K_theta)
    x0 = numpy.cos(k)
    return (1/2)*numpy.sqrt(2)*alpha*(K_s - K_theta)*numpy.sin(k)/numpy.sqrt(-K_s*x0 + K_s + K_theta*x0 + 2*K_theta)


def g1(k, alpha, K_s, K_theta):
    r"""Dispersion coefficient g1 = d^2 omega/dk^2 of the lattice branch. Semi-discrete: derived from eq. `norm` itself (exact carrier on the lattice).

    Paper: eq. `g_i`. Derived closed form:

    .. math:: \frac{\sqrt{2} \alpha \left(2 \left(K_{s} - K_{\theta}\right) \left(- K_{s} \cos{\left(k \right)} + K_{s} + K_{\theta} \cos{\left(k \right)} + 2 K_{\theta}\right) \cos{\left(k \right)} + \left(- K_{s}^{2} + 2 K_{s} K_{\theta} - K_{\theta}^{2}\right) \sin^{2}{\left(k \right)}\right)}{4 \left(- K_{s} \cos{\left(k \right)} + K_{s} + K_{\theta} \cos{\left(k \right)} + 2 K_{\theta}\right)^{\frac{3}{2}}}

    Parameters are floats or arrays (NumPy broadcasting); singular points
    give inf/nan with NumPy's RuntimeWarning, never an exception.
    """
    k = _real('k', k)
    alpha = _real('alpha', alpha)
    K_s = _real('K_s', K_s)
    K_theta = _real('K_theta', K_theta)
    x0 = numpy.cos(k)
    x1 = -K_s*x0 + K_s + K_theta*x0 + 2*K_theta
    return (1/4)*numpy.sqrt(2)*alpha*(2*x0*x1*(K_s - K_theta) + (-K_s**2 + 2*K_s*K_theta - K_theta**2)*numpy.sin(k)**2)/x1**(3/2)


def g2_rotation(k, alpha, K_s, K_theta):
    r"""Nonlinear coefficient, case (I): the lattice's own cubic terms (neighbour products, shear nonlinearity). Semi-discrete: derived from eq. `norm` itself (exact carrier on the lattice).

    Paper: eq. `g_i`. Derived closed form:

    .. math:: \frac{\sqrt{2} \alpha \left(- 4 K_{s} \cos{\left(k \right)} + 4 K_{s} - \cos{\left(2 k \right)} - 5\right)}{4 \sqrt{- K_{s} \cos{\left(k \right)} + K_{s} + K_{\theta} \cos{\left(k \right)} + 2 K_{\theta}}}

    Parameters are floats or arrays (NumPy broadcasting); singular points
    give inf/nan with NumPy's RuntimeWarning, never an exception.
    """
    k = _real('k', k)
    alpha = _real('alpha', alpha)
    K_s = _real('K_s', K_s)
    K_theta = _real('K_theta', K_theta)
    x0 = numpy.cos(k)
    x1 = K_s*x0
    return (1/4)*numpy.sqrt(2)*alpha*(4*K_s - 4*x1 - numpy.cos(2*k) - 5)/numpy.sqrt(K_s + K_theta*x0 + 2*K_theta - x1)


def g2_coupled(k, alpha, K_s, K_theta):
    r"""Nonlinear coefficient, case (II): lattice cubic terms, the discrete second harmonic of U (eq. `discrete1` at 2k) and the induced mean flow (mean_flow_coefficient). Semi-discrete: derived from eq. `norm` itself (exact carrier on the lattice).

    Paper: eq. `g_i`. Derived closed form:

    .. math:: - \frac{\sqrt{2} \alpha \left(8 \alpha^{2} \left(4 \alpha^{2} \left(- K_{s} \cos{\left(k \right)} + K_{s} + K_{\theta} \cos{\left(k \right)} + 2 K_{\theta}\right) + \cos{\left(2 k \right)} - 1\right) \left(- K_{s} \cos{\left(k \right)} + K_{s} + K_{\theta} \cos{\left(k \right)} + 2 K_{\theta}\right) + \left(4 \alpha^{2} \left(- K_{s} \cos{\left(k \right)} + K_{s} + K_{\theta} \cos{\left(k \right)} + 2 K_{\theta}\right) + \cos{\left(2 k \right)} - 1\right) \left(4 K_{s} \cos{\left(k \right)} - 4 K_{s} + \cos{\left(2 k \right)} + 5\right) \left(K_{s}^{2} \alpha^{4} \sin^{2}{\left(k \right)} - 2 K_{s} K_{\theta} \alpha^{4} \sin^{2}{\left(k \right)} + K_{\theta}^{2} \alpha^{4} \sin^{2}{\left(k \right)} - 2 \alpha^{2} \left(- K_{s} \cos{\left(k \right)} + K_{s} + K_{\theta} \cos{\left(k \right)} + 2 K_{\theta}\right)\right) + \left(K_{s}^{2} \alpha^{4} \sin^{2}{\left(k \right)} - 2 K_{s} K_{\theta} \alpha^{4} \sin^{2}{\left(k \right)} + K_{\theta}^{2} \alpha^{4} \sin^{2}{\left(k \right)} - 2 \alpha^{2} \left(- K_{s} \cos{\left(k \right)} + K_{s} + K_{\theta} \cos{\left(k \right)} + 2 K_{\theta}\right)\right) \sin^{2}{\left(2 k \right)}\right)}{4 \left(4 \alpha^{2} \left(- K_{s} \cos{\left(k \right)} + K_{s} + K_{\theta} \cos{\left(k \right)} + 2 K_{\theta}\right) + \cos{\left(2 k \right)} - 1\right) \sqrt{- K_{s} \cos{\left(k \right)} + K_{s} + K_{\theta} \cos{\left(k \right)} + 2 K_{\theta}} \left(K_{s}^{2} \alpha^{4} \sin^{2}{\left(k \right)} - 2 K_{s} K_{\theta} \alpha^{4} \sin^{2}{\left(k \right)} + K_{\theta}^{2} \alpha^{4} \sin^{2}{\left(k \right)} - 2 \alpha^{2} \left(- K_{s} \cos{\left(k \right)} + K_{s} + K_{\theta} \cos{\left(k \right)} + 2 K_{\theta}\right)\right)}

    Parameters are floats or arrays (NumPy broadcasting); singular points
    give inf/nan with NumPy's RuntimeWarning, never an exception.
    """
    k = _real('k', k)
    alpha = _real('alpha', alpha)
    K_s = _real('K_s', K_s)
    K_theta = _real('K_theta', K_theta)
    x0 = 2*K_theta
    x1 = numpy.cos(k)
    x2 = K_s*x1
    x3 = K_s + K_theta*x1 + x0 - x2
    x4 = 2*k
    x5 = numpy.cos(x4)
    x6 = alpha**2*x3
    x7 = x5 + 4*x6 - 1
    x8 = alpha**4*numpy.sin(k)**2
    x9 = K_s**2*x8 - K_s*x0*x8 + K_theta**2*x8 - 2*x6
    return -1/4*numpy.sqrt(2)*alpha*(8*x6*x7 + x7*x9*(-4*K_s + 4*x2 + x5 + 5) + x9*numpy.sin(x4)**2)/(numpy.sqrt(x3)*x7*x9)


def g_rotation(k, alpha, K_s, K_theta):
    r"""g = g2/g1, case (I), lattice. Semi-discrete: derived from eq. `norm` itself (exact carrier on the lattice).

    Paper: eq. `g1`. Derived closed form:

    .. math:: \frac{\left(- 4 K_{s} \cos{\left(k \right)} + 4 K_{s} - \cos{\left(2 k \right)} - 5\right) \left(- K_{s} \cos{\left(k \right)} + K_{s} + K_{\theta} \cos{\left(k \right)} + 2 K_{\theta}\right)}{2 \left(K_{s} - K_{\theta}\right) \left(- K_{s} \cos{\left(k \right)} + K_{s} + K_{\theta} \cos{\left(k \right)} + 2 K_{\theta}\right) \cos{\left(k \right)} + \left(- K_{s}^{2} + 2 K_{s} K_{\theta} - K_{\theta}^{2}\right) \sin^{2}{\left(k \right)}}

    Parameters are floats or arrays (NumPy broadcasting); singular points
    give inf/nan with NumPy's RuntimeWarning, never an exception.
    """
    k = _real('k', k)
    alpha = _real('alpha', alpha)
    K_s = _real('K_s', K_s)
    K_theta = _real('K_theta', K_theta)
    x0 = numpy.cos(k)
    x1 = K_s*x0
    x2 = K_s + K_theta*x0 + 2*K_theta - x1
    return x2*(4*K_s - 4*x1 - numpy.cos(2*k) - 5)/(2*x0*x2*(K_s - K_theta) + (-K_s**2 + 2*K_s*K_theta - K_theta**2)*numpy.sin(k)**2)


def g_coupled(k, alpha, K_s, K_theta):
    r"""g = g2/g1, case (II), lattice, mean flow included. Semi-discrete: derived from eq. `norm` itself (exact carrier on the lattice).

    Paper: eq. `g2`. Derived closed form:

    .. math:: - \frac{\left(8 \alpha^{2} \left(4 \alpha^{2} \left(- K_{s} \cos{\left(k \right)} + K_{s} + K_{\theta} \cos{\left(k \right)} + 2 K_{\theta}\right) + \cos{\left(2 k \right)} - 1\right) \left(- K_{s} \cos{\left(k \right)} + K_{s} + K_{\theta} \cos{\left(k \right)} + 2 K_{\theta}\right) + \left(4 \alpha^{2} \left(- K_{s} \cos{\left(k \right)} + K_{s} + K_{\theta} \cos{\left(k \right)} + 2 K_{\theta}\right) + \cos{\left(2 k \right)} - 1\right) \left(4 K_{s} \cos{\left(k \right)} - 4 K_{s} + \cos{\left(2 k \right)} + 5\right) \left(K_{s}^{2} \alpha^{4} \sin^{2}{\left(k \right)} - 2 K_{s} K_{\theta} \alpha^{4} \sin^{2}{\left(k \right)} + K_{\theta}^{2} \alpha^{4} \sin^{2}{\left(k \right)} - 2 \alpha^{2} \left(- K_{s} \cos{\left(k \right)} + K_{s} + K_{\theta} \cos{\left(k \right)} + 2 K_{\theta}\right)\right) + \left(K_{s}^{2} \alpha^{4} \sin^{2}{\left(k \right)} - 2 K_{s} K_{\theta} \alpha^{4} \sin^{2}{\left(k \right)} + K_{\theta}^{2} \alpha^{4} \sin^{2}{\left(k \right)} - 2 \alpha^{2} \left(- K_{s} \cos{\left(k \right)} + K_{s} + K_{\theta} \cos{\left(k \right)} + 2 K_{\theta}\right)\right) \sin^{2}{\left(2 k \right)}\right) \left(- K_{s} \cos{\left(k \right)} + K_{s} + K_{\theta} \cos{\left(k \right)} + 2 K_{\theta}\right)}{\left(2 \left(K_{s} - K_{\theta}\right) \left(- K_{s} \cos{\left(k \right)} + K_{s} + K_{\theta} \cos{\left(k \right)} + 2 K_{\theta}\right) \cos{\left(k \right)} + \left(- K_{s}^{2} + 2 K_{s} K_{\theta} - K_{\theta}^{2}\right) \sin^{2}{\left(k \right)}\right) \left(4 \alpha^{2} \left(- K_{s} \cos{\left(k \right)} + K_{s} + K_{\theta} \cos{\left(k \right)} + 2 K_{\theta}\right) + \cos{\left(2 k \right)} - 1\right) \left(K_{s}^{2} \alpha^{4} \sin^{2}{\left(k \right)} - 2 K_{s} K_{\theta} \alpha^{4} \sin^{2}{\left(k \right)} + K_{\theta}^{2} \alpha^{4} \sin^{2}{\left(k \right)} - 2 \alpha^{2} \left(- K_{s} \cos{\left(k \right)} + K_{s} + K_{\theta} \cos{\left(k \right)} + 2 K_{\theta}\right)\right)}

    Parameters are floats or arrays (NumPy broadcasting); singular points
    give inf/nan with NumPy's RuntimeWarning, never an exception.
    """
    k = _real('k', k)
    alpha = _real('alpha', alpha)
    K_s = _real('K_s', K_s)
    K_theta = _real('K_theta', K_theta)
    x0 = 2*K_theta
    x1 = numpy.cos(k)
    x2 = K_s*x1
    x3 = K_s + K_theta*x1 + x0 - x2
    x4 = 2*k
    x5 = numpy.cos(x4)
    x6 = alpha**2*x3
    x7 = x5 + 4*x6 - 1
    x8 = numpy.sin(k)**2
    x9 = K_s**2
    x10 = K_theta**2
    x11 = alpha**4*x8
    x12 = -K_s*x0*x11 + x10*x11 + x11*x9 - 2*x6
    return -x3*(x12*x7*(-4*K_s + 4*x2 + x5 + 5) + x12*numpy.sin(x4)**2 + 8*x6*x7)/(x12*x7*(2*x1*x3*(K_s - K_theta) + x8*(2*K_s*K_theta - x10 - x9)))


def u2_coefficient(k, alpha, K_s, K_theta):
    r"""c in u2 = c B^2 e^{2 i sigma} + c.c. on the lattice: i sin 2k / (8 (sin^2 k - omega^2)). Diverges at sin^2 k = omega^2. Semi-discrete: derived from eq. `norm` itself (exact carrier on the lattice).

    Paper: eq. `u1`. Derived closed form:

    .. math:: - \frac{i \sin{\left(2 k \right)}}{16 \alpha^{2} \left(- K_{s} \cos{\left(k \right)} + K_{s} + K_{\theta} \cos{\left(k \right)} + 2 K_{\theta}\right) + 4 \cos{\left(2 k \right)} - 4}

    Parameters are floats or arrays (NumPy broadcasting); singular points
    give inf/nan with NumPy's RuntimeWarning, never an exception.
    """
    k = _real('k', k)
    alpha = _real('alpha', alpha)
    K_s = _real('K_s', K_s)
    K_theta = _real('K_theta', K_theta)
    x0 = 2*k
    x1 = numpy.cos(k)
    return -1j*numpy.sin(x0)/(16*alpha**2*(-K_s*x1 + K_s + K_theta*x1 + 2*K_theta) + 4*numpy.cos(x0) - 4)


def mean_flow_coefficient(k, alpha, K_s, K_theta):
    r"""mu in the induced mean strain U_n+1 - U_n = eps^2 mu |A|^2 (zeroth harmonic of U, driven by gradients of |A|^2): mu = 1/(v_g^2 - 1). The paper sets it to zero; it adds -2 alpha^2 mu / omega = 2 alpha^2 / (omega (1 - v_g^2)) > 0 to g2_coupled. Semi-discrete: derived from eq. `norm` itself (exact carrier on the lattice).

    Paper: eq. `u1`. Derived closed form:

    .. math:: \frac{2 \left(- K_{s} \cos{\left(k \right)} + K_{s} + K_{\theta} \cos{\left(k \right)} + 2 K_{\theta}\right)}{K_{s}^{2} \alpha^{2} \sin^{2}{\left(k \right)} - 2 K_{s} K_{\theta} \alpha^{2} \sin^{2}{\left(k \right)} + 2 K_{s} \cos{\left(k \right)} - 2 K_{s} + K_{\theta}^{2} \alpha^{2} \sin^{2}{\left(k \right)} - 2 K_{\theta} \cos{\left(k \right)} - 4 K_{\theta}}

    Parameters are floats or arrays (NumPy broadcasting); singular points
    give inf/nan with NumPy's RuntimeWarning, never an exception.
    """
    k = _real('k', k)
    alpha = _real('alpha', alpha)
    K_s = _real('K_s', K_s)
    K_theta = _real('K_theta', K_theta)
    x0 = 2*K_theta
    x1 = numpy.cos(k)
    x2 = 2*K_s
    x3 = alpha**2
    x4 = numpy.sin(k)**2
    return 2*(-K_s*x1 + K_s + K_theta*x1 + x0)/(K_s**2*x3*x4 + 2*K_s*x1 + K_theta**2*x3*x4 - K_theta*x2*x3*x4 - 4*K_theta - x0*x1 - x2)


def mi_cutoff(g, A0):
    r"""Cutoff K_c of the unstable band |K| < K_c (NLS units, xi1 = eps X). NaN for g < 0: there is no band. A0 enters as |A0| (B -> -B).

    Paper: eq. `kc`. Derived closed form:

    .. math:: 2 \sqrt{g} \left|{A_{0}}\right|

    Parameters are floats or arrays (NumPy broadcasting); singular points
    give inf/nan with NumPy's RuntimeWarning, never an exception.
    """
    g = _real('g', g)
    A0 = _real('A0', A0)
    return 2*numpy.sqrt(g)*numpy.abs(A0)


def mi_fastest(g, A0):
    r"""Fastest-growing perturbation wavenumber K_m. NaN for g < 0. A0 enters as |A0| (B -> -B).

    Paper: eq. `K_m`. Derived closed form:

    .. math:: \sqrt{2} \sqrt{g} \left|{A_{0}}\right|

    Parameters are floats or arrays (NumPy broadcasting); singular points
    give inf/nan with NumPy's RuntimeWarning, never an exception.
    """
    g = _real('g', g)
    A0 = _real('A0', A0)
    return numpy.sqrt(2)*numpy.sqrt(g)*numpy.abs(A0)


def mi_growth_rate(K, g, A0):
    r"""Growth rate Omega_I(K) in the NLS time tilde-tau2 = g1 eps^2 T; 0 outside the band (and for g <= 0). The lattice rate is eps^2 |g1| Omega_I.

    Paper: eq. `Omega_I`. Derived closed form:

    .. math:: \left|{K}\right| \sqrt{\max\left(0, A_{0}^{2} g - \frac{K^{2}}{4}\right)}

    Parameters are floats or arrays (NumPy broadcasting); singular points
    give inf/nan with NumPy's RuntimeWarning, never an exception.
    """
    K = _real('K', K)
    g = _real('g', g)
    A0 = _real('A0', A0)
    return numpy.abs(K)*numpy.sqrt(numpy.maximum(0, A0**2*g - 1/4*K**2))
