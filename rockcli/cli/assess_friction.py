"""``assess column --friction MU`` and ``assess fragility --friction MU``: every body with Coulomb friction at its
contacts, as a model (docs/physics-sliding.md). Each column becomes a :class:`rockcli.solve.slide_many.Sliding`
(a body alone slides on the floor with MU, or the base's MU; a body on its plinth, ``--on``, with ``base=..`` on the
floor and ``joint=..`` on the plinth); where nothing slides the rows are the rocking model's, bit for bit; the
margin is the smallest factor that topples the body or slides it off its plinth."""

from __future__ import annotations

import click

from rockcli.errors import RockcliInputError

FRICTION_ASSESS_HELP = ("Coulomb friction as a model (docs/physics-sliding.md): every contact may stick, slide, "
                        "rock or rock while it slides; MU for every contact (a column of drums: one MU, required), "
                        "or with --on base=MU,joint=MU. A scene where nothing slides keeps the rocking answer; the "
                        "margin is the smallest factor that topples the body or slides it off its plinth. On the "
                        "ground and on linear bearings.")


def friction_option(func):
    return click.option("--friction", default=None, metavar="MU|base=MU,joint=MU", help=FRICTION_ASSESS_HELP)(func)


def with_friction(columns, configurations, friction, *, isolation_given: bool, refused=(), restitution=None):
    """``(columns, configurations, note)``: every column with friction (module notes), the configurations the
    friction model runs on (the rigid foundation and linear bearings with gamma > 0: a default set keeps those with a
    note, one given with --isolation is refused in one sentence), the note."""
    from rockcli.cli.simulate_friction import parse_friction
    from rockcli.models import LinearIsolation, Rigid, Stack
    from rockcli.solve.slide_many import Sliding

    if friction is None:
        return columns, configurations, ""
    bad = [name for name, given in refused if given]
    if bad:
        raise RockcliInputError(f"--friction runs the friction model from rest under the horizontal ground motion "
                                f"with the plastic impact law: {', '.join(bad)} "
                                f"{'is' if len(bad) == 1 else 'are'} not taken with --friction yet")
    stacked = any(isinstance(c, Stack) for c in columns)
    mu = parse_friction(friction, stacked)
    out = []
    for c in columns:
        if isinstance(c, Stack):
            out.append(Sliding(c, mu))
        else:
            out.append(Sliding(c, mu[0] if isinstance(mu, tuple) else mu))

    def runs(conf) -> bool:
        f = conf.foundation
        return isinstance(f, Rigid) or (isinstance(f, LinearIsolation) and f.gamma > 0)

    kept = [c for c in configurations if runs(c)]
    if restitution is not None and any(not isinstance(c, Stack) for c in columns) and \
            any(not isinstance(c.foundation, Rigid) for c in kept):
        raise RockcliInputError("--friction with --restitution runs on the ground, or for a body on its plinth: a "
                                "single block on bearings reads the restitution another way (docs/simulate.md); "
                                "give --isolation none")
    note = ""
    if len(kept) < len(configurations):
        dropped = [c.header for c in configurations if not runs(c)]
        if isolation_given:
            raise RockcliInputError(f"--friction runs on the ground and on linear bearings with a base of finite mass "
                                    f"(gamma > 0): not on {', '.join(dropped)}")
        note = (f"Friction: the friction model runs on the ground and on linear bearings with a base of finite "
                f"mass, so {', '.join(dropped)} {'is' if len(dropped) == 1 else 'are'} left out.")
    return out, kept, note
