"""Writing files atomically: nothing is ever left half-written."""

from __future__ import annotations

import contextlib
import os
from pathlib import Path

from rockcli.errors import RockcliInputError


@contextlib.contextmanager
def atomic_path(path: str | os.PathLike):
    """Yield a temporary path next to ``path``; rename it onto ``path`` when the block succeeds.

    Raises
    ------
    RockcliInputError
        If the folder of ``path`` does not exist.
    """
    path = Path(path)
    if not path.parent.is_dir():
        raise RockcliInputError(f"{path}: folder {path.parent} does not exist")
    tmp = path.with_name(f".{path.stem}.tmp{os.getpid()}{path.suffix}")
    try:
        yield tmp
        os.replace(tmp, path)
    finally:
        if tmp.exists():
            tmp.unlink()
