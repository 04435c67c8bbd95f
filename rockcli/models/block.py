"""The rigid block (:class:`Block`), the paper's column presets, :func:`build_block` (the one block
builder of the library and the CLI) and :func:`impact_coefficient` (the ratio of angular
velocities across an impact).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from rockcli.errors import RockcliInputError
from rockcli.io.inputs import format_number
from rockcli.models.limits import ALPHA_MIN_DEG, R_RANGE_M, _check, _finite, _num
from rockcli.io.units import G


@dataclass(frozen=True)
class Block:
    """A rigid rectangular block rocking about its base corners.

    Parameters
    ----------
    R : float
        Semi-diagonal, centre of mass to a base corner [m], > 0.
    alpha : float
        Slenderness ``atan(b / h)`` [rad], 0 < alpha < pi/2.
    name : str
        Label used in reports.
    """

    R: float
    alpha: float
    name: str = "block"

    def __post_init__(self):
        _check_block(self.R, self.alpha)
        object.__setattr__(self, "R", float(self.R))
        object.__setattr__(self, "alpha", float(self.alpha))

    @classmethod
    def from_dimensions(cls, height: float, width: float, name: str = "block") -> "Block":
        """Block of full ``height`` and base ``width`` [m] (for a column: the base drum diameter)."""
        _check(_finite(height) and float(height) > 0,
               lambda: f"block height must be a positive length in m, got {_num(height)}")
        _check(_finite(width) and float(width) > 0,
               lambda: f"block width must be a positive length in m, got {_num(width)}")
        h, b = 0.5 * float(height), 0.5 * float(width)
        R, alpha = math.hypot(h, b), math.atan2(b, h)
        _check_block(R, alpha, dimensions=(height, width))
        return cls(R, alpha, name)

    @classmethod
    def from_degrees(cls, R: float, alpha_deg: float, name: str = "block") -> "Block":
        """Block from its semi-diagonal [m] and slenderness in degrees."""
        _check(_finite(alpha_deg) and 0 < float(alpha_deg) < 90,
               lambda: f"block slenderness alpha must lie strictly between 0 and 90 degrees, got "
                       f"{_num(alpha_deg)}")
        _check_block(R, math.radians(float(alpha_deg)), alpha_deg=alpha_deg)  # quoting the degrees as given
        return cls(R, math.radians(float(alpha_deg)), name)

    @property
    def b(self) -> float:
        """Half width [m]."""
        return self.R * math.sin(self.alpha)

    @property
    def h(self) -> float:
        """Half height, height of the centre of mass [m]."""
        return self.R * math.cos(self.alpha)

    @property
    def height(self) -> float:
        return 2.0 * self.h

    @property
    def width(self) -> float:
        return 2.0 * self.b

    @property
    def alpha_deg(self) -> float:
        return math.degrees(self.alpha)

    @property
    def p(self) -> float:
        """Frequency parameter ``sqrt(3 g / (4 R))`` [rad/s] (rectangular block, I_o = 4/3 m R^2)."""
        return math.sqrt(0.75 * G / self.R)

    @property
    def uplift_acceleration(self) -> float:
        """Base acceleration that uplifts the block from rest, ``g tan(alpha)`` [m/s^2]."""
        return G * math.tan(self.alpha)

    @property
    def housner_restitution(self) -> float:
        """Housner's ratio of angular velocities across an impact on a rigid base, ``1 - 1.5 sin^2 alpha``."""
        return 1.0 - 1.5 * math.sin(self.alpha) ** 2


