"""Probe 100: every checkable claim of README.md and docs/*.md, one line a claim.

What it checks (each line names the page and line of the claim, ``ok`` or ``!!``):

- ``names``: every backticked path (``tests/...``, ``bench/...``, ``numerics/...``) exists,
  with the ``::name`` it names; every backticked dotted name (``numerics.models.four_wave``)
  and every ``autofunction``/``autoclass`` of docs/api.md imports and resolves;
- ``cli``: every ``--option`` of a ``flexmm SUB ...`` command a page shows (console blocks
  and inline code) is one of SUB's options (its ``--help``); every ``make TARGET`` is a
  target of the Makefile; every scene a page names is registered; the cheap examples of the
  subcommands' ``--help`` epilogs run (exit 0);
- ``physics``: the formulas and numbers the pages state, against computations written here
  from the equations (nothing of the code under test makes an expected value):
  FPUT's omega = 2 sin(k/2), v_g = cos(k/2), g1 = -sin(k/2)/2 and its g2 (the cubic term by
  Lindstedt, the second harmonic and the mean flow derived by hand below) against the pages'
  closed forms and printed numbers, and the code's at seeded random (alpha, beta, k);
  the quarter-wavelength four-wave closed forms and ratios; sine-Gordon's g2 = omega0^2 /
  (4 omega) and the Klein-Gordon Duffing shift; the paper chain's continuum dispersion
  omega^2 = alpha^2 (6 K_theta + delta k^2) against README's table (omega, v_g, g1), case I's
  g = -(delta k^2 + 6 K_theta) / (2 K_theta delta), K_c = 2 sqrt(g) A0, K_m = K_c / sqrt 2;
  the rotational branch's edges (erratum 4); the soliton widths 2 / (amplitude sqrt g);
- ``measured``: numbers the pages say were measured, against bench/results.json (the bench's
  own record) to the digits shown;
- ``remeasured``: a few cheap ones measured again here (the import time of the generated
  module);
- ``tested``: tolerances and numbers the pages tie to a test, measured again (the trig
  polynomial's ulp, the Hill truncation's 2 -> 4 harmonics, `--model flexmm`'s soliton against
  the paper flags', the scene count), and bench/stress.md's counts against the pages;
- ``keys``: the store variables, attributes and JSON keys the pages name, in the outputs of
  the README's theory-only map, a model map with its ring, ``point --json`` and
  ``coefficients --json``;
- ``runs``: the README's simulated point (exact to 0.1%, NLS 14% high, 1.5e3x measured against
  3.3e3x predicted) and docs/models.md's lossy FPUT amplifications, measured again;
- ``install``: README's Install and Layout claims against pyproject.toml, the Makefile, LICENSE;
- ``constants``: bounds and tolerances the pages state against the constants the code uses.

    python -m bench.probe_docs100 [--part names|cli|physics|measured|remeasured|tested|keys|runs|install|constants]

Exit 1 where any claim disagrees (``!!``); the list at the end. ~2-3 min on the 2-core VM.
"""

from __future__ import annotations

import argparse
import glob
import importlib
import json
import math
import os
import re
import subprocess
import sys
import tempfile
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
PAGES = [ROOT / "README.md"] + sorted((ROOT / "docs").glob("*.md"))
FAILS: list[str] = []
COUNT = [0]


def _rel(p: Path) -> str:
    return str(p.relative_to(ROOT))


def line_of(page: str, needle: str) -> int:
    """The line of ``page`` holding ``needle`` (0 where the claim's text is gone)."""
    for i, line in enumerate((ROOT / page).read_text().splitlines(), 1):
        if needle in line:
            return i
    return 0


def claim(page: str, needle: str, ok: bool, detail: str) -> None:
    """One line: page:line, ok or !!, what was compared."""
    COUNT[0] += 1
    n = line_of(page, needle)
    where = f"{page}:{n}" if n else f"{page}:? (text {needle!r} not found)"
    ok = bool(ok) and n > 0
    print(f"{'ok' if ok else '!!'}  {where}  {detail}", flush=True)
    if not ok:
        FAILS.append(f"{where}  {detail}")


def close(x: float, y: float, rel: float = 0.0, abs_: float = 0.0) -> bool:
    return abs(x - y) <= max(rel * abs(y), abs_)


def shown(x: float, text: str) -> bool:
    """x printed to the digits of ``text`` (half a unit of its last digit)."""
    t = text.strip()
    mant = t.lower().split("e")[0]
    decimals = len(mant.split(".")[1]) if "." in mant else 0
    exp = int(t.lower().split("e")[1]) if "e" in t.lower() else 0
    return abs(x - float(t)) <= 0.5 * 10.0 ** (exp - decimals) * (1 + 1e-9)


def py(args: list[str], timeout: int = 120) -> subprocess.CompletedProcess:
    env = dict(os.environ, PYTHONPATH=str(ROOT), PYTHONWARNINGS="ignore")
    return subprocess.run([sys.executable, *args], cwd=tempfile.gettempdir(), env=env,
                          capture_output=True, text=True, timeout=timeout)


# ---------------------------------------------------------------------------- names

