"""The answer in plain words (rockcli.assess.verdicts) and the self-contained HTML report (--report).

The report is parsed with the standard library's html.parser: every section is there, in order; the
record's SHA-256 is that of its file; the answer on the first screen says what the CSV says; and no
resource is external (every image a data: URI, every link an in-page anchor, no script, no @import,
no url()).
"""

from __future__ import annotations

import base64
import hashlib
import math
import re
from html.parser import HTMLParser

import pytest
from click.testing import CliRunner
from conftest import write_pulse_record

from rockcli.assess import AssessmentRow
from rockcli.assess.verdicts import (SURVIVES, TOPPLES, UNDECIDED, body_noun, configuration_sentence, outcome,
                                     scene_sentence)
from rockcli.cli import main
from rockcli.models import Block, column
from rockcli.report.html import SECTIONS
from rockcli.report.tables import read_assessment_csv


# --------------------------------------------------------------------------------------------------
# plain words
# --------------------------------------------------------------------------------------------------

def _row(**kw) -> AssessmentRow:
    base = dict(column="statue", R_m=0.93, alpha_deg=15.5, height_m=1.79, width_m=0.5, record="rec",
                excitation="record", source="", pga_g=0.5, a_p_g=math.nan, T_p_s=math.nan, isolation="none",
                configuration="none", Tb_s=math.nan, xi=math.nan, mu=math.nan, gamma=0.0, verdict="rocked",
                overturned=False, proven=True)
    base.update(kw)
    return AssessmentRow(**base)


def test_body_noun_fits_the_body():
    assert body_noun(column("bassae")) == "the column"
    assert body_noun(Block.from_degrees(0.93, 15.5, "statue")) == "the statue"
    assert body_noun(Block.from_degrees(0.93, 15.5, "marble_vase")) == "the marble vase"
    for unnamed in ("custom", "R0.93m-alpha15.5deg", "1.8x0.5m"):
        assert body_noun(Block.from_degrees(0.93, 15.5, unnamed)) == "the block"


@pytest.mark.parametrize("peak, scale", [(0.39, 1.6), (0.713, 2.345), (0.05, 1.04)])
def test_survivor_sentence_states_peak_and_margin(peak, scale):
    s = scene_sentence(_row(theta_max_over_alpha=peak, overturn_scale=scale, overturn_scale_survives=scale / 1.01))
    assert s.startswith("survives: it rocks to ")
    assert f"{100 * peak:.0f} % of its overturning angle" in s
    assert f"a record {scale:.2f} times stronger would topple it" in s


@pytest.mark.parametrize("peak, past", [(0.994, False), (0.996, True), (1.03, True), (1.8, True)])
def test_a_survivor_past_its_overturning_angle_is_said_to_have_been_brought_back(peak, past):
    """A block that rocked past its overturning angle (alpha: where it falls if all stands still) and survived: the
    sentence says why that is no contradiction, from where the percentage shows 100 % on; a body on its plinth too."""
    from rockcli.assess.plinth_words import peak_words
    from rockcli.assess.verdicts import PAST_WORDS

    s = scene_sentence(_row(theta_max_over_alpha=peak, overturn_scale=1.2, overturn_scale_survives=1.19))
    assert f"{100 * peak:.0f} % of its overturning angle" in s
    assert (PAST_WORDS in s) == past and ("brought it back" in s) == past
    w = peak_words(peak, 0.42, body="the statue")
    assert w.count("brought it back") == past and f"{100 * peak:.0f} % of its overturning angle" in w
    assert peak_words(0.42, peak, body="the statue").count("brought it back") == past


@pytest.mark.parametrize("width", range(30, 61))
def test_the_printout_never_breaks_a_number_from_its_unit(width):
    """The plain-words lines are wrapped at spaces, but never between a number and its unit (``62 %``)."""
    from rockcli.assess.verdicts import _fill

    text = ("the statue rocks on its plinth to at most 62 % of its overturning angle; the base moves up to 0.34 m; "
            "it falls after 6.8 s; it lifts off at 0.28 g; 3 stones, 5 mm and 7 sec stay as written; ") * 2
    out = _fill(text, width, initial_indent="  ", subsequent_indent="    ")
    assert out.split() == text.split()
    assert all(len(line) <= width for line in out.splitlines())
    for line in out.splitlines():
        assert not re.match(r"\s*(%|m|s|g)(\W|$)", line), line


