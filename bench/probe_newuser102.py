"""Probe newuser102: an experimentalist's sample (SI units, a measured damping) through
``flexmm coefficients`` and the honest mistakes of a first afternoon, as checks.

At seeded random points of the paper chain with losses (``flexmm-lossy``: alpha 1.5-3.5,
K_s 0.005-0.05, K_theta 0.005-0.05, k 0.1-3.0, a measured amplitude ring-down Gamma
0.05-5 1/s, a lattice time unit sqrt(m/k_l) of 0.2-5 ms), each against physics written
here from eq. `norm` and the Rayleigh function, never by the code under test:

- the recipe of docs/models.md: gamma_theta = 2 Gamma sqrt(m/k_l) / alpha^2 put in, the
  carrier damping `coefficients --json` reports in 1/s is Gamma again (1e-9 relative: theta
  and U are not coupled linearly, so the rotational carrier is pure theta);
- omega in 1/s and the printed f in Hz against the rotational branch's closed form
  omega^2 = alpha^2 (4 K_s sin^2(k/2) + 4 K_theta cos^2(k/2) + 2 K_theta) (f to the 4
  digits printed);
- the paper chain's `--physical` table: its semi-discrete f = omega/2pi row against the same
  closed form (6 digits printed);
- the mistakes: a negative damping, a damping typed in 1/s (an overdamped carrier, said),
  an amplitude in degrees (paper flags: refused with the value in rad; a model: a note with
  it), --physical with --model, k above pi: one line on stderr and exit 2, or the note.

    python -m bench.probe_newuser102 [--points 12] [--seed S]

One line a check (``ok`` / ``!!``), the disagreements at the end (exit 1 where any). About
3 s on the 2-core VM (2026-11-27: 12 points, 54 checks, 0 disagreements after the fixes of
commits 904a432 and 00e019e; 26 before them: the 24 Hz checks and the two degrees ones).
"""

from __future__ import annotations

import argparse
import contextlib
import io
import json
import math
import sys

import numpy as np

from cli.app import main

BAD: list[str] = []


def _check(ok: bool, what: str) -> None:
    print(("ok  " if ok else "!!  ") + what)
    if not ok:
        BAD.append(what)


def _run(argv) -> tuple[int, str, str]:
    out, err = io.StringIO(), io.StringIO()
    with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
        code = main(argv)
    return code, out.getvalue(), err.getvalue()


def _omega(alpha, K_s, K_theta, k):
    """The rotational branch of eq. `norm` linearised (kinetic theta_t^2 / 2 alpha^2)."""
    return alpha * math.sqrt(4 * K_s * math.sin(k / 2) ** 2
                             + 4 * K_theta * math.cos(k / 2) ** 2 + 2 * K_theta)


