"""What a long command shows on a terminal while it works: the notices and the progress lines.

All of it goes to the standard error, and all but the compile notice only when it is a terminal: a progress
line redrawn in place would fill a log with carriage returns, and a script could not act on it.

* :func:`watch_compiles`: the first run on a machine compiles the kernels (minutes on a loaded machine, nothing
  else moves); one line says so when the compile begins (:mod:`rockcli.compiling` tells when), once
  per process, whatever the standard error is: a run piped, redirected or in CI would otherwise sit silent
  for minutes, and the line tells why that run took longer than the next. A run whose kernels load from the
  cache says nothing.
* :func:`watch_waits`: one line when a step that can report no progress begins (a record read
  through gmprocess, whose first read loads its readers: :func:`rockcli.progress.announce`).
* :class:`Progress`: one line per part of the work (:func:`rockcli.progress.phase`: the verdicts at
  1x, the margin search, the neighbourhood), with the count done and the time it has taken, redrawn
  every second. A time left (ETA) is shown only for a part whose steps are runs of a similar cost
  (``known``), measured on the runs done after the kernels were ready, once there are enough of them
  to measure; never for the margin search, whose (scene, factor) pairs settle mostly without a run
  and whose length is what it finds out (the ETA it used to show swung from 0:03 to 0:34 and showed
  0:00 with three minutes left; docs/performance.md).
"""

from __future__ import annotations

import shutil
import sys
import threading
import time

#: The notice, in one line (the times: ``benchmarks/bench_first_run.py`` on 2 cores; docs/performance.md).
COMPILE_NOTICE = ("rockcli: compiling the solver kernels for this machine (first run only; about 20-40 s per "
                  "foundation type, later runs load them from the cache) ...")

_watching = False


def watch_compiles(stream=None) -> None:
    """Print :data:`COMPILE_NOTICE` once on ``stream`` (stderr) when a kernel compile begins, on a terminal (over a
    progress line) or not: piped, redirected, in a CI log (idempotent; costs nothing until the kernels are used)."""
    global _watching
    stream = stream or sys.stderr
    if _watching:
        return
    from rockcli import compiling

    said = []

    def on_start(name):
        if said:
            return
        said.append(name)
        if _isatty(stream):
            _notice(stream, COMPILE_NOTICE)
        else:  # a plain line: no carriage return or erase-line code in a log
            with _screen:
                stream.write(COMPILE_NOTICE + "\n")
                stream.flush()

    compiling.subscribe(on_start=on_start)
    _watching = True


def watch_waits(stream=None) -> None:
    """Print each wait the library announces (:func:`rockcli.progress.announce`) as one line
    ``rockcli: ...`` on ``stream`` (stderr) if it is a terminal (idempotent)."""
    global _watching_waits
    stream = stream or sys.stderr
    if _watching_waits or not _isatty(stream):
        return
    from rockcli import progress

    progress.subscribe(lambda text: _notice(stream, "rockcli: " + text))
    _watching_waits = True


_watching_waits = False
#: One writer at a time on the terminal: the notices, the progress line and its clock thread.
_screen = threading.RLock()
#: The progress line on the terminal now, drawn again under a notice.
_active = None


def _notice(stream, text: str) -> None:
    """``text`` as a line of its own, over a progress line, which is then drawn again below it."""
    with _screen:
        stream.write("\r\033[K" + text + "\n")
        stream.flush()
        if _active is not None:
            _active.draw(force=True)


def _isatty(stream) -> bool:
    try:
        return bool(stream.isatty())
    except (AttributeError, ValueError, OSError):
        return False


def clock_text(seconds: float) -> str:
    """``m:ss`` (``h:mm:ss`` from an hour on)."""
    t = int(round(max(0.0, seconds)))
    return f"{t // 3600:d}:{t // 60 % 60:02d}:{t % 60:02d}" if t >= 3600 else f"{t // 60:d}:{t % 60:02d}"


