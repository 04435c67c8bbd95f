"""``assess column --on PLINTH`` and ``assess fragility --on PLINTH``: every body alone and on the plinth.

Each body named is assessed twice, alone and standing on the plinth (a :class:`rockcli.models.Stack`, a column of
its own named ``statue on plinth``), on the same configurations and records, so that the answer can say whether the
plinth helps or hurts (:func:`rockcli.assess.verdicts.plinth_summary`).

Foundations (the choice, docs/plinth.md): a body on a plinth is modelled on the rigid foundation and on linear,
sliding and lead-rubber bearings with gamma > 0 (:func:`rockcli.solve.stack_many.plinth_foundation_supported`). A
configuration of another kind in a default set is left out with a note; one the user names with ``--on`` is
refused in one sentence (a cell that cannot be computed is not an answer to what was asked).
"""

from __future__ import annotations

import math

from rockcli.errors import RockcliInputError


def with_plinth(columns, configurations, plinth_spec, *, isolation_given: bool, cap_ratio=0.0,
                refused=()) -> tuple[list, list, str]:
    """``(columns, configurations, note)``: each body followed by itself on the plinth, the configurations the
    stack runs on, and a note naming those left out (empty when none). ``refused``: ``(option, given)`` pairs that
    ``--on`` does not take (one sentence)."""
    from rockcli.cli.options import stack_from_option
    from rockcli.solve.stack_many import PLINTH_RIGID_ONLY, plinth_foundation_supported

    if cap_ratio:
        raise RockcliInputError("--on stands each body alone on its plinth: not with --cap-ratio")
    from rockcli.cli.options import given_vertical

    v = given_vertical()
    vertical = any(v[k] is not None for k in ("source", "pulse", "component"))
    given = [name for name, on in (*refused, ("--vertical/--vertical-pulse/--vertical-component", vertical)) if on]
    if given:
        raise RockcliInputError(f"--on: {', '.join(given)} {'is' if len(given) == 1 else 'are'} not taken with a "
                                f"body on a plinth yet")
    out = []
    for b in columns:
        out += [b, stack_from_option(b, plinth_spec)]
    kept = [c for c in configurations if plinth_foundation_supported(c.foundation)]
    left = [c for c in configurations if c not in kept]
    if left and isolation_given:
        raise RockcliInputError(f"--on: {PLINTH_RIGID_ONLY} ({', '.join(c.spec for c in left)}); give "
                                f"--isolation none or bearings with gamma > 0")
    note = ""
    if left:
        note = (f"Plinth: {PLINTH_RIGID_ONLY}, so every body, alone and on its plinth, is assessed without them "
                f"(left out of the default set: {', '.join(c.header for c in left)}).")
    return out, kept, note


def plinth_notes(result, note: str = "") -> str:
    """The notes of an assessment with plinths: what the columns of the stacks mean, and the note of
    :func:`with_plinth`."""
    from rockcli.models import Rigid, Stack

    stacks = [b for b in result.columns if isinstance(b, Stack)]
    if not stacks:
        return ""
    from rockcli.io.units import G

    head = "On a plinth (docs/plinth.md): the body and its plinth rock as two rigid blocks (rocking only, no sliding); "
    if hasattr(result, "curves"):
        head += "a record's capacity is the smallest factor that topples either block (the body falls with its plinth)."
    else:
        head += ("r is the body's peak rotation on the plinth over its own alpha, pQ the plinth's over the slenderness "
                 "of body and plinth as one block (alpha_asm); OVERTURNS body/plinth: which one topples (the body "
                 "falls with its plinth).")
    if any(not isinstance(c.foundation, Rigid) for c in getattr(result, "configurations", ())):
        head += " On bearings gamma counts body and plinth together as the mass the base carries."
    lines = ["", head]
    for s in stacks:
        p = s.plinth
        lines.append(f"  {s.name}: the plinth {p.height:g} m tall x {p.width:g} m wide weighs {s.m2:.3g} times the "
                     f"body{'' if p.mass_ratio is not None else ' (same density)'}; from rest the body lifts off "
                     f"it at {s.body_uplift_acceleration / G:.3f} g, body and plinth together at "
                     f"{s.assembly_uplift_acceleration / G:.3f} g.")
    for s in stacks if hasattr(result, "curves") else ():  # assess fragility: the medians compared
        for c in result.configurations:
            try:
                on, alone = result.curve(s.name, c.header).median, result.curve(s.body.name, c.header).median
            except KeyError:
                continue
            if math.isfinite(on) and math.isfinite(alone) and alone > 0:
                r = on / alone
                word = ("no difference" if abs(r - 1) <= 0.01 else
                        "the plinth makes it more fragile" if r < 1 else "the plinth makes it less fragile")
                lines.append(f"  {c.header}: median capacity of {s.name} over {s.body.name} alone = {r:.2f} "
                             f"({word}).")
    if note:
        lines.append(note)
    return "\n".join(lines)
