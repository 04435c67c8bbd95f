"""rockcli: rocking and overturning of free-standing rigid blocks on rigid and isolated bases.

Implements Vassiliou & Makris (2012), "Analysis of the rocking response of rigid blocks standing
free on a seismically isolated base", Earthquake Engng Struct Dyn 41:177-196.

The main names are importable from here (``from rockcli import Block, simulate``; ``docs/python.md``):

==========================  =====================================================================
bodies and foundations      :class:`Block`, :func:`column` (the presets), :class:`Rigid`,
                            :class:`LinearIsolation`, :class:`SingleConcaveSliding`,
                            :class:`DoubleConcaveSliding`, :class:`LeadRubber`,
                            :func:`parse_isolation_spec`
ground motions              :func:`read_record`, :class:`Record`, :func:`make_pulse`,
                            :func:`parse_pulse_spec`, :func:`fit_pulse`
runs                        :func:`simulate` (-> :class:`Response` with its :class:`History`),
                            :func:`simulate_many`, :func:`simulate_verdicts`, :func:`default_rtol`
spectra                     :func:`overturning_map`, :func:`min_overturning_curves`,
                            :func:`critical_sizes`, :func:`parse_grid`
assessment                  :func:`run_assessment`, :func:`run_fragility`, :func:`parse_column_spec`,
                            :func:`parse_configurations`, :func:`resolve_excitations`,
                            :func:`find_overturn_scales`, :func:`format_verdicts`
errors                      :class:`RockcliInputError` (bad input, in one sentence)
==========================  =====================================================================

Importing this package is cheap: each name is imported from its module on first use (PEP 562), and
heavy dependencies (ObsPy, numba, pandas, matplotlib, SciPy) only by the submodules that need them.
"""

from __future__ import annotations

import importlib

__version__ = "0.1.0"

#: Each public name and the module that defines it (imported on first access).
_LAZY = {
    **dict.fromkeys(("Block", "column", "Rigid", "LinearIsolation", "SingleConcaveSliding", "DoubleConcaveSliding",
                     "LeadRubber", "parse_isolation_spec"), "rockcli.models"),
    **dict.fromkeys(("Record", "read_record"), "rockcli.records"),
    **dict.fromkeys(("make_pulse", "parse_pulse_spec", "fit_pulse"), "rockcli.pulses"),
    **dict.fromkeys(("simulate", "simulate_many", "simulate_verdicts", "default_rtol", "Response", "History"),
                    "rockcli.solve"),
    **dict.fromkeys(("overturning_map", "min_overturning_curves", "critical_sizes", "parse_grid"), "rockcli.spectra"),
    **dict.fromkeys(("run_assessment", "run_fragility", "parse_column_spec", "parse_configurations",
                     "resolve_excitations", "find_overturn_scales", "format_verdicts"), "rockcli.assess"),
    "RockcliInputError": "rockcli.errors",
}

__all__ = ["__version__", *sorted(_LAZY)]


def __getattr__(name: str):
    """Import a public name from its module on first use, then keep it here (PEP 562)."""
    module = _LAZY.get(name)
    if module is None:
        raise AttributeError(f"module 'rockcli' has no attribute {name!r}")
    value = getattr(importlib.import_module(module), name)
    globals()[name] = value
    return value


def __dir__():
    return sorted(set(globals()) | set(_LAZY))
