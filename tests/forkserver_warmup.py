"""The fork server's warm-up (see forkserver.py): imports, kernels, a first figure, the environment it reads,
and the checks that forking is safe."""

from __future__ import annotations

import os
import sys

from forkserver import LAZY_IMPORTS


def _dispatchers():
    """Every numba dispatcher defined in rockcli.kernels (its modules all imported)."""
    import importlib
    import pkgutil

    import rockcli.kernels as kernels
    from numba.core.dispatcher import Dispatcher

    found = []
    for info in pkgutil.iter_modules(kernels.__path__):
        module = importlib.import_module(f"rockcli.kernels.{info.name}")
        for obj in vars(module).values():
            if isinstance(obj, Dispatcher) and getattr(obj.py_func, "__module__", None) == module.__name__:
                found.append(obj)
    return found


class Kernels:
    """Loads every specialisation numba's disk cache holds for the current sources, again when an index changes."""

    def __init__(self):
        self.dispatchers = _dispatchers()
        self.seen = {}  # index path -> (mtime_ns, size) when last loaded
        self.loaded = 0

    def refresh(self) -> None:
        for disp in self.dispatchers:
            cache = disp._cache
            index = getattr(getattr(cache, "_cache_file", None), "_index_path", None)
            if not index:
                continue
            try:
                st = os.stat(index)
            except OSError:
                continue
            stamp = (st.st_mtime_ns, st.st_size)
            if self.seen.get(index) == stamp:
                continue
            self.seen[index] = stamp
            codegen = disp.targetctx.codegen()
            for key in cache._cache_file._load_index():
                sig = key[0]
                args = tuple(sig.args) if hasattr(sig, "args") else tuple(sig)
                if key != cache._index_key(sig, codegen) or args in disp.overloads:
                    continue
                disp.compile(sig)  # a load from the disk cache (the key is there); see the module notes
                self.loaded += 1


def _draw_once() -> None:
    """What a process's first figure pays and its later ones do not: matplotlib's fonts opened (FreeType), the
    mathtext parser built, the Agg renderer and constrained layout run, text measured as rockcli measures it
    (about 0.4 s of CPU per command that draws). Into memory, outside pyplot (no figure number is taken), on texts
    no rockcli figure has (its cache of parsed formulas then holds nothing a command looks up).
    tests/test_forkserver.py checks that a figure is byte for byte the real process's."""
    import io

    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure
    from matplotlib.font_manager import FontProperties
    from matplotlib.textpath import TextToPath

    fig = Figure(figsize=(3.0, 2.0), layout="constrained")
    FigureCanvasAgg(fig)
    ax = fig.add_subplot()
    ax.plot([0.0, 1.0], [0.0, 1.0], label="warm-up")
    ax.set_xlabel(r"$\omega_{\mathrm{warm}}/p$ [-]")
    ax.set_ylabel("warm-up [m]")
    ax.legend()
    fig.suptitle(r"fork server warm-up $\theta_{warm}$", fontsize=9)
    fig.savefig(io.BytesIO(), format="png", dpi=50)
    for text in ("fork server warm-up", r"$\alpha_{\mathrm{warm}}$ = 1 s"):
        TextToPath().get_text_width_height_descent(text, FontProperties(size=9), ismath=text.count("$") >= 2)


def warm_up():
    """Import what the commands import and load the cached kernels; the :class:`Kernels`."""
    import importlib
    import pkgutil

    import rockcli
    import rockcli.cli

    for target in rockcli.cli._COMMANDS.values():
        importlib.import_module(target.split(":")[0])
    for info in pkgutil.walk_packages(rockcli.__path__, "rockcli."):
        importlib.import_module(info.name)
    for name in LAZY_IMPORTS:
        importlib.import_module(name)
    from rockcli.report.figures import pyplot

    pyplot()  # matplotlib on Agg, as a command that draws sets it up
    _draw_once()
    kernels = Kernels()
    kernels.refresh()
    return kernels


class EnvReads:
    """Records the environment variables Python code looks up by name (``os.environ[...]``, ``.get``,
    ``os.getenv``, ``in``) while active; a walk over the whole environment (numba's search for NUMBA_*) is not
    a lookup. Variables read by C code (getenv) are not seen: none of them is in :data:`RUNTIME_ENV`."""

    def __init__(self):
        self.names = set()

    def __enter__(self):
        cls = type(os.environ)
        self.saved = get = cls.__getitem__
        names = self.names

        def getitem(environ, key):
            caller = sys._getframe(1).f_code
            if not (caller.co_name == "__iter__" and "_collections_abc" in caller.co_filename):  # items(), values()
                names.add(os.fsdecode(key) if isinstance(key, bytes) else key)
            return get(environ, key)

        cls.__getitem__ = getitem
        return self

    def __exit__(self, *exc):
        type(os.environ).__getitem__ = self.saved


def _native_threads() -> int:
    try:
        return len(os.listdir("/proc/self/task"))
    except OSError:
        return 1


def fork_unsafe(max_native: int) -> str | None:
    """Why forking now would not be safe, or None."""
    import threading

    if threading.active_count() != 1 or threading.enumerate() != [threading.main_thread()]:
        return f"Python threads are running: {threading.enumerate()}"
    parallel = sys.modules.get("numba.np.ufunc.parallel")
    if parallel is not None and getattr(parallel, "_is_initialized", False):
        return "numba's threading layer was started"
    if _native_threads() > max_native:
        return f"{_native_threads()} native threads, more than the {max_native} the warm-up left"
    return None
