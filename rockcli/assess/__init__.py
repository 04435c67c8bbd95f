"""Assessment of free-standing columns: scenes, margin search, and fragility.

The library behind ``rockcli assess`` (no click, no pandas). Read it in this order:

:mod:`rockcli.assess.scenes`
    What is assessed: *columns* (presets or custom blocks), *configurations* (isolation specs)
    and *excitations* (catalogue records, files, folders; a file that cannot be read is kept
    with its ``error``). A scene is one column on one configuration under one excitation.
:mod:`rockcli.assess.excitations`
    The records of a run: catalogue ids, files, folders (files that are not records skipped), manifests,
    pairs of horizontal components projected onto the rocking plane.
:mod:`rockcli.assess.vertical`
    The vertical ground motion of each record (its own vertical component, or one vertical motion for
    all), carried by the record through every run; the margins scale the horizontal motion only.
:mod:`rockcli.assess.margin`
    The margin search: the smallest scale factor of a record that overturns a scene (the first
    overturning factor of 373 log-spaced factors 0.1..4 in steps just under 1 %, run upwards from
    the scene's lift-off floor, then a bisection below it), the neighbourhood share, and
    :func:`map_chunks`, the seam for running the search elsewhere.
:mod:`rockcli.assess.liftoff`
    The lift-off floor of a scene: the scale factor below which the block provably never leaves its
    base (rigid foundation: the peak ground acceleration; linear bearings: one exact run of the base).
:mod:`rockcli.assess.table`
    ``assess column``: every scene verdict-only, with its margin -> :class:`Assessment` rows.
:mod:`rockcli.assess.verdicts`
    The answer in plain words as ``assess column`` prints it (:func:`format_verdicts`): one sentence per body and
    configuration (``survives: it rocks to 39 % of its overturning angle; a record 1.60 times stronger would
    topple it``), in words that fit the body, with the stroke the isolation bearings must allow. The words are
    made in :mod:`rockcli.report.words` and :mod:`rockcli.report.verdicts` (the report never imports this
    package) and re-exported here.
:mod:`rockcli.assess.plinth_words`
    A body on a free plinth in words (:mod:`rockcli.report.plinth_words`, re-exported): how each block rocked
    (``nothing lifts: the statue stays put on its plinth and the plinth does not rock``), one run of
    ``simulate --on``, and "Does the plinth help?".
:mod:`rockcli.assess.drums`
    Columns of drums beside their monoliths (``assess column nemea-drums --friction MU``): the monoliths added,
    what the drums add to each row (where the column fails, which joint moves first, the openings, the residual
    offsets), drums against monolith record by record, and whether each answer is reliable.
:mod:`rockcli.assess.fragility`
    ``assess fragility``: each record's overturning capacity (smallest overturning scale x the
    record's intensity measure) and a lognormal fragility per column x configuration fitted by
    maximum likelihood with right-censoring, with a bootstrap confidence band.
:mod:`rockcli.assess.lognormal`
    The statistics of the fragility: the censored (Tobit) maximum-likelihood lognormal fit, its
    paired bootstrap over records, and the fragility function ``Phi(ln(x/theta)/beta)``.

Every public name is importable from ``rockcli.assess``.
"""

from rockcli.assess.fragility import IMS, Fragility, FragilityCurve, FragilityRow, intensity_measure, run_fragility
from rockcli.assess.lognormal import bootstrap_lognormal, fit_lognormal, fragility_probability
from rockcli.assess.margin import (MARGIN_GRID, MARGIN_RTOL, NEIGHBOURHOOD, find_overturn_scales, map_chunks,
                                   overturn_scales_chunked, overturn_shares, run_local)
from rockcli.assess.scenes import (DEFAULT_ISOLATION, EXCITATION_MODES, EXCITATION_PULSE, EXCITATION_RECORD,
                                   Configuration, Excitation, Unavailable, column_title, custom_column,
                                   parse_column_spec, parse_configurations, resolve_excitations, table_ii_entries)
from rockcli.assess.table import (ROW_FIELDS, Assessment, AssessmentRow, count_runs, history_runs, run_assessment,
                                  safe_name)
from rockcli.assess.verdicts import body_noun, configuration_sentence, format_verdicts, scene_sentence
from rockcli.assess.vertical import attach_verticals, vertical_labels

__all__ = ["DEFAULT_ISOLATION", "EXCITATION_MODES", "EXCITATION_PULSE", "EXCITATION_RECORD", "IMS", "MARGIN_GRID",
           "MARGIN_RTOL", "NEIGHBOURHOOD", "ROW_FIELDS", "Assessment", "AssessmentRow", "Configuration", "Excitation",
           "bootstrap_lognormal",
           "Fragility", "FragilityCurve", "FragilityRow", "Unavailable", "body_noun", "column_title",
           "configuration_sentence", "count_runs", "format_verdicts", "scene_sentence",
           "custom_column", "find_overturn_scales", "fit_lognormal", "fragility_probability", "history_runs",
           "intensity_measure", "map_chunks", "overturn_scales_chunked", "overturn_shares", "parse_column_spec",
           "parse_configurations", "resolve_excitations", "run_assessment", "run_fragility", "run_local",
           "safe_name", "table_ii_entries", "attach_verticals", "vertical_labels"]
