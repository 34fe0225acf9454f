"""Run control of ``simulate``: Ctrl-C deferred to a consistent state, bounded calls into
compiled code, the progress bar."""

from __future__ import annotations

import contextlib
import signal
import threading

from common.signals import SIGNALS, Interrupted, is_interrupt_handler


class _Interrupt(Exception):
    """Ctrl-C (or SIGTERM) noticed between two calls into compiled code (state and time
    consistent); ``args[0]``: the signal."""


@contextlib.contextmanager
def _deferred_interrupt():
    """Turn SIGINT (and SIGTERM where it is handled as an interrupt, e.g. by the CLI) into
    a flag checked between calls into compiled code, so an interrupted run stops on a
    state whose time is known exactly. Only in the main thread and for signals whose
    handler raises KeyboardInterrupt (else nothing changes); a second signal raises at
    once. Yields a function returning the signal number that came (0: none)."""
    flag = []
    if threading.current_thread() is not threading.main_thread():
        yield lambda: 0
        return
    old = {s: signal.getsignal(s) for s in SIGNALS}
    ours = [s for s, h in old.items() if is_interrupt_handler(h)]
    if not ours:
        yield lambda: 0
        return

    def handler(signum, frame):
        if flag:
            raise Interrupted(signum)
        flag.append(signum)

    for s in ours:
        signal.signal(s, handler)
    try:
        yield lambda: flag[0] if flag else 0
    finally:
        for s in ours:
            signal.signal(s, old[s])


#: site-evaluations per call into compiled code: ~0.1 s, so Ctrl-C answers promptly
_WORK_PER_CALL = 3e7


def _steps_per_call(N, method, per_save):
    if not method.fixed_step:  # scipy: one solve_ivp per record, as before
        return per_save
    return max(1, min(per_save, int(_WORK_PER_CALL / (N * method.evaluations))))


#: public names for any lattice's runs (numerics.models): Ctrl-C deferred to the end of a
#: compiled call, and the steps of one call
deferred_interrupt = _deferred_interrupt
steps_per_call = _steps_per_call


def _progress(total, enabled):
    try:
        from common.progress import progress_class
        tqdm = progress_class()
    except ImportError:  # pragma: no cover - tqdm is a dependency
        return None
    # disable=None: silent when stderr is not a terminal
    return tqdm(total=total, unit="T", disable=None if enabled is None else not enabled,
                leave=False, desc="lattice")
