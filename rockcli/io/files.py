"""Output files: a run's outputs are one transaction, checked before the work, all written or none.

Every file rockcli writes (CSV tables, figures, time histories, the catalogue) goes through this
module, so that the rules hold everywhere:

* :func:`check_output` (and :func:`check_output_folder`, from :mod:`rockcli.io.output_checks`) run
  right after the options are parsed: the folder must exist and accept a new file, the path must
  not be a folder, a device or a read-only file, its name must fit ``NAME_MAX``, a figure needs a
  known suffix. A long run therefore never computes for minutes and then fails on its output.
* A :class:`Transaction` (:func:`transaction`; the CLI opens one around every command) collects
  the run's outputs. :meth:`Transaction.declare` refuses two outputs on one path and an output
  that is also an input (:meth:`Transaction.add_inputs`, :func:`note_inputs`: record files, manifests,
  every file of a suite folder, vertical records, both files of a pair, the catalogue), compared
  after following symbolic links and by inode (hard links). Writes (:func:`write_bytes`,
  :func:`write_text`, :func:`atomic_path`, :func:`save_figure`) go to hidden temporary files
  next to their targets; only when the whole run succeeded are they renamed onto the targets, one
  after the other with SIGINT, SIGTERM and SIGHUP held back. A run that fails, or is stopped by
  one of these signals, removes its temporary files and the folders it created: nothing changes.
* An existing output is replaced where it lives: a symbolic link stays a link (the file it points
  to is replaced) and the replaced file keeps its permission bits (and owner, where allowed).
* Every :class:`OSError` (missing folder, a path through a regular file, permission denied,
  read-only or virtual file system such as ``/proc``, disk full, quota, a name too long) becomes
  one :class:`~rockcli.errors.RockcliInputError` sentence naming the path and the reason.

Without an open transaction (library use), each write is its own transaction: atomic on its own.
Only the standard library is imported here (records, report and the CLI all use it).
"""

from __future__ import annotations

import contextlib
import io
import os
import secrets
import signal
import stat
import threading
from pathlib import Path

from rockcli.errors import RockcliInputError
from rockcli.io.output_checks import (IMAGE_SUFFIXES, _check_image_suffix, _file_in_path, _label, check_output,
                                   check_output_folder, describe_os_error, name_max, os_error_reason)

__all__ = ["IMAGE_SUFFIXES", "Transaction", "atomic_path", "check_output", "check_output_folder", "current",
           "describe_os_error", "file_key", "note_inputs", "os_error_reason", "same_file", "save_figure", "transaction",
           "write_bytes", "write_text"]

#: Signals that stop a run; while a transaction is open they remove its temporary files first.
STOP_SIGNALS = tuple(getattr(signal, n) for n in ("SIGINT", "SIGTERM", "SIGHUP") if hasattr(signal, n))



# --------------------------------------------------------------------------------------------------
# the transaction
# --------------------------------------------------------------------------------------------------
def _identity(path) -> tuple:
    """(real path, (device, inode) or None): two paths name one file when either agrees."""
    real = os.path.realpath(path)
    try:
        st = os.stat(real)
    except OSError:
        return real, None
    return real, (st.st_dev, st.st_ino)


def _same(a: tuple, b: tuple) -> bool:
    return a[0] == b[0] or (a[1] is not None and a[1] == b[1])


def file_key(path):
    """What names one file however it is reached: ``(device, inode)`` after following symbolic links (a hard
    link, a symbolic link and the file itself give one key), else the real path (a file that does not exist)."""
    real, devino = _identity(path)
    return devino if devino is not None else real


def same_file(a, b) -> bool:
    """``a`` and ``b`` name one file (after following symbolic links, or by inode: hard links)."""
    return _same(_identity(a), _identity(b))


