"""A body on a free plinth in plain words: made in :mod:`rockcli.report.plinth_words` (only words), re-exported here
(``rockcli.assess.plinth_words`` keeps every name it had)."""

from rockcli.report.plinth_words import (PLINTH_QUESTION, _margin_words, _plinth_peak, _share,  # noqa: F401
                                         _topple_counts, peak_words, plinth_help_parts, plinth_name, plinth_summary,
                                         row_peak_words, run_sentence, survivors_peak_words)

__all__ = ["PLINTH_QUESTION", "peak_words", "plinth_help_parts", "plinth_name", "plinth_summary", "row_peak_words",
           "run_sentence", "survivors_peak_words"]
