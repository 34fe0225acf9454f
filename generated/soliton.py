# -----------------------------------------------------------------------------
# GENERATED FILE - DO NOT EDIT BY HAND.
# Written by `make derive` (python -m derivation --out generated) from the
# SymPy derivation in derivation/ (SymPy 1.14.0). Regenerate, never edit.
# -----------------------------------------------------------------------------

"""Envelope solitons of the NLS (eq. `NLS`) and the kink of U they carry (case II).

Bright (g = g2/g1 > 0) and dark, black or grey (g < 0), solitons of
i E_t + g1/2 E_xixi + g2 |E|^2 E = 0 in lattice units (xi = n - v_g t, theta_n =
E e^{i(k n - omega t)} + c.c.; `amplitude` is the peak rotation 2|E|, as everywhere in the
project: a size, so each form takes |amplitude|, E -> -E being a symmetry of the NLS), each
checked symbolically to solve the NLS by `make derive`. Take g1, g2 (and omega, v_g) from
`generated.coefficients` for the paper's continuum NLS or from
`generated.lattice_coefficients` for the semi-discrete NLS. The mean strain under the
envelope is U_{n+1} - U_n = mu (|E|^2 - background), mu = 1/(v_g^2 - 1); the kink is its
integral. Follow-up: Demiquel et al., arXiv 2406.09871 (envelope vector solitons).
"""

import numpy

__all__ = ['bright_envelope', 'bright_width', 'bright_frequency_shift', 'bright_kink', 'dark_envelope', 'dark_width', 'dark_velocity', 'dark_frequency_shift', 'dark_phase_jump', 'dark_kink', 'continuum_mean_flow_coefficient', 'lattice_g2_mean_flow']


def _real(name, value):
    """``value`` as a float array; TypeError naming ``name`` unless it holds real numbers
    (a bool, a string or a complex number is refused, not cast)."""
    a = numpy.asarray(value)
    if a.dtype.kind not in "fiu":
        raise TypeError(f"{name} must hold real numbers, got {type(value).__name__} "
                        f"{value!r}"[:200])
    return a.astype(float, copy=False)


def bright_envelope(xi, t, amplitude, g1, g2):
    r"""Bright soliton E(xi, t) of i E_t + g1/2 E_xixi + g2 |E|^2 E = 0 (g2/g1 > 0); theta_n = E e^{i(k n - omega t)} + c.c. Lattice units: xi = n - v_g t (sites), t in T, amplitude = peak rotation 2|E| (rad); g1, g2 from generated.coefficients (paper NLS) or generated.lattice_coefficients (semi-discrete NLS).

    Paper: eq. `NLS`. Derived closed form:

    .. math:: \frac{e^{\frac{i amplitude^{2} g_{2} t}{8}} \left|{amplitude}\right|}{2 \cosh{\left(\frac{\xi \sqrt{\frac{g_{2}}{g_{1}}} \left|{amplitude}\right|}{2} \right)}}

    Parameters are floats or arrays (NumPy broadcasting); singular points
    give inf/nan with NumPy's RuntimeWarning, never an exception.
    """
    xi = _real('xi', xi)
    t = _real('t', t)
    amplitude = _real('amplitude', amplitude)
    g1 = _real('g1', g1)
    g2 = _real('g2', g2)
    x0 = (1/2)*numpy.abs(amplitude)
    return x0*numpy.exp((1/8)*1j*amplitude**2*g2*t)/numpy.cosh(x0*xi*numpy.sqrt(g2/g1))


def bright_width(amplitude, g1, g2):
    r"""Width w of the bright soliton, |E| = a sech(xi/w): 1/(a sqrt(g2/g1)), a = amplitude/2 (sites). Lattice units: xi = n - v_g t (sites), t in T, amplitude = peak rotation 2|E| (rad); g1, g2 from generated.coefficients (paper NLS) or generated.lattice_coefficients (semi-discrete NLS).

    Paper: eq. `NLS`. Derived closed form:

    .. math:: \frac{2}{\sqrt{\frac{g_{2}}{g_{1}}} \left|{amplitude}\right|}

    Parameters are floats or arrays (NumPy broadcasting); singular points
    give inf/nan with NumPy's RuntimeWarning, never an exception.
    """
    amplitude = _real('amplitude', amplitude)
    g1 = _real('g1', g1)
    g2 = _real('g2', g2)
    return 2/(numpy.sqrt(g2/g1)*numpy.abs(amplitude))