def _temp_name(target: Path) -> str:
    """A hidden temporary name next to ``target`` that fits the file system's name limit."""
    tag = f".{os.getpid()}-{secrets.token_hex(4)}.tmp"
    room = name_max(target.parent) - len(tag) - 1
    stem = target.name
    while stem and len(os.fsencode(stem)) > room:  # shorten by characters: never cut a UTF-8 sequence
        stem = stem[:-1]
    return f".{stem}{tag}"


class Transaction:
    """The outputs of one run: declared and checked before the work, staged, then all committed.

    Use :func:`transaction` to open one; writes made while it is open are staged into it.
    """

    def __init__(self):
        self.outputs: list[tuple[tuple, Path, str | None]] = []   # (identity, path, option)
        self.inputs: list[tuple[tuple, str]] = []                 # (identity, what)
        self.staged: list[tuple[Path, Path, str | None]] = []     # (temporary, real target, option)
        self.created: list[Path] = []                             # folders this run made
        self.stopped = False                                      # a signal discarded the outputs

    # -- before the work ------------------------------------------------------------------------
    def declare(self, path, option: str | None = None, *, image: bool = False, check: bool = True,
                suffixes: tuple | None = None) -> Path:
        """Check the output file ``path`` (:func:`check_output`, with its ``image`` and ``suffixes``) against the
        other outputs and the inputs.

        ``check=False`` for a file in an output folder that is created later (the folder was
        checked by :meth:`declare_folder`): only the comparisons are made.
        """
        path = check_output(path, option, image=image, suffixes=suffixes) if check else Path(path)
        ident = _identity(path)
        for other, other_path, other_option in self.outputs:
            if _same(ident, other):
                if (other_path, other_option) == (path, option):
                    return path
                raise RockcliInputError(f"{_label(other_path, other_option)} and {_label(path, option)} are the "
                                        f"same file; give each output its own path")
        for other, what in self.inputs:
            if _same(ident, other):
                raise RockcliInputError(f"{_label(path, option)} is also an input ({what}); writing it would "
                                        f"replace what is being read: give another path")
        self.outputs.append((ident, path, option))
        return path

    def declare_folder(self, path, option: str | None = None) -> Path:
        """Check the output folder ``path`` (:func:`check_output_folder`; created when first written)."""
        return check_output_folder(path, option)

    def add_inputs(self, paths, what: str = "an input file") -> None:
        """Files the run reads: an output on one of them is refused (checked both ways)."""
        for p in paths:
            if p is None or str(p) == "":
                continue
            ident = _identity(p)
            for out, out_path, option in self.outputs:
                if _same(ident, out):
                    raise RockcliInputError(f"{_label(out_path, option)} is also an input ({what} {p}); writing it "
                                            f"would replace what is being read: give another path")
            self.inputs.append((ident, f"{what} {p}"))

    # -- during the work ------------------------------------------------------------------------
    def make_folder(self, folder, option: str | None = None) -> Path:
        """Create ``folder`` (and missing parents) now; removed again if the run fails."""
        folder = Path(folder)
        missing = [p for p in (folder, *folder.parents) if not p.exists()]
        try:
            folder.mkdir(parents=True, exist_ok=True)
        except OSError as exc:
            raise describe_os_error(exc, folder, option) from None
        self.created += reversed(missing)
        return folder

    def stage(self, path, option: str | None = None) -> Path:
        """A new empty temporary file that replaces ``path`` on :meth:`commit` (removed on failure)."""
        if self.stopped:
            raise RockcliInputError("the run was stopped by a signal; nothing was written")
        path = Path(path)
        label = _label(path, option)
        if path.is_dir():
            raise RockcliInputError(f"{label}: is a folder; give a file name")
        blocker = _file_in_path(path)
        if blocker is not None:
            raise RockcliInputError(f"{label}: cannot write there: {blocker} is a file, not a folder")
        real = Path(os.path.realpath(path))  # a symbolic link stays a link: its target is replaced
        if not real.parent.is_dir():
            raise RockcliInputError(f"{label}: cannot write there: folder {real.parent} does not exist")
        for _ in range(100):
            tmp = real.with_name(_temp_name(real))
            entry = (tmp, real, option)
            self.staged.append(entry)  # known before it exists: a signal in between removes it too
            try:
                fd = os.open(tmp, os.O_WRONLY | os.O_CREAT | os.O_EXCL, 0o666)
            except FileExistsError:
                self.staged.remove(entry)
                continue
            except OSError as exc:
                self.staged.remove(entry)
                raise describe_os_error(exc, path, option) from None
            os.close(fd)
            return tmp
        raise RockcliInputError(f"{label}: cannot create a temporary file next to it")  # pragma: no cover

    def unstage(self, tmp: Path) -> None:
        """Drop one staged file (its write failed)."""
        for entry in [e for e in self.staged if e[0] == tmp]:
            self.staged.remove(entry)
            with contextlib.suppress(OSError):
                os.unlink(tmp)

    # -- after the work -------------------------------------------------------------------------
    def commit(self) -> None:
        """Rename every staged file onto its target (signals held back meanwhile); keep modes and links."""
        if self.stopped:
            raise RockcliInputError("the run was stopped by a signal; nothing was written")
        blocked = _block_signals()
        try:
            while self.staged:
                tmp, real, option = self.staged[0]
                _keep_mode(tmp, real)
                try:
                    os.replace(tmp, real)
                except OSError as exc:
                    raise describe_os_error(exc, real, option) from None
                self.staged.pop(0)
            self.created.clear()
        finally:
            _unblock_signals(blocked)

    def discard(self) -> None:
        """Remove every staged temporary file and every folder this run created (idempotent)."""
        for tmp, _, _ in self.staged:
            with contextlib.suppress(OSError):
                os.unlink(tmp)
        self.staged.clear()
        for folder in reversed(self.created):
            with contextlib.suppress(OSError):
                folder.rmdir()  # only when empty: a folder that held files before is never touched
        self.created.clear()


