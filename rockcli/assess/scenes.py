"""The inputs of an assessment: columns, configurations (foundations) and excitations (records).

A *scene* is one column standing on one configuration under one excitation; an assessment runs
every combination. This module turns what the user wrote into those three lists:

* :func:`parse_column_spec`: ``bassae``, ``nemea``, ``NAME:R=<m>,alpha=<deg>``, ``NAME:height=<m>,width=<m>``;
* :func:`parse_configurations`: isolation specs (default: the paper's Table III set);
* :func:`resolve_excitations` (in :mod:`rockcli.assess.excitations`, re-exported here): catalogue ids,
  files, folders and manifests -> :class:`Excitation` objects.
"""

from __future__ import annotations

from typing import Sequence

from rockcli.assess.excitations import (EXCITATION_MODES, EXCITATION_PULSE, EXCITATION_RECORD,  # noqa: F401
                                       MANIFEST_COLUMNS, Excitation, Skipped, Unavailable, is_manifest,
                                       read_manifest, resolve_excitations, table_ii_entries, unavailable_notes)
from rockcli.errors import RockcliInputError
from rockcli.models import Block, Rigid, Stack, build_block, column, parse_isolation_spec
from rockcli.models.spec import Configuration, _short_header  # noqa: F401 (Configuration re-exported)
from rockcli.report.words import column_title  # noqa: F401 (re-exported)

#: The paper's Table III configurations: rigid foundation and linear bearings with
#: T_b = 2, 2.5, 3 s and xi_b = 0.1 (gamma = rockcli.models.DEFAULT_GAMMA = 0.01).
DEFAULT_ISOLATION = ("none", "linear:Tb=2,xi=0.1", "linear:Tb=2.5,xi=0.1", "linear:Tb=3,xi=0.1")



# --------------------------------------------------------------------------------------------------
# columns
# --------------------------------------------------------------------------------------------------

def parse_column_spec(text: str) -> Block:
    """A column from a preset name or a custom spec.

    ``bassae``, ``nemea`` (presets, see :data:`rockcli.models.COLUMN_PRESETS`), or
    ``NAME:R=<m>,alpha=<deg>`` or ``NAME:height=<m>,width=<m>`` (full height and base width). A column of
    drums (:class:`rockcli.models.drums.DrumColumn`, :func:`rockcli.models.drums.parse_drum_spec`): ``nemea-drums``,
    ``bassae-drums`` (presets) or ``NAME:height=<m>,width=<m>,drums=<N>``; it is assessed with friction, beside its
    monolith (:mod:`rockcli.assess.drums`).

    Examples
    --------
    >>> parse_column_spec("statue:R=1.2,alpha=14").name
    'statue'
    """
    from rockcli.models.drums import parse_drum_spec

    drums = parse_drum_spec(text)
    if drums is not None:
        return drums
    raw = str(text).strip()
    name, colon, rest = raw.partition(":")
    name = name.strip()
    if not colon:
        return _preset(name)
    if not name:
        raise RockcliInputError(f"column {raw!r} needs a name before ':' (e.g. statue:R=1.2,alpha=14)")
    from rockcli.io.inputs import spec_numbers

    values = spec_numbers(rest, f"column {raw!r}", {"r": "R", "alpha": "alpha", "height": "height", "width": "width"},
                          "R=<m>, alpha=<deg>, height=<m>, width=<m>")
    return custom_column(name, **values)