def test_topples_sentence_states_the_fraction_of_the_record():
    s = scene_sentence(_row(verdict="overturned", overturned=True, theta_max_over_alpha=math.pi / 2 / 0.27,
                            t_overturn_s=6.76, overturn_scale=0.73, overturn_scale_survives=0.72))
    assert s.startswith("topples: already at 0.73 times this record") and "after 6.8 s" in s
    no_margin = scene_sentence(_row(verdict="overturned", overturned=True, t_overturn_s=3.24))
    assert no_margin == "topples: as recorded, it falls after 3.2 s"


def test_safe_island_no_uplift_undecided_and_stroke():
    island = scene_sentence(_row(theta_max_over_alpha=0.6, overturn_scale=0.8, overturn_scale_survives=0.79))
    assert island.startswith("survives") and "weaker record, 0.80 times this one, topples it" in island
    none = scene_sentence(_row(verdict="no_uplift", theta_max_over_alpha=0.0, margin_note="no overturning up to 4x"))
    assert "does not even lift off" in none and "not even a record 4 times stronger" in none
    row = _row(proven=False, theta_max_over_alpha=0.55)
    assert outcome(row) == UNDECIDED and scene_sentence(row).startswith("undecided") and "55 %" in scene_sentence(row)
    iso = _row(configuration="Tb=2.5s", theta_max_over_alpha=0.2, base_disp_max_m=0.3369)
    assert "the base moves up to 0.34 m" in scene_sentence(iso, isolated=True)
    assert "base moves" not in scene_sentence(iso, isolated=False)
    # a toppled run's displacement is no stroke to design for: said as such
    fell = _row(configuration="Tb=2.5s", verdict="overturned", overturned=True, t_overturn_s=6.6, base_disp_max_m=0.524)
    words = scene_sentence(fell, isolated=True)
    assert "the base had moved up to 0.52 m when it toppled (not a stroke to design for)" in words
    assert "the stroke the bearings must allow" not in words


def test_configuration_sentence_over_several_records():
    rows = [_row(record="a", theta_max_over_alpha=0.3, overturn_scale=2.0, base_disp_max_m=0.2),
            _row(record="b", verdict="overturned", overturned=True, overturn_scale=0.7, base_disp_max_m=0.45),
            _row(record="c", theta_max_over_alpha=0.5, overturn_scale=1.3, base_disp_max_m=0.31),
            _row(record="d", verdict="overturned", overturned=True, overturn_scale=0.5, base_disp_max_m=0.1)]
    s = configuration_sentence(rows, isolated=True)
    # the records that topple it, smallest factor first; the closest call among the survivors; the largest stroke
    # where it survives (b, in which it toppled, moved the base 0.45 m: no stroke to design for, left out)
    assert s.startswith("topples under 2 of 4 records (d already at 0.50 times, b already at 0.70 times)")
    assert "the closest call is c: 1.30 times stronger" in s
    assert "where it survives, the base moves up to 0.31 m (c;" in s
    assert "0.45" not in s
    assert "up to 0.31 m (c;" in configuration_sentence([rows[0], rows[2]], isolated=True)
    assert "where it survives" not in configuration_sentence([rows[0], rows[2]], isolated=True)
    assert "base moves" not in configuration_sentence([rows[1], rows[3]], isolated=True)  # it survives none
    survivors = configuration_sentence([rows[0], rows[2]])
    assert survivors.startswith("survives both records") and "50 % of its overturning angle (c)" in survivors


def _in_short(ground, bearings) -> str:
    """``isolation_summary`` of the statue with ``ground`` and ``bearings`` rows (the same records, in order)."""
    from types import SimpleNamespace as NS

    from rockcli.assess.verdicts import isolation_summary
    from rockcli.models import parse_isolation_spec

    statue = Block.from_dimensions(1.79, 0.5, "statue")
    confs = [NS(header="none", foundation=parse_isolation_spec("none"), isolated=False),
             NS(header="Tb=2.5s", foundation=parse_isolation_spec("linear:Tb=2.5"), isolated=True)]
    table = {(r.record, "none"): r for r in ground} | {(r.record, "Tb=2.5s"): r for r in bearings}
    a = NS(columns=[statue], excitations=[NS(label=r.record, motion=object()) for r in ground],
           configurations=confs, row=lambda c, x, h: table[(x, h)])
    return re.sub(r"\s+", " ", isolation_summary(a, statue))


def _iso(**kw) -> AssessmentRow:
    return _row(configuration="Tb=2.5s", isolation="linear:Tb=2.5", base_disp_max_m=0.34, **kw)


