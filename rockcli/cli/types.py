"""Click parameter types for numbers: every numeric option goes through :func:`rockcli.io.inputs.parse_number`.

``click``'s own ``float`` and ``int`` take what Python's ``float()``/``int()`` take (``1_0`` is 10,
``inf`` and ``nan`` pass) and answer with a usage block; these types refuse those forms and a decimal
comma with one sentence quoting what was written (``Error: --R '1,5' is written with a decimal
comma ...``), exit code 2.
"""

from __future__ import annotations

import click

from rockcli.cli.errors import InputError


class Number(click.ParamType):
    """A finite decimal number (optionally within a range), parsed by :func:`rockcli.io.inputs.parse_number`.

    Range checks belong to the library when it states the range with its reason (``--R``,
    ``--tail``); give ``lo``/``hi`` here only for options whose range is the option's own
    (``--seed >= 0``).
    """

    name = "float"

    def __init__(self, *, lo=None, hi=None, lo_open=False, hi_open=False, unit="", integer=False):
        self.bounds = dict(lo=lo, hi=hi, lo_open=lo_open, hi_open=hi_open, unit=unit, integer=integer)
        if integer:
            self.name = "integer"

    def convert(self, value, param, ctx):
        from rockcli.errors import RockcliInputError
        from rockcli.io.inputs import parse_number

        what = (param.opts[0] if param is not None and param.opts else
                param.human_readable_name if param is not None else "value")
        try:
            return parse_number(value, what, **self.bounds)
        except RockcliInputError as exc:
            raise InputError(str(exc)) from None

    def __repr__(self) -> str:
        return "WHOLE" if self.bounds["integer"] else "NUMBER"


#: A finite decimal number (no range of its own).
NUMBER = Number()
#: A whole number (no range of its own).
WHOLE = Number(integer=True)
#: A random seed: a whole number from 0 (numpy refuses negative seeds with a traceback).
SEED = Number(integer=True, lo=0, hi=2**32 - 1)
