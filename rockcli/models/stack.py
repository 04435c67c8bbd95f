"""A body standing on a free plinth: :class:`Plinth`, :class:`Stack` (the two-block rocking assembly on a
rigid foundation) and :func:`parse_plinth_spec` (the command line's ``--on NAME:height=H,width=W[,mass_ratio=M]``).

The derivation is docs/physics-plinth.md. Numbering: block 1 is the body (upper), block 2 the plinth (lower);
the body stands centred on the plinth and is no wider than it. Masses are per unit mass of the body
(``m1 = 1``, ``m2 = mass_ratio``); the model is planar, so "the same density" means masses in proportion to the
areas ``height x width`` of the two rectangles.

Derived quantities of the assembly rocking as one rigid body on a corner of the plinth (pattern P of the note):
its centre of mass at height ``y_c`` over the base, ``R_asm = hypot(b2, y_c)``, ``alpha_asm = atan(b2/y_c)``,
inertia about the corner ``J_asm`` and ``p_asm^2 = M g R_asm / J_asm``, so that it obeys the single block's
Eq (3) with ``(p_asm, alpha_asm)``; its Housner ratio ``eta_asm = K_asm / J_asm`` (angular momentum about the new
corner after / before an impact on the ground, the whole impulse at the new corner).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from rockcli.errors import RockcliInputError
from rockcli.models.block import Block
from rockcli.models.limits import _check, _finite, _num
from rockcli.io.units import G


def _apart(a: float, b: float) -> tuple[str, str]:
    """Two numbers a sentence compares, never rounded to the same text (:func:`rockcli.io.inputs.format_apart`)."""
    from rockcli.io.inputs import format_apart

    return format_apart(a, b)


#: Supported plinth mass over body mass: from a thin slab under a heavy bronze to a massive pedestal.
MASS_RATIO_RANGE = (1e-3, 1e3)


@dataclass(frozen=True)
class Plinth:
    """A free plinth: full ``height`` and ``width`` [m]; ``mass_ratio`` its mass over the body's (None: the
    same density as the body, i.e. the ratio of the areas ``height x width``, the model being planar)."""

    height: float
    width: float
    mass_ratio: float | None = None
    name: str = "plinth"

    def __post_init__(self):
        _check(_finite(self.height) and float(self.height) > 0,
               lambda: f"plinth height must be a positive length in m, got {_num(self.height)}")
        _check(_finite(self.width) and float(self.width) > 0,
               lambda: f"plinth width must be a positive length in m, got {_num(self.width)}")
        object.__setattr__(self, "height", float(self.height))
        object.__setattr__(self, "width", float(self.width))
        if self.mass_ratio is not None:
            lo, hi = MASS_RATIO_RANGE
            ok = _finite(self.mass_ratio) and lo <= float(self.mass_ratio) <= hi
            _check(ok, lambda: f"plinth mass_ratio (its mass over the body's) must lie between {lo:g} and {hi:g}, "
                               f"got {_num(self.mass_ratio)}")
            object.__setattr__(self, "mass_ratio", float(self.mass_ratio))
        self.block  # the plinth's own size and slenderness within the supported ranges

    @property
    def block(self) -> Block:
        """The plinth as a rigid block (its own ``R``, ``alpha``)."""
        return Block.from_dimensions(self.height, self.width, self.name)


@dataclass(frozen=True)
class Stack:
    """The body (:class:`Block`) standing centred on a :class:`Plinth` on a rigid foundation.

    Lengths [m], angles [rad], masses per unit body mass, inertias per unit body mass [m^2].
    """

    body: Block
    plinth: Plinth

    def __post_init__(self):
        if not isinstance(self.body, Block):
            raise RockcliInputError(f"the body must be a rockcli.models.Block, got {type(self.body).__name__}")
        if not isinstance(self.plinth, Plinth):
            raise RockcliInputError(f"the plinth must be a rockcli.models.Plinth, got {type(self.plinth).__name__}")
        _check(self.body.width <= self.plinth.width * (1 + 1e-12),
               lambda: "the body ({} m wide) must be no wider than its plinth ({} m wide): rockcli models a body "
                       "standing centred on its plinth's top".format(*_apart(self.body.width, self.plinth.width)))
        m2 = self.m2
        lo, hi = MASS_RATIO_RANGE
        _check(lo <= m2 <= hi, lambda: f"the plinth's mass over the body's, {m2:.4g} (same density), lies outside the "
                                       f"supported {lo:g} to {hi:g}: give mass_ratio= explicitly")

    # ---- the two blocks -------------------------------------------------------------------------
    @property
    def b1(self) -> float:
        return self.body.b

    @property
    def h1(self) -> float:
        return self.body.h

    @property
    def b2(self) -> float:
        return 0.5 * self.plinth.width

    @property
    def h2(self) -> float:
        return 0.5 * self.plinth.height

    @property
    def R2(self) -> float:
        return math.hypot(self.b2, self.h2)

    @property
    def alpha2(self) -> float:
        return math.atan2(self.b2, self.h2)

    @property
    def m1(self) -> float:
        return 1.0

    @property
    def m2(self) -> float:
        """The plinth's mass per unit body mass (``mass_ratio``, or the ratio of areas)."""
        if self.plinth.mass_ratio is not None:
            return self.plinth.mass_ratio
        return (self.plinth.height * self.plinth.width) / (self.body.height * self.body.width)

    # ---- the assembly as one rigid body on a plinth corner (pattern P) ------------------------------
    @property
    def y_c(self) -> float:
        """Height of the assembly's centre of mass over the ground [m]."""
        return (self.m2 * self.h2 + self.m1 * (2 * self.h2 + self.h1)) / (self.m1 + self.m2)

    @property
    def alpha_asm(self) -> float:
        """Slenderness of the assembly about a plinth corner, ``atan(b2 / y_c)`` [rad]."""
        return math.atan2(self.b2, self.y_c)

    @property
    def R_asm(self) -> float:
        return math.hypot(self.b2, self.y_c)

    @property
    def J_asm(self) -> float:
        """Inertia of the assembly about a base corner of the plinth, per unit body mass [m^2]."""
        J2 = self.m2 * 4.0 / 3.0 * self.R2 ** 2
        J1 = self.m1 * (self.body.R ** 2 / 3.0 + self.b2 ** 2 + (2 * self.h2 + self.h1) ** 2)
        return J1 + J2

    @property
    def p_asm(self) -> float:
        """Frequency parameter of the assembly, ``sqrt(M g R_asm / J_asm)`` [rad/s]."""
        return math.sqrt((self.m1 + self.m2) * G * self.R_asm / self.J_asm)

    @property
    def eta_asm(self) -> float:
        """Housner's ratio of the assembly on the ground, ``K_asm / J_asm``: each block's angular momentum
        about the new corner, ``I_G w + m w (r - O') . (r - O)``, turning about the old corner O."""
        b2, h2, h1 = self.b2, self.h2, self.h1
        K2 = self.m2 * (self.R2 ** 2 / 3.0 + (h2 * h2 - b2 * b2))
        y1 = 2 * h2 + h1
        K1 = self.m1 * (self.body.R ** 2 / 3.0 + (y1 * y1 - b2 * b2))
        return (K1 + K2) / self.J_asm

    # ---- static uplift thresholds ---------------------------------------------------------------
    @property
    def body_uplift_acceleration(self) -> float:
        """Ground acceleration that lifts the body off the still plinth, ``g tan(alpha1)`` [m/s^2]."""
        return G * math.tan(self.body.alpha)

    @property
    def assembly_uplift_acceleration(self) -> float:
        """Ground acceleration that lifts the assembly off the ground, ``g tan(alpha_asm)`` [m/s^2]."""
        return G * self.b2 / self.y_c

    @property
    def uplift_acceleration(self) -> float:
        """The smaller of the two static thresholds [m/s^2]: from rest, the first ground acceleration at which
        something lifts (the body off the plinth, or the assembly off the ground)."""
        return min(self.body_uplift_acceleration, self.assembly_uplift_acceleration)

    # ---- the body's figures, under the stack's name: what a table row of an assessment shows -------------
    @property
    def name(self) -> str:
        """``statue on plinth``: the body's name on the plinth's."""
        return f"{self.body.name} on {self.plinth.name}"

    @property
    def R(self) -> float:
        return self.body.R

    @property
    def alpha(self) -> float:
        return self.body.alpha

    @property
    def alpha_deg(self) -> float:
        return self.body.alpha_deg

    @property
    def b(self) -> float:
        return self.body.b

    @property
    def h(self) -> float:
        return self.body.h

    @property
    def p(self) -> float:
        return self.body.p

    @property
    def height(self) -> float:
        return self.body.height

    @property
    def width(self) -> float:
        return self.body.width

    def as_block(self) -> Block:
        """The assembly as one rigid block on a plinth corner: the single block with ``p_asm`` and
        ``alpha_asm`` (``R`` chosen so that ``3 g/(4 R) = p_asm^2``; its impact ratio is :attr:`eta_asm`, not
        Housner's of that block)."""
        return Block(0.75 * G / self.p_asm ** 2, self.alpha_asm, f"{self.body.name}+{self.plinth.name}")


_KEYS = {"height": "height", "width": "width", "mass_ratio": "mass_ratio", "massratio": "mass_ratio"}


def parse_plinth_spec(text: str) -> Plinth:
    """``"plinth:height=1.0,width=0.6[,mass_ratio=2]"`` -> :class:`Plinth` (lengths in m; the name before the
    colon labels it). Any bad spec raises :class:`RockcliInputError` with one sentence."""
    from rockcli.io.inputs import spec_numbers

    raw = str(text).strip()
    name, colon, rest = raw.partition(":")
    name = name.strip() or "plinth"
    if not colon:
        raise RockcliInputError(f"plinth {raw!r} must be written NAME:height=<m>,width=<m>[,mass_ratio=<plinth mass "
                                f"over the body's>], e.g. plinth:height=1.0,width=0.6")
    values = spec_numbers(rest, f"plinth {raw!r}", _KEYS, "height=..., width=..., mass_ratio=...")
    for need in ("height", "width"):
        if need not in values:
            raise RockcliInputError(f"plinth {raw!r} needs {need}=<m>")
    try:
        return Plinth(values["height"], values["width"], values.get("mass_ratio"), name)
    except RockcliInputError as exc:
        raise RockcliInputError(f"plinth {raw!r}: {exc}") from None
