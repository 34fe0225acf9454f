"""The Dask cluster of a map: a LocalCluster, or an existing scheduler checked first.

An address is probed before ``Client`` touches it: a Dask scheduler speaks first (its
comm handshake: an 8-byte little-endian frame count, then the frames), so within
``timeout`` seconds we know whether something answers, and whether it speaks Dask. An
HTTP server, a port that accepts and never answers, or a closed port fail in one line
naming the address, within the timeout (``Client`` itself would hang on a silent port and
try to allocate exabytes from an HTTP reply).

Signals: local workers ignore SIGINT (a Ctrl-C to the terminal's process group reaches
them too; the client stops them in order instead of each printing a traceback), and the
client blocks SIGINT/SIGTERM while the cluster starts, so an interrupt during start-up is
handled once the cluster can be closed cleanly (a second or two later), not in the middle
of Dask's start-up.
"""

from __future__ import annotations

import contextlib
import logging
import signal
import socket
import struct
import sys
import threading
import time
from urllib.parse import urlparse

_QUIET = ("distributed", "distributed.worker", "distributed.scheduler", "distributed.nanny",
          "distributed.core", "distributed.comm", "distributed.client", "tornado",
          "asyncio")


class SchedulerError(ValueError):
    """--scheduler does not lead to a Dask scheduler (one line naming the address)."""


class ClusterLost(ValueError):
    """The map's cluster stopped working mid-map: its scheduler is gone, or it has had no
    worker for ``timeout`` seconds (one line naming the address and what was kept)."""


class Watchdog:
    """Is the cluster still able to finish the map? Called while no task finishes:
    :meth:`check` raises ClusterLost once the scheduler has been unreachable, or has had
    no worker, for ``timeout`` seconds (a worker that comes back resets the count). Each
    call asks the scheduler at most every ``every`` seconds, within ``every`` seconds."""

    def __init__(self, client, address: str, timeout: float, every: float = 1.0):
        self.client, self.address, self.timeout = client, address, timeout
        self.every = min(every, timeout / 4)
        now = time.monotonic()
        self.asked = now - self.every
        self.connected = self.had_workers = now

    def _workers(self) -> int | None:
        """Workers the scheduler has (None: it did not answer)."""
        try:
            return len(self.client.nthreads(callback_timeout=self.every))
        except Exception:  # noqa: BLE001 - no answer, whatever the reason
            return None

    def check(self) -> str | None:
        """None while the cluster works or may still; else why it cannot finish."""
        now = time.monotonic()
        if now - self.asked < self.every:
            return None
        self.asked = now
        running = self.client.status == "running"
        n = self._workers() if running else None
        now = time.monotonic()
        if running and n is not None:
            self.connected = now
        if n:
            self.had_workers = now
        if self.client.status in ("closing", "closed") or now - self.connected > self.timeout:
            return (f"lost the scheduler {self.address}: no answer for {self.timeout:g} s "
                    "(--timeout; it stopped, or the network did)")
        if now - self.had_workers > self.timeout:
            return (f"the scheduler {self.address} has had no worker for {self.timeout:g} s "
                    "(--timeout)")
        return None


def probe(address: str, timeout: float) -> None:
    """SchedulerError unless ``address`` (tcp://host:port or host:port) answers like a
    Dask scheduler within ``timeout`` seconds. Other schemes (tls, inproc, ucx) are left to
    ``Client``."""
    url = urlparse(address if "://" in address else f"tcp://{address}")
    if url.scheme == "inproc":
        raise SchedulerError(f"--scheduler {address}: an inproc:// address reaches a scheduler "
                             "inside this same process only; give tcp://HOST:PORT of a "
                             "running `dask scheduler`")
    if url.scheme != "tcp":
        return
    try:
        host, port = url.hostname, url.port
    except ValueError:
        host = port = None
    if not host or not port:
        raise SchedulerError(f"--scheduler {address!r}: give an address tcp://HOST:PORT")
    try:
        conn = socket.create_connection((host, port), timeout=timeout)
    except TimeoutError:
        raise SchedulerError(f"--scheduler {address}: no connection within {timeout:g} s") \
            from None
    except OSError as exc:
        raise SchedulerError(f"--scheduler {address}: cannot connect "
                             f"({exc.strerror or exc}); is a Dask scheduler running there?") \
            from None
    with conn:
        conn.settimeout(timeout)
        try:
            head = conn.recv(8)
        except TimeoutError:
            raise SchedulerError(f"--scheduler {address}: connected, but it sent nothing "
                                 f"within {timeout:g} s; a Dask scheduler greets at once, so "
                                 "this is not one (or it hangs)") from None
        except OSError as exc:
            raise SchedulerError(f"--scheduler {address}: the connection failed "
                                 f"({exc.strerror or exc})") from None
    if len(head) < 8 or not 1 <= struct.unpack("<Q", head)[0] <= 64:
        shown = head.decode("ascii", "replace").strip() or "nothing; it closed the connection"
        raise SchedulerError(f"--scheduler {address}: this is not a Dask scheduler (it "
                             f"answered {shown[:40]!r})")


