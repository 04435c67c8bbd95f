"""Honest progress (issue 35): one line per part of the work, an ETA only where the steps measure the
time (never in a margin search), the clock moving while a batch runs, the parts the library announces
adding up, and one line when a slow step without progress begins (a first read through gmprocess,
a Dask cluster starting)."""

from __future__ import annotations

import io
import re
import sys
import time
import types

import numpy as np
import pytest

from rockcli import compiling
from rockcli import progress as library
from rockcli.assess import NEIGHBOURHOOD, MARGIN_GRID, parse_column_spec, parse_configurations, run_assessment
from rockcli.assess.excitations import Excitation
from rockcli.cli import progress as display
from rockcli.errors import RockcliInputError
from rockcli.pulses import make_pulse
from rockcli.io.units import G


class _Tty(io.StringIO):
    def isatty(self):
        return True


class _Clock:
    def __init__(self):
        self.t = 0.0

    def __call__(self):
        return self.t


def _screen(text: str) -> list[str]:
    """The lines a terminal shows after ``text`` (``\\r`` back to the line's start, ``ESC[K`` clears the rest)."""
    lines, cur, col = [], [], 0
    for tok in re.split(r"(\r|\n|\x1b\[K)", text):
        if tok == "\r":
            col = 0
        elif tok == "\n":
            lines.append("".join(cur))
            cur, col = [], 0
        elif tok == "\x1b[K":
            del cur[col:]
        else:
            for ch in tok:
                cur[col:col + 1] = [ch]
                col += 1
    return lines + ["".join(cur)]


@pytest.fixture
def no_compile(monkeypatch):
    monkeypatch.setattr(compiling, "compiling", lambda: False)


# --------------------------------------------------------------------------------------------------
# the lines
# --------------------------------------------------------------------------------------------------

#: The margin search of ``assess column bassae nemea`` (80 scenes) as it went on 2 loaded cores: (seconds,
#: share of its (scene, factor) pairs settled). A third was settled in the first 12 % of the time, 81 % by
#: 96 % of it: a rate of pairs promised 0:26 left at 0:12 when 1:33 were.
MAIN_JOB_SEARCH = [(3.5, 0.003), (12.7, 0.328), (25.6, 0.447), (37.1, 0.485), (49.7, 0.522), (60.3, 0.559),
                   (68.3, 0.596), (75.5, 0.630), (81.2, 0.664), (85.7, 0.695), (90.0, 0.724), (95.0, 0.753),
                   (98.6, 0.781), (101.5, 0.809), (103.0, 0.836), (104.1, 0.864), (105.1, 0.878), (105.3, 0.938),
                   (105.5, 0.964), (105.6, 0.985), (105.7, 1.0)]


def test_a_search_shows_its_time_and_never_an_eta(no_compile):
    clock, tty = _Clock(), _Tty()
    total = 29760
    with display.Progress(total, stream=tty, clock=clock, tick=None) as bar:
        bar.phase("margin search", total, known=False)
        done = 0
        for t, share in MAIN_JOB_SEARCH:
            clock.t = t
            bar(int(round(share * total)) - done)
            done = int(round(share * total))
            assert bar.eta() is None and "ETA" not in bar.line()
            assert bar.line().endswith(display.clock_text(t)) and f"{int(share * 100):3d}%" in bar.line()
    assert _screen(tty.getvalue())[-2].startswith("margin search  [" + "#" * display.Progress.BAR + "]  100%  1:46")


def test_a_known_part_measures_its_eta_after_the_wait(monkeypatch):
    """A compile, and the first update after it (whose steps took the wait's time), are not measured; the
    ETA waits for MIN_SECONDS, MIN_UPDATES and MIN_SHARE; a compile in the middle restarts it."""
    clock = _Clock()
    state = {"compiling": True}
    monkeypatch.setattr(compiling, "compiling", lambda: state["compiling"])
    with display.Progress(1000, "verdicts", unit="runs", stream=_Tty(), clock=clock, tick=None) as bar:
        clock.t = 5.0
        bar(1)  # during a compile
        assert bar.eta() is None
        state["compiling"] = False
        clock.t = 60.0  # the compile took a minute: it must not count
        bar(9)  # the rate clock starts after this update (pos 10)
        clock.t = 61.0
        bar(40)
        assert bar.eta() is None  # 1 s measured
        clock.t = 64.0
        bar(50)  # 90 steps in 4 s since the clock started, 2 updates
        assert bar.eta() == pytest.approx(4 / 90 * 900)
        assert "100/1000 runs" in bar.line() and bar.line().endswith(f", ETA {display.clock_text(40)}")
        clock.t = 74.0  # no update for 10 s: the ETA counts down
        assert bar.eta() == pytest.approx(4 / 90 * 900 - 10)
        clock.t = 120.0  # and once it has run out it is not shown (no "ETA 0:00" over work going on)
        assert bar.eta() is None and "ETA" not in bar.line()
        state["compiling"] = True  # a compile in the middle restarts the measurement
        bar(10)
        state["compiling"] = False
        clock.t = 121.0
        bar(10)
        assert bar.eta() is None
    few = display.Progress(10, stream=_Tty(), clock=clock, tick=None, eta=False)
    with few:
        for _ in range(5):
            clock.t += 10
            few(1)
            assert few.eta() is None


