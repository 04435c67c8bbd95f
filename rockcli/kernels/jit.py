"""The decorator of every kernel function: numba's ``njit`` with the options they all share.

``@kernel`` is ``@njit(cache=True, no_cfunc_wrapper=True)``; ``@kernel(inline='always')`` or
``@kernel(nogil=True)`` add to them. ``cache=True``: compiled once per machine, then loaded from the disk
cache (:mod:`rockcli.kernels.cache`). ``no_cfunc_wrapper=True``: numba otherwise also builds, optimises and
emits a C-ABI wrapper of each function, for its use as a first-class function value, which the kernels never
need (a function passed as an argument is typed as its own dispatcher; calls from Python go through the
CPython wrapper, which is kept).
"""

from __future__ import annotations

from numba import njit


def kernel(func=None, **options):
    """``njit(cache=True, no_cfunc_wrapper=True, **options)``, as ``@kernel`` or ``@kernel(**options)``."""
    decorate = njit(cache=True, no_cfunc_wrapper=True, **options)
    return decorate if func is None else decorate(func)
