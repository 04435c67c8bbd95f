"""Write docs/cli.md, the command-line reference, from the commands' own help.

    python docs/gen_cli_reference.py           # rewrite docs/cli.md
    python docs/gen_cli_reference.py --check   # exit 1 when docs/cli.md is stale

Every command and subcommand of ``rockcli`` (hidden ones left out, as ``--help`` leaves them out) gets
a section holding its help: the usage line, the help text, the options and, for a group, its
commands, laid out as a terminal 100 columns wide shows ``--help``. The text is generated, never
edited by hand: ``tests/test_docs.py`` fails when docs/cli.md differs from what this script writes,
so a changed option or help text shows up as a one-line fix (run the script).

The layout is this script's own, not click's: click's help formatter changes between its releases
(click 8.5 prints a group's one-line summaries differently from 8.1-8.3, and each cuts them at other
places), and the page must be the same whatever click a fresh install gets (``click>=8.1``). So the
page is made from what each command declares, through click's per-item calls (the usage pieces, each
option's help row as its class builds it, the help texts), laid out here with the standard
library's :mod:`textwrap` in click's familiar layout; a group lists each command with the whole first
sentence of its help, never cut (a terminal's ``--help`` may shorten it to fit).
``tests/test_docs.py`` runs ``--check`` with click's layout code made to fail. (Checked: click 8.1.7,
8.2.1, 8.3.0 and 8.5.1 give the same page.)
"""

from __future__ import annotations

import inspect
import sys
import textwrap
from pathlib import Path

import click

#: where the reference goes
OUTPUT = Path(__file__).resolve().parent / "cli.md"
#: the terminal width the help is laid out for (fixed, so that the page does not depend on the machine)
WIDTH = 100
#: indent of a section's body, widest first column of a definition list, and the gap after it
INDENT, COL_MAX, GAP = 2, 30, 2

HEADER = """\
# Command-line reference

Generated from the commands' help by `python docs/gen_cli_reference.py`; do not edit by hand
(`tests/test_docs.py` fails when this page is stale). The same text is one `rockcli COMMAND --help`
away (a terminal may wrap it at another width, and shortens a group's one-line summaries to fit it).
For what the options mean and when to use them, see the how-to pages listed in
[the documentation map](README.md).
"""


# --------------------------------------------------------------------------------------------------
# text
# --------------------------------------------------------------------------------------------------

def _fill(text: str, width: int, first: str = "", rest: str = "") -> str:
    return textwrap.fill(text, max(width, 10), initial_indent=first, subsequent_indent=rest,
                         replace_whitespace=False)


def _paragraphs(text: str, width: int, indent: str = "") -> str:
    """``text`` wrapped paragraph by paragraph (blank lines between them). A paragraph keeps the indent of
    its first line; one that begins with a line holding only ``\\b`` is kept line for line (examples)."""
    pars, buf = [], []
    for line in text.expandtabs().splitlines() + [""]:
        if line.strip():
            buf.append(line.rstrip())
            continue
        if buf:
            pad = indent + " " * (len(buf[0]) - len(buf[0].lstrip()))
            if buf[0].strip() == "\b":
                pars.append("\n".join(pad + ln for ln in buf[1:]))
            else:
                pars.append(_fill(" ".join(ln.strip() for ln in buf), width, pad, pad))
        buf = []
    return "\n\n".join(pars)


def _definitions(rows: list[tuple[str, str]]) -> list[str]:
    """Two columns: each term, then its text wrapped beside it (on the next line when the term is wider
    than :data:`COL_MAX`)."""
    first = min(max(len(term) for term, _ in rows), COL_MAX) + GAP
    width = max(WIDTH - first - 2, 10)
    lines = []
    for term, text in rows:
        head = " " * INDENT + term
        body = _paragraphs(text, width).splitlines() if text else []
        if not body:
            lines.append(head)
            continue
        if len(term) <= first - GAP:
            lines.append(head + " " * (first - len(term)) + body[0])
        else:
            lines += [head, " " * (INDENT + first) + body[0]]
        lines += [(" " * (INDENT + first) + ln) if ln else "" for ln in body[1:]]
    return lines


