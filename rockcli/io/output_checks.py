"""Output paths checked before any work, and OS errors as one sentence (used by :mod:`rockcli.io.files`).

* :func:`check_output` (and :func:`check_output_folder`) run right after the options are parsed:
  the folder must exist (an output folder may be missing: its nearest existing ancestor must
  accept it), be a folder and accept a new file (probed by creating and removing an empty
  temporary file), the path must not be a folder, a device or a read-only file, its name must fit
  the file system's limit (``NAME_MAX``), and a figure needs a suffix matplotlib can write. A long
  run therefore never computes for minutes and then fails on its output.
* :func:`describe_os_error`: every :class:`OSError` (missing folder, a path through a regular file,
  permission denied, read-only or virtual file system such as ``/proc``, disk full, quota, a name
  too long) as one :class:`~rockcli.errors.RockcliInputError` sentence naming the path and the reason.

Only the standard library is imported here.
"""

from __future__ import annotations

import contextlib
import errno
import os
import tempfile
from pathlib import Path

from rockcli.errors import RockcliInputError

__all__ = ["IMAGE_SUFFIXES", "REPORT_SUFFIXES", "check_output", "check_output_folder", "describe_os_error", "name_max",
           "os_error_reason"]

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
    errno.EFBIG: "the file is too large for the file system (or the file size limit)",
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
    return RockcliInputError(f"{label}: cannot write there: {os_error_reason(exc)}")


def os_error_reason(exc: OSError) -> str:
    """The reason of an :class:`OSError` in a few plain words (``no space left on the device``)."""
    return _REASONS.get(exc.errno) or (exc.strerror or type(exc).__name__).lower()


def name_max(folder: Path) -> int:
    """The longest file name [bytes] the file system of ``folder`` (or its nearest existing ancestor)
    accepts; 255 when unknown."""
    for candidate in (folder, *folder.parents):
        try:
            return int(os.pathconf(candidate, "PC_NAME_MAX"))
        except (OSError, ValueError, AttributeError):
            continue
    return 255


def _check_name_length(path: Path, label: str) -> None:
    """Refuse a path component longer than the file system allows (before anything touches the path)."""
    limit = name_max(path.parent)
    for part in path.parts:
        size = len(os.fsencode(part))
        if size > limit:
            raise RockcliInputError(f"{label}: the name {part[:20]}... is {size} bytes long, more than this file "
                                    f"system's limit of {limit}")


def _probe_folder(folder: Path, target: Path, option: str | None) -> None:
    """Create and remove an empty temporary file in ``folder`` (raises one sentence when it fails)."""
    try:
        fd, name = tempfile.mkstemp(dir=folder, prefix=".rockcli-check-", suffix=".tmp")
    except OSError as exc:
        raise describe_os_error(exc, target, option) from None
    os.close(fd)
    with contextlib.suppress(OSError):
        os.unlink(name)


def _check_image_suffix(path: Path, label: str) -> None:
    suffix = path.suffix.lstrip(".").lower()
    if not suffix:
        raise RockcliInputError(f"{label}: give the figure a suffix such as .png or .pdf")
    if suffix not in IMAGE_SUFFIXES:
        raise RockcliInputError(f"{label}: cannot draw a {suffix!r} figure (use one of "
                                f"{', '.join('.' + s for s in IMAGE_SUFFIXES)})")


#: The suffixes of the HTML report (``--report``): it is one HTML page, whatever the name says.
REPORT_SUFFIXES = ("html", "htm")


def _check_suffix(path: Path, label: str, suffixes: tuple) -> None:
    """Refuse a suffix other than ``suffixes``: the file is written in the format of the first whatever its name."""
    if path.suffix.lstrip(".").lower() not in suffixes:
        raise RockcliInputError(f"{label}: this file is written as {suffixes[0].upper()}, so give it the suffix "
                                f"{' or '.join('.' + s for s in suffixes)}")


def _os_errors_named(check):
    """``check(path, option, ...)`` with an :class:`OSError` of looking at the path (``path.is_dir()`` in a folder
    without permission raises ``PermissionError``) turned into one sentence naming the path and the reason."""
    import functools

    @functools.wraps(check)
    def checked(path, option: str | None = None, **kwargs):
        try:
            return check(path, option, **kwargs)
        except OSError as exc:
            raise describe_os_error(exc, path, option) from None

    return checked


@_os_errors_named
def check_output(path, option: str | None = None, *, image: bool = False, suffixes: tuple | None = None) -> Path:
    """Check that the output file ``path`` can be written, before any work is done.

    Parameters
    ----------
    path : path-like
        The file to be written (a symbolic link is followed: the file it points to is checked).
    option : str, optional
        The option that named it (``--csv``), for the message.
    image : bool
        The file is a figure: its suffix must be one of :data:`IMAGE_SUFFIXES`.
    suffixes : tuple of str, optional
        The only suffixes (without the dot, lower case) the file may have, e.g. :data:`REPORT_SUFFIXES` for the
        HTML report (an HTML page written into ``x.pdf`` would open as a broken PDF).

    Returns
    -------
    Path

    Raises
    ------
    RockcliInputError
        The path is a folder, a device or a read-only file, its folder is missing or is a file, the
        folder does not accept a new file (permissions, read-only or virtual file system), its name
        is longer than the file system allows, a figure has no known suffix, or the suffix is not one of
        ``suffixes``.
    """
    path = Path(path)
    label = _label(path, option)
    if str(path) in ("", "."):
        raise RockcliInputError(f"{option or 'output'}: give a file name")
    _check_name_length(path, label)
    if path.is_dir():
        raise RockcliInputError(f"{label}: is a folder; give a file name")
    if image:
        _check_image_suffix(path, label)
    if suffixes:
        _check_suffix(path, label, suffixes)
    blocker = _file_in_path(path)
    if blocker is not None:
        raise RockcliInputError(f"{label}: cannot write there: {blocker} is a file, not a folder")
    if not path.parent.exists():
        raise RockcliInputError(f"{label}: cannot write there: folder {path.parent} does not exist")
    real = Path(os.path.realpath(path))  # a symbolic link: the file it points to is replaced
    if not real.parent.is_dir():
        raise RockcliInputError(f"{label}: cannot write there: the link points into {real.parent}, not a folder")
    if real.exists():
        if not real.is_file():
            raise RockcliInputError(f"{label}: exists and is not a regular file (a device, pipe or socket)")
        if not os.access(real, os.W_OK):
            raise RockcliInputError(f"{label}: the file is read-only; make it writable or give another path")
    _probe_folder(real.parent, path, option)
    return path


@_os_errors_named
def check_output_folder(path, option: str | None = None) -> Path:
    """Check that files can be written into the folder ``path`` (created later if missing).

    The folder itself is not created here, so that nothing is left behind when the run fails;
    its nearest existing ancestor must be a folder that accepts new entries.
    """
    path = Path(path)
    label = _label(path, option)
    if str(path) == "":
        raise RockcliInputError(f"{option or 'output folder'}: give a folder name")
    _check_name_length(path, label)
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
