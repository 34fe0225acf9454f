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
import os
import re
import subprocess
import sys
import tempfile
from pathlib import Path

from bench._docs100_claims import COUNT, FAILS, PAGES, ROOT, claim, py
from bench._docs100_outputs import (
    part_constants,
    part_install,
    part_keys,
    part_measured,
    part_remeasured,
    part_runs,
    part_tested,
)
from bench._docs100_physics import part_physics


def _rel(p: Path) -> str:
    return str(p.relative_to(ROOT))


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
