"""A suite's records counted once: by the file they are read from and its component, however named.

:class:`Suite` collects the excitations of :func:`rockcli.assess.resolve_excitations` in order. Two
excitations are one record when they are read from one file (the same file after following symbolic
links, or by inode: hard links; :func:`rockcli.io.files.file_key`) and are the same component of it (the
component read, by the name the file gives it, so ``N28W`` and ``332`` are one); a pair of horizontal
components is its two components (in either order) and the azimuth they are projected onto; a
catalogued pulse is its catalogue id. The second of two such excitations is not run: when it was named
differently (a symbolic link in a folder, a second spelling of a component) the notes say so
(:class:`~rockcli.assess.excitations.Duplicate`); the same name again is simply read once.

Two different records never share a label: two components of one file are labelled ``FILE:COMP``
(both of them), two files of one name in different folders ``folder/name`` (and the full path when
that is taken too).
"""

from __future__ import annotations

from dataclasses import replace
from pathlib import Path

from rockcli.assess.excitations import Duplicate, Excitation, Unavailable


def _component(x: Excitation, requested) -> str:
    """The component an excitation was read as: the name the file gives it, else the one asked for."""
    meta = getattr(x.motion, "meta", None) or {}
    name = meta.get("component")
    return str(name) if name not in (None, "") else ("" if requested is None else str(requested))


class Suite:
    """The excitations of one run, each record once, with labels that differ (see the module notes)."""

    def __init__(self):
        self.out: list = []
        self.unavailable: list = []
        self._keys: dict = {}    # record key -> the label it was kept under
        self._labels: dict = {}  # label -> (index in out, file key or None, component)

    def skip(self, u: Unavailable) -> None:
        self.unavailable.append(u)

    def _key(self, x: Excitation, path, component: str):
        from rockcli.io.files import file_key

        if x.pair is not None:
            ends = frozenset((file_key(r.meta.get("path") or r.name), str(r.meta.get("component") or ""))
                             for r in x.pair)
            return ("pair", ends, float(x.azimuth_deg))
        if path is None:
            return ("id", x.label)
        if x.motion is None:
            return ("unread", file_key(path), component, x.label)
        return ("file", file_key(path), component)

    def add(self, x: Excitation, path=None, component=None) -> None:
        """Add ``x`` (read from ``path``; ``component`` the one asked for) unless its record is in already."""
        from rockcli.io.files import file_key

        comp = _component(x, component)
        key = self._key(x, path, comp)
        if key in self._keys:
            kept = self._keys[key]
            if kept != x.label:
                self.unavailable.append(Duplicate(x.label, f"the same record as {kept}"))
            return
        fkey = None if path is None else file_key(path)
        if x.label in self._labels:
            i, other_fkey, other_comp = self._labels[x.label]
            if fkey is not None and fkey == other_fkey and comp and other_comp and comp != other_comp:
                first = self.out[i]
                del self._labels[first.label]
                self._rekey(first.label, f"{first.label}:{other_comp}")
                self.out[i] = replace(first, label=f"{first.label}:{other_comp}")
                self._labels[self.out[i].label] = (i, other_fkey, other_comp)
                x = replace(x, label=f"{x.label}:{comp}")
            elif path is not None:
                p = Path(path)
                x = replace(x, label=f"{p.parent.name}/{p.name}")
                if x.label in self._labels:
                    x = replace(x, label=str(p))
        if x.label in self._labels:  # still taken (a user's label): keep both apart
            x = replace(x, label=f"{x.label} ({len(self.out) + 1})")
        self._keys[key] = x.label
        self._labels[x.label] = (len(self.out), fkey, comp)
        self.out.append(x)

    def _rekey(self, old: str, new: str) -> None:
        for k, label in self._keys.items():
            if label == old:
                self._keys[k] = new