def part_names() -> None:
    for page in PAGES:
        rel = _rel(page)
        for i, line in enumerate(page.read_text().splitlines(), 1):
            toks = re.findall(r"`([^`]+)`", line)
            toks += re.findall(r"(?:autofunction|autoclass)::\s*([\w.]+)", line)
            # paths in plain text too: "(tests/test_derivation.py::test_paper_test_points)"
            toks += [t for t in re.findall(r"(?<![\w/`])((?:tests|bench)/[\w./*-]+\.(?:py|json|md)"
                                           r"(?:::\w+)?)", line) if t not in toks]
            for t in dict.fromkeys(toks):
                t = t.strip()
                m = re.fullmatch(r"((?:tests|bench|numerics|derivation|generated|cli|common|"
                                 r"scenes|energy|docs)/[\w./*-]+)(::\w+)?", t)
                if m:
                    if "NAME" in m.group(1):
                        continue
                    hits = glob.glob(str(ROOT / m.group(1)))
                    ok = bool(hits) and (not m.group(2)
                                         or m.group(2)[2:] in Path(hits[0]).read_text())
                    _token(rel, i, ok, f"names: {t} exists")
                    continue
                m = re.fullmatch(r"((?:numerics|energy|generated|derivation|common|scenes|cli)"
                                 r"(?:\.\w+)+)(\(.*)?", t)
                if m:
                    _token(rel, i, _resolves(m.group(1)), f"names: {m.group(1)} resolves")


def _token(page: str, line: int, ok: bool, detail: str) -> None:
    COUNT[0] += 1
    print(f"{'ok' if ok else '!!'}  {page}:{line}  {detail}", flush=True)
    if not ok:
        FAILS.append(f"{page}:{line}  {detail}")


def _resolves(dotted: str) -> bool:
    parts = dotted.split(".")
    for j in range(len(parts), 0, -1):
        try:
            obj = importlib.import_module(".".join(parts[:j]))
        except ImportError:
            continue
        for a in parts[j:]:
            if not hasattr(obj, a):
                return False
            obj = getattr(obj, a)
        return True
    return False


# ---------------------------------------------------------------------------- cli

SUBCOMMANDS = ("coefficients", "table", "scenes", "scene", "run", "point", "map", "soliton",
               "models")


def _options() -> dict[str, set[str]]:
    out = {}
    for sub in SUBCOMMANDS:
        r = py(["-m", "cli", sub, "--help"])
        out[sub] = set(re.findall(r"(?<![\w-])(--[a-zA-Z][\w-]*)", r.stdout))
    return out


def part_cli() -> None:
    opts = _options()
    for page in PAGES:
        rel = _rel(page)
        for i, line in enumerate(page.read_text().splitlines(), 1):
            cmds = re.findall(r"^\$ (flexmm .*)$", line)
            cmds += [t for t in re.findall(r"`([^`]+)`", line) if t.startswith("flexmm ")]
            cmds += ["flexmm " + t for t in re.findall(r"`([^`]+)`", line)
                     if t.split(" ")[0] in ("point", "map", "soliton", "coefficients")
                     and "--" in t]
            for c in cmds:
                words = c.split()
                if len(words) < 2 or words[1] not in SUBCOMMANDS:
                    continue
                sub = words[1]
                used = {w.split("=")[0] for w in words[2:] if w.startswith("--")}
                unknown = sorted(used - opts[sub])
                _token(rel, i, not unknown,
                       f"cli: `{c[:60]}`: options of `flexmm {sub}`"
                       + (f" (unknown: {', '.join(unknown)})" if unknown else ""))
            for target in re.findall(r"`make ([\w-]+)", line):
                mk = (ROOT / "Makefile").read_text()
                _token(rel, i, re.search(rf"^{re.escape(target)}:", mk, re.M) is not None,
                       f"cli: make {target} is a Makefile target")
    scenes = py(["-m", "cli", "scenes"]).stdout.split()
    for page in PAGES:
        rel = _rel(page)
        for i, line in enumerate(page.read_text().splitlines(), 1):
            for t in re.findall(r"(?:scene |`)((?:fig\d|gain-|soliton-|four-wave-|harmonics)"
                                r"[\w-]*)`", line):
                if t.endswith("-"):
                    continue
                _token(rel, i, t in scenes, f"cli: scene {t} is registered")
    # docs/models.md's built-in table: the names, fields and defaults `flexmm models` lists
    listing = py(["-m", "cli", "models"]).stdout
    listed = {m.group(1): m.group(2).replace(" ", "").split(",")
              for m in re.finditer(r"^([\w-]+)\s+fields ([\w, ]+?)\s{2,}", listing, re.M)}
    table = {m.group(1): m.group(2).replace(" ", "").split(",")
             for m in re.finditer(r"^\| `([\w-]+)` \| ([\w, ]+) \|",
                                  (ROOT / "docs/models.md").read_text(), re.M)}
    claim("docs/models.md", "| name | fields | what |", table == listed,
          f"cli: the built-in table ({len(table)} models, their fields) = `flexmm models` "
          f"({len(listed)})")
    claim("docs/models.md", "(`gamma_theta`, `gamma_U`, 1e-3 each by default)",
          "gamma_theta=0.001, gamma_U=0.001" in listing, "cli: flexmm-lossy's damping defaults")
    # the cheap epilog examples run as written (the ones with --simulate or `run` are
    # tests/test_cli_help.py's; ~1 min here)
    with tempfile.TemporaryDirectory() as tmp:
        for sub in SUBCOMMANDS:
            r = py(["-m", "cli", sub, "--help"])
            for ex in re.findall(r"^\s+(flexmm .*)$", r.stdout, re.M):
                if "--simulate" in ex or ex.startswith("flexmm run") or ">" in ex:
                    continue
                env = dict(os.environ, PYTHONPATH=str(ROOT), PYTHONWARNINGS="ignore")
                p = subprocess.run([sys.executable, "-m", "cli", *ex.split()[1:]], cwd=tmp,
                                   env=env, capture_output=True, text=True, timeout=300)
                COUNT[0] += 1
                ok = p.returncode == 0 and "Traceback" not in p.stderr
                print(f"{'ok' if ok else '!!'}  flexmm {sub} --help  epilog `{ex}` "
                      f"exits {p.returncode}", flush=True)
                if not ok:
                    FAILS.append(f"flexmm {sub} --help: `{ex}` exits {p.returncode}: "
                                 f"{p.stderr.strip()[-200:]}")


