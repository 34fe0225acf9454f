"""A map's progress as plain lines where no bar is drawn: stderr not a terminal (a log
file, ``nohup``, a batch job, ``flexmm map ... 2>&1 | tee``), where tqdm's bar is off and
a map of a hundred cells said nothing between its estimate and its end (minutes).

The first line comes FIRST_LINE_S after the tasks' start (the cluster's start-up included,
as in the estimate the caller gives), then one every EVERY_S at most
(also while no cell finishes, so that a silent map is a working one): cells done, the
time since the tasks started and what is left. What is left is measured, not assumed:
the cells finished since the first block came back over the time since then (the
workers' start-up, paid before the first block, is not a cell's cost), the tasks'
measured mean where only the first block is back, and before any the caller's estimate
(less the time gone), or nothing.
"""

from __future__ import annotations

import sys
import time

from common.text import duration

#: seconds from the tasks' start to the first line
FIRST_LINE_S = 10.0
#: seconds between two lines at most
EVERY_S = 30.0


class ProgressLines:
    """``update(n)`` after each block of n cells written, ``tick()`` while waiting (both
    print a line when one is due); ``write`` (a callable given the line) defaults to
    stderr. ``estimate``: seconds the cells were estimated to take, or None."""

    def __init__(self, total: int, what: str, estimate: float | None = None, write=None,
                 clock=time.perf_counter):
        self.total, self.what, self.estimate = int(total), what, estimate
        self._write = write or (lambda line: print(line, file=sys.stderr, flush=True))
        self._clock = clock
        self.t0 = clock()
        self.done = 0
        self._first = None  # (time, cells) when the first block came back
        self._due = self.t0 + FIRST_LINE_S

    def update(self, n: int) -> None:
        self.done += int(n)
        if self._first is None:
            self._first = (self._clock(), self.done)
        self.tick()

    def left(self, now: float) -> float | None:
        """Seconds left, measured (module docstring); None where nothing says."""
        rest = self.total - self.done
        if self._first is not None:
            t1, d1 = self._first
            if self.done > d1 and now > t1:
                return rest * (now - t1) / (self.done - d1)
            return rest * (t1 - self.t0) / d1  # one block back: its mean, start-up included
        if self.estimate is not None and now - self.t0 < self.estimate:
            return self.estimate - (now - self.t0)
        # past the estimate with no cell back: nothing measured says what is left (probe
        # 97: "about 0 s left" at 40 s of a paper map that took 72 s more)
        return None

    def line(self, now: float) -> str:
        left = self.left(now)
        share = f" ({100 * self.done / self.total:.0f}%)" if self.total else ""
        # "at the pace so far": cells are not alike (a stable cell runs all of T, an MI
        # one stops at 20x), so the pace moves: a 100-cell fput map in grid order said 49 s
        # left at 36% where 13 s were (its first rows the slow ones)
        when = ("" if left is None else
                f"; about {duration(left)} left" + (" at the pace so far"
                                                    if self._first is not None
                                                    else " (the estimate; no cell back yet)"))
        if left is None and self.estimate is not None and self._first is None:
            when = (f"; no cell back yet, past the estimate ({duration(self.estimate)}): "
                    "slower than measured (a busier machine, or slow cells)")
        return (f"map: {self.done} of {self.total} cells {self.what}{share} in "
                f"{now - self.t0:.0f} s{when}")

    def tick(self) -> None:
        now = self._clock()
        if now >= self._due and self.done < self.total:
            self._write(self.line(now))
            self._due = now + EVERY_S


def progress_lines(progress, total: int, what: str, estimate: float | None = None):
    """A ProgressLines where ``progress`` is None (the default: a bar only where stderr is a
    terminal) and stderr is no terminal; else None (a bar, a caller's callable, or off)."""
    if progress is not None:
        return None
    try:
        tty = sys.stderr.isatty()
    except (AttributeError, ValueError):  # a closed or replaced stderr: no lines
        return None
    return None if tty else ProgressLines(total, what, estimate)
