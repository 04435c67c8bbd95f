"""Where the test suite's time goes: a pytest plugin that logs each test's CPU and wall time, and a summary.

Load it into a run (each worker writes its own log; without ``-n``, the one process)::

    SUITE_TIME_DIR=out/suite PYTHONPATH=benchmarks python -m pytest -q -n 2 -p suite_time

(``PYTEST_ADDOPTS="-p suite_time"`` does the same for ``bash .ci/run`` in a fresh clone.) Each log line is the
test's CPU in its worker, the CPU of the child processes the worker reaped meanwhile (commands run for real, the
fork server's children when it stops), its wall time, and its node id; and, once per worker, when it configured,
finished collecting and finished its session. Then::

    python benchmarks/suite_time.py out/suite [--top 30]

prints the time of each phase per worker and the test files and tests that cost the most CPU. The suite is
CPU-bound on two cores (its wall time is about its CPU over two), so CPU is what to cut; cProfile alone misleads
here: it inflates code made of many small Python calls several times over.
"""

from __future__ import annotations

import argparse
import os
import resource
import sys
import time
from collections import defaultdict
from pathlib import Path

_start: dict[str, tuple] = {}
_here = [True]  # False in xdist's main process, which hears of its workers' tests (their times are theirs)


def _cpu() -> tuple[float, float]:
    own, kids = resource.getrusage(resource.RUSAGE_SELF), resource.getrusage(resource.RUSAGE_CHILDREN)
    return own.ru_utime + own.ru_stime, kids.ru_utime + kids.ru_stime


def _log(line: str) -> None:
    worker = os.environ.get("PYTEST_XDIST_WORKER", "main")
    folder = Path(os.environ.get("SUITE_TIME_DIR", "out/suite"))
    folder.mkdir(parents=True, exist_ok=True)
    with open(folder / f"{worker}.tsv", "a", encoding="utf-8") as f:
        f.write(line + "\n")


def _phase(name: str) -> None:
    _log(f"#\t{time.time():.2f}\t{_cpu()[0]:.2f}\t{name}")


def pytest_configure(config):
    _here[0] = hasattr(config, "workerinput") or not getattr(config.option, "numprocesses", None)
    if _here[0]:
        _phase("configure")


def pytest_collection_finish(session):
    if _here[0]:
        _phase("collected")


def pytest_sessionfinish(session):
    if _here[0]:
        _phase("finished")


def pytest_runtest_logstart(nodeid, location):
    if _here[0]:
        _start[nodeid] = (_cpu(), time.time())


def pytest_runtest_logfinish(nodeid, location):
    if nodeid not in _start:
        return
    (own0, kids0), wall0 = _start.pop(nodeid)
    own1, kids1 = _cpu()
    _log(f"{own1 - own0:.3f}\t{kids1 - kids0:.3f}\t{time.time() - wall0:.3f}\t{nodeid}")


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("folder", type=Path)
    parser.add_argument("--top", type=int, default=25)
    args = parser.parse_args(argv)
    tests, files = [], defaultdict(lambda: [0.0, 0.0, 0.0])
    for log in sorted(args.folder.glob("*.tsv")):
        phases = {}
        for line in log.read_text(encoding="utf-8").splitlines():
            cells = line.split("\t")
            if cells[0] == "#":
                phases[cells[3]] = float(cells[1])
                continue
            own, kids, wall = map(float, cells[:3])
            tests.append((own, kids, wall, cells[3]))
            total = files[cells[3].split("::")[0]]
            total[0] += own
            total[1] += kids
            total[2] += wall
        if {"configure", "collected", "finished"} <= phases.keys():
            print(f"{log.stem}: collecting {phases['collected'] - phases['configure']:.1f} s, "
                  f"tests {phases['finished'] - phases['collected']:.1f} s (wall)")
    print(f"\n{len(tests)} tests: {sum(t[0] for t in tests):.1f} s of CPU, {sum(t[1] for t in tests):.1f} s in "
          f"reaped child processes, {sum(t[2] for t in tests):.1f} s of wall summed over the workers")
    print(f"\n{'CPU s':>7} {'child s':>7} {'wall s':>7}  file")
    for name, (own, kids, wall) in sorted(files.items(), key=lambda kv: -kv[1][0])[:args.top]:
        print(f"{own:7.1f} {kids:7.1f} {wall:7.1f}  {name}")
    print(f"\n{'CPU s':>7} {'child s':>7} {'wall s':>7}  test")
    for own, kids, wall, node in sorted(tests, reverse=True)[:args.top]:
        print(f"{own:7.1f} {kids:7.1f} {wall:7.1f}  {node}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
