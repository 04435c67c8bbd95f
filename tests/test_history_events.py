"""Exact histories (issue 26 item 3): the event rows of a history (uplift, impact with both sides of
the impact map, peak, rest, overturn), ``simulate(..., history_dt=...)`` / ``simulate --history-dt``
rows on a uniform grid from the solver's dense output, the ``event`` column of the history CSV and
the ``events`` of ``--json``.

Checked against Housner's decay law of free rocking, against the stepwise rows of the same run,
against a run at a 1000x tighter tolerance, and the grid's ground acceleration against the motion
itself (the record's samples, the analytic pulse)."""

from __future__ import annotations

import csv
import json
import math

import numpy as np
import pytest
from click.testing import CliRunner

from rockcli.errors import RockcliInputError
from rockcli.models.impact import impact_ratio
from rockcli.models import Block, LinearIsolation, Rigid, SingleConcaveSliding
from rockcli.pulses import make_pulse
from rockcli.records import Record
from rockcli.report.response import history_columns, history_table, write_history_csv
from rockcli.solve import default_rtol, response, simulate
from rockcli.io.units import G

ALPHA = 0.2
BLOCK = Block(0.5 / math.sin(ALPHA), ALPHA)


def _synthetic_record(seed=7, n=400, dt=0.01, pga_g=0.35):
    """A smooth random record (filtered noise under a window), strong enough to rock the block."""
    rng = np.random.default_rng(seed)
    x = np.convolve(rng.standard_normal(n), np.hanning(15), mode="same")
    x *= np.sin(np.pi * np.arange(n) / (n - 1)) ** 2
    return Record(acc=x / np.max(np.abs(x)) * pga_g * G, dt=dt, name="synthetic")


def _events(h, name):
    return [e for e in h.events if e.event == name]


def _housner_next(alpha, eta, th):
    """Housner's decay law: cos(alpha - theta_{k+1}) = cos alpha + eta^2 [cos(alpha - theta_k) - cos alpha]."""
    return alpha - np.arccos(np.cos(alpha) + eta ** 2 * (np.cos(alpha - th) - np.cos(alpha)))


@pytest.mark.parametrize("restitution", [None, 0.9])
@pytest.mark.parametrize("history_dt", [None, 0.01])
def test_free_rocking_peak_events_follow_housners_decay_law(restitution, history_dt):
    res = simulate(BLOCK, Rigid(), None, theta0=0.6 * ALPHA, history=True, history_dt=history_dt, tail=6.0,
                   restitution=restitution)
    h = res.history
    peaks = np.abs([e.theta_rad for e in _events(h, "peak")])
    impacts = _events(h, "impact")
    assert peaks.size >= 4 and len(impacts) >= peaks.size - 1
    assert peaks[0] == 0.6 * ALPHA  # the release is the first peak
    eta = impact_ratio(ALPHA, 0.0, restitution)
    for e in impacts:  # the impact map, both sides, at theta = 0
        assert e.theta_rad == 0.0 and e.theta_dot_after == pytest.approx(eta * e.theta_dot_before, rel=1e-14)
    # one peak between two impacts, and the decay law from each to the next (measured 6.6e-9, 8.8e-9 relative)
    t_pk, t_imp = [e.t_s for e in _events(h, "peak")], [e.t_s for e in impacts]
    assert np.all(np.searchsorted(t_imp, t_pk) == np.arange(len(t_pk)))
    np.testing.assert_allclose(peaks[1:], _housner_next(ALPHA, eta, peaks[:-1]), rtol=1e-6, atol=0)
    # the peak events are the recorded peaks and the run's peak
    np.testing.assert_array_equal(np.abs(h.peak_theta), peaks)
    assert peaks.max() == pytest.approx(res.theta_max, rel=1e-14)


