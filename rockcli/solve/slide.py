"""Rocking and sliding: a body (or a body on its plinth) with Coulomb friction at every contact, as a model
(docs/physics-sliding.md): :func:`simulate_friction` and its :class:`SlideResponse`.

The chain of blocks (one block, or the plinth and the body on it) is run by the friction driver
(:mod:`rockcli.kernels.chain_run`), on a rigid foundation or on linear bearings. Masses are per unit mass of
the body (the plinth's is ``Stack.m2``); the bearings' ``gamma`` reads ``m`` as everything they carry.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from rockcli.errors import RockcliInputError
from rockcli.io.units import G
from rockcli.models import Block, LinearIsolation, Rigid
from rockcli.models.stack import Stack
from rockcli.solve.options import (DEFAULT_HORIZON, DEFAULT_MAX_STEPS, DEFAULT_REST_TOL, DEFAULT_TAIL, _rtol,
                                   validate_options)

#: Relative slack of the contact law's consistency tests (as the plinth's impact law).
CONTACT_TOL = 1e-9
#: Largest friction coefficient taken: above it no contact of a rocking body ever slides in practice (and the
#: static threshold of a face, ``mu N``, stays a number).
MU_MAX = 10.0


def check_mu(mu, name: str = "friction") -> float:
    """``mu`` as a float when it is a finite friction coefficient in ``(0, MU_MAX]``, else one sentence."""
    if isinstance(mu, bool):
        value = math.nan
    else:
        try:
            value = float(mu)
        except (TypeError, ValueError):
            value = math.nan
    if not (math.isfinite(value) and 0.0 < value <= MU_MAX):
        raise RockcliInputError(f"{name} must be a friction coefficient between 0 (excluded) and {MU_MAX:g}, "
                                f"got {mu!r}")
    return value


@dataclass(frozen=True)
class InterfacePeak:
    """What one contact did: the block above it rocking on it (``psi``, about its own corners) and sliding on it."""

    name: str
    alpha: float  # the slenderness of everything above the contact, as one body about its corner [rad]
    psi_max: float  # peak |psi| [rad]
    t_psi_max: float
    t_exceed: float  # first time |psi| >= alpha
    t_uplift: float
    n_impacts: int
    slide_max_m: float  # peak |s| [m]: the block's base from its start along the surface below
    slide_residual_m: float  # s at the end [m]
    t_slide: float  # first slip [s]
    n_slips: int
    edge_m: float  # the slip at which the block's base passes the edge of the surface below (inf on the ground)
    tilt_max: float  # peak absolute tilt of the block above [rad]

    @property
    def psi_max_over_alpha(self) -> float:
        return self.psi_max / self.alpha

    def as_dict(self) -> dict[str, Any]:
        def num(x):
            return None if x is None or (isinstance(x, float) and not math.isfinite(x)) else x

        return {"name": self.name, "alpha_deg": math.degrees(self.alpha), "psi_max_rad": self.psi_max,
                "psi_max_over_alpha": self.psi_max_over_alpha, "t_uplift_s": num(self.t_uplift),
                "n_impacts": self.n_impacts, "slide_max_m": self.slide_max_m,
                "slide_residual_m": self.slide_residual_m, "t_slide_s": num(self.t_slide), "n_slips": self.n_slips,
                "edge_m": num(self.edge_m), "tilt_max_rad": self.tilt_max}


@dataclass(frozen=True)
class SlideResponse:
    """The outcome of :func:`simulate_friction`: per contact (``base``: on the ground or the bearings; ``joint``:
    the body on its plinth, None for a single block) what it did, and the verdict: ``"overturned"`` (a block
    toppled: ``toppled`` names which), ``"slid off"`` (the body slid off its plinth: its base reached the plinth's
    edge), ``"survives"``, or ``"no motion"`` (nothing lifted or slid); ``"undecided"`` when the step cap ended it."""

    verdict: str
    status: int
    mu: tuple
    base: InterfacePeak
    joint: InterfacePeak | None
    toppled: str | None
    slid_off: bool
    t_fail: float
    u_max: float
    n_jumps: int
    n_inconsistent: int
    n_slip_impacts: int
    n_slips_inside: int  # slips that started while every block leaned less than its slenderness (not in a fall)
    n_plastic: int  # impacts where a given restitution's impulses left the cone: the plastic impact instead
    settled: bool
    t_end: float
    steps: int
    nrhs: int
    history: Any = field(default=None, repr=False)
    all_peaks: tuple = ()  # every contact bottom to top (a column of drums: the base, then each joint)

    @property
    def body(self) -> InterfacePeak:
        """The body's own contact (the joint on a plinth, the base alone)."""
        return self.joint if self.joint is not None else self.base

    @property
    def rocks(self) -> bool:
        return any(math.isfinite(p.t_uplift) for p in self.interfaces)

    @property
    def why_undecided(self) -> str:
        """Why an undecided run stopped, in words ("" when it was decided)."""
        from rockcli.kernels.chain_out import STATUS_STALLED

        if self.status >= 0:
            return ""
        if self.status == STATUS_STALLED:
            return (f"the run stopped at t = {self.t_end:.2f} s where it made no progress (its steps, or its events at "
                    f"one instant, went on without time passing: the contact law found no way on, as where pivots "
                    f"pull, which the model without flight cannot follow)")
        return f"the run stopped at the solver's step cap ({self.steps:,} steps) at t = {self.t_end:.2f} s"

    @property
    def slides(self) -> bool:
        """A contact slid, between impacts or during one."""
        return any(p.n_slips > 0 for p in self.interfaces) or self.n_slip_impacts > 0

    @property
    def falls_only(self) -> bool:
        """It topples, and its contacts slid only during the fall (every slip started with a block past its
        slenderness): the rocking model's fall, whose contact unloads as it goes (docs/physics-sliding.md, "Where
        nothing slides")."""
        return self.verdict == "overturned" and self.slides and self.n_slips_inside == 0

    @property
    def interfaces(self) -> tuple:
        if len(self.all_peaks) > 2:
            return self.all_peaks
        return (self.base,) if self.joint is None else (self.base, self.joint)

    def as_dict(self) -> dict[str, Any]:
        def num(x):
            return None if x is None or (isinstance(x, float) and not math.isfinite(x)) else x

        d = {"verdict": self.verdict, "toppled": self.toppled, "slid_off": self.slid_off,
             "t_fail_s": num(self.t_fail), "friction_mu": list(self.mu)}
        if len(self.all_peaks) > 2:
            d["base"] = self.base.as_dict()
            d["joints"] = [p.as_dict() for p in self.all_peaks[1:]]
        elif self.joint is None:
            d.update(self.base.as_dict())
        else:
            d["base"] = self.base.as_dict()
            d["joint"] = self.joint.as_dict()
        d.update({"base_disp_max_m": num(self.u_max), "n_jumps": self.n_jumps,
                  "n_inconsistent": self.n_inconsistent, "n_slipping_impacts": self.n_slip_impacts,
                  "settled": self.settled, "t_end_s": self.t_end, "steps": self.steps, "nrhs": self.nrhs})
        return d