# --------------------------------------------------------------------------------------------------
# what a command declares
# --------------------------------------------------------------------------------------------------

def _usage(command: click.Command, ctx: click.Context) -> str:
    prefix = f"Usage: {ctx.command_path} "
    return _fill(" ".join(command.collect_usage_pieces(ctx)), WIDTH, prefix, " " * len(prefix))


def summary(command: click.Command) -> str:
    """A command's one-line summary in a group's list: its ``short_help``, else the first sentence of its
    help, whole (a word ending in '.', '?' or '!' ends it when no lowercase word follows)."""
    if command.short_help:
        return " ".join(inspect.cleandoc(command.short_help).split())
    words = inspect.cleandoc(command.help or "").partition("\f")[0].partition("\n\n")[0].split()
    if words and words[0] == "\b":
        words = words[1:]
    for i, word in enumerate(words):
        if word.endswith((".", "?", "!")) and (i == len(words) - 1 or not words[i + 1][0].islower()):
            return " ".join(words[:i + 1])
    return " ".join(words)


def help_text(command: click.Command, ctx: click.Context) -> str:
    """The help of ``command`` as the page shows it (lines of at most :data:`WIDTH` columns where words allow)."""
    parts = [_usage(command, ctx)]
    text = inspect.cleandoc(command.help or "").partition("\f")[0]
    if text:
        parts.append(_paragraphs(text, WIDTH, " " * INDENT))
    rows = [p.get_help_record(ctx) for p in command.get_params(ctx) if isinstance(p, click.Option)]
    rows = [row for row in rows if row is not None]  # a hidden option has none
    if rows:
        parts.append("\n".join(["Options:"] + _definitions(rows)))
    if isinstance(command, click.Group):
        subs = [(name, command.get_command(ctx, name)) for name in command.list_commands(ctx)]
        rows = [(name, summary(sub)) for name, sub in subs if sub is not None and not sub.hidden]
        if rows:
            parts.append("\n".join(["Commands:"] + _definitions(rows)))
    if command.epilog:
        parts.append(_paragraphs(inspect.cleandoc(command.epilog), WIDTH, " " * INDENT))
    return "\n\n".join(parts) + "\n"


# --------------------------------------------------------------------------------------------------
# the page
# --------------------------------------------------------------------------------------------------

def _commands(group: click.Group, ctx: click.Context):
    """Yield ``(context, command)`` for every visible subcommand of *group*, depth first, sorted."""
    for name in group.list_commands(ctx):
        command = group.get_command(ctx, name)
        if command is None or getattr(command, "hidden", False):
            continue
        sub = click.Context(command, info_name=name, parent=ctx)
        yield sub, command
        if isinstance(command, click.Group):
            yield from _commands(command, sub)


def render() -> str:
    """The whole page as a string."""
    from rockcli.cli import main

    root = click.Context(main, info_name="rockcli", **main.context_settings)
    entries = [(root, main)] + list(_commands(main, root))
    parts = [HEADER, "\n"]
    titles = [ctx.command_path for ctx, _ in entries]
    parts.append("Commands: " + ", ".join(f"[`{t}`](#{_anchor(t)})" for t in titles) + ".\n")
    for ctx, command in entries:
        parts.append(f"\n## {ctx.command_path}\n\n```text\n{help_text(command, ctx)}```\n")
    return "".join(parts)


def _anchor(title: str) -> str:
    """GitHub's anchor for a heading made of *title* (lower case, spaces to hyphens)."""
    return "".join(c for c in title.lower().replace(" ", "-") if c.isalnum() or c in "-_")


def main(argv: list[str] | None = None) -> int:
    argv = sys.argv[1:] if argv is None else argv
    text = render()
    if argv == ["--check"]:
        current = OUTPUT.read_text(encoding="utf-8") if OUTPUT.exists() else ""
        if current != text:
            print(f"{OUTPUT} is stale: run python docs/gen_cli_reference.py", file=sys.stderr)
            return 1
        return 0
    if argv:
        print(__doc__, file=sys.stderr)
        return 2
    OUTPUT.write_text(text, encoding="utf-8")
    print(f"wrote {OUTPUT}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