def test_impact_events_carry_both_velocities_and_the_rest():
    """A cascade of impacts down to rest after a pulse: every impact's after-velocity is eta times
    its before-velocity (the CSV's two rows), the last impact is followed by the rest."""
    e = make_pulse("sine", 0.25 * G, 0.8)
    res = simulate(BLOCK, Rigid(), e, history=True, tail=40.0, rest_tol=1e-3)
    h = res.history
    names = [ev.event for ev in h.events]
    assert names[0] == "uplift" and "rest" in names
    rest = _events(h, "rest")[0]
    last_impact = [ev for ev in h.events if ev.event == "impact" and ev.t_s == rest.t_s]
    assert len(last_impact) == 1 and rest.theta_dot_rad_s == 0.0 and rest.theta_rad == 0.0
    assert h.events[0].t_s == pytest.approx(res.t_uplift_s, abs=0)
    # in the CSV rows an impact is two rows at one time, the state before it and after it
    ev = h.row_event
    i = np.flatnonzero(ev == "impact")
    first = i[0]
    assert ev[first + 1] in ("impact", "rest") and h.rows[first, 0] == h.rows[first + 1, 0]
    assert h.rows[first + 1, 3] == pytest.approx(impact_ratio(ALPHA, 0.0, None) * h.rows[first, 3], rel=1e-14)


def test_overturn_event_ends_the_history():
    res = simulate(BLOCK, Rigid(), make_pulse("sine", 0.6 * G, 1.0), history_dt=0.005)
    assert res.overturned
    h = res.history
    assert h.events[-1].event == "overturn" and h.events[-1].t_s == res.t_overturn_s
    assert abs(h.events[-1].theta_rad) == pytest.approx(math.pi / 2, abs=1e-12)
    assert h.row_event[-1] == "overturn" and h.t[-1] <= res.t_overturn_s  # no grid row past it
    assert np.all(np.abs(h.theta) <= math.pi / 2 + 1e-12)


def _shared(a, b):
    common, i, j = np.intersect1d(a.t, b.t, return_indices=True)
    return common, i, j


SCENES = {"rigid": (Rigid(), 0.35, 400), "linear": (LinearIsolation(T_b=2.0, xi=0.1, gamma=0.3), 0.35, 800),
          "scss": (SingleConcaveSliding(T_b=1.5, mu=0.15), 0.6, 800)}  # each rocks and survives
#: |theta| between the grid at the default rtol and at rtol/1000, over alpha: the runs' global error
#: (measured 3.2e-8 rigid, 1.1e-8 linear, 3.6e-6 on the sliding base, whose stick-slip passes on more)
GLOBAL_ERROR = {"rigid": 1e-6, "linear": 1e-6, "scss": 5e-5}


@pytest.mark.parametrize("scene", SCENES)
def test_grid_rows_agree_with_the_steps_and_a_tighter_run(scene):
    foundation, pga_g, n = SCENES[scene]
    rec = _synthetic_record(pga_g=pga_g, n=n)
    kw = dict(history=True, tail=3.0)
    step = simulate(BLOCK, foundation, rec, **kw)
    grid = simulate(BLOCK, foundation, rec, history_dt=rec.dt, **kw)
    assert step.verdict == grid.verdict == "rocked" and step.theta_max == grid.theta_max  # the same run
    for r in (step, grid):  # one event per uplift, impact and rest the run counted, the same in both
        names = [e.event for e in r.history.events]
        assert (names.count("uplift"), names.count("impact"), names.count("rest")) == (
            r.n_uplifts, r.n_impacts_total, r.n_rests)
    assert step.history.events == grid.history.events
    g = grid.history
    n = int(math.floor(g.t[-1] / rec.dt + 1e-9)) + 1
    np.testing.assert_allclose(g.t, rec.dt * np.arange(n), rtol=0, atol=1e-12)  # the uniform grid
    # at shared times (the steps end at every sample): the same state to the solver's tolerance
    common, i, j = _shared(step.history, g)
    assert common.size >= 0.9 * rec.npts  # every sample of the record, and the tail's end
    rtol = default_rtol(foundation)
    s = step.history
    assert np.max(np.abs(s.theta[i] - g.theta[j])) <= 10 * rtol * ALPHA
    assert np.max(np.abs(s.theta_dot[i] - g.theta_dot[j])) <= 10 * rtol * BLOCK.p * ALPHA
    assert np.max(np.abs(s.u[i] - g.u[j])) <= 10 * rtol * max(1.0, np.max(np.abs(s.u)))
    if s.z is not None:
        assert np.max(np.abs(s.z[i] - g.z[j])) <= 1e-6
    # between the steps: against the same grid at a 1000x tighter tolerance
    tight = simulate(BLOCK, foundation, rec, history_dt=rec.dt, rtol=rtol / 1000, **kw).history
    m = min(g.t.size, tight.t.size)
    np.testing.assert_array_equal(g.t[:m], tight.t[:m])
    assert np.max(np.abs(g.theta[:m] - tight.theta[:m])) <= GLOBAL_ERROR[scene] * ALPHA
    # the ground acceleration of a grid row is the record itself (piecewise linear between samples)
    np.testing.assert_allclose(g.ag, np.interp(g.t, rec.times, rec.acc, right=0.0), rtol=0, atol=1e-12 * G)


