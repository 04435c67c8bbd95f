"""Every figure the commands draw: its titles and legends name the parameters of the run (in the
paper's symbols, with units), nothing drawn falls off the canvas, and motions are drawn from the
motion itself (no image comparisons).

The figures are caught as they are saved (``Figure.savefig`` wrapped), then measured: the tight
bounding box of everything drawn (titles, labels, tick labels, legends, notes) must lie inside the
figure, and the text of every visible text artist is searched for the parameters.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from click.testing import CliRunner

from rockcli.cli import main
from rockcli.models import DEFAULT_GAMMA, DEFAULT_XI
from rockcli.pulses import make_pulse
from rockcli.io.units import G

from conftest import write_pulse_record

pytest.importorskip("matplotlib")


@pytest.fixture()
def drawn(monkeypatch):
    """The figures saved while the test runs, in order."""
    from matplotlib.figure import Figure

    figs = []
    original = Figure.savefig

    def savefig(self, *args, **kwargs):
        out = original(self, *args, **kwargs)
        self.measured_outside = outside(self)  # measured before the plotter closes the figure
        figs.append(self)
        return out

    monkeypatch.setattr(Figure, "savefig", savefig)
    return figs


def texts(fig) -> str:
    """The text of every visible text artist of ``fig`` (titles, labels, legends, notes), one per line."""
    from matplotlib.text import Text

    return "\n".join(t.get_text() for t in fig.findobj(Text) if t.get_visible() and t.get_text()).replace("\u00a0", " ")


def outside(fig, tol_in: float = 0.02) -> list[str]:
    """What sticks out of the canvas of ``fig`` (drawn as saved): the sides of the tight bounding box of
    everything drawn that lie beyond the figure's edges, and the text artists that do."""
    from matplotlib.text import Text

    from matplotlib.backends.backend_agg import FigureCanvasAgg

    canvas = fig.canvas if hasattr(fig.canvas, "get_renderer") else FigureCanvasAgg(fig)
    renderer = canvas.get_renderer()
    fig.draw(renderer)
    w, h = fig.get_size_inches()
    bb = fig.get_tightbbox(renderer)
    out = [f"{side} {v:.3f} in" for side, v, bad in (("left", bb.x0, bb.x0 < -tol_in), ("bottom", bb.y0, bb.y0 < -tol_in),
                                                       ("right", bb.x1, bb.x1 > w + tol_in),
                                                       ("top", bb.y1, bb.y1 > h + tol_in)) if bad]
    box = fig.bbox.padded(tol_in * fig.dpi)
    for t in fig.texts + [a for ax in fig.axes for a in (ax.title, ax._left_title, ax.xaxis.label, ax.yaxis.label)]:
        if isinstance(t, Text) and t.get_visible() and t.get_text():
            e = t.get_window_extent(renderer)
            if e.x0 < box.x0 or e.y0 < box.y0 or e.x1 > box.x1 or e.y1 > box.y1:
                out.append(repr(t.get_text()[:60]))
    return out


def run(args):
    res = CliRunner().invoke(main, [str(a) for a in args])
    assert res.exit_code == 0, res.output
    return res


def check(fig, *needles):
    got = texts(fig).replace("\n", " ")  # titles are wrapped to the figure's width
    missing = [n for n in needles if n not in got]
    assert not missing, f"missing {missing} in:\n{got}"
    assert fig.measured_outside == []
    assert "mu1" not in got and "xi/gamma" not in got and "theta_max" not in got


# --------------------------------------------------------------------------------------------------
# the checker itself can fail
# --------------------------------------------------------------------------------------------------
def test_the_checker_sees_a_clipped_footnote():
    from rockcli.report.figures import footnote, new_figure, pyplot

    note = "lines: lognormal MLE; bands: 90 % bootstrap (1000 resamples); dots: records (Kaplan-Meier positions) " * 2
    fig = pyplot().figure(figsize=(4, 3))
    fig.add_subplot().plot([1, 2])
    fig.text(0.99, 0.01, note, ha="right", fontsize=7)  # the old fragility footnote: off the left edge
    assert outside(fig) and "left" in outside(fig)[0]
    fig = new_figure(4, 3)
    fig.add_subplot().plot([1, 2])
    footnote(fig, note)
    assert outside(fig) == []


