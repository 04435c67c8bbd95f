"""What a spectrum is run on: the pulse choice, the isolation with ``T_b / T_p`` fixed, and the family.

Dimensionless presentation
--------------------------
A map is drawn over ``x = omega_p / p`` and ``y = a_p / (g tan alpha)`` for a block of slenderness
``alpha``. Written in the time ``p t``, Eq (3) (rigid foundation) depends only on ``alpha``,
``a_p / g`` and ``omega_p / p``; Eqs (7)-(11) (isolated base) in addition on ``omega_b / omega_p =
T_p / T_b``, ``xi`` and ``gamma`` (``gamma R p^2 / g = 0.75 gamma``). So a map does not depend on the
block size as long as ``T_b / T_p`` is kept fixed over the map, as the paper does. rockcli runs
every cell on one reference block, ``R = REFERENCE_R = 1 m`` (``p = 2.712 rad/s``) unless told
otherwise, and sets ``T_p = 2 pi / (x p)`` for each column; ``tests/test_spectra.py`` checks that
another ``R`` gives the same map. The solver's tolerances are scaled by ``alpha``, ``p alpha`` and
``g tan(alpha) / max(omega_b, p)^2`` and its first step by ``1/p`` and ``T_p``, and a verdict-only run
ends when its verdict is proven (the theorems of :mod:`rockcli.kernels.rigid` and :mod:`rockcli.kernels.driver_end`), which does not
depend on the block size either: the dimensionless result is the same to rounding. (A run still
unproven at the solver's horizon, 600 s after the pulse, would end there: such cells are counted and
reported as "still moving", ``settled`` False.)

Pulses have ``a_p > 0`` (the larger lobe first for the antisymmetric Ricker). Reversing the sign
mirrors theta and leaves every verdict unchanged (the block is symmetric).
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass, replace
from typing import Optional

from rockcli.errors import RockcliInputError
from rockcli.models import Block, Rigid, parse_isolation_spec
from rockcli.pulses import make_pulse
from rockcli.spectra.grids import _NUMBER
from rockcli.io.units import G

#: Semi-diagonal of the reference block every cell is run on [m] (``p = sqrt(3 g / 4) = 2.712 rad/s``).
REFERENCE_R = 1.0
#: Pulse shapes of the spectra.
SHAPES = ("ricker-sym", "ricker-anti", "sine", "cosine")


@dataclass(frozen=True)
class PulseChoice:
    """The pulse of a spectrum: a shape, optionally its period, and where it comes from.

    ``T_p`` [s] only matters for the conversion to block sizes (critical size, the R axis);
    the dimensionless spectra do not depend on it.
    """

    shape: str
    T_p: Optional[float] = None
    source: str = "pulse"
    note: str = ""

    @property
    def label(self) -> str:
        return self.shape if self.T_p is None else f"{self.shape} T_p={self.T_p:g}s"


def parse_pulse_choice(text: str) -> PulseChoice:
    """``ricker-sym`` or ``ricker-sym:Tp=0.6`` (shape, optional period in s)."""
    raw = str(text).strip()
    shape, _, rest = raw.partition(":")
    shape = shape.strip().lower()
    shape = {"one-sine": "sine", "one-cosine": "cosine"}.get(shape, shape)
    if shape not in SHAPES:
        raise RockcliInputError(f"pulse {raw!r}: unknown shape {shape!r} (use {', '.join(SHAPES)})")
    from rockcli.io.inputs import parse_number, spec_items

    T_p = None
    for key, val, eq in spec_items(rest, f"pulse {raw!r}"):
        if key.lower() != "tp" or not eq:
            item = f"{key}={val}" if eq else key
            raise RockcliInputError(f"pulse {raw!r}: {item!r} is not Tp=<period in s> (the amplitude is swept)")
        from rockcli.pulses import T_P_RANGE_S  # the supported periods, as every pulse: 1 ms to 1000 s

        T_p = parse_number(val, f"pulse {raw!r}: Tp", lo=T_P_RANGE_S[0], hi=T_P_RANGE_S[1], unit="s",
                           bad=f"pulse {raw!r}: Tp must be a positive period in s, got {val!r}")
    return PulseChoice(shape, T_p)


def pulse_from_record(record, *, wavelet: str = "best") -> PulseChoice:
    """Shape and ``T_p`` of a record's fitted pulse (:func:`rockcli.pulses_fit.fit_pulse`)."""
    from rockcli.pulses_fit import fit_pulse

    fit = fit_pulse(record, wavelet)
    note = (f"T_p and shape from the pulse fitted to record {fit.record_name}: {fit.shape}, "
            f"a_p = {fit.a_p_g:+.3f} g, T_p = {fit.T_p_s:.3f} s, energy fraction {fit.energy_fraction:.2f}"
            + (" (T_p on the end of the searched period range)" if fit.at_period_bound else ""))
    return PulseChoice(fit.shape, float(fit.T_p_s), f"record {fit.record_name} (fitted pulse)", note)


