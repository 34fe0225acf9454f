"""Sphinx configuration of the HTML documentation (`make docs`, into build/docs/).

Sphinx rather than MkDocs: the API reference comes from numpydoc docstrings (the project's
convention), which Sphinx's numpydoc extension reads as written; myst-nb reads the Markdown
pages and executes the tutorial notebook at build time, so its outputs and figures are in
the HTML. Built with -W: a warning fails the build.
"""

from __future__ import annotations

import re
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

project = "flexmm-mi"
author = "flexmm-mi authors"
copyright = "flexmm-mi authors, MIT licence"

extensions = ["myst_nb", "numpydoc", "sphinx.ext.autodoc", "sphinx.ext.mathjax"]
source_suffix = {".md": "myst-nb", ".ipynb": "myst-nb"}

root_doc = "index"

# the tutorial runs at every build (about a minute): a reader sees its outputs and figures
nb_execution_mode = "force"
nb_execution_timeout = 900
nb_execution_raise_on_error = True
nb_execution_allow_errors = False

myst_enable_extensions = ["dollarmath", "amsmath"]
myst_heading_anchors = 3

# numpydoc: the docstrings' sections as written, no autosummary tables of every member
numpydoc_show_class_members = False
numpydoc_class_members_toctree = False
numpydoc_xref_param_type = False
autodoc_typehints = "none"
autodoc_member_order = "bysource"

html_theme = "alabaster"
html_title = "flexmm-mi"
html_static_path = ["_static"]  # custom.css (alabaster links it): wide code blocks
html_theme_options = {"page_width": "1240px", "sidebar_width": "220px"}

exclude_patterns = ["_build", "**.ipynb_checkpoints"]

_OUTSIDE = re.compile(r"\[([^\]]+)\]\(((?:bench|tests|numerics|scenes|derivation|generated|"
                      r"common)/[^)\s]*|LICENSE|Makefile|pyproject\.toml)\)")


def _escape_bars(app, what, name, obj, options, lines):
    """Docstrings write |x| for an absolute value; reST would read a substitution."""
    for i, line in enumerate(lines):
        lines[i] = re.sub(r"(?<!\\)\|", r"\\|", line)


def _repository_files(app, relative_path, parent_docname, content):
    """README's links to repository files outside docs/ become file names (the site holds
    the documentation, not the source tree)."""
    content[0] = _OUTSIDE.sub(lambda m: f"`{m.group(2)}` (in the repository)"
                              if m.group(1) == m.group(2) else
                              f"{m.group(1)} (`{m.group(2)}` in the repository)", content[0])


def setup(app):
    app.connect("autodoc-process-docstring", _escape_bars)
    app.connect("include-read", _repository_files)
