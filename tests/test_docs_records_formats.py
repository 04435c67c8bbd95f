"""docs/records-formats.md: every command of its ```bash blocks runs as printed from the repository root, in
order (exit 0). ``rockcli ...`` runs in this process (click's runner), the rest in bash."""

from __future__ import annotations

import os
import re
import shlex
import subprocess
from pathlib import Path

import pytest
from click.testing import CliRunner

ROOT = Path(__file__).resolve().parents[1]
PAGE = ROOT / "docs" / "records-formats.md"


def _commands() -> list[str]:
    blocks = re.findall(r"```bash\n(.*?)```", PAGE.read_text(), re.S)
    return [line for b in blocks for line in b.splitlines() if line.strip()]


def test_the_page_shows_commands_writing_under_out():
    cmds = _commands()
    assert len(cmds) >= 10 and all(c.startswith(("rockcli ", "mkdir -p out")) for c in cmds)
    for c in cmds:
        for target in re.findall(r"(?:--csv|--plot|--report|>)\s*(\S+)", c):
            assert target.startswith("out/"), c


def test_commands_run_as_printed(monkeypatch):
    from rockcli.cli import main

    if not (ROOT.parent / "shared" / "records").is_dir():
        pytest.skip("../shared/records (the record files) is not beside the repository")
    monkeypatch.chdir(ROOT)
    monkeypatch.setenv("ROCKCLI_RECORDS", "../shared/records:../shared/records/extra")
    monkeypatch.delenv("ROCKCLI_CATALOG", raising=False)
    for line in _commands():
        for part in line.split(" && "):
            if part.startswith("rockcli "):
                res = CliRunner().invoke(main, shlex.split(part)[1:], catch_exceptions=False)
                assert res.exit_code == 0, (part, res.output[-2000:])
            else:
                out = subprocess.run(["bash", "-c", part], cwd=ROOT, env=os.environ.copy(), capture_output=True,
                                     text=True, timeout=60)
                assert out.returncode == 0, (part, out.stderr)