def test_in_short_compares_margins_where_the_verdicts_agree():
    """Issue 44: isolation that turns a survival by the luck of the timing (x0.61: a weaker record topples it) into
    no uplift with a margin of x1.21 did "change no verdict" / "survive too": the same verdicts both ways are now
    compared by their toppling factors, record by record, and a survival by luck is named."""
    luck = _row(record="kobe", theta_max_over_alpha=1.03, overturn_scale=0.61)
    margin = _iso(record="kobe", verdict="no_uplift", theta_max_over_alpha=0.0, overturn_scale=1.21)
    one = _in_short([luck], [margin])
    assert "it survives on isolation Tb=2.5s too, provided the bearings can move 0.34 m" in one
    assert ("by the margin isolation Tb=2.5s makes it better: on the ground it survives only by the luck of the "
            "timing (a weaker record, 0.61 times this one, topples it); on the bearings a record 1.21 times stronger "
            "would topple it") in one
    # the reverse, and both toppling: the margins say which way
    assert "by the margin isolation Tb=2.5s makes it worse" in _in_short(
        [_row(record="a", theta_max_over_alpha=0.2, overturn_scale=1.5)],
        [_iso(record="a", theta_max_over_alpha=0.3, overturn_scale=0.9)])
    fell = _in_short([_row(record="a", verdict="overturned", overturned=True, overturn_scale=0.5)],
                     [_iso(record="a", verdict="overturned", overturned=True, overturn_scale=0.8)])
    assert ("does not save it; by the margin isolation Tb=2.5s makes it better: on the ground it topples already at "
            "0.50 times the record; on the bearings it topples already at 0.80 times the record") in fell
    # a suite with the same verdicts under every record: "changes no verdict", then record by record
    ground = [luck, _row(record="sup", verdict="overturned", overturned=True, overturn_scale=0.80),
              _row(record="park", theta_max_over_alpha=0.39, overturn_scale=1.12)]
    bearings = [margin, _iso(record="sup", verdict="overturned", overturned=True, overturn_scale=0.52),
                _iso(record="park", theta_max_over_alpha=0.01, overturn_scale=1.20)]
    suite = _in_short(ground, bearings)
    assert "isolation Tb=2.5s changes no verdict: the statue topples under the same 1 of 3 records either way (sup)" \
        in suite
    assert ("by the margin, record by record, isolation Tb=2.5s helps under some records and hurts under others: the "
            "toppling factor (on the ground, then on the bearings) rises under kobe (0.61 to 1.21: from a survival by "
            "the luck of the timing to a margin) and park (1.12 to 1.20), and falls under sup (0.80 to 0.52)") in suite
    same = _in_short([_row(record="a", overturn_scale=1.5), _row(record="b", overturn_scale=2.0)],
                     [_iso(record="a", overturn_scale=1.505), _iso(record="b", overturn_scale=2.01)])
    assert "no difference in the margin either" in same
    # a save on the bearings by the luck of the timing is said to be one
    saved = _in_short([_row(record="a", verdict="overturned", overturned=True, overturn_scale=0.7)],
                      [_iso(record="a", theta_max_over_alpha=0.8, overturn_scale=0.6)])
    assert "saves it, provided the bearings can move 0.34 m (but only by the luck of the timing" in saved


# --------------------------------------------------------------------------------------------------
# the HTML report
# --------------------------------------------------------------------------------------------------

class _Page(HTMLParser):
    """Collects section ids, every tag and its attributes, the text per section and the style sheets."""

    def __init__(self):
        super().__init__()
        self.sections, self.tags, self.styles, self.text = [], [], [], {}
        self._in_style, self._section = False, None
        self.cards = []  # (css classes, text)
        self._card = None

    def handle_starttag(self, tag, attrs):
        a = dict(attrs)
        self.tags.append((tag, a))
        if tag == "section":
            self._section = a.get("id")
            self.sections.append(self._section)
            self.text[self._section] = ""
        if tag == "style":
            self._in_style = True
        if tag == "div" and "card" in (a.get("class") or "").split():
            self._card = [a["class"], ""]

    def handle_endtag(self, tag):
        if tag == "style":
            self._in_style = False
        if tag == "div" and self._card is not None:
            self.cards.append(tuple(self._card))
            self._card = None

    def handle_data(self, data):
        if self._in_style:
            self.styles.append(data)
        elif self._section:
            self.text[self._section] += data
        if self._card is not None:
            self._card[1] += data


def parse(path) -> _Page:
    p = _Page()
    p.feed(path.read_text(encoding="utf-8"))
    return p


