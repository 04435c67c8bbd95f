"""The assessment CSV written without pandas is byte for byte what pandas writes (issue 33).

:func:`rockcli.report.csv_text.csv_text` against ``DataFrame.to_csv(index=False, float_format="%.6g",
lineterminator="\\n")`` on 250 random tables (every kind of column it formats: floats with NaN, infinities,
-0.0, tiny and huge values; ints with and without missing values; strings with commas, quotes, line breaks,
empty and non-ASCII; bools with and without missing values; all missing; the nullable casts), and
:func:`rockcli.report.tables.write_assessment_csv` against the pandas table of the same assessment, on real rows
with random values in every field and every optional column (azimuth, plinth, check, restitution).
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pandas as pd
import pytest

from rockcli.report.csv_text import BOOLEAN, INT64, csv_text

_FLOATS = [0.0, -0.0, 1.0, -2.5, 1e-300, 5e-324, 1e300, 123456.5, 1234567.0, 0.1, 2.0 / 3.0, math.nan, math.inf,
           -math.inf, 1e-5, 999999.5]
_STRINGS = ["", "a", "survives", "x, y", 'say "no"', "two\nlines", "cr\rhere", "naïve", " lead", "trail ", "#"]


def _pandas(columns, casts):
    df = pd.DataFrame({k: v for k, v in columns.items()}, columns=list(columns))
    for k, dtype in casts.items():
        if k in df:
            df[k] = df[k].astype(dtype)
    return df.to_csv(index=False, float_format="%.6g", lineterminator="\n")


def _column(rng, kind, n):
    def some(values, missing=0.0):
        return [None if rng.random() < missing else values[rng.integers(len(values))] for _ in range(n)]

    if kind == "float":
        return [float(v) if v is not None else None for v in some(_FLOATS + list(rng.normal(0, 1e3, 5)), 0.2)]
    if kind == "float_np":
        return [np.float64(v) for v in some(_FLOATS)]
    if kind == "int":
        return [int(v) for v in rng.integers(-10**7, 10**7, n)]
    if kind == "int_missing":
        return some([0, 3, 17, 123456, 1234567, -5], 0.3)
    if kind == "int_float":
        return some([0, 3, 1234567, 0.5, math.nan, 2.25e-7])
    if kind == "str":
        return some(_STRINGS, 0.2)
    if kind == "bool":
        return some([True, False])
    if kind == "bool_missing":
        return some([True, False], 0.3)
    if kind == "none":
        return [None] * n
    if kind == BOOLEAN:
        return some([True, False, np.bool_(True)], 0.3)
    if kind == INT64:
        return some([0, 7, 1234567, np.int64(42)], 0.3)
    raise AssertionError(kind)


KINDS = ["float", "float_np", "int", "int_missing", "int_float", "str", "bool", "bool_missing", "none", BOOLEAN, INT64]


def test_random_tables_equal_pandas_byte_for_byte():
    rng = np.random.default_rng(33)
    for table in range(250):
        n = int(rng.integers(1, 12))
        kinds = [KINDS[i] for i in rng.integers(len(KINDS), size=int(rng.integers(1, 8)))]
        columns = {f"c{j}_{kind}": _column(rng, kind, n) for j, kind in enumerate(kinds)}
        casts = {name: kind for name, kind in zip(columns, kinds) if kind in (BOOLEAN, INT64)}
        got = csv_text(columns, casts)
        assert got is not None, kinds
        assert got == _pandas(columns, casts), (table, kinds)


@pytest.mark.parametrize("column", [[1.0, "a"], [True, 1.0], [True, "a"], [1, math.nan, "x"], [[1], [2]]])
def test_mixed_columns_are_left_to_pandas(column):
    assert csv_text({"a": column}) is None


def test_a_cast_column_with_another_kind_is_left_to_pandas():
    assert csv_text({"a": [1.5, None]}, {"a": INT64}) is None
    assert csv_text({"a": [1, None]}, {"a": BOOLEAN}) is None


def _rows(rng, n):
    from rockcli.assess.table import AssessmentRow

    rows = []
    for _ in range(n):
        values = {}
        for f in dataclasses.fields(AssessmentRow):
            t = str(f.type)
            if t == "str":
                values[f.name] = _STRINGS[rng.integers(len(_STRINGS))]
            elif t == "float":
                values[f.name] = _FLOATS[rng.integers(len(_FLOATS))]
            elif t == "bool | None":
                values[f.name] = [True, False, None][rng.integers(3)]
            elif t == "int | None":
                values[f.name] = [None, 0, 12, 1234567][rng.integers(4)]
            else:
                raise AssertionError((f.name, t))
        rows.append(AssessmentRow(**values))
    return rows


def test_assessment_csv_equals_the_pandas_table(tmp_path, monkeypatch):
    """Random values in every field of real rows, with and without the optional columns."""
    from rockcli.assess.table import Assessment, ToleranceCheck
    from rockcli.report.tables import assessment_table, write_assessment_csv

    rng = np.random.default_rng(1980)
    for case in range(40):
        rows = _rows(rng, int(rng.integers(1, 9)))
        if case % 2:  # no --azimuth, no --on: those columns left out
            for r in rows:
                r.azimuth_deg, r.azimuths_run, r.plinth = math.nan, None, ""
        solver = {"restitution": 0.7} if case % 3 == 0 else {}
        a = Assessment([], [], [], rows, solver=solver)
        check = None
        if case % 4 == 1:
            per_row = [(r, ["rocked", "overturned"][rng.integers(2)], _FLOATS[rng.integers(len(_FLOATS))],
                        ("rocked", "no_uplift"), _FLOATS[rng.integers(len(_FLOATS))]) for r in rows[::2]]
            check = ToleranceCheck(1e-10, 1e-8, len(per_row), [], 0.0, per_row=per_row)
        with monkeypatch.context() as m:  # written without pandas: its table is not asked for
            m.setattr("rockcli.report.tables.assessment_table", None)
            path = write_assessment_csv(a, tmp_path / f"a{case}.csv", check=check)
        want = assessment_table(a, check).to_csv(index=False, float_format="%.6g", lineterminator="\n")
        assert path.read_bytes() == want.encode(), case
