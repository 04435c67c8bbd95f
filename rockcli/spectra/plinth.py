"""A free plinth under every cell of a spectrum, in proportion to the body: :class:`PlinthRatio` and
:func:`parse_plinth_ratio` (``--on NAME:height_ratio=H2/H1,width_ratio=B2/B1[,mass_ratio=M]``).

Why ratios, not metres (the judgement, docs/spectra.md "A body on a free plinth")
--------------------------------------------------------------------------------
A spectrum's axes are dimensionless, ``x = omega_p/p`` and ``y = a_p/(g tan alpha)``, and every cell is run on one
reference block (:data:`rockcli.spectra.REFERENCE_R`) because the single block's answer does not depend on its size
(:mod:`rockcli.spectra.scenes`). The two-block assembly keeps that property when every length scales together:

* Equations of motion (docs/physics-plinth.md): each term is a mass times a length squared times an angular
  acceleration, a mass times a length times ``g`` (gravity) or times ``a_g`` (the ground). Divided by ``m1 R1``
  and written in the time ``tau = p t`` (``p^2 = 3 g / 4 R1``), they depend on the angles, on the length ratios
  ``b2/b1, h2/h1, h1/b1`` and the mass ratio ``m2/m1``, and on ``a_g/g = y tan(alpha1) f(x tau)`` only. On linear
  bearings the base adds ``u/R1``, ``omega_b/p = (T_p/T_b) x``, ``xi`` and ``gamma``: fixed with ``T_b/T_p``.
* Impacts (momentum conservation about the new corners): every angular momentum is a mass times a length squared
  times an angular velocity, so the maps relate ``d psi/d tau`` and ``d theta2/d tau`` by the same ratios.

So, with the plinth given as ratios of the body's height and width (and its mass as a ratio of the body's, or the
same density: ``height_ratio x width_ratio``), the stack's verdict and peaks over ``x`` and ``y`` are the same for a
body of any size (``tests/test_spectrum_plinth.py`` runs two sizes). A plinth in metres would not be: under the
reference block of 1 m it would stand for a different proportion than under the researcher's body, so a spectrum
refuses it in one sentence (``rockcli simulate --on`` and ``assess --on`` take metres: they run a body of a size).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Optional

from rockcli.errors import RockcliInputError

#: How ``--on`` of a spectrum is written.
PLINTH_RATIO_FORM = "NAME:height_ratio=<H2/H1>,width_ratio=<B2/B1>[,mass_ratio=<M2/M1>]"

_KEYS = {"height_ratio": "height_ratio", "heightratio": "height_ratio", "width_ratio": "width_ratio",
         "widthratio": "width_ratio", "mass_ratio": "mass_ratio", "massratio": "mass_ratio"}


@dataclass(frozen=True)
class PlinthRatio:
    """A free plinth in proportion to the body it carries: ``height_ratio`` its height over the body's,
    ``width_ratio`` its width over the body's (at least 1: the body stands centred on it), ``mass_ratio`` its mass
    over the body's (None: the same density, ``height_ratio x width_ratio``, the model being planar)."""

    height_ratio: float
    width_ratio: float
    mass_ratio: Optional[float] = None
    name: str = "plinth"

    def plinth_for(self, block):
        """The :class:`rockcli.models.Plinth` under ``block`` (lengths in m)."""
        from rockcli.models import Plinth

        return Plinth(self.height_ratio * block.height, self.width_ratio * block.width, self.mass_ratio, self.name)

    def stack(self, block):
        """``block`` on this plinth (a :class:`rockcli.models.Stack`)."""
        from rockcli.models import Stack

        return Stack(block, self.plinth_for(block))

    @property
    def label(self) -> str:
        """``plinth:height_ratio=0.5,width_ratio=1.5`` (and ``mass_ratio=`` when given): the CSV's column, a spec
        that gives the same plinth when rerun (each number the shortest text that reads back as the same double)."""
        from rockcli.io.inputs import format_number as num

        items = [f"height_ratio={num(self.height_ratio)}", f"width_ratio={num(self.width_ratio)}"]
        if self.mass_ratio is not None:
            items.append(f"mass_ratio={num(self.mass_ratio)}")
        return f"{self.name}:{','.join(items)}"


def parse_plinth_ratio(text: str, option: str = "--on") -> PlinthRatio:
    """``"plinth:height_ratio=0.5,width_ratio=1.5[,mass_ratio=2]"`` -> :class:`PlinthRatio`; anything else (a plinth
    in metres among them) is one sentence naming ``option``."""
    from rockcli.io.inputs import spec_numbers

    raw = str(text).strip()
    what = f"{option} {raw!r}"
    name, colon, rest = raw.partition(":")
    name = name.strip() or "plinth"
    if not colon:
        raise RockcliInputError(f"{what} must be written {PLINTH_RATIO_FORM}, e.g. "
                                f"plinth:height_ratio=0.5,width_ratio=1.5")
    values = spec_numbers(
        rest, what, _KEYS, "height_ratio=..., width_ratio=..., mass_ratio=...",
        limits={"height_ratio": {"lo": 0.0, "lo_open": True}, "width_ratio": {"lo": 1.0},
                "mass_ratio": {"lo": 0.0, "lo_open": True}},
        refuse=dict.fromkeys(("height", "width"), "a spectrum is dimensionless (it holds for a body of any size), so "
                             "give the plinth in proportion to the body, height_ratio=<H2/H1> and width_ratio=<B2/B1>, "
                             "not {key}= in metres (docs/spectra.md)"))
    for need in ("height_ratio", "width_ratio"):
        if need not in values:
            raise RockcliInputError(f"{what} needs {need}=<{'H2/H1' if need == 'height_ratio' else 'B2/B1'}>")
    if "mass_ratio" in values:
        from rockcli.models.stack import MASS_RATIO_RANGE

        lo, hi = MASS_RATIO_RANGE
        if not lo <= values["mass_ratio"] <= hi:
            raise RockcliInputError(f"{what}: mass_ratio (the plinth's mass over the body's) must lie between "
                                    f"{lo:g} and {hi:g}, got {values['mass_ratio']:g}")
    return PlinthRatio(values["height_ratio"], values["width_ratio"], values.get("mass_ratio"), name)


def check_plinth_ratio(plinth: PlinthRatio, blocks, option: str = "--on") -> None:
    """Each of ``blocks`` can stand on ``plinth`` (its size, slenderness and mass within the supported ranges),
    or one sentence saying which cannot."""
    for block in blocks:
        try:
            plinth.stack(block)
        except RockcliInputError as exc:
            raise RockcliInputError(f"{option} {plinth.label!r} under the block of alpha = {block.alpha_deg:.4g} deg, "
                                    f"R = {block.R:.4g} m: {exc}") from None


__all__ = ["PLINTH_RATIO_FORM", "PlinthRatio", "check_plinth_ratio", "parse_plinth_ratio"]
