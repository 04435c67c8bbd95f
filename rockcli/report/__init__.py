"""Reports: the only place that builds DataFrames and draws figures (pandas/matplotlib, imported lazily).

One module per subject: ``records`` (record plots), ``pulses`` (pulse-fit figures), ``response``
(time-history figures and CSVs), ``tables`` (assessment tables and CSV reports); the self-contained
HTML report (``--report``): ``html`` (the page and its shared sections), ``html_pages`` (the reports
of ``assess column``, ``assess fragility`` and ``simulate``), ``html_figures`` (its figures).
"""