def probe_point(rng, i):
    alpha, K_s, K_theta = rng.uniform(1.5, 3.5), rng.uniform(0.005, 0.05), \
        rng.uniform(0.005, 0.05)
    k, gamma_s, T = rng.uniform(0.1, 3.0), 10 ** rng.uniform(-1.3, 0.7), \
        10 ** rng.uniform(-3.7, -2.3)
    gamma_theta = 2 * gamma_s * T / alpha**2  # docs/models.md's recipe
    argv = ["coefficients", "--model", "flexmm-lossy", "--param", f"alpha={alpha!r}",
            "--param", f"K_s={K_s!r}", "--param", f"K_theta={K_theta!r}", "--param",
            f"gamma_theta={gamma_theta!r}", "--param", "gamma_U=0", "--k", repr(k),
            "--amplitude", "0.02", "--time-unit", repr(T)]
    where = (f"point {i}: alpha {alpha:.3g}, K_s {K_s:.3g}, K_theta {K_theta:.3g}, k "
             f"{k:.3g}, Gamma {gamma_s:.3g} 1/s, T {T:.3g} s")
    code, out, err = _run(argv + ["--json"])
    if code != 0:
        _check(False, f"{where}: exit {code}: {err.strip()}")
        return
    co = json.loads(out)
    got = co["si"]["carrier_damping"]
    _check(abs(got / gamma_s - 1) < 1e-9, f"{where}: carrier damping {got:.6g} 1/s, "
           f"measured {gamma_s:.6g}")
    w = _omega(alpha, K_s, K_theta, k)
    _check(abs(co["si"]["omega"] / (w / T) - 1) < 1e-9,
           f"{where}: omega {co['si']['omega']:.6g} 1/s, closed form {w / T:.6g}")
    code, out, _ = _run(argv)
    line = next((ln for ln in out.splitlines() if ln.startswith("omega (1/time)")), "")
    hz = float(line.split("(f = ")[1].split(" Hz")[0]) if "Hz" in line else math.nan
    want = w / (2 * math.pi * T)
    _check(abs(hz / want - 1) < 6e-4, f"{where}: f {hz:.5g} Hz printed, closed form "
           f"{want:.5g} (4 digits)")
    # the same material in SI through the paper chain's --physical: m 1 g, a 10 mm
    m, a = 1e-3, 0.01
    k_l = m / T**2
    J = m * a * a / (4 * alpha**2)
    phys = f"{m!r},{J!r},{a!r},{k_l!r},{K_s * k_l!r},{K_theta * k_l * a * a / 4!r}"
    code, out, err = _run(["coefficients", "--physical", phys, "--k", repr(k)])
    row = next((ln for ln in out.splitlines() if ln.startswith("f = omega/2pi")), "")
    semi = float(row.split()[-1]) if row else math.nan
    _check(abs(semi / want - 1) < 1e-5, f"{where}: --physical f row {semi:.6g} Hz, closed "
           f"form {want:.6g} (6 digits)")


def probe_mistakes():
    lossy = ["--model", "flexmm-lossy", "--k", "0.81681"]

    def one_line_refusal(argv, must, what):
        code, _, err = _run(argv)
        lines = err.strip().splitlines()
        _check(code == 2 and len(lines) == 1 and all(m in err for m in must),
               f"{what}: exit {code}, {len(lines)} line(s): {err.strip()[:160]}")

    one_line_refusal(["coefficients", *lossy, "--param", "gamma_theta=-1e-4"],
                     ["gamma_theta", "semi-definite"], "a negative damping")
    one_line_refusal(["point", "--alpha", "2.5", "--K-s", "0.01851", "--K-theta", "0.01551",
                      "--k", "0.81681", "--case", "coupled", "--amplitude", "3"],
                     ["rad", f"--amplitude {math.radians(3):.4g}"],
                     "paper flags, amplitude 3 meant in degrees")
    one_line_refusal(["point", *lossy, "--physical", "1e-3,4e-9,0.01,1000,18.51,3.8775e-4"],
                     ["--time-unit", "--param"], "--physical with --model")
    one_line_refusal(["coefficients", *lossy[:2], "--k", "4"], ["--k", "3.14159"],
                     "k above pi (no wave: past the zone)")
    code, out, _ = _run(["coefficients", *lossy, "--amplitude", "3", "--json"])
    notes = json.loads(out)["warnings"] if code == 0 else []
    _check(any(f"--amplitude {math.radians(3):.4g}" in n for n in notes),
           "a model's angle of 3 rad (meant: degrees): the note gives 0.05236")
    # Gamma = 0.3125 1/s typed as gamma_theta (1 ms, alpha 2.5: 3125x too strong)
    code, out, _ = _run(["coefficients", *lossy, "--param", "gamma_theta=0.3125", "--param",
                         "gamma_U=0.3125", "--amplitude", "0.028", "--json"])
    notes = json.loads(out)["warnings"] if code == 0 else []
    _check(any("overdamped" in n for n in notes),
           "a damping typed in 1/s: the overdamped carrier is said")


def main_probe(argv=None) -> int:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--points", type=int, default=12)
    p.add_argument("--seed", type=int, default=102)
    args = p.parse_args(argv)
    rng = np.random.default_rng(args.seed)
    for i in range(args.points):
        probe_point(rng, i)
    probe_mistakes()
    print(f"\n{len(BAD)} disagreement(s)" + "".join(f"\n  {b}" for b in BAD))
    return 1 if BAD else 0


if __name__ == "__main__":
    sys.exit(main_probe())
