"""Shared fixtures.

``records_dir``: the folders of real records named by ROCKCLI_RECORDS (os.pathsep-separated);
tests that need them skip cleanly when the variable is unset or names no existing folder.
"""

from __future__ import annotations

import os
from pathlib import Path

import pytest


def _record_folders() -> list[Path]:
    return [Path(p) for p in os.environ.get("ROCKCLI_RECORDS", "").split(os.pathsep) if p and Path(p).is_dir()]


@pytest.fixture(scope="session")
def records_dirs() -> list[Path]:
    """All existing folders named by ROCKCLI_RECORDS (skips when there are none)."""
    folders = _record_folders()
    if not folders:
        pytest.skip("ROCKCLI_RECORDS names no existing folder of records")
    return folders


@pytest.fixture(scope="session")
def records_dir(records_dirs) -> Path:
    """The first folder named by ROCKCLI_RECORDS (skips when there is none)."""
    return records_dirs[0]


@pytest.fixture(scope="session")
def find_record(records_dirs):
    """Function ``find_record(name) -> Path`` looking a file up in ROCKCLI_RECORDS (skips if absent)."""

    def find(name: str) -> Path:
        for folder in records_dirs:
            if (folder / name).is_file():
                return folder / name
        pytest.skip(f"{name} not found in ROCKCLI_RECORDS")

    return find