def test_parts_leave_their_lines_complete_and_an_error_clears_the_line(no_compile):
    clock, tty = _Clock(), _Tty()
    with display.Progress(500, stream=tty, clock=clock, tick=None) as bar:
        bar.phase("verdicts", 4, unit="runs")  # nothing done in the first (default) part: replaced, not kept
        clock.t = 2.0
        bar(4)
        bar.phase("margin search", 400, known=False)
        clock.t = 5.0
        bar(300)  # 100 pairs not needed (the last phase completes it)
        display._notice(tty, "rockcli: a notice")  # over the line, which is drawn again below it
        bar.phase("neighbourhood", 84, unit="runs")
        clock.t = 6.0
        bar(84)
    lines = _screen(tty.getvalue())
    assert [ln.split("  [")[0] for ln in lines] == ["verdicts", "rockcli: a notice", "margin search", "neighbourhood",
                                                    ""]
    assert lines[0].endswith("]  4/4 runs  0:02") and lines[2].endswith("]  100%  0:03")  # its own time
    assert lines[3].endswith("]  84/84 runs  0:01")

    tty = _Tty()
    with pytest.raises(KeyError):
        with display.Progress(10, stream=tty, clock=clock, tick=None) as bar:
            bar(3)
            raise KeyError("x")
    assert _screen(tty.getvalue()) == [""]  # the error's sentence will stand alone


def test_the_clock_moves_while_a_batch_runs(no_compile):
    tty = _Tty()
    with display.Progress(10, "margin search", eta=False, stream=tty, tick=0.02) as bar:
        time.sleep(0.3)
        assert bar.pos == 0
    assert tty.getvalue().count("\r") >= 5  # redrawn by the clock, without a step done


def test_a_line_never_wraps(no_compile, monkeypatch):
    monkeypatch.setattr(display.shutil, "get_terminal_size", lambda fallback=None: types.SimpleNamespace(columns=40))
    tty = _Tty()
    with display.Progress(10, "margin search on Dask (12 tasks)", unit="scenes", stream=tty, tick=None) as bar:
        bar(3)
    assert all(len(line) <= 39 for line in _screen(tty.getvalue()))


# --------------------------------------------------------------------------------------------------
# the parts the library announces
# --------------------------------------------------------------------------------------------------

class _Recorder:
    """A progress callable that wants the parts: [(name, steps, known, unit, steps told)]."""

    def __init__(self):
        self.parts = []

    def phase(self, name, steps, *, known, unit):
        self.parts.append([name, steps, known, unit, 0])

    def __call__(self, n):
        assert n > 0 and self.parts
        self.parts[-1][4] += n


def test_run_assessment_announces_its_parts_and_they_add_up():
    blocks = [parse_column_spec("a:R=0.8,alpha=12")]
    confs = parse_configurations(["none", "linear:Tb=2,xi=0.1"])
    xs = [Excitation(label=f"p{k}", kind="pulse", source="test", motion=make_pulse(shape, ap * G, tp))
          for k, (shape, ap, tp) in enumerate([("ricker-anti", 0.3, 0.8), ("ricker-sym", 0.15, 1.5)])]
    rec = _Recorder()
    run_assessment(blocks, xs, confs, neighbourhood=True, progress=rec)
    n, m = 4, MARGIN_GRID.size
    assert rec.parts == [["verdicts", n, True, "runs", n], ["margin search", n * (m - 1), False, None, n * (m - 1)],
                         ["neighbourhood", n * NEIGHBOURHOOD.size, True, "runs", n * NEIGHBOURHOOD.size]]
    plain = []
    run_assessment(blocks, xs[:1], confs[:1], margin=False, progress=plain.append)  # a plain callable: steps only
    assert sum(plain) == 1