# ---------------------------------------------------------------------------- physics

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


# ---------------------------------------------------------------------------- measured

def part_measured() -> None:
    d = json.loads((ROOT / "bench" / "results.json").read_text())
    sp, mp, sim = d["speed"], d["maps"], d["simulator"]
    sm = "docs/simulator.md"
    rows = [
        (sm, "= **1.52x** the stencil-only floor", sp["force"]["kernel_over_stencil"], "1.52"),
        (sm, "RK4 5.1 ns, srkn11b 4.1 ns", sp["force"]["ns_per_site_per_evaluation_in_loop"]["rk4"],
         "5.1"),
        (sm, "RK4 5.1 ns, srkn11b 4.1 ns",
         sp["force"]["ns_per_site_per_evaluation_in_loop"]["srkn11b"], "4.1"),
        (sm, "NumPy's sin+cos alone 16.6-18.5 ns", sim["sincos_ns_per_site_numpy"], "16.6"),
        (sm, "NumPy's sin+cos alone 16.6-18.5 ns", sp["force"]["ns_per_site"]["NumPy sin+cos"],
         "18.5"),
        (sm, "the plain NumPy force 154-214 ns", sp["force"]["ns_per_site"]["plain NumPy force"],
         "214"),
        (sm, "**3.5-4.2 ns** = **1.52x**", sim["force_ns_per_site_compiled"], "3.5"),
        (sm, "**3.5-4.2 ns** = **1.52x**", sp["force"]["ns_per_site"]["kernel"], "4.1"),
        (sm, "| compiled RK4 vs plain NumPy RK4", sim["rk4_speedup_vs_numpy"], "41.8"),
        (sm, "srkn11b 6.0 ms, DOP853 395 ms", sp["time_to_1e-6"]["runs"]["srkn11b"]["wall_s"] * 1e3,
         "6.0"),
        (sm, "srkn11b 6.0 ms, DOP853 395 ms",
         sp["time_to_1e-6"]["runs"]["dop853 (numpy force)"]["wall_s"] * 1e3, "395"),
        (sm, "srkn11b 6.0 ms, DOP853 395 ms / 49.4 ms",
         sp["time_to_1e-6"]["runs"]["dop853 (kernel force)"]["wall_s"] * 1e3, "49.4"),
        (sm, "**65x** and **8.2x**", sp["time_to_1e-6"]["speedup_vs_dop853_numpy"], "65"),
        (sm, "**65x** and **8.2x**", sp["time_to_1e-6"]["speedup_vs_dop853_kernel"], "8.2"),
        (sm, "blue II 7.1x, green I 8.1x", d["headline_time_to_1e-6"]["blue-II"]["speedup_at_1e-6"],
         "7.1"),
        (sm, "blue II 7.1x, green I 8.1x",
         d["headline_time_to_1e-6"]["green-I"]["speedup_at_1e-6"], "8.1"),
        (sm, "3.04 s with the old libm loops",
         sp["paper_run"]["wall_s"]["rk4 dt = 0.05, libm loops (before)"], "3.04"),
        (sm, "**0.78 s** fused", sp["paper_run"]["wall_s"]["rk4 dt = 0.05, fused loops"], "0.78"),
        (sm, "srkn11b at the paper's accuracy", sp["paper_run"]["wall_s"]["srkn11b, same accuracy"],
         "0.11"),
        (sm, "RK4's error over T = 200, 6.4e-6", sp["paper_run"]["rk4_error_over_T_acc"], "6.4e-6"),
        (sm, "slope -2.2e-9 per T", d["long_time"]["methods"]["rk4"]["drift_slope_per_T"],
         "-2.2e-9"),
        (sm, "verlet bounded at 4.7e-5", d["long_time"]["methods"]["verlet"]["max_abs_error"],
         "4.7e-5"),
        (sm, "srkn6b 5.4e-12", d["long_time"]["methods"]["srkn6b"]["max_abs_error"], "5.4e-12"),
        (sm, "| `make derive` / import of the generated modules",
         d["derivation"]["make_derive_s"], "18"),
        (sm, "| `make derive` / import of the generated modules",
         d["derivation"]["import_generated_s"] * 1e3, "3"),
        ("docs/theory.md", "`make derive` takes", d["derivation"]["make_derive_s"], "18"),
        ("docs/theory.md", "costs about 3 ms on top of", d["derivation"]["import_generated_s"] * 1e3,
         "3"),
        ("docs/maps.md", "| 0.100 s, **10.0 cells per second", mp["per_cell_serial_s"], "0.100"),
        ("docs/maps.md", "| 0.100 s, **10.0 cells per second", mp["cells_per_second_per_core"],
         "10.0"),
        ("docs/maps.md", "| 0.865 s (8.7x)", mp["per_cell_serial_rk4_s"], "0.865"),
        ("docs/maps.md", "| 0.865 s (8.7x)", mp["default_over_rk4"], "8.7"),
        ("docs/maps.md", "one core | 0.130 s", mp["prediction_per_cell_serial_s"], "0.130"),
        ("docs/maps.md", "17.8 s -> 10.0 s", mp["layout_map_wall_s"]["1 process"], "17.8"),
        ("docs/maps.md", "17.8 s -> 10.0 s", mp["layout_map_wall_s"]["2 processes"], "10.0"),
        ("docs/maps.md", "17.8 s -> 10.0 s", mp["speedup_2_workers"], "1.78"),
        ("docs/maps.md", "| 2.7 ms per task", mp["scheduling_overhead_per_task_s"] * 1e3, "2.7"),
        ("docs/maps.md", "| **4.1 min** (goal 5 min", mp["map_64x64"]["wall_s"] / 60, "4.1"),
        ("docs/maps.md", "predicted (cluster start-up included) | 13.2 min",
         mp["map_64x64_run_map"]["wall_s"] / 60, "13.2"),
        ("docs/maps.md", "srkn11b dt = 0.1 | 0 verdict changes; growth factors within 1.7e-4",
         mp["cell_accuracy"]["rotation"]["largest_growth_curve_error"], "1.7e-4"),
        ("docs/maps.md", "srkn11b dt = 0.1 | 0 verdict changes; growth factors within 1.7e-4",
         mp["cell_accuracy"]["coupled"]["largest_growth_curve_error"], "6.3e-3"),
        ("README.md", "the 64 x 64 map's 4 096 cells simulated on 2 workers: 4.1 min",
         mp["map_64x64"]["wall_s"] / 60, "4.1"),
        ("README.md", "the same map through `run_map`, every cell also predicted: 13.2 min",
         mp["map_64x64_run_map"]["wall_s"] / 60, "13.2"),
    ]
    for ns, n_ in zip([38, 21, 21, 19, 20, 19], d["scaling"]["per_N"], strict=True):
        rows.append((sm, "38, 21, 21, 19, 20, 19 ns", n_["ns_per_site_per_step"], str(ns)))
    for page, needle, val, txt in rows:
        claim(page, needle, shown(val, txt), f"measured: {txt} against bench/results.json "
              f"{val:.4g}")
    em = d["exact_maps"]["wall_s"]
    for key, txt in (("resonance_map_rotation_travelling_s", "1.5"),
                     ("stability_map_20_offsets_rotation_s", "4.1"),
                     ("resonance_map_coupled_travelling_s", "2.6"),
                     ("resonance_map_coupled_paper_s", "2.8"),
                     ("stability_map_20_offsets_coupled_s", "15.4")):
        claim("docs/theory.md", "case I 1.5 s (the 20-offset" if "rotation" in key
              else "II 2.6 s travelling and 2.8 s", shown(em[key], txt),
              f"measured: {key} {txt} s against bench/results.json {em[key]:.3f}")
    stress = (ROOT / "bench" / "stress.md").read_text()
    m = re.search(r"Fault catalogue.*?: (\d+) tried, (\d+) clear errors, (\d+) worked, (\d+) "
                  r"problems", stress)
    claim("docs/reliability.md", "bad inputs,", m is not None and
          f"**{m.group(1)} bad inputs, {m.group(2)} clear errors, {m.group(3)} that must work"
          in (ROOT / "docs/reliability.md").read_text() and m.group(4) == "0",
          "measured: the fault catalogue's counts against bench/stress.md "
          f"({m.group(1)} tried, {m.group(2)} clear, {m.group(3)} worked)" if m else "no counts")
    m = re.search(r"Stress tests \(full\): (\d+)/(\d+) pass", stress)
    claim("docs/simulator.md", "36/36 stability checks pass", m is not None
          and m.group(1) == m.group(2) == "36", "measured: bench/stress.md's pass count")
    errs = [float(x) for x in re.findall(r"amplitude theta_max = [\d.]+ rad.*?energy_error = "
                                         r"([\d.e+-]+)", stress)]
    claim("docs/simulator.md", "theta = 1 rad conserve energy to 1e-4 (at most 8.1e-5",
          len(errs) >= 10 and max(errs) < 1e-4 and shown(max(errs), "8.1e-5"),
          f"measured: largest amplitude-sweep energy error in bench/stress.md {max(errs):.3g}")
    gpu = json.loads((ROOT / "bench" / "results_gpu.json").read_text())
    gm = "docs/gpu.md"
    claim(gm, "the kernel 27.5 ps per site-evaluation", shown(gpu["ps_per_site_evaluation"], "27.5"),
          f"measured: GPU kernel {gpu['ps_per_site_evaluation']:.2f} ps (bench/results_gpu.json)")
    for name, txt in (("fput", "42"), ("klein-gordon", "36"), ("sine-gordon", "44"),
                      ("flexmm-stiff-hinge", "66"), ("diatomic-fput", "71"),
                      ("flexmm-rotation", "77"), ("flexmm", "79")):
        v = gpu["models"][name]["ps_per_site_evaluation"]
        claim(gm, "ps (fput 42, klein-gordon 36", shown(v, txt),
              f"measured: GPU {name} {txt} ps against bench/results_gpu.json {v:.2f}")
    claim(gm, "**81.7 s on the GPU (84.2 s again),", shown(gpu["map_32x32_wall_s"], "81.7")
          and shown(gpu["map_32x32_cpu_wall_s"], "88.2") and shown(gpu["gpu_speedup"], "1.08"),
          "measured: the 32 x 32 map GPU / CPU walls and 1.08x against bench/results_gpu.json")
    claim(gm, "269 s wall, 179 s in the", shown(gpu["map_64x64_wall_s"], "269"),
          f"measured: the 64 x 64 GPU map {gpu['map_64x64_wall_s']:.1f} s")
    wp = d["work_precision"]
    claim("bench/README.md", "(fit of log distance, T = 100 .. 1000): 1.05e-3",
          shown(wp["blue-II"]["separation_rate"], "1.05e-3")
          and shown(wp["green-I"]["separation_rate"], "7.3e-4"),
          "measured: separation rates against bench/results.json")


