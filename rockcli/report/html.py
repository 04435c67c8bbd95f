"""Self-contained HTML reports: one file a conservator can hand to a committee.

The page is built from plain strings (the standard library's :func:`html.escape`); the figures are
PNG images embedded as base64 ``data:`` URIs and the style sheet is inline, so the file refers to no
other file and to no network resource: it opens offline, anywhere, and can be mailed as it is.

Every report has the same sections, in this order (their ``id`` is in :data:`SECTIONS`): the
question and the answer in one sentence per body and configuration (the first screen), the body,
the configurations, the records with their provenance (file, format, SHA-256, units as stated,
PGA, PGV, fitted pulse), the verdicts with their margins, the figures, how sure the numbers are,
the assumptions and limits, and how to reproduce it (the command line and the versions).

This module holds the page and the sections every report shares; :mod:`rockcli.report.html_records`
the records' provenance (their section); :mod:`rockcli.report.html_pages` fills them for ``assess
column``, ``assess fragility`` and ``simulate``; :mod:`rockcli.report.html_deciding` picks and draws the
records that decide each verdict, and :mod:`rockcli.report.html_figures` draws the figures.
"""

from __future__ import annotations

import base64
import html
import math
import os
import platform
from datetime import datetime, timezone
from pathlib import Path

from rockcli.io.files import write_text

#: Section ids and titles, in the order of the page.
SECTIONS = (("answer", "The answer"), ("body", "The body"), ("configurations", "How it stands"),
            ("records", "The ground motions"), ("verdicts", "Verdicts and margins"), ("figures", "Figures"),
            ("certainty", "How sure is this?"), ("assumptions", "Assumptions and limits"),
            ("reproduce", "How to reproduce it"))

CSS = """
body{font-family:-apple-system,"Segoe UI",Roboto,"DejaVu Sans",Arial,sans-serif;margin:0;color:#1d1d1d;
background:#fafafa;line-height:1.45}
main{max-width:1180px;margin:0 auto;padding:18px 28px 60px;background:#fff}
h1{font-size:1.7em;margin:.2em 0 .1em}
h2{font-size:1.25em;border-bottom:2px solid #ddd;padding-bottom:.2em;margin-top:1.8em}
h3{font-size:1.05em;margin:1.2em 0 .3em}
.question{font-size:1.2em;margin:.4em 0 .8em}
.short{font-size:1.1em;font-weight:600;margin:.5em 0}
ul.short{font-weight:400;margin-top:0}ul.short li{margin:.25em 0}
.subtitle{color:#555;margin:0 0 .6em}
.card{border-left:8px solid #777;background:#f4f4f4;padding:.55em .9em;margin:.45em 0;font-size:1.08em}
.card .word{font-weight:700;text-transform:uppercase;letter-spacing:.03em}
.card .where{font-weight:600}
.topples{border-color:#c0392b;background:#fbeeee}.topples .word{color:#c0392b}
.survives{border-color:#2e7d32;background:#edf6ee}.survives .word{color:#2e7d32}
.undecided{border-color:#e69500;background:#fdf5e6}.undecided .word{color:#b37400}
.w-topples{color:#c0392b}.w-survives{color:#2e7d32}.w-undecided{color:#b37400}
.keyfacts{display:flex;flex-wrap:wrap;gap:10px;margin:.8em 0}
.fact{border:1px solid #ddd;border-radius:6px;padding:.4em .8em;background:#fff;max-width:24em}
.fact b{font-size:1.2em}
nav{font-size:.92em;color:#555;margin:1em 0}nav a{color:#1f5fa8;margin-right:.8em}
table{border-collapse:collapse;margin:.5em 0;font-size:.9em}
th,td{border:1px solid #ddd;padding:.25em .55em;text-align:left;vertical-align:top}
th{background:#f0f0f0}td.num{text-align:right;white-space:nowrap;font-variant-numeric:tabular-nums}
td.num .note{white-space:normal;display:inline-block;min-width:7em;max-width:11em;text-align:left}
.words{min-width:15em}
.figrow{display:flex;flex-wrap:wrap;gap:12px}.figrow figure{flex:1 1 480px;margin:0}
figure{margin:.8em 0}figure img{max-width:100%;border:1px solid #eee;display:block}
figcaption{font-size:.88em;color:#444}
code.hash{font-size:.78em;word-break:break-all;display:inline-block;max-width:15em}
code,pre{font-family:"DejaVu Sans Mono",Consolas,monospace;font-size:.88em}
pre{background:#f4f4f4;padding:.6em;white-space:pre-wrap;word-break:break-all}
.note{color:#555;font-size:.92em}
"""