def test_wrapping_never_breaks_a_formula():
    from rockcli.report.figures import new_figure, wrap_to

    fig = new_figure(2.0, 2.0)
    text = "minimum overturning $a_p / (g \\tan\\alpha)$ of a block " * 3
    for line in wrap_to(fig, text, 9).splitlines():
        assert line.count("$") % 2 == 0


def _wrapped_word_by_word(fig, text, fontsize, share=1.0):
    """The wrapping as it was first written: each line grows a word at a time while it fits (the reference of
    the bisection in wrap_to)."""
    from rockcli.report.figures import glued_words, text_width_pt, wrap_room

    room = wrap_room(fig, share)
    out = []
    for para in glued_words(text).split("\n"):
        if text_width_pt(para.replace("\0", " "), fontsize) <= room:
            out.append(para)
            continue
        line = ""
        for word in para.split(" "):
            trial = f"{line} {word}" if line else word
            if line and text_width_pt(trial.replace("\0", " "), fontsize) > room:
                out.append(line)
                line = word
            else:
                line = trial
        out.append(line)
    return "\n".join(out).replace("\0", " ")


def test_wrapping_by_bisection_is_the_word_by_word_wrapping():
    """60 random titles (words of 1-14 letters, a few formulas, values with units, double spaces, paragraphs,
    a word wider than the room) on figures 1.5-8 inches wide: the same lines as growing each line a word at a
    time."""
    from rockcli.report.figures import new_figure, wrap_to

    rng = np.random.default_rng(12)
    pieces = ["$T_b$ = 2 s", "$a_p/(g \\tan\\alpha)$", "$\\alpha$ = 14°", "R = 1.03 m", "", "Supercalifragilistic" * 2]
    for k in range(60):
        words = []
        for _ in range(int(rng.integers(1, 30))):
            if rng.random() < 0.12:
                words.append(pieces[int(rng.integers(len(pieces)))])
            else:
                words.append("".join(rng.choice(list("abcdefghijklmnopqrstuvwxyzWM"), int(rng.integers(1, 15)))))
            if rng.random() < 0.03:
                words.append("\n")
        text = " ".join(words).replace(" \n ", "\n")
        fig = new_figure(float(rng.uniform(1.5, 8.0)), 2.0)
        size, share = float(rng.choice([7.0, 9.0, 11.0])), float(rng.choice([1.0, 0.45]))
        assert wrap_to(fig, text, size, share) == _wrapped_word_by_word(fig, text, size, share), (k, text)
        plt = __import__("matplotlib.pyplot").pyplot
        plt.close(fig)


# --------------------------------------------------------------------------------------------------
# simulate --plot (Figures 1 and 12)
# --------------------------------------------------------------------------------------------------
def test_simulate_figure1_draws_the_pulse_itself_and_names_its_parameters(tmp_path, drawn):
    run(["simulate", "--height", 2, "--width", 0.5, "--pulse", "sine:ap=0.29,Tp=2", "--plot", tmp_path / "f.png"])
    fig = drawn[-1]
    check(fig, "$a_p$ = 0.29 g", "$T_p$ = 2 s", "rigid foundation", r"$\alpha$ = 14°", "$R$ = 1.03 m", "OVERTURNS")
    t, ag = fig.axes[0].lines[0].get_data()
    pulse = make_pulse("sine", 0.29 * G, 2.0)
    # the ground acceleration is the pulse on a fine grid, not a ramp between the solver's steps
    assert np.allclose(ag, pulse.acceleration(t) / G, atol=1e-12)
    assert np.diff(t).max() <= 2.0 / 200 and abs(ag.max() - 0.29) < 1e-4
    before = t < 0.5  # before the uplift (about 1 s) the line follows the sine, 0.29 sin(pi t)
    assert before.sum() > 50 and np.allclose(ag[before], 0.29 * np.sin(np.pi * t[before]), atol=1e-9)
    # the response from the dense history: points between the steps
    th_t, _ = fig.axes[1].lines[0].get_data()
    assert np.diff(th_t).max() <= 2.0 / 400 + 1e-12
    # the label "topples at 2.81 s" beside the red line, not over it, nor over the tilt curve, inside its panel
    tilt = fig.axes[1]
    label = next(a for a in tilt.texts if a.get_text().startswith("topples at"))
    from matplotlib.backends.backend_agg import FigureCanvasAgg

    renderer = (fig.canvas if hasattr(fig.canvas, "get_renderer") else FigureCanvasAgg(fig)).get_renderer()
    fig.draw(renderer)
    box = label.get_window_extent(renderer)
    line_x = next(ln for ln in tilt.lines if ln.get_color() == "tab:red").get_xdata()[0]
    x_px = tilt.transData.transform((line_x, 0.0))[0]
    assert box.x1 < x_px - 1 or box.x0 > x_px + 1, (box, x_px)
    frame = tilt.get_window_extent(renderer)
    assert frame.x0 <= box.x0 and box.x1 <= frame.x1 and frame.y0 <= box.y0 and box.y1 <= frame.y1
    curve = tilt.transData.transform(np.column_stack(tilt.lines[0].get_data()))
    assert not ((curve[:, 0] >= box.x0) & (curve[:, 0] <= box.x1) & (curve[:, 1] >= box.y0)
                & (curve[:, 1] <= box.y1)).any()