def test_grid_peaks_are_never_above_the_peak_events():
    """Between two impacts theta on the grid stays within the exact peak of that flight."""
    rec = _synthetic_record(seed=11)
    for dt in (0.01, 0.0037):
        res = simulate(BLOCK, Rigid(), rec, history_dt=dt, tail=6.0)
        h = res.history
        peaks = _events(h, "peak")
        bounds = [ev.t_s for ev in h.events if ev.event in ("impact", "uplift", "rest")]
        assert len(peaks) >= 5
        for pk in peaks:
            k = np.searchsorted(bounds, pk.t_s)
            lo = bounds[k - 1] if k > 0 else -np.inf
            hi = bounds[k] if k < len(bounds) else np.inf
            inside = (h.t > lo) & (h.t < hi)
            assert np.all(np.abs(h.theta[inside]) <= abs(pk.theta_rad) + 1e-15)
        assert np.max(np.abs(h.theta)) <= res.theta_max + 1e-15


def test_grid_ground_acceleration_is_the_pulse_itself():
    p = make_pulse("ricker-sym", 0.4 * G, 0.6)
    res = simulate(BLOCK, Rigid(), p, history_dt=0.002, tail=1.0)
    h = res.history
    np.testing.assert_allclose(h.ag, p.acceleration(h.t), rtol=0, atol=1e-12 * G)
    assert np.allclose(np.diff(h.t), 0.002, rtol=0, atol=1e-12)


def test_default_csv_is_the_step_rows_with_the_event_column(tmp_path):
    """Without a grid the CSV's rows are the step rows, unchanged, those at events named in the
    column ``event``, which comes last (the peaks fall between steps: they are not rows here)."""
    f, pga_g, n = SCENES["scss"]
    rec = _synthetic_record(pga_g=pga_g, n=n)
    res = simulate(BLOCK, f, rec, history=True, tail=3.0)
    path = write_history_csv(res, BLOCK, tmp_path / "h.csv")
    with open(path) as fh:
        rows = list(csv.reader(fh))
    assert rows[0] == list(history_columns(res)) + ["event"]
    body = rows[1:]
    today = [[f"{v:.10g}" for v in row] for row in history_table(res, BLOCK)]
    assert [r[:-1] for r in body] == today
    events = [r[-1] for r in body]
    assert {"uplift", "impact"} <= set(events) <= {"", "uplift", "impact", "rest", "overturn"}
    assert events.count("impact") == 2 * sum(e.event == "impact" for e in res.history.events)
    assert res.history.peak_t.size > 0
    t = [float(r[0]) for r in body]
    assert t == sorted(t)