def bright_frequency_shift(amplitude, g1, g2):
    r"""E ~ e^{i s t}: the soliton's carrier frequency is omega - s, s = g2 a^2/2. Lattice units: xi = n - v_g t (sites), t in T, amplitude = peak rotation 2|E| (rad); g1, g2 from generated.coefficients (paper NLS) or generated.lattice_coefficients (semi-discrete NLS).

    Paper: eq. `NLS`. Derived closed form:

    .. math:: \frac{amplitude^{2} g_{2}}{8}

    Parameters are floats or arrays (NumPy broadcasting); singular points
    give inf/nan with NumPy's RuntimeWarning, never an exception.
    """
    amplitude = _real('amplitude', amplitude)
    g1 = _real('g1', g1)
    g2 = _real('g2', g2)
    return (1/8)*amplitude**2*g2


def bright_kink(amplitude, g1, g2, mu):
    r"""Height of the kink of U under a bright soliton: the integral of the mean strain mu |E|^2, 2 mu a^2 w (case II; mu = 1/(v_g^2 - 1) < 0). Lattice units: xi = n - v_g t (sites), t in T, amplitude = peak rotation 2|E| (rad); g1, g2 from generated.coefficients (paper NLS) or generated.lattice_coefficients (semi-discrete NLS).

    Paper: eq. `u1`. Derived closed form:

    .. math:: \frac{\mu \left|{amplitude}\right|}{\sqrt{\frac{g_{2}}{g_{1}}}}

    Parameters are floats or arrays (NumPy broadcasting); singular points
    give inf/nan with NumPy's RuntimeWarning, never an exception.
    """
    amplitude = _real('amplitude', amplitude)
    g1 = _real('g1', g1)
    g2 = _real('g2', g2)
    mu = _real('mu', mu)
    return mu*numpy.abs(amplitude)/numpy.sqrt(g2/g1)


def dark_envelope(xi, t, amplitude, phi, g1, g2):
    r"""Dark soliton on a background of peak rotation `amplitude` (g2/g1 < 0), grey with angle phi (|phi| < pi/2; phi = 0 black, at rest in the frame moving with v_g). Lattice units: xi = n - v_g t (sites), t in T, amplitude = peak rotation 2|E| (rad); g1, g2 from generated.coefficients (paper NLS) or generated.lattice_coefficients (semi-discrete NLS).

    Paper: eq. `NLS`. Derived closed form:

    .. math:: \frac{\left(i \sin{\left(\phi \right)} + \cos{\left(\phi \right)} \tanh{\left(\frac{\sqrt{- \frac{g_{2}}{g_{1}}} \left(- \frac{g_{1} t \sqrt{- \frac{g_{2}}{g_{1}}} \sin{\left(\phi \right)} \left|{amplitude}\right|}{2} + \xi\right) \cos{\left(\phi \right)} \left|{amplitude}\right|}{2} \right)}\right) e^{\frac{i amplitude^{2} g_{2} t}{4}} \left|{amplitude}\right|}{2}

    Parameters are floats or arrays (NumPy broadcasting); singular points
    give inf/nan with NumPy's RuntimeWarning, never an exception.
    """
    xi = _real('xi', xi)
    t = _real('t', t)
    amplitude = _real('amplitude', amplitude)
    phi = _real('phi', phi)
    g1 = _real('g1', g1)
    g2 = _real('g2', g2)
    x0 = numpy.sin(phi)
    x1 = numpy.cos(phi)
    x2 = (1/2)*numpy.abs(amplitude)
    x3 = x2*numpy.sqrt(-g2/g1)
    return x2*(1j*x0 + x1*numpy.tanh(x1*x3*(-g1*t*x0*x3 + xi)))*numpy.exp((1/4)*1j*amplitude**2*g2*t)


