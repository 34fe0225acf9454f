"""Envelope solitons of the project's NLS and the kink of U they carry (generated/soliton.py).

The NLS of eq. `NLS`, written in lattice units: with theta_n = E e^{i(k n - omega t)} + c.c.
and E(xi, t) = eps B (xi = n - v_g t the site measured in the frame moving with v_g), the
scaled variables eps xi and eps^2 t of the derivation drop out exactly and

    i E_t + g1/2 E_xixi + g2 |E|^2 E = 0,

the same equation for the continuum (``generated.coefficients``) and the semi-discrete NLS
(``generated.lattice_coefficients``): the two theories differ only in omega, v_g, g1, g2.
The peak rotation of the carrier is 2 |E| (the paper's 2 eps |B|), which is the
``amplitude`` every generated function here takes, as elsewhere in the project.

- bright (g = g2/g1 > 0): E = a sech(xi/w) e^{i g2 a^2 t/2}, w = 1/(a sqrt(g));
- dark (g < 0), grey with angle phi (phi = 0: black): on a background a e^{i g2 a^2 t},
  E = a e^{i g2 a^2 t} [cos(phi) tanh((xi - V t)/w) + i sin(phi)], w = 1/(a cos(phi)
  sqrt(-g)), V = g1 a sin(phi) sqrt(-g) relative to v_g; the phase jumps by 2 phi - pi.

Each is substituted into the NLS and the residual simplified to zero (``check``); ``derive``
fails otherwise. The mean flow of case (II): the zeroth harmonic of the U equation, for a
profile travelling with v_g, gives the strain U_{n+1} - U_n = mu (|E|^2 - background);
mu = 1/(v_g^2 - 1) is read off the continuum U equation (eq. `eqnorm1`) here and is the
lattice's ``mean_flow_coefficient`` (derived in ``_multiscale``) on the lattice. Its integral
across the soliton is the kink of U.
"""

from __future__ import annotations

import sympy as sp

from ._continuum import K_s, K_theta, X, alpha, derive_continuum, fields, k

xi, t = sp.symbols("xi t", real=True)
amplitude = sp.Symbol("amplitude", positive=True)  # peak rotation 2|E| (rad)
phi = sp.Symbol("phi", real=True)  # greyness angle of a dark soliton, |phi| < pi/2
g1, g2, mu = sp.symbols("g1 g2 mu", real=True)

#: the envelope's modulus, half the peak rotation
_a = amplitude / 2
NLS_ARGS = (amplitude, g1, g2)


def nls_residual(E):
    """i E_t + g1/2 E_xixi + g2 |E|^2 E for an explicit envelope E(xi, t)."""
    return sp.I * E.diff(t) + g1 / 2 * E.diff(xi, 2) + g2 * E * sp.conjugate(E) * E


def bright():
    """Bright soliton (g1 g2 > 0): envelope, width, frequency shift, kink."""
    w = 1 / (_a * sp.sqrt(g2 / g1))
    E = _a / sp.cosh(xi / w) * sp.exp(sp.I * g2 * _a**2 * t / 2)
    shift = g2 * _a**2 / 2  # E ~ e^{+i shift t}: the lattice frequency is omega - shift
    strain = mu * _a**2 / sp.cosh(xi / w) ** 2
    kink = sp.integrate(strain.subs(xi, w * xi) * w, (xi, -sp.oo, sp.oo))
    return {"envelope": E, "width": w, "frequency_shift": shift, "strain": strain,
            "kink": sp.simplify(kink)}


def dark():
    """Dark soliton (g1 g2 < 0), grey with angle phi (black at phi = 0)."""
    h = -g2 / g1  # > 0
    w = 1 / (_a * sp.cos(phi) * sp.sqrt(h))
    V = g1 * _a * sp.sin(phi) * sp.sqrt(h)
    E = (_a * sp.exp(sp.I * g2 * _a**2 * t)
         * (sp.cos(phi) * sp.tanh((xi - V * t) / w) + sp.I * sp.sin(phi)))
    shift = g2 * _a**2
    # |E|^2 - a^2 = -a^2 cos^2(phi) sech^2((xi - V t)/w)
    strain = -mu * _a**2 * sp.cos(phi) ** 2 / sp.cosh((xi - V * t) / w) ** 2
    s = sp.Symbol("s", real=True)
    kink = sp.integrate((-mu * _a**2 * sp.cos(phi) ** 2 / sp.cosh(s) ** 2) * w,
                        (s, -sp.oo, sp.oo))
    return {"envelope": E, "width": w, "velocity": V, "frequency_shift": shift,
            "strain": strain, "kink": sp.simplify(kink), "phase_jump": 2 * phi - sp.pi}


