"""Every command and code block of README.md and docs/*.md runs as written, and prints what
the page shows (Sybil parses the pages; shell sessions are checked by the evaluator below).

- ```console blocks: each ``$ command`` runs in bash, with ``.venv/bin`` first on PATH (as
  after ``source .venv/bin/activate``); the lines after it are its expected output, to the
  shown digits (blank lines ignored). ``...`` on a line of its own skips any number of lines; inside a line it
  matches anything. A command must exit 0.
- ```python blocks: run (doctest style where they show ``>>>`` and output).
- ``<!-- skip: next -->`` before a block: not run here (the slow ones: ``make setup``,
  ``make run``, ``make test``, which CI runs anyway); at most 4 across the pages.

Blocks of one page run in order in one temporary folder (``out/`` goes there), sharing one
namespace, so a page reads top to bottom as a user would run it.
"""

from __future__ import annotations

import os
import re
import subprocess
import sys
from pathlib import Path

import pytest
from sybil import Sybil
from sybil.parsers.markdown import CodeBlockParser, PythonCodeBlockParser, SkipParser

ROOT = Path(__file__).resolve().parents[1]
PAGES = [ROOT / "README.md"] + sorted((ROOT / "docs").glob("*.md"))
MAX_SKIPPED = 4


def _expected_regex(lines: list[str]) -> re.Pattern:
    parts = []
    for line in lines:
        if line.strip() == "...":
            parts.append(r"(?:[^\n]*\n)*?")
        else:
            parts.append(re.escape(line.rstrip()).replace(re.escape("..."), r"[^\n]*") + r"\n")
    return re.compile("".join(parts))


def run_console(example):
    """Run each ``$ cmd`` of a console block; check its output against the shown lines."""
    env = dict(os.environ, PATH=f"{Path(sys.executable).parent}{os.pathsep}"
               f"{os.environ.get('PATH', '')}", PYTHONWARNINGS="ignore")
    sessions, cur = [], None
    for line in example.parsed.splitlines():
        if line.startswith("$ "):
            cur = [line[2:], []]
            sessions.append(cur)
        elif cur is not None and line.strip():
            cur[1].append(line)
    for cmd, expected in sessions:
        proc = subprocess.run(["bash", "-c", cmd], cwd=os.getcwd(), env=env,
                              capture_output=True, text=True, timeout=600)
        assert proc.returncode == 0, (f"`{cmd}` exited {proc.returncode}:\n"
                                      f"{proc.stdout[-2000:]}\n{proc.stderr[-2000:]}")
        out = "".join(ln.rstrip() + "\n" for ln in proc.stdout.splitlines() if ln.strip())
        if expected:
            pat = _expected_regex(expected)
            assert pat.match(out), (f"`{cmd}` printed\n{out[:4000]}\nwhich does not match "
                                    "the page's\n" + "\n".join(expected))


SYBIL = Sybil(parsers=[CodeBlockParser("console", run_console), PythonCodeBlockParser(),
                       SkipParser()])


def _examples(page: Path):
    return list(SYBIL.parse(page))


@pytest.mark.parametrize("page", PAGES, ids=[p.name for p in PAGES])
def test_page_runs_as_written(page, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    doc = SYBIL.parse(page)
    examples = list(doc)
    for example in examples:
        example.evaluate()


def test_few_blocks_are_skipped():
    text = "".join(p.read_text() for p in PAGES)
    skipped = text.count("<!-- skip: next -->")
    assert skipped <= MAX_SKIPPED, f"{skipped} blocks are not run in CI (at most {MAX_SKIPPED})"


#: the HTML site's MyST directives (docs/index.md, api.md, readme.md): Sphinx runs them
#: in `make docs` (with -W), no reader copies them
SITE_DIRECTIVES = ("{toctree}", "{eval-rst}", "{include}")


def test_every_fenced_block_is_checked():
    """A fence this test does not run (```bash, ```sh, a bare ```) would go untested."""
    for page in PAGES:
        for lang in re.findall(r"^```(\{[\w-]+\}|\w*)(?:[ \t]+\S.*)?[ \t]*$",
                               page.read_text(), flags=re.M)[::2]:
            assert lang in ("console", "python", "text") + SITE_DIRECTIVES, (
                f"{page.name}: a ```{lang or '(bare)'} block; use console, python or text")


def test_the_output_matcher_can_fail():
    pat = _expected_regex(["a 1.23", "...", "end ..."])
    assert pat.match("a 1.23\nx\ny\nend 42 s\n")
    assert not pat.match("a 1.24\nend 1\n")
    assert not pat.match("a 1.23\n")


def test_the_readme_is_a_front_door():
    """CONVENTIONS (User documentation): a few hundred lines at most, deep dives in docs/
    (issue 44 item 10: 300)."""
    lines = (ROOT / "README.md").read_text().count("\n")
    assert lines <= 300, f"README.md has {lines} lines; move a deep dive to docs/"