def _keep_mode(tmp: Path, real: Path) -> None:
    """The new file gets the permission bits (and, where allowed, the owner) of the file it replaces."""
    try:
        st = os.stat(real)
    except OSError:
        return
    with contextlib.suppress(OSError):
        os.chmod(tmp, stat.S_IMODE(st.st_mode))
    if hasattr(os, "chown"):
        with contextlib.suppress(OSError):
            tst = os.stat(tmp)
            if (tst.st_uid, tst.st_gid) != (st.st_uid, st.st_gid):
                os.chown(tmp, st.st_uid, st.st_gid)


def _block_signals():
    if not hasattr(signal, "pthread_sigmask"):
        return None
    try:
        return signal.pthread_sigmask(signal.SIG_BLOCK, STOP_SIGNALS)
    except (OSError, ValueError):
        return None


def _unblock_signals(previous) -> None:
    if previous is not None:
        signal.pthread_sigmask(signal.SIG_SETMASK, previous)


# --------------------------------------------------------------------------------------------------
# the open transaction and the signal handlers that protect it
# --------------------------------------------------------------------------------------------------
_open: list[Transaction] = []
_previous_handlers: dict = {}


def current() -> Transaction | None:
    """The open transaction of this run, if any."""
    return _open[-1] if _open else None


def note_inputs(paths, what: str = "an input file") -> None:
    """Files the run reads (records, manifests, every file of a suite folder, the catalogue): while a
    transaction is open, an output on one of them is refused, whichever is named first. Without one
    (library use) nothing is checked."""
    t = current()
    if t is not None:
        t.add_inputs([p for p in paths if p is not None and str(p) != ""], what)


def _on_stop_signal(signum, frame):
    """SIGINT, SIGTERM or SIGHUP while outputs are open: remove them, then let the signal act."""
    for t in list(_open):
        t.discard()
        t.stopped = True
    previous = _previous_handlers.get(signum, signal.SIG_DFL)
    if callable(previous):  # SIGINT: Python's KeyboardInterrupt
        return previous(signum, frame)
    signal.signal(signum, signal.SIG_DFL)
    os.kill(os.getpid(), signum)  # the default action: the process ends by this signal