def assert_self_contained(page: _Page, raw: str):
    """No resource outside the file: images are data: URIs, links are anchors, no scripts or imports."""
    for tag, attrs in page.tags:
        assert tag not in ("script", "link", "iframe", "object", "embed", "base"), tag
        for name in ("src", "href", "srcset", "action", "poster", "data"):
            value = attrs.get(name)
            if value is None:
                continue
            if name == "href":
                assert value.startswith("#"), value
            else:
                assert value.startswith("data:image/png;base64,"), value[:60]
                png = base64.b64decode(value.split(",", 1)[1], validate=True)
                assert png.startswith(b"\x89PNG\r\n\x1a\n")
    css = "".join(page.styles)
    assert "@import" not in css and "url(" not in css
    assert not re.search(r"""(src|href)\s*=\s*["']?\s*(https?:)?//""", raw, re.I)


def test_assess_column_report(find_record, tmp_path):
    """The acceptance scene: a statue under Kobe, on the ground and on linear bearings."""
    rec = find_record("RSN1119_KOBE_TAZ000.AT2")
    html_path, csv_path = tmp_path / "statue.html", tmp_path / "statue.csv"
    res = CliRunner().invoke(main, ["assess", "column", "statue:R=0.93,alpha=15.5", "--records", str(rec),
                                    "--isolation", "none", "--isolation", "linear:Tb=2.5", "--csv", str(csv_path),
                                    "--report", str(html_path)])
    assert res.exit_code == 0, res.output
    raw = html_path.read_text(encoding="utf-8")
    page = parse(html_path)
    assert page.sections == [sid for sid, _ in SECTIONS]
    assert_self_contained(page, raw)
    assert not list(tmp_path.glob(".*tmp*"))  # written atomically: no temporary file left

    # provenance: the SHA-256 of the very file, its format, units and PGA
    digest = hashlib.sha256(rec.read_bytes()).hexdigest()
    records = page.text["records"]
    assert digest in records and rec.name in records and "PEER_AT2" in records

    # the first screen answers the question, one card per configuration, as the CSV says
    df = read_assessment_csv(csv_path)
    answer = page.text["answer"]
    assert "Does the statue topple" in answer
    assert len(page.cards) == len(df) == 2
    for (classes, text), row in zip(page.cards, df.itertuples()):
        word = TOPPLES if row.overturned else SURVIVES
        assert word in classes.split() and word.upper() in text.upper()
        if math.isfinite(row.overturn_scale):
            assert f"{row.overturn_scale:.2f} times" in text
        if row.configuration != "none":
            assert f"{row.base_disp_max_m:.2f} m" in text  # the bearings' stroke
    # no card on the first screen counts zero runs not proven (it read as an alarm)
    assert "not proven" not in answer.lower() and df.proven.all()
    # the figures: the responses (the deciding record on both configurations, side by side), margins, stroke
    images = [a for t, a in page.tags if t == "img"]
    assert len(images) >= 3
    alts = " ".join(a["alt"] for a in images)
    assert "standing on the ground" in alts and "linear (rubber) bearings" in alts
    assert "assess column" in page.text["reproduce"]
    assert "Margins are found on a grid" in page.text["assumptions"]

    # the terminal: the answer in plain words after the table, readable without the legend
    out = res.output
    plain = out[out.index("In plain words:"):]
    assert "The statue, 1.79 m tall" in plain
    for row in df.itertuples():
        word = "topples" if row.overturned else "survives"
        where = "standing on the ground" if row.configuration == "none" else "on linear (rubber) bearings, Tb=2.5s"
        assert f"{where}: {word}" in plain
    if df.overturned.tolist() == [True, False]:  # the README's words for one record
        assert re.search(r"In short: the statue topples on the ground; isolation Tb=2\.5s saves it, provided the "
                         r"bearings can move \d\.\d\d m\.", re.sub(r"\s+", " ", plain))


