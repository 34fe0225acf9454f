"""Probe 100 of the docs (``bench.probe_docs100 --part physics``): the formulas and numbers
the pages state, against computations written here from the equations (FPUT by hand, the
quarter-wavelength four-wave forms, sine-Gordon's and Klein-Gordon's g2, the paper chain's
continuum dispersion, case I's g, erratum 4's edges, the soliton widths)."""

from __future__ import annotations

import json
import math
import re

import numpy as np

from bench._docs100_claims import ROOT, claim, close, py, shown


def fput_by_hand(alpha: float, beta: float, k: float) -> dict:
    """FPUT, V(r) = r^2/2 + alpha r^3/3 + beta r^4/4, unit mass, derived here.

    u_n = A e^{i theta} + c.c. + B e^{2 i theta} + c.c. + mean, theta = k n - omega t; the
    NLS convention of the pages: Omega = omega - g2 a^2 / 4 with a = 2|A| (the peak of u),
    so each part of g2 is -4 (its frequency shift) / a^2.
    """
    s, c = math.sin(k / 2), math.cos(k / 2)
    om = 2 * s
    A = 1.0
    rho = np.exp(1j * k) - 1                       # r_n = rho A e^{i theta}
    back = 1 - np.exp(-1j * k)                     # (.)_n - (.)_{n-1} on e^{i theta}
    # cubic force beta r^3: its first harmonic 3 beta |A|^2 A rho |rho|^2 e^{i theta}
    F3 = 3 * beta * abs(A) ** 2 * A * rho * abs(rho) ** 2 * back
    # second harmonic: -4 omega^2 B = -4 sin^2 k B + alpha A^2 rho^2 (1 - e^{-2ik})
    if abs(4 * math.sin(k) ** 2 - 4 * om ** 2) > 1e-12:
        B = alpha * A ** 2 * rho ** 2 * (1 - np.exp(-2j * k)) / (4 * math.sin(k) ** 2
                                                                 - 4 * om ** 2)
    else:
        B = 0.0
    sigma = np.exp(2j * k) - 1
    F2 = 2 * alpha * np.conj(A) * B * np.conj(rho) * sigma * back
    # mean strain m travelling at v_g: (v_g^2 - 1) m = alpha <r^2> = alpha 2 |rho A|^2;
    # it stiffens the bond (1 + 2 alpha m): omega^2 -> omega^2 (1 + 2 alpha m)
    vg = c
    m = alpha * 2 * abs(rho * A) ** 2 / (vg ** 2 - 1) if vg ** 2 != 1 else 0.0
    a2 = (2 * abs(A)) ** 2
    # -Omega^2 A = -omega^2 A + F  ->  Omega - omega = -F / (2 omega A)
    d3 = (-F3 / (2 * om * A)).real
    d2 = (-F2 / (2 * om * A)).real
    dmf = om * alpha * m
    return dict(omega=om, vg=vg, g1=-s / 2, cubic=-4 * d3 / a2, sh=-4 * d2 / a2,
                mf=-4 * dmf / a2, g2=-4 * (d3 + d2 + dmf) / a2)