def _poly_in_tanh(expr, phase):
    """expr e^{-i phase} as a polynomial in tanh(z) and sech^2 = 1 - tanh^2: each
    coefficient simplified (an exp rewrite of the dark soliton costs minutes)."""
    T = sp.Symbol("T")
    out = sp.expand(sp.powsimp(sp.expand(expr * sp.exp(-sp.I * phase))))
    out = out.replace(sp.tanh, lambda z: T).replace(sp.cosh, lambda z: 1 / sp.sqrt(1 - T**2))
    poly = sp.Poly(sp.expand(out), T)
    return [sp.simplify(c) for c in poly.all_coeffs()]


def check(sol, sign):
    """Residual of the NLS for ``sol`` where sign(g2/g1) = ``sign``; zero or raise."""
    gpos = sp.Symbol("g", positive=True)
    G1 = sp.Symbol("G1", nonzero=True, real=True)
    on = {g2: sign * gpos * G1, g1: G1}
    E = sol["envelope"].subs(on)
    r = nls_residual(sol["envelope"]).subs(on)
    phase = (on[g2] * _a**2 * t / (2 if sign > 0 else 1))
    bg = 0 if sign > 0 else _a**2
    st = sol["strain"].subs(on)
    if sign > 0:
        r = sp.simplify(sp.expand(r.rewrite(sp.exp)))
        bad = [r] if r != 0 else []
        dens = sp.simplify(sp.expand((E * sp.conjugate(E)).rewrite(sp.exp)) - bg)
        bad += [] if sp.simplify((mu * dens - st).rewrite(sp.exp)) == 0 else ["strain"]
    else:
        bad = [c for c in _poly_in_tanh(r, phase) if c != 0]
        bad += [c for c in _poly_in_tanh(mu * (E * sp.conjugate(E) - bg) - st, 0) if c != 0]
    if bad:
        raise ArithmeticError(f"soliton does not solve the NLS (or its strain is not "
                              f"mu (|E|^2 - background)): {bad}")
    return True


def continuum_mean_flow():
    """mu of the continuum: U_TT = U_XX + N(theta) (eq. `eqnorm1`), zeroth harmonic of N
    for theta = B e^{i k X} + c.c., U = F(X - v T): (v^2 - 1) F'' = b (|B|^2)'."""
    U, th = fields()
    eq = derive_continuum().eq_U
    N = sp.expand(eq - U.diff(X, 2))
    B, Bc = sp.Function("B")(X), sp.Function("Bbar")(X)
    car = sp.exp(sp.I * k * X)
    wave = B * car + Bc / car
    N = sp.expand(N.subs(th, wave).doit())
    zeroth = sp.Add(*[term for term in sp.Add.make_args(N) if not term.has(sp.exp)])
    b = sp.simplify(zeroth / sp.expand((B * Bc).diff(X)))
    if b.has(X):
        raise ArithmeticError(f"mean-flow forcing not of the form b (|B|^2)': {zeroth}")
    from ._multiscale import solve_case

    v = solve_case("coupled").group_velocity
    return sp.simplify(b / (v**2 - 1))