def esc(text) -> str:
    """``text`` escaped for HTML (quotes too)."""
    return html.escape(str(text), quote=True)


def breakable(text) -> str:
    """``text`` escaped, with a line break allowed after each ``+ _ . / @`` (a record label such as
    ``RSN982_NORTHR_JEN022.AT2+JEN292.AT2`` is one word to a browser, which would widen its column to it)."""
    import re

    return re.sub(r"([+_./@])", r"\1<wbr>", esc(text))


def num(x, spec: str = ".3g", unit: str = "") -> str:
    """A number for a table cell: ``-`` when missing or not finite."""
    try:
        x = float(x)
    except (TypeError, ValueError):
        return "-"
    if not math.isfinite(x):
        return "-"
    return format(x, spec) + (f" {unit}" if unit else "")


def table(head, rows, numeric=()) -> str:
    """An HTML table; ``rows`` hold already escaped cells; columns in ``numeric`` align right; no header
    row when ``head`` is None (a two-column list of names and values)."""
    out = ["<table>" + ("<thead><tr>" + "".join(f"<th>{h}</th>" for h in head) + "</tr></thead>" if head else "")
           + "<tbody>"]
    for r in rows:
        out.append("<tr>" + "".join(f'<td class="num">{c}</td>' if i in numeric else f"<td>{c}</td>"
                                    for i, c in enumerate(r)) + "</tr>")
    out.append("</tbody></table>")
    return "\n".join(out)


#: CSS pixels per inch (the CSS standard): a figure drawn ``w`` inches wide is shown ``w * 96`` pixels wide, so
#: that a font of ``f`` points is ``f * 96 / 72`` pixels tall on the page (8 pt: 10.7 px), whatever the
#: resolution it was rendered at.
CSS_PX_PER_INCH = 96.0


def png_size(png: bytes) -> tuple[int, int, float]:
    """``(width, height, dots per inch)`` of a PNG: the pixels from its header, the resolution from its
    ``pHYs`` chunk (matplotlib writes the figure's dpi there); dpi NaN when the PNG does not say."""
    import struct

    if png[:8] != b"\x89PNG\r\n\x1a\n":
        raise ValueError("not a PNG")
    width, height = struct.unpack(">II", png[16:24])
    dpi, pos = math.nan, 8
    while pos + 8 <= len(png):
        length, kind = struct.unpack(">I4s", png[pos:pos + 8])
        if kind == b"pHYs" and length == 9:
            ppu_x, _, unit = struct.unpack(">IIB", png[pos + 8:pos + 17])
            if unit == 1 and ppu_x > 0:  # pixels per metre
                dpi = ppu_x * 0.0254
            break
        if kind == b"IDAT":
            break
        pos += 12 + length
    return width, height, dpi


#: The smallest text on the page's figures [CSS px].
MIN_TEXT_PX = 10.0


def figure(png: bytes | None, caption: str, smallest_pt: float = 8.0) -> str:
    """A ``<figure>`` with the PNG embedded as a base64 ``data:`` URI (empty when ``png`` is None).

    The image is shown at its drawn size (:data:`CSS_PX_PER_INCH`, from the PNG's resolution), enlarged
    when its smallest font (``smallest_pt`` [pt]) would be under :data:`MIN_TEXT_PX` pixels, and at most
    as wide as the page.
    """
    if not png:
        return ""
    data = base64.b64encode(png).decode("ascii")
    width, height, dpi = png_size(png)
    size = ""
    if math.isfinite(dpi) and dpi > 0:
        zoom = max(1.0, MIN_TEXT_PX / (smallest_pt * CSS_PX_PER_INCH / 72.0))
        w = round(width / dpi * CSS_PX_PER_INCH * zoom)
        size = f' width="{w}" style="width:{w}px;height:auto"'
    return (f'<figure><img alt="{esc(caption)}"{size} src="data:image/png;base64,{data}">'
            f"<figcaption>{esc(caption)}</figcaption></figure>")


