"""No module of rockcli/report imports rockcli/assess (the layers of ../shared/DESIGN.md: data flows from the
assessment to its report; ``rockcli.assess`` may import ``rockcli.report``, never the reverse). What the report
needs and does not compute lives in the report itself (the plain words: :mod:`rockcli.report.words`,
:mod:`rockcli.report.verdicts`, :mod:`rockcli.report.plinth_words`) or below both (:mod:`rockcli.models.spec`'s
configuration of one spec, :mod:`rockcli.records.unavailable`); what it computes comes in with the objects it is
given (the fragility's plotting positions and fitted probabilities are methods of the result).

Read from the sources (``ast``), nothing imported: every import statement, at module level or inside a function,
absolute or relative, and every ``importlib.import_module``/``__import__`` of a literal name."""

from __future__ import annotations

import ast
from pathlib import Path

import pytest

REPORT = Path(__file__).resolve().parents[1] / "rockcli" / "report"


def _is_assess(name: str) -> bool:
    return name == "rockcli.assess" or name.startswith("rockcli.assess.")


def assess_imports(source: str, package: str = "rockcli.report") -> list[str]:
    """The imports of ``rockcli.assess`` (or of a module of it) in ``source``, a module of ``package``, as
    ``line N: what``."""
    found = []
    for node in ast.walk(ast.parse(source)):
        if isinstance(node, ast.Import):
            found += [f"line {node.lineno}: import {a.name}" for a in node.names if _is_assess(a.name)]
        elif isinstance(node, ast.ImportFrom):
            base = node.module or ""
            if node.level:  # relative: from the package (level 1) or the packages above it
                parts = package.split(".")
                up = parts[:len(parts) - node.level + 1]
                base = ".".join(up + ([base] if base else []))
            names = [a.name for a in node.names]
            if _is_assess(base) or any(_is_assess(f"{base}.{n}") for n in names):
                found.append(f"line {node.lineno}: from {base} import {', '.join(names)}")
        elif isinstance(node, ast.Call) and node.args and isinstance(node.args[0], ast.Constant):
            f = node.func
            name = f.attr if isinstance(f, ast.Attribute) else getattr(f, "id", "")
            if name in ("import_module", "__import__") and _is_assess(str(node.args[0].value)):
                found.append(f"line {node.lineno}: {name}({node.args[0].value!r})")
    return found


def test_no_module_of_report_imports_assess():
    modules = sorted(REPORT.glob("*.py"))
    assert len(modules) > 10  # the package is where it is
    offenders = {p.name: assess_imports(p.read_text()) for p in modules}
    offenders = {k: v for k, v in offenders.items() if v}
    assert not offenders, offenders


@pytest.mark.parametrize("source", [
    "from rockcli.assess.verdicts import body_noun",
    "import rockcli.assess.scenes as s",
    "def f():\n    from rockcli.assess import column_title\n",
    "from rockcli import assess",
    "from ..assess import scenes",
    "from .. import assess",
    "import importlib\nimportlib.import_module('rockcli.assess.fragility')",
])
def test_every_form_of_import_is_seen(source):
    """The check can fail: each way of writing an import of assess is found."""
    assert assess_imports(source), source


@pytest.mark.parametrize("source", [
    "from rockcli.report.words import body_noun",
    "from rockcli.models.spec import configuration_of",
    "from . import words",
    "import rockcli.assessment_notes",  # another name that starts alike
    "text = 'rockcli.assess is imported by nobody here'",
])
def test_other_imports_are_not_counted(source):
    assert not assess_imports(source), source