def _quiet():
    for name in _QUIET:
        logging.getLogger(name).setLevel(logging.CRITICAL)  # worker tracebacks stay off


@contextlib.contextmanager
def signals_held():
    """SIGINT and SIGTERM held meanwhile, then handled as they would have been (their
    Python handlers, or the default action): a map block is written whole. Swaps the
    handlers: a signal mask of the main thread alone does not hold a signal to the
    process, which the kernel gives to any thread not masking it (the client's), whose
    handler then raises in the main thread at once."""
    if threading.current_thread() is not threading.main_thread():
        yield
        return
    got = []
    old = {s: signal.getsignal(s) for s in (signal.SIGINT, signal.SIGTERM)}
    for s, handler in old.items():
        if handler not in (signal.SIG_IGN, None):
            signal.signal(s, lambda signum, frame: got.append((signum, frame)))
    try:
        yield
    finally:
        for s, handler in old.items():
            if handler not in (signal.SIG_IGN, None):
                signal.signal(s, handler)
        if got:
            signum, frame = got[0]
            handler = old[signum]
            if callable(handler):
                handler(signum, frame)
            else:  # SIG_DFL: the default action, as if it came now
                signal.raise_signal(signum)


@contextlib.contextmanager
def _signals_deferred():
    """Block SIGINT and SIGTERM in this thread (and the threads it starts) meanwhile; a
    signal that came is delivered, and handled, on exit."""
    if threading.current_thread() is not threading.main_thread():
        yield
        return
    old = signal.pthread_sigmask(signal.SIG_BLOCK, {signal.SIGINT, signal.SIGTERM})
    try:
        yield
    finally:
        signal.pthread_sigmask(signal.SIG_SETMASK, old)


def connect(scheduler: str | None, workers: int | None, timeout: float = 20.0):
    """(client, cluster or None): a Client of ``scheduler`` (probed first) or of a new
    LocalCluster of ``workers`` processes."""
    from dask.distributed import Client

    from ._params import local_cores

    _quiet()
    if scheduler:
        probe(scheduler, timeout)
        try:
            return Client(scheduler, timeout=f"{timeout}s"), None
        except Exception as exc:  # noqa: BLE001 - whatever Dask says, one line naming it
            text = str(exc).splitlines()[0] if str(exc) else ""
            why = ("it answers as a Dask worker, not a scheduler: give the address its "
                   "scheduler printed" if "Worker." in text else
                   "give tcp://HOST:PORT of a running `dask scheduler`")
            raise SchedulerError(f"--scheduler {scheduler}: cannot use it as a Dask scheduler "
                                 f"({type(exc).__name__}: {text[:120]}); {why}") from None
    with _signals_deferred():
        cluster = local_cluster(workers or local_cores())
        client = Client(cluster)
    return client, cluster


#: Dask's settings for the LocalCluster a map starts (an existing scheduler keeps its own).
#: Both give workers' time back to the cells; bench/model_maps.py measures them
#: (bench/README.md, issue 40's row "2 workers against 1").
LOCAL_CLUSTER_CONFIG = {
    # the statistical profiler samples each worker's stacks every 10 ms for the dashboard's
    # profile page, which a map never shows: its thread and the GIL it takes cost a flexmm
    # model map's task phase ~10% on 2 workers of 2 cores (1.44 -> 1.26 s, measured)
    "distributed.worker.profile.enabled": False,
    # a worker is sent its next block when it is free (Dask's default, 1.1, sends one block
    # ahead, which no other worker may take: at a map's end one worker still had two blocks
    # while the other was idle)
    "distributed.scheduler.worker-saturation": 1.0,
}


def local_cluster(workers: int):
    """The LocalCluster of a map: ``workers`` processes of one thread, which ignore SIGINT
    (``numerics.maps._worker_preload``), with ``LOCAL_CLUSTER_CONFIG``. The caller closes
    it (``close``)."""
    import dask
    from dask.distributed import LocalCluster

    # multiprocessing's resource tracker (started with this interpreter's -W options) warns
    # of "leaked semaphores" of workers stopped by a signal: nothing leaks past its clean-up
    flag = "ignore:resource_tracker:UserWarning"
    if flag not in sys.warnoptions:
        sys.warnoptions.append(flag)
    # the scheduler reads its settings when it starts, each nanny keeps a copy of the
    # settings for the worker processes it starts (and restarts)
    with dask.config.set(LOCAL_CLUSTER_CONFIG):
        return LocalCluster(n_workers=workers, threads_per_worker=1, processes=True,
                            dashboard_address=":0", silence_logs=logging.CRITICAL,
                            preload=["numerics.maps._worker_preload"])


def close(client, cluster) -> None:
    """Close the client and the cluster, quietly, with SIGINT/SIGTERM deferred meanwhile
    (a second Ctrl-C does not leave worker processes behind)."""
    with _signals_deferred():
        with contextlib.suppress(Exception):
            client.close(timeout=10)
        if cluster is not None:
            with contextlib.suppress(Exception):
                cluster.close(timeout=10)