def test_cli_history_dt_csv_and_json_events(tmp_path):
    from rockcli.cli import main

    out = tmp_path / "free.csv"
    r = CliRunner().invoke(main, ["simulate", "--R", str(BLOCK.R), "--alpha", str(math.degrees(ALPHA)),
                                  "--theta0", str(0.6 * ALPHA), "--tail", "4", "--history-dt", "0.02",
                                  "--history", str(out), "--json"])
    assert r.exit_code == 0, r.output
    d = json.loads(r.output)
    events = d["events"]
    assert [e["event"] for e in events[:2]] == ["peak", "impact"]
    for e in events:
        assert {"event", "t_s", "theta_rad", "theta_dot_rad_s"} <= set(e)
        assert ("theta_dot_before" in e) == (e["event"] == "impact")
    with open(out) as fh:
        rows = list(csv.DictReader(fh))
    plain = [row for row in rows if row["event"] == ""]
    np.testing.assert_allclose([float(row["t_s"]) for row in plain], 0.02 * np.arange(len(plain)), atol=1e-12)
    peaks = [float(row["theta_rad"]) for row in rows if row["event"] == "peak"]
    assert peaks == pytest.approx([e["theta_rad"] for e in events if e["event"] == "peak"], rel=1e-9)


@pytest.mark.parametrize("bad", ["0", "-0.01", "nan", "inf", "x"])
def test_bad_history_dt_is_one_sentence(bad, tmp_path):
    from rockcli.cli import main

    r = CliRunner().invoke(main, ["simulate", "--R", "1", "--alpha", "12", "--theta0", "0.1", "--history-dt", bad,
                                  "--history", str(tmp_path / "h.csv")])
    assert r.exit_code == 2 and "--history-dt" in r.output and "Traceback" not in r.output
    assert not (tmp_path / "h.csv").exists()
    with pytest.raises(RockcliInputError, match="history_dt"):
        simulate(BLOCK, Rigid(), None, theta0=0.1, history_dt=float(bad) if bad != "x" else bad)
    with pytest.raises(RockcliInputError, match="rows"):
        simulate(BLOCK, Rigid(), None, theta0=0.1, history_dt=1e-9)


# --------------------------------------------------------------------------------------------------
# the History of the kernel's rows, against the rows read the plain way
# --------------------------------------------------------------------------------------------------
def _plain_history(k, H, fkind, grid_dt):
    """The fields of the :class:`History` of rows ``H``, read one obvious step at a time: each column copied,
    each event kind labelled in turn, the shown rows sorted by time (stably) whether in order or not, and the
    events read from the rows off the grid, an impact's far side from the next of them."""
    kinds = H[:, k.H_KIND]
    step_rows = (kinds != k.HK_PEAK) & (kinds != k.HK_GRID)
    plain, shown = ((kinds == k.HK_GRID, kinds != k.HK_STATE) if grid_dt else (step_rows, step_rows))
    shown_rows = H[shown][np.argsort(H[shown][:, k.H_T], kind="stable")]
    labels = np.full(len(shown_rows), "", dtype=object)
    for code, name in response.EVENT_KINDS:
        labels[shown_rows[:, k.H_KIND] == getattr(k, code)] = name
    P = H[plain]
    hyst = fkind in (k.FOUNDATION_BILINEAR, k.FOUNDATION_DCSS)
    off_grid = H[kinds != k.HK_GRID]
    names = {k.HK_UPLIFT: "uplift", k.HK_OVERTURN: "overturn", k.HK_PEAK: "peak", k.HK_REST: "rest"}
    events = []
    for i, row in enumerate(off_grid):
        kind = row[k.H_KIND]
        if kind in (k.HK_STATE, k.HK_IMPACT_AFTER):
            continue
        state = [float(row[c]) for c in (k.H_T, k.H_TH, k.H_THD, k.H_U, k.H_UD, k.H_AG)]
        if kind == k.HK_IMPACT:
            after = float(off_grid[min(i + 1, len(off_grid) - 1), k.H_THD])
            events.append(response.HistoryEvent("impact", *state, theta_dot_before=state[2], theta_dot_after=after))
        else:
            events.append(response.HistoryEvent(names[kind], *state))
    events.sort(key=lambda e: e.t_s)
    column = (lambda c: P[:, c].copy())
    return dict(t=column(k.H_T), ag=column(k.H_AG), theta=column(k.H_TH), theta_dot=column(k.H_THD),
                u=column(k.H_U), u_dot=column(k.H_UD), z=column(k.H_Z) if hyst else None,
                z2=column(k.H_Z2) if fkind == k.FOUNDATION_DCSS else None,
                bearing_force=column(k.H_FB) if fkind != k.FOUNDATION_RIGID else None,
                peak_t=H[kinds == k.HK_PEAK][:, k.H_T].copy(), peak_theta=H[kinds == k.HK_PEAK][:, k.H_TH].copy(),
                events=repr(tuple(events)), rows=shown_rows[:, :k.H_KIND].copy(), row_event=labels,
                grid_dt=grid_dt or None)


