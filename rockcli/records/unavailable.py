"""What could not be run, as data: a record asked for (or in the default set) that is neither a file nor a pulse
(:class:`Unavailable`), a file of a folder suite that is not a record (:class:`Skipped`), a source naming a record the
suite holds already (:class:`Duplicate`). Made by :mod:`rockcli.assess` (its excitations), said by
:mod:`rockcli.report` (:func:`rockcli.report.words.unavailable_notes`).
"""

from __future__ import annotations

from dataclasses import dataclass


@dataclass(frozen=True)
class Unavailable:
    """A record asked for (or in the default set) that cannot be run: neither file nor pulse."""

    label: str
    reason: str


@dataclass(frozen=True)
class Skipped(Unavailable):
    """A file of a folder suite that is not a record by its content (no reader recognises it)."""


@dataclass(frozen=True)
class Duplicate(Unavailable):
    """A source that names a record the suite holds already (a symbolic link, a second spelling of a
    component): run once (:mod:`rockcli.assess.suite`); ``reason`` names the one kept."""
