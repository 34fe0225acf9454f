# -----------------------------------------------------------------------------
# GENERATED FILE - DO NOT EDIT BY HAND.
# Written by `make derive` (python -m derivation --out generated) from the
# SymPy derivation in derivation/ (SymPy 1.14.0). Regenerate, never edit.
# -----------------------------------------------------------------------------

"""NLS coefficients and MI band of rotational waves in a flexible mechanical metamaterial.

Continuum-limit multiple-scales results of Demiquel, Achilleos, Theocharis & Tournat,
"Modulation instability in nonlinear flexible mechanical metamaterials". Equation labels
are the paper's. Case (I): rotation only; case (II): rotation coupled to displacement.
Arguments: carrier wavenumber k (rad per site), inertia alpha, stiffnesses K_s, K_theta;
the MI functions take the NLS nonlinearity g = g2/g1 and the envelope amplitude A0.
"""

import numpy

__all__ = ['omega', 'group_velocity', 'g1', 'g2_rotation', 'g2_coupled', 'g_rotation', 'g_coupled', 'u2_coefficient', 'mi_cutoff', 'mi_fastest', 'mi_growth_rate']


def _real(name, value):
    """``value`` as a float array; TypeError naming ``name`` unless it holds real numbers
    (a bool, a string or a complex number is refused, not cast)."""
    a = numpy.asarray(value)
    if a.dtype.kind not in "fiu":
        raise TypeError(f"{name} must hold real numbers, got {type(value).__name__} "
                        f"{value!r}"[:200])
    return a.astype(float, copy=False)


def omega(k, alpha, K_s, K_theta):
    r"""Carrier frequency of the rotational branch, continuum limit.

    Paper: eq. `continuum2`. Derived closed form:

    .. math:: \alpha \sqrt{K_{s} k^{2} - K_{\theta} k^{2} + 6 K_{\theta}}

    Parameters are floats or arrays (NumPy broadcasting); singular points
    give inf/nan with NumPy's RuntimeWarning, never an exception.
    """
    k = _real('k', k)
    alpha = _real('alpha', alpha)
    K_s = _real('K_s', K_s)
    K_theta = _real('K_theta', K_theta)
    x0 = k**2
    return alpha*numpy.sqrt(K_s*x0 - K_theta*x0 + 6*K_theta)


def group_velocity(k, alpha, K_s, K_theta):
    r"""Group velocity v_g = d omega/dk, from the O(eps^2) solvability condition.

    Paper: eq. `solvability_condition`. Derived closed form:

    .. math:: \frac{\alpha k \left(K_{s} - K_{\theta}\right)}{\sqrt{K_{s} k^{2} - K_{\theta} k^{2} + 6 K_{\theta}}}

    Parameters are floats or arrays (NumPy broadcasting); singular points
    give inf/nan with NumPy's RuntimeWarning, never an exception.
    """
    k = _real('k', k)
    alpha = _real('alpha', alpha)
    K_s = _real('K_s', K_s)
    K_theta = _real('K_theta', K_theta)
    x0 = k**2
    return alpha*k*(K_s - K_theta)/numpy.sqrt(K_s*x0 - K_theta*x0 + 6*K_theta)


def g1(k, alpha, K_s, K_theta):
    r"""Dispersion coefficient of the NLS, g1 = d^2 omega/dk^2. Vanishes at delta = 0 (alpha^2 delta = v_g^2).

    Paper: eq. `g_i`. Derived closed form:

    .. math:: \frac{6 K_{\theta} \alpha \left(K_{s} - K_{\theta}\right)}{\left(K_{s} k^{2} - K_{\theta} k^{2} + 6 K_{\theta}\right)^{\frac{3}{2}}}

    Parameters are floats or arrays (NumPy broadcasting); singular points
    give inf/nan with NumPy's RuntimeWarning, never an exception.
    """
    k = _real('k', k)
    alpha = _real('alpha', alpha)
    K_s = _real('K_s', K_s)
    K_theta = _real('K_theta', K_theta)
    x0 = 6*K_theta
    x1 = k**2
    return alpha*x0*(K_s - K_theta)/(K_s*x1 - K_theta*x1 + x0)**(3/2)


def g2_rotation(k, alpha, K_s, K_theta):
    r"""Nonlinear coefficient of the NLS, case (I) (rotation only).

    Paper: eq. `g_i`. Derived closed form:

    .. math:: - \frac{3 \alpha}{\sqrt{K_{s} k^{2} - K_{\theta} k^{2} + 6 K_{\theta}}}

    Parameters are floats or arrays (NumPy broadcasting); singular points
    give inf/nan with NumPy's RuntimeWarning, never an exception.
    """
    k = _real('k', k)
    alpha = _real('alpha', alpha)
    K_s = _real('K_s', K_s)
    K_theta = _real('K_theta', K_theta)
    x0 = k**2
    return -3*alpha/numpy.sqrt(K_s*x0 - K_theta*x0 + 6*K_theta)


