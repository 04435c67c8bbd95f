"""Do two versions of rockcli give the same answers? (simulate JSON, spectrum CSVs, assess CSV, fit-pulse CSV)

Runs a fixed set of commands with the rockcli of the working tree and with the rockcli of a git revision
(checked out into a temporary worktree), then compares every output: verdicts, statuses and other words must be
identical, numbers equal to 1e-9 relative (NaN equals NaN). Prints one line per output and exits 1 on a
difference. Used to check that a refactor changed no answer::

    ROCKCLI_RECORDS=../shared/records python benchmarks/compare_outputs.py --baseline 387b748
    python benchmarks/compare_outputs.py --write out/now            # only run, keep the outputs
    python benchmarks/compare_outputs.py --compare out/old out/now  # only compare two folders

It takes about a minute per version on a warm kernel cache (the first run of a version compiles).
"""

from __future__ import annotations

import argparse
import csv
import json
import math
import os
import shutil
import subprocess
import sys
import tempfile
from pathlib import Path

REL_TOL = 1e-9

#: (output file, arguments). ``{out}`` is the output folder. Small grids: the point is equality, not coverage.
COMMANDS = (
    ("sim-rigid-pulse.json", ["simulate", "--body", "bassae", "--pulse", "ricker-sym:ap=0.5,Tp=1.2", "--json"]),
    ("sim-rigid-sine.json", ["simulate", "--height", "2", "--width", "0.5", "--pulse", "sine:ap=0.29,Tp=2",
                             "--json", "--history", "{out}/sim-rigid-sine-history.csv"]),
    ("sim-linear-pulse.json", ["simulate", "--R", "1", "--alpha", "16", "--pulse", "ricker-anti:ap=0.6,Tp=0.8",
                               "--isolation", "linear:Tb=2.5,xi=0.1,gamma=0.01", "--json"]),
    ("sim-scss-pulse.json", ["simulate", "--R", "1", "--alpha", "16", "--pulse", "ricker-sym:ap=0.5,Tp=0.6",
                             "--isolation", "scss:Tb=1.8,mu=0.05", "--json"]),
    ("sim-dcss-pulse.json", ["simulate", "--R", "1", "--alpha", "16", "--pulse",
                             "ricker-sym:ap=1.2882024776235352,Tp=1.158400945180849",
                             "--isolation", "dcss:Tb=3.475202835542547,mu1=0.03,mu2=0.07,r=1", "--json"]),
    ("sim-lrb-pulse.json", ["simulate", "--R", "2", "--alpha", "12", "--pulse", "sine:ap=0.4,Tp=1.0",
                            "--isolation", "lrb:Tb=2.5,Q=0.06,uy=0.015", "--json"]),
    ("sim-kobe-linear.json", ["simulate", "--body", "nemea", "--record", "kobe-1995-takarazuka-000",
                              "--isolation", "linear:Tb=3", "--json"]),
    ("spectrum-overturning.csv", ["spectrum", "overturning", "--alpha", "10", "--pulse", "ricker-sym",
                                  "--isolation", "none", "--isolation", "linear:TbTp=2,xi=0.1,gamma=0.01",
                                  "--wp-over-p", "1:8:8", "--ap", "1:6:8", "--csv", "{out}/spectrum-overturning.csv"]),
    ("spectrum-min-overturning.csv", ["spectrum", "min-overturning", "--alpha", "16", "--pulse", "ricker-sym",
                                      "--isolation", "none", "--isolation", "scss:TbTp=3,mu=0.05",
                                      "--wp-over-p", "1:7:4", "--csv", "{out}/spectrum-min-overturning.csv"]),
    ("spectrum-critical-size.csv", ["spectrum", "critical-size", "--alpha", "10", "--tbtp", "2", "--xi", "0.05",
                                    "--pulse", "ricker-sym:Tp=0.6", "--wp-over-p", "0.5:12:24",
                                    "--csv", "{out}/spectrum-critical-size.csv"]),
    ("assess-column.csv", ["assess", "column", "bassae", "nemea", "--csv", "{out}/assess-column.csv"]),
    ("fit-pulse-catalog.csv", ["fit-pulse", "--catalog", "--csv", "{out}/fit-pulse-catalog.csv"]),
)


def run_all(out: Path, python: str = sys.executable, cwd: Path | None = None, env: dict | None = None) -> None:
    """Run every command of :data:`COMMANDS` with ``python -m rockcli``; stdout of ``--json`` runs is kept."""
    out.mkdir(parents=True, exist_ok=True)
    for name, args in COMMANDS:
        argv = [python, "-m", "rockcli"] + [a.replace("{out}", str(out.resolve())) for a in args]
        proc = subprocess.run(argv, cwd=cwd, env=env, capture_output=True, text=True)
        if name.endswith(".json"):
            (out / name).write_text(proc.stdout)
        (out / (name + ".exit")).write_text(f"{proc.returncode}\n")
        if proc.returncode != 0:
            print(f"  {name}: exit {proc.returncode}: {proc.stderr.strip()[-300:]}", file=sys.stderr)