# ---------------------------------------------------------------------------- remeasured

def part_remeasured() -> None:
    code = ("import time, numpy; t = time.perf_counter(); import generated.coefficients, "
            "generated.lattice_coefficients, generated.lattice_model; "
            "print(time.perf_counter() - t); import sys; print('sympy' in sys.modules)")
    best, sympy_in = 1e9, True
    for _ in range(5):
        r = py(["-c", code])
        t, s = r.stdout.split()
        best, sympy_in = min(best, float(t)), s == "True"
    claim("docs/theory.md", "costs about 3 ms on top of", not sympy_in and best < 0.01,
          f"remeasured: importing the generated modules after numpy: best of 5 "
          f"{best * 1e3:.1f} ms, sympy imported: {sympy_in} (page: about 3 ms; bar 10 ms: a shared VM)")


def part_tested() -> None:
    """Tolerances and measured numbers the pages tie to a test, measured again here."""
    import numpy as np

    from numerics import Material, mi_gain
    from numerics.lattice import _kernels as kernels
    # simulator.md: sin and cos within 2 ulp of libm for |theta| <= 1e4 (polynomial path)
    x = np.concatenate([np.linspace(-100, 100, 200_001),
                        np.random.default_rng(1).uniform(-kernels.TRIG_LIMIT, kernels.TRIG_LIMIT,
                                                         100_000)])
    sys.path.insert(0, str(ROOT / "tests"))
    import test_kernels as tk
    s_, c_, _ = tk._poly(x)
    ulp = max(np.max(np.abs(s_ - np.sin(x)) / tk.ULP(np.abs(np.sin(x)))),
              np.max(np.abs(c_ - np.cos(x)) / tk.ULP(np.abs(np.cos(x)))))
    claim("docs/simulator.md", "sin and cos within 2 ulp of libm", ulp <= 2
          and kernels.TRIG_LIMIT == 1e4, f"tested: polynomial sin/cos {ulp:.2f} ulp of libm over "
          f"|theta| <= {kernels.TRIG_LIMIT:g}")
    # theory.md: the peak gain from 2 to 4 harmonics
    blue = Material(alpha=2.5, K_s=0.01851, K_theta=0.01551)
    q = np.linspace(0.05, 1.0, 400)
    p2, p4 = (mi_gain(blue, "coupled", 0.81681, 0.02, q, harmonics=h).max() for h in (2, 4))
    claim("docs/theory.md", "from 2 to 4 harmonics (measured 6.6e-7",
          abs(p2 - p4) / p4 < 1e-6 and shown(abs(p2 - p4) / p4, "6.6e-7"),
          f"measured: blue II peak gain, 2 vs 4 harmonics: {abs(p2 - p4) / p4:.2e}")
    # models.md: --model flexmm launches the paper flags' soliton (~20 s)
    from energy import load_model
    from numerics.models import simulate_soliton
    from numerics.theory import simulate_soliton as paper_soliton
    mat = Material(alpha=2.0, K_s=0.03, K_theta=0.02)
    paper = paper_soliton(mat, "coupled", 1.0, 0.005, travel=2)
    model = simulate_soliton(load_model("flexmm", alpha=2.0, K_s=0.03, K_theta=0.02), 1.0,
                             0.005, N=paper.N, travel=2)
    pm, mm = paper.measured(), model.measured()
    dv = abs(mm["velocity"] / pm["velocity"] - 1)
    dw = abs(mm["width"] / pm["width"] - 1)
    dk = abs(mm["kink_U"] / pm["kink_height"] - 1)
    claim("docs/models.md", "velocity equal to 1e-8", dv <= 1e-8
          and dw <= 3e-5 and dk <= 3e-5, f"measured: --model flexmm vs the flags' soliton "
          f"(alpha 2, k 1, a 0.005, 2 widths): velocity {dv:.1e}, width {dw:.1e}, kink {dk:.1e}")
    # README: make run's 17 scenes
    n = len(py(["-m", "cli", "scenes"]).stdout.strip().splitlines())
    claim("README.md", "(17 scenes in 119 s", n == 17, f"flexmm scenes lists {n} scenes")