def _check_block(R, alpha, dimensions=None, alpha_deg=None) -> None:
    """Raise one sentence when R [m] or alpha [rad] lies outside :data:`R_RANGE_M` / :data:`ALPHA_MIN_DEG`.

    The slenderness is quoted as it was given: ``alpha_deg`` (degrees, :meth:`Block.from_degrees`), else the
    radians of :class:`Block` with their degrees, or (``dimensions``: the ``(height, width)`` they were derived
    from, quoted as given) the degrees to 12 significant digits (:func:`rockcli.io.inputs.format_number` with
    ``derived=True``). The sentences are written only for a check that fails (a block is built thousands of times
    in a sweep)."""
    _check(_finite(R) and float(R) > 0, lambda: f"block size R must be a positive length in m, got {_num(R)}")
    _check(_finite(alpha) and 0 < float(alpha) < math.pi / 2,
           lambda: f"block slenderness alpha must lie strictly between 0 and 90 degrees, got {_num(alpha)} rad")

    def source() -> str:
        return "" if dimensions is None else f" (from height {_num(dimensions[0])} m and width {_num(dimensions[1])} m)"

    lo, hi = R_RANGE_M
    _check(lo <= float(R) <= hi,  # a derived R: the source quotes the input
           lambda: f"block size R = {_num(R) if dimensions is None else format_number(R, derived=True)} m{source()} "
                   f"lies outside the supported {lo:g} m to {hi:g} m (a figurine 2 cm tall to a 140 m monolith; "
                   f"smaller bodies rock too fast to integrate, p = sqrt(3 g/4 R))")
    deg = math.degrees(float(alpha))

    def shown() -> str:
        return (f"{_num(alpha_deg)} deg" if alpha_deg is not None else f"{format_number(deg, derived=True)} deg"
                if dimensions is not None else f"{_num(alpha)} rad ({deg:.3g} deg)")

    _check(deg >= ALPHA_MIN_DEG * (1 - 1e-12),
           lambda: f"block slenderness alpha = {shown()}{source()} is below the supported {ALPHA_MIN_DEG:g} deg "
                   f"(h/b = {1 / math.tan(float(alpha)):.3g} > 57): such a needle uplifts under ground noise, "
                   f"rocks through ever longer impact cascades, and its theta/alpha means nothing")


#: The temple columns of the paper (monolithic idealisation): full height and base drum diameter [m].
COLUMN_PRESETS = {
    "bassae": (5.95, 1.11, "Temple of Apollo at Bassae"),
    "nemea": (10.33, 1.52, "Temple of Zeus at Nemea"),
}


def column(name: str) -> Block:
    """A named column preset (``bassae`` or ``nemea``) as a :class:`Block`."""
    key = str(name).strip().lower()
    if key not in COLUMN_PRESETS:
        import difflib

        close = difflib.get_close_matches(key, COLUMN_PRESETS, n=1)
        raise RockcliInputError(
            f"unknown body {name!r}" + (f" (did you mean {close[0]!r}?)" if close else "")
            + f": the presets are the columns {' and '.join(sorted(COLUMN_PRESETS))}; a body of your own is written "
              f"NAME:R=<m>,alpha=<deg> or NAME:height=<m>,width=<m>, e.g. {key or 'statue'}:height=1.7,width=0.45")
    height, width, _ = COLUMN_PRESETS[key]
    return Block.from_dimensions(height, width, key)


#: How :func:`build_block` names each quantity in its messages (the library's words). The CLI
#: passes its flag names instead (``{"R": "--R", ...}``).
BLOCK_LABELS = {"preset": "a preset name", "R": "R (m)", "alpha": "alpha (deg)", "height": "height (m)",
                "width": "width (m)"}


