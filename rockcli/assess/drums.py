"""Columns of drums in an assessment (``assess column nemea-drums --friction MU``, docs/physics-drums.md).

A column of drums (:class:`rockcli.models.drums.DrumColumn`, with friction: a
:class:`rockcli.solve.slide_many.Sliding`) runs beside its monolith (:func:`rockcli.models.drums.monolith_beside`: for
a preset the paper's column itself), with the same friction at the base, on the same records and configurations:
:func:`with_monoliths` adds the monoliths to the columns. Each run is the friction driver's own answer (there is no
rocking model of a stack of drums; the monolith's run is the rocking model's where nothing slides, as for any body
with friction, :mod:`rockcli.solve.slide_many`). The margin is the existing search's
(:mod:`rockcli.assess.margin`): the smallest factor of the record at which the column fails, a drum falling (or the
whole column) or sliding off the one below.

:func:`drum_fields` fills what the drums add to a row (where the column fails, which joint moves first, the openings,
the residual offsets, the contact law's counts); :func:`pair_drum_rows` sets, record by record, the drums against
their monolith (``safer``, ``worse``, ``alike``: :func:`rockcli.solve.drums.compare`, the rule of ``simulate
--drums``) and whether each answer is reliable (no event without a consistent contact pattern, in the run or in the
runs its margin rests on).
"""

from __future__ import annotations

import math

from rockcli.errors import RockcliInputError

#: ``drums_vs_monolith`` where a run of the pair is not proven (still moving at the solver's horizon).
UNDECIDED = "undecided"


def _subject(column):
    return getattr(column, "subject", column)


def is_drum_column(column) -> bool:
    """A column of drums (bare, or with friction as a :class:`rockcli.solve.slide_many.Sliding`)."""
    from rockcli.models.drums import DrumColumn

    return isinstance(_subject(column), DrumColumn)


def with_monoliths(columns) -> list:
    """``columns`` with each column of drums followed by its monolith (:func:`rockcli.models.drums.monolith_beside`);
    a monolith already among the columns (``assess column nemea nemea-drums``) is not added twice; a column of
    another shape under the monolith's name is refused in one sentence."""
    from rockcli.models.drums import monolith_beside

    named = {getattr(c, "name", None): c for c in columns}
    out = []
    for c in columns:
        out.append(c)
        if not is_drum_column(c):
            continue
        mono = monolith_beside(_subject(c))
        there = named.get(mono.name)
        if there is None:
            out.append(mono)
            named[mono.name] = mono
        elif _subject(there) != mono:
            raise RockcliInputError(f"column {mono.name!r} is the name of the monolith beside {c.name!r}: give the "
                                    f"other column another name")
    return out


def drum_roles(columns) -> dict:
    """``{column name: ("drums" | "monolith", the drum column's name)}`` for the columns of drums and their monoliths
    among ``columns`` (empty without drums)."""
    from rockcli.models.drums import monolith_beside

    names = {getattr(c, "name", None) for c in columns}
    roles = {}
    for c in columns:
        if is_drum_column(c):
            roles[c.name] = ("drums", c.name)
            mono = monolith_beside(_subject(c)).name
            if mono in names:
                roles[mono] = ("monolith", c.name)
    return roles


def monolith_name(roles: dict, drum_name: str) -> str | None:
    """The name of the monolith beside the drum column ``drum_name`` in ``roles`` (None: not assessed)."""
    return next((n for n, (kind, d) in roles.items() if kind == "monolith" and d == drum_name), None)


def drum_row(row, column, role) -> None:
    """Name on ``row`` the column of drums it belongs to and its drums (1 for the monolith), before any run."""
    row.drum_column = role[1]
    row.drums = len(_subject(column).drums) if role[0] == "drums" else 1


def drum_fields(row, r, role) -> None:
    """What a column of drums (``r`` a :class:`rockcli.solve.drums.DrumSlideRun`) or its monolith (``r`` a
    :class:`rockcli.solve.slide_many.SlideRun`) adds to ``row`` (:class:`rockcli.assess.AssessmentRow`)."""
    from rockcli.solve.drums import first_move

    kind = role[0]
    if kind == "drums":
        st = r.slide
        row.falls_at = r.falls_at or ""
        fm = r.first_move
        offsets = r.residual_offsets_m
        joints = st.interfaces[1:]
        opened = [p for p in joints if math.isfinite(p.t_uplift)]
        if opened:  # the first joint between drums to open (the base, the whole column, usually moves first)
            first = min(opened, key=lambda p: p.t_uplift)
            row.first_joint_open, row.first_joint_open_t_s = first.name, first.t_uplift
        if joints:
            top = max(joints, key=lambda p: p.psi_max_over_alpha)
            row.joint_open_max_over_alpha, row.joint_open_max_at = top.psi_max_over_alpha, top.name
            far = max(joints, key=lambda p: p.slide_max_m)
            row.joint_slide_max_m, row.joint_slide_max_at = far.slide_max_m, far.name
        row.peak_openings_over_alpha = " ".join(f"{p.psi_max_over_alpha:.4g}" for p in st.interfaces)
        row.n_inconsistent, row.n_jumps = r.n_inconsistent, r.n_jumps
    else:  # the monolith: one drum; where nothing slid its run is the rocking model's
        row.falls_at = "base" if r.overturned else ""
        fm = first_move(r.slide) if r.slid else (("base", r.t_uplift_s, "opens") if math.isfinite(r.t_uplift_s)
                                                 else None)
        offsets = [r.slide_residual_m]
        row.peak_openings_over_alpha = f"{r.theta_max_over_alpha:.4g}"
        row.n_inconsistent = r.slide.n_inconsistent if r.slid else 0
        row.n_jumps = r.slide.n_jumps if r.slid else 0
    if fm is not None:
        row.first_move, row.first_move_t_s = f"{fm[0]} {fm[2]}", fm[1]
    if not r.overturned:  # where the drums were left (a column that failed has no residual state)
        row.residual_offsets_m = " ".join(f"{x:.6g}" for x in offsets)
        row.residual_offset_max_m = max(offsets, key=abs)


def pair_drum_rows(rows, roles: dict, margin: bool) -> None:
    """After the runs (and the margins): each row of a column of drums or of its monolith says whether it is
    ``reliable``; each row of drums says how it compares with its monolith's row of the same record and
    configuration (``drums_vs_monolith``, :data:`UNDECIDED` when either run is not proven), with the monolith's
    verdict and margin."""
    from rockcli.assess.margin import NOTE_INCONSISTENT
    from rockcli.solve.drums import compare

    if not roles:
        return
    flag = NOTE_INCONSISTENT.partition("}")[2]
    by_key = {(r.column, r.record, r.configuration): r for r in rows}
    for row in rows:
        role = roles.get(row.column)
        if role is None or row.error or not row.verdict:
            continue
        row.reliable = not row.n_inconsistent and not (margin and flag in row.margin_note)
        if role[0] != "drums":
            continue
        m = by_key.get((monolith_name(roles, row.column), row.record, row.configuration))
        if m is None or m.error or not m.verdict:
            continue
        row.monolith_verdict, row.monolith_overturn_scale = m.verdict, m.overturn_scale
        if row.proven is False or m.proven is False:
            row.drums_vs_monolith = UNDECIDED
        else:
            row.drums_vs_monolith = compare(bool(row.overturned), bool(m.overturned), row.theta_max_over_alpha,
                                            m.theta_max_over_alpha)


__all__ = ["UNDECIDED", "drum_fields", "drum_roles", "drum_row", "is_drum_column", "monolith_name", "pair_drum_rows",
           "with_monoliths"]
