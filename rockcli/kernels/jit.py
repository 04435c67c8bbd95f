"""The decorator of every kernel function: numba's ``njit`` with the options they all share.

``@kernel`` is ``@njit(cache=True, no_cfunc_wrapper=True)``; ``@kernel(inline='always')`` or
``@kernel(nogil=True)`` add to them. ``cache=True``: compiled once per machine, then loaded from the disk
cache (:mod:`rockcli.kernels.cache`). ``no_cfunc_wrapper=True``: numba otherwise also builds, optimises and
emits a C-ABI wrapper of each function, for its use as a first-class function value, which the kernels never
need (a function passed as an argument is typed as its own dispatcher; calls from Python go through the
CPython wrapper, which is kept).

A function that takes a kernel function as an argument (``_dp5_step``'s right-hand side, ``_accept_step``'s
step, ``_to_impact``'s re-step, ``_step_start``, ``batch._run_scenes``'s driver) stays ``inline='always'``:
called for real, its caller would pass the function as a value, which numba lowers as a pointer to a Python
object, and a function holding one cannot be cached ("uses dynamic globals"). The other inlined functions are
inlined for speed: without any inlining the cold compile is about a sixth cheaper, but the main job about a sixth
slower.

``@hot``: a kernel that never allocates and runs many times a step (the friction driver's mechanics, its step and
its event scans), compiled without numba's reference counting (``_nrt=False``). Numba otherwise counts a
reference to every array of an argument a function uses, on entry and on return: with the chain's workspace (a
tuple of 15 arrays) that was about 130 ns a call, half the friction driver's time (measured with ``perf``; 180 ns
against 50 ns a call of ``kernels.chain.accelerations`` for a single block). The arrays stay alive in the caller,
which holds them; a ``@hot`` function that tried to allocate would not compile.
"""

from __future__ import annotations

from numba import njit


def kernel(func=None, **options):
    """``njit(cache=True, no_cfunc_wrapper=True, **options)``, as ``@kernel`` or ``@kernel(**options)``."""
    decorate = njit(cache=True, no_cfunc_wrapper=True, **options)
    return decorate if func is None else decorate(func)


def hot(func=None, **options):
    """``kernel(_nrt=False, **options)``: for functions that never allocate (see the module notes)."""
    return kernel(func, _nrt=False, **options)