def _assert_same_history(k, H, fkind, grid_dt, where):
    got, want = response._history(k, H, fkind, grid_dt), _plain_history(k, H, fkind, grid_dt)
    for name, value in want.items():
        mine = getattr(got, name)
        if name == "events":
            assert repr(mine) == value, (where, name)
        elif isinstance(value, np.ndarray):
            assert mine.dtype == value.dtype and mine.shape == value.shape, (where, name)
            assert np.array_equal(mine, value, equal_nan=value.dtype != object), (where, name)
        else:
            assert mine == value, (where, name)


def test_the_history_is_the_rows_read_the_plain_way():
    """The History of a run (columns, peaks, events with both sides of each impact, the CSV rows and their event
    names) equals the kernel's rows read the plain way (:func:`_plain_history`): on the raw rows of 140 random
    runs (rigid and linear bases, sliding, lead-rubber and double concave bearings, at the steps and on a grid),
    and on 3,000 random row tables made to be awkward (grid rows between an impact's two sides, times out of
    order, ties, NaN, a single row, no row)."""
    from test_sliding import random_sliding_scenes
    from test_verdict_paths import random_scenes

    k = response._kernel()
    captured = []
    real = response._history

    def capture(kk, H, fkind, grid_dt):
        captured.append((H.copy(), fkind, grid_dt))
        return real(kk, H, fkind, grid_dt)

    jobs = random_scenes(100, 4411) + random_sliding_scenes(40, 4412)
    response._history = capture
    try:
        for i, job in enumerate(jobs):
            simulate(*job, history=True, **({"history_dt": job[2].T_p / 7.0} if i % 3 == 0 else {}))
    finally:
        response._history = real
    assert len(captured) == len(jobs)
    assert {fk for _, fk, _ in captured} >= {k.FOUNDATION_RIGID, k.FOUNDATION_BILINEAR, k.FOUNDATION_DCSS}
    for i, (H, fkind, grid_dt) in enumerate(captured):
        _assert_same_history(k, H, fkind, grid_dt, ("run", i))
    rng = np.random.default_rng(2026)
    codes = [k.HK_STATE, k.HK_PEAK, k.HK_GRID, k.HK_UPLIFT, k.HK_IMPACT, k.HK_IMPACT_AFTER, k.HK_REST, k.HK_OVERTURN]
    for i in range(3000):
        n = int(rng.integers(0, 40))
        H = rng.normal(size=(n, k.H_KIND + 1))
        H[:, k.H_KIND] = rng.choice(codes, size=n)
        t = np.cumsum(rng.choice([0.0, 0.01, 0.1], size=n))
        if i % 3 == 1:
            t = rng.permutation(t)  # out of order
        if i % 7 == 2 and n:
            t[rng.integers(0, n)] = np.nan
        H[:, k.H_T] = t
        fkind = int(rng.choice([k.FOUNDATION_RIGID, k.FOUNDATION_BILINEAR, k.FOUNDATION_DCSS, k.FOUNDATION_LINEAR]))
        _assert_same_history(k, H, fkind, 0.01 if i % 2 else None, ("table", i))
