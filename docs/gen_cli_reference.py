"""Write docs/cli.md, the command-line reference, from the commands' own ``--help``.

    python docs/gen_cli_reference.py           # rewrite docs/cli.md
    python docs/gen_cli_reference.py --check   # exit 1 when docs/cli.md is stale

Every command and subcommand of ``rockcli`` (hidden ones left out, as ``--help`` leaves them out) gets
a section holding its help text exactly as a terminal 100 columns wide shows it. The text is
generated, never edited by hand: ``tests/test_docs.py`` fails when docs/cli.md differs from what
this script writes, so a changed option or help text shows up as a one-line fix (run the script).
"""

from __future__ import annotations

import sys
from pathlib import Path

import click

#: where the reference goes
OUTPUT = Path(__file__).resolve().parent / "cli.md"
#: the terminal width the help is rendered at (fixed, so that the page does not depend on the machine)
WIDTH = 100

HEADER = """\
# Command-line reference

Generated from the commands' `--help` by `python docs/gen_cli_reference.py`; do not edit by hand
(`tests/test_docs.py` fails when this page is stale). The same text is one `rockcli COMMAND --help`
away. For what the options mean and when to use them, see the how-to pages listed in
[the documentation map](README.md).
"""


def _commands(group: click.Group, ctx: click.Context):
    """Yield ``(path, command)`` for every visible subcommand of *group*, depth first, sorted."""
    for name in group.list_commands(ctx):
        command = group.get_command(ctx, name)
        if command is None or getattr(command, "hidden", False):
            continue
        sub = click.Context(command, info_name=name, parent=ctx, terminal_width=WIDTH, max_content_width=WIDTH)
        yield sub, command
        if isinstance(command, click.Group):
            yield from _commands(command, sub)


def _help(command: click.Command, ctx: click.Context) -> str:
    return command.get_help(ctx).rstrip() + "\n"


def render() -> str:
    """The whole page as a string."""
    from rockcli.cli import main

    settings = {**main.context_settings, "terminal_width": WIDTH, "max_content_width": WIDTH}
    root = click.Context(main, info_name="rockcli", **settings)
    entries = [(root, main)] + list(_commands(main, root))
    parts = [HEADER, "\n"]
    titles = [ctx.command_path for ctx, _ in entries]
    parts.append("Commands: " + ", ".join(f"[`{t}`](#{_anchor(t)})" for t in titles) + ".\n")
    for ctx, command in entries:
        parts.append(f"\n## {ctx.command_path}\n\n```text\n{_help(command, ctx)}```\n")
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
