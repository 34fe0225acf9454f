"""Newuser 101's checks, reproducible: a new user's own model files (a Morse chain, a
two-field chain with a linear cross term, its damped twin) against physics computed here,
the docs' edited statements run as written, and the findings fixed on branch newuser101.

- Morse (D 0.5, b 1: unit stiffness): omega = 2 sin(k/2), v_g = cos(k/2), g1 = -sin(k/2)/2;
  g2 against FPUT's closed form (docs/models.md) with the Morse bond's Taylor coefficients
  by hand (alpha = -3 D b^3, beta = 7/3 D b^4), its cubic part -12 beta s^3 alone too;
- two-field chain: omega from its 2 x 2 dynamical matrix by hand; the frequency shift from
  the averaged Lagrangian (6 beta a^2 s^4 / (n omega), n the mode's kinetic norm); the
  damped twin's carrier damping gamma/2 x u's kinetic share; the NLS's amplification
  along the decaying carrier from the linearised damped NLS integrated here (solve_ivp,
  the growing eigenvector's start) at 1e-2 (the offset grid here is 0.0025 apart);
- the zone boundary's NLS (g2 = 16 alpha^2 - 12 beta at k = pi) and the exact rate the docs
  give (0.0058), the narrow bands' three rates docs/models.md gives (3.63e-5, 2.0e-4,
  2.95e-6, 1%);
- the fixes: a lossy point's estimate covers its runs, the branch-index note per row
  (against the hand omegas), four-wave's reason at eta 0, the zero-mode refusal's remedy.

    python -m bench.probe_newuser101

One line a check, ``!!`` where it disagrees, the list at the end (exit 1 where any). ~15 s
on the 2-core VM (2026-11-27: 18 checks in 12 s, 0 disagreements on branch newuser101, 4 on main before it).
"""

from __future__ import annotations

import math
import subprocess
import sys
import tempfile
from pathlib import Path

import numpy as np

from bench._fourwave100_models import MORSE

TWOFIELD = '''name = "twofield"
fields = ["u", "v"]
[parameters]
Cv = 0.5
eta = 0.3
w0 = 1.5
beta = 1.0
[energy]
kinetic = "u_t**2/2 + v_t**2/2"
bond = "(u_next - u)**2/2 + Cv*(v_next - v)**2/2 + eta*(u_next - u)*(v_next - v) + beta*(u_next - u)**4/4"
site = "w0**2*v**2/2"
'''
LOSSY = TWOFIELD.replace('"twofield"', '"twofield-lossy"').replace(
    "beta = 1.0\n", "beta = 1.0\ngamma = 0.0005\n") + '[dissipation]\nsite = "gamma*u_t**2/2"\n'

BAD: list[str] = []


def say(name: str, ok: bool, text: str) -> None:
    print(f"{'ok' if ok else '!!'} {name}: {text}")
    if not ok:
        BAD.append(name)


def hand_twofield(k, eta=0.3, Cv=0.5, w0=1.5):
    """(omegas ascending, eigenvectors) of the two-field chain's dynamical matrix by hand."""
    c = 2 * (1 - math.cos(k))
    K = np.array([[c, eta * c], [eta * c, Cv * c + w0 ** 2]])
    lam, vec = np.linalg.eigh(K)
    return np.sqrt(lam), vec


def damped_nls_amplification(g1, g2, a, gamma_c, qs, t_end=8000.0):
    """max over q, t of a(t)/a0 |w(t)| from the growing eigenvector of the linearised
    damped NLS i A_t + g1/2 A_xx + g2 |A|^2 A + i Gamma A = 0 (|A| = a/2)."""
    from scipy.integrate import solve_ivp

    P, Q, A0 = g1 / 2, g2, a / 2
    best = (0.0, 0.0)
    for q in qs:
        def f(t, y, q=q):
            a2 = (A0 * math.exp(-gamma_c * t)) ** 2
            return [P * q * q * y[1], (2 * Q * a2 - P * q * q) * y[0]]
        M0 = np.array([[0, P * q * q], [2 * Q * A0 ** 2 - P * q * q, 0]])
        w, V = np.linalg.eig(M0)
        if not np.max(w.real) > 0:
            continue
        e = np.real(V[:, np.argmax(w.real)])
        ts = np.linspace(0, t_end, 4001)
        s = solve_ivp(f, (0, t_end), e / np.linalg.norm(e), t_eval=ts, rtol=1e-10, atol=1e-13)
        amp = np.linalg.norm(s.y, axis=0) * np.exp(-gamma_c * ts)
        i = int(np.argmax(amp))
        best = max(best, (float(amp[i]), float(ts[i])))
    return best


