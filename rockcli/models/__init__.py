"""Physical models: the rigid block and the foundations it stands on.

Everything here is SI: lengths [m], angles [rad], periods [s]. Each foundation carries its
kind code for :mod:`rockcli.kernels` and the number of states it adds; :mod:`rockcli.solve` turns
it into the kernel's parameter vector.

Notation follows Vassiliou & Makris (2012): ``R`` semi-diagonal, ``alpha`` slenderness,
``p = sqrt(3 g / (4 R))`` frequency parameter, ``gamma = m / (m + m_b)`` mass ratio,
``T_b = 2 pi / omega_b`` isolation period with ``omega_b = sqrt(k_b / (m + m_b))``.

Read it in this order:

===============  ========================================================================================
``limits``       the foundation kind codes, the default parameters (gamma, xi, u_y, Bouc-Wen), the
                 supported ranges (:data:`R_RANGE_M`, :data:`ALPHA_MIN_DEG`, :data:`TB_RANGE_S`,
                 :data:`XI_MAX`, :data:`UY_RANGE_M`) and the checks that refuse a value outside them
``block``        :class:`Block`, the column presets (:func:`column`), :func:`build_block`, and
                 :func:`impact_coefficient`
``foundations``  :class:`Rigid`, :class:`LinearIsolation`, :class:`SingleConcaveSliding`,
                 :class:`LeadRubber`, :class:`DoubleConcaveSliding`; :data:`HYSTERETIC`
``spec``         :func:`parse_isolation_spec`: ``"scss:Tb=3,mu=0.05"`` -> a foundation
``stack``        a body on a free plinth: :class:`Plinth`, :class:`Stack`, :func:`parse_plinth_spec`
``impact``       the impact map with a given coefficient of restitution ``E`` (``--restitution``)
``initial``      a start away from rest (``--theta0``) and the still ground of a free-rocking run
``colonnade``    a capped colonnade (``--cap-ratio``): N equal columns carrying a rigid beam
===============  ========================================================================================

Every public name is importable from ``rockcli.models``.
"""

from rockcli.models.limits import (ALPHA_MIN_DEG, DEFAULT_BW_BETA, DEFAULT_BW_GAMMA, DEFAULT_BW_N, DEFAULT_GAMMA,
                                   DEFAULT_UY, DEFAULT_XI, KIND_BILINEAR, KIND_DCSS, KIND_LINEAR, KIND_RIGID,
                                   R_RANGE_M, TB_RANGE_S, UY_RANGE_M, XI_MAX)
from rockcli.models.block import BLOCK_LABELS, COLUMN_PRESETS, Block, build_block, column, impact_coefficient
from rockcli.models.foundations import (HYSTERETIC, DoubleConcaveSliding, Foundation, LeadRubber, LinearIsolation,
                                        Rigid, SingleConcaveSliding)
from rockcli.models.spec import parse_isolation_spec
from rockcli.models.stack import MASS_RATIO_RANGE, Plinth, Stack, parse_plinth_spec

__all__ = ["ALPHA_MIN_DEG", "BLOCK_LABELS", "COLUMN_PRESETS", "DEFAULT_BW_BETA", "DEFAULT_BW_GAMMA", "DEFAULT_BW_N",
           "DEFAULT_GAMMA", "DEFAULT_UY", "DEFAULT_XI", "HYSTERETIC", "KIND_BILINEAR", "KIND_DCSS", "KIND_LINEAR",
           "KIND_RIGID", "MASS_RATIO_RANGE", "R_RANGE_M", "TB_RANGE_S", "UY_RANGE_M", "XI_MAX", "Block",
           "DoubleConcaveSliding", "Foundation", "LeadRubber", "LinearIsolation", "Plinth", "Rigid",
           "SingleConcaveSliding", "Stack", "build_block", "column", "impact_coefficient", "parse_isolation_spec",
           "parse_plinth_spec"]