# --------------------------------------------------------------------------------------------------
# waits without progress
# --------------------------------------------------------------------------------------------------

@pytest.fixture
def fresh_waits(monkeypatch):
    monkeypatch.setattr(display, "_watching_waits", False)
    before = list(library._listeners)
    yield
    library._listeners[:] = before


def test_a_wait_is_one_line_on_a_terminal_and_nothing_when_piped(fresh_waits):
    tty = _Tty()
    display.watch_waits(tty)
    display.watch_waits(tty)  # idempotent
    library.announce("starting a Dask LocalCluster on this machine ...")
    assert _screen(tty.getvalue()) == ["rockcli: starting a Dask LocalCluster on this machine ...", ""]
    display._watching_waits = False
    piped = io.StringIO()
    display.watch_waits(piped)
    library.announce("x")
    assert piped.getvalue() == ""

    def boom(_):
        raise OSError("stderr closed")

    unsubscribe = library.subscribe(boom)
    library.announce("y")  # a listener that fails does not stop the work
    unsubscribe()


def test_the_first_read_through_gmprocess_says_so_once(fresh_waits, monkeypatch, tmp_path):
    from rockcli.records import extra
    from rockcli.records.components import NotARecord

    def read_data(path):
        raise ValueError("not a format gmprocess knows")

    fake = types.ModuleType("gmprocess.io.read")
    fake.read_data = read_data
    for name in ("gmprocess", "gmprocess.io"):
        monkeypatch.setitem(sys.modules, name, sys.modules.get(name) or types.ModuleType(name))
    monkeypatch.setitem(sys.modules, "gmprocess.io.read", fake)
    monkeypatch.setattr(extra, "_loaded", False)
    said = []
    library.subscribe(said.append)
    path = tmp_path / "x.v2"
    path.write_text("junk\n")
    for _ in range(2):
        with pytest.raises(NotARecord):
            extra.read_with_extra(path, None)
    assert len(said) == 1 and "5-20 s" in said[0]
    assert said[0].startswith("x.v2: no built-in reader recognises it; trying gmprocess (the formats extra;")
    monkeypatch.setattr(extra, "_loaded", False)
    with pytest.raises(RockcliInputError, match="gmprocess cannot read either"):  # a format rockcli knows (USGS SMC)
        extra.read_with_extra(path, None, recognised="SMC")
    assert said[1].startswith("reading x.v2 with gmprocess (the formats extra;")


# --------------------------------------------------------------------------------------------------
# the minimum overturning search: its runs move the line long before a column is done
# --------------------------------------------------------------------------------------------------

def test_min_search_tells_its_runs_as_they_finish():
    """`spectrum min-overturning` counts columns, and a column is done only when its whole search ends (the
    line sat at 0/1488 columns for minutes): the search tells its runs as they finish (progress.runs), the first of
    them before any column is done, adding up to the runs it made; a plain callable still sees columns only."""
    import math

    from rockcli.spectra import Family, Isolation, search_min_overturning

    events = []

    class Seen:
        def __call__(self, n):
            events.append(("columns", n))

        def runs(self, n):
            events.append(("runs", n))

    fam = Family(math.radians(12.0), "ricker-sym", Isolation("none"))
    s = search_min_overturning([fam], [0, 0], [2.0, 4.0], step=0.2, tol=0.05, refine=0.0, progress=Seen())
    assert events and events[0][0] == "runs"
    assert sum(n for k, n in events if k == "runs") == s.runs > 0
    assert sum(n for k, n in events if k == "columns") == 2
    plain = []
    search_min_overturning([fam], [0, 0], [2.0, 4.0], step=0.2, tol=0.05, refine=0.0, progress=plain.append)
    assert sum(plain) == 2


def test_the_line_counts_the_runs_beside_the_steps(no_compile):
    tty, clock = _Tty(), _Clock()
    with display.Progress(1488, "search", eta=False, unit="columns", stream=tty, clock=clock, tick=None) as bar:
        assert "0/1488 columns " in bar.line() and "runs" not in bar.line()
        bar.runs(1200)
        bar.runs(34_010)
        bar(3)
        assert "3/1488 columns, 35,210 runs" in bar.line()
        bar.draw(force=True)  # (the clock thread's redraw)
        assert "3/1488 columns, 35,210 runs" in _screen(tty.getvalue())[-1]