def _run_cli(args: list[str], cwd: str) -> subprocess.CompletedProcess:
    env = dict(os.environ, PYTHONPATH=str(ROOT), PYTHONWARNINGS="ignore")
    return subprocess.run([sys.executable, "-m", "cli", *args], cwd=cwd, env=env,
                          capture_output=True, text=True, timeout=300)


def part_keys() -> None:
    """The store variables, attributes and JSON keys the pages name, in real outputs."""
    import xarray as xr
    with tempfile.TemporaryDirectory() as tmp:
        # the README's theory-only paper map (~15 s)
        r = _run_cli(["map", "--alpha", "2.5", "--K-s", "0.01851", "--delta=-0.012:0.012:3",
                      "--k", "0.25:2.9:6", "--case", "rotation", "--theory-only", "--out",
                      "out/m"], tmp)
        ds = xr.open_zarr(f"{tmp}/out/m/map.zarr", chunks=None)
        names = set(ds.data_vars) | set(ds.coords)
        want = ["verdict_simulated", "verdict_paper", "verdict_semidiscrete", "verdict_exact",
                "verdict_exact_all", "checksum", "growth", "growth_exponential",
                "growth_field", "growth_q", "peak_gain", "peak_gain_paper", "k_simulated",
                "K_theta", "t_simulated", "done", "growth_predicted", "verdict_predicted",
                "rate_predicted", "predicted_status", "growth_log_ratio", "done_predicted"]
        missing = [w for w in want if w not in names]
        claim("docs/maps.md", "writes `OUT/map.zarr` (open with", r.returncode == 0 and not missing
              and set(ds.dims) == {"delta", "k"} and "criterion" in ds.attrs,
              f"keys: the paper map's store holds dims delta, k, the criterion and {len(want)} "
              f"variables named" + (f" (missing {missing})" if missing else ""))
        summ = json.loads(Path(f"{tmp}/out/m/summary.json").read_text())
        want = ["alpha", "K_s", "case", "axes", "amplitude", "N", "t_end", "seeds", "start",
                "device", "theory_only"]
        missing = [w for w in want if w not in summ["inputs"]]
        claim("docs/maps.md", "over it) and `summary.json` (`inputs`", not missing,
              "keys: summary.json inputs" + (f" (missing {missing})" if missing else ""))
        ds.close()
        # a model map with the ring (--exact), its store and --json
        r = _run_cli(["map", "--model", "fput", "--param", "alpha=1", "--param",
                      "beta=0.8,1.6", "--k", "2.6,2.8", "--amplitude", "0.1", "--theory-only",
                      "--exact", "--N", "64", "--workers", "1", "--out", "out/f", "--json"], tmp)
        ds = xr.open_zarr(f"{tmp}/out/f/map.zarr", chunks=None)
        want = ["verdict_semidiscrete", "verdict_exact", "verdict_fourwave",
                "peak_gain_semidiscrete", "peak_gain_exact", "peak_gain_fourwave",
                "mode_kind_fourwave", "g1", "g2", "growth", "growth_q", "t_simulated",
                "k_simulated", "done", "nls_band_unsampled", "no_wave"]
        missing = [w for w in want if w not in ds.data_vars]
        kinds = ds["mode_kind_fourwave"].attrs.get("flag_meanings", "")
        claim("docs/models.md", "`mode_kind_fourwave` (the fastest four-wave pair, int8",
              not missing and kinds == "undefined none sidebands backward parametric"
              and ds["mode_kind_fourwave"].dtype == np.int8,
              "keys: model store variables and mode_kind_fourwave's int8 -1..3 meanings"
              + (f" (missing {missing})" if missing else ""))
        want = ["theories", "time_unit_s", "length_unit_m", "nls_band_unsampled_cells",
                "amplitude", "model_hash"]
        missing = [w for w in want if w not in ds.attrs]
        claim("docs/models.md", "the attribute `nls_band_unsampled_cells`", not missing,
              "keys: model store attributes" + (f" (missing {missing})" if missing else ""))
        out = json.loads(r.stdout)
        summ = json.loads(Path(f"{tmp}/out/f/summary.json").read_text())
        missing = [w for w in ("inputs", "cells", "simulated", "mi_fraction",
                               "undetermined_cells") if w not in summ]
        missing += [w for w in ("mi_share", "nls_band_unsampled", "axes") if w not in out]
        claim("docs/models.md", "`summary.json` has the paper map's keys", not missing,
              "keys: model map summary.json and --json" + (f" (missing {missing})"
                                                          if missing else ""))
        ds.close()
        # point --model --json: one object per theory with verdict and peak_gain
        r = _run_cli(["point", "--model", "fput", "--param", "alpha=0.8", "--param", "beta=1",
                      "--k", "1.5708", "--amplitude", "0.1", "--N", "256", "--json"], tmp)
        pt = json.loads(r.stdout)
        rows = [pt.get(t, {}) for t in ("semi-discrete NLS", "four-wave", "exact lattice")]
        claim("README.md", "`--json` prints one object (for `point`, one per",
              all("verdict" in x and "peak_gain" in x for x in rows),
              "keys: point --json has verdict and peak_gain per theory")
        ex = pt.get("exact lattice", {})
        missing = [w for w in ("mode_kind", "mode_waves", "fastest_offset", "modulational_gain")
                   if w not in ex] + [w for w in ("notes", "ring_misses", "curves", "field")
                                      if w not in pt]
        claim("docs/models.md", "(`fastest_offset`; the Hill offset of a copy", not missing,
              "keys: point --json exact row and notes/ring_misses/curves"
              + (f" (missing {missing})" if missing else ""))
        claim("README.md", "four-wave                             MI            0.005307          0",
              shown(pt["four-wave"]["peak_gain"], "0.005307")
              and ex.get("mode_kind") == "backward",
              f"point --json: four-wave {pt['four-wave']['peak_gain']:.6f}, exact kind "
              f"{ex.get('mode_kind')!r}")
        r = _run_cli(["coefficients", "--model", "fput", "--param", "alpha=1", "--param",
                      "beta=1", "--k", "1.5708", "--amplitude", "0.1", "--json"], tmp)
        co = json.loads(r.stdout)
        missing = [w for w in ("field", "field_rule", "four_wave") if w not in co]
        claim("docs/models.md", "(`field`, and `field_rule` in the JSON of `coefficients`)",
              not missing, "keys: coefficients --model --json"
              + (f" (missing {missing})" if missing else ""))


