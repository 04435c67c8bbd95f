"""numba's on-disk cache, keyed on the sources of the whole kernel package.

numba stamps each cached function with a hash of *its own* source file only. A kernel that calls
(or inlines) a function from another file of this package would then be loaded stale after an
edit of that callee. :class:`PackageLocator` fixes this for the functions of this package (and
only for them): their cache stamp is a SHA-256 of every ``*.py`` file of ``rockcli/kernels``,
so an edit anywhere in the package recompiles every kernel, and an unchanged package loads from
the cache. The cache lives in the package's ``__pycache__`` (numba's own default place), or, when
that is not writable, in the user cache folder (``NUMBA_CACHE_DIR`` when set).

:func:`install` registers the locator with numba; it must run before the kernel modules are
imported (numba picks a function's locator when ``@njit(cache=True)`` is applied). It changes
nothing for functions outside this package.
"""

from __future__ import annotations

import hashlib
import os
from pathlib import Path

PACKAGE_DIR = Path(__file__).resolve().parent


def source_hash(folder: Path = PACKAGE_DIR) -> str:
    """SHA-256 (hex) over the names and contents of the ``*.py`` files of ``folder``, sorted by name."""
    h = hashlib.sha256()
    for path in sorted(folder.glob("*.py")):
        h.update(path.name.encode())
        h.update(b"\0")
        h.update(path.read_bytes())
        h.update(b"\0")
    return h.hexdigest()


def install() -> None:
    """Register :class:`PackageLocator` first in numba's list of cache locators (idempotent)."""
    from numba.core import caching

    locators = caching.CacheImpl._locator_classes
    for cls in list(locators):  # a re-import of this module defines a new class: replace the old one
        if getattr(cls, "_rockcli_package_locator", False) and cls is not PackageLocator:
            locators.remove(cls)
    if PackageLocator not in locators:
        locators.insert(0, PackageLocator)


def _make_locator():
    from numba.core import caching, config

    class _PackageLocator(caching.InTreeCacheLocator):
        """Cache locator of the kernel package: stamp = hash of all its sources (see the module notes)."""

        _rockcli_package_locator = True
        _stamp = None

        def __init__(self, py_func, py_file, cache_path):
            self._py_file = py_file
            self._lineno = py_func.__code__.co_firstlineno
            self._cache_path = cache_path

        def get_source_stamp(self):
            if _PackageLocator._stamp is None:
                _PackageLocator._stamp = source_hash()
            return _PackageLocator._stamp

        @classmethod
        def from_function(cls, py_func, py_file):
            try:
                inside = Path(py_file).resolve().parent == PACKAGE_DIR
            except OSError:
                return None
            if not inside:
                return None  # not ours: numba's own locators decide
            candidates = []
            if config.CACHE_DIR:
                candidates.append(os.path.join(config.CACHE_DIR, cls.get_suitable_cache_subpath(py_file)))
            else:
                candidates.append(str(PACKAGE_DIR / "__pycache__"))
                from numba.misc.appdirs import AppDirs

                user = AppDirs(appname="numba", appauthor=False).user_cache_dir
                candidates.append(os.path.join(user, "rockcli", cls.get_suitable_cache_subpath(py_file)))
            for path in candidates:
                self = cls(py_func, py_file, path)
                try:
                    self.ensure_cache_path()
                except OSError:
                    continue
                return self
            return None

    return _PackageLocator


PackageLocator = _make_locator()
