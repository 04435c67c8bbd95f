"""Output files: checked before the work starts, written atomically, every OS error as one sentence.

Every file rockcli writes (CSV tables, figures, time histories, the catalogue) goes through this
module, so that the rules hold everywhere:

* :func:`check_output` runs right after the options are parsed: the folder of an output file must
  exist, be a folder and accept a new file (probed by creating and removing an empty temporary
  file), the path must not be a folder, and a figure needs a suffix matplotlib can write. An output
  folder (``--histories DIR``) may be missing, but its nearest existing ancestor must be a writable
  folder. A long run therefore never computes for minutes and then fails on its output.
* :func:`atomic_path` (and :func:`write_bytes`, :func:`write_text`) write to a temporary file in
  the target folder and rename it onto the target with :func:`os.replace`; the temporary file is
  removed on any failure, so a reader never sees a half-written file.
* Every :class:`OSError` (missing folder, a path through a regular file, permission denied,
  read-only or virtual file system such as ``/proc``, disk full, quota) becomes one
  :class:`~rockcli.errors.RockcliInputError` sentence naming the path and the reason.

Only the standard library is imported here (records, report and the CLI all use it).
"""

from __future__ import annotations

import contextlib
import errno
import os
import secrets
import tempfile
from pathlib import Path

from rockcli.errors import RockcliInputError

__all__ = ["IMAGE_SUFFIXES", "atomic_path", "check_output", "check_output_folder", "describe_os_error",
           "write_bytes", "write_text"]

#: Image suffixes matplotlib's Agg backend writes without extra packages (jpg/tif/webp need Pillow,
#: which matplotlib requires).
IMAGE_SUFFIXES = ("png", "pdf", "svg", "svgz", "eps", "ps", "jpg", "jpeg", "tif", "tiff", "webp", "pgf", "raw",
                  "rgba")

_REASONS = {
    errno.ENOSPC: "no space left on the device",
    errno.EDQUOT: "disk quota exceeded",
    errno.EACCES: "permission denied",
    errno.EPERM: "operation not permitted",
    errno.EROFS: "read-only file system",
    errno.EISDIR: "it is a folder",
    errno.ENAMETOOLONG: "the file name is too long",
    errno.EFBIG: "the file is too large for the file system",
    errno.EIO: "input/output error of the device",
}


def _label(path, option: str | None) -> str:
    return f"{option} {path}" if option else str(path)


def _file_in_path(path: Path) -> Path | None:
    """The first component of ``path``'s folders that exists and is not a folder, if any."""
    for parent in reversed(path.parents):
        if parent.exists() and not parent.is_dir():
            return parent
    return None


def describe_os_error(exc: OSError, path, option: str | None = None) -> RockcliInputError:
    """One sentence for an :class:`OSError` met while writing ``path`` (named with its option)."""
    path = Path(path)
    label = _label(path, option)
    code = exc.errno
    if code == errno.ENOTDIR or (code == errno.ENOENT and _file_in_path(path) is not None):
        blocker = _file_in_path(path)
        if blocker is not None:
            return RockcliInputError(f"{label}: cannot write there: {blocker} is a file, not a folder")
        return RockcliInputError(f"{label}: cannot write there: a part of the path is not a folder")
    if code == errno.ENOENT:
        folder = path.parent
        if not folder.exists():
            return RockcliInputError(f"{label}: cannot write there: folder {folder} does not exist")
        return RockcliInputError(f"{label}: cannot write there: folder {folder} does not accept new files "
                                 f"(a virtual or special file system)")
    reason = _REASONS.get(code) or (exc.strerror or type(exc).__name__).lower()
    return RockcliInputError(f"{label}: cannot write there: {reason}")


def _probe_folder(folder: Path, target: Path, option: str | None) -> None:
    """Create and remove an empty temporary file in ``folder`` (raises one sentence when it fails)."""
    try:
        fd, name = tempfile.mkstemp(dir=folder, prefix=".rockcli-check-", suffix=".tmp")
    except OSError as exc:
        raise describe_os_error(exc, target, option) from None
    os.close(fd)
    with contextlib.suppress(OSError):
        os.unlink(name)


