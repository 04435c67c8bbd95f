"""Documentation that cannot rot.

Every ```bash block of README.md and docs/*.md (every page, found by glob, so pages added later are
covered too) is run as a user would run it: from a folder laid out like a fresh clone (a copy of the
repository's files, with ``../shared/records`` pointing at the first folder of ROCKCLI_RECORDS; the
package itself is imported from the repository, so that its compiled-kernel cache is reused) and
with ``ROCKCLI_RECORDS=../shared/records:../shared/records/extra``, each block on its own (``out/`` is
removed before it, so a block that writes there must create it). Each block must exit with code 0,
every file or folder under ``out/`` that it names must exist and be non-empty (a CSV with a header
row, a JSON output that parses), and it must write nothing outside ``out/``: neither in the copy
(the clone's files are compared before and after) nor in the repository itself (``git status``).
The commands run this repository's code (``rockcli`` and ``python`` on PATH are shims with
PYTHONPATH set to it), so the install of the machine does not matter. ``rockcli`` runs through a
pre-warmed fork server of the pytest worker (tests/forkserver*.py: each command is a child forked from a
process that has imported rockcli and loaded the kernels, set up as the real process would be; about
0.8 s of CPU less per command); ``ROCKCLI_TEST_FORKSERVER=0`` runs every command as a real process.

A page steers the test with an HTML comment just before a block (the reader does not see it; a page
that shrinks a command says so in its text):

- ``<!-- docs-test: replace "OLD" "NEW" -->`` runs the block with OLD replaced by NEW (repeat the
  comment, or give several pairs, for several replacements); used to run slow commands on a smaller
  grid or fewer records, and to send a developer's outputs into ``out/`` instead of ``docs/``;
- ``<!-- docs-test: skip REASON -->`` does not run the block (the set-up command that installs
  the package and runs this very suite).

Also checked: every relative link and image of the pages resolves (files, and ``#anchors`` to
headings), docs/cli.md is what ``docs/gen_cli_reference.py`` writes, and README.md stays a front
page (under 200 lines).
"""

from __future__ import annotations

import hashlib
import json
import os
import re
import shlex
import shutil
import subprocess
import sys
from pathlib import Path

import pytest
from forkserver import ForkServers

ROOT = Path(__file__).resolve().parents[1]
PAGES = [ROOT / "README.md"] + sorted((ROOT / "docs").glob("*.md"))

FENCE = re.compile(r"^```bash[ \t]*\n(.*?)^```[ \t]*$", re.S | re.M)
MARKER = re.compile(r"<!--\s*docs-test:(.*?)-->", re.S)
OUT_PATH = re.compile(r"(?<![\w./-])out/[\w.@%+=,/-]*[\w]")
#: per block; the slowest (the README's main job on one record, a small map) take a few seconds
TIMEOUT_S = 300


def _blocks(page: Path):
    """Yield ``(line, script, directives)`` for each ```bash block of *page*."""
    text = page.read_text(encoding="utf-8")
    for match in FENCE.finditer(text):
        before = text[: match.start()].rstrip()
        directives = []
        while before.endswith("-->"):
            start = before.rfind("<!--")
            comment = MARKER.fullmatch(before[start:]) if start >= 0 else None
            if comment is None:
                break
            directives.insert(0, comment.group(1).strip())
            before = before[:start].rstrip()
        line = text.count("\n", 0, match.start()) + 1
        yield line, match.group(1), directives


def _apply(script: str, directives: list[str]) -> tuple[str | None, str]:
    """The script to run after the page's directives (None: skipped), and the reason for a skip."""
    for directive in directives:
        words = shlex.split(directive)
        if not words:
            continue
        if words[0] == "skip":
            return None, " ".join(words[1:]) or "skipped by the page"
        if words[0] == "replace":
            pairs = words[1:]
            assert pairs and len(pairs) % 2 == 0, f"docs-test replace needs OLD NEW pairs: {directive!r}"
            for old, new in zip(pairs[::2], pairs[1::2]):
                assert old in script, f"docs-test replace: {old!r} is not in the block"
                script = script.replace(old, new)
            continue
        raise AssertionError(f"unknown docs-test directive: {directive!r}")
    return script, ""


