"""Probe 100 of the docs (``bench.probe_docs100``): what every part shares -- the pages, the
one-line claim and its count, the digits a page shows, a fresh interpreter."""

from __future__ import annotations

import os
import subprocess
import sys
import tempfile
from pathlib import Path

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