def dark_width(amplitude, phi, g1, g2):
    r"""Width w of the dark soliton, |E|^2 = a^2 (1 - cos^2(phi) sech^2((xi - V t)/w)): 1/(a cos(phi) sqrt(-g2/g1)) (sites). Lattice units: xi = n - v_g t (sites), t in T, amplitude = peak rotation 2|E| (rad); g1, g2 from generated.coefficients (paper NLS) or generated.lattice_coefficients (semi-discrete NLS).

    Paper: eq. `NLS`. Derived closed form:

    .. math:: \frac{2}{\sqrt{- \frac{g_{2}}{g_{1}}} \cos{\left(\phi \right)} \left|{amplitude}\right|}

    Parameters are floats or arrays (NumPy broadcasting); singular points
    give inf/nan with NumPy's RuntimeWarning, never an exception.
    """
    amplitude = _real('amplitude', amplitude)
    phi = _real('phi', phi)
    g1 = _real('g1', g1)
    g2 = _real('g2', g2)
    return 2/(numpy.sqrt(-g2/g1)*numpy.cos(phi)*numpy.abs(amplitude))


def dark_velocity(amplitude, phi, g1, g2):
    r"""Velocity V of a grey soliton relative to v_g (sites per T); 0 for the black one. Lattice units: xi = n - v_g t (sites), t in T, amplitude = peak rotation 2|E| (rad); g1, g2 from generated.coefficients (paper NLS) or generated.lattice_coefficients (semi-discrete NLS).

    Paper: eq. `NLS`. Derived closed form:

    .. math:: \frac{g_{1} \sqrt{- \frac{g_{2}}{g_{1}}} \sin{\left(\phi \right)} \left|{amplitude}\right|}{2}

    Parameters are floats or arrays (NumPy broadcasting); singular points
    give inf/nan with NumPy's RuntimeWarning, never an exception.
    """
    amplitude = _real('amplitude', amplitude)
    phi = _real('phi', phi)
    g1 = _real('g1', g1)
    g2 = _real('g2', g2)
    return (1/2)*g1*numpy.sqrt(-g2/g1)*numpy.sin(phi)*numpy.abs(amplitude)


def dark_frequency_shift(amplitude, g2):
    r"""E ~ e^{i s t} on the background: carrier frequency omega - s, s = g2 a^2. Lattice units: xi = n - v_g t (sites), t in T, amplitude = peak rotation 2|E| (rad); g1, g2 from generated.coefficients (paper NLS) or generated.lattice_coefficients (semi-discrete NLS).

    Paper: eq. `NLS`. Derived closed form:

    .. math:: \frac{amplitude^{2} g_{2}}{4}

    Parameters are floats or arrays (NumPy broadcasting); singular points
    give inf/nan with NumPy's RuntimeWarning, never an exception.
    """
    amplitude = _real('amplitude', amplitude)
    g2 = _real('g2', g2)
    return (1/4)*amplitude**2*g2


def dark_phase_jump(phi):
    r"""Jump of arg E across a dark soliton, 2 phi - pi (rad): a ring of N sites closes only if k N + jump is a multiple of 2 pi. Lattice units: xi = n - v_g t (sites), t in T, amplitude = peak rotation 2|E| (rad); g1, g2 from generated.coefficients (paper NLS) or generated.lattice_coefficients (semi-discrete NLS).

    Paper: eq. `NLS`. Derived closed form:

    .. math:: 2 \phi - \pi

    Parameters are floats or arrays (NumPy broadcasting); singular points
    give inf/nan with NumPy's RuntimeWarning, never an exception.
    """
    phi = _real('phi', phi)
    return 2*phi - numpy.pi


