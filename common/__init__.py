"""What every layer may import: the paper's numbers and atomic file writing.

A leaf: it imports nothing from the project, so derivation, numerics, scenes, tests and
bench all read the paper's numbers from one place (:mod:`common.paper`) and write files
one way (:mod:`common.files`).
"""

from . import files, paper
from .files import atomic_write, write_text

__all__ = ["paper", "files", "atomic_write", "write_text"]