def _preset(name: str) -> Block:
    """A preset column (:func:`rockcli.models.column`); an unknown name is refused naming the drum presets too."""
    from rockcli.models.block import COLUMN_PRESETS
    from rockcli.models.drums import DRUM_PRESETS

    key = name.lower()
    if key in COLUMN_PRESETS:
        return column(name)
    import difflib

    close = difflib.get_close_matches(key, list(COLUMN_PRESETS) + list(DRUM_PRESETS), n=1)
    raise RockcliInputError(
        f"unknown body {name!r}" + (f" (did you mean {close[0]!r}?)" if close else "")
        + f": the presets are the columns {' and '.join(sorted(COLUMN_PRESETS))} and the same as stacks of drums "
          f"{' and '.join(sorted(DRUM_PRESETS))}; a body of your own is written NAME:R=<m>,alpha=<deg> or "
          f"NAME:height=<m>,width=<m> (and ,drums=<N> for a column of drums), e.g. "
          f"{key or 'statue'}:height=1.7,width=0.45")


def custom_column(name: str, R=None, alpha=None, height=None, width=None, *, labels: dict | None = None) -> Block:
    """A custom block from ``R`` [m] and ``alpha`` [deg], or from ``height`` and ``width`` [m].

    ``labels`` names the quantities in error messages (see :func:`rockcli.models.build_block`;
    the CLI passes its flags).
    """
    return build_block(R=R, alpha_deg=alpha, height=height, width=width, name=name, labels=labels,
                       allow_preset=False, context="" if labels else f"column {name!r}")


# --------------------------------------------------------------------------------------------------
# configurations
# --------------------------------------------------------------------------------------------------

def check_scenes(columns, excitations, configurations) -> tuple[list, list, list]:
    """The three lists of an assessment (:func:`rockcli.assess.run_assessment`, :func:`rockcli.assess.run_fragility`)
    with the types they must hold, else one sentence naming the argument and what was given."""
    from rockcli.io.inputs import as_list, check_type
    from rockcli.solve.slide_many import Sliding

    cols = as_list(columns, "columns", "a list of Block (parse_column_spec('bassae'), ...)",
                   one=(Block, Stack, Sliding))
    exc = as_list(excitations, "excitations", "a list of Excitation (resolve_excitations(...))", one=Excitation)
    conf = as_list(configurations, "configurations", "a list of Configuration (parse_configurations(...))",
                   one=Configuration)
    for items, kind, what, expected in ((cols, (Block, Stack, Sliding), "columns", "a Block"),
                                        (exc, Excitation, "excitations", "an Excitation (resolve_excitations)"),
                                        (conf, Configuration, "configurations", "a Configuration "
                                                                                "(parse_configurations)")):
        for x in items:
            if kind is Excitation and isinstance(x, list):  # the usual slip: the pair resolve_excitations returns
                raise RockcliInputError("excitations must be the Excitation objects of resolve_excitations, "
                                        "unpacked: excitations, unavailable = resolve_excitations([...]); got a list")
            check_type(x, kind, f"{what}: each item", expected)
    if not cols:
        raise RockcliInputError("no body to assess: name a preset (bassae, nemea) or give a body of your own")
    if not exc:
        raise RockcliInputError("no record to run: excitations is empty (resolve_excitations found none; the second "
                                "list it returns, the unavailable records, says why)")
    if not conf:
        raise RockcliInputError("no isolation configuration to assess")
    return cols, exc, conf


def check_flag(value, what: str) -> bool:
    """``value`` when it is True or False (a numpy bool too), else one sentence: ``margin="no"`` is no False (a
    non-empty string is true: it would run the margins)."""
    import numpy as np

    from rockcli.io.inputs import check_type

    return bool(check_type(value, (bool, np.bool_), what, "True or False"))


def check_count(value, what: str, expected: str, *, lo: int = 1, none: bool = True):
    """``value`` as an int when it is a whole number >= ``lo`` (not a bool) or, with ``none``, None; else one
    sentence."""
    if value is None and none:
        return None
    import numpy as np

    from rockcli.io.inputs import check_type

    check_type(value, (int, np.integer), what, expected)
    if value < lo:
        raise RockcliInputError(f"{what} must be {expected}, got {value}")
    return int(value)