def part_runs() -> None:
    """Numbers the pages give from runs and damped theories, measured again (~25 s)."""
    from energy import load_model, parse_model
    from numerics.models import exact_amplification, nls_amplification
    lossy = ("name = \"fput-lossy\"\nfields = [\"u\"]\n[parameters]\nbeta = 1.0\n"
             "gamma = 0.03\n[energy]\nkinetic = \"u_t**2/2\"\n"
             "bond = \"(u_next - u)**2/2 + beta*(u_next - u)**4/4\"\n[dissipation]\n"
             "site = \"gamma*u_t**2/2\"\n")
    for g, nls_txt, ex_txt, ring_txt in ((0.012, "252", "146", "217"), (0.03, "5.8", "4.6", "5.5")):
        m = load_model(parse_model(lossy, "fput-lossy.toml"), gamma=g)
        a_chain = nls_amplification(m, 2.5, 0.2).amplification
        a_ring = nls_amplification(m, 2 * math.pi * 25 / 64, 0.2).amplification
        a_ex = exact_amplification(m, 2.5, 0.2, N=64).amplification
        claim("docs/models.md", f"| FPUT, {g} | {nls_txt} |", shown(a_chain, nls_txt)
              and shown(a_ex, ex_txt), f"measured: lossy FPUT gamma {g}: NLS at k 2.5 "
              f"{a_chain:.4g}, exact (N 64) {a_ex:.4g}")
        claim("docs/models.md", "where the NLS reads 217 and 5.5", shown(a_ring, ring_txt),
              f"measured: lossy FPUT gamma {g}: NLS at 2 pi 25/64 {a_ring:.4g} (page {ring_txt})")
    # docs/theory.md's four-wave table: two rows measured again (~9 s)
    with tempfile.TemporaryDirectory() as tmp:
        for args, row, fw_txt, ex_txt, nls_txt in (
                (["fput", "--param", "alpha=0.5", "--param", "beta=1"],
                 "| FPUT α 0.5, β 1, N 256, k = 2π 64/256 |", "8.760e-3", "8.666e-3", "5.30e-3"),
                (["klein-gordon", "--param", "C=1", "--param", "omega0=1", "--param",
                  "alpha=0.5", "--param", "beta=1"], "| Klein-Gordon C 1, ω0 1, α 0.5, β 1, k = π/2",
                 "2.076e-3", "2.075e-3", "1.49e-3")):
            r = _run_cli(["point", "--model", *args, "--k", "1.5708", "--amplitude", "0.1",
                          "--N", "256", "--json"], tmp)
            pt = json.loads(r.stdout)
            fw, ex = pt["four-wave"]["peak_gain"], pt["exact lattice"]["peak_gain"]
            nl = pt["semi-discrete NLS"]["peak_gain"]
            claim("docs/theory.md", row, shown(fw, fw_txt) and shown(ex, ex_txt)
                  and shown(nl, nls_txt) and pt["exact lattice"]["mode_kind"] == "backward",
                  f"measured: four-wave {fw:.4g}, exact {ex:.4g}, NLS {nl:.3g}, kind "
                  f"{pt['exact lattice']['mode_kind']}")
    # README's --simulate point (~16 s): exact to 0.1%, NLS 14% high, 1.5e3x / 3.3e3x
    with tempfile.TemporaryDirectory() as tmp:
        r = _run_cli(["point", "--alpha", "2.0", "--K-s", "0.03", "--K-theta", "0.02", "--k",
                      "1.2", "--amplitude", "0.04", "--case", "coupled", "--simulate",
                      "--seeds", "2", "--out", "out/point"], tmp)
        rate = {}
        for line in r.stdout.splitlines():
            m = re.match(r"(semi-discrete NLS|exact lattice, paper start|simulated \(.*?\))\s+MI"
                         r"\s+(\S+)", line)
            if m:
                rate[m.group(1).split(" (")[0].split(",")[0]] = float(m.group(2))
        gm = re.search(r"predicted ([\d.e+]+)x, ([\d.e+]+)x; measured ([\d.e+]+)x, ([\d.e+]+)x",
                       r.stdout)
        ok = len(rate) == 3 and gm is not None
        ex = abs(rate["exact lattice"] / rate["simulated"] - 1) if ok else float("nan")
        nl = rate["semi-discrete NLS"] / rate["simulated"] - 1 if ok else float("nan")
        claim("README.md", "The exact theory (at the ring's fastest pair) predicts the measured",
              ok and ex <= 0.0015 and shown(nl * 100, "14"),
              f"measured: README's point: exact / run - 1 = {ex:.1e}, NLS / run - 1 = {nl:.3f}")
        claim("README.md", "(1.5e3x measured, 3.3e3x", ok and shown(float(gm.group(3)), "1.5e3")
              and shown(float(gm.group(1)), "3.3e3"),
              f"measured: README's point: predicted {gm.group(1) if gm else '?'}x, measured "
              f"{gm.group(3) if gm else '?'}x (seed 0)")