def card(word: str, where: str, sentence: str) -> str:
    """One answer: the configuration, the outcome word and the sentence (escaped here)."""
    css = word if word in ("topples", "survives", "undecided") else ""
    rest = sentence[len(word) + 1:].strip() if sentence.startswith((word + ":", word + " ")) else sentence
    return (f'<div class="card {css}"><span class="where">{esc(where[:1].upper() + where[1:])}</span>: '
            f'<span class="word">{esc(word)}</span> &mdash; {esc(rest)}.</div>')


def plural(n: int, word: str) -> str:
    """``1 scene``, ``2 scenes``."""
    return f"{n} {word}" + ("" if n == 1 else "s")


def body_section(blocks, *, restitution: float | None = None, cap_ratio: float = 0.0) -> str:
    """Dimensions, R, alpha and p of every body, with what they mean; ``e`` as the run's impacts use it: Housner's
    rule, a given coefficient of restitution, a capped colonnade's ratio, or a body on a plinth's two-block law."""
    from rockcli.report.words import body_noun
    from rockcli.io.units import G
    from rockcli.models.colonnade import impact_ratio_on_base
    from rockcli.models.impact import impact_ratio

    def e_cell(b):
        if isinstance(getattr(b, "drums", None), tuple):  # a column of drums: the plastic impact with Coulomb's law
            return "plastic"
        if getattr(b, "plinth", None) is not None:
            return num(restitution, ".3f") if restitution is not None else "two-block law"
        if cap_ratio > 0.0:
            return num(impact_ratio_on_base(b.alpha, 0.0, cap_ratio, restitution), ".3f")
        return num(impact_ratio(b.alpha, 0.0, restitution), ".3f")

    def one(b):  # a column of drums: its figures as one block (its monolith's), its first joint to move below
        return b.monolith if isinstance(getattr(b, "drums", None), tuple) else b

    rows = [(esc(b.name), esc(body_noun(b)), num(b.height, ".3f", "m"), num(b.width, ".3f", "m"),
             num(one(b).h / one(b).b, ".2f"), num(b.R, ".3f", "m"), num(b.alpha_deg, ".2f", "deg"),
             num(one(b).p, ".3f", "rad/s"), num(one(b).uplift_acceleration / G, ".3f", "g"), e_cell(b))
            for b in blocks]
    head = ("name", "called", "height", "width", "height / width", "R", "alpha", "p", "lifts off at", "e")
    stacks = [b for b in blocks if getattr(b, "plinth", None) is not None]
    plinths = "".join(
        f" {esc(s.name)}: the body (its figures in the table) stands on a free plinth {s.plinth.height:g} m tall and "
        f"{s.plinth.width:g} m wide, {s.m2:.3g} times its mass; from rest the body lifts off the plinth at "
        f"{s.body_uplift_acceleration / G:.3f} g and body and plinth lift together at "
        f"{s.assembly_uplift_acceleration / G:.3f} g (the smaller is in the table); they rock as two rigid blocks, "
        f"without sliding (docs/plinth.md)." for s in stacks)
    drums = "".join(
        f" {esc(b.name)}: {len(b.drums)} drums free at every joint (its figures in the table are the column's as one "
        f"block; 'lifts off at' is the base's); from rest each joint would open at "
        f"{', '.join(f'{t:.3f}' for t in b.static_thresholds())} g, bottom to top, unless it slides first (at mu g); "
        f"impacts are plastic with Coulomb's law (docs/physics-drums.md)."
        for b in blocks if isinstance(getattr(b, "drums", None), tuple))
    if restitution is not None:
        rule = f"the coefficient of restitution given (--restitution {restitution:g}), not Housner's rule"
    elif cap_ratio > 0.0:
        rule = (f"in a capped colonnade (beam/columns mass {cap_ratio:g}), the columns and the beam's momenta "
                f"together (Makris &amp; Vassiliou 2013)")
    else:
        rule = "Housner's rule"
    if stacks and restitution is None:
        rule += ("; a body on a plinth has no single e: its impacts keep both blocks' momenta (the two-block law, "
                 "docs/plinth.md)")
    return (table(head, rows, numeric=range(2, 10)) + (f"<p class='note'>{plinths.strip()}</p>" if stacks else "") +
            (f"<p class='note'>{drums.strip()}</p>" if drums else "") +
            "<p class='note'>The body is taken as a rigid block. R: distance from its centre of mass to a corner "
            "of its base; alpha: its slenderness, atan(width/height) (the angle it must tilt to fall); p = "
            "sqrt(3g/4R): its frequency parameter (larger bodies rock more slowly and are harder to topple); "
            "it lifts off when the ground acceleration exceeds g tan(alpha); e: the share of rocking velocity "
            f"kept at each impact on the ground ({rule}).</p>")