@dataclass(frozen=True)
class VerticalChoice:
    """A vertical pulse under every cell of a spectrum, scaled with the cell's horizontal pulse.

    ``shape`` one of :data:`SHAPES`, ``a_v_g`` its amplitude [g, upward positive], ``ratio`` its period
    over the horizontal pulse's, ``T_v = ratio T_p``; the middle of its support is placed at the middle
    of the horizontal pulse's (the same shape with ``ratio = 1``: in phase), moved later if it would
    otherwise start before t = 0. Written in the time ``p t`` the rocking equation then depends on
    ``a_v/g`` and ``T_v/T_p`` only, so a map stays independent of the block size
    (``tests/test_vertical_assess.py`` checks it).
    """

    shape: str
    a_v_g: float
    ratio: float = 1.0

    @property
    def label(self) -> str:
        return f"{self.shape}:ap={self.a_v_g:g},TvTp={self.ratio:g}"

    def pulse(self, horizontal):
        """The vertical pulse under the horizontal pulse ``horizontal``."""
        unit = make_pulse(self.shape, self.a_v_g * G, self.ratio * float(horizontal.T_p))
        ts, te = unit.support()
        hs, he = horizontal.support()
        shift = max(0.5 * (hs + he) - 0.5 * (ts + te), -ts)
        return make_pulse(self.shape, self.a_v_g * G, self.ratio * float(horizontal.T_p), t0=unit.t0 + shift)


def parse_vertical_choice(text: str, option: str = "--vertical-pulse") -> VerticalChoice:
    """``SHAPE:ap=<a_v in g>[,TvTp=<T_v/T_p>]`` (default ``TvTp=1``); ``|a_v| < 1 g`` (lift-off beyond)."""
    from rockcli.io.inputs import parse_number, spec_items

    raw = str(text).strip()
    shape, _, rest = raw.partition(":")
    shape = {"one-sine": "sine", "one-cosine": "cosine"}.get(shape.strip().lower(), shape.strip().lower())
    what = f"{option} {raw!r}"
    if shape not in SHAPES:
        raise RockcliInputError(f"{what}: unknown shape {shape!r} (use {', '.join(SHAPES)})")
    got = {}
    for key, val, eq in spec_items(rest, what):
        k = {"ap": "ap", "tvtp": "tvtp"}.get(key.lower())
        if k is None or not eq:
            raise RockcliInputError(f"{what}: {key!r} is not ap=<a_v in g> or TvTp=<T_v/T_p> (a spectrum keeps the "
                                    f"vertical pulse's period a fixed multiple of the horizontal one's)")
        got[k] = val
    if "ap" not in got:
        raise RockcliInputError(f"{what}: give the vertical amplitude ap=<a_v in g>")
    a_v = parse_number(got["ap"], f"{what}: ap", unit="g")
    ratio = 1.0
    if "tvtp" in got:
        ratio = parse_number(got["tvtp"], f"{what}: TvTp", lo=0.0, lo_open=True)
    from rockcli.solve.excitation import _vertical_arrays

    try:  # g + a_v > 0 throughout: the same for every period, so checked once
        _vertical_arrays(VerticalChoice(shape, float(a_v), float(ratio)).pulse(make_pulse(shape, G, 1.0)), None,
                         Rigid(), G)
    except RockcliInputError as exc:
        raise RockcliInputError(f"{what}: {exc}") from None
    return VerticalChoice(shape, float(a_v), float(ratio))


