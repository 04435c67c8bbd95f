"""The lift-off floor of a body on a plinth on linear bearings (rockcli.assess.liftoff, module notes).

At rest body, plinth and base move as one mass on the bearings; the stack leaves rest where the base's absolute
acceleration first exceeds the smaller static threshold. Below the floor the compiled stack driver must therefore
never leave rest: checked on random stacks, bearings and short records at the floor itself, and the margin search
from the floor must equal the scan of every factor (a coarse grid keeps it cheap).
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from rockcli.assess.liftoff import STACK_LINEAR_MARGIN, liftoff_floors
from rockcli.assess.margin import MARGIN_RTOL, find_overturn_scales
from rockcli.models import Block, LinearIsolation, Plinth, Stack
from synthetic import random_record
from test_margin_search import _full_scan
from rockcli.solve.stack import simulate_stack


def _scene(rng):
    h1 = rng.uniform(0.6, 3.0)
    body = Block.from_dimensions(h1, h1 / rng.uniform(2.0, 6.0), "body")
    b1 = body.b * 2
    plinth = Plinth(rng.uniform(0.2, 1.5), b1 * rng.uniform(1.0, 3.0),
                    None if rng.random() < 0.5 else rng.uniform(0.3, 3.0))
    bearings = LinearIsolation(rng.uniform(1.0, 4.0), xi=rng.uniform(0.03, 0.3), gamma=rng.uniform(0.01, 0.5))
    return Stack(body, plinth), bearings, random_record(rng)


def test_nothing_lifts_at_the_floor_on_linear_bearings():
    rng = np.random.default_rng(3601)
    scenes = [_scene(rng) for _ in range(800)]
    floors = liftoff_floors(scenes)
    ran = lifted_above = 0
    for (stack, bearings, rec), floor in zip(scenes, floors):
        assert floor > 0.0
        if not math.isfinite(floor) or floor > 4.0 or floor < 0.05:
            continue
        at = simulate_stack(stack, rec.scaled(floor), isolation=bearings)
        assert math.isnan(at.body.t_uplift_s) and math.isnan(at.plinth.t_uplift_s), (stack, bearings, floor)
        assert at.toppled is None and at.settled
        ran += 1
        # the floor is not far below the true threshold: 1 % above it (ten margins) something lifts
        above = simulate_stack(stack, rec.scaled(floor * 1.01), isolation=bearings)
        lifted_above += not (math.isnan(above.body.t_uplift_s) and math.isnan(above.plinth.t_uplift_s))
    assert ran >= 300
    assert lifted_above >= 0.95 * ran  # (410 of 410 with this seed; a peak may fall between the driver's samples)
    assert STACK_LINEAR_MARGIN <= 1e-3


#: 24 factors 0.1 .. 4 with 1 among them (the search's logic, not its resolution)
GRID = np.unique(np.concatenate([np.geomspace(0.1, 1.0, 13), np.geomspace(1.0, 4.0, 12)]))


@pytest.mark.parametrize("seed", [11, 12, 13])
def test_the_margin_search_from_the_floor_equals_the_full_scan(seed):
    """The search (from each floor upwards) against every factor of the grid run, with the same bisection."""
    rng = np.random.default_rng(seed)
    scenes = [_scene(rng) for _ in range(2)]
    assert all(f > 0.1 for f in liftoff_floors(scenes))  # the floor leaves factors out
    assert find_overturn_scales(scenes, grid=GRID) == _full_scan(scenes, GRID, MARGIN_RTOL)
