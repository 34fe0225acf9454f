"""A line said when a command's step takes longer than a user waits in silence (a fresh
clone's first `flexmm point --model fput-lossy.toml ...` printed nothing for 93 s, under
load, while its theories' kernels compiled once; the paper chain's `point --simulate`
nothing for 94 s)."""

from __future__ import annotations

import contextlib
import sys
import threading

#: seconds of silence after which a step says what it is doing (as `map`'s estimate does)
SLOW_NOTE_S = 5.0


@contextlib.contextmanager
def said_if_slow(log, message: str, after: float | None = None):
    """Run the ``with`` body; where it is still running ``after`` seconds (default
    ``SLOW_NOTE_S``) on, ``log(message)`` once, from a timer thread. Nothing is said
    where the body ends first (or raises), or where the body cancels the timer it is
    given (``with said_if_slow(...) as timer``: a step that says more itself)."""
    timer = threading.Timer(SLOW_NOTE_S if after is None else after, lambda: log(message))
    timer.daemon = True
    timer.start()
    try:
        yield timer
    finally:
        timer.cancel()


def to_stderr(message: str) -> None:
    """A note that depends on the machine (how long a step took) goes to stderr: stdout's
    text, and JSON, stay the same on every machine."""
    print(message, file=sys.stderr, flush=True)


#: said where a point's theories take over ``SLOW_NOTE_S`` (the first point after an
#: install compiles their kernels: 93 s of silence under load for the README's lossy FPUT;
#: newuser99: a wave whose exact state needs many harmonics took minutes with the kernels
#: compiled, on the machine where the other points took seconds: a cross-coupled chain's
#: k 0.49, near 3 omega = w0, 65 s against 3.5 s at its other k; the paper chain at
#: A0 = 25, 3.5 min; and the note blamed the machine)
_WHY_SLOW = ("slow here: a busy machine, the kernels compiling once after an install (a "
             "minute or two), or an exact wave that needs many harmonics: a large amplitude "
             "or a harmonic near resonance with a branch (minutes)")
SLOW_MODEL_POINT = f"point: computing the theories ({_WHY_SLOW})"
SLOW_PAPER_POINT = f"point: computing the theories and each seed's predicted growth ({_WHY_SLOW})"
