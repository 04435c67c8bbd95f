"""The answer in plain words (``rockcli assess column``'s printout): :func:`format_verdicts`.

The words themselves are made in :mod:`rockcli.report` (only words, nothing computed): one body and one run in
:mod:`rockcli.report.words` (:func:`scene_sentence`, :func:`body_noun`, the stroke), many runs in
:mod:`rockcli.report.verdicts` (:func:`configuration_sentence`, :func:`verdict_lines`, :func:`isolation_summary`), a
body on a plinth in :mod:`rockcli.report.plinth_words`; this module re-exports them (``rockcli.assess.verdicts``
keeps every name it had) and prints them for an :class:`rockcli.assess.Assessment`.
"""

from __future__ import annotations

import re

from rockcli.report.drum_words import DRUM_QUESTION, drum_answer, drum_noun, is_drums  # noqa: F401
from rockcli.report.plinth_words import PLINTH_QUESTION, plinth_help_parts, plinth_summary  # noqa: F401
from rockcli.report.verdicts import (_factor, _fx, _key, _luck, _margin_clause, _names, _one_margin,  # noqa: F401
                                     _one_record_clause, _saved_by_luck, _smallest_factor, _suite_clause,
                                     compare_foundations, configuration_sentence, isolation_summary, question,
                                     verdict_lines)
from rockcli.report.words import (FAILED, PAST_WORDS, SURVIVES, TOPPLES, UNDECIDED, _BEARINGS, _UNNAMED,  # noqa: F401
                                  _all_azimuths, _pct, _share_words, _x, body_noun, body_words, configuration_words,
                                  outcome, past_words, scene_sentence, stroke_m, stroke_words, survivor_stroke)


def _fill(text: str, width: int, **kw) -> str:
    """``textwrap.fill`` that never breaks a number from its unit (``62 %``, ``0.34 m``, ``6.8 s``, ``0.28 g``)."""
    import textwrap

    glued = re.sub(r"(\d) (%|m|s|g)(?!\w)", "\\1\x1f\\2", text)
    return textwrap.fill(glued, width, **kw).replace("\x1f", " ")


def format_verdicts(assessment, width: int = 100) -> str:
    """The answer as ``rockcli assess column`` prints it: per body, one sentence per configuration.

    Raises
    ------
    RockcliInputError
        ``assessment`` is not what :func:`rockcli.assess.run_assessment` returns, or ``width`` is not a whole
        number >= 40.
    """
    import numbers

    from rockcli.assess.table import Assessment
    from rockcli.errors import RockcliInputError
    from rockcli.io.inputs import check_type

    check_type(assessment, Assessment, "assessment", "the Assessment of run_assessment(...)")
    check_type(width, numbers.Integral, "width", "a whole number of characters >= 40")
    if width < 40:
        raise RockcliInputError(f"width must be a whole number of characters >= 40, got {width}")

    lines = ["In plain words:"]
    xs = [x.label for x in assessment.excitations if x.motion is not None]
    under = f"under {xs[0]}" if len(xs) == 1 else f"under {len(xs)} records"
    answers = verdict_lines(assessment)
    for b in assessment.columns:
        lines.append(f"{body_words(b)}, {under}:")
        for _, c, _, sentence in (a for a in answers if a[0] is b):
            lines.append(_fill(f"{configuration_words(c)}: {sentence}.", width, initial_indent="  ",
                                       subsequent_indent="      "))
        short = isolation_summary(assessment, b)
        if short:
            lines.append(_fill(short, width, initial_indent="  ", subsequent_indent="      "))
        helps = plinth_help_parts(assessment, b) if getattr(b, "plinth", None) is not None else []
        if helps:
            lines.append(f"  {PLINTH_QUESTION}")
            lines += [_fill(h, width, initial_indent="  - ", subsequent_indent="    ") for h in helps]
    for b in (b for b in assessment.columns if is_drums(b)):  # each column of drums beside its monolith
        lines.append(f"{DRUM_QUESTION} {drum_noun(b)[:1].upper()}{drum_noun(b)[1:]}, record by record:")
        for head, sentences in drum_answer(assessment, b):
            lines.append(_fill(head[:1].upper() + head[1:] + ".", width, initial_indent="  ",
                               subsequent_indent="      "))
            lines += [_fill(t + ".", width, initial_indent="  - ", subsequent_indent="      ") for _, t in sentences]
    return "\n".join(lines)
