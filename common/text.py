"""Wording shared by every layer's messages."""

from __future__ import annotations


def duration(seconds: float) -> str:
    """A run time as a person reads it: "42 s", "17 min", "2.5 h"."""
    if seconds < 90:
        return f"{seconds:.0f} s"
    if seconds < 5400:
        return f"{seconds / 60:.0f} min"
    return f"{seconds / 3600:.1f} h"


def plural(n: int, word: str, words: str | None = None) -> str:
    """``n`` and its noun, singular or plural: "1 cell", "4 cells", "0 cells" (``words``:
    the plural where it is not ``word`` + "s")."""
    return f"{n} {word if n == 1 else words or word + 's'}"
