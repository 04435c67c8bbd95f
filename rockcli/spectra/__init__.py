"""Overturning spectra, minimum overturning acceleration and critical block size (sweeps layer).

The paper's Figures 6-9 and 11 and its Table I, for any slenderness, pulse shape and isolation
(no click, no pandas: the figures and CSVs are in :mod:`rockcli.report.spectra`). Read it in this
order:

:mod:`rockcli.spectra.grids`
    The number inputs: ``start:stop:count`` grids (:class:`Grid`) and comma lists.
:mod:`rockcli.spectra.scenes`
    What is swept: a :class:`PulseChoice` (shape, optional ``T_p``, or a record's fitted pulse), an
    :class:`Isolation` with ``T_b / T_p`` fixed, and a :class:`Family` (slenderness x pulse x
    isolation on the reference block), whose cells differ only in ``x = omega_p/p`` and
    ``y = a_p/(g tan alpha)``. Its notes say why the maps do not depend on the block size. A
    :class:`VerticalChoice` is a vertical pulse under every cell (``a_v/g`` and ``T_v/T_p`` fixed).
:mod:`rockcli.spectra.plinth`
    A free plinth under every cell, in proportion to the body (:class:`PlinthRatio`, ``--on``): why ratios
    keep a spectrum dimensionless and metres would not.
:mod:`rockcli.spectra.runner`
    :class:`Cells` (the outcome arrays) and the :class:`Runner`: cells run in one batch on this
    machine or in chunks on a Dask cluster.
:mod:`rockcli.spectra.maps`
    Overturning maps over ``x`` x ``y`` (Figures 6, 9).
:mod:`rockcli.spectra.minimum`
    The uplift threshold and the minimum overturning acceleration per ``x`` (Figures 7, 8, 9, 11):
    a scan up from the uplift threshold, a finer second scan just below its first overturning
    value, then a bisection; its notes state what it guarantees and why (issue 28).
:mod:`rockcli.spectra.critical`
    Where the rigid and isolated minimum curves cross, as a block size (Table I), and the Table I
    scenes.
:mod:`rockcli.spectra.rocking`
    A record's rocking spectrum: peak ``|theta|/alpha`` against the block size R (and p), one
    :class:`RockingCurve` per slenderness and foundation, full peaks (issue 27 item 5).

Every public name is importable from ``rockcli.spectra``.
"""

from rockcli.spectra.critical import (CROSSING_GRID, TABLE_I_ALPHAS_DEG, TABLE_I_GAMMA, TABLE_I_PULSES, TABLE_I_TB_TP,
                                      TABLE_I_XI, CriticalResult, CriticalRow, critical_R, critical_sizes,
                                      table_i_isolations, table_i_pulses)
from rockcli.spectra.grids import Grid, parse_grid, parse_list
from rockcli.spectra.maps import OverturningMap, overturning_map, overturning_maps
from rockcli.spectra.minimum import (DEFAULT_AP_MAX, DEFAULT_REFINE, DEFAULT_REFINE_BAND, DEFAULT_STEP, DEFAULT_TOL,
                                     MinCurve, MinSearch, describe_search, min_overturning_curves,
                                     search_min_overturning)
from rockcli.spectra.rocking import (RecordFamily, RockingCurve, describe_sizes, frequency_parameter,
                                     isolation_helps, rocking_spectrum, size_grid, size_ranges)
from rockcli.spectra.plinth import PlinthRatio, parse_plinth_ratio
from rockcli.spectra.runner import Cells, Runner, run_cells_local
from rockcli.spectra.scenes import (REFERENCE_R, SHAPES, Family, Isolation, PulseChoice, VerticalChoice,
                                    parse_isolation, parse_pulse_choice, parse_vertical_choice, pulse_from_record)

__all__ = ["CROSSING_GRID", "DEFAULT_AP_MAX", "DEFAULT_REFINE", "DEFAULT_REFINE_BAND", "DEFAULT_STEP",
           "DEFAULT_TOL", "REFERENCE_R", "SHAPES", "TABLE_I_ALPHAS_DEG", "TABLE_I_GAMMA", "TABLE_I_PULSES",
           "TABLE_I_TB_TP", "TABLE_I_XI", "Cells", "CriticalResult", "CriticalRow", "Family", "Grid",
           "Isolation", "MinCurve", "MinSearch", "OverturningMap", "PlinthRatio", "PulseChoice", "RecordFamily",
           "RockingCurve", "Runner", "VerticalChoice", "critical_R", "critical_sizes", "describe_search", "describe_sizes",
           "frequency_parameter", "isolation_helps", "min_overturning_curves", "overturning_map",
           "overturning_maps", "parse_grid", "parse_isolation", "parse_list", "parse_plinth_ratio", "parse_pulse_choice", "parse_vertical_choice",
           "pulse_from_record", "rocking_spectrum", "run_cells_local", "search_min_overturning",
           "size_grid", "size_ranges", "table_i_isolations", "table_i_pulses"]
