"""A line said when a command's step takes longer than a user waits in silence (a fresh
clone's first `flexmm point --model fput-lossy.toml ...` printed nothing for 93 s, under
load, while its theories' kernels compiled once; the paper chain's `point --simulate`
nothing for 94 s)."""

from __future__ import annotations

import contextlib
import threading

#: seconds of silence after which a step says what it is doing (as `map`'s estimate does)
SLOW_NOTE_S = 5.0


@contextlib.contextmanager
def said_if_slow(log, message: str, after: float | None = None):
    """Run the ``with`` body; where it is still running ``after`` seconds (default
    ``SLOW_NOTE_S``) on, ``log(message)`` once, from a timer thread. Nothing is said
    where the body ends first (or raises)."""
    timer = threading.Timer(SLOW_NOTE_S if after is None else after, lambda: log(message))
    timer.daemon = True
    timer.start()
    try:
        yield
    finally:
        timer.cancel()
