"""The named scenes of the work-precision study, as text, and how they become a run's inputs.

A :class:`Scene` names a block, an isolation spec and an excitation as the CLI spells them;
:func:`resolve_scene` turns it into ``(block, foundation, excitation)`` or raises
:class:`SceneUnavailable` (a sliding bearing not parsed yet, a refused input, a record not found).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from rockcli.errors import RockcliInputError

PENDING_SLIDING = "pending: sliding bearings not available"


@dataclass(frozen=True)
class Scene:
    """A named scene: block, isolation spec and excitation, as text (resolved by :func:`resolve_scene`).

    ``block``: a column preset (``bassae``) or ``R=<m>,alpha=<deg>`` or ``height=<m>,width=<m>``.
    ``excitation``: ``pulse:<spec>`` (``rockcli.pulses.parse_pulse_spec``, a_p in g) or
    ``record:<catalogue id or file>``.
    """

    name: str
    title: str
    block: str
    isolation: str
    excitation: str

    @property
    def sliding(self) -> bool:
        return self.isolation.split(":")[0].strip().lower() in ("scss", "dcss", "lrb")


class SceneUnavailable(Exception):
    """A scene that cannot run here: ``reason`` starts with ``pending:``, ``refused:`` or ``skipped:``."""

    def __init__(self, reason: str):
        super().__init__(reason)
        self.reason = reason


KOBE = "record:kobe-1995-takarazuka-000"
WP_SCENES = (
    Scene("rigid-ricker", "Bassae, rigid, symmetric Ricker 0.5 g, 1.2 s", "bassae", "none",
          "pulse:ricker-sym:ap=0.5,Tp=1.2"),
    Scene("rigid-sine-overturn", "2 m x 0.5 m block, rigid, one-sine 0.29 g, 2 s (overturns, Figure 1)",
          "height=2,width=0.5", "none", "pulse:sine:ap=0.29,Tp=2"),
    Scene("rigid-kobe", "Bassae, rigid, Kobe Takarazuka 000", "bassae", "none", KOBE),
    Scene("linear-ricker", "Bassae, linear Tb = 2 s, xi = 0.1, symmetric Ricker 0.3 g, 1.2 s", "bassae",
          "linear:Tb=2,xi=0.1", "pulse:ricker-sym:ap=0.3,Tp=1.2"),
    Scene("linear-kobe", "Bassae, linear Tb = 2.5 s, xi = 0.1, Kobe Takarazuka 000", "bassae",
          "linear:Tb=2.5,xi=0.1", KOBE),
    Scene("scss-ricker", "Bassae, SCSS Tb = 3 s, mu = 0.1, symmetric Ricker 0.5 g, 1.2 s", "bassae",
          "scss:Tb=3,mu=0.1", "pulse:ricker-sym:ap=0.5,Tp=1.2"),
    Scene("scss-kobe", "Nemea, SCSS Tb = 3 s, mu = 0.1, Kobe Takarazuka 000", "nemea", "scss:Tb=3,mu=0.1", KOBE),
    Scene("dcss-ricker", "Bassae, DCSS R1 = R2 = 1.1 m, mu1 = 0.03, mu2 = 0.07, symmetric Ricker 0.5 g, 1.2 s",
          "bassae", "dcss:R1=1.1,R2=1.1,mu1=0.03,mu2=0.07", "pulse:ricker-sym:ap=0.5,Tp=1.2"),
    Scene("dcss-kobe", "Nemea, DCSS R1 = R2 = 1.1 m, mu1 = 0.03, mu2 = 0.07, Kobe Takarazuka 000", "nemea",
          "dcss:R1=1.1,R2=1.1,mu1=0.03,mu2=0.07", KOBE),
)


def _block(spec: str):
    from rockcli.models import build_block

    spec = spec.strip()
    if "=" not in spec:
        return build_block(preset=spec)
    from rockcli.io.inputs import parse_number, spec_items

    kv = {k.lower(): parse_number(v, f"block {spec!r}: {k}") for k, v, _ in spec_items(spec, f"block {spec!r}")}
    if "r" in kv:
        return build_block(R=kv["r"], alpha_deg=kv["alpha"])
    return build_block(height=kv["height"], width=kv["width"])


def parse_foundation(spec: str):
    """The foundation of an isolation spec; :class:`SceneUnavailable` ``pending`` for a sliding
    bearing the installed :mod:`rockcli.models` cannot parse yet."""
    from rockcli.models import parse_isolation_spec

    try:
        return parse_isolation_spec(spec)
    except RockcliInputError as exc:
        kind = spec.split(":")[0].strip().lower()
        if kind in ("scss", "dcss", "lrb") and "unknown isolation" in str(exc):
            raise SceneUnavailable(PENDING_SLIDING) from None
        raise SceneUnavailable(f"refused: {exc}") from None


def _excitation(spec: str):
    kind, _, rest = spec.partition(":")
    if kind == "pulse":
        from rockcli.pulses import parse_pulse_spec

        return parse_pulse_spec(rest)
    if kind == "record":
        from rockcli.records import read_record

        try:
            return read_record(rest)
        except RockcliInputError as exc:
            raise SceneUnavailable(f"skipped: record {rest} not found ({exc}); set ROCKCLI_RECORDS") from None
    raise ValueError(f"bad excitation {spec!r}")


def resolve_scene(scene: Scene):
    """``(block, foundation, excitation)`` of a scene, or :class:`SceneUnavailable`."""
    foundation = parse_foundation(scene.isolation)
    try:
        block = _block(scene.block)
    except RockcliInputError as exc:
        raise SceneUnavailable(f"refused: {exc}") from None
    return block, foundation, _excitation(scene.excitation)


def select_scenes(names, catalogue) -> list:
    """The scenes named (all when ``names`` is empty); an unknown name raises RockcliInputError."""
    by_name = {s.name: s for s in catalogue}
    if not names:
        return list(catalogue)
    out = []
    for n in names:
        if n not in by_name:
            raise RockcliInputError(f"unknown scene {n!r} (known: {', '.join(by_name)})")
        if by_name[n] not in out:
            out.append(by_name[n])
    return out


def excitation_end(excitation) -> float:
    """End of the ground motion [s] (a record's last sample; a pulse's support end)."""
    if hasattr(excitation, "acc"):
        return (np.asarray(excitation.acc).size - 1) * float(excitation.dt)
    return float(excitation.support()[1])