def check_output(path, option: str | None = None, *, image: bool = False) -> Path:
    """Check that the output file ``path`` can be written, before any work is done.

    Parameters
    ----------
    path : path-like
        The file to be written.
    option : str, optional
        The option that named it (``--csv``), for the message.
    image : bool
        The file is a figure: its suffix must be one of :data:`IMAGE_SUFFIXES`.

    Returns
    -------
    Path

    Raises
    ------
    RockcliInputError
        The path is a folder, its folder is missing or is a file, the folder does not accept a new
        file (permissions, read-only or virtual file system), or a figure has no known suffix.
    """
    path = Path(path)
    label = _label(path, option)
    if str(path) in ("", "."):
        raise RockcliInputError(f"{option or 'output'}: give a file name")
    if path.is_dir():
        raise RockcliInputError(f"{label}: is a folder; give a file name")
    if image:
        suffix = path.suffix.lstrip(".").lower()
        if not suffix:
            raise RockcliInputError(f"{label}: give the figure a suffix such as .png or .pdf")
        if suffix not in IMAGE_SUFFIXES:
            raise RockcliInputError(f"{label}: cannot draw a {suffix!r} figure (use one of "
                                    f"{', '.join('.' + s for s in IMAGE_SUFFIXES)})")
    blocker = _file_in_path(path)
    if blocker is not None:
        raise RockcliInputError(f"{label}: cannot write there: {blocker} is a file, not a folder")
    folder = path.parent
    if not folder.exists():
        raise RockcliInputError(f"{label}: cannot write there: folder {folder} does not exist")
    if path.exists() and not path.is_file():
        raise RockcliInputError(f"{label}: exists and is not a regular file (a device, pipe or socket)")
    _probe_folder(folder, path, option)
    return path


def check_output_folder(path, option: str | None = None) -> Path:
    """Check that files can be written into the folder ``path`` (created later if missing).

    The folder itself is not created here, so that nothing is left behind when the run fails;
    its nearest existing ancestor must be a folder that accepts new entries.
    """
    path = Path(path)
    label = _label(path, option)
    if str(path) == "":
        raise RockcliInputError(f"{option or 'output folder'}: give a folder name")
    if path.exists():
        if not path.is_dir():
            raise RockcliInputError(f"{label}: exists and is not a folder")
        _probe_folder(path, path / "x", option)
        return path
    blocker = _file_in_path(path)
    if blocker is not None:
        raise RockcliInputError(f"{label}: cannot create the folder: {blocker} is a file, not a folder")
    ancestor = next(p for p in path.parents if p.exists())
    _probe_folder(ancestor, path, option)
    return path


def _create_temporary(path: Path, option: str | None) -> Path:
    """A new, empty, hidden file next to ``path`` with the same suffix (mode 0666 less the umask)."""
    for _ in range(100):
        tmp = path.with_name(f".{path.stem}.{os.getpid()}-{secrets.token_hex(4)}.tmp{path.suffix}")
        try:
            fd = os.open(tmp, os.O_WRONLY | os.O_CREAT | os.O_EXCL, 0o666)
        except FileExistsError:
            continue
        except OSError as exc:
            raise describe_os_error(exc, path, option) from None
        os.close(fd)
        return tmp
    raise RockcliInputError(f"{_label(path, option)}: cannot create a temporary file next to it")  # pragma: no cover


@contextlib.contextmanager
def atomic_path(path, option: str | None = None):
    """Yield a temporary path next to ``path``; rename it onto ``path`` when the block succeeds.

    The temporary file (hidden, same folder and suffix) is removed whatever happens; an
    :class:`OSError` inside the block or during the rename becomes a
    :class:`~rockcli.errors.RockcliInputError` naming ``path``.

    Raises
    ------
    RockcliInputError
        If the folder of ``path`` is missing or not writable, the disk is full, ...
    """
    path = Path(path)
    if path.is_dir():
        raise RockcliInputError(f"{_label(path, option)}: is a folder; give a file name")
    blocker = _file_in_path(path)
    if blocker is not None:
        raise RockcliInputError(f"{_label(path, option)}: cannot write there: {blocker} is a file, not a folder")
    if not path.parent.is_dir():
        raise RockcliInputError(f"{_label(path, option)}: cannot write there: folder {path.parent} does not exist")
    tmp = _create_temporary(path, option)
    try:
        yield tmp
        os.replace(tmp, path)
    except OSError as exc:
        raise describe_os_error(exc, path, option) from None
    finally:
        with contextlib.suppress(OSError):
            if tmp.exists():
                tmp.unlink()


def _write(fh, data: bytes) -> None:
    """Write all of ``data`` to the open binary file ``fh`` (the one low-level write of every output)."""
    fh.write(data)


def write_bytes(path, data: bytes, option: str | None = None) -> Path:
    """Write ``data`` to ``path`` atomically (see :func:`atomic_path`)."""
    with atomic_path(path, option) as tmp:
        with open(tmp, "wb") as fh:
            _write(fh, data)
    return Path(path)


def write_text(path, text: str, option: str | None = None) -> Path:
    """Write ``text`` (UTF-8) to ``path`` atomically."""
    return write_bytes(path, text.encode("utf-8"), option)