def part_install() -> None:
    """README's Install and Layout claims against pyproject.toml, the Makefile and LICENSE."""
    import tomllib
    pp = tomllib.loads((ROOT / "pyproject.toml").read_text())["project"]
    mk = (ROOT / "Makefile").read_text()
    claim("README.md", "Python ≥ 3.11 and `make`", pp["requires-python"] == ">=3.11",
          f"install: requires-python {pp['requires-python']}")
    claim("README.md", "adds dask-jobqueue for HPC clusters",
          any("dask-jobqueue" in x for x in pp["optional-dependencies"].get("jobqueue", [])),
          "install: the jobqueue extra holds dask-jobqueue")
    claim("README.md", "Then put `flexmm` on your PATH", pp["scripts"].get("flexmm") == "cli:main",
          f"install: the flexmm entry point is {pp['scripts'].get('flexmm')!r} "
          "(docs/architecture.md: cli:main)")
    claim("README.md", "all of it as an HTML site in `build/docs/index.html`",
          re.search(r"sphinx .*-b html docs build/docs", mk) is not None,
          "install: make docs builds docs/ into build/docs")
    claim("docs/gpu.md", "The GPU path needs the `gpu` extra",
          any(x.startswith("numba-cuda") for x in pp["optional-dependencies"].get("gpu", [])),
          "install: the gpu extra holds numba-cuda")
    claim("README.md", "License: MIT", (ROOT / "LICENSE").read_text().startswith("MIT License"),
          "install: LICENSE is MIT")


