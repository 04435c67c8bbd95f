"""The vertical ground motion of an assessment's records: :func:`attach_verticals`.

Each record of an assessment (or of a fragility suite) may run under a vertical ground acceleration:
its own vertical component, read from the same multi-component file (``--vertical-component UP``), or
one vertical motion for every record (a record file ``--vertical``, a pulse ``--vertical-pulse``). The
record then carries it (:func:`rockcli.solve.with_vertical`) through every run of the assessment: the
table, the margin search, the neighbourhood, the tolerance checks and the histories. The scale factors
of the margin search multiply the horizontal motion only (the recorded vertical motion is kept as it
is, so the uplift condition ``s |a_h| > (g + a_v) tan(alpha)`` stays monotone in ``s``: the margin
search's pruning below the first uplift still holds, and ``g + a_v > 0`` is checked once).

A record that cannot carry the vertical motion (a catalogued pulse in place of a record, a file without
the component, another time base, ``g + a_v <= 0``) becomes an error row with the reason; the others run.
Vertical motion is modelled on a rigid foundation only (the command refuses isolated configurations).
"""

from __future__ import annotations

from dataclasses import replace
from pathlib import Path
from typing import Sequence

from rockcli.assess.excitations import EXCITATION_PULSE, Excitation
from rockcli.errors import RockcliInputError
from rockcli.report.tables import vertical_labels  # noqa: F401 (re-exported: the labels are words of the report)


def _record_path(x: Excitation):
    """The file a record excitation was read from (the first component's for a pair)."""
    motion = x.pair[0] if x.pair else x.motion
    return (getattr(motion, "meta", {}) or {}).get("path") or x.source


def _own_component(x: Excitation, component: str, read_kwargs: dict, scale: float, cache: dict):
    """``(vertical record, label)``: component ``component`` of the file ``x`` was read from."""
    from rockcli.records.components import component_name, select_component
    from rockcli.records.reader import read_components

    path = _record_path(x)
    if path not in cache:
        try:
            comps = read_components(path, **{k: v for k, v in read_kwargs.items() if v is not None})
            cache[path] = select_component(comps, component, str(path))
        except RockcliInputError as exc:
            cache[path] = exc
    got = cache[path]
    if isinstance(got, RockcliInputError):
        raise got
    from rockcli.io.inputs import check_scale, format_number

    vertical = got if check_scale(scale, got.pga_g, "--vertical-scale", "the vertical component") == 1.0 else \
        got.scaled(scale)
    return vertical, (f"component {component_name(got)} of {Path(path).name}"
                      + (f" x {format_number(scale)}" if scale != 1.0 else ""))


def attach_verticals(excitations: Sequence[Excitation], *, component: str | None = None, motion=None,
                     label: str = "", scale: float = 1.0, read_kwargs: dict | None = None) -> list:
    """The excitations with their vertical ground motion attached to each record.

    Parameters
    ----------
    excitations : sequence of Excitation
    component : str, optional
        Name of the vertical component in each record's own file (``UP``, ``HNZ``, ``Z``, ...;
        :func:`rockcli.records.components.select_component`).
    motion : Record or pulse, optional
        One vertical motion [m/s^2, upward positive] for every record (instead of ``component``).
    label : str
        What ``motion`` is, for the outputs.
    scale : float
        Multiplies each record's own vertical component (``motion`` comes scaled).
    read_kwargs : dict
        ``units``/``dt`` filling in what a file does not state (as the records were read).

    Returns
    -------
    list of Excitation
        In order; an excitation that cannot take the vertical motion carries the reason in ``error``
        (and no motion), the others a record that carries its vertical motion.
    """
    from rockcli.models import Rigid
    from rockcli.solve import with_vertical
    from rockcli.solve.excitation import _vertical_arrays
    from rockcli.io.units import G

    if (component is None) == (motion is None):
        raise RockcliInputError("give the vertical motion as exactly one of a component name or a motion")
    cache: dict = {}
    out = []
    for x in excitations:
        if x.motion is None:
            out.append(x)
            continue
        try:
            if x.kind == EXCITATION_PULSE or not hasattr(x.motion, "acc"):
                raise RockcliInputError(f"{x.label} runs as its catalogued pulse, which has no vertical component: "
                                        f"give the record file (--excitation record)")
            if component is not None:
                vertical, what = _own_component(x, component, dict(read_kwargs or {}), scale, cache)
            else:
                vertical, what = motion, label
            _vertical_arrays(vertical, x.motion, Rigid(), G)  # the same time base, g + a_v > 0
        except RockcliInputError as exc:
            out.append(replace(x, motion=None, error=f"{x.label}: vertical motion: {exc}"))
            continue
        out.append(replace(x, motion=with_vertical(x.motion, vertical, what)))
    return out

