"""A column as it stands: a stack of rigid drums (and, on top, a capital), free at every joint
(:class:`DrumColumn`).

Each drum is a rectangle in the plane of rocking (full ``height`` and ``width`` [m]), centred on the one below at
rest. Masses are in proportion to the areas ``height x width`` (the model is planar, as for the body on its
plinth: docs/physics-plinth.md) and given per unit mass of the whole column; a drum's central inertia is the
rectangle's, ``m (b^2 + h^2)/3`` with ``b``, ``h`` its half width and half height. A drum may be wider than the
one below (a capital on the top drum): its contact is then the top below, and a drum that slides keeps the part
of its base that still overlaps the top below as its contact (docs/physics-drums.md).

The mechanics is the friction driver's chain (:mod:`rockcli.kernels.chain`) with ``n`` drums; a column of one
drum is a single block, of two a body on its plinth.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from rockcli.models.block import Block
from rockcli.models.limits import _check, _finite, _num

#: The most drums a column may have (the complementarity solve grows with them; real columns have 1-20).
MAX_DRUMS = 32

#: The paper's two columns as stacks of equal drums: (full height [m], base drum diameter [m], drums, the source).
#: The paper gives the height and the base drum's diameter of each column and, for Nemea, the number of drums;
#: the drums are taken equal, of the base diameter (the shaft's taper and the capital are not in the paper: a
#: column you have measured is given drum by drum, docs/physics-drums.md).
DRUM_PRESETS = {
    "nemea-drums": (10.33, 1.52, 13, "Temple of Zeus at Nemea: 13 drums (the paper: 'All columns consist of 13 "
                                     "drums')"),
    "bassae-drums": (5.95, 1.11, 6, "Temple of Apollo at Bassae: 6 drums, an assumption (the paper: 'The number of "
                                    "drums in each column is not constant'; give drums=N for a column you know)"),
}


#: The words of a drum column's NAME on the command line (``assess column``), after ``NAME:``.
DRUM_SPEC_KEYS = {"height": "height", "width": "width", "drums": "drums"}


def parse_drum_spec(text) -> "DrumColumn | None":
    """The drum column a NAME of ``assess column`` names: a preset of :data:`DRUM_PRESETS` (``nemea-drums``), or
    ``NAME:height=<m>,width=<m>,drums=<N>`` (``N`` equal drums of the base width); None when ``text`` names no drum
    column (a preset block, a custom block without ``drums=``), one sentence when a drum spec is wrong."""
    from rockcli.errors import RockcliInputError
    from rockcli.io.inputs import spec_numbers

    raw = str(text).strip()
    name, colon, rest = raw.partition(":")
    name = name.strip()
    if not colon:
        return drum_preset(name) if name.lower() in DRUM_PRESETS else None
    if "drums" not in [part.partition("=")[0].strip().lower() for part in rest.split(",")]:
        return None
    what = f"column {raw!r}"
    if not name:
        raise RockcliInputError(f"{what} needs a name before ':' (e.g. shaft:height=6,width=1.1,drums=6)")
    values = spec_numbers(rest, what, DRUM_SPEC_KEYS, "height=<m>, width=<m>, drums=<N>")
    missing = [k for k in DRUM_SPEC_KEYS if k not in values]
    if missing:
        raise RockcliInputError(f"{what}: a column of drums needs height=<m>, width=<m> and drums=<N> (missing: "
                                f"{', '.join(missing)})")
    n = values["drums"]
    if not (n == int(n) and 1 <= n <= MAX_DRUMS):
        raise RockcliInputError(f"{what}: drums must be a whole number from 1 to {MAX_DRUMS}, got {n:g}")
    return DrumColumn.uniform(values["height"], values["width"], int(n), name)


def monolith_beside(column: "DrumColumn") -> Block:
    """The monolith an assessment runs beside ``column``: for a preset (``nemea-drums``) the paper's column itself
    (:func:`rockcli.models.column`, named ``nemea``: the same height and width, the monolithic idealisation of the
    paper); else :attr:`DrumColumn.monolith` named ``<name> monolith``."""
    from rockcli.models.block import COLUMN_PRESETS, column as preset_column

    key = column.name.lower()
    if key in DRUM_PRESETS and key.endswith("-drums") and key[:-len("-drums")] in COLUMN_PRESETS:
        height, width, n, _ = DRUM_PRESETS[key]
        if column == DrumColumn.uniform(height, width, n, column.name):
            return preset_column(key[:-len("-drums")])
    m = column.monolith
    return Block(m.R, m.alpha, f"{column.name} monolith")


def drum_preset(name: str) -> "DrumColumn":
    """A named drum column (:data:`DRUM_PRESETS`)."""
    key = str(name).strip().lower()
    if key not in DRUM_PRESETS:
        from rockcli.errors import RockcliInputError

        raise RockcliInputError(f"unknown drum column {name!r}: the presets are {', '.join(sorted(DRUM_PRESETS))}")
    height, width, n, _ = DRUM_PRESETS[key]
    return DrumColumn.uniform(height, width, n, key)


@dataclass(frozen=True)
class DrumColumn:
    """A column of drums, bottom to top: ``drums`` a tuple of ``(height, width)`` [m]; ``name`` for tables."""

    drums: tuple
    name: str = "column"

    def __post_init__(self):
        drums = tuple(self.drums)
        _check(1 <= len(drums) <= MAX_DRUMS,
               lambda: f"a drum column needs 1 to {MAX_DRUMS} drums, got {len(drums)}")
        clean = []
        for i, d in enumerate(drums):
            _check(isinstance(d, (tuple, list)) and len(d) == 2,
                   lambda: f"drum {i + 1}: give (height, width) in m, got {d!r}")
            h, w = d
            _check(_finite(h) and float(h) > 0, lambda: f"drum {i + 1}: height must be a positive length in m, "
                                                       f"got {_num(h)}")
            _check(_finite(w) and float(w) > 0, lambda: f"drum {i + 1}: width must be a positive length in m, "
                                                       f"got {_num(w)}")
            clean.append((float(h), float(w)))
        object.__setattr__(self, "drums", tuple(clean))
        for i, (h, w) in enumerate(self.drums):
            # each drum's own size and slenderness within the supported ranges of a block
            Block.from_dimensions(h, w, f"drum {i + 1}")

    @classmethod
    def uniform(cls, height: float, width: float, n: int, name: str = "column") -> "DrumColumn":
        """``n`` equal drums making a shaft ``height`` tall and ``width`` wide."""
        _check(isinstance(n, int) and not isinstance(n, bool) and n >= 1,
               lambda: f"drums must be a whole number >= 1, got {n!r}")
        _check(_finite(height) and float(height) > 0,
               lambda: f"column height must be a positive length in m, got {_num(height)}")
        return cls(tuple((float(height) / n, width) for _ in range(n)), name)

    @property
    def n(self) -> int:
        return len(self.drums)

    @property
    def height(self) -> float:
        return sum(h for h, _ in self.drums)

    @property
    def width(self) -> float:
        """The width of the bottom drum (the column's footprint)."""
        return self.drums[0][1]

    @property
    def R(self) -> float:
        """The column's semi-diagonal as one block [m] (its monolith's)."""
        return self.monolith.R

    @property
    def alpha(self) -> float:
        """The column's slenderness as one block [rad] (its monolith's: the base's static threshold is ``tan``)."""
        return self.monolith.alpha

    @property
    def alpha_deg(self) -> float:
        return math.degrees(self.alpha)

    @property
    def monolith(self) -> Block:
        """The column as one rigid block of its height and bottom width (the paper's idealisation)."""
        return Block.from_dimensions(self.height, self.width, self.name)

    def blocks(self) -> list:
        """``[(b, h, m), ...]`` bottom to top: half widths, half heights, masses per unit mass of the top drum (the
        areas' ratios), read as a body on its plinth reads them (the top drum a :class:`Block`, the others as a
        plinth), so that one drum is that block and two are that body on that plinth, to the last bit."""
        top = Block.from_dimensions(*self.drums[-1])
        ref = top.height * top.width
        return [(0.5 * w, 0.5 * h, (h * w) / ref) for h, w in self.drums[:-1]] + [(top.b, top.h, 1.0)]

    def joint_names(self) -> list:
        """``base`` (the bottom drum on the ground), then ``joint 1`` .. (under drum 2, 3, ...)."""
        return ["base"] + [f"joint {j}" for j in range(1, self.n)]

    def static_thresholds(self) -> list:
        """Per contact, bottom to top: the ground acceleration [m/s^2 over g] at which everything above it, standing
        centred as one rigid body, starts to rock on it (``tan`` of its slenderness about the contact's corner:
        ``b_contact M_above / sum m_i y_i``, ``y_i`` heights of the centres over the contact). Without friction
        limits the smallest opens first."""
        blocks = self.blocks()
        out = []
        for j in range(self.n):
            bc = blocks[j][0] if j == 0 else min(blocks[j][0], blocks[j - 1][0])
            mass = 0.0
            ym = 0.0
            y0 = 0.0
            for (b, h, m) in blocks[j:]:
                mass += m
                ym += m * (y0 + h)
                y0 += 2.0 * h
            out.append(bc * mass / ym)
        return out

    def __str__(self) -> str:
        return (f"{self.name}: {self.n} drums, {self.height:.3f} m tall, {self.width:.3f} m wide at the base "
                f"(monolith R = {math.hypot(self.height, self.width) / 2:.3f} m)")