def part_physics() -> None:
    import energy
    import numerics.models as M
    from generated import coefficients as GC
    from generated import lattice_coefficients as GL
    from generated import lattice_model as LM

    rng = np.random.default_rng(100)
    # FPUT closed forms of docs/models.md against the hand derivation
    worst_form, worst_code = 0.0, 0.0
    worst = {"omega": 0.0, "vg": 0.0, "g1": 0.0}
    for _ in range(12):
        al, be, k = rng.uniform(-1.5, 1.5), rng.uniform(0.1, 2), rng.uniform(0.05, 3.1)
        h = fput_by_hand(al, be, k)
        s, c = math.sin(k / 2), math.cos(k / 2)
        form = -12 * be * s ** 3 + 8 * al ** 2 * s * (1 + s ** 2)
        form_nomf = -12 * be * s ** 3 - 8 * al ** 2 * s * c ** 2
        worst_form = max(worst_form, abs(form - h["g2"]) / max(1, abs(form)),
                         abs(form_nomf - (h["cubic"] + h["sh"])) / max(1, abs(form_nomf)))
        r = M.nls(energy.load_model("fput", alpha=al, beta=be), k)
        worst_code = max(worst_code, abs(r.g2 - h["g2"]) / max(1, abs(h["g2"])))
        for key, v in (("omega", r.carrier.omega), ("vg", abs(r.carrier.group_velocity)),
                       ("g1", r.carrier.g1)):
            worst[key] = max(worst[key], abs(v - h[key]))
    claim("docs/models.md", "g2 = −12 β s³ + 8 α² s (1 + s²)", worst_form < 1e-12,
          f"FPUT g2 with and without mean flow = hand derivation at 12 (alpha, beta, k): "
          f"worst {worst_form:.1e} (bar 1e-12: the same algebra, round-off)")
    claim("docs/models.md", "g2 = −12 β s³ + 8 α² s (1 + s²)", worst_code < 1e-7,
          f"FPUT g2 of numerics.models.nls = hand derivation: worst {worst_code:.1e} "
          f"(bar 1e-7: the code's Taylor tensors are exact, its eigensolver to ~1e-12)")
    claim("README.md", "The mean flow of the carrier's own field is what makes",
          max(worst.values()) < 1e-9,
          "FPUT omega = 2 sin(k/2), |v_g| = cos(k/2), g1 = -sin(k/2)/2 = the code's at 12 "
          f"points: worst {max(worst.values()):.1e} (bar 1e-9)")
    # README's printed FPUT coefficients (alpha = beta = 1, k = 1.5708)
    h = fput_by_hand(1, 1, 1.5708)
    for needle, val, key in (("g2 (1/(time amplitude^2))                  4.24264", "4.24264", "g2"),
                             ("of which cubic                          -4.24266", "-4.24266",
                              "cubic"),
                             ("of which second harmonic                -2.82842", "-2.82842",
                              "sh"),
                             ("of which mean flow                       11.3137", "11.3137",
                              "mf")):
        claim("README.md", needle, shown(h[key], val), f"FPUT k 1.5708 {key} by hand "
              f"{h[key]:.6g} printed {val}")
    claim("README.md", "g = g2/g1 (1/(site^2 amplitude^2))             -12",
          shown(h["g2"] / h["g1"], "-12"), f"FPUT g = {h['g2'] / h['g1']:.4f} printed -12")
    # models.md's units example: alpha 1, beta 1.5, k 2.5, time 1e-3 s, site 1e-2 m
    h = fput_by_hand(1, 1.5, 2.5)
    for needle, val, key, scale in (
            ("omega (1/time)                             1.89797", "1.89797", "omega", 1),
            ("= 1898 1/s", "1898", "omega", 1e3),
            ("group velocity (site/time)                0.315322", "0.315322", "vg", 1),
            ("= 3.153 m/s", "3.153", "vg", 10),
            ("g1 = d^2 omega/dk^2 (site^2/time)        -0.474492", "-0.474492", "g1", 1),
            ("= -0.04745 m^2/s", "-0.04745", "g1", 0.1),
            ("g2 (1/(time amplitude^2))                -0.954411", "-0.954411", "g2", 1),
            ("= -954.4 1/(s amplitude^2)", "-954.4", "g2", 1e3)):
        claim("docs/models.md", needle, shown(h[key] * scale, val),
              f"FPUT (1, 1.5) k 2.5 {key} x {scale:g} by hand {h[key] * scale:.6g} "
              f"printed {val}")
    # models.md's soliton example: fput alpha 0.5 at k 1.6, simulated at 2 pi 65/256
    h = fput_by_hand(0.5, 1, 1.6)
    line = "carrier:  k = 1.6 rad/site on branch 0, omega = 1.43471; g1 = -0.358678, g2 = -2.2568, g = g2/g1 = 6.292"
    claim("docs/models.md", line, shown(h["omega"], "1.43471") and shown(h["g1"], "-0.358678")
          and shown(h["g2"], "-2.2568") and shown(h["g2"] / h["g1"], "6.292"),
          f"FPUT (0.5, 1) k 1.6 omega {h['omega']:.6g} g1 {h['g1']:.6g} g2 {h['g2']:.5g} "
          f"g {h['g2'] / h['g1']:.4g} by hand")
    ks = 2 * math.pi * 65 / 256
    claim("docs/models.md", "k = 1.59534 rad/site (the nearest a ring carries",
          shown(ks, "1.59534"), f"2 pi 65/256 = {ks:.6f} (N = 256, 8-site soliton)")
    hs = fput_by_hand(0.5, 1, ks)
    w = 2 / (0.1 * math.sqrt(hs["g2"] / hs["g1"]))
    claim("docs/models.md", "width      8.00294", shown(w, "8.00294"),
          f"bright width 2/(a sqrt g) at k = 2 pi 65/256 by hand {w:.6f}")
    claim("docs/models.md", "velocity   0.698376", shown(hs["vg"], "0.698376"),
          f"velocity v_g = cos(k/2) at the ring's k by hand {hs['vg']:.6f}")
    # models.md's three-way point: fput beta 1 at k 2 pi 81/256, a 0.1: NLS peak and offset
    kk = 2 * math.pi * 81 / 256
    h = fput_by_hand(0, 1, kk)
    g = h["g2"] / h["g1"]
    claim("docs/models.md", "carrier:  k = 1.98804 rad/site", shown(kk, "1.98804"),
          f"2 pi 81/256 = {kk:.6f}")
    claim("docs/models.md", "semi-discrete NLS                     MI             0.01767     0.2904",
          shown(abs(h["g2"]) * 0.01 / 4, "0.01767") and shown(0.1 * math.sqrt(g / 2), "0.2904"),
          f"NLS peak |g2| a^2/4 = {abs(h['g2']) * 0.01 / 4:.5f} at q = a sqrt(g/2) = "
          f"{0.1 * math.sqrt(g / 2):.4f} (hand g2)")
    # quarter wavelength (docs/theory.md, docs/models.md, README)
    a, al, be = 0.1, 0.8, 1.0
    sig = a * a * al * math.sqrt(3 * be - 4 * al * al)
    claim("README.md", "four-wave                             MI            0.005307          0",
          shown(sig, "0.005307"), f"backward rate a^2 alpha sqrt(3 beta - 4 alpha^2) at "
          f"alpha 0.8, beta 1, a 0.1 = {sig:.6f}")
    claim("docs/models.md", "β = 1 grows at 0.531 a²", shown(sig / a / a, "0.531"),
          f"the same over a^2 = {sig / a / a:.4f}")
    for al_, txt in ((0.5, "1.667x"), (0.3, "1.146x")):
        ratio = (3 - 2 * al_ ** 2) / abs(3 - 6 * al_ ** 2)
        claim("docs/theory.md", txt, shown(ratio, txt[:-1]),
              f"backward / NLS (3 beta - 2 alpha^2)/|3 beta - 6 alpha^2| at alpha {al_} = "
              f"{ratio:.4f}")
    g2q = math.sqrt(2) * (6 * 0.25 - 3)
    h = fput_by_hand(0.5, 1, math.pi / 2)
    claim("docs/theory.md", "NLS, g2 = √2 (6α² − 3β), says stable", close(h["g2"], g2q, 1e-12),
          f"g2 at pi/2 = sqrt2 (6 alpha^2 - 3 beta) = hand {h['g2']:.6f} (alpha 0.5)")
    claim("docs/theory.md", "g1 = −√2/4", close(h["g1"], -math.sqrt(2) / 4, 1e-12),
          "g1 at pi/2 = -sqrt2/4")
    for n_, nls_ in ((64, "5.30e-3"), (62, "4.75e-3"), (66, "5.88e-3")):
        h = fput_by_hand(0.5, 1, 2 * math.pi * n_ / 256)
        claim("docs/theory.md", f"k = 2π {n_}/256 |" if n_ != 64 else "N 256, k = 2π 64/256",
              shown(abs(h["g2"]) * 0.01 / 4, nls_),
              f"FPUT (0.5, 1) k 2 pi {n_}/256 NLS peak |g2| a^2/4 = "
              f"{abs(h['g2']) * 0.01 / 4:.3e} printed {nls_}")
    kq = math.pi / 2 - 0.049
    Q = 2 * math.acos(math.tan(kq / 2))
    claim("docs/theory.md", "(Q = 0.62 at k = π/2 − 0.049", shown(Q, "0.62"),
          f"cos(Q/2) = tan(k/2) at k = pi/2 - 0.049: Q = {Q:.4f}")
    worst = 0.0
    for _ in range(20):
        k, Q = rng.uniform(0.1, 3), rng.uniform(0, 3)
        w1 = 2 * abs(math.sin((k - math.pi + Q) / 2))
        w2 = 2 * abs(math.sin((k - math.pi - Q) / 2))
        if abs(k + Q) < math.pi and abs(k - Q) < math.pi:
            worst = max(worst, abs(w1 + w2 - 2 * 2 * math.sin(k / 2)
                                   - 4 * (math.cos(k / 2) * math.cos(Q / 2)
                                          - math.sin(k / 2))))
    claim("docs/theory.md", "detuning is 4 [cos(k/2) cos(Q/2) − sin(k/2)]", worst < 1e-12,
          f"backward pair's linear detuning at 20 (k, Q): worst {worst:.1e}")
    # zone boundary: MI iff 3 beta > 4 alpha^2 (g1 < 0 there, so MI where g2 < 0)
    flips = []
    for al_ in (0.8, 0.86, 0.87, 1.0):
        h = fput_by_hand(al_, 1, math.pi - 1e-6)
        flips.append((h["g2"] / h["g1"] > 0) == (3 > 4 * al_ ** 2))
    claim("README.md", "MI needs 3β > 4α²", all(flips),
          "hand g at k -> pi: MI iff 3 beta > 4 alpha^2 at alpha 0.8, 0.86, 0.87, 1")
    # sine-Gordon and Klein-Gordon
    worst_sg = 0.0
    for _ in range(6):
        C, w0, k = rng.uniform(0.3, 2), rng.uniform(0.5, 2), rng.uniform(0.1, 3)
        r = M.nls(energy.load_model("sine-gordon", C=C, omega0=w0), k)
        om = math.sqrt(w0 ** 2 + 4 * C * math.sin(k / 2) ** 2)
        worst_sg = max(worst_sg, abs(r.g2 - w0 ** 2 / (4 * om)) / (w0 ** 2 / (4 * om)),
                       abs(r.carrier.omega - om) / om)
    claim("docs/models.md", "sine-Gordon: g2 = ω0²/(4ω)", worst_sg < 1e-8,
          f"sine-Gordon omega and g2 = omega0^2/(4 omega) (site 1 - cos u = u^2/2 - u^4/24: "
          f"Lindstedt) vs the code at 6 points: worst {worst_sg:.1e}")
    al_, be_ = 0.7, 1.3
    r = M.nls(energy.load_model("klein-gordon", C=1e-7, omega0=1.0, alpha=al_, beta=be_), 1.0)
    duff = -4 * (3 * be_ / 8 - 5 * al_ ** 2 / 12)       # g2 = -4 shift / a^2
    claim("docs/models.md", "shift of one oscillator (3β/8 − 5α²/12) a²",
          close(r.g2, duff, 1e-5), f"Klein-Gordon C 1e-7: g2 {r.g2:.7f} = -4 (3 beta/8 - "
          f"5 alpha^2/12) = {duff:.7f} (Duffing, by hand)")
    # the paper chain: README's table from the continuum dispersion by hand
    for name, k, d, Kt, row in (("blue", 0.81681, 0.003, 0.01551, (" blue  rotation", "0.7708",
                                                                    "0.019869", "0.023813")),
                                ("green", 0.92991, -0.003, 0.02151,
                                 ("green  rotation", "0.88905", "-0.019612", "-0.021523"))):
        al = 2.5
        om = al * math.sqrt(6 * Kt + d * k * k)
        vg = al * al * d * k / om
        g1 = al * al * d / om - vg * vg / om
        claim("README.md", row[0], shown(om, row[1]) and shown(vg, row[2]) and shown(g1, row[3]),
              f"{name}: continuum omega^2 = alpha^2 (6 K_theta + delta k^2): omega {om:.5f}, "
              f"v_g {vg:.6f}, g1 {g1:.6f} (printed {', '.join(row[1:])})")
    tab = {}
    for line in (ROOT / "README.md").read_text().splitlines():
        m = re.match(r"\s*(blue|green)\s+(rotation|coupled)\s+(\S+)\s+(\S+)\s+\S+\s+\S+\s+\S+\s+"
                     r"(\S+)\s+(\S+)\s+(\S+)\s+(\S+)\s+(.*)$", line)
        if m:
            tab[(m.group(1), m.group(2))] = m.groups()
    for (pt, case), gr in tab.items():
        k, d, g2, g, Kc, Km = float(gr[2]), float(gr[3]), float(gr[4]), float(gr[5]), gr[6], gr[7]
        Kt = 0.01851 - d
        if case == "rotation":
            gf = -(d * k * k + 6 * Kt) / (2 * Kt * d)
            claim("README.md", f"{pt:>5}  rotation", shown(gf, gr[5]),
                  f"{pt} I: g = -(delta k^2 + 6 K_theta)/(2 K_theta delta) = {gf:.2f}")
        if g > 0:
            # g is printed to 5 digits: K_c and K_m carry half its last unit's share
            dg = 0.5 * 10.0 ** (-len(gr[5].split(".")[1]) if "." in gr[5] else 0) / g / 2
            ok = (close(2 * math.sqrt(g), float(Kc), abs_=dg * 2 * math.sqrt(g) + 0.0005)
                  and close(math.sqrt(2 * g), float(Km), abs_=dg * math.sqrt(2 * g) + 0.0005))
            detail = f"K_c = 2 sqrt(g) = {2 * math.sqrt(g):.3f}, K_m = {math.sqrt(2 * g):.3f}"
        else:
            ok = Kc == "-" and Km == "-"
            detail = "g < 0: no band"
        verdict_ok = ("MI" in gr[8]) == (g > 0)
        claim("README.md", f"{pt:>5}  {case:>8}", ok and verdict_ok,
              f"{pt} {case}: {detail}; verdict {gr[8].strip()!r} for g {g}")
    # simulator.md's full-run table: the paper NLS's peak |g2| a^2/4 and half-gain edge
    # (sigma = sigma_max/2 at q^2 = g a^2 (1 + sqrt3/2)/2), and the carrier's frequency
    for pt, case, peak, edge in (("blue", "coupled", "4.97e-3", "0.883"),
                                 ("green", "rotation", "2.11e-3", "0.605")):
        g2_, g_ = float(tab[(pt, case)][4]), float(tab[(pt, case)][5])
        pk, ed = abs(g2_) * 0.02 ** 2 / 4, 0.02 * math.sqrt(g_ * (1 + math.sqrt(3) / 2) / 2)
        claim("docs/simulator.md", f"| peak gain, {pt} case {'II' if case == 'coupled' else 'I'} | {peak}",
              shown(pk, peak), f"{pt} {case}: paper NLS peak |g2| a^2/4 = {pk:.3e} (a = 0.02)")
        claim("docs/simulator.md", f"| half-gain band edge, {pt} case", shown(ed, edge),
              f"{pt} {case}: half-gain edge {ed:.4f} (by hand from sigma(q))")
    om_l = 2.5 * math.sqrt(6 * 0.02151 - 0.012 * math.sin(0.92991 / 2) ** 2)
    fr = om_l - 1e-4 * float(tab[("green", "coupled")][4])
    claim("docs/simulator.md", "discrete2 - eps^2 g2 A0^2 = 0.8836", shown(fr, "0.8836"),
          f"green II: discrete2 {om_l:.5f} - eps^2 g2 = {fr:.5f}")
    gg = tab[("green", "coupled")]
    om_g = 2.5 * math.sqrt(6 * 0.02151 - 0.003 * 0.92991 ** 2)
    vg_g = -2.5 ** 2 * 0.003 * 0.92991 / om_g
    g1 = -2.5 ** 2 * 0.003 / om_g - vg_g * vg_g / om_g     # continuum g1 at the green point
    claim("docs/reliability.md", "g_coupled(k=0.92991, delta=-0.003) = -2.82e3 < 0 (g2 > 0, g1 < 0)",
          float(gg[5]) < 0 and float(gg[4]) > 0 and g1 < 0 and shown(float(gg[5]), "-2.82e3"),
          f"erratum 1: green II g {gg[5]}, g2 {gg[4]} > 0, g1 {g1:.6f} < 0 (hand dispersion)")
    # README's coefficients example: peak |g2| a^2/4, e-folding 1/peak, U at 2k = |c| amp^2/2
    pk = 1.3722 * 0.02 ** 2 / 4
    claim("README.md", "peak gain (1/T)                         0       0.00013722",
          shown(pk, "0.00013722"), f"coefficients: peak |g2| a^2/4 = {pk:.5g}")
    claim("README.md", "e-folding time (T)                      -             7288",
          shown(1 / 1.3722e-4, "7288"), f"coefficients: e-folding 1/peak = {1 / 1.3722e-4:.1f}")
    claim("README.md", "U at 2k = |c| amp^2/2             6.649e-05        5.001e-05",
          shown(0.332447 * 0.02 ** 2 / 2, "6.649e-05") and shown(0.250034 * 0.02 ** 2 / 2, "5.001e-05"),
          "coefficients: U at 2k = |c| amp^2/2 from the printed |c|")
    worst = 0.0
    for _ in range(40):
        al, Ks, Kt, k = (rng.uniform(1.5, 3.5), rng.uniform(0.005, 0.05),
                         rng.uniform(0.005, 0.05), rng.uniform(0.05, 3))
        d = Ks - Kt
        if abs(d) < 1e-3:
            continue
        gf = -(d * k * k + 6 * Kt) / (2 * Kt * d)
        worst = max(worst, abs(GC.g_rotation(k, al, Ks, Kt) - gf) / abs(gf))
    claim("docs/theory.md", "g = -(delta k^2 + 6 K_theta) /", worst < 1e-10,
          f"case I g formula vs generated g_rotation at random materials: worst {worst:.1e}")
    # theory.md's singular points: NumPy semantics, never an exception
    import warnings
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        sing = dict(g1=GC.g1(0.8, 2.5, 0.02, 0.02), g=GC.g_rotation(0.8, 2.5, 0.02, 0.02),
                    cut=GC.mi_cutoff(-5.0, 1.0), fast=GC.mi_fastest(-5.0, 1.0),
                    out=GC.mi_growth_rate(100.0, 50.0, 1.0), inb=GC.mi_growth_rate(1.0, 50.0, 1.0),
                    im=GC.omega(3.5, 2.5, 0.01, 0.02))
    kr = math.sqrt(6 * 2.5 ** 2 * 0.01551 / (1 - 2.5 ** 2 * 0.003))   # k^2 = omega^2 (continuum)
    near = abs(GC.u2_coefficient(kr + 1e-7, 2.5, 0.01851, 0.01551))
    far = abs(GC.u2_coefficient(kr + 0.1, 2.5, 0.01851, 0.01551))
    claim("docs/theory.md", "Singular points follow NumPy semantics", sing["g1"] == 0
          and math.isinf(sing["g"]) and math.isnan(sing["cut"]) and math.isnan(sing["fast"])
          and sing["out"] == 0 and sing["inb"] > 0 and len(caught) > 0,
          f"g1 = 0, g = {sing['g']} at delta = 0; mi_cutoff/fastest NaN for g < 0; growth 0 "
          f"outside the band; {len(caught)} RuntimeWarning(s), no exception")
    claim("docs/theory.md", "diverge at the resonance k^2 = omega^2", near > 1e4 * far,
          f"u2 at k_r + 1e-7 ({near:.3g}) against k_r + 0.1 ({far:.3g}), k_r = "
          f"sqrt(6 alpha^2 K_theta / (1 - alpha^2 delta)) = {kr:.5f} by hand")
    claim("docs/maps.md", "(δ < 0, k² > 6 K_θ / |δ|)", math.isnan(sing["im"])
          and not math.isnan(GC.omega(3.4, 2.5, 0.01, 0.02)),
          "continuum omega NaN at delta -0.01, K_theta 0.02, k 3.5 (k^2 > 12), real at 3.4")
    # erratum 4: the rotational branch's edges, from eq. discrete2's generated form
    worst = 0.0
    for _ in range(20):
        al, Ks, Kt = rng.uniform(1.5, 3.5), rng.uniform(0.005, 0.05), rng.uniform(0.005, 0.05)
        lo = LM.omega_rotation(0.0, al, Ks, Kt)
        hi = LM.omega_rotation(math.pi, al, Ks, Kt)
        worst = max(worst, abs(lo - al * math.sqrt(6 * Kt)) / lo,
                    abs(hi - al * math.sqrt(2 * Kt + 4 * Ks)) / hi)
    claim("docs/reliability.md", "lower edge is alpha sqrt(2 K_theta + 4 K_s)", worst < 1e-12,
          f"omega_rotation(0) = alpha sqrt(6 K_theta), (pi) = alpha sqrt(2 K_theta + 4 K_s): "
          f"worst {worst:.1e}")
    # solitons.md: the green bright soliton at amplitude 0.02 is 2.8 sites (g = 1274)
    gs = GL.g_rotation(0.92991, 2.5, 0.01851, 0.02151)
    claim("docs/solitons.md", "(semi-discrete g = 1274)", shown(gs, "1274")
          and shown(2 / (0.02 * math.sqrt(gs)), "2.8"),
          f"green I semi-discrete g {gs:.1f}, width 2/(0.02 sqrt g) = "
          f"{2 / (0.02 * math.sqrt(gs)):.2f}")
    # solitons.md's command: the semi-discrete carrier is eq. discrete2's lattice branch,
    # omega^2 = alpha^2 (6 K_theta + 4 delta sin^2(k/2)) (alpha 2, K_theta 0.02, delta 0.01)
    al, Kt, d, k = 2.0, 0.02, 0.01, 1.0
    om = al * math.sqrt(6 * Kt + 4 * d * math.sin(k / 2) ** 2)
    vg = al * al * d * math.sin(k) / om
    g1 = al * al * d * math.cos(k) / om - vg * vg / om
    claim("docs/solitons.md", "NLS (semi-discrete): omega = 0.718871 1/T, v_g = 0.046822",
          shown(om, "0.718871") and shown(vg, "0.046822") and shown(g1, "0.02701"),
          f"discrete2 by hand: omega {om:.6f}, v_g {vg:.6f}, g1 {g1:.5f}")
    # theory.md: the free U wave at 2k of the blue point, omega_U(2k) = 2 sin(k) (c = 1)
    claim("docs/theory.md", "(frequency omega_U(2k) = 1.458", shown(2 * math.sin(0.81681), "1.458"),
          f"omega_U(2k) = 2 sin(k) at k 0.81681: {2 * math.sin(0.81681):.4f}")
    # solitons.md's Python example: the dark soliton's width and kink from its closed forms
    al, Ks, Kt, k, amp = 3.0, 0.05, 0.03, 0.7, 0.009
    gd = GL.g_coupled(k, al, Ks, Kt)
    a = amp / 2
    w = 1 / (a * math.sqrt(-gd))
    mu = 1 / (GL.group_velocity(k, al, Ks, Kt) ** 2 - 1)
    claim("docs/solitons.md", "dark 31.15 sites, v = 0.08882, kink 0.001272",
          gd < 0 and shown(w, "31.15") and shown(-2 * mu * a * a * w, "0.001272")
          and shown(GL.group_velocity(k, al, Ks, Kt), "0.08882"),
          f"black soliton: w = 1/(a sqrt(-g)) {w:.2f}, kink -2 mu a^2 w {-2 * mu * a * a * w:.4g}, "
          f"v = v_g {GL.group_velocity(k, al, Ks, Kt):.5f} (generated g, v_g; the page's forms)")
    # theory.md: the blue point's near-resonance 2 sin(k + q/2) = Omega + omega(k + q), q ~ 0.13
    from scipy.optimize import brentq
    al, Ks, Kt, k = 2.5, 0.01851, 0.01551, 0.81681

    def w2(q):
        return al * math.sqrt(6 * Kt + 4 * (Ks - Kt) * math.sin(q / 2) ** 2)
    qr = brentq(lambda q: 2 * math.sin(k + q / 2) - w2(k) - w2(k + q), 0.01, 0.5)
    claim("docs/theory.md", "(2 sin(k + q/2) = Omega + omega(k + q) at q ~ 0.13)", shown(qr, "0.13"),
          f"blue II near-resonance by hand (discrete2, U's 2 sin(q/2), Omega ~ omega): q = {qr:.4f}")
    # simulator.md: the green point's second-harmonic denominators
    kg, Ktg = 0.92991, 0.02151
    om_c2 = 2.5 ** 2 * (6 * Ktg - 0.003 * kg * kg)
    om_l2 = 2.5 ** 2 * (6 * Ktg - 0.012 * math.sin(kg / 2) ** 2)
    claim("docs/simulator.md", "(+0.074) and the lattice one, sin^2 k - omega^2 (-0.15)",
          shown(kg * kg - om_c2, "0.074") and shown(math.sin(kg) ** 2 - om_l2, "-0.15"),
          f"green: k^2 - omega_c^2 = {kg * kg - om_c2:.4f}, sin^2 k - omega_l^2 = "
          f"{math.sin(kg) ** 2 - om_l2:.4f} (by hand)")
    # theory.md: the mean flow mu = 1/(v_g^2 - 1) adds 2 alpha^2/(omega (1 - v_g^2)) to g2
    from generated import soliton as GS
    worst = 0.0
    for _ in range(20):
        p_ = (rng.uniform(0.05, 3), rng.uniform(1.5, 3.5), rng.uniform(0.005, 0.05),
              rng.uniform(0.005, 0.05))
        w_, v_ = GL.omega(*p_), GL.group_velocity(*p_)
        worst = max(worst, abs(GS.lattice_g2_mean_flow(*p_) / (2 * p_[1] ** 2 / (w_ * (1 - v_ * v_)))
                               - 1), abs(GL.mean_flow_coefficient(*p_) * (v_ * v_ - 1) - 1))
    claim("docs/theory.md", "and the induced mean flow mu = 1/(v_g^2 - 1), which adds", worst < 1e-12,
          f"generated mean flow = 1/(v_g^2 - 1) and its g2 part 2 alpha^2/(omega (1 - v_g^2)) at 20 "
          f"random points: worst {worst:.1e}")
    # flexmm-lossy: theta decays at gamma_theta alpha^2 / 2
    claim("docs/models.md", "θ decays at `gamma_theta` α²/2", shown(1e-3 * 2.5 ** 2 / 2, "0.003125"),
          "gamma_theta alpha^2/2 = 1e-3 x 6.25 / 2 = 0.003125")
    r = py(["-m", "cli", "coefficients", "--model", "flexmm-lossy", "--k", "1", "--amplitude",
            "0.01", "--json"])
    try:
        cd = json.loads(r.stdout)
        got = _find_key(cd, "carrier_damping")
    except (ValueError, KeyError):
        got = float("nan")
    claim("docs/models.md", "θ decays at `gamma_theta` α²/2", close(got, 0.003125, 1e-3),
          f"flexmm-lossy k 1: coefficients --json carrier_damping {got} (bar 0.1%: U's share "
          "of the branch at k = 1)")
    claim("docs/models.md", "(Γ = 0.025 on the carrier", shown(0.008 * 2.5 ** 2 / 2, "0.025"),
          "gamma 0.008: 0.008 x 6.25 / 2 = 0.025")
    claim("README.md", "semi-discrete NLS               0.015", shown(0.03 / 2, "0.015"),
          "fput-lossy gamma 0.03 on site, unit mass: amplitude decay gamma/2 = 0.015")
    # models.md: FPUT alpha 1, beta 1.5 at k 2.45: g2 = -0.80 of a cubic -15.0 and mean flow +15.1
    h = fput_by_hand(1.0, 1.5, 2.45)
    claim("docs/models.md", "has g2 = −0.80 left of a cubic part −15.0", shown(h["g2"], "-0.80")
          and shown(h["cubic"], "-15.0") and shown(h["mf"], "15.1"),
          f"FPUT (1, 1.5) k 2.45 by hand: g2 {h['g2']:.3f}, cubic {h['cubic']:.2f}, mean flow "
          f"{h['mf']:.2f}")
    # solitons.md's closed forms solve i E_t + g1/2 E_xx + g2 |E|^2 E = 0 (finite differences)
    worst = 0.0
    for _ in range(6):
        g1_ = rng.uniform(0.01, 0.5) * rng.choice([-1, 1])
        a = rng.uniform(0.001, 0.05)
        for kind in ("bright", "dark"):
            g2_ = abs(rng.uniform(0.5, 50)) * (np.sign(g1_) if kind == "bright" else -np.sign(g1_))
            g = g2_ / g1_
            phi = rng.uniform(-1.2, 1.2)
            if kind == "bright":
                w = 1 / (a * math.sqrt(g))

                def E(x, t, a=a, w=w, g2_=g2_):
                    return a / np.cosh(x / w) * np.exp(1j * g2_ * a * a * t / 2)
            else:
                w = 1 / (a * math.cos(phi) * math.sqrt(-g))
                V = g1_ * a * math.sin(phi) * math.sqrt(-g)

                def E(x, t, a=a, w=w, g2_=g2_, V=V, phi=phi):
                    return (a * np.exp(1j * g2_ * a * a * t)
                            * (math.cos(phi) * np.tanh((x - V * t) / w) + 1j * math.sin(phi)))
            x = np.linspace(-4 * w, 4 * w, 41)
            hx, ht = w * 1e-3, 1e-3 / (abs(g2_) * a * a)
            Et = (E(x, ht) - E(x, -ht)) / (2 * ht)
            Exx = (E(x + hx, 0) - 2 * E(x, 0) + E(x - hx, 0)) / hx ** 2
            res = 1j * Et + g1_ / 2 * Exx + g2_ * np.abs(E(x, 0)) ** 2 * E(x, 0)
            worst = max(worst, np.max(np.abs(res)) / (abs(g2_) * a ** 3))
    claim("docs/solitons.md", "| bright (g > 0) | a sech(xi/w) e^{i g2 a^2 t/2}", worst < 1e-4,
          f"bright and grey closed forms solve the NLS at 12 random (g1, g2, a, phi): residual "
          f"{worst:.1e} of g2 a^3 (bar 1e-4: second differences at h = 1e-3 w, O(h^2))")
    a_, mu_, g_ = 0.0031, -1.7, 45.0
    w_ = 1 / (a_ * math.sqrt(g_))
    claim("docs/solitons.md", "2 mu a^2 w = mu amplitude / sqrt(g)",
          close(2 * mu_ * a_ * a_ * w_, mu_ * (2 * a_) / math.sqrt(g_), 1e-14),
          "kink 2 mu a^2 w = mu amplitude / sqrt(g) with w = 1/(a sqrt g), amplitude = 2a")
    # NLS gain formulas (models.md): peak |g2| a^2/4 at a sqrt(g/2), edge a sqrt(g)
    g1, g2, a = -0.3, -1.7, 0.07
    g = g2 / g1
    q = np.linspace(1e-6, a * math.sqrt(g) - 1e-9, 200001)
    sg = abs(g1) / 2 * q * np.sqrt(g * a * a - q * q)
    claim("docs/models.md", "peak\n" if False else "|g2| a²/4 at offset q = a √(g/2), band edge a √g",
          close(sg.max(), abs(g2) * a * a / 4, 1e-8) and close(q[sg.argmax()], a * math.sqrt(g / 2),
                                                              1e-3),
          "sigma(q) = (|g1|/2)|q| sqrt(g a^2 - q^2): max |g2| a^2/4 at a sqrt(g/2) (numeric max)")


def _find_key(obj, key):
    if isinstance(obj, dict):
        if key in obj and isinstance(obj[key], (int, float)):
            return obj[key]
        for v in obj.values():
            try:
                return _find_key(v, key)
            except KeyError:
                pass
    if isinstance(obj, list):
        for v in obj:
            try:
                return _find_key(v, key)
            except KeyError:
                pass
    raise KeyError(key)
