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
    def monolith(self) -> Block:
        """The column as one rigid block of its height and bottom width (the paper's idealisation)."""
        return Block.from_dimensions(self.height, self.width, self.name)

    def blocks(self) -> list:
        """``[(b, h, m), ...]`` bottom to top: half widths, half heights, masses per unit mass of the column."""
        areas = [h * w for h, w in self.drums]
        total = sum(areas)
        return [(0.5 * w, 0.5 * h, a / total) for (h, w), a in zip(self.drums, areas)]

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
