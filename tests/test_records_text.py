"""Plain-text records: layouts, round trips of written files (seeded property tests), bad input."""

from __future__ import annotations

import numpy as np
import pytest

from rockcli.errors import RockcliInputError
from rockcli.records import read_record
from rockcli.records.text import format_text, parse_comments, parse_text
from rockcli.io.units import G

SEEDS = range(12)


def _random_case(seed):
    rng = np.random.default_rng(seed)
    n = int(rng.integers(3, 400))
    ncols = int(rng.integers(1, 4))
    values = rng.normal(0, 10.0 ** rng.integers(-4, 3), (n, ncols))
    dt = float(rng.choice([0.001, 0.0024, 0.005, 0.01, 0.02, 0.05]))
    t0 = float(rng.choice([0.0, 0.02, 1.5]))
    delimiter = str(rng.choice([" ", "\t", ",", "  ", ";"]))
    return rng, values, dt, t0, delimiter


@pytest.mark.parametrize("seed", SEEDS)
def test_round_trip_with_time_column(tmp_path, seed):
    _, values, dt, t0, delimiter = _random_case(seed)
    path = tmp_path / "r.txt"
    path.write_text(format_text(values, dt=dt, t_start=t0, comments=[f"seed {seed}"], delimiter=delimiter))
    for col in range(values.shape[1]):
        rec = read_record(path, units="m/s^2", column=col + 2 if values.shape[1] > 1 else None)
        np.testing.assert_array_equal(rec.acc, values[:, col])  # exact: repr() round-trips floats
        assert rec.dt == pytest.approx(dt, rel=1e-9) and rec.t_start == t0
        assert rec.meta["time_column"] and rec.meta["dt_source"] == "time column"


@pytest.mark.parametrize("seed", SEEDS)
def test_round_trip_without_time_column(tmp_path, seed):
    _, values, dt, _, delimiter = _random_case(seed)
    path = tmp_path / "r.dat"
    path.write_text(format_text(values, delimiter=delimiter))
    col = values.shape[1]
    # gal: the values reach a few hundred, beyond the largest record peak read (100 g) were they in g
    rec = read_record(path, units="gal", dt=dt, column=col if col > 1 else None)
    np.testing.assert_array_equal(rec.acc, values[:, col - 1] * 0.01)
    assert rec.dt == dt and rec.t_start == 0.0 and not rec.meta["time_column"]


@pytest.mark.parametrize("seed", SEEDS)
def test_parse_text_matches_numpy_loadtxt(seed):
    _, values, dt, _, _ = _random_case(seed)
    text = format_text(values, dt=dt)
    table = np.loadtxt(text.splitlines())
    out = parse_text(text, "x", column=2 if values.shape[1] == 1 else values.shape[1] + 1)
    np.testing.assert_array_equal(out["values"], table.reshape(len(values), -1)[:, -1])


@pytest.mark.parametrize("line_end", ["\n", "\r\n", "\r"])
def test_comments_state_units_and_dt(tmp_path, line_end):
    """The erzikan.txt / sylmar.txt layout: %-comments state cm/sec^2 and dt."""
    text = ("%ERZIKAN 1992. First column consists of N-S component and" + line_end
            + "%second column consists of E-W component. Acc. in cm/sec^2 and dt=0.005 sec." + line_end
            + "  2.9638835e-001  1.4237498e-001" + line_end + " -6.4786996e+000 -3.0e+000" + line_end
            + "1.0\t2.0" + line_end)
    path = tmp_path / "e.txt"
    path.write_bytes(text.encode())
    rec = read_record(path, column=2)
    np.testing.assert_allclose(rec.acc, [1.4237498e-3, -3.0e-2, 2.0e-2], rtol=1e-15)
    assert rec.dt == 0.005 and rec.meta["units"] == "cm/sec^2" and rec.meta["units_source"] == "file"
    assert rec.meta["dt_source"] == "comment"


@pytest.mark.parametrize("comment,expected", [
    ("units: g", {"dt": None, "units": "g"}),
    ("Acceleration in m/s^2, time step 0.01 s", {"dt": 0.01, "units": "m/s^2"}),
    ("dt = 5 ms", {"dt": 0.005, "units": None}),
    ("Acc. in the N-S direction", {"dt": None, "units": None}),  # not a unit word: not a statement
])
def test_parse_comments(comment, expected):
    assert parse_comments([comment]) == expected


def test_column_names_header_line(tmp_path):
    path = tmp_path / "c.csv"
    path.write_text("time,acc_g\n0.0,0.1\n0.01,-0.2\n0.02,0.3\n0.03,0.0\n")
    rec = read_record(path, units="g")
    assert rec.meta["column_names"] == ["time", "acc_g"] and rec.dt == 0.01
    np.testing.assert_allclose(rec.acc / G, [0.1, -0.2, 0.3, 0.0])