def build_block(*, preset: str | None = None, R: float | None = None, alpha_deg: float | None = None,
                height: float | None = None, width: float | None = None, name: str | None = None,
                labels: dict | None = None, allow_preset: bool = True, context: str = "",
                check_only: bool = False) -> Block | None:
    """The :class:`Block` given by exactly one of three forms: a preset, R with alpha, height with width.

    The one block builder of rockcli (the library's custom columns and the CLI's block options).

    Parameters
    ----------
    preset : str, optional
        A column preset (:data:`COLUMN_PRESETS`); with ``allow_preset=False`` it is not offered.
    R, alpha_deg : float, optional
        Semi-diagonal [m] and slenderness [deg], together.
    height, width : float, optional
        Full height and base width [m], together.
    name : str, optional
        Label of a custom block (default ``R<R>m-alpha<alpha>deg`` or ``<height>x<width>m``).
    labels : dict, optional
        How to name ``preset``, ``R``, ``alpha``, ``height``, ``width`` in error messages
        (default :data:`BLOCK_LABELS`; the CLI gives its flags, e.g. ``{"R": "--R"}``).
    context : str
        Prefix of error messages (e.g. ``"column 'statue'"``).
    check_only : bool
        Only check that exactly one form is given (and return None).

    Raises
    ------
    RockcliInputError
        No form or more than one; half a pair; values out of range (from :class:`Block`).
    """
    L = {**BLOCK_LABELS, **(labels or {})}
    head = f"{context}: " if context else ""
    by_preset = allow_preset and preset is not None
    by_r = R is not None or alpha_deg is not None
    by_dim = height is not None or width is not None
    pairs = f"{L['R']} with {L['alpha']}, or {L['height']} with {L['width']}"
    n = by_preset + by_r + by_dim
    if n != 1:
        if allow_preset:
            raise RockcliInputError(f"{head}give the block as exactly one of {L['preset']}, {pairs}")
        raise RockcliInputError(f"{head}give {pairs}" + (", not both" if n > 1 else ""))
    if check_only:  # exactly one form was given; the caller builds it
        return None
    if by_preset:
        return column(preset)
    if by_r:
        if R is None or alpha_deg is None:
            raise RockcliInputError(f"{head}{L['R']} and {L['alpha']} go together")
        return Block.from_degrees(R, alpha_deg, name or f"R{R:g}m-alpha{alpha_deg:g}deg")
    if height is None or width is None:
        raise RockcliInputError(f"{head}{L['height']} and {L['width']} go together")
    return Block.from_dimensions(height, width, name or f"{height:g}x{width:g}m")


def impact_coefficient(alpha: float, gamma: float) -> float:
    """Ratio theta_dot after / before an impact, with momentum conserved (paper Eq 18, corrected).

    With ``gamma = m/(m+m_b)`` and ``k = (4 - 3 gamma) cot^2(alpha)``: ``(k - 2)/(k + 4)``.
    ``gamma = 0`` (rigid foundation) gives Housner's ``1 - 1.5 sin^2(alpha)``. A block too squat
    for this ratio to be positive stops rocking at its first impact (ratio 0).
    """
    cot2 = (math.cos(alpha) / math.sin(alpha)) ** 2
    k = (4.0 - 3.0 * gamma) * cot2
    return max(0.0, (k - 2.0) / (k + 4.0))


#: Height or width [m] above which a body is larger than any free-standing body ever set up (the tallest
#: monolith erected, the Lateran obelisk in Rome, is 32 m tall): such a size is most likely centimetres
#: written as metres (``statue:height=180,width=50``, a 180 m statue). :func:`size_warning` says so and
#: the run goes on: sizes up to R = 100 m are accepted (:data:`R_RANGE_M`), only a warning is given.
PLAUSIBLE_SIZE_M = 35.0


def size_warning(block: Block) -> str:
    """One sentence when ``block`` is taller or wider than :data:`PLAUSIBLE_SIZE_M` (sizes that look like
    centimetres), naming the sizes in centimetres' reading; else an empty string."""
    h, w = block.height, block.width
    if max(h, w) <= PLAUSIBLE_SIZE_M:
        return ""
    return (f"{block.name} is {h:.3g} m tall and {w:.3g} m wide, larger than any free-standing body (the tallest "
            f"monolith ever set up, the Lateran obelisk, is 32 m); sizes are in metres: if these are centimetres, "
            f"give height={h / 100:.3g},width={w / 100:.3g}")
