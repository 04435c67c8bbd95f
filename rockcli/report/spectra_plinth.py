"""The plinth of ``rockcli spectrum ... --on`` in the spectra's outputs: its CSV columns (``plinth``, ``toppled``)
and its words in the figures (a panel or curve ``alone`` or ``on plinth``, the plinth's proportions in the title).
Used by :mod:`rockcli.report.spectra` and :mod:`rockcli.report.rocking`; nothing changes without a plinth."""

from __future__ import annotations


def plinth_columns(m, n) -> dict:
    """A map's ``plinth`` and ``toppled`` columns (``--on``)."""
    import numpy as np

    label = "" if m.plinth is None else m.plinth.label
    toppled = np.zeros(n, np.int8) if m.toppled is None else np.asarray(m.toppled).ravel()
    return {"plinth": np.full(n, label, dtype=object),
            "toppled": np.array(["", "body", "plinth"], dtype=object)[toppled]}


def with_plinth(columns, items) -> tuple:
    """``columns`` with ``plinth`` after ``isolation`` (and ``toppled`` after ``overturned``) when any of ``items``
    (maps or curves) stands on a plinth: the CSV of ``--on`` names the plinth on every row."""
    if not any(getattr(i, "plinth", None) is not None for i in items):
        return tuple(columns)
    out = []
    for c in columns:
        out.append(c)
        if c == "isolation":
            out.append("plinth")
        elif c == "overturned":
            out.append("toppled")
    return tuple(out)


def on_words(item, items) -> str:
    """``, on plinth`` for a map or curve on a plinth, ``, alone`` for one without among some with (``--on``), empty
    otherwise (the plinth's proportions are in the title: :func:`plinth_title`)."""
    if item.plinth is None:
        return ", alone" if any(getattr(i, "plinth", None) is not None for i in items) else ""
    from rockcli.report.figures import plain

    return f", on {plain(item.plinth.name)}"


def plinth_title(title, items):
    """The figure's title with the plinth of ``--on`` in words: ``on a free plinth: H2/H1 = 0.5, B2/B1 = 1.5 (the
    body's height and width), same density`` (``title`` alone when no item stands on a plinth)."""
    plinths = list(dict.fromkeys(i.plinth for i in items if getattr(i, "plinth", None) is not None))
    if not plinths:
        return title
    from rockcli.report.figures import plain

    words = []
    for p in plinths:
        mass = "same density" if p.mass_ratio is None else f"$M_2/M_1$ = {p.mass_ratio:g}"
        words.append(f"{plain(p.name)}: $H_2/H_1$ = {p.height_ratio:g}, $B_2/B_1$ = {p.width_ratio:g} "
                     f"(of the body's height and width), {mass}, rocking with the body")
    return "; ".join(([title] if title else []) + words)
