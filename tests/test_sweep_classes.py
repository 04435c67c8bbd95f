"""The classes of the hostile sweep of issue 44 (item 4), one test each, each answered by a general rule:

* a spec key given twice in any spelling (case, ``_``, an alias) is refused wherever specs are parsed
  (:func:`rockcli.io.inputs.spec_items`), never "the last one wins";
* every user string that reaches a figure is drawn as written (:func:`rockcli.report.figures.plain`): a ``$`` in a
  name neither stops the drawing nor opens a formula; the Python spectra check ``plinths=``;
* a refusal says what is wrong: numbers it compares are never rounded to the same text, a pair ``A+B`` needs
  ``--azimuth`` and two files, ``--on`` runs on every bearing and its help says so, ``--component _242`` is no
  azimuth;
* a label that quotes a spec gives the same thing when it is run again;
* the Python API refuses wrong types and empty inputs in one sentence.

Cheap: pulses and self-describing pulse records written here; the CLI through CliRunner.
"""

from __future__ import annotations

import re
from pathlib import Path

import numpy as np
import pytest
from click.testing import CliRunner

from rockcli.cli import main
from rockcli.errors import RockcliInputError
from rockcli.io.units import G

from conftest import write_pulse_record
from test_bad_input import assert_one_sentence, snapshot

BODY = "statue:height=1.79,width=0.5"
PULSE = ["--pulse", "ricker-sym:ap=0.4,Tp=0.5"]


def run_cli(args):
    return CliRunner().invoke(main, [str(a) for a in args])


def refused(args, *words):
    """``rockcli ARGS`` exits 2 with one sentence holding ``words``, writing nothing."""
    here = Path.cwd()
    before = snapshot(here)
    assert_one_sentence(run_cli(args), words)
    assert snapshot(here) == before


