"""``assess column nemea-drums --friction MU``: columns of drums, each beside its monolith (:mod:`rockcli.assess.drums`,
docs/physics-drums.md). What a column of drums does not take yet is refused here in one sentence, before any work."""

from __future__ import annotations

from rockcli.errors import RockcliInputError


def drum_names(columns) -> list:
    """The names of the columns of drums among ``columns``."""
    from rockcli.assess.drums import is_drum_column

    return [c.name for c in columns if is_drum_column(c)]


def with_drums(columns, *, friction, refused=()) -> list:
    """``columns`` with each column of drums followed by its monolith (:func:`rockcli.assess.drums.with_monoliths`);
    unchanged without drums. ``refused``: ``(option, given)`` pairs a column of drums does not take (one sentence);
    a column of drums needs ``--friction`` with one coefficient."""
    from rockcli.assess.drums import with_monoliths

    names = drum_names(columns)
    if not names:
        return list(columns)
    what = f"{', '.join(names)} {'is a column' if len(names) == 1 else 'are columns'} of drums"
    if friction is None:
        raise RockcliInputError(f"{what}: give --friction MU, the friction of every joint and of the base (stone on "
                                f"stone: 0.5-0.8); the joints stick, open or slide by it")
    if "=" in str(friction):
        raise RockcliInputError(f"{what}: --friction takes one coefficient for every contact (base=..,joint=.. is for "
                                f"a body on its plinth, --on)")
    bad = [name for name, given in refused if given]
    if bad:
        raise RockcliInputError(f"{what}, run from rest under the horizontal ground motion with the plastic impact "
                                f"and Coulomb's law: {', '.join(bad)} {'is' if len(bad) == 1 else 'are'} not taken "
                                f"with drums yet")
    return with_monoliths(columns)


def refuse_drums_in_fragility(columns) -> None:
    """``assess fragility`` does not take columns of drums yet: one sentence."""
    names = drum_names(columns)
    if names:
        raise RockcliInputError(f"assess fragility does not take columns of drums yet ({', '.join(names)}): run "
                                f"'rockcli assess column {' '.join(names)} --friction MU' for their margins, record by "
                                f"record, beside their monoliths")


def drums_json(column) -> dict:
    """A column of drums' drums, static thresholds and monolith, for ``--json``'s columns (nothing for a body)."""
    from rockcli.assess.drums import is_drum_column

    if not is_drum_column(column):
        return {}
    from rockcli.models.drums import monolith_beside

    col = getattr(column, "subject", column)
    return {"drums": [{"height_m": h, "width_m": w} for h, w in col.drums],
            "static_thresholds_g": col.static_thresholds(), "monolith": monolith_beside(col).name}