def configurations_section(configurations) -> str:
    """Every configuration with all its parameters."""
    from rockcli.report.words import configuration_words

    rows = []
    for c in configurations:
        f = c.foundation
        params = {k: v for k, v in vars(f).items() if isinstance(v, (int, float))}
        text = ", ".join(f"{k} = {v:g}" for k, v in params.items()) or "-"
        rows.append((esc(c.header), esc(configuration_words(c)), f"<code>{esc(f.label)}</code>", esc(text)))
    return (table(("short name", "in words", "specification", "parameters"), rows) +
            "<p class='note'>Tb: period of the isolated base [s]; xi: damping ratio of linear bearings; mu: "
            "friction coefficient of sliding bearings; Q: strength of lead-rubber bearings over the weight; uy: "
            "yield displacement [m]; gamma = m/(m + m_b): the mass of the body over that of body and isolated "
            "base. The bearings are assumed to allow any displacement (no stops).</p>")


ASSUMPTIONS = (
    "The body is rigid: it does not bend, crack or break, and its base does not slide or bounce; it rocks in "
    "one vertical plane about the two edges of its base (the model of Housner 1963 and of Vassiliou & Makris "
    "2012).",
    "At each impact it keeps a share e of its rocking velocity given by Housner's rule from its slenderness; a "
    "real base (mortar, a soft floor) may dissipate more or less energy. A body stands on the ground itself unless "
    "it is assessed on a free plinth (--on): then body and plinth are two rigid blocks that rock without sliding, "
    "each impact losing what the plastic impact of the two blocks loses (docs/physics-plinth.md); on "
    "bearings (linear, sliding or lead-rubber) the base carries both, a base of finite mass (gamma > 0).",
    "Only the horizontal ground motion in the plane of rocking is applied, as given in its file: the vertical "
    "motion and the other horizontal direction are ignored.",
    "A record is one sample of what an earthquake can do: another station, another event or the other "
    "component can be much stronger or weaker at the same PGA; a design decision needs a suite of records "
    "chosen for the site.",
    "On isolation, the bearings follow their idealised laws (linear spring and dashpot; or friction with a "
    "smooth Bouc-Wen transition) and move as far as needed: the displacement shown is the demand the bearings "
    "and the space around the base must allow.",
    "'Survives' means it does not overturn: impacts can still chip edges, and a body that rocks close to its "
    "overturning angle is not safe in any practical sense.",
)


#: The assumptions of the margins (the toppling factors), for the reports that searched them.
MARGIN_ASSUMPTIONS = (
    "Margins are scale factors of these records only: a record of another shape can topple the body at a "
    "lower PGA.",
    "Margins are found on a grid of scale factors 0.1 to 4 about 1 % apart (the smallest factor of the grid "
    "that topples the body): a window of toppling factors narrower than 1 % between two surviving ones can "
    "be missed.",
)


