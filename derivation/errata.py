"""Errata of the paper found while deriving and simulating (shown in derivation.md).

Each entry: where in the paper, what it says, what is right, how we know.
"""

ERRATA = (
    {
        "where": "Sec. 'Stabilizing plane waves using the coupling of dofs', first paragraph",
        "says": "case (II) at the green point is described by a 'focusing' NLS, hence stable",
        "right": "it is *defocusing*: g_coupled(k=0.92991, delta=-0.003) = -2.82e3 < 0 "
                 "(g2 > 0, g1 < 0), which is why the plane wave is stable",
        "how": "derived g (tests/test_derivation.py::test_paper_test_points) and the "
               "paper's own definition below eq. `NLS_final` (focusing iff g > 0)",
    },
    {
        "where": "Caption of Fig. `Spectrumline` (Fig. 9)",
        "says": "'For case (II), t = 2500 ... For case (II), t = 5000 for A0 = 0.8 and "
                "t = 1700 for A0 = 1.4'",
        "right": "the second sentence is case (I): the green point is unstable only in "
                 "case (I) (panels b, d)",
        "how": "panels (a,c) are the blue point case (II), (b,d) the green point case (I), "
               "as the caption's first sentence says; g > 0 only for those two runs",
    },
    {
        "where": "Normalisation below eq. `norm`",
        "says": "alpha = a / sqrt(m / (4 J))",
        "right": "alpha = a / sqrt(4 J / m) = a sqrt(m / (4 J))",
        "how": "alpha must be dimensionless (it multiplies a dimensionless equation); "
               "a/sqrt(m/(4J)) has the dimension of a length squared, since J/m is a "
               "length squared. Time scaling T = t sqrt(k_l/m) and the rotational inertia "
               "J give 1/alpha^2 = 4J/(m a^2) in front of theta_TT",
    },
    {
        "where": "Text after eq. `discrete2`",
        "says": "the rotational branch has 'a lower cutoff frequency at omega = alpha "
                "sqrt(6 K_theta)'",
        "right": "only for delta > 0. For delta < 0 the branch decreases with q: "
                 "alpha sqrt(6 K_theta) is its upper edge and the lower edge is "
                 "alpha sqrt(2 K_theta + 4 K_s) at q = pi",
        "how": "eq. `discrete2` at q = 0 and q = pi",
    },
    {
        "where": "Eq. `IC`",
        "says": "theta(n, 0) = 2 eps (1 + b0) cos(k n) (no A0)",
        "right": "theta(n, 0) = 2 eps A0 (1 + b0) cos(k n); Fig. 9 varies A0, and B = A0 "
                 "in theta = eps (B e^{i sigma} + c.c.)",
        "how": "eq. `leadingorder` with B = A0 gives amplitude 2 eps A0",
    },
    {
        "where": "Text after eq. `u1`",
        "says": "the homogeneous part of u2 'is omitted due to our choice of initial "
                "conditions U(0,X) = U_T(0,X) = 0'",
        "right": "with U = U_T = 0 at T = 0 the homogeneous part is *required*: free "
                 "longitudinal waves at 2k (frequency 2k, not 2 omega) cancel the forced "
                 "second harmonic at T = 0 and beat against it. Also the zeroth harmonic of "
                 "u (the induced mean flow, driven by d|B|^2/dX at O(eps^3)) is set to zero",
        "how": "the O(eps^2) U-equation is a wave equation; its forced solution "
               "c B^2 e^{2 i sigma} + c.c. does not vanish at T = 0, so the initial "
               "condition fixes a non-zero free part",
    },
)
