"""The kernels' package and module docstrings list the proofs that :mod:`rockcli.kernels.driver_end` states for
isolated bases (P9, P9s were added without the lists: polish of issue 33). Read from the sources, no
import (nothing compiles)."""

from __future__ import annotations

import ast
import re
from pathlib import Path

KERNELS = Path(__file__).resolve().parents[1] / "rockcli" / "kernels"


def _docstring(file: str, function: str | None = None) -> str:
    tree = ast.parse((KERNELS / file).read_text())
    if function is None:
        return ast.get_docstring(tree)
    return ast.get_docstring(next(n for n in ast.walk(tree) if isinstance(n, ast.FunctionDef) and n.name == function))


def _stated(doc: str) -> set:
    """The proofs a docstring states, each as a paragraph ``P9 (...)``."""
    return set(re.findall(r"^\s*(P\d+s?) \(", doc, re.M))


def test_the_lists_name_every_proof_of_the_isolated_base():
    isolated = _stated(_docstring("driver_end.py"))
    assert {"P3", "P3s", "P5", "P8", "P9", "P9s"} <= isolated
    package = " ".join(_docstring("__init__.py").split())
    listing = package[package.index("``driver``"):package.index("``batch``")]
    assert set(re.findall(r"\bP\d+s?\b", listing)) == isolated, listing
    rigid = " ".join(_docstring("rigid.py").split())
    named = set(re.findall(r"\bP\d+s?\b", rigid[:rigid.index("simulate_core")]))
    assert isolated <= named and _stated(_docstring("rigid.py")) <= named, named
