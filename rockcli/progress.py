"""What a long computation tells whoever shows progress (plain Python: the display is :mod:`rockcli.cli.progress`).

Two things, both optional for the caller of the library:

* **Phases.** A function that takes ``progress`` (a callable told ``progress(n)`` as ``n`` more steps
  are done) may do its work in parts of different kinds; before each part it calls
  :func:`phase`, which passes the part's name, its number of steps and whether those steps measure
  the work (``known``) to ``progress.phase`` when the callable has that method, and does nothing
  otherwise (a plain function or a bound method sees only the steps). ``known=False`` says that the
  steps do not predict the time left: the margin search settles (scene, scale factor) pairs, most of
  them at once without a run (every factor above the first that overturns, every factor below one
  that does not lift the body off) and the others one run each, of very different costs, and how
  far each search goes is what it finds out; a display shows no time left for such a part.
* **Runs.** A part whose steps come rarely (the minimum overturning search counts columns, each done only when
  its whole search ends, minutes into a large search) may also tell the runs it makes as they finish, through
  :func:`runs_counter`: ``progress.runs(n)`` when the callable has that method, so that a display moves.
* **Waits.** A step that takes seconds and can report nothing while it runs (a reader's first use of
  a heavy library) calls :func:`announce` with one line saying what it is doing; whoever listens
  (:func:`subscribe`; the command line on a terminal) shows it. Nobody listening: nothing happens.
"""

from __future__ import annotations

import threading

_listeners: list = []
_lock = threading.Lock()


def phase(progress, name: str, steps: int, *, known: bool = True, unit: str | None = None) -> None:
    """Tell ``progress`` that a part of the work of ``steps`` steps begins, if it wants to know.

    Parameters
    ----------
    progress : callable or None
        The caller's progress callable; its ``phase(name, steps, known=..., unit=...)`` is called when it
        has one.
    name : str
        What the part does, in a few words (``"verdicts"``, ``"margins"``).
    steps : int
        The steps of the part, told as ``progress(n)`` increments that add up to it.
    known : bool
        The steps are units of work of a similar cost (runs at scale 1, a grid of runs), so the time
        of those done predicts the time of the rest; False when they do not (see the module notes).
    unit : str, optional
        What one step is, for a count (``"runs"``, ``"scenes"``); None when a count would mean nothing
        to the reader.
    """
    begin = getattr(progress, "phase", None)
    if callable(begin):
        begin(name, int(steps), known=bool(known), unit=unit)


def runs_counter(progress):
    """``progress.runs`` (told ``runs(n)`` as ``n`` more runs finish, within a part's steps), or None when the caller's
    progress callable has no such method (a plain function counts the part's steps only)."""
    runs = getattr(progress, "runs", None)
    return runs if callable(runs) else None


def subscribe(listener):
    """Call ``listener(text)`` on every :func:`announce`; returns a function that unsubscribes."""
    with _lock:
        _listeners.append(listener)

    def unsubscribe():
        with _lock:
            if listener in _listeners:
                _listeners.remove(listener)

    return unsubscribe


def announce(text: str) -> None:
    """Say, in one line, that a wait without progress begins (``text``: what is being done and how long it
    may take); a listener's error is dropped (a notice that cannot be shown is no reason to fail)."""
    with _lock:
        listeners = list(_listeners)
    for listener in listeners:
        try:
            listener(text)
        except Exception:  # noqa: BLE001
            pass