def forms(closed_form, derivation):
    """The ClosedForm tuple of generated/soliton.py (``closed_form`` is the class)."""
    br, dk = bright(), dark()
    check(br, +1)
    check(dk, -1)
    check({**dk, "envelope": dk["envelope"].subs(phi, 0),
           "strain": dk["strain"].subs(phi, 0)}, -1)
    material = (k, alpha, K_s, K_theta)
    # amplitude is the peak rotation 2|E|: a size. E -> -E is a symmetry of the NLS, so the
    # soliton of amplitude -a is the one of |a| (a phase pi): every form takes |amplitude|
    # (printed as typed, a width 2/(amplitude sqrt(g)) was -500 sites at amplitude -0.002)
    even = ("amplitude",)
    note = (" Lattice units: xi = n - v_g t (sites), t in T, amplitude = peak rotation "
            "2|E| (rad); g1, g2 from generated.coefficients (paper NLS) or "
            "generated.lattice_coefficients (semi-discrete NLS).")
    lat = derivation.lattice["coupled"]
    return (
        closed_form("bright_envelope", br["envelope"], (xi, t) + NLS_ARGS,
                    "Bright soliton E(xi, t) of i E_t + g1/2 E_xixi + g2 |E|^2 E = 0 "
                    "(g2/g1 > 0); theta_n = E e^{i(k n - omega t)} + c.c." + note, "NLS",
                    even_in=even),
        closed_form("bright_width", br["width"], NLS_ARGS,
                    "Width w of the bright soliton, |E| = a sech(xi/w): 1/(a sqrt(g2/g1)), "
                    "a = amplitude/2 (sites)." + note, "NLS", even_in=even),
        closed_form("bright_frequency_shift", br["frequency_shift"], NLS_ARGS,
                    "E ~ e^{i s t}: the soliton's carrier frequency is omega - s, "
                    "s = g2 a^2/2." + note, "NLS", even_in=even),
        closed_form("bright_kink", br["kink"], (amplitude, g1, g2, mu),
                    "Height of the kink of U under a bright soliton: the integral of the "
                    "mean strain mu |E|^2, 2 mu a^2 w (case II; mu = 1/(v_g^2 - 1) < 0)."
                    + note, "u1", even_in=even),
        closed_form("dark_envelope", dk["envelope"], (xi, t, amplitude, phi, g1, g2),
                    "Dark soliton on a background of peak rotation `amplitude` (g2/g1 < 0), "
                    "grey with angle phi (|phi| < pi/2; phi = 0 black, at rest in the frame "
                    "moving with v_g)." + note, "NLS", even_in=even),
        closed_form("dark_width", dk["width"], (amplitude, phi, g1, g2),
                    "Width w of the dark soliton, |E|^2 = a^2 (1 - cos^2(phi) "
                    "sech^2((xi - V t)/w)): 1/(a cos(phi) sqrt(-g2/g1)) (sites)." + note,
                    "NLS", even_in=even),
        closed_form("dark_velocity", dk["velocity"], (amplitude, phi, g1, g2),
                    "Velocity V of a grey soliton relative to v_g (sites per T); 0 for the "
                    "black one." + note, "NLS", even_in=even),
        closed_form("dark_frequency_shift", dk["frequency_shift"], (amplitude, g2),
                    "E ~ e^{i s t} on the background: carrier frequency omega - s, "
                    "s = g2 a^2." + note, "NLS", even_in=even),
        closed_form("dark_phase_jump", dk["phase_jump"], (phi,),
                    "Jump of arg E across a dark soliton, 2 phi - pi (rad): a ring of N "
                    "sites closes only if k N + jump is a multiple of 2 pi." + note, "NLS"),
        closed_form("dark_kink", dk["kink"], (amplitude, phi, g1, g2, mu),
                    "Height of the kink of U across a dark soliton: the integral of mu "
                    "(|E|^2 - a^2), -2 mu a^2 cos^2(phi) w (case II)." + note, "u1",
                    even_in=even),
        closed_form("continuum_mean_flow_coefficient", continuum_mean_flow(), material,
                    "mu of the continuum, U_X = mu |E|^2 under a profile moving with v_g: "
                    "1/(v_g^2 - 1), from eq. `eqnorm1`. The paper's NLS leaves its feedback "
                    "on g2 out; the kink is still there.", "eqnorm1"),
        closed_form("lattice_g2_mean_flow", lat.g2_mean_flow, material,
                    "The part of the semi-discrete g2_coupled that the mean flow gives "
                    "(-2 alpha^2 mu / omega): on a ring the mean strain is zero, so a dark "
                    "soliton's background does not feel it (its frequency shift omits it).",
                    "u1"),
    )


MODULE_DOC = """Envelope solitons of the NLS (eq. `NLS`) and the kink of U they carry (case II).

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
