"""Reports: the only place that builds DataFrames and draws figures (pandas/matplotlib, imported lazily).

One module per subject: ``records`` (record plots), ``pulses`` (pulse-fit figures), ``response``
(time-history figures and CSVs), ``tables`` (assessment tables and CSV reports), ``csv_text`` (a table's CSV
as pandas writes it, without pandas: the assessment CSV of the main job); the self-contained
HTML report (``--report``): ``html`` (the page and its shared sections), ``html_records`` (the records
and their provenance), ``html_pages`` (the reports of ``assess column``, ``assess fragility`` and
``simulate``), ``html_stack`` (the report of ``simulate --on``), ``html_deciding`` (the records that decide
each verdict, drawn), ``html_figures`` (its figures); ``stack`` (a body on a plinth: its history CSV and its
figure, drawn for ``simulate --on --plot`` and both reports).
"""