def _all_blocks():
    params = []
    for page in PAGES:
        for line, script, directives in _blocks(page):
            rel = page.relative_to(ROOT).as_posix()
            params.append(pytest.param(page, script, directives, id=f"{rel}:{line}"))
    return params


# ---------------------------------------------------------------------------------------------------
# the clone


def _tracked_files() -> list[Path]:
    try:
        out = subprocess.run(
            ["git", "-C", str(ROOT), "ls-files", "-z"], capture_output=True, check=True, timeout=60
        ).stdout.decode()
        files = [ROOT / name for name in out.split("\0") if name]
    except (OSError, subprocess.SubprocessError):
        skip = {".git", "out", "__pycache__", ".pytest_cache", "build", "dist"}
        files = [p for p in ROOT.rglob("*") if p.is_file() and not skip & set(p.relative_to(ROOT).parts)]
    return [f for f in files if f.is_file()]


def _snapshot(folder: Path) -> dict[str, str]:
    """Every file under *folder* outside ``out/``: path -> SHA-1 of its content (links: their target)."""
    state = {}
    for path in folder.rglob("*"):
        rel = path.relative_to(folder).as_posix()
        if rel == "out" or rel.startswith("out/") or path.is_dir():
            continue
        if path.is_symlink():
            state[rel] = "link:" + os.readlink(path)
        else:
            state[rel] = hashlib.sha1(path.read_bytes()).hexdigest()
    return state


def _git_status() -> str | None:
    try:
        return subprocess.run(
            ["git", "-C", str(ROOT), "status", "--porcelain", "--untracked-files=all"],
            capture_output=True, text=True, check=True, timeout=60,
        ).stdout
    except (OSError, subprocess.SubprocessError):
        return None


def _make_clone(base: Path, records: Path, servers: ForkServers | None = None) -> tuple[Path, dict]:
    """Lay out *base* like a clone next to ``shared/records`` (a link to *records*); ``(cwd, env)``. The
    ``rockcli`` on PATH runs through one of *servers* (a pre-warmed fork server) when there is one."""
    (base / "shared").mkdir()
    (base / "shared" / "records").symlink_to(records.resolve(), target_is_directory=True)
    cwd = base / "rockcli"
    for src in _tracked_files():
        rel = src.relative_to(ROOT)
        if rel.parts[0] == "rockcli":  # the code runs from ROOT (PYTHONPATH), so numba's cache there is used
            continue
        dst = cwd / rel
        dst.parent.mkdir(parents=True, exist_ok=True)
        shutil.copy2(src, dst)
    bin_dir = base / "bin"
    bin_dir.mkdir()
    # a script, not a link: a link to a virtual environment's python, run from another folder, finds no
    # pyvenv.cfg beside it and starts the base interpreter without the environment's packages
    python = bin_dir / "python"
    python.write_text(f'#!/bin/sh\nexec "{sys.executable}" "$@"\n')
    python.chmod(0o755)
    env = {k: v for k, v in os.environ.items() if not k.startswith("ROCKCLI_")}
    env.update(
        PATH=f"{bin_dir}{os.pathsep}{env.get('PATH', '')}",
        PYTHONPATH=str(ROOT),
        ROCKCLI_RECORDS=os.pathsep.join(["../shared/records", "../shared/records/extra"]),
        MPLBACKEND="Agg",
    )
    # the real process, or a client of a fork server warmed up for this environment (tests/forkserver.py)
    shim = bin_dir / "rockcli"
    shim.write_text(servers.shim(env) if servers is not None else ForkServers.real_shim())
    shim.chmod(0o755)
    return cwd, env


@pytest.fixture(scope="module")
def clone(tmp_path_factory, fork_servers):
    """``(cwd, env)``: a copy of the repository next to ``shared/records``, and the environment."""
    folders = [p for p in os.environ.get("ROCKCLI_RECORDS", "").split(os.pathsep) if p and Path(p).is_dir()]
    if not folders:
        pytest.skip("ROCKCLI_RECORDS names no folder of records: the documented commands need them")
    # rockcli's Python bytecode is written by tests/conftest.py at the start of the session
    return _make_clone(tmp_path_factory.mktemp("docs"), Path(folders[0]), fork_servers)


# ---------------------------------------------------------------------------------------------------
# the commands


