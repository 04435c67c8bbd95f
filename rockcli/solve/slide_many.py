"""Bodies with friction in a batch: the :class:`Sliding` jobs of :func:`rockcli.solve.simulate_many` (a body, or a
body on its plinth, with a friction coefficient), one :func:`rockcli.solve.slide.simulate_friction` run each, read
back as a :class:`SlideRun` that answers to the names of a :class:`rockcli.solve.Response` (the margin search, the
assessment table and the fragility read those).

The rocking answer where nothing slides (exact, the shortcut's theorem). A run of the friction model in which no
contact ever slides, at an impact or between them, has followed the rocking model's patterns, events and impact law
throughout: every pattern it entered sticks, and the rocking model's choice of pattern and impact is the friction
model's when the forces and impulses stay inside Coulomb's cone (docs/physics-sliding.md, "Where nothing slides").
Its answer is therefore the rocking model's, and the rocking model's own run of the scene (the same job without
friction, through the same path: the batch of single blocks or the stack driver) is returned for it, so that an
assessment with a friction nothing reaches gives the assessment without friction bit for bit. The same holds for a
run that topples and whose contacts slid only during the fall (every slip starting with a block past its
slenderness: the contact of a falling block unloads, its force ratio grows without bound, and what fails there is the
model's "no flight", not friction), provided the rocking run topples too: the fall is the rocking model's. The two runs are the
same solution computed by two codes: they differ only at the solvers' tolerance, and where the friction run's
largest force ratio comes within that tolerance of ``mu`` the rocking run's could cross it; tests compare both paths
(``tests/test_friction_assess.py``).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

from rockcli.errors import RockcliInputError
from rockcli.solve.response import JobError


@dataclass(frozen=True)
class Sliding:
    """A body (:class:`rockcli.models.Block`, a :class:`rockcli.models.Stack`: the body on its plinth, or a
    :class:`rockcli.models.drums.DrumColumn`, read back as a :class:`rockcli.solve.drums.DrumSlideRun`) with Coulomb
    friction ``mu`` at every contact (one coefficient, or one per contact bottom to top: ``(base, joint)``). A job's
    first item in :func:`rockcli.solve.simulate_many`, and a column of an assessment: ``subject`` is the body (or the
    body on its plinth), and the wrapper reads as it does (``name``, ``alpha``, a stack's ``body`` and ``plinth``)."""

    subject: Any
    mu: Any

    def __post_init__(self):
        from rockcli.models import Block, Stack
        from rockcli.models.drums import DrumColumn
        from rockcli.solve.slide import _mus

        if not isinstance(self.subject, (Block, Stack, DrumColumn)):
            raise RockcliInputError(f"Sliding: the body must be a Block, a Stack or a DrumColumn, got "
                                    f"{type(self.subject).__name__}")
        n = self.subject.n if isinstance(self.subject, DrumColumn) else 2 if isinstance(self.subject, Stack) else 1
        object.__setattr__(self, "mu", _mus(self.mu, n))

    def __getattr__(self, name):
        if name.startswith("__"):
            raise AttributeError(name)
        return getattr(self.__dict__["subject"], name)

    @property
    def friction_label(self) -> str:
        """``mu=0.5``, or ``base=0.5,joint=0.7`` where the contacts differ."""
        if len(set(self.mu)) == 1:
            return f"mu={self.mu[0]:g}"
        return ",".join(f"{k}={v:g}" for k, v in zip(("base", "joint"), self.mu))


@dataclass(frozen=True)
class SlideRun:
    """One friction run as the batch callers read a :class:`rockcli.solve.Response`: ``slide`` the
    :class:`rockcli.solve.slide.SlideResponse`; ``rock`` the rocking model's own run where nothing slid (then every
    Response name is its, bit for bit), else None and the names are the friction run's. Overturned: a block toppled,
    or the body slid off its plinth."""

    slide: Any
    rock: Any = None
    error: str = ""

    @property
    def slid(self) -> bool:
        """The friction run's answer stands (a contact slid before any fall)."""
        return self.rock is None

    def __getattr__(self, name):
        if name.startswith("__"):
            raise AttributeError(name)
        rock = self.__dict__.get("rock")
        if rock is not None:
            return getattr(rock, name)
        raise AttributeError(name)

    # the names of a Response, where the friction run answers
    @property
    def verdict(self) -> str:
        if self.rock is not None:
            return self.rock.verdict
        v = self.slide.verdict
        return {"overturned": "overturned", "slid off": "slid_off", "survives": "rocked" if self.slide.rocks
                else "slid", "no motion": "no_uplift", "undecided": "undecided"}[v]

    @property
    def overturned(self) -> bool:
        if self.rock is not None:
            return self.rock.overturned
        return self.slide.verdict in ("overturned", "slid off")

    @property
    def settled(self) -> bool:
        return self.rock.settled if self.rock is not None else self.slide.settled

    @property
    def status(self) -> int:
        if self.rock is not None:
            return self.rock.status
        return -1 if self.slide.status < 0 else (1 if self.overturned else 0)

    @property
    def message(self) -> str:
        if self.rock is not None:
            return self.rock.message
        return self.slide.verdict

    @property
    def peak_final(self) -> bool:
        return self.rock.peak_final if self.rock is not None else True

    @property
    def theta_max_over_alpha(self) -> float:
        if self.rock is not None:
            return self.rock.theta_max_over_alpha
        return self.slide.body.psi_max_over_alpha

    @property
    def t_overturn_s(self) -> float:
        return self.rock.t_overturn_s if self.rock is not None else self.slide.t_fail

    @property
    def t_uplift_s(self) -> float:
        if self.rock is not None:
            return self.rock.t_uplift_s
        times = [p.t_uplift for p in self.slide.interfaces if not math.isnan(p.t_uplift)]
        return min(times) if times else math.nan

    @property
    def n_impacts(self) -> int:
        return self.rock.n_impacts if self.rock is not None else self.slide.body.n_impacts

    @property
    def steps(self) -> int:
        return self.rock.steps if self.rock is not None else self.slide.steps

    @property
    def nfev(self) -> int:
        return self.rock.nfev if self.rock is not None else self.slide.nrhs

    @property
    def base_disp_max_m(self) -> float:
        if self.rock is not None:
            return self.rock.base_disp_max_m
        u = self.slide.u_max
        return 0.0 if math.isnan(u) else u

    # what sliding adds: the body's own contact, and the plinth's
    @property
    def slide_max_m(self) -> float:
        return 0.0 if self.rock is not None else self.slide.body.slide_max_m

    @property
    def slide_residual_m(self) -> float:
        return 0.0 if self.rock is not None else self.slide.body.slide_residual_m

    @property
    def plinth_slide_max_m(self) -> float:
        if self.slide.joint is None:
            return math.nan
        return 0.0 if self.rock is not None else self.slide.base.slide_max_m

    @property
    def plinth_slide_residual_m(self) -> float:
        if self.slide.joint is None:
            return math.nan
        return 0.0 if self.rock is not None else self.slide.base.slide_residual_m


def is_slide_job(job) -> bool:
    return isinstance(job, (tuple, list)) and len(job) >= 3 and isinstance(job[0], Sliding)


def run_slide(sliding: Sliding, foundation, motion, scale: float = 1.0, **solver):
    """One :func:`rockcli.solve.slide.simulate_friction` run of ``sliding`` on ``foundation`` under ``scale`` times
    ``motion``; ``solver`` its keywords (``cap_ratio``, ``vertical`` refused when given)."""
    from rockcli.models import Rigid
    from rockcli.solve.slide import simulate_friction

    for key in ("cap_ratio", "vertical"):
        value = solver.pop(key, None)
        if value:
            raise RockcliInputError(f"friction as a model runs without {key} (docs/physics-sliding.md)")
    solver.pop("early", None)
    if scale != 1.0:
        motion = motion.scaled(scale)
    return simulate_friction(sliding.subject, motion, sliding.mu, None if isinstance(foundation, Rigid) else foundation,
                             **solver)


def mixed_slides(jobs, many, *, progress=None, **options) -> list:
    """:func:`rockcli.solve.simulate_many` over jobs some of which are :class:`Sliding`: the friction runs on the
    process's pool, then the rocking model's runs of those where nothing slid and of the other jobs, through
    ``many`` (``simulate_many`` itself), results in job order (module notes)."""
    from rockcli.solve.options import _kernel
    from rockcli.solve.pool import run_tasks

    _kernel()
    jobs = list(jobs)
    slide_idx = [i for i, j in enumerate(jobs) if is_slide_job(j)]
    keep = {k: options[k] for k in ("rtol", "tail", "rest_tol", "horizon", "max_steps") if k in options}
    for key in ("restitution", "cap_ratio", "vertical"):
        value = options.get(key)
        if value is not None and not isinstance(value, (int, float)):
            raise RockcliInputError(f"{key}: friction as a model takes one value for every job")
        if value:
            keep[key] = value
    if not isinstance(keep.get("tail", 0.0), (int, float)):
        raise RockcliInputError("tail: friction as a model takes one value for every job")

    def one(job):
        sliding, foundation, motion = job[:3]
        scale = float(job[3]) if len(job) > 3 else 1.0
        try:
            return run_slide(sliding, foundation, motion, scale, **dict(keep))
        except RockcliInputError as exc:
            return JobError(str(exc))
        except ArithmeticError as exc:  # a fault of the compiled driver in one scene: that scene's error, not the batch's
            return JobError(f"the friction driver failed on this scene ({type(exc).__name__}: {exc}; x{scale:g} the "
                            f"motion): a fault of the driver, not of the input")

    count = [0]

    def finished(_):
        count[0] += 1
        if progress is not None:
            progress(count[0])

    slides = run_tasks([lambda job=jobs[i]: one(job) for i in slide_idx], done=finished) if slide_idx else []
    out = [None] * len(jobs)
    rock_jobs, rock_at = [], []
    from rockcli.models.drums import DrumColumn

    for i, s in zip(slide_idx, slides):
        if isinstance(s, JobError):
            out[i] = s
        elif isinstance(jobs[i][0].subject, DrumColumn):  # no rocking model of a column of drums: its own run
            from rockcli.solve.drums import DrumSlideRun

            out[i] = DrumSlideRun(s)
        elif s.slides and not s.falls_only:
            out[i] = SlideRun(s)
        else:  # nothing slid (or only in its fall): the rocking model's own run of the same scene (module notes)
            job = jobs[i]
            rock_jobs.append((job[0].subject, *job[1:]))
            rock_at.append(i)
    others = [i for i in range(len(jobs)) if not is_slide_job(jobs[i])]
    todo = [jobs[i] for i in others] + rock_jobs
    if todo:
        done = many(todo, progress=None, **options)
        for i, r in zip(others, done[:len(others)]):
            out[i] = r
        slide_at = dict(zip(slide_idx, slides))
        for i, r in zip(rock_at, done[len(others):]):
            s = slide_at[i]
            if isinstance(r, JobError):
                out[i] = r
            elif s.falls_only and not r.overturned:  # the rocking run does not fall: the friction run's answer
                out[i] = SlideRun(s)
            else:
                out[i] = SlideRun(s, rock=r)
    return out


__all__ = ["SlideRun", "Sliding", "is_slide_job", "mixed_slides", "run_slide"]
