"""Run control of ``simulate``: Ctrl-C deferred to a consistent state, bounded calls into
compiled code, the progress bar."""

from __future__ import annotations

import contextlib
import signal
import threading


class _Interrupt(Exception):
    """Ctrl-C noticed between two calls into compiled code (state and time consistent)."""


@contextlib.contextmanager
def _deferred_interrupt():
    """Turn SIGINT into a flag checked between calls into compiled code, so an interrupted
    run stops on a state whose time is known exactly. Only in the main thread and when
    Python's default handler is installed (else nothing changes); a second Ctrl-C raises
    at once. Yields a function returning whether Ctrl-C was pressed."""
    flag = []
    if (threading.current_thread() is not threading.main_thread()
            or signal.getsignal(signal.SIGINT) is not signal.default_int_handler):
        yield lambda: False
        return

    def handler(signum, frame):
        if flag:
            raise KeyboardInterrupt
        flag.append(signum)

    signal.signal(signal.SIGINT, handler)
    try:
        yield lambda: bool(flag)
    finally:
        signal.signal(signal.SIGINT, signal.default_int_handler)


#: site-evaluations per call into compiled code: ~0.1 s, so Ctrl-C answers promptly
_WORK_PER_CALL = 3e7


def _steps_per_call(N, method, per_save):
    if not method.fixed_step:  # scipy: one solve_ivp per record, as before
        return per_save
    return max(1, min(per_save, int(_WORK_PER_CALL / (N * method.evaluations))))


def _progress(total, enabled):
    try:
        from tqdm.auto import tqdm
    except ImportError:  # pragma: no cover - tqdm is a dependency
        return None
    # disable=None: silent when stderr is not a terminal
    return tqdm(total=total, unit="T", disable=None if enabled is None else not enabled,
                leave=False, desc="lattice")