def test_simulate_draws_the_papers_two_panel_figures_in_one(tmp_path, drawn):
    """Figure 1 (two pulses) and Figure 12 (the ground and an isolated base) have two panels each: several --pulse
    or --isolation draw their scenes side by side, one column each, each named by its motion, foundation and
    verdict; one motion on several foundations shares its time axis."""
    res = run(["simulate", "--height", 2, "--width", 0.5, "--pulse", "sine:ap=0.5,Tp=0.5", "--pulse",
               "sine:ap=0.29,Tp=2", "--plot", tmp_path / "f1.png"])
    assert (tmp_path / "f1.png").exists()
    assert "scene 1 (column 1)" in res.output and "scene 2 (column 2)" in res.output
    fig = drawn[-1]
    check(fig, "$a_p$ = 0.5 g", "$T_p$ = 0.5 s", "$a_p$ = 0.29 g", "$T_p$ = 2 s", "survives", "OVERTURNS",
          "$R$ = 1.03 m")
    tops = [ax for ax in fig.axes if ax.get_title()]
    assert len(tops) == 2 and tops[0].get_position().x0 < tops[1].get_position().x0
    assert "0.5 g" in tops[0].get_title() and "survives" in tops[0].get_title()
    assert "0.29 g" in tops[1].get_title() and "OVERTURNS" in tops[1].get_title()
    for ax, (ap, tp) in zip(tops, ((0.5, 0.5), (0.29, 2.0))):  # each column's ground row is its own pulse
        t, ag = ax.lines[0].get_data()
        assert np.allclose(ag, make_pulse("sine", ap * G, tp).acceleration(t) / G, atol=1e-12)
    assert len(fig.axes) == 6

    run(["simulate", "--height", 2, "--width", 0.5, "--pulse", "ricker-sym:ap=0.3,Tp=1", "--isolation", "none",
         "--isolation", "linear:Tb=2", "--plot", tmp_path / "f12.png"])
    fig = drawn[-1]
    check(fig, "rigid foundation", "linear bearings, $T_b$ = 2 s", "the base does not move")
    assert len(fig.axes) == 8
    tops = [ax for ax in fig.axes if ax.get_title()]
    assert tops[0].get_xlim() == tops[1].get_xlim()  # one motion: one time axis


def test_simulate_isolated_record_figure(tmp_path, drawn):
    rec = write_pulse_record(tmp_path / "r.txt", 0.6, 0.5, "ricker-anti", dt=0.01, pad=1.0)
    run(["simulate", "--R", 0.8, "--alpha", 12, "--record", rec, "--isolation", "scss:Tb=2,mu=0.08",
         "--plot", tmp_path / "f.png"])
    fig = drawn[-1]
    check(fig, "$T_b$ = 2 s", r"$\mu$ = 0.08", r"$\gamma$ = 0.01", "$u_y$ = 0.25 mm", "PGA = 0.6 g", "r.txt",
          "base displacement $u$ [m]", "force-displacement loop")
    t, ag = fig.axes[0].lines[0].get_data()
    from rockcli.records import read_record

    r = read_record(rec)  # the record's own samples are drawn, and the ground at rest after it
    assert np.allclose(np.interp(r.times, t, ag), r.acc / G, rtol=0, atol=1e-12) and r.times[-1] < t[-1]
    assert np.all(ag[t > r.times[-1]] == 0.0)


def test_simulate_dcss_title_names_both_frictions(tmp_path, drawn):
    run(["simulate", "--R", 1, "--alpha", 16, "--pulse", "ricker-sym:ap=0.57,Tp=0.46",
         "--isolation", "dcss:Tb=0.927,mu1=0.03,mu2=0.07", "--tail", 1, "--plot", tmp_path / "f.png"])
    check(drawn[-1], r"$\mu_1$ = 0.03", r"$\mu_2$ = 0.07", r"$\mu_e$ = 0.05", "$T_b$ = 0.927 s",
          "symmetric Ricker pulse, $a_p$ = 0.57 g, $T_p$ = 0.46 s")