class Progress:
    """Progress lines on ``stream``, one per part of the work, with an ETA only where it can be measured.

    Use as a context manager; the work calls it (or :meth:`update`) with increments of steps, and
    :meth:`phase` when a new part begins (through :func:`rockcli.progress.phase`). A part's line shows
    its name, a bar, the count (``12/80 runs``) or the share of its steps done, the time it has taken
    and, for a ``known`` part only, the time left. When a part ends its line stays, complete, and the
    next one is drawn below it. The line is redrawn every ``tick`` seconds (the clock moves while a
    long batch runs) and never wider than the terminal.

    The time left of a known part is the time per step measured from the first update after the
    kernels were ready (a compile during the part restarts the measurement; the steps of that first
    update are not counted, as their time included the wait), times the steps left, less the time
    since the last update; it is shown only after :attr:`MIN_SECONDS` of measurement, at least
    :attr:`MIN_UPDATES` further updates and :attr:`MIN_SHARE` of the steps, and not once it has run
    out (no ``ETA 0:00`` over work still going on).
    """

    #: share of the part's steps (after the rate clock started) before an ETA is shown
    MIN_SHARE = 0.02
    #: seconds of measured work before an ETA is shown
    MIN_SECONDS = 3.0
    #: updates after the one that started the rate clock before an ETA is shown
    MIN_UPDATES = 2
    #: characters of the bar
    BAR = 30
    #: seconds between redraws of the clock
    TICK = 1.0

    def __init__(self, total: int, label: str = "runs", *, eta: bool = True, unit: str | None = None, stream=None,
                 clock=time.monotonic, tick: float | None = TICK):
        self.stream = stream or sys.stderr
        self.clock = clock
        self.tick = tick
        self._stop = threading.Event()
        self._thread = None
        self._entered = False
        self._drawn = 0.0
        self._begin(label, total, eta, unit)

    # ---- the work's side -------------------------------------------------------------------------

    def __call__(self, n: int) -> None:
        self.update(n)

    def update(self, n: int) -> None:
        """Advance the current part by ``n`` steps."""
        from rockcli import compiling

        with _screen:
            self.pos += int(n)
            if compiling.compiling():
                self._start = None
            elif self._start is None:
                self._start, self._updates = (self.clock(), self.pos), 0
            else:
                self._updates += 1
            self._last = self.clock()
            self.draw()

    def runs(self, n: int) -> None:
        """``n`` more runs of the current part are done (:func:`rockcli.progress.runs_counter`): counted beside its
        steps, for a part whose steps come rarely; they measure no time left."""
        with _screen:
            self.runs_done += int(n)
            self.draw()

    def phase(self, name: str, steps: int, *, known: bool = True, unit: str | None = None) -> None:
        """A new part of ``steps`` steps begins: the current part's line is completed (left as it is when
        nothing of it was done) and the new part's drawn below it."""
        with _screen:
            if self._entered and self.pos > 0:
                self._close(complete=True)
            self._begin(name, steps, known, unit)
            self.draw(force=True)

    # ---- what is shown ---------------------------------------------------------------------------

    def elapsed(self) -> float:
        """Seconds since the current part began."""
        return self.clock() - self._t_begin

    def eta(self) -> float | None:
        """Seconds still to go in the current part, or None while it cannot be told (see the class notes)."""
        if not self.known or self._start is None or self.pos >= self.total:
            return None
        t0, p0 = self._start
        measured, done = self._last - t0, self.pos - p0
        if done <= 0 or measured < self.MIN_SECONDS or self._updates < self.MIN_UPDATES:
            return None
        if done < self.MIN_SHARE * (self.total - p0):
            return None
        left = measured / done * (self.total - self.pos) - (self.clock() - self._last)
        return left if left > 0 else None

    def line(self) -> str:
        """The current part's line: ``name  [####    ]  12/80 runs  0:42, ETA 1:10``; with runs told by :meth:`runs`,
        ``search  [#       ]  12/1488 columns, 35,210 runs  1:42``."""
        share = min(1.0, self.pos / self.total) if self.total > 0 else 1.0
        fill = int(share * self.BAR)
        count = (f"{min(self.pos, self.total)}/{self.total} {self.unit}" if self.unit
                 else f"{int(share * 100):3d}%")
        if self.runs_done:
            count += f", {self.runs_done:,} run{'s' if self.runs_done != 1 else ''}"
        when = clock_text(self.elapsed())
        eta = self.eta()
        if eta is not None:
            when += f", ETA {clock_text(eta)}"
        return f"{self.label}  [{'#' * fill}{' ' * (self.BAR - fill)}]  {count}  {when}"

    def draw(self, force: bool = False) -> None:
        """Draw the line again (at most ten times a second unless ``force``), cut to the terminal's width."""
        if not self._entered:
            return
        now = time.monotonic()
        if not force and now - self._drawn < 0.1:
            return
        self._drawn = now
        width = max(20, shutil.get_terminal_size((80, 24)).columns - 1)
        with _screen:
            self.stream.write("\r" + self.line()[:width] + "\033[K")
            self.stream.flush()

    # ---- the context -----------------------------------------------------------------------------

    def __enter__(self):
        global _active
        with _screen:
            self._entered = True
            _active = self
            self.draw(force=True)
        if self.tick:
            self._thread = threading.Thread(target=self._tick, name="rockcli-progress", daemon=True)
            self._thread.start()
        return self

    def __exit__(self, exc_type, *exc):
        global _active
        self._stop.set()
        if self._thread is not None:
            self._thread.join()
        with _screen:
            if exc_type is None:
                self._close(complete=True)
            else:  # an error: the line goes, so that the sentence saying what went wrong stands alone
                self.stream.write("\r\033[K")
                self.stream.flush()
            self._entered = False
            if _active is self:
                _active = None
        return False

    def _begin(self, label, steps, known, unit) -> None:
        self.label, self.total, self.known, self.unit = str(label), max(0, int(steps)), bool(known), unit
        self.pos = 0
        self.runs_done = 0  # runs told by runs(), within the part's steps
        self._t_begin = self._last = self.clock()
        self._start = None  # (time, pos) from which the rate is measured
        self._updates = 0  # updates since then

    def _close(self, complete: bool) -> None:
        """The current part's last line (its steps all counted when ``complete``), then a new line."""
        if complete:
            self.pos = max(self.pos, self.total)
        self.draw(force=True)
        self.stream.write("\n")
        self.stream.flush()

    def _tick(self) -> None:
        while not self._stop.wait(self.tick):
            self.draw(force=True)