def _blocks(body) -> tuple[list, list]:
    """``([(b, h, m), ...] bottom to top, names)`` of a Block or a Stack (masses per unit body mass)."""
    from rockcli.models.drums import DrumColumn

    if isinstance(body, DrumColumn):
        return body.blocks(), body.joint_names()
    if isinstance(body, Stack):
        return [(body.b2, body.h2, body.m2), (body.b1, body.h1, 1.0)], ["base", "joint"]
    if isinstance(body, Block):
        return [(body.b, body.h, 1.0)], ["base"]
    raise RockcliInputError(f"the body must be a rockcli.models.Block, Stack or DrumColumn, got "
                            f"{type(body).__name__}")


def _mus(mu, n: int) -> tuple:
    if isinstance(mu, (tuple, list)):
        if len(mu) != n:
            raise RockcliInputError(f"friction: give one coefficient per contact ({n}), got {len(mu)}")
        return tuple(check_mu(m, "friction") for m in mu)
    return tuple([check_mu(mu, "friction")] * n)


def chain_parameters(body, mu, foundation=None, *, rtol=None, rest_tol: float = DEFAULT_REST_TOL,
                     restitution=None) -> np.ndarray:
    """The friction driver's parameter array ``cp`` (:mod:`rockcli.kernels.chain`) of ``body`` (a Block or a Stack)
    with friction ``mu`` (one number, or one per contact bottom to top) on ``foundation`` (None, Rigid or a
    LinearIsolation with gamma > 0)."""
    from rockcli.kernels import chain as ch
    from rockcli.kernels import chain_step as cs

    from rockcli.models.drums import DrumColumn

    blocks, _ = _blocks(body)
    n = len(blocks)
    mus = _mus(mu, n)
    drums = isinstance(body, DrumColumn)
    cp = np.zeros(ch.cp_size(n))
    cp[ch.CP_N] = n
    cp[ch.CP_G] = G
    cp[ch.CP_RTOL] = _rtol(foundation if foundation is not None else Rigid(), rtol)
    cp[ch.CP_REST] = float(rest_tol)
    cp[ch.CP_E] = -1.0 if restitution is None else float(restitution)
    cp[ch.CP_TOL] = CONTACT_TOL
    p2max = 0.0
    for i, (b, h, m) in enumerate(blocks):
        o = ch.CP_BLK + ch.NF_BLK * i
        R = math.hypot(b, h)
        p = math.sqrt(0.75 * G / R)
        p2max = max(p2max, p * p)
        cp[o + ch.F_B], cp[o + ch.F_H], cp[o + ch.F_M] = b, h, m
        cp[o + ch.F_I] = m * (b * b + h * h) / 3.0
        cp[o + ch.F_MU] = mus[i]
        # everything above interface i as one body about a corner of the interface
        mass = sum(mm for _, _, mm in blocks[i:])
        y0 = 0.0
        ym = 0.0
        for (bb, hh, mm) in blocks[i:]:
            ym += mm * (y0 + hh)
            y0 += 2.0 * hh
        if drums:
            # a drum keeps the overlap of its base with the top below as its contact (kernels.chain: the pivot at
            # the end of the overlap) and falls off only when no overlap is left
            bl = math.inf if i == 0 else blocks[i - 1][0]
            cp[o + ch.F_AREST] = math.atan2(min(b, bl) * mass, ym)
            cp[o + ch.F_BLOW] = bl
            cp[o + ch.F_EDGE] = bl + b
        else:
            # the body on its plinth falls once its base reaches the plinth's edge (docs/physics-sliding.md)
            cp[o + ch.F_AREST] = math.atan2(b * mass, ym)
            cp[o + ch.F_BLOW] = math.inf
            cp[o + ch.F_EDGE] = math.inf if i == 0 else blocks[i - 1][0] - b
        cp[o + ch.F_SC_S] = b
        cp[o + ch.F_SC_PSI] = cp[o + ch.F_AREST]
        cp[o + ch.F_P] = p
    cp[ch.CP_P2MAX] = p2max
    if foundation is None or isinstance(foundation, Rigid):
        cp[ch.CP_BASE] = ch.BASE_RIGID
        cp[cs.CP_SC_U] = cp[cs.CP_SC_UD] = 1.0
    elif isinstance(foundation, LinearIsolation):
        if not foundation.gamma > 0:
            raise RockcliInputError("friction on bearings needs a base of finite mass (gamma > 0)")
        m = sum(mm for _, _, mm in blocks)
        total = m / foundation.gamma
        w = foundation.omega_b
        cp[ch.CP_BASE] = ch.BASE_LINEAR
        cp[ch.CP_MB] = total - m
        cp[ch.CP_KB] = total * w * w
        cp[ch.CP_CB] = 2.0 * foundation.xi * w * total
        thr = G * math.tan(min(cp[ch.CP_BLK + ch.NF_BLK * i + ch.F_AREST] for i in range(n)))
        pmax = math.sqrt(p2max)
        cp[cs.CP_SC_U] = thr / max(w, pmax) ** 2
        cp[cs.CP_SC_UD] = thr / max(w, pmax)
    else:
        raise RockcliInputError("friction as a model runs on the rigid foundation and on linear bearings: give "
                                "--isolation none or linear")
    return cp


