"""Compressed record files (``.gz``, ``.bz2``, ``.xz``, ``.zip``): decompressed here, then read by rockcli's own
readers with the units the record states.

Why not let ObsPy do it: ``obspy.read`` decompresses too, and then finds rockcli's PEER_AT2 plugin, which
returns the samples already converted to m/s^2. Read that way a compressed AT2 in g came back with no
stated units, the user gave ``--units g`` and the samples were converted a second time (PGA 6.84 g for a
0.697 g record). Decompressing first sends the file through exactly the path of its uncompressed copy:
same format detection, same units, one conversion.

The decompressed bytes go to a private temporary folder (the readers take paths; ObsPy's take paths or
buffers) that is removed before the function returns. At most :data:`MAX_BYTES` are decompressed: a
record is a few MB, and a small archive that expands without end must not fill the memory.
"""

from __future__ import annotations

import bz2
import gzip
import io
import lzma
import tempfile
import zipfile
from pathlib import Path
from typing import Callable

from rockcli.errors import RockcliInputError

#: First bytes -> compression.
MAGIC = {b"\x1f\x8b": "gzip", b"BZh": "bzip2", b"PK\x03\x04": "zip", b"PK\x05\x06": "zip", b"\xfd7zXZ\x00": "xz"}
#: Suffixes a compressed file's name ends with (removed to name what is inside).
_SUFFIXES = {"gzip": (".gz", ".gzip", ".z"), "bzip2": (".bz2", ".bz"), "xz": (".xz",), "zip": (".zip",)}
#: Largest decompressed record [bytes] (256 MiB: a record of 30 million samples written as text).
MAX_BYTES = 256 * 2**20
_CHUNK = 2**20


def _limited_read(stream, name: str) -> bytes:
    out = io.BytesIO()
    while True:
        chunk = stream.read(_CHUNK)
        if not chunk:
            return out.getvalue()
        out.write(chunk)
        if out.tell() > MAX_BYTES:
            raise RockcliInputError(f"{name}: decompresses to more than {MAX_BYTES // 2**20} MiB, far more than a "
                                    f"record; decompress it yourself if it really is one")


def decompress(path: Path, kind: str) -> tuple[str, bytes]:
    """The name and bytes of the one record inside the compressed file ``path``.

    Raises
    ------
    RockcliInputError
        A damaged file, an archive of several files or of a folder tree, a file compressed twice, or
        more than :data:`MAX_BYTES` once decompressed.
    """
    name = str(path)
    inner = path.name
    for suffix in _SUFFIXES[kind]:
        if inner.lower().endswith(suffix) and len(inner) > len(suffix):
            inner = inner[: -len(suffix)]
            break
    try:
        if kind == "zip":
            with zipfile.ZipFile(path) as zf:
                members = [m for m in zf.infolist() if not m.is_dir()]
                if len(members) != 1:
                    listed = ", ".join(m.filename for m in members[:5]) + (" ..." if len(members) > 5 else "")
                    raise RockcliInputError(f"{name}: the zip archive holds {len(members)} files"
                                            + (f" ({listed})" if members else "")
                                            + "; rockcli reads a zip that holds one record: extract the record first")
                with zf.open(members[0]) as fh:
                    data = _limited_read(fh, name)
                inner = Path(members[0].filename).name
        else:
            opener = {"gzip": gzip.open, "bzip2": bz2.open, "xz": lzma.open}[kind]
            with opener(path, "rb") as fh:
                data = _limited_read(fh, name)
    except RockcliInputError:
        raise
    except (OSError, EOFError, ValueError, zipfile.BadZipFile, lzma.LZMAError, RuntimeError) as exc:
        raise RockcliInputError(f"{name}: a damaged {kind} file ({exc})") from None
    if not data:
        raise RockcliInputError(f"{name}: the {kind} file holds an empty file")
    if any(data.startswith(m) for m in MAGIC):
        raise RockcliInputError(f"{name}: the {kind} file holds another compressed file; decompress it first")
    if len(data) > 262 and data[257:262] == b"ustar":
        raise RockcliInputError(f"{name}: the {kind} file holds a tar archive; extract the record first")
    return inner, data


def read_compressed(path: Path, kind: str, read: Callable[[Path], object]):
    """Decompress ``path`` and read what it holds with ``read(inner_path)``, as if it had not been compressed.

    Messages name ``path`` and the file inside (``k.AT2.gz (k.AT2 inside)``); the Record keeps ``path``
    as its file, its name, and ``meta["compression"]``.
    """
    from dataclasses import replace

    inner, data = decompress(path, kind)
    with tempfile.TemporaryDirectory(prefix="rockcli-") as tmp:
        inner_path = Path(tmp) / inner
        inner_path.write_bytes(data)
        try:
            record = read(inner_path)
        except RockcliInputError as exc:
            raise RockcliInputError(str(exc).replace(str(inner_path), f"{path} ({inner} inside)")) from None
    meta = {**record.meta, "path": str(path), "compression": kind, "member": inner}
    return replace(record, name=path.name, meta=meta)
