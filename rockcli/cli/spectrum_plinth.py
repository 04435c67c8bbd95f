"""``rockcli spectrum ... --on PLINTH``: every configuration of a spectrum twice, the block alone and standing on a
free plinth in proportion to it (:mod:`rockcli.spectra.plinth`: why ratios and not metres).

What ``--on`` does not take is refused in one sentence before any run: a plinth in metres, a vertical pulse, a
capped colonnade, a foundation the stack is not modelled on
(:func:`rockcli.solve.stack_many.plinth_foundation_supported`).
"""

from __future__ import annotations

import math

import click

from rockcli.errors import RockcliInputError

#: The ``--on`` of the spectra (``help``).
ON_HELP = ("Run every configuration twice: the block alone and standing on a free plinth in proportion to it, "
           "NAME:height_ratio=<H2/H1>,width_ratio=<B2/B1>[,mass_ratio=<M2/M1>] (e.g. "
           "plinth:height_ratio=0.5,width_ratio=1.5): heights, widths and masses over the body's, so that the "
           "spectrum stays dimensionless (docs/spectra.md); mass_ratio left out: the same density. The two-block "
           "assembly, rocking only (docs/plinth.md), on a rigid foundation or linear bearings; a_p stays in units of "
           "the body's g tan alpha.")


def on_option(func):
    """``--on PLINTH`` of a spectrum (``plinth_spec``)."""
    return click.option("--on", "plinth_spec", default=None, metavar="PLINTH", help=ON_HELP)(func)


def spectrum_plinths(plinth_spec, alphas_deg, isolations, *, cap_ratio=0.0, sizes=None) -> list:
    """``[None]`` without ``--on``; else ``[None, PlinthRatio]`` (alone, then on the plinth), after checking that
    every configuration can take it. ``isolations``: the spectra's :class:`rockcli.spectra.Isolation` list, or
    foundations (``spectrum rocking``); ``sizes``: the block sizes R [m] to check (None: the reference block)."""
    if plinth_spec is None:
        return [None]
    from rockcli.cli.options import given_vertical
    from rockcli.models import Block
    from rockcli.solve.stack_many import PLINTH_RIGID_ONLY, plinth_foundation_supported
    from rockcli.spectra import REFERENCE_R
    from rockcli.spectra.plinth import check_plinth_ratio, parse_plinth_ratio

    plinth = parse_plinth_ratio(plinth_spec)
    if cap_ratio:
        raise RockcliInputError("--on stands the block alone on its plinth: not with --cap-ratio")
    if given_vertical()["pulse"] is not None:
        raise RockcliInputError("--on: a body on a plinth runs under the horizontal ground motion only, so "
                                "--vertical-pulse is not taken with it")
    left = [iso.label for iso in isolations
            if not plinth_foundation_supported(iso.foundation(1.0) if hasattr(iso, "foundation") else iso)]
    if left:
        raise RockcliInputError(f"--on: {PLINTH_RIGID_ONLY} ({', '.join(left)}); give --isolation none or "
                                f"bearings with gamma > 0")
    check_plinth_ratio(plinth, [Block(R, math.radians(a), "reference") for a in alphas_deg
                                for R in ([REFERENCE_R] if sizes is None else sorted({min(sizes), max(sizes)}))])
    return [None, plinth]


def plinth_summary(plinth) -> dict:
    """The JSON's ``plinth`` of a map or a curve (None: the block alone)."""
    if plinth is None:
        return {"plinth": None}
    return {"plinth": plinth.label}


__all__ = ["ON_HELP", "on_option", "plinth_summary", "spectrum_plinths"]