def _logical_commands(script: str) -> list[str]:
    """The script's commands: continuation lines joined, comments and blank lines dropped."""
    joined = re.sub(r"\\\n", " ", script)
    return [ln.strip() for ln in joined.splitlines() if ln.strip() and not ln.strip().startswith("#")]


def _check_outputs(script: str, cwd: Path) -> None:
    names = sorted(set(OUT_PATH.findall(script)))
    for name in names:
        path = cwd / name
        assert path.exists(), f"{name} was named by the block but not written"
        if path.is_dir():
            assert any(path.iterdir()), f"{name} is an empty folder"
            continue
        assert path.stat().st_size > 0, f"{name} is empty"
        if path.suffix == ".csv":
            header = path.read_text(encoding="utf-8").splitlines()[0].split(",")
            assert len(header) >= 2, f"{name} has no header row: {header}"
            for cell in header:
                assert cell and not re.fullmatch(r"[-+.\deE]+", cell), f"{name}: {cell!r} is not a column name"
        elif path.suffix == ".json":
            json.loads(path.read_text(encoding="utf-8"))


@pytest.mark.parametrize("page, script, directives", _all_blocks())
def test_documented_commands_run(page, script, directives, clone):
    cwd, env = clone
    to_run, reason = _apply(script, directives)
    if to_run is None:
        pytest.skip(reason)
    shutil.rmtree(cwd / "out", ignore_errors=True)  # each block starts as on a fresh clone
    before_clone, before_repo = _snapshot(cwd), _git_status()
    done = subprocess.run(
        ["bash", "-e", "-o", "pipefail", "-c", to_run],
        cwd=cwd, env=env, capture_output=True, text=True, timeout=TIMEOUT_S,
    )
    tail = f"\n--- stdout ---\n{done.stdout[-3000:]}\n--- stderr ---\n{done.stderr[-3000:]}"
    assert done.returncode == 0, f"exit code {done.returncode} from:\n{to_run}{tail}"
    _check_outputs(to_run, cwd)
    commands = _logical_commands(to_run)
    if len(commands) == 1 and "--json" in commands[0].split():
        json.loads(done.stdout)
    after_clone = _snapshot(cwd)
    changed = sorted(k for k in set(before_clone) | set(after_clone) if before_clone.get(k) != after_clone.get(k))
    assert not changed, f"the block wrote outside out/: {changed}"
    assert _git_status() == before_repo, "the block changed the repository itself (git status differs)"


# ---------------------------------------------------------------------------------------------------
# links, the generated reference, the front page

LINK = re.compile(r"!?\[[^\]]*\]\(([^)\s]+)(?:\s+\"[^\"]*\")?\)")
HTML_SRC = re.compile(r"<(?:img|a)\b[^>]*?(?:src|href)=\"([^\"]+)\"")


def _anchors(page: Path) -> set[str]:
    """GitHub's anchors of the headings of *page* (outside code blocks)."""
    text = re.sub(r"^```.*?^```", "", page.read_text(encoding="utf-8"), flags=re.S | re.M)
    anchors, seen = set(), {}
    for title in re.findall(r"^#{1,6}\s+(.*?)\s*#*\s*$", text, flags=re.M):
        slug = re.sub(r"[^\w\- ]", "", title.lower().replace("`", "")).replace(" ", "-")
        n = seen.get(slug, 0)
        seen[slug] = n + 1
        anchors.add(slug if n == 0 else f"{slug}-{n}")
    return anchors


@pytest.mark.parametrize("page", PAGES, ids=lambda p: p.relative_to(ROOT).as_posix())
def test_links_and_images_resolve(page):
    text = re.sub(r"^```.*?^```", "", page.read_text(encoding="utf-8"), flags=re.S | re.M)
    text = re.sub(r"`[^`\n]*`", "", text)
    broken = []
    for target in LINK.findall(text) + HTML_SRC.findall(text):
        if re.match(r"[a-z][a-z0-9+.-]*:", target, flags=re.I):  # http:, https:, mailto:
            continue
        path_part, _, fragment = target.partition("#")
        dest = (page.parent / path_part).resolve() if path_part else page
        if not dest.exists():
            broken.append(target)
        elif fragment and dest.suffix == ".md" and fragment not in _anchors(dest):
            broken.append(target)
    assert not broken, f"{page.name}: links that do not resolve: {broken}"