def _const(path: str, name: str) -> float:
    """A module-level constant read from the source (the bench reaches no private module)."""
    m = re.search(rf"^{name} = ([^#\n]+)", (ROOT / path).read_text(), re.M)
    if m is None:
        return float("nan")
    expr = m.group(1).strip()
    if not re.fullmatch(r"[\d_.e+\-* ()]+", expr):
        return float("nan")
    return float(eval(expr, {"__builtins__": {}}))  # digits and * only, checked above


def part_constants() -> None:
    """Bounds and tolerances the pages state, against the constants the code uses."""
    import inspect

    from numerics.lattice import simulate
    E, S = "energy/_expressions.py", "energy/_spec.py"
    mm = "docs/models.md"
    claim(mm, "a file of at most 256 KiB, 8 fields, 64", _const(S, "MAX_FILE_BYTES") == 256 * 1024
          and _const(S, "MAX_FIELDS") == 8 and _const(S, "MAX_PARAMETERS") == 64,
          "constants: 256 KiB, 8 fields, 64 parameters (energy/_spec.py)")
    claim(mm, "parameters; an energy of at most 20 000 characters and 10 000 terms and symbols,",
          _const(E, "MAX_EXPRESSION") == 20_000 and _const(E, "MAX_NODES") == 10_000,
          "constants: 20 000 characters, 10 000 nodes (energy/_expressions.py)")
    claim(mm, "functions nested at most 4 deep, numbers up to 1e15, constant exponents up to 64",
          _const(E, "MAX_CALL_DEPTH") == 4 and _const(E, "MAX_CONSTANT") == 1e15
          and _const(E, "MAX_EXPONENT") == 64, "constants: call depth 4, 1e15, exponent 64")
    claim("docs/reliability.md", "nesting <= 60 levels", _const(E, "MAX_DEPTH") == 60,
          "constants: nesting 60")
    claim(mm, "ASCII letters and digits with single `_` between them, at most 64",
          _const(S, "MAX_NAME") == 64, "constants: names up to 64 characters")
    claim(mm, "Rates below 3e-7 ω are eigen-solver round-off",
          _const("numerics/models/_exact.py", "GAIN_FLOOR") == 3e-7,
          "constants: exact_gain's floor 3e-7 omega (numerics/models/_exact.py)")
    claim("docs/solitons.md", "`MIN_WIDTH` = 8 sites",
          _const("numerics/theory/_soliton.py", "MIN_WIDTH") == 8
          and _const("numerics/models/_soliton_ring.py", "MIN_WIDTH") == 8,
          "constants: MIN_WIDTH 8 (paper chain and models)")
    claim("docs/simulator.md", "`energy_tolerance` (default 1e-3)",
          inspect.signature(simulate).parameters["energy_tolerance"].default == 1e-3,
          "constants: simulate's energy_tolerance default 1e-3")
    lim = _const("numerics/lattice/_kernels.py", "TRIG_LIMIT")
    claim("docs/simulator.md", "beyond |theta| = 1e4 the libm loops take over", lim == 1e4,
          f"constants: TRIG_LIMIT {lim:g}")


PARTS = {"names": part_names, "cli": part_cli, "physics": part_physics,
         "measured": part_measured, "remeasured": part_remeasured, "tested": part_tested, "keys": part_keys,
         "runs": part_runs, "install": part_install,
         "constants": part_constants}


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--part", choices=sorted(PARTS), action="append")
    args = ap.parse_args(argv)
    sys.path.insert(0, str(ROOT))
    for name in args.part or PARTS:
        print(f"# {name}", flush=True)
        PARTS[name]()
    print(f"\n{COUNT[0]} claims checked, {len(FAILS)} disagree")
    for f in FAILS:
        print(f"!! {f}")
    return 1 if FAILS else 0


if __name__ == "__main__":
    sys.exit(main())
