"""Dask preload of the local map workers: a worker ignores SIGINT (a Ctrl-C to the
terminal reaches the whole process group; the client stops its workers in order)."""

import signal


def dask_setup(worker):  # the dask preload hook
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    signal.pthread_sigmask(signal.SIG_UNBLOCK, {signal.SIGTERM})