@pytest.fixture
def work(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    return tmp_path


@pytest.fixture
def pair(work):
    """Two pulse records in the current folder (``a.txt``, ``b.txt``)."""
    write_pulse_record(work / "a.txt", 0.45, 0.7, "ricker-sym")
    write_pulse_record(work / "b.txt", -0.5, 0.5, "ricker-anti")
    return "a.txt", "b.txt"


# --------------------------------------------------------------------------------------------------
# silently wrong: two spellings of one key
# --------------------------------------------------------------------------------------------------
TWICE = {
    "plinth-alias": (["simulate", "--body", BODY, "--on", "plinth:height=1.0,width=0.6,mass_ratio=1,massratio=2",
                      *PULSE], ["--on 'plinth:height=1.0,width=0.6,mass_ratio=1,massratio=2'",
                                "mass_ratio (as massratio) is given twice"]),
    "plinth-camel": (["simulate", "--body", BODY, "--on", "plinth:height=1.0,width=0.6,MassRatio=2,mass_ratio=3",
                      *PULSE], ["MassRatio (as mass_ratio) is given twice"]),
    "assess-plinth-alias": (["assess", "column", BODY, "--on", "plinth:height=1,width=0.6,massratio=1,MASS_RATIO=2",
                             "--records", "a.txt", "--no-margin"], ["massratio (as MASS_RATIO) is given twice"]),
    "spectrum-plinth-alias": (["spectrum", "min-overturning", "--alpha", "14", "--on",
                               "plinth:height_ratio=0.5,heightratio=0.6,width_ratio=1.5"],
                              ["height_ratio (as heightratio) is given twice"]),
    "spectrum-isolation-underscore": (["spectrum", "min-overturning", "--alpha", "14", "--isolation",
                                       "linear:TbTp=2,Tb_Tp=3"], ["TbTp (as Tb_Tp) is given twice"]),
    "critical-plinth-alias": (["spectrum", "critical-size", "--alpha", "10", "--tbtp", "2", "--pulse",
                               "ricker-sym:Tp=0.6", "--on", "p:height_ratio=0.5,width_ratio=1.5,massratio=1,"
                                                            "mass_ratio=2"],
                              ["massratio (as mass_ratio) is given twice"]),
}


@pytest.mark.parametrize("case", TWICE.values(), ids=list(TWICE))
def test_a_key_given_twice_in_any_spelling_is_refused(pair, case):
    args, words = case
    refused(args, *words)


def test_spec_items_compare_keys_by_what_they_mean():
    from rockcli.io.inputs import spec_items

    names = {"mass_ratio": "mass_ratio", "massratio": "mass_ratio", "height": "height"}
    for text in ("mass_ratio=1,massratio=2", "MassRatio=2,mass_ratio=3", "mass_ratio=1,MASS_RATIO=1"):
        with pytest.raises(RockcliInputError, match="is given twice"):
            spec_items(text, "plinth", names)
        with pytest.raises(RockcliInputError, match="is given twice"):  # without the table: case and '_' alone
            spec_items(text, "plinth")
    assert [k for k, _, _ in spec_items("height=1,mass_ratio=2", "plinth", names)] == ["height", "mass_ratio"]


# --------------------------------------------------------------------------------------------------
# tracebacks: a '$' in a name; the spectra's plinths=
# --------------------------------------------------------------------------------------------------
@pytest.fixture()
def drawn(monkeypatch):
    """The figures saved while the test runs."""
    pytest.importorskip("matplotlib")
    from matplotlib.figure import Figure

    figs = []
    original = Figure.savefig

    def savefig(self, *args, **kwargs):
        out = original(self, *args, **kwargs)
        figs.append(self)
        return out

    monkeypatch.setattr(Figure, "savefig", savefig)
    return figs


def shown(text_artist) -> tuple[str, list[str]]:
    """What a text artist draws: its plain text (formulas as ``<f>``) and its formulas, as matplotlib reads it."""
    s, ismath = text_artist._preprocess_math(text_artist.get_text())
    if not ismath:
        return s, []
    parts = re.split(r"(?<!\\)\$", s)
    return "".join(p.replace(r"\$", "$") if i % 2 == 0 else "<f>" for i, p in enumerate(parts)), parts[1::2]


def assert_drawn_as_written(figs, *names):
    """Every figure of ``figs`` saved; no formula holds a user's text ('zz' is in the names only); each of
    ``names`` drawn literally somewhere."""
    from matplotlib.text import Text

    assert figs, "no figure was drawn"
    literal = []
    for fig in figs:
        for t in fig.findobj(Text):
            if t.get_text():
                text, formulas = shown(t)
                assert not [f for f in formulas if "zz" in f or f.strip() == "1"], t.get_text()
                literal.append(text)
    for name in names:
        assert any(name in text for text in literal), name


DOLLAR_BODY = "st$zz$:height=1.79,width=0.5"
DOLLAR_PLINTH = "Plinth $1 $zz$:height=1,width=0.6"


@pytest.mark.parametrize("out", ["p.png", "r.html"])
def test_a_dollar_in_a_name_is_drawn_as_written_on_a_plinth(work, drawn, out):
    """``--on 'Plinth $1:...' --plot`` (or ``--report``) stopped matplotlib's mathtext and wrote nothing."""
    res = run_cli(["simulate", "--body", DOLLAR_BODY, "--on", DOLLAR_PLINTH, *PULSE,
                   "--plot" if out.endswith(".png") else "--report", out])
    assert res.exit_code == 0, res.output
    assert (work / out).stat().st_size > 0
    assert_drawn_as_written(drawn, "st$zz$", "Plinth $1 $zz$")


def test_a_dollar_in_record_and_body_names_is_drawn_as_written_in_reports(work, drawn):
    """The report's margin figure named the records by their file names as tick labels: ``r$zz$`` drew an
    italic zz."""
    write_pulse_record(work / "r$zz$.txt", 0.45, 0.7, "ricker-sym")
    write_pulse_record(work / "s$1.txt", -0.5, 0.5, "ricker-anti")
    res = run_cli(["assess", "column", DOLLAR_BODY, "--records", "r$zz$.txt", "--records", "s$1.txt",
                   "--isolation", "none", "--report", "a.html"])
    assert res.exit_code == 0, res.output
    assert_drawn_as_written(drawn, "st$zz$", "r$zz$.txt")


def test_a_dollar_in_a_record_name_is_drawn_as_written_in_the_rocking_spectrum(work, drawn):
    write_pulse_record(work / "r$zz$.txt", 0.45, 0.7, "ricker-sym")
    res = run_cli(["spectrum", "rocking", "r$zz$.txt", "--alpha", "14", "--R", "0.5:2:2", "--plot", "s.png"])
    assert res.exit_code == 0, res.output
    assert_drawn_as_written(drawn, "r$zz$")


def test_wrapping_tells_a_dollar_sign_from_a_formula():
    """A title is wrapped at spaces outside formulas: an escaped dollar opens none (the words after it wrap)."""
    from rockcli.report.figures import glued_words, plain

    text = f"{plain('Plinth $1')} 1 m tall x 0.6 m wide, $R$ = 1 m"
    glued = glued_words(text)
    assert r"Plinth \$1 1 m tall x 0.6 m wide," in glued  # its spaces are still places to wrap
    assert "$R$\x00=\x001\x00m" in glued  # the formula's value and unit stay with it


def test_the_spectra_check_plinths():
    """``plinths=`` of the Python spectra: a Plinth in metres, a spec in metres, a number or an empty list is one
    sentence (it was an AttributeError from deep inside); a spec in proportion is read."""
    from rockcli.models import Plinth
    from rockcli.records.record import Record
    from rockcli.models import Rigid
    from rockcli.spectra import PlinthRatio, critical_sizes, min_overturning_curves, overturning_maps, rocking_spectrum

    record = Record(acc=np.array([0.0, 0.3 * G, -0.2 * G, 0.0]), dt=0.01, name="r")
    runs = {
        "min_overturning_curves": lambda pl: min_overturning_curves([14], ["ricker-sym"], ["none"], [2.0],
                                                                    plinths=pl),
        "critical_sizes": lambda pl: critical_sizes(["ricker-sym:Tp=0.6"], [10], ["linear:TbTp=2"], plinths=pl),
        "rocking_spectrum": lambda pl: rocking_spectrum(record, [14], [Rigid()], [1.0], plinths=pl),
        "overturning_maps": lambda pl: overturning_maps([14], ["ricker-sym"], ["none"], "2:4:2", "1:2:2", plinths=pl),
    }
    for name, run in runs.items():
        for bad, words in (([Plinth(1.0, 0.6)], "not a Plinth in metres"), (Plinth(1.0, 0.6), "not a Plinth"),
                           ("plinth:height=1,width=0.6", "not height= in metres"), ([None, 3], "got int 3"),
                           ([], "plinths is empty")):
            with pytest.raises(RockcliInputError, match=re.escape(words)):
                run(bad)
    from rockcli.spectra.arguments import as_plinths

    assert as_plinths("p:height_ratio=0.5,width_ratio=1.5") == [PlinthRatio(0.5, 1.5, None, "p")]
    assert as_plinths(None) == [None] and as_plinths([None, PlinthRatio(0.5, 1.5)]) == [None, PlinthRatio(0.5, 1.5)]


# --------------------------------------------------------------------------------------------------
# unclear refusals
# --------------------------------------------------------------------------------------------------
def test_a_refusal_never_rounds_the_numbers_it_compares_to_the_same_text(work):
    refused(["simulate", "--body", BODY, "--on", "plinth:height=1.0,width=0.49999", *PULSE],
            "the body (0.5 m wide) must be no wider than its plinth (0.49999 m wide)")
    from rockcli.models import Block, Plinth, Stack

    body = Block.from_dimensions(1.79, 0.5)
    for width in (body.width * (1 - 3e-12), 0.4999999999, 0.49999999999):
        with pytest.raises(RockcliInputError) as exc:
            Stack(body, Plinth(1.0, width))
        shown_body, shown_plinth = re.findall(r"\(([-+0-9.e]+) m wide\)", str(exc.value))
        assert shown_body != shown_plinth, str(exc.value)
        assert float(shown_plinth) < float(shown_body)


def test_a_pair_says_what_it_needs(pair):
    a, b = pair
    refused(["assess", "column", BODY, "--no-margin", "--records", f"{a}+{b}"],
            f"--records {a}+{b} is a pair of horizontal components", "needs --azimuth")
    for azimuth in ([], ["--azimuth", "30"]):
        refused(["assess", "column", BODY, "--no-margin", "--records", f"{a}+", *azimuth],
                "this pair is missing its second file")
        refused(["assess", "column", BODY, "--no-margin", "--records", f"+{b}", *azimuth],
                "this pair is missing its first file")
    for source in (f"{a}+{b}", f"{a}+"):
        refused(["simulate", "--body", BODY, "--record", source], "--record A --record-2 B", "--azimuth")
    refused(["simulate", "--body", BODY, "--record", "none.txt"], "none.txt: no such file")  # not a pair


def test_the_python_pair_without_azimuth_is_said_as_such(pair):
    from rockcli import resolve_excitations

    with pytest.raises(RockcliInputError, match="is a pair of horizontal components"):
        resolve_excitations(["a.txt+b.txt"])


def test_on_runs_on_sliding_bearings_and_its_help_says_so(work):
    for command in (["simulate"], ["assess", "column"], ["assess", "fragility"]):
        text = " ".join(run_cli([*command, "--help"]).output.split())
        assert "not yet on sliding" not in text
        assert "sliding and lead-rubber bearings" in text, command
    res = run_cli(["simulate", "--body", BODY, "--on", "plinth:height=1,width=0.6", *PULSE, "--isolation",
                   "scss:Tb=3,mu=0.05", "--json"])
    assert res.exit_code == 0, res.output


def test_a_component_is_read_as_the_user_wrote_it():
    """``--component _242`` picked the component at 242 deg (a leading '_' is skipped in names files give)."""
    from rockcli.records.components import orientation_meta, select_component
    from rockcli.records.record import Record

    comps = [Record(acc=np.zeros(4), dt=0.01, name=c, meta={"component": c, **orientation_meta(c, "test")})
             for c in ("N28W", "S62W")]
    assert select_component(comps, "242", "f").meta["component"] == "S62W"
    with pytest.raises(RockcliInputError, match=r"no component '_242'"):
        select_component(comps, "_242", "f")
    assert orientation_meta("_242", "file")["azimuth_deg"] == 242.0  # a file's own name keeps its reading


# --------------------------------------------------------------------------------------------------
# reproducibility: a label that quotes a spec gives the same thing again
# --------------------------------------------------------------------------------------------------
def test_the_plinth_label_of_the_csv_reruns_the_same_plinth(pair):
    import csv

    base = ["assess", "column", BODY, "--records", "a.txt", "--isolation", "none", "--no-margin", "-q"]
    res = run_cli([*base, "--on", "plinth:height=1.23456789,width=0.6", "--csv", "one.csv"])
    assert res.exit_code == 0, res.output
    rows = [r for r in csv.DictReader(open("one.csv")) if r["plinth"]]
    label = rows[0]["plinth"]
    res = run_cli([*base, "--on", label, "--csv", "two.csv"])
    assert res.exit_code == 0, res.output
    again = [r for r in csv.DictReader(open("two.csv")) if r["plinth"]]
    assert again == rows  # the same plinth, the same mass ratio, the same run: every column, the label too
    from rockcli.models import parse_plinth_spec

    assert parse_plinth_spec(label).height == 1.23456789


def test_spec_labels_read_back_as_the_same_numbers():
    from rockcli.models import LinearIsolation, parse_isolation_spec
    from rockcli.spectra.plinth import PlinthRatio, parse_plinth_ratio

    p = PlinthRatio(1 / 3, 1.2345678, 0.123456789, "p")
    assert parse_plinth_ratio(p.label) == p
    f = LinearIsolation(T_b=2.1234567, xi=0.0123456789, gamma=1 / 7)
    assert parse_isolation_spec(f.label) == f
    assert LinearIsolation(T_b=2.5).label == "linear:Tb=2.5,xi=0.1,gamma=0.01"  # short numbers stay short


# --------------------------------------------------------------------------------------------------
# the Python API: wrong types and empty inputs
# --------------------------------------------------------------------------------------------------
def _suite():
    from rockcli import parse_configurations, resolve_excitations
    from rockcli.assess import parse_column_spec

    xs, _ = resolve_excitations(["kobe-1995-takarazuka-000"], "pulse")
    return [parse_column_spec(BODY)], xs, parse_configurations(["none"])


@pytest.mark.parametrize("kwargs, words", [
    ({"margin": "no"}, "margin must be True or False, got str 'no'"),
    ({"margin": False, "neighbourhood": 5}, "neighbourhood must be True or False, got int 5"),
    ({"chunks": 0}, "chunks must be None (one chunk of everything) or a whole number of chunks >= 1, got 0"),
    ({"chunks": 1.5}, "got float 1.5"),
])
def test_run_assessment_refuses_wrong_types(kwargs, words):
    from rockcli import run_assessment

    columns, xs, confs = _suite()
    with pytest.raises(RockcliInputError, match=re.escape(words)):
        run_assessment(columns, xs, confs, **kwargs)


def test_an_empty_excitation_list_is_refused_as_the_cli_refuses_it():
    from rockcli import run_assessment, run_fragility

    columns, xs, confs = _suite()
    for run in (run_assessment, run_fragility):
        with pytest.raises(RockcliInputError, match="no record to run: excitations is empty"):
            run(columns, [], confs)
    with pytest.raises(RockcliInputError, match="chunk_size must be None"):
        run_fragility(columns, xs, confs, chunk_size=0)
    with pytest.raises(RockcliInputError, match="n_boot must be a whole number"):
        run_fragility(columns, xs, confs, n_boot=2.5)


def test_one_job_not_in_a_list_is_refused():
    """``simulate_many((block, foundation, pulse))`` gave three error rows; the docs promise an exception."""
    from rockcli import Block, Rigid, make_pulse, simulate_many
    from rockcli.models import Plinth, Stack
    from rockcli.solve import simulate_verdicts

    block = Block.from_dimensions(1.79, 0.5)
    job = (block, Rigid(), make_pulse("ricker-sym", 0.4 * G, 0.5))
    for run in (simulate_many, simulate_verdicts):
        with pytest.raises(RockcliInputError, match=r"got one job's items .*give the job in a list"):
            run(job)
    with pytest.raises(RockcliInputError, match="one job's items"):
        simulate_many((Stack(block, Plinth(1.0, 0.6)), Rigid(), job[2]))
    assert simulate_many([job])[0].verdict in ("rocked", "no_uplift", "overturned")


def test_a_bool_is_no_number_for_a_model():
    from rockcli.models import Block, LinearIsolation, Plinth

    for make, words in ((lambda: Plinth(True, 0.6), "plinth height must be a positive length in m, got True"),
                        (lambda: Plinth(1.0, 0.6, np.True_), "got True"),
                        (lambda: Block(True, 0.2), "block size R must be a positive length in m, got True"),
                        (lambda: LinearIsolation(2.5, xi=True), "got True")):
        with pytest.raises(RockcliInputError, match=re.escape(words)):
            make()
    assert Plinth("1", 0.6).height == 1.0  # a numeric string stays a number, as the specs give