def _same(a, b, where: str, diffs: list) -> None:
    if isinstance(a, dict) and isinstance(b, dict):
        for k in sorted(set(a) | set(b)):
            if k not in a or k not in b:
                diffs.append(f"{where}.{k}: only in {'new' if k in b else 'old'}")
            else:
                _same(a[k], b[k], f"{where}.{k}", diffs)
        return
    if isinstance(a, list) and isinstance(b, list):
        if len(a) != len(b):
            diffs.append(f"{where}: length {len(a)} != {len(b)}")
            return
        for i, (x, y) in enumerate(zip(a, b)):
            _same(x, y, f"{where}[{i}]", diffs)
        return
    a, b = _BOOLEANS.get(a, a), _BOOLEANS.get(b, b)
    fa, fb = _number(a), _number(b)
    if fa is not None and fb is not None:
        if math.isnan(fa) and math.isnan(fb):
            return
        if fa == fb or abs(fa - fb) <= REL_TOL * max(abs(fa), abs(fb)):
            return
        diffs.append(f"{where}: {a!r} != {b!r}")
        return
    if isinstance(a, str) and isinstance(b, str) and "/" in a and "/" in b:
        a, b = os.path.basename(a), os.path.basename(b)  # a record's path depends on where the run started
    if a != b:
        diffs.append(f"{where}: {a!r} != {b!r}")


#: CSV booleans: the spectra and bench CSVs wrote 1/0 before the one convention (True/False, as pandas and the
#: other CSVs write them); the same answer either way.
_BOOLEANS = {"True": "1", "False": "0"}


def _number(x):
    if isinstance(x, bool):
        return None
    if isinstance(x, (int, float)):
        return float(x)
    if isinstance(x, str):
        try:
            return float(x)
        except ValueError:
            return None
    if x is None:
        return None
    return None


def _load(path: Path):
    if path.suffix == ".json":
        text = path.read_text()
        return json.loads(text) if text.strip() else None
    if path.suffix == ".csv":
        with path.open(newline="") as f:
            return [row for row in csv.reader(f)]
    return path.read_text()


def compare(old: Path, new: Path) -> int:
    """Compare every file of ``old`` with its namesake in ``new``; print one line each; return the difference count."""
    bad = 0
    names = sorted({p.name for p in old.iterdir()} | {p.name for p in new.iterdir()})
    for name in names:
        a, b = old / name, new / name
        if not a.exists() or not b.exists():
            print(f"DIFF  {name}: only in {'new' if b.exists() else 'old'}")
            bad += 1
            continue
        diffs: list = []
        _same(_load(a), _load(b), name, diffs)
        if diffs:
            bad += 1
            print(f"DIFF  {name}: {len(diffs)} differences, first: {diffs[0]}")
        else:
            print(f"same  {name}")
    return bad


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--baseline", metavar="REV", help="git revision to compare the working tree with")
    ap.add_argument("--write", metavar="DIR", help="only run the commands into DIR")
    ap.add_argument("--compare", nargs=2, metavar=("OLD", "NEW"), help="only compare two output folders")
    ap.add_argument("--keep", metavar="DIR", help="with --baseline: keep both output folders under DIR")
    args = ap.parse_args(argv)
    root = Path(__file__).resolve().parent.parent
    if args.compare:
        return 1 if compare(Path(args.compare[0]), Path(args.compare[1])) else 0
    if args.write:
        run_all(Path(args.write), cwd=root)
        return 0
    if not args.baseline:
        ap.error("give --baseline REV, --write DIR or --compare OLD NEW")
    work = Path(args.keep) if args.keep else Path(tempfile.mkdtemp(prefix="rockcli-compare-"))
    tree = Path(tempfile.mkdtemp(prefix="rockcli-baseline-")) / "tree"
    subprocess.run(["git", "-C", str(root), "worktree", "add", "--detach", str(tree), args.baseline],
                   check=True, capture_output=True)
    try:
        env = dict(os.environ, PYTHONPATH=str(tree))
        print(f"running {args.baseline} ...", file=sys.stderr)
        run_all(work / "old", cwd=tree, env=env)
        print("running the working tree ...", file=sys.stderr)
        run_all(work / "new", cwd=root, env=dict(os.environ, PYTHONPATH=str(root)))
        bad = compare(work / "old", work / "new")
    finally:
        subprocess.run(["git", "-C", str(root), "worktree", "remove", "--force", str(tree)], capture_output=True)
        shutil.rmtree(tree.parent, ignore_errors=True)
    print(f"{'identical' if not bad else f'{bad} outputs differ'} (numbers to {REL_TOL:g} relative)")
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