def assumptions_section(extra=(), *, margins: bool = True) -> str:
    """The assumptions and limits (with those of the margins when ``margins``: a report that searched none,
    e.g. ``simulate``, does not speak of them)."""
    items = (*ASSUMPTIONS, *(MARGIN_ASSUMPTIONS if margins else ()), *extra)
    return "<ul>" + "".join(f"<li>{esc(t)}</li>" for t in items) + "</ul>"


#: Environment variables that change what rockcli reads (the record folders, the catalogue).
REPRODUCE_ENVIRONMENT = ("ROCKCLI_RECORDS", "ROCKCLI_CATALOG")


def reproduce_command(command: str, environ=None, cwd=None) -> str:
    """The command as a reader can paste it in a shell: the folder it ran in (record paths may be relative
    to it), the environment variables that decide which files are read (:data:`REPRODUCE_ENVIRONMENT`;
    catalogue ids are looked up on ``ROCKCLI_RECORDS``) and the command, one option per line."""
    import shlex

    environ = os.environ if environ is None else environ
    cwd = os.getcwd() if cwd is None else cwd
    env = [f"{k}={shlex.quote(environ[k])}" for k in REPRODUCE_ENVIRONMENT if environ.get(k, "").strip()]
    if not command.startswith("rockcli ") or "(called from Python" in command:
        lines = [command]
    else:
        words, lines = shlex.split(command), []
        for w in words:
            if w.startswith("--") or not lines:
                lines.append(shlex.quote(w))
            else:
                lines[-1] += " " + shlex.quote(w)
        lines[0] = " ".join([*env, lines[0]])
        env = []
    head = [f"cd {shlex.quote(str(cwd))}"] + ([f"export {' '.join(env)}"] if env else [])
    return "\n".join(head + [" \\\n    ".join(lines)])


def reproduce_section(command: str) -> str:
    """The exact command line (with its folder and environment) and the versions of rockcli and its main
    libraries."""
    import rockcli

    versions = [("rockcli", rockcli.__version__), ("Python", platform.python_version())]
    for mod in ("numpy", "scipy", "numba"):
        try:
            versions.append((mod, __import__(mod).__version__))
        except Exception:  # pragma: no cover - every supported install has them
            pass
    when = datetime.now(timezone.utc).strftime("%Y-%m-%d %H:%M UTC")
    return (f"<p>Run this command, with the same record files (check their SHA-256 above), to get the same "
            f"numbers:</p><pre>{esc(reproduce_command(command))}</pre>"
            + table(("software", "version"), [(esc(k), esc(v)) for k, v in versions])
            + f"<p class='note'>Written {esc(when)} on {esc(platform.system())} {esc(platform.machine())}.</p>")


def page(title: str, subtitle: str, sections: dict, names: dict | None = None) -> str:
    """The whole page: ``sections`` maps every id of :data:`SECTIONS` to its HTML body; ``names`` renames
    sections (``simulate`` has a verdict and no margins)."""
    named = [(sid, (names or {}).get(sid, name)) for sid, name in SECTIONS]
    nav = " ".join(f'<a href="#{sid}">{esc(name)}</a>' for sid, name in named[1:])
    body = []
    for sid, name in named:
        head = f"<h1>{esc(title)}</h1><p class='subtitle'>{esc(subtitle)}</p>" if sid == "answer" else \
            f"<h2>{esc(name)}</h2>"
        body.append(f'<section id="{sid}">{head}\n{sections[sid]}\n' + (f"<nav>Contents: {nav}</nav>"
                                                                        if sid == "answer" else "") + "</section>")
    return ("<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\">"
            "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">"
            f"<title>{esc(title)}</title><style>{CSS}</style></head>\n<body><main>\n"
            + "\n".join(body) + "\n</main></body></html>\n")


def write_report(path: str | os.PathLike, text: str) -> Path:
    """Write the report atomically (a complete file or none)."""
    return write_text(path, text, "--report")