def _install_handlers() -> bool:
    if threading.current_thread() is not threading.main_thread():
        return False
    for sig in STOP_SIGNALS:
        try:
            previous = signal.getsignal(sig)
            if previous == signal.SIG_IGN or previous is None:  # e.g. SIGHUP under nohup: stays ignored
                continue
            signal.signal(sig, _on_stop_signal)
            _previous_handlers[sig] = previous
        except (OSError, ValueError):
            continue
    return True


def _restore_handlers() -> None:
    for sig, previous in list(_previous_handlers.items()):
        with contextlib.suppress(OSError, ValueError, TypeError):
            signal.signal(sig, previous)
        _previous_handlers.pop(sig, None)


@contextlib.contextmanager
def transaction():
    """Open the outputs of a run: committed when the block ends normally, discarded otherwise.

    Inside an open transaction this joins it (the outermost one commits). While it is open,
    SIGINT, SIGTERM and SIGHUP first remove its temporary files and created folders.
    """
    if _open:
        yield _open[-1]
        return
    t = Transaction()
    installed = _install_handlers()
    _open.append(t)
    try:
        yield t
        t.commit()
    finally:
        t.discard()
        _open.remove(t)
        if installed:
            _restore_handlers()


@contextlib.contextmanager
def atomic_path(path, option: str | None = None):
    """Yield a temporary path that replaces ``path`` when the run succeeds (see :class:`Transaction`).

    An :class:`OSError` inside the block becomes a :class:`~rockcli.errors.RockcliInputError`
    naming ``path``; the temporary file is then removed.
    """
    with transaction() as t:
        tmp = t.stage(path, option)
        try:
            yield tmp
        except OSError as exc:
            t.unstage(tmp)
            raise describe_os_error(exc, path, option) from None
        except BaseException:
            t.unstage(tmp)
            raise


def _write(fh, data: bytes) -> None:
    """Write all of ``data`` to the open binary file ``fh`` (the one low-level write of every output)."""
    fh.write(data)


def write_bytes(path, data: bytes, option: str | None = None) -> Path:
    """Write ``data`` to ``path`` as part of the open transaction (or atomically on its own)."""
    with atomic_path(path, option) as tmp:
        with open(tmp, "wb") as fh:
            _write(fh, data)
    return Path(path)


def write_text(path, text: str, option: str | None = None) -> Path:
    """Write ``text`` (UTF-8) to ``path`` (see :func:`write_bytes`)."""
    return write_bytes(path, text.encode("utf-8"), option)


#: Open :func:`captured_figures` blocks: each maps a figure's path to its bytes instead of writing it.
_captures: list = []


@contextlib.contextmanager
def captured_figures():
    """Inside this block :func:`save_figure` writes nothing: it records ``{path: bytes}`` in the yielded dict.

    For figures that are embedded elsewhere (the HTML report) rather than written as files: the run's
    transaction is not involved, so nothing is staged, and nothing is left behind on a signal.
    """
    got: dict = {}
    _captures.append(got)
    try:
        yield got
    finally:
        _captures.remove(got)


def save_figure(fig, path: str | os.PathLike, *, dpi: int = 120) -> Path:
    """Render the matplotlib figure ``fig`` in the format named by the suffix of ``path`` and write it."""
    path = Path(path)
    _check_image_suffix(path, str(path))
    fmt = path.suffix.lstrip(".").lower()
    buf = io.BytesIO()
    try:
        fig.savefig(buf, dpi=dpi, format=fmt)
    except ValueError as exc:
        raise RockcliInputError(f"{path}: cannot draw a {fmt!r} figure ({exc})") from None
    if _captures:
        _captures[-1][path] = buf.getvalue()
        return path
    return write_bytes(path, buf.getvalue())
