"""Reports: the only place that builds DataFrames and draws figures (pandas/matplotlib, imported lazily).

One module per subject: ``records`` (record plots), ``pulses`` (pulse-fit figures), ``response``
(time-history figures and CSVs), ``tables`` (assessment tables and CSV reports).
"""
