"""Writing report files: re-exported from :mod:`rockcli.files`, the one place that opens outputs.

:func:`save_figure` renders a matplotlib figure in memory and writes it atomically, so a figure is
either complete or absent.
"""

from __future__ import annotations

import io
import os
from pathlib import Path

from rockcli.errors import RockcliInputError
from rockcli.files import (IMAGE_SUFFIXES, atomic_path, check_output, check_output_folder, write_bytes,
                           write_text)

__all__ = ["IMAGE_SUFFIXES", "atomic_path", "check_output", "check_output_folder", "save_figure", "write_bytes",
           "write_text"]


def save_figure(fig, path: str | os.PathLike, *, dpi: int = 120) -> Path:
    """Render ``fig`` in the format named by the suffix of ``path`` and write it atomically."""
    path = Path(path)
    fmt = path.suffix.lstrip(".").lower()
    if not fmt:
        raise RockcliInputError(f"{path}: give the figure a suffix such as .png or .pdf")
    if fmt not in IMAGE_SUFFIXES:
        raise RockcliInputError(f"{path}: cannot draw a {fmt!r} figure (use one of "
                                f"{', '.join('.' + s for s in IMAGE_SUFFIXES)})")
    buf = io.BytesIO()
    try:
        fig.savefig(buf, dpi=dpi, format=fmt)
    except ValueError as exc:
        raise RockcliInputError(f"{path}: cannot draw a {fmt!r} figure ({exc})") from None
    return write_bytes(path, buf.getvalue())