def g2_coupled(k, alpha, K_s, K_theta):
    r"""Nonlinear coefficient of the NLS, case (II) (rotation + displacement). Diverges at the resonance k^2 = omega^2.

    Paper: eq. `g_i`. Derived closed form:

    .. math:: - \frac{\alpha \left(3 \alpha^{2} \left(K_{s} k^{2} - K_{\theta} k^{2} + 6 K_{\theta}\right) - 2 k^{2}\right)}{\left(\alpha^{2} \left(K_{s} k^{2} - K_{\theta} k^{2} + 6 K_{\theta}\right) - k^{2}\right) \sqrt{K_{s} k^{2} - K_{\theta} k^{2} + 6 K_{\theta}}}

    Parameters are floats or arrays (NumPy broadcasting); singular points
    give inf/nan with NumPy's RuntimeWarning, never an exception.
    """
    k = _real('k', k)
    alpha = _real('alpha', alpha)
    K_s = _real('K_s', K_s)
    K_theta = _real('K_theta', K_theta)
    x0 = k**2
    x1 = K_s*x0 - K_theta*x0 + 6*K_theta
    x2 = alpha**2*x1
    return -alpha*(-2*x0 + 3*x2)/(numpy.sqrt(x1)*(-x0 + x2))


def g_rotation(k, alpha, K_s, K_theta):
    r"""g = g2/g1, case (I); g > 0: focusing (MI), g < 0: defocusing. Diverges at delta = 0.

    Paper: eq. `g1`. Derived closed form:

    .. math:: \frac{- K_{s} k^{2} + K_{\theta} k^{2} - 6 K_{\theta}}{2 K_{\theta} \left(K_{s} - K_{\theta}\right)}

    Parameters are floats or arrays (NumPy broadcasting); singular points
    give inf/nan with NumPy's RuntimeWarning, never an exception.
    """
    k = _real('k', k)
    alpha = _real('alpha', alpha)
    K_s = _real('K_s', K_s)
    K_theta = _real('K_theta', K_theta)
    x0 = k**2
    return (1/2)*(-K_s*x0 + K_theta*x0 - 6*K_theta)/(K_theta*(K_s - K_theta))


def g_coupled(k, alpha, K_s, K_theta):
    r"""g = g2/g1, case (II). Diverges at delta = 0 and at k^2 = omega^2.

    Paper: eq. `g2`. Derived closed form:

    .. math:: - \frac{\left(3 \alpha^{2} \left(K_{s} k^{2} - K_{\theta} k^{2} + 6 K_{\theta}\right) - 2 k^{2}\right) \left(K_{s} k^{2} - K_{\theta} k^{2} + 6 K_{\theta}\right)}{6 K_{\theta} \left(K_{s} - K_{\theta}\right) \left(\alpha^{2} \left(K_{s} k^{2} - K_{\theta} k^{2} + 6 K_{\theta}\right) - k^{2}\right)}

    Parameters are floats or arrays (NumPy broadcasting); singular points
    give inf/nan with NumPy's RuntimeWarning, never an exception.
    """
    k = _real('k', k)
    alpha = _real('alpha', alpha)
    K_s = _real('K_s', K_s)
    K_theta = _real('K_theta', K_theta)
    x0 = k**2
    x1 = K_s*x0 - K_theta*x0 + 6*K_theta
    x2 = alpha**2*x1
    return -1/6*x1*(-2*x0 + 3*x2)/(K_theta*(K_s - K_theta)*(-x0 + x2))


def u2_coefficient(k, alpha, K_s, K_theta):
    r"""Complex c of the second-harmonic displacement, u2 = c B^2 e^{2 i sigma} + c.c. (case II). Diverges at the resonance k^2 = omega^2.

    Paper: eq. `u1`. Derived closed form:

    .. math:: - \frac{i k}{4 \alpha^{2} \left(K_{s} k^{2} - K_{\theta} k^{2} + 6 K_{\theta}\right) - 4 k^{2}}

    Parameters are floats or arrays (NumPy broadcasting); singular points
    give inf/nan with NumPy's RuntimeWarning, never an exception.
    """
    k = _real('k', k)
    alpha = _real('alpha', alpha)
    K_s = _real('K_s', K_s)
    K_theta = _real('K_theta', K_theta)
    x0 = k**2
    return -1j*k/(4*alpha**2*(K_s*x0 - K_theta*x0 + 6*K_theta) - 4*x0)


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