def check_scale_search(scenes, grid, known=None, progress=None) -> list:
    """The arguments of :func:`rockcli.assess.find_overturn_scales` checked for their types: ``scenes`` a list of
    ``(Block, foundation, Record or pulse)``, ``grid`` increasing positive finite factors, ``known`` None or one
    Response per scene, ``progress`` None or callable; else one sentence naming the argument and what was given.
    Returns the scenes as a list."""
    import math

    from rockcli.io.inputs import as_list, check_type, type_words
    from rockcli.pulses.shapes import Pulse
    from rockcli.records.record import Record
    from rockcli.solve import Response
    from rockcli.solve.options import check_foundation
    from rockcli.solve.slide_many import SlideRun, Sliding
    from rockcli.solve.stack_many import StackRun

    expected = "a list of (block, foundation, motion) scenes, e.g. [(column('bassae'), Rigid(), record)]"
    scenes = as_list(scenes, "scenes", expected)
    for i, scene in enumerate(scenes):
        if not isinstance(scene, (tuple, list)) or len(scene) != 3:
            raise RockcliInputError(f"scenes: scene {i} must be a (block, foundation, motion) tuple, got "
                                    f"{type_words(scene)}")
        block, foundation, motion = scene
        check_type(block, (Block, Stack, Sliding), f"scenes: scene {i}: the block",
                   "a Block (column('bassae'), Block(R, alpha)), a Stack or a Sliding")
        check_foundation(foundation, f"scenes: scene {i}: the foundation")
        check_type(motion, (Record, Pulse), f"scenes: scene {i}: the motion", "a Record (read_record) or a pulse "
                                                                            "(make_pulse)")
    try:
        factors = [float(g) for g in as_list(grid, "grid", "a list of increasing scale factors")]
    except (TypeError, ValueError):
        raise RockcliInputError(f"grid must be a list of increasing scale factors, got {type_words(grid)}") from None
    if not factors or not all(math.isfinite(g) and g > 0 for g in factors) or \
            any(b <= a for a, b in zip(factors, factors[1:])):
        raise RockcliInputError(f"grid must be a non-empty list of finite positive scale factors in increasing "
                                f"order, got {type_words(grid)}")
    if known is not None:
        known = as_list(known, "known", "None or one Response per scene (at scale 1)")
        if len(known) != len(scenes):
            raise RockcliInputError(f"known must hold one Response per scene: {len(known)} for {len(scenes)} scenes")
        for r in known:
            check_type(r, (Response, StackRun, SlideRun), "known: each item", "a Response (simulate(...))")
    if progress is not None and not callable(progress):
        raise RockcliInputError(f"progress must be None or a function progress(n), got {type_words(progress)}")
    return scenes


def parse_configurations(specs: Sequence[str] | None = None) -> list[Configuration]:
    """Parse isolation specs (default :data:`DEFAULT_ISOLATION`) with column headers for the table.

    Headers are short (``none``, ``Tb=2s``) when that is unambiguous, else the spec as written.
    Any spec :func:`rockcli.models.parse_isolation_spec` accepts works.
    """
    from rockcli.io.inputs import as_list, check_type

    specs = [] if specs is None else as_list(specs, "specs", "a list of isolation specs ('none', 'linear:Tb=2.5', "
                                                          "...)", one=str)
    specs = specs or list(DEFAULT_ISOLATION)
    for s in specs:
        check_type(s, str, "specs: each spec", "an isolation spec such as 'none' or 'linear:Tb=2.5'")
    out, seen = [], set()
    for s in specs:
        f = parse_isolation_spec(s)
        if f.label in seen:
            continue  # the same foundation twice: run it once
        seen.add(f.label)
        out.append((s.strip(), f))
    headers = [_short_header(f, s) for s, f in out]
    if len(set(headers)) < len(headers):
        headers = ["none" if isinstance(f, Rigid) else s for s, f in out]
    return [Configuration(s, f, h) for (s, f), h in zip(out, headers)]