def test_simulate_report_with_pulse(tmp_path):
    html_path = tmp_path / "one.html"
    res = CliRunner().invoke(main, ["simulate", "--height", "2", "--width", "0.5", "--name", "cabinet", "--pulse",
                                    "sine:ap=0.5,Tp=1", "--isolation", "linear:Tb=2", "--json", "--report",
                                    str(html_path)])
    assert res.exit_code == 0, res.output
    import json

    out = json.loads(res.output)  # --json output stays pure JSON
    page = parse(html_path)
    assert page.sections == [sid for sid, _ in SECTIONS]
    assert_self_contained(page, html_path.read_text(encoding="utf-8"))
    assert "Does the cabinet topple" in page.text["answer"]
    ((classes, text),) = page.cards
    assert (TOPPLES if out["verdict"] == "overturned" else SURVIVES) in classes.split()
    assert f"{out['base_disp_max_m']:.2f} m" in text
    assert "idealised" in page.text["records"].lower() and "sine" in page.text["records"]
    # simulate searches no margin: the page does not speak of margins or toppling factors
    for sid, text in page.text.items():
        assert "margin" not in text.lower() and "toppling factor" not in text.lower(), sid


def _e_cells(html: str) -> list:
    """The last cell (e) of each row of the body table (the first table of the page)."""
    table = re.search(r"<table.*?</table>", html, re.S).group(0)
    return [re.findall(r"<td[^>]*>(.*?)</td>", row)[-1] for row in re.findall(r"<tr>(.*?)</tr>", table, re.S)
            if "<td" in row]


def test_the_body_table_gives_the_impact_rule_the_runs_use():
    """e in the body table is what the runs' impacts keep on the ground: Housner's 1 - 1.5 sin^2(alpha) by default,
    a given --restitution, a capped colonnade's ratio, and for a body on its plinth the two-block law (no single e)
    unless E is given; the note under the table says which."""
    from rockcli.models import Plinth, Stack
    from rockcli.models.colonnade import impact_ratio_on_base
    from rockcli.report.html import body_section

    statue = Block.from_dimensions(1.79, 0.5, "statue")
    stack = Stack(statue, Plinth(1.0, 0.6))
    housner = 1.0 - 1.5 * math.sin(statue.alpha) ** 2
    html = body_section([statue, stack])
    assert _e_cells(html) == [f"{housner:.3f}", "two-block law"]
    assert "Housner's rule" in html and "the two-block law" in html
    html = body_section([statue, stack], restitution=0.8)
    assert _e_cells(html) == ["0.800", "0.800"]
    assert "--restitution 0.8" in html and "two-block law" not in html
    html = body_section([statue], cap_ratio=0.5)
    assert _e_cells(html) == [f"{impact_ratio_on_base(statue.alpha, 0.0, 0.5, None):.3f}"]
    assert float(_e_cells(html)[0]) < housner and "capped colonnade" in html


def test_a_report_with_a_given_restitution_shows_it(tmp_path):
    html_path = tmp_path / "e.html"
    res = CliRunner().invoke(main, ["simulate", "--height", "2", "--width", "0.5", "--pulse", "sine:ap=0.5,Tp=1",
                                    "--restitution", "0.85", "--report", str(html_path)])
    assert res.exit_code == 0, res.output
    assert _e_cells(html_path.read_text(encoding="utf-8")) == ["0.850"]


def test_fragility_report(tmp_path):
    folder = tmp_path / "suite"
    folder.mkdir()
    for k, (a, T) in enumerate([(0.4, 0.5), (0.3, 0.8), (0.5, 0.4)]):
        write_pulse_record(folder / f"p{k}.txt", a_p_g=a, T_p=T)
    html_path = tmp_path / "frag.html"
    res = CliRunner().invoke(main, ["assess", "fragility", "--R", "0.6", "--alpha", "12", "--name", "statue",
                                    "--records", str(folder), "--isolation", "none", "--bootstrap", "20",
                                    "--report", str(html_path)])
    assert res.exit_code == 0, res.output
    page = parse(html_path)
    assert page.sections == [sid for sid, _ in SECTIONS]
    assert_self_contained(page, html_path.read_text(encoding="utf-8"))
    for k in range(3):
        p = folder / f"p{k}.txt"
        assert hashlib.sha256(p.read_bytes()).hexdigest() in page.text["records"]
    assert len(page.cards) == 1 and "median" in page.text["verdicts"]


def test_report_to_a_missing_folder_is_refused_before_any_work(tmp_path):
    target = tmp_path / "nowhere" / "r.html"
    res = CliRunner().invoke(main, ["simulate", "--R", "1", "--alpha", "10", "--pulse", "sine:ap=0.3,Tp=1",
                                    "--report", str(target)])
    assert res.exit_code == 2 and "--report" in res.output and "does not exist" in res.output
    assert "Traceback" not in res.output and not target.parent.exists()


@pytest.mark.parametrize("bad", ['<img src="https://example.org/a.png">', '<a href="http://example.org">x</a>',
                                 "<style>@import 'x.css';</style>", "<style>body{background:url(//x/y.png)}</style>",
                                 '<script src="data:image/png;base64,AAAA"></script>'])
