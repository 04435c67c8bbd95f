"""Isolation specs: ``parse_isolation_spec("scss:Tb=3,mu=0.05")`` -> a foundation (the CLI's ``--isolation``); a
:class:`Configuration`, a foundation with how the user wrote it and its short header (:func:`configuration_of` for
one spec; :func:`rockcli.assess.parse_configurations` for the list of an assessment)."""

from __future__ import annotations

from dataclasses import dataclass

from rockcli.errors import RockcliInputError
from rockcli.models.foundations import DoubleConcaveSliding, LeadRubber, LinearIsolation, Rigid, SingleConcaveSliding


_BW_KEYS = {"n": "n", "beta": "beta", "gammabw": "gamma_bw"}
_SPEC_KEYS = {
    "linear": {"tb": "T_b", "xi": "xi", "gamma": "gamma"},
    "scss": {"tb": "T_b", "mu": "mu", "uy": "u_y", "gamma": "gamma", **_BW_KEYS},
    "lrb": {"tb": "T_b", "q": "Q_ratio", "uy": "u_y", "gamma": "gamma", **_BW_KEYS},
    "dcss": {"r1": "R1_eff", "r2": "R2_eff", "tb": "T_b", "r": "ratio", "mu1": "mu1", "mu2": "mu2", "uy": "u_y",
             "gamma": "gamma", **_BW_KEYS},
}
_SPEC_EXAMPLES = ("'none', 'linear:Tb=2.5,xi=0.1,gamma=0.01', 'scss:Tb=3,mu=0.05[,uy=0.00025,gamma=0.01]', "
                  "'lrb:Tb=2.5,Q=0.06,uy=0.015' or 'dcss:R1=1.1,R2=1.1,mu1=0.03,mu2=0.07[,uy=..,gamma=..]'")
_REQUIRED = {
    "linear": (("T_b", "Tb=<period in s>"),),
    "scss": (("T_b", "Tb=<period in s>"), ("mu", "mu=<friction coefficient>")),
    "lrb": (("T_b", "Tb=<period in s>"), ("Q_ratio", "Q=<strength / weight>"), ("u_y", "uy=<yield displacement in m>")),
    "dcss": (("mu1", "mu1=<friction of surface 1>"), ("mu2", "mu2=<friction of surface 2>")),
}
_CLASSES = {"linear": LinearIsolation, "scss": SingleConcaveSliding, "lrb": LeadRubber}


def parse_isolation_spec(text: str):
    """Parse an isolation spec into a foundation.

    ``none``; ``linear:Tb=2.5[,xi=0.1,gamma=0.01]``; ``scss:Tb=3,mu=0.05[,uy=0.00025,gamma=0.01]``;
    ``lrb:Tb=2.5,Q=0.06,uy=0.015[,gamma=0.01]`` (``Q`` = strength / weight);
    ``dcss:R1=1.1,R2=1.1,mu1=0.03,mu2=0.07[,uy=0.00025,gamma=0.01]`` (effective radii ``R_i - h_i`` in m),
    or ``dcss:Tb=3,mu1=0.03,mu2=0.07[,r=<R2/R1, default 1>]``. The Bouc-Wen elements also take
    ``n``, ``beta``, ``gammabw``. Periods in s, lengths in m; defaults as in :mod:`rockcli.models`.
    Any bad spec raises :class:`RockcliInputError` with one sentence.
    """
    raw = str(text).strip()
    kind, _, rest = raw.partition(":")
    kind = kind.strip().lower()
    if kind in ("none", "rigid", "fixed") and not rest.strip():
        return Rigid()
    if kind not in _SPEC_KEYS:
        raise RockcliInputError(f"unknown isolation {kind!r} in {raw!r} (use {_SPEC_EXAMPLES})")
    from rockcli.io.inputs import spec_numbers

    keys = _SPEC_KEYS[kind]
    values = spec_numbers(rest, f"isolation {raw!r}", keys, ", ".join(k + "=..." for k in keys))
    if "beta" in values and "gamma_bw" not in values:  # A = 1: one of them fixes the other
        values["gamma_bw"] = 1.0 - values["beta"]
    elif "gamma_bw" in values and "beta" not in values:
        values["beta"] = 1.0 - values["gamma_bw"]
    for name, hint in _REQUIRED[kind]:
        if name not in values:
            raise RockcliInputError(f"isolation {raw!r} needs {hint}")
    by_radii = "R1_eff" in values or "R2_eff" in values
    by_period = "T_b" in values or "ratio" in values
    if kind == "dcss" and (by_radii == by_period or (by_radii and not ("R1_eff" in values and "R2_eff" in values))
                           or (by_period and "T_b" not in values)):
        raise RockcliInputError(f"isolation {raw!r} needs either R1=<m>,R2=<m> or Tb=<s>[,r=<R2/R1>]")
    try:
        if kind != "dcss":
            return _CLASSES[kind](**values)
        if by_period:
            T_b, ratio = values.pop("T_b"), values.pop("ratio", 1.0)
            return DoubleConcaveSliding.from_period(T_b, ratio=ratio, **values)
        return DoubleConcaveSliding(**values)
    except RockcliInputError as exc:
        raise RockcliInputError(f"isolation {raw!r}: {exc}") from None


@dataclass(frozen=True)
class Configuration:
    """A foundation and how the user wrote it."""

    spec: str
    foundation: object
    header: str

    @property
    def label(self) -> str:
        return self.foundation.label

    @property
    def isolated(self) -> bool:
        return not isinstance(self.foundation, Rigid)


def _short_header(foundation, spec: str) -> str:
    if isinstance(foundation, Rigid):
        return "none"
    T_b = getattr(foundation, "T_b", None)
    if T_b is None:
        return spec
    family = foundation.label.partition(":")[0]
    return f"Tb={T_b:g}s" if family == "linear" else f"{family} Tb={T_b:.3g}s"


def configuration_of(spec: str) -> Configuration:
    """The :class:`Configuration` of one isolation spec alone (its short header: ``none``, ``Tb=2.5s``), as
    :func:`rockcli.assess.parse_configurations` gives it for a list of one."""
    foundation = parse_isolation_spec(spec)
    return Configuration(spec.strip(), foundation, _short_header(foundation, spec.strip()))
