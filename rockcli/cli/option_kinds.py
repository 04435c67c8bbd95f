"""The kinds of option every command group builds on: rockcli's click ``Command`` and ``Group``, an old spelling kept
as a hidden alias, extra spellings left out of ``--help``, options kept on the click context instead of passed to
the command, and a list of options applied as one decorator (:mod:`rockcli.cli.options` re-exports them)."""

from __future__ import annotations

import click

class Command(click.Command):
    """A rockcli command: "did you mean" for a mistyped option suggests only the options ``--help`` lists
    (never an old spelling kept as a hidden alias)."""

    def parse_args(self, ctx, args):
        try:
            return super().parse_args(ctx, args)
        except click.NoSuchOption as exc:
            hidden = {o for p in self.params if getattr(p, "hidden", False) for o in p.opts}
            exc.possibilities = [o for o in (exc.possibilities or ()) if o not in hidden]
            raise


class Group(click.Group):
    """A rockcli command group: its commands are :class:`Command`."""

    command_class = Command


class AliasOption(click.Option):
    """The old spelling of an option, kept for a release: hidden from ``--help``, the value goes to the
    new option's argument, and a note naming the new spelling is printed on stderr once per run.

    ``check(value)`` (optional) may refuse a value the new option would misread (raise
    :class:`rockcli.errors.RockcliInputError`). When both spellings are given, the one written last wins.
    """

    def __init__(self, param_decls, *, target: str, new: str, check=None, **kwargs):
        old = param_decls[0]
        super().__init__([old, f"{target}__old_{old.strip('-').replace('-', '_')}"], hidden=True,
                         expose_value=False, **kwargs)
        self.old, self.target, self.new, self.check = old, target, new, check

    def handle_parse_result(self, ctx, opts, args):
        from click.core import ParameterSource

        value, args = super().handle_parse_result(ctx, opts, args)
        if ctx.get_parameter_source(self.name) != ParameterSource.COMMANDLINE or ctx.resilient_parsing:
            return value, args
        if self.check is not None:
            from rockcli.errors import RockcliInputError

            try:
                self.check(value)
            except RockcliInputError as exc:
                from rockcli.cli.errors import InputError

                raise InputError(str(exc)) from None
        ctx.params[self.target] = value
        ctx.set_parameter_source(self.target, ParameterSource.COMMANDLINE)
        noted = ctx.meta.setdefault("rockcli.aliases_noted", set())
        if self.old not in noted:
            noted.add(self.old)
            click.echo(f"Note: {self.old} is now {self.new}; the old spelling works for one more release "
                       f"(docs/cli-conventions.md).", err=True)
        return value, args


class QuietSpellingOption(click.Option):
    """An option with extra spellings that work but are not listed in ``--help`` (``assess --record`` for
    ``--records``: a repeatable option whose values from both spellings are collected together)."""

    def __init__(self, *args, quiet_spellings=(), **kwargs):
        super().__init__(*args, **kwargs)
        self.quiet_spellings = set(quiet_spellings)

    def get_help_record(self, ctx):
        opts = self.opts
        self.opts = [o for o in opts if o not in self.quiet_spellings]
        try:
            return super().get_help_record(ctx)
        finally:
            self.opts = opts


def alias_option(old: str, target: str, new: str, **kwargs):
    """A decorator adding :class:`AliasOption` ``old`` for the argument ``target`` of the option ``new``."""
    return click.option(old, cls=AliasOption, target=target, new=new, **kwargs)


def _remember(key):
    """A click callback keeping a given value on the click context under ``key`` (read back by ``given_*``)."""
    def callback(ctx, param, value):
        if value is not None:
            ctx.meta[key] = value
        return value

    return callback


def _kept(flag: str, **kwargs):
    """An option not passed to the command: kept on the click context as ``rockcli.<name>`` (``--vertical-scale``
    -> ``rockcli.vertical_scale``), None when not given."""
    return click.option(flag, default=None, expose_value=False,
                        callback=_remember("rockcli." + flag.lstrip("-").replace("-", "_")), **kwargs)


def _stacked(func, options):
    """``func`` decorated with ``options``, the first listed shown first in ``--help``."""
    for option in reversed(options):
        func = option(func)
    return func