# --------------------------------------------------------------------------------------------------
# records show --plot, fit-pulse --plot
# --------------------------------------------------------------------------------------------------
def test_records_show_and_fit_pulse_figures(tmp_path, drawn):
    rec = write_pulse_record(tmp_path / "r.txt", 0.45, 0.7, "ricker-sym")
    run(["records", "show", rec, "--plot", tmp_path / "a.png"])
    check(drawn[-1], "r.txt", "PGA = 0.45 g", r"$\Delta t$ = 0.01 s", "velocity", "[m/s]", "[m]")
    run(["fit-pulse", rec, "--plot", tmp_path / "b.png"])
    check(drawn[-1], "$a_p$ = +0.450 g", "$T_p$ = 0.700 s", "symmetric Ricker", "PGA = 0.45 g")


# --------------------------------------------------------------------------------------------------
# assess column --plot and the HTML reports' figures
# --------------------------------------------------------------------------------------------------
def test_assess_column_figures_and_report(pulse_records, tmp_path, drawn):
    run(["assess", "column", "s:R=0.8,alpha=12", "--records", pulse_records / "anti.txt", "--isolation", "none",
         "--isolation", "linear:Tb=2", "--no-margin", "--plot", tmp_path / "f"])
    assert len(drawn) == 2
    check(drawn[0], "rigid foundation", "anti.txt, PGA = 0.5 g", r"$\alpha$ = 12°", "$R$ = 0.8 m")
    check(drawn[1], "linear bearings, $T_b$ = 2 s", r"$\xi$ = 0.1", r"$\gamma$ = 0.01")
    del drawn[:]
    run(["assess", "column", "s:R=0.8,alpha=12", "--records", pulse_records, "--isolation", "none",
         "--isolation", "linear:Tb=2", "--isolation", "linear:Tb=3", "--report", tmp_path / "r.html"])
    assert len(drawn) >= 4  # the critical record on each configuration, the margins, the share, the stroke
    for fig in drawn:
        check(fig, "s: $R$ = 0.8 m")
    assert any(r"$\xi$ = 0.1" in texts(f) and "$T_b$ = 3 s" in texts(f) for f in drawn)


def test_simulate_report_figure(tmp_path, drawn):
    run(["simulate", "--body", "nemea", "--pulse", "ricker-anti:ap=0.4,Tp=1.2", "--isolation", "linear:Tb=3",
         "--report", tmp_path / "r.html"])
    check(drawn[-1], "nemea", "$a_p$ = 0.4 g", "$T_p$ = 1.2 s", "$T_b$ = 3 s", r"$\xi$ = 0.1")


# --------------------------------------------------------------------------------------------------
# assess fragility --plot: one column (the plot that clipped its footnote) and two
# --------------------------------------------------------------------------------------------------
def test_fragility_figures_one_and_two_columns(pulse_records, tmp_path, drawn):
    for k, (name, a, T, shape) in enumerate((("c.txt", 0.25, 1.2, "ricker-sym"), ("d.txt", 0.40, 0.35, "ricker-anti"))):
        write_pulse_record(pulse_records / name, a, T, shape, pad=2.0)
    for cols in (["small:R=0.6,alpha=12"], ["small:R=0.6,alpha=12", "big:R=1.5,alpha=10"]):
        run(["assess", "fragility", *cols, "--records", pulse_records, "--isolation", "none", "--isolation",
             "linear:Tb=2", "--bootstrap", 50, "--plot", tmp_path / f"f{len(cols)}.png"])
        check(drawn[-1], "rigid foundation", "$T_b$ = 2 s", r"$\beta$ =", r"$\xi$ = 0.1", "Kaplan-Meier",
              "small: $R$ = 0.6 m", "PGA [g]")