# ---------------------------------------------------------------- bad input

def _write(tmp_path, text, name="bad.txt"):
    p = tmp_path / name
    p.write_text(text)
    return p


def test_single_column_needs_dt_and_units(tmp_path):
    path = _write(tmp_path, "0.1\n0.2\n-0.1\n")
    with pytest.raises(RockcliInputError, match=r"does not state its units; give them with --units"):
        read_record(path, dt=0.01)
    with pytest.raises(RockcliInputError, match=r"does not state its time step; give it with --dt"):
        read_record(path, units="g")


def test_multi_column_needs_column(tmp_path):
    path = _write(tmp_path, "0.1 0.3\n0.2 -0.1\n-0.1 0.2\n0.0 0.1\n")
    with pytest.raises(RockcliInputError, match=r"2 data columns; choose one with --record-column"):
        read_record(path, dt=0.01, units="g")
    with pytest.raises(RockcliInputError, match=r"column 3 does not exist \(the file has 2 columns\)"):
        read_record(path, dt=0.01, units="g", column=3)


def test_time_column_is_not_data(tmp_path):
    path = _write(tmp_path, "0 0.1\n0.01 0.2\n0.02 -0.1\n0.03 0.1\n")
    with pytest.raises(RockcliInputError, match=r"column 1 is the time column"):
        read_record(path, units="g", column=1)


def test_non_increasing_time_column(tmp_path):
    rows = [f"{0.01 * i:.2f} {np.sin(i):.4f}" for i in range(40)]
    rows[20] = f"0.18 {0.5:.4f}"  # goes back in time
    path = _write(tmp_path, "\n".join(rows) + "\n")
    with pytest.raises(RockcliInputError, match=r"line 21: the time column is not increasing"):
        read_record(path, units="g")


def test_non_uniform_time_column(tmp_path):
    t = np.cumsum(np.r_[0, np.full(30, 0.01)])
    t[15:] += 0.004
    path = _write(tmp_path, "".join(f"{a:.4f} {np.cos(a):.4f}\n" for a in t))
    with pytest.raises(RockcliInputError, match=r"line 16: the time column is not uniformly sampled"):
        read_record(path, units="g")


def test_dt_contradicting_time_column(tmp_path):
    path = _write(tmp_path, "0 0.1\n0.01 0.2\n0.02 -0.1\n0.03 0.1\n")
    with pytest.raises(RockcliInputError, match=r"states dt=0.01 s but dt=0.02 s was given"):
        read_record(path, units="g", dt=0.02)


@pytest.mark.parametrize("token", ["nan", "inf", "-inf", "NaN"])
def test_nonfinite_sample(tmp_path, token):
    path = _write(tmp_path, f"0.1\n0.2\n{token}\n0.3\n")
    with pytest.raises(RockcliInputError, match=r"line 3: value .* in column 1 is not a finite number"):
        read_record(path, units="g", dt=0.01)


def test_non_numeric_token(tmp_path):
    path = _write(tmp_path, "0.1\n0.2\n0.3x\n0.3\n")
    with pytest.raises(RockcliInputError, match=r"line 3: '0.3x' is not a number"):
        read_record(path, units="g", dt=0.01, format="TEXT")


def test_ragged_rows(tmp_path):
    path = _write(tmp_path, "0.1 0.2\n0.2 0.1\n0.3\n")
    with pytest.raises(RockcliInputError, match=r"line 3: 1 values where the first data row has 2"):
        read_record(path, units="g", dt=0.01, format="TEXT")


@pytest.mark.parametrize("dt", [0.0, -0.01, float("nan"), float("inf")])
def test_zero_or_negative_dt(tmp_path, dt):
    path = _write(tmp_path, "0.1\n0.2\n0.3\n")
    with pytest.raises(RockcliInputError, match=r"must be a positive finite number"):
        read_record(path, units="g", dt=dt)


def test_unknown_units_word(tmp_path):
    path = _write(tmp_path, "0.1\n0.2\n0.3\n")
    with pytest.raises(RockcliInputError, match=r"unknown acceleration unit 'furlongs/s\^2'"):
        read_record(path, units="furlongs/s^2", dt=0.01)


def test_comments_only(tmp_path):
    path = _write(tmp_path, "# nothing\n% here\n")
    with pytest.raises(RockcliInputError, match=r"holds no numbers"):
        read_record(path, units="g", dt=0.01, format="TEXT")