@dataclass(frozen=True)
class Isolation:
    """A foundation with ``T_b / T_p`` fixed, for any pulse period.

    ``kind`` is ``none`` (rigid foundation) or a bearing kind of
    :func:`rockcli.models.parse_isolation_spec`; ``params`` its other ``key=value`` items;
    ``ratio`` is ``T_b / T_p``. :meth:`foundation` substitutes ``Tb = ratio * T_p`` and parses the
    spec, so every bearing kind that takes ``Tb=`` works.
    """

    kind: str
    ratio: Optional[float] = None
    params: tuple = ()

    @property
    def rigid(self) -> bool:
        return self.kind == "none"

    def spec(self, T_p: float) -> str:
        items = [f"Tb={float(self.ratio) * float(T_p)!r}"] + [f"{k}={v}" for k, v in self.params]
        return f"{self.kind}:{','.join(items)}"

    def foundation(self, T_p: float):
        if self.rigid:
            return Rigid()
        return parse_isolation_spec(self.spec(T_p))

    def param(self, key: str):
        for k, v in self.params:
            if k.lower() == key.lower():
                return v
        return None

    def with_param(self, key: str, value) -> "Isolation":
        """The same isolation with ``key=value`` set (added or replaced)."""
        params = [(k, v) for k, v in self.params if k.lower() != key.lower()] + [(key, f"{value:g}")]
        return replace(self, params=tuple(params))

    @property
    def label(self) -> str:
        """The spec with every parameter resolved (defaults included), ``TbTp=`` for ``Tb=``."""
        if self.rigid:
            return "none"
        resolved = self.foundation(1.0).label
        if re.search(r"\bTb=[^,]*", resolved):
            return re.sub(r"\bTb=[^,]*", f"TbTp={self.ratio:g}", resolved, count=1)
        return ",".join([f"{self.kind}:TbTp={self.ratio:g}"] + [f"{k}={v}" for k, v in self.params])


def parse_isolation(text: str) -> Isolation:
    """Parse ``none`` or ``KIND:TbTp=<T_b/T_p>,...`` (e.g. ``linear:TbTp=2,xi=0.05,gamma=0.01``).

    Spectra keep ``T_b / T_p`` fixed over the map, as the paper does, so ``Tb=`` (a period in s) is
    refused. The spec is checked once (with ``T_p = 1 s``) so that errors surface before any run.
    """
    raw = str(text).strip()
    kind, _, rest = raw.partition(":")
    kind = kind.strip().lower()
    if kind in ("none", "rigid", "fixed") and not rest.strip():
        return Isolation("none")
    from rockcli.io.inputs import parse_number, spec_items

    ratio = None
    params = []
    for key, val, eq in spec_items(rest, f"isolation {raw!r}"):
        if not eq:
            raise RockcliInputError(f"isolation {raw!r}: {key!r} is not key=value")
        if key.lower() == "tb":
            raise RockcliInputError(f"isolation {raw!r}: spectra keep T_b/T_p fixed over the map; "
                                    f"write TbTp=<ratio> instead of Tb=")
        if key.lower() == "tbtp":
            ratio = parse_number(val, f"isolation {raw!r}: TbTp", lo=0.0, lo_open=True,
                                 bad=f"isolation {raw!r}: TbTp must be a positive number, got {val!r}")
        else:
            params.append((key, val))
    if ratio is None:
        raise RockcliInputError(f"isolation {raw!r} needs TbTp=<T_b/T_p> (e.g. linear:TbTp=2,xi=0.05,gamma=0.01)")
    iso = Isolation(kind, ratio, tuple(params))
    iso.foundation(1.0)  # raises with the parser's own sentence if anything else is wrong
    return iso


@dataclass(frozen=True)
class Family:
    """Scenes that differ only in ``x = omega_p/p`` and ``y = a_p/(g tan alpha)``: one map or one curve.

    ``plinth``: a :class:`rockcli.spectra.plinth.PlinthRatio` the block stands on in every cell (None: the block
    alone); its scene's first item is then the :class:`rockcli.models.Stack`, ``y`` still in units of the body's
    ``g tan alpha``."""

    alpha: float  # [rad]
    shape: str
    isolation: Isolation
    R: float = REFERENCE_R
    plinth: Optional[object] = None

    @property
    def alpha_deg(self) -> float:
        return math.degrees(self.alpha)

    @property
    def block(self) -> Block:
        return Block(self.R, self.alpha, "reference")

    def T_p(self, x: float) -> float:
        """Pulse period [s] of column ``x`` on the reference block."""
        return 2.0 * math.pi / (x * self.block.p)

    @property
    def body(self):
        """What every cell runs: the reference block, or the block on its plinth (a Stack)."""
        return self.block if self.plinth is None else self.plinth.stack(self.block)

    def scene(self, x: float, y: float):
        """``(block or stack, foundation, pulse)`` of cell ``(x, y)``."""
        T_p = self.T_p(x)
        return self.body, self.isolation.foundation(T_p), make_pulse(self.shape, y * (G * math.tan(self.alpha)), T_p)
