"""SIGINT and SIGTERM, handled alike: both raise :class:`Interrupted` (a KeyboardInterrupt
that knows its signal), so every ``except KeyboardInterrupt`` (checkpoints, Dask clean-up,
the CLI's one-line message) serves ``kill PID`` as it serves Ctrl-C, and the exit code is
128 + the signal's number (130, 143)."""

from __future__ import annotations

import contextlib
import os
import signal
import threading

#: the signals handled alike
SIGNALS = (signal.SIGINT, signal.SIGTERM)


class Interrupted(KeyboardInterrupt):
    """SIGINT or SIGTERM arrived (``signum``)."""

    def __init__(self, signum: int = signal.SIGINT):
        super().__init__(signal.Signals(signum).name)
        self.signum = int(signum)


#: signals :func:`raise_interrupted` received inside :func:`interrupts`: an interrupt that a
#: library turned into another error on its way up (a pipe closed mid-read: EBADF) is still
#: reported as the interrupt
_received: list = []


def raise_interrupted(signum, frame):  # a signal handler
    _received.append(int(signum))
    raise Interrupted(signum)


def received() -> Interrupted | None:
    """The interrupt that arrived inside the current :func:`interrupts` block, if any."""
    return Interrupted(_received[-1]) if _received else None


def is_interrupt_handler(handler) -> bool:
    """Does ``handler`` turn its signal into a KeyboardInterrupt (Python's default SIGINT
    handler, or :func:`raise_interrupted`)? Code that defers interrupts replaces only these."""
    return handler is signal.default_int_handler or handler is raise_interrupted


def signal_number(exc: BaseException) -> int:
    """The signal behind a KeyboardInterrupt (SIGINT unless it says otherwise)."""
    return int(getattr(exc, "signum", signal.SIGINT))


def exit_code(exc: BaseException) -> int:
    """128 + the signal number: 130 for SIGINT, 143 for SIGTERM (the shell's convention)."""
    return 128 + signal_number(exc)


@contextlib.contextmanager
def interrupts():
    """SIGINT and SIGTERM raise :class:`Interrupted` meanwhile (main thread only)."""
    if threading.current_thread() is not threading.main_thread():
        yield
        return
    old = {s: signal.getsignal(s) for s in SIGNALS}
    _received.clear()
    for s in SIGNALS:
        signal.signal(s, raise_interrupted)
    try:
        yield
    finally:
        for s, h in old.items():
            signal.signal(s, h if h is not None else signal.SIG_DFL)


@contextlib.contextmanager
def held():
    """SIGINT and SIGTERM held back meanwhile (main thread; elsewhere nothing changes): one
    that comes is recorded and handled, by the handler in place before, on exit. For a few
    file writes that must land together (``common.files.write_results``). Python-level, as
    a signal mask is per thread: a process-directed signal blocked in this thread went to
    another (numba's, a BLAS pool's), and Python ran its handler here at once."""
    if threading.current_thread() is not threading.main_thread():
        yield
        return
    came: list = []
    old = {s: signal.getsignal(s) for s in SIGNALS}
    for s in SIGNALS:
        signal.signal(s, lambda signum, frame: came.append(signum))
    try:
        yield
    finally:
        for s, h in old.items():
            signal.signal(s, h if h is not None else signal.SIG_DFL)
        if came:
            handler = old[came[0]]
            if callable(handler):
                handler(came[0], None)
            elif handler == signal.SIG_DFL:
                os.kill(os.getpid(), came[0])
