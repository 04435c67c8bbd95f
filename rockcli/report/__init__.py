"""Reports: the only place that builds DataFrames and draws figures (pandas/matplotlib, imported lazily).

One module per subject: ``words``, ``verdicts``, ``plinth_words`` (the answer in plain words: one run, many runs,
a body on a plinth; :mod:`rockcli.assess.verdicts` prints them), ``records`` (record plots), ``pulses`` (pulse-fit
figures), ``response`` (time-history figures and CSVs), ``tables`` (assessment tables and CSV reports),
``csv_text`` (a table's CSV as pandas writes it, without pandas: the assessment CSV of the main job); the
self-contained HTML report (``--report``): ``html`` (the page and its shared sections), ``html_records`` (the
records and their provenance), ``html_pages`` (the reports of ``assess column``, ``assess fragility`` and
``simulate``), ``html_stack`` (the report of ``simulate --on``), ``html_deciding`` (the records that decide each
verdict, drawn), ``html_figures`` (its figures); ``stack`` (a body on a plinth: its history CSV and its figure,
drawn for ``simulate --on --plot`` and both reports).

The report never imports :mod:`rockcli.assess` (``tests/test_report_layers.py``): it is given the assessment's
results; what it needs and does not compute lives here or below both (:mod:`rockcli.models.spec`'s
:class:`~rockcli.models.spec.Configuration`, :mod:`rockcli.records.unavailable`).
"""