# --------------------------------------------------------------------------------------------------
# spectrum overturning / min-overturning / critical-size --plot
# --------------------------------------------------------------------------------------------------
def test_spectrum_map_figures(tmp_path, drawn):
    for isos in (["linear:TbTp=2,xi=0.05"], ["none", "linear:TbTp=2,xi=0.05", "scss:TbTp=2,mu=0.05"]):
        run(["spectrum", "overturning", "--alpha", 16, "--wp-over-p", "1:6:4", "--ap", "1:4:4",
             *[a for i in isos for a in ("--isolation", i)], "--plot", tmp_path / f"m{len(isos)}.png"])
        check(drawn[-1], r"$\alpha$ = 16°", "symmetric Ricker", "$T_b/T_p$ = 2", r"$\omega_p / p$", "overturning")
    assert r"$\xi$ = 0.05" in texts(drawn[-1]) and r"$\mu$ = 0.05" in texts(drawn[-1])


def test_min_overturning_figure11_curves_are_told_apart(tmp_path, drawn):
    isos = ["none", "dcss:TbTp=2,mu1=0.03,mu2=0.07,r=1", "dcss:TbTp=2,mu1=0.03,mu2=0.06,r=2", "scss:TbTp=2,mu=0.05",
            "dcss:TbTp=3,mu1=0.03,mu2=0.07,r=1", "dcss:TbTp=3,mu1=0.03,mu2=0.06,r=2", "scss:TbTp=3,mu=0.05"]
    run(["spectrum", "min-overturning", "--alpha", 16, "--wp-over-p", "2:4:2", "--step", 0.2, "--refine", 0,
         *[a for i in isos for a in ("--isolation", i)], "--plot", tmp_path / "f11.png"])
    fig = drawn[-1]
    check(fig, r"$\mu_1$ = 0.03", r"$\mu_2$ = 0.06", r"$R_2/R_1$ = 2", r"$\mu_e$ = 0.05", "$T_b/T_p$ = 3",
          "rigid foundation", "minimum: ")
    lines = [ln for ln in fig.axes[0].lines if not ln.get_label().startswith("_")]
    styles = {(ln.get_color(), str(ln.get_linestyle()), ln.get_marker()) for ln in lines}
    assert len(lines) == 7 and len(styles) == 7  # every curve its own colour, line style and marker
    assert len({ln.get_marker() for ln in lines if ln.get_marker() not in (None, "None", "")}) == 6


def test_min_overturning_and_critical_size_panels(tmp_path, drawn):
    run(["spectrum", "min-overturning", "--alpha", "10,20", "--pulse", "ricker-sym", "--pulse", "ricker-anti",
         "--wp-over-p", "2:4:2", "--step", 0.2, "--refine", 0, "--plot", tmp_path / "f7.png"])
    check(drawn[-1], r"$\alpha$ = 10°", r"$\alpha$ = 20°", "antisymmetric Ricker", "$T_b/T_p$ = 4",
          rf"$\xi$ = {DEFAULT_XI:g}", rf"$\gamma$ = {DEFAULT_GAMMA:g}")  # the one set of defaults
    run(["spectrum", "critical-size", "--alpha", 10, "--pulse", "ricker-sym:Tp=0.6", "--tbtp", 2,
         "--wp-over-p", "1:8:8", "--step", 0.2, "--refine", 0, "--plot", tmp_path / "t1.png"])
    check(drawn[-1], "$R$ = ", "m ($T_p$ = 0.6 s, $T_b/T_p$ = 2)", rf"$\xi$ = {DEFAULT_XI:g}")


# --------------------------------------------------------------------------------------------------
# bench work-precision --plot
# --------------------------------------------------------------------------------------------------
def test_work_precision_figure(tmp_path, drawn):
    run(["bench", "work-precision", "--scene", "rigid-sine-overturn", "--kernel-rtol", "1e-5", "--methods", "none",
         "--no-check", "--plot", tmp_path / "wp.png"])
    check(drawn[-1], "rigid-sine-overturn", "$a_p$ = 0.29 g", "$T_p$ = 2 s", "rigid foundation",
          "error in $t_{overturn}$ [s]")


def test_motion_text_of_a_scaled_pulse_and_a_record():
    from rockcli.records.record import Record
    from rockcli.report.figures import motion_text

    assert motion_text(make_pulse("ricker-anti", 0.3 * G, 0.9).scaled(2.0)) == \
        "antisymmetric Ricker pulse, $a_p$ = 0.6 g, $T_p$ = 0.9 s"
    rec = Record(acc=np.array([0.0, -0.2 * G, 0.1 * G]), dt=0.01, name="x$y")
    assert motion_text(rec) == r"record x\$y, PGA = 0.2 g"
    assert math.isclose(rec.scaled(3.0).pga_g, 0.6) and "PGA = 0.6 g" in motion_text(rec.scaled(3.0))