#: docs/gen_cli_reference.py --check with click's layout code made to fail: the page must not depend on it
_CLI_CHECK = r"""
import sys
import click
import click.formatting

def _no(*args, **kwargs):
    raise AssertionError("docs/gen_cli_reference.py used click's help layout")

for name in ("write_usage", "write_text", "write_dl", "write_heading", "write_paragraph"):
    setattr(click.formatting.HelpFormatter, name, _no)
click.formatting.wrap_text = _no
click.Command.get_short_help_str = click.Command.format_help = click.Command.get_help = _no
sys.path.insert(0, sys.argv[1])
import gen_cli_reference
sys.exit(gen_cli_reference.main(["--check"]))
"""


def test_cli_reference_is_current():
    """docs/cli.md is what docs/gen_cli_reference.py writes, and the script lays the page out itself: click's
    help formatter (which wraps and shortens differently from one click release to the next) is made to
    fail here, so the page is the same whatever click a fresh install gets.

    In a process of its own: click caches a command's help option on the command the first time it is
    asked for, so a test that invoked a command outside ``rockcli``'s group (no ``-h``) would change the
    help this process renders."""
    res = subprocess.run([sys.executable, "-c", _CLI_CHECK, str(ROOT / "docs")],
                         capture_output=True, text=True, cwd=ROOT, env={**os.environ, "PYTHONPATH": str(ROOT)})
    assert res.returncode == 0, f"docs/cli.md is stale: run python docs/gen_cli_reference.py\n{res.stdout}{res.stderr}"
    page = (ROOT / "docs" / "cli.md").read_text(encoding="utf-8")
    # a group lists each command with its whole first sentence (click 8.1 cut this one after "NAME...")
    assert "column     Do the columns NAME... survive the records, on a rigid base and on isolators?" in page


def test_readme_is_a_front_page():
    lines = (ROOT / "README.md").read_text(encoding="utf-8").splitlines()
    assert len(lines) < 200, f"README.md has {len(lines)} lines"
    first_blocks = [script.strip() for _, script, _ in _blocks(ROOT / "README.md")][:2]
    # the first command makes a virtual environment, installs what the three tasks use (task 3: Dask) and runs
    # the main job; the second, the test command, installs into the same environment
    venv = "python3 -m venv .venv && . .venv/bin/activate && "
    assert first_blocks[0].startswith(venv + 'python -m pip install -e ".[dask]" && ')
    assert "rockcli assess column" in first_blocks[0] and "--scheduler local" in (ROOT / "README.md").read_text()
    assert first_blocks[1].startswith(venv + "python -m pip install -e ")
    assert ".venv/" in (ROOT / ".gitignore").read_text(encoding="utf-8").split()
    # the test command is what CI runs: .ci/run runs the README's test command, line by line, in a fresh
    # virtual environment of its own (it refuses a clone that already has .venv)
    run = (ROOT / ".ci" / "run").read_text(encoding="utf-8")
    assert "if [ -e .venv ]" in run
    ci = [line.strip() for line in run.partition("# the README's test command:\n")[2].splitlines()
          if line.strip() and not line.strip().startswith("#")]
    assert first_blocks[1] == " && ".join(ci), (ci, first_blocks[1])


def test_the_harness_can_fail(tmp_path):
    """The checks above are not vacuous: a missing output, an empty one and a header-less CSV fail."""
    with pytest.raises(AssertionError):
        _check_outputs("rockcli x --csv out/missing.csv", tmp_path)
    (tmp_path / "out").mkdir()
    (tmp_path / "out" / "empty.png").write_bytes(b"")
    with pytest.raises(AssertionError):
        _check_outputs("rockcli x --plot out/empty.png", tmp_path)
    (tmp_path / "out" / "t.csv").write_text("1.0,2.0\n3,4\n")
    with pytest.raises(AssertionError):
        _check_outputs("rockcli x --csv out/t.csv", tmp_path)
    with pytest.raises(AssertionError):
        _apply("rockcli a", ['replace "not there" "x"'])
    assert _apply("rockcli a --R 0.2:20:200", ['replace "--R 0.2:20:200" "--R 0.2:20:8"'])[0] == "rockcli a --R 0.2:20:8"
