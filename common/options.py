"""Options that act only together with another: an option whose help opens with
``with --FLAG:`` does nothing unless FLAG is given too, so giving it alone is refused (one
line naming both) rather than silently ignored. The rule reads the parser, so an option
added later with such a help is covered without a change here."""

from __future__ import annotations

import argparse
import re

_WITH = re.compile(r"with (--[A-Za-z][\w-]*):")


def _given(action: argparse.Action, tokens: list, value) -> bool:
    """Was ``action`` on the command line: one of its option strings (or a prefix argparse
    would expand to it, ``--trav``) among ``tokens``, or its value not its default."""
    for t in tokens:
        if not t.startswith("--") or len(t) < 3:
            continue
        head = t.split("=", 1)[0]
        if any(o == head or (len(head) > 3 and o.startswith(head))
               for o in action.option_strings):
            return True
    return value != action.default


def unused_without(parser: argparse.ArgumentParser, args, tokens: list) -> None:
    """ValueError for the first option of ``parser`` given in ``tokens`` whose help says it
    acts ``with --FLAG:`` while FLAG is not set in ``args``."""
    flags = {o: a.dest for a in parser._actions for o in a.option_strings}
    for action in parser._actions:
        m = _WITH.match(action.help or "")
        if not m or m.group(1) not in flags:
            continue
        if getattr(args, flags[m.group(1)], None):
            continue
        if _given(action, tokens, getattr(args, action.dest, action.default)):
            opt = action.option_strings[-1]
            raise ValueError(f"{opt} does nothing without {m.group(1)}; add {m.group(1)}, "
                             f"or leave {opt} out")
