"""The plinth model (rockcli.models.stack): its spec, its checks, the assembly's derived quantities."""

from __future__ import annotations

import math

import pytest

from rockcli.errors import RockcliInputError
from rockcli.models import Block, Plinth, Stack, parse_plinth_spec
from rockcli.io.units import G

STATUE = Block.from_dimensions(1.79, 0.5, "statue")


def test_spec_and_defaults():
    p = parse_plinth_spec("plinth:height=1.0,width=0.6")
    assert (p.height, p.width, p.mass_ratio, p.name) == (1.0, 0.6, None, "plinth")
    s = Stack(STATUE, p)
    assert s.m2 == pytest.approx(0.6 / (1.79 * 0.5), rel=1e-15)  # the same density: the ratio of areas
    assert parse_plinth_spec("base:height=0.2,width=4,mass_ratio=3").mass_ratio == 3.0


@pytest.mark.parametrize("spec, words", [("plinth", "NAME:height=<m>,width=<m>"), ("p:height=1", "needs width"),
                                         ("p:height=1,width=0.6,mass=2", "'mass=2' is not one of"),
                                         ("p:height=1,width=x", "width must be a number"),
                                         ("p:height=-1,width=1", "plinth height must be a positive length"),
                                         ("p:height=1,width=1,mass_ratio=1e6", "mass_ratio")])
def test_bad_specs_say_what_is_wrong(spec, words):
    with pytest.raises(RockcliInputError, match=words.replace("(", r"\(").replace(")", r"\)")):
        parse_plinth_spec(spec)


def test_a_body_wider_than_its_plinth_is_refused():
    with pytest.raises(RockcliInputError, match="no wider than its plinth"):
        Stack(STATUE, Plinth(1.0, 0.4))


def test_the_assembly_as_one_block():
    """Closed forms of pattern P against the separate rectangles' sums."""
    s = Stack(STATUE, Plinth(1.0, 0.6, mass_ratio=2.0))
    M = 3.0
    yc = (2.0 * 0.5 + 1.0 * (1.0 + 1.79 / 2)) / M
    assert s.y_c == pytest.approx(yc, rel=1e-15)
    assert s.alpha_asm == pytest.approx(math.atan(0.3 / yc), rel=1e-15)
    assert s.assembly_uplift_acceleration == pytest.approx(G * math.tan(s.alpha_asm), rel=1e-14)
    # inertia about the corner: each rectangle's own (m (w^2 + h^2)/12) plus m d^2
    J = 2.0 * ((0.6 ** 2 + 1.0 ** 2) / 12 + 0.3 ** 2 + 0.5 ** 2) + ((0.5 ** 2 + 1.79 ** 2) / 12 + 0.3 ** 2 + 1.895 ** 2)
    assert s.J_asm == pytest.approx(J, rel=1e-14)
    assert s.p_asm ** 2 == pytest.approx(M * G * math.hypot(0.3, yc) / J, rel=1e-14)
    # a massless body: the plinth's own p and Housner ratio
    light = Stack(Block.from_dimensions(0.3, 0.6), Plinth(1.0, 0.6, mass_ratio=1e3))
    assert light.p_asm == pytest.approx(Plinth(1.0, 0.6).block.p, rel=2e-3)
    assert light.eta_asm == pytest.approx(Plinth(1.0, 0.6).block.housner_restitution, rel=2e-3)
    assert s.as_block().p == pytest.approx(s.p_asm, rel=1e-14)
