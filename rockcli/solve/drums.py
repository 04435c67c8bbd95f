"""A column of drums (:class:`rockcli.models.drums.DrumColumn`) under a ground motion, beside its monolith: the
friction model's run of the stack (:func:`rockcli.solve.slide.simulate_friction`, every joint a contact that sticks,
opens about either corner or slides) and of the one block of the same height and base width with the same friction
at its base, and what an archaeologist or a conservator reads from them (docs/physics-drums.md): which joint moves
first, each joint's peak opening and slip, the residual dislocation of each drum, which drums fall."""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

from rockcli.errors import RockcliInputError
from rockcli.solve.slide_many import SlideRun


#: Peaks of the base within this share of the larger are ``alike`` (:func:`compare`).
ALIKE = 0.02


def falls_at(stack) -> str | None:
    """Where the column of ``stack`` (a :class:`rockcli.solve.slide.SlideResponse` of a column of drums) failed: the
    contact about which it fell (``base``: the whole column; ``joint k``: the drums above it), or the joint at which a
    drum slid off the one below; None when it stands."""
    if stack.verdict == "overturned":
        return stack.toppled
    if stack.verdict == "slid off":
        j = next((p for p in stack.interfaces if p.slide_max_m >= p.edge_m * (1 - 1e-9)), None)
        return None if j is None else j.name
    return None


def first_move(stack) -> tuple | None:
    """``(contact name, time [s], "opens" or "slides")`` of the first contact of ``stack`` to move, None if none did."""
    best = None
    for p in stack.interfaces:
        for t, what in ((p.t_uplift, "opens"), (p.t_slide, "slides")):
            if math.isfinite(t) and (best is None or t < best[1]):
                best = (p.name, t, what)
    return best


def residual_offsets(stack) -> list:
    """Each drum's horizontal offset from the axis of the column's footprint at the end of ``stack`` [m], bottom to
    top (the sum of the residual slips of the contacts under it)."""
    out = []
    x = 0.0
    for p in stack.interfaces:
        x += p.slide_residual_m
        out.append(x)
    return out


def compare(drums_fail: bool, monolith_fails: bool, drums_peak: float, monolith_peak: float) -> str:
    """``safer``, ``worse`` or ``alike``: the drums against the monolith by the verdict (one fails, the other does
    not), then, when both stand, by the peak rotation of the base over its slenderness (the whole column rocking on
    its footprint: within :data:`ALIKE` of the larger, ``alike``); both failing is ``alike`` (the margins say more).
    The one rule of ``simulate --drums`` and ``assess column`` (docs/physics-drums.md)."""
    if drums_fail != monolith_fails:
        return "worse" if drums_fail else "safer"
    if drums_fail:
        return "alike"
    a, b = drums_peak, monolith_peak
    if abs(a - b) <= ALIKE * max(a, b, 1e-12):
        return "alike"
    return "safer" if a < b else "worse"


@dataclass(frozen=True)
class DrumRun:
    """The drums' run (``stack``, a :class:`rockcli.solve.slide.SlideResponse` with every contact in
    ``stack.interfaces``: the base, then joint 1 under drum 2, ...) and the monolith's (``monolith``)."""

    column: Any
    stack: Any
    monolith: Any

    @property
    def verdict(self) -> str:
        return self.stack.verdict

    @property
    def falls_at(self) -> str | None:
        """The contact about which the column fell (``base``: the whole column; ``joint k``: the drums above it),
        or where a drum slid off the one below; None when it stands."""
        return falls_at(self.stack)

    @property
    def first_move(self) -> tuple | None:
        """``(contact name, time [s], "opens" or "slides")`` of the first joint to move, None if none did."""
        return first_move(self.stack)

    @property
    def residual_offsets_m(self) -> list:
        """Each drum's horizontal offset from the axis of the column's footprint at the end [m], bottom to top (the
        sum of the residual slips of the joints under it; the residual tilts are 0 at rest)."""
        return residual_offsets(self.stack)

    @property
    def compared(self) -> str:
        """``safer``, ``worse`` or ``alike``: the drums against the monolith, by the verdict, then by the peak
        rotation of the base (the whole column rocking on its footprint) over its slenderness (:func:`compare`)."""
        fails = {"overturned", "slid off"}
        return compare(self.stack.verdict in fails, self.monolith.verdict in fails,
                       self.stack.base.psi_max_over_alpha, self.monolith.base.psi_max_over_alpha)

    def as_dict(self) -> dict:
        d = self.stack.as_dict()
        d["column"] = {"name": self.column.name, "drums": [{"height_m": h, "width_m": w} for h, w in
                                                            self.column.drums],
                       "static_thresholds_g": self.column.static_thresholds()}
        fm = self.first_move
        d["first_move"] = None if fm is None else {"contact": fm[0], "t_s": fm[1], "how": fm[2]}
        d["falls_at"] = self.falls_at
        d["residual_offsets_m"] = self.residual_offsets_m
        d["monolith"] = {"verdict": self.monolith.verdict,
                         "psi_max_over_alpha": self.monolith.base.psi_max_over_alpha,
                         "slide_max_m": self.monolith.base.slide_max_m}
        d["drums_against_monolith"] = self.compared
        return d