def main() -> int:
    from energy import load_model
    from numerics.maps import ModelPointSpec, measure_point
    from numerics.models import exact_gain, four_wave, nls

    tmp = Path(tempfile.mkdtemp(prefix="nu101-"))
    for name, text in (("morse", MORSE), ("twofield", TWOFIELD), ("lossy", LOSSY)):
        (tmp / f"{name}.toml").write_text(text)
    morse, two, lossy = (load_model(tmp / f"{n}.toml") for n in ("morse", "twofield", "lossy"))

    for k in (0.7, 2.0, 2.9):  # Morse: the FPUT closed forms with its Taylor coefficients
        c = nls(morse, k)
        s = math.sin(k / 2)
        al, be = -3 * 0.5, 7 / 3 * 0.5
        g2 = -12 * be * s ** 3 + 8 * al ** 2 * s * (1 + s * s)
        err = max(abs(c.carrier.omega - 2 * s), abs(c.carrier.group_velocity - math.cos(k / 2)),
                  abs(c.g1 + s / 2), abs(c.g2 - g2) / abs(g2))
        say(f"morse k {k}", err < 1e-9, f"omega, v_g, g1, g2 against FPUT's forms: {err:.1e}")

    c = nls(two, 1.0)
    w, v = hand_twofield(1.0)
    e = v[:, 0] / v[0, 0]  # a measures u
    shift = 6 * 1.0 * 0.01 * math.sin(0.5) ** 4 / (e @ e * w[0])
    err = max(abs(c.carrier.omega - w[0]), abs(c.g2 * 0.01 / 4 + shift) / shift)
    say("twofield k 1", err < 1e-8, f"omega by hand, frequency shift by averaging: {err:.1e}")

    d = measure_point(ModelPointSpec(lossy, 1.0, 0.1, N=256)).as_dict()
    nl = d["semi-discrete NLS"]
    share = 1 / (e @ e)  # u's kinetic share of the carrier at k 1 (the ring's k is 1.00629)
    gam = d["exact lattice"]["carrier_damping"]
    say("lossy damping", abs(gam / (0.0005 / 2 * share) - 1) < 2e-2,
        f"{gam:.6g} against gamma/2 x u's share {0.0005 / 2 * share:.6g} (k 1; ring k 1.006)")
    co = nls(lossy, float(d["k"]))
    amp, t = damped_nls_amplification(co.g1, co.g2, 0.1, gam, np.arange(0.06, 0.12, 0.0025))
    say("lossy NLS amplification", abs(nl["amplification"] / amp - 1) < 1e-2,
        f"{nl['amplification']:.4g} at {nl['amplification_time']:.4g} against {amp:.4g} at "
        f"{t:.4g} (linearised damped NLS here)")

    fput = load_model("fput")
    for al, grows in ((0.8, True), (1.0, False)):
        c = nls(fput.with_params(alpha=al, beta=1.0), math.pi)
        say(f"fput pi alpha {al}", abs(c.g2 - (16 * al * al - 12)) < 1e-9,
            f"g2 {c.g2:.6g} = 16 alpha^2 - 12 beta")
        g = exact_gain(fput.with_params(alpha=al, beta=1.0), math.pi, 0.1, N=256).peak_gain
        ok = abs(g / 0.0058 - 1) < 0.01 if grows else g == 0
        say(f"fput pi alpha {al} exact", ok, f"{g:.4g} (docs: 0.0058 / no growth)")
    for name, m, k, a, want in (("morse", morse, 1.2855, 0.015, 3.63e-5),
                                ("fput 0.6", fput.with_params(alpha=0.5), 0.6, 0.1, 2.0e-4),
                                ("fput 1.5", fput.with_params(alpha=0.5), 1.5, 0.002, 2.95e-6)):
        g = exact_gain(m, k, a).peak_gain
        say(f"narrow band {name}", abs(g / want - 1) < 0.01, f"{g:.4g} (docs {want:g})")

    seen = []
    p = measure_point(ModelPointSpec(lossy, 1.0, 0.1, N=64, simulate=True, seeds=1),
                      on_estimate=seen.append).as_dict()
    say("lossy estimate", seen[0].t_end >= p["simulated"]["t_end"],
        f"estimated T {seen[0].t_end:.5g}, the runs went to {p['simulated']['t_end']:.5g}")

    fw = four_wave(two.with_params(eta=0.0), 2.8, 0.1, N=256)
    say("four-wave eta 0", "driven wave" not in fw.undefined and "crossing" in fw.undefined,
        fw.undefined[:90])

    (tmp / "x.toml").write_text(TWOFIELD.replace("w0 = 1.5", "w0 = 1.0"))
    out = subprocess.run([sys.executable, "-m", "cli", "map", "--model", str(tmp / "x.toml"),
                          "--branch", "v", "--k", "0.2,3.0", "--param", "eta=0.1,0.3",
                          "--amplitude", "0.05", "--theory-only", "--workers", "1",
                          "--out", str(tmp / "m")], capture_output=True, text=True).stdout
    for eta in (0.1, 0.3):
        want = [hand_twofield(k, eta, w0=1.0) for k in (0.2, 3.0)]
        vdom = [float(w[int(np.argmax(np.abs(v[1])))]) for w, v in want]
        line = next((ln for ln in out.splitlines() if "changes along k" in ln), "")
        part = line.split(f"at eta = {eta:g}: ")[-1].split(";")[0] if line else ""
        got = [float(x) for x in __import__("re").findall(r"omega ([\d.]+)", part)]
        ok = len(got) == 2 and all(abs(g - h) < 1e-3 for g, h in zip(got, vdom, strict=True))
        say(f"branch note eta {eta}", ok, f"{got} against hand {np.round(vdom, 4).tolist()}")

    (tmp / "z.toml").write_text('name = "z"\nfields = ["u"]\n[energy]\nkinetic = "u_t**2/2"\n'
                                'bond = "(u_next - u)**2"\nsite = "u**3"\n')
    r = subprocess.run([sys.executable, "-m", "cli", "coefficients", "--model",
                        str(tmp / "z.toml"), "--k", "1"], capture_output=True, text=True)
    say("zero mode refusal", r.returncode == 2 and "on-site stiffness" in r.stderr
        and r.stderr.count("\n") == 1, r.stderr.strip()[:90])

    print(f"{len(BAD)} disagreement(s)" + (": " + ", ".join(BAD) if BAD else ""))
    return 1 if BAD else 0


if __name__ == "__main__":
    sys.exit(main())