def simulate_friction(body, excitation, mu, foundation=None, *, rtol: float | None = None, history: bool = False,
                      tail: float = DEFAULT_TAIL, rest_tol: float = DEFAULT_REST_TOL,
                      horizon: float = DEFAULT_HORIZON, max_steps: int = DEFAULT_MAX_STEPS,
                      restitution: float | None = None) -> SlideResponse:
    """Rocking and sliding of ``body`` (a :class:`rockcli.models.Block`, or a :class:`rockcli.models.Stack`: the body
    on its plinth) under ``excitation`` (a record or a pulse), with Coulomb friction ``mu`` at every contact (one
    coefficient, or one per contact bottom to top: the base, then the joint), on ``foundation`` (None or
    :class:`rockcli.models.Rigid`, or :class:`rockcli.models.LinearIsolation` with ``gamma > 0``).

    The options are those of :func:`rockcli.solve.simulate`; ``restitution`` (``0 < E <= 1``) the rocking model's
    energetic rule at every impact whose impulses fit Coulomb's cone (else the plastic impact with Coulomb's law):
    on the ground, and for a body on its plinth on bearings (the rule the plinth uses there); a single block on
    bearings reads ``E`` another way (:mod:`rockcli.models.impact`) and is refused. Returns a :class:`SlideResponse`.
    """
    from rockcli.kernels import chain_out as co
    from rockcli.kernels import chain_run as cr
    from rockcli.solve.excitation import _excitation_arrays, attached_vertical

    if excitation is None:
        raise RockcliInputError("simulate_friction needs an excitation (a record or a pulse)")
    if attached_vertical(excitation) is not None:
        raise RockcliInputError("friction as a model runs under the horizontal ground motion only: the record "
                                "carries a vertical component")
    validate_options(rtol, tail, rest_tol, horizon, max_steps)
    blocks, names = _blocks(body)
    n = len(blocks)
    if restitution is not None:
        from rockcli.models.impact import check_restitution

        restitution = check_restitution(restitution)
        if n > 2:
            raise RockcliInputError("a column of drums takes the plastic impact with Coulomb's law: a restitution is "
                                    "not taken with drums yet")
        if not isinstance(body, Stack) and foundation is not None and not isinstance(foundation, Rigid):
            raise RockcliInputError("friction with a restitution runs on the ground, or for a body on its plinth: a "
                                    "single block on bearings reads the restitution with the base's impulsive couple "
                                    "(docs/simulate.md), which the friction model does not")
    cp = chain_parameters(body, mu, foundation, rtol=rtol, rest_tol=float(rest_tol), restitution=restitution)
    ekind, epar, acc, jtab, dt, t_begin, t_exc_end = _excitation_arrays(excitation)
    xo = np.zeros(co.n_out(n))
    H = cr.simulate_chain(cp, np.zeros(2 * n), np.zeros(2 + 4 * n), ekind, np.asarray(epar, float), acc, dt,
                          float(t_begin), float(t_exc_end), float(tail), float(horizon), int(max_steps), bool(history),
                          xo)
    return _response(cp, xo, H if history else None, names)