def dark_kink(amplitude, phi, g1, g2, mu):
    r"""Height of the kink of U across a dark soliton: the integral of mu (|E|^2 - a^2), -2 mu a^2 cos^2(phi) w (case II). Lattice units: xi = n - v_g t (sites), t in T, amplitude = peak rotation 2|E| (rad); g1, g2 from generated.coefficients (paper NLS) or generated.lattice_coefficients (semi-discrete NLS).

    Paper: eq. `u1`. Derived closed form:

    .. math:: - \frac{\mu \cos{\left(\phi \right)} \left|{amplitude}\right|}{\sqrt{- \frac{g_{2}}{g_{1}}}}

    Parameters are floats or arrays (NumPy broadcasting); singular points
    give inf/nan with NumPy's RuntimeWarning, never an exception.
    """
    amplitude = _real('amplitude', amplitude)
    phi = _real('phi', phi)
    g1 = _real('g1', g1)
    g2 = _real('g2', g2)
    mu = _real('mu', mu)
    return -mu*numpy.cos(phi)*numpy.abs(amplitude)/numpy.sqrt(-g2/g1)


def continuum_mean_flow_coefficient(k, alpha, K_s, K_theta):
    r"""mu of the continuum, U_X = mu |E|^2 under a profile moving with v_g: 1/(v_g^2 - 1), from eq. `eqnorm1`. The paper's NLS leaves its feedback on g2 out; the kink is still there.

    Paper: eq. `eqnorm1`. Derived closed form:

    .. math:: \frac{K_{s} k^{2} - K_{\theta} k^{2} + 6 K_{\theta}}{- K_{s} k^{2} + K_{\theta} k^{2} - 6 K_{\theta} + \alpha^{2} k^{2} \left(K_{s} - K_{\theta}\right)^{2}}

    Parameters are floats or arrays (NumPy broadcasting); singular points
    give inf/nan with NumPy's RuntimeWarning, never an exception.
    """
    k = _real('k', k)
    alpha = _real('alpha', alpha)
    K_s = _real('K_s', K_s)
    K_theta = _real('K_theta', K_theta)
    x0 = k**2
    x1 = K_s*x0 - K_theta*x0 + 6*K_theta
    return x1/(alpha**2*x0*(K_s - K_theta)**2 - x1)


def lattice_g2_mean_flow(k, alpha, K_s, K_theta):
    r"""The part of the semi-discrete g2_coupled that the mean flow gives (-2 alpha^2 mu / omega): on a ring the mean strain is zero, so a dark soliton's background does not feel it (its frequency shift omits it).

    Paper: eq. `u1`. Derived closed form:

    .. math:: - \frac{2 \sqrt{2} \alpha^{3} \sqrt{- K_{s} \cos{\left(k \right)} + K_{s} + K_{\theta} \cos{\left(k \right)} + 2 K_{\theta}}}{K_{s}^{2} \alpha^{4} \sin^{2}{\left(k \right)} - 2 K_{s} K_{\theta} \alpha^{4} \sin^{2}{\left(k \right)} + K_{\theta}^{2} \alpha^{4} \sin^{2}{\left(k \right)} - 2 \alpha^{2} \left(- K_{s} \cos{\left(k \right)} + K_{s} + K_{\theta} \cos{\left(k \right)} + 2 K_{\theta}\right)}

    Parameters are floats or arrays (NumPy broadcasting); singular points
    give inf/nan with NumPy's RuntimeWarning, never an exception.
    """
    k = _real('k', k)
    alpha = _real('alpha', alpha)
    K_s = _real('K_s', K_s)
    K_theta = _real('K_theta', K_theta)
    x0 = 2*K_theta
    x1 = numpy.cos(k)
    x2 = -K_s*x1 + K_s + K_theta*x1 + x0
    x3 = alpha**4*numpy.sin(k)**2
    return -2*numpy.sqrt(2)*alpha**3*numpy.sqrt(x2)/(K_s**2*x3 - K_s*x0*x3 + K_theta**2*x3 - 2*alpha**2*x2)