def simulate_drums(column, excitation, mu, foundation=None, **options) -> DrumRun:
    """The column of drums and its monolith under ``excitation`` with friction ``mu`` (one coefficient, or one per
    contact bottom to top; the monolith takes the base's), on ``foundation`` (None, Rigid, or LinearIsolation with
    gamma > 0); ``options`` those of :func:`rockcli.solve.slide.simulate_friction` (``restitution`` is refused: a
    column of drums takes the plastic impact with Coulomb's law)."""
    from rockcli.models.drums import DrumColumn
    from rockcli.solve.slide import _mus, simulate_friction

    if not isinstance(column, DrumColumn):
        raise RockcliInputError(f"simulate_drums: the column must be a DrumColumn, got {type(column).__name__}")
    if options.get("restitution") is not None:
        raise RockcliInputError("a column of drums takes the plastic impact with Coulomb's law: a restitution is "
                                "not taken with drums yet")
    mus = _mus(mu, column.n)
    stack = simulate_friction(column, excitation, mus, foundation, **options)
    options.pop("history", None)
    mono = simulate_friction(column.monolith, excitation, mus[0], foundation, **options)
    return DrumRun(column, stack, mono)


class DrumSlideRun(SlideRun):
    """A column of drums in a batch (:func:`rockcli.solve.simulate_many` with a
    :class:`rockcli.solve.slide_many.Sliding` of a :class:`rockcli.models.drums.DrumColumn`): always the friction
    run's own answer (there is no rocking model of a stack of drums to hand it to). The names of a
    :class:`rockcli.solve.Response` read the whole column on its footprint (the base contact: its peak rotation over
    the column's slenderness, its impacts, its slip on the ground); what the drums add is read from every contact
    (:func:`falls_at`, :func:`first_move`, :func:`residual_offsets`, the openings, the counts of the contact law)."""

    @property
    def theta_max_over_alpha(self) -> float:
        return self.slide.base.psi_max_over_alpha

    @property
    def n_impacts(self) -> int:
        return self.slide.base.n_impacts

    @property
    def slide_max_m(self) -> float:
        return self.slide.base.slide_max_m

    @property
    def slide_residual_m(self) -> float:
        return self.slide.base.slide_residual_m

    @property
    def plinth_slide_max_m(self) -> float:
        return math.nan

    @property
    def plinth_slide_residual_m(self) -> float:
        return math.nan

    @property
    def message(self) -> str:
        st = self.slide
        if st.status >= 0:
            return st.verdict
        return f"undecided: {st.why_undecided}, with {st.n_inconsistent} events without a consistent contact pattern"

    @property
    def falls_at(self) -> str | None:
        return falls_at(self.slide)

    @property
    def first_move(self) -> tuple | None:
        return first_move(self.slide)

    @property
    def residual_offsets_m(self) -> list:
        return residual_offsets(self.slide)

    @property
    def n_inconsistent(self) -> int:
        """Events at which no contact pattern met every condition of the contact law: the answer is not reliable
        when > 0 (docs/physics-drums.md, "Not yet")."""
        return self.slide.n_inconsistent

    @property
    def n_jumps(self) -> int:
        return self.slide.n_jumps