def test_the_self_contained_check_catches_external_resources(bad, tmp_path):
    p = tmp_path / "bad.html"
    p.write_text(f"<html><body><section id='answer'>{bad}</section></body></html>")
    with pytest.raises(AssertionError):
        assert_self_contained(parse(p), p.read_text())


# --------------------------------------------------------------------------------------------------
# provenance, unavailable records, the pulse's sign, the command to reproduce it
# --------------------------------------------------------------------------------------------------

def test_units_provenance_says_where_the_units_came_from(find_record, tmp_path):
    """A catalogue record without a header is read with the catalogue's units: said so, not "given"."""
    from rockcli.assess.excitations import resolve_excitations
    from rockcli.report.html_records import records_section

    find_record("C02-065")
    (x,), _ = resolve_excitations(["parkfield-1966-c02-065"])
    assert x.motion.meta["units_source"] == "catalogue"
    text = records_section([x])
    assert "from rockcli&#x27;s record catalogue" in text and "given" not in text
    assert "time step from rockcli&#x27;s record catalogue" in text
    # the same file outside the catalogue, with --units and --dt given: given by the user
    copy = tmp_path / "headerless.txt"
    copy.write_bytes(find_record("C02-065").read_bytes())
    (y,), _ = resolve_excitations([str(copy)], units="g", dt=0.01)
    assert "as given by the user (--units" in records_section([y])
    # a file that states its units
    (z,), _ = resolve_excitations([str(write_pulse_record(tmp_path / "p.txt", -0.5, 0.5, "ricker-anti"))])
    text = records_section([z])
    assert "as stated in the file" in text
    # the fitted pulse's sign in words: a direction along the record's axis
    assert ("a_p &lt; 0: its first peak accelerates the ground toward the negative side of the record&#x27;s axis"
            in text)


def test_unavailable_and_skipped_records_are_listed():
    from rockcli.assess.excitations import Skipped, Unavailable
    from rockcli.report.html_records import records_section

    text = records_section([], [Unavailable("vrancea-1977-bucharest", "no public file is known"),
                                Skipped("SOURCES.csv", "not a record")])
    assert "Not available" in text and "vrancea-1977-bucharest: no public file is known" in text
    assert "Skipped 1 file" in text and "SOURCES.csv" in text


def test_reproduce_command_has_its_folder_and_environment():
    from rockcli.report.html import reproduce_command

    cmd = ("rockcli assess column statue:height=1.79,width=0.5 --records kobe-1995-takarazuka-000 --records "
           "'my file.AT2' --isolation none --report out/s.html")
    got = reproduce_command(cmd, {"ROCKCLI_RECORDS": "/data/records:/data/extra", "HOME": "/root"}, "/work/x y")
    lines = got.splitlines()
    assert lines[0] == "cd '/work/x y'"
    assert lines[1].startswith("ROCKCLI_RECORDS=/data/records:/data/extra rockcli assess column statue:")
    assert "HOME" not in got and "--records 'my file.AT2' \\" in got and lines[-1].strip() == "--report out/s.html"
    import shlex

    # what a shell would run is the command given, word for word
    joined = " ".join(line.rstrip(" \\") for line in lines[1:])
    assert shlex.split(joined) == ["ROCKCLI_RECORDS=/data/records:/data/extra", *shlex.split(cmd)]
    assert "ROCKCLI_RECORDS" not in reproduce_command(cmd, {}, "/w")


def test_figures_are_embedded_at_their_drawn_size():
    """A figure w inches wide is shown 96 w CSS pixels wide, whatever its dpi, so that 8 pt is 10.7 px; a
    figure whose smallest text is 7 pt is enlarged to keep it at 10 px."""
    import io

    from rockcli.report.figures import new_figure
    from rockcli.report.html import figure, png_size

    for dpi in (90, 144):
        fig = new_figure(5.0, 2.0, dpi=dpi)
        fig.add_subplot().plot([0, 1])
        buf = io.BytesIO()
        fig.savefig(buf, format="png", dpi=dpi)
        png = buf.getvalue()
        width, _, got_dpi = png_size(png)
        assert abs(got_dpi - dpi) < 0.5 and width == 5 * dpi
        assert 'width="480"' in figure(png, "x")
        assert f'width="{round(480 * 10 / (7 * 96 / 72))}"' in figure(png, "x", smallest_pt=7.0)
