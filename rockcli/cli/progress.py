"""What a long command shows on a terminal while it works: the compile notice and the progress bar.

Both go to the standard error and only when it is a terminal: output that is piped, redirected or
checked by tests (and CI logs) is the same on the first run and on every later one, and a script
could not act on either.

* :func:`watch_compiles`: the first run on a machine compiles the kernels (tens of seconds, nothing
  else moves); one line says so when the compile begins (:mod:`rockcli.compiling` tells when), once
  per process. A run whose kernels load from the cache says nothing.
* :class:`Progress`: a click progress bar whose ETA is measured from the work done after the
  kernels were ready, and shown only once enough of it is done to measure: the compile (and the
  first, uneven batch) would otherwise be read as the pace of the whole job (an ETA of hours).
"""

from __future__ import annotations

import sys
import time

import click

#: The notice, in one line (the times: ``benchmarks/bench_first_run.py`` on 2 cores; docs/performance.md).
COMPILE_NOTICE = ("rockcli: compiling the solver kernels for this machine (first run only; about 20-40 s per "
                  "foundation type, later runs load them from the cache) ...")

_watching = False


def watch_compiles(stream=None) -> None:
    """Print :data:`COMPILE_NOTICE` once on ``stream`` (stderr) when a kernel compile begins, if it is a
    terminal (idempotent; costs nothing until the kernels are used)."""
    global _watching
    stream = stream or sys.stderr
    if _watching or not _isatty(stream):
        return
    from rockcli import compiling

    said = []

    def on_start(name):
        if said:
            return
        said.append(name)
        stream.write("\r\033[K" + COMPILE_NOTICE + "\n")  # over a progress bar's line, which is drawn again
        stream.flush()

    compiling.subscribe(on_start=on_start)
    _watching = True


def _isatty(stream) -> bool:
    try:
        return bool(stream.isatty())
    except (AttributeError, ValueError, OSError):
        return False


class Progress:
    """A progress bar of ``total`` steps on ``stream`` with an ETA that is not fooled by a compile.

    The rate is measured from the first update after the kernels were ready (a compile during the
    run restarts the measurement), and the ETA is shown only once :attr:`MIN_SHARE` of the
    remaining steps, or :attr:`MIN_SECONDS`, have passed since then; until then the bar shows the
    share done and nothing else. Use as a context manager; :meth:`update` takes increments.
    """

    #: share of the steps (after the rate clock started) before an ETA is shown
    MIN_SHARE = 0.02
    #: seconds of measured work before an ETA is shown
    MIN_SECONDS = 3.0

    def __init__(self, total: int, label: str = "runs", *, eta: bool = True, stream=None, clock=time.monotonic):
        self.total, self.eta_wanted, self.clock = int(total), eta, clock
        self.pos = 0
        self._start = None  # (time, pos) from which the rate is measured
        self._bar = click.progressbar(length=self.total, label=label, file=stream or sys.stderr, show_eta=False,
                                      item_show_func=self._eta_text)

    def __enter__(self):
        self._bar.__enter__()
        return self

    def __exit__(self, *exc):
        return self._bar.__exit__(*exc)

    def update(self, n: int) -> None:
        """Advance by ``n`` steps."""
        from rockcli import compiling

        if compiling.compiling():
            self._start = None
        elif self._start is None:
            self._start = (self.clock(), self.pos)  # the work before this update included the wait
        self.pos += int(n)
        self._bar.update(n)

    def eta(self) -> float | None:
        """Seconds still to go, or None while it cannot be told (see the class notes)."""
        if not self.eta_wanted or self._start is None or self.pos >= self.total:
            return None
        t0, p0 = self._start
        elapsed, done = self.clock() - t0, self.pos - p0
        if done <= 0 or elapsed <= 0:
            return None
        if done < self.MIN_SHARE * (self.total - p0) and elapsed < self.MIN_SECONDS:
            return None
        return elapsed / done * (self.total - self.pos)

    def _eta_text(self, _item=None):
        eta = self.eta()
        if eta is None:
            return None
        t = int(round(eta))
        return f"ETA {t // 3600:d}:{t // 60 % 60:02d}:{t % 60:02d}" if t >= 3600 else f"ETA {t // 60:d}:{t % 60:02d}"