def _response(cp, xo, H, names) -> SlideResponse:
    from rockcli.kernels import chain as ch
    from rockcli.kernels import chain_out as co
    from rockcli.kernels import chain_run as cr

    n = int(cp[ch.CP_N])
    peaks = []
    for j in range(n):
        o = co.N_XG + co.NX_J * j
        f = cp[ch.CP_BLK + ch.NF_BLK * j:]
        peaks.append(InterfacePeak(
            name=names[j], alpha=float(f[ch.F_AREST]), psi_max=float(xo[o + co.J_PSI_MAX]),
            t_psi_max=float(xo[o + co.J_T_PSI_MAX]), t_exceed=float(xo[o + co.J_T_EXCEED]),
            t_uplift=float(xo[o + co.J_T_UPLIFT]), n_impacts=int(xo[o + co.J_N_IMP]),
            slide_max_m=float(xo[o + co.J_S_MAX]), slide_residual_m=float(xo[o + co.J_S_END]),
            t_slide=float(xo[o + co.J_T_SLIDE]), n_slips=int(xo[o + co.J_N_SLIPS]), edge_m=float(f[ch.F_EDGE]),
            tilt_max=float(xo[o + co.J_TILT])))
    status = int(xo[co.X_STATUS])
    toppled_j = int(xo[co.X_TOPPLED])
    if status == cr.STATUS_OVERTURNED:
        verdict = "overturned"
    elif status == co.STATUS_SLID_OFF:
        verdict = "slid off"
    elif status < 0:
        verdict = "undecided"
    elif any(math.isfinite(p.t_uplift) or p.n_slips > 0 for p in peaks):
        verdict = "survives"
    else:
        verdict = "no motion"
    toppled = None
    if toppled_j >= 0 and n > 2:
        toppled = names[toppled_j]  # a column of drums: the drums above that contact fall
    elif toppled_j >= 0:
        toppled = "body" if toppled_j == n - 1 else "plinth"
    mus = tuple(float(cp[ch.CP_BLK + ch.NF_BLK * j + ch.F_MU]) for j in range(n))
    return SlideResponse(
        verdict=verdict, status=status, mu=mus, base=peaks[0], joint=peaks[1] if n > 1 else None, toppled=toppled,
        slid_off=status == co.STATUS_SLID_OFF, t_fail=float(xo[co.X_T_FAIL]),
        u_max=float(xo[co.X_U_MAX]) if cp[ch.CP_BASE] != ch.BASE_RIGID else math.nan,
        n_jumps=int(xo[co.X_N_JUMP]), n_inconsistent=int(xo[co.X_N_INCONS]),
        n_slip_impacts=int(xo[co.X_N_SLIP_IMPACTS]), n_slips_inside=int(xo[co.X_N_SLIP_IN]),
        n_plastic=int(xo[co.X_N_PLASTIC]), settled=bool(xo[co.X_SETTLED]), t_end=float(xo[co.X_T_END]),
        steps=int(xo[co.X_STEPS]), nrhs=int(xo[co.X_NRHS]), history=H, all_peaks=tuple(peaks))
