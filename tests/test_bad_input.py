"""Bad input never crashes, hangs or half-writes (issue 14): a parametrised table, like ObsPy's format tests.

Every CLI case must give exit code 2, exactly one line ``Error: ...`` naming the culprit, no traceback,
and leave the test folder exactly as it was (no output file, no temporary file). Every library case
must raise :class:`RockcliInputError` with a one-line message naming the culprit. The bad files are
synthesised here (small AT2 and text records), so no record folder is needed.
"""

from __future__ import annotations

import errno
import math
import os
from pathlib import Path

import numpy as np
import pytest
from click.testing import CliRunner

from rockcli.cli import main
from rockcli.errors import RockcliInputError
from rockcli.models import Block, LinearIsolation, Rigid, parse_isolation_spec
from rockcli.pulses import RickerSymmetric, make_pulse, parse_pulse_spec
from rockcli.pulses_fit import fit_pulse
from rockcli.records import read_record
from rockcli.records.record import Record
from rockcli.assess import parse_configurations, resolve_excitations, run_assessment, run_fragility
from rockcli.io.inputs import check_scale
from rockcli.solve import default_rtol, simulate, simulate_many
from rockcli.spectra import critical_sizes, min_overturning_curves, overturning_map
from rockcli.io.units import G

PROC = Path("/proc")
needs_proc = pytest.mark.skipif(not (PROC / "self").exists(), reason="no /proc file system")

# --------------------------------------------------------------------------------------------------
# synthetic records
# --------------------------------------------------------------------------------------------------
DT = 0.01
_T = DT * np.arange(600)
#: a symmetric Ricker of 0.3 g, T_p = 0.8 s, at t0 = 2.4 s: 6 s of record [g]
PULSE_G = RickerSymmetric(0.3 * G, 0.8).acceleration(_T) / G
HEAD = ["PEER NGA STRONG MOTION DATABASE RECORD", "Synthetic, 1/1/2000, Test station, 0",
        "ACCELERATION TIME SERIES IN UNITS OF G"]


def at2_text(values=PULSE_G, npts=None, dt=".0100", line4=None, head=HEAD, newline="\r\n") -> str:
    line4 = line4 if line4 is not None else f"NPTS=   {len(values) if npts is None else npts}  DT=   {dt} SEC,"
    rows = ["".join(f"{v:15.7E}" for v in values[i:i + 5]) for i in range(0, len(values), 5)]
    return newline.join([*head, line4, *rows]) + newline


def _with_token(text: str, line: int, token: str) -> str:
    """Replace the first value of (1-based) ``line`` by ``token``."""
    lines = text.split("\r\n")
    first = lines[line - 1].split()[0]
    lines[line - 1] = lines[line - 1].replace(first, token, 1)
    return "\r\n".join(lines)


GOOD_AT2 = at2_text()

#: file name -> content (str, or bytes)
BAD_FILES = {
    "nan.AT2": _with_token(GOOD_AT2, 11, "NaN"),
    "inf.AT2": _with_token(GOOD_AT2, 6, "-Infinity"),
    "token.AT2": _with_token(GOOD_AT2, 7, "1.0O00000E-02"),
    "dt0.AT2": at2_text(dt="0.0000"),
    "dtneg.AT2": at2_text(dt="-.0100"),
    "dtnan.AT2": at2_text(line4="NPTS=    600  DT=   nan SEC,"),
    "nptsneg.AT2": at2_text(line4="NPTS=  -4096  DT=   .0100 SEC,"),
    "line4.AT2": at2_text(line4="NPTS   600  DT  .0100"),
    "header2.AT2": "\r\n".join(HEAD[:2]) + "\r\n",
    "header3": "\r\n".join(HEAD) + "\r\n",  # no suffix: PEER on line 1 says it is meant as an AT2
    "short.AT2": at2_text(npts=700),
    "long.AT2": at2_text(npts=500),
    "furlongs.AT2": at2_text(head=[HEAD[0], HEAD[1], "ACCELERATION TIME SERIES IN UNITS OF FURLONGS"]),
    "velocity.AT2": at2_text(head=[HEAD[0], HEAD[1], "VELOCITY TIME SERIES IN UNITS OF CM/S"]),
    "empty.txt": "",
    "furlongs.txt": "# units: furlongs\n# dt=0.01 sec\n" + "".join(f"{float(v)!r}\n" for v in PULSE_G[:50]),
    "nounits.txt": "# dt=0.01 sec\n0.1\n0.2\n0.3\n",
    "nodt.txt": "# units: g\n0.1\n0.2\n0.3\n",
    "nan.txt": "# units: g\n# dt=0.01\n0.1\n0.2\nnan\n0.3\n",
    "word.txt": "# units: g\n# dt=0.01\n0.1\n0.2\n0.3x\n",
    "ragged.txt": "# units: g\n0 0.1\n0.01 0.2\n0.02\n",
    "time-back.txt": "# units: g\n" + "".join(f"{0.01 * i:.2f} 0.1\n" for i in (0, 1, 2, 3, 2, 5, 6, 7, 8, 9, 10, 11)),
    "time-uneven.txt": "# units: g\n" + "".join(f"{t:.3f} 0.1\n" for t in (0, .01, .02, .03, .045, .055, .065)),
    "one.txt": "# units: g\n# dt=0.01\n0.1\n",
    "zeros.txt": "# units: g\n# dt=0.01\n" + "0.0\n" * 300,
    "eight.txt": "# units: g\n# dt=0.01\n" + "0.1\n" * 5,
    "binary.bin": bytes(range(256)) * 8,
}

#: file name -> words the message must contain (read_record, records show, fit-pulse, simulate, assess)
BAD_FILE_WORDS = {
    "nan.AT2": ["nan.AT2, line 11", "is nan, not a finite number"],
    "inf.AT2": ["inf.AT2, line 6", "is -inf, not a finite number"],
    "token.AT2": ["token.AT2, line 7", "'1.0O00000E-02' is not a number"],
    "dt0.AT2": ["dt0.AT2, line 4", "DT=0 s", "must be positive"],
    "dtneg.AT2": ["dtneg.AT2, line 4", "DT=-0.01 s", "must be positive"],
    "dtnan.AT2": ["dtnan.AT2, line 4", "DT=nan is not a positive time step"],
    "nptsneg.AT2": ["nptsneg.AT2, line 4", "NPTS=-4096 is not a positive whole number"],
    "line4.AT2": ["line4.AT2, line 4", "'NPTS   600  DT  .0100'", "expected a layout such as"],
    "header2.AT2": ["header2.AT2: truncated AT2 header", "2 line(s)", "4 header lines"],
    "header3": ["header3: truncated AT2 header", "3 line(s)"],
    "short.AT2": ["short.AT2: truncated AT2 file", "NPTS=700 but only 600 values"],
    "long.AT2": ["long.AT2", "NPTS=500 but 600 values follow"],
    "furlongs.AT2": ["furlongs.AT2", "states units 'FURLONGS', which rockcli does not know", "known: g"],
    "velocity.AT2": ["velocity.AT2", "holds velocity, not acceleration"],
    "empty.txt": ["empty.txt: the file is empty"],
    "furlongs.txt": ["furlongs.txt", "states units 'furlongs', which rockcli does not know", "known: g"],
    "nounits.txt": ["nounits.txt: the file does not state its units", "--units"],
    "nodt.txt": ["nodt.txt: the file does not state its time step", "--dt"],
    "nan.txt": ["nan.txt, line 5", "value nan in column 1 is not a finite number"],
    "word.txt": ["word.txt, line 5", "'0.3x' is not a number"],
    "ragged.txt": ["ragged.txt, line 4", "1 values where the first data row has 2"],
    "time-back.txt": ["time-back.txt, line 6", "the time column is not increasing"],
    "time-uneven.txt": ["time-uneven.txt", "not uniformly sampled"],
    "one.txt": ["one.txt", "at least 2 are needed"],
    "binary.bin": ["binary.bin", "format not recognised"],
}


@pytest.fixture
def work(tmp_path, monkeypatch):
    """A scratch folder (the current directory) holding the bad files, a good AT2 and a plain file."""
    for name, content in BAD_FILES.items():
        (tmp_path / name).write_bytes(content if isinstance(content, bytes) else content.encode("latin-1"))
    (tmp_path / "good.AT2").write_bytes(GOOD_AT2.encode("latin-1"))
    (tmp_path / "afile").write_text("a regular file, not a folder\n")
    (tmp_path / "adir").mkdir()
    (tmp_path / "notes").mkdir()  # a suite folder holding no record
    (tmp_path / "notes" / "README.md").write_text("# Records\n\nnone yet\n")
    (tmp_path / "m.csv").write_text("file,units\ngood.AT2,\n")  # a manifest
    (tmp_path / "hdr.csv").write_text("file,units\n")  # a manifest with only its header
    (tmp_path / "latin.csv").write_bytes("file,units\nr\u00e9.AT2,g\n".encode("latin-1"))
    (tmp_path / "link.AT2").symlink_to("good.AT2")
    monkeypatch.chdir(tmp_path)
    return tmp_path


def snapshot(folder: Path) -> dict:
    """Every path under ``folder`` (hidden ones too); files with their size and modification time."""
    return {str(p.relative_to(folder)): (p.stat().st_size, p.stat().st_mtime_ns) if p.is_file() else "folder"
            for p in sorted(folder.rglob("*"))}


def assert_one_sentence(res, words):
    out = res.output
    assert "Traceback" not in out, out
    lines = [ln for ln in out.splitlines() if ln.strip()]
    assert res.exit_code == 2, out
    assert len(lines) == 1 and lines[0].startswith("Error: "), out
    for w in words:
        assert w in lines[0], (w, out)
    assert "np.float64" not in out


def run_cli(args):
    return CliRunner().invoke(main, [str(a) for a in args])


# --------------------------------------------------------------------------------------------------
# the table: (command line, words the single error line must contain)
# --------------------------------------------------------------------------------------------------
SIM = ["simulate", "--height", "2", "--width", "0.5"]
SINE = ["--pulse", "sine:ap=0.5,Tp=0.5"]
ASSESS = ["assess", "column", "bassae", "--no-margin", "--isolation", "none"]

CLI_CASES = {
    # ---- records show: every bad file, and bad options
    **{f"show-{name}": (["records", "show", name], words) for name, words in BAD_FILE_WORDS.items()},
    "show-dev-zero": (["records", "show", "/dev/zero"], ["/dev/zero: is not a regular file"]),
    "show-missing": (["records", "show", "missing.AT2"], ["missing.AT2: no such file"]),
    "show-folder": (["records", "show", "adir"], ["adir: is a folder, not a record file"]),
    "show-under-file": (["records", "show", "afile/x.AT2"], ["afile/x.AT2: no such file"]),
    "show-dt0": (["records", "show", "nounits.txt", "--units", "g", "--dt", "0"], ["dt=0 s must be a positive"]),
    "show-units": (["records", "show", "nodt.txt", "--units", "furlongs", "--dt", "0.01"],
                   ["unknown acceleration unit 'furlongs'", "known: g"]),
    "show-column0": (["records", "show", "good.AT2", "--record-column", "0"], ["column 0 must be a whole number >= 1"]),
    "show-units-conflict": (["records", "show", "good.AT2", "--units", "gal"], ["states units 'G' but 'gal' was given"]),
    "show-plot-proc": pytest.param((["records", "show", "good.AT2", "--plot", "/proc/x.png"],
                                    ["--plot /proc/x.png: cannot write there", "/proc"]), marks=needs_proc),
    "show-plot-under-file": (["records", "show", "good.AT2", "--plot", "afile/x.png"],
                             ["--plot afile/x.png: cannot write there: afile is a file, not a folder"]),
    "show-plot-missing-folder": (["records", "show", "good.AT2", "--plot", "nope/x.png"],
                                 ["folder nope does not exist"]),
    "show-plot-suffix": (["records", "show", "good.AT2", "--plot", "x.foo"], ["--plot x.foo", "'foo' figure"]),
    "show-plot-nosuffix": (["records", "show", "good.AT2", "--plot", "x"], ["--plot x: give the figure a suffix"]),
    "show-plot-is-folder": (["records", "show", "good.AT2", "--plot", "adir"], ["--plot adir: is a folder"]),
    "list-csv-proc": pytest.param((["records", "list", "--csv", "/proc/x.csv"], ["--csv /proc/x.csv: cannot write"]),
                                  marks=needs_proc),
    "list-csv-under-file": (["records", "list", "--csv", "afile/x.csv"], ["afile is a file, not a folder"]),
    # ---- fit-pulse
    "fit-nan": (["fit-pulse", "nan.AT2"], BAD_FILE_WORDS["nan.AT2"]),
    "fit-dt0": (["fit-pulse", "dt0.AT2"], BAD_FILE_WORDS["dt0.AT2"]),
    "fit-one-bad-of-two": (["fit-pulse", "good.AT2", "token.AT2", "--csv", "fits.csv"], BAD_FILE_WORDS["token.AT2"]),
    "fit-zeros": (["fit-pulse", "zeros.txt"], ["'zeros.txt' is all zeros"]),
    "fit-few": (["fit-pulse", "eight.txt"], ["too few samples"]),
    "fit-periods-beyond-record": (["fit-pulse", "good.AT2", "--periods", "50:100"],
                                  ["lasts 5.99 s", "shortest period searched 50 s"]),
    "fit-periods-reversed": (["fit-pulse", "good.AT2", "--periods", "6:0.1"], ["--periods '6:0.1'", "0 < min < max"]),
    "fit-periods-zero": (["fit-pulse", "good.AT2", "--periods", "0:1"], ["0 < min < max"]),
    "fit-periods-nan": (["fit-pulse", "good.AT2", "--periods", "nan:1"], ["--periods 'nan:1'"]),
    "fit-periods-word": (["fit-pulse", "good.AT2", "--periods", "x"], ["--periods 'x' must be MIN:MAX"]),
    "fit-periods-dt": (["fit-pulse", "good.AT2", "--periods", "0.001:0.02"], ["too short for its time step 0.01 s"]),
    "fit-csv-proc": pytest.param((["fit-pulse", "good.AT2", "--csv", "/proc/x.csv"], ["--csv /proc/x.csv"]),
                                 marks=needs_proc),
    "fit-csv-under-file": (["fit-pulse", "good.AT2", "--csv", "afile/x.csv"],
                           ["--csv afile/x.csv: cannot write there: afile is a file, not a folder"]),
    "fit-csv-is-folder": (["fit-pulse", "good.AT2", "--csv", "adir"], ["--csv adir: is a folder"]),
    "fit-plot-suffix": (["fit-pulse", "good.AT2", "--plot", "fits.xyz"], ["--plot fits.xyz", "'xyz' figure"]),
    # ---- simulate
    "sim-t0-negative": ([*SIM, "--pulse", "sine:ap=0.5,Tp=0.5,t0=-0.25"],
                        ["starts at -0.25 s, before the run starts at t = 0 s", "t0 >= 0 s"]),
    "sim-ricker-t0-early": ([*SIM, "--pulse", "ricker-sym:ap=0.5,Tp=0.5,t0=1"],
                            ["starts at -0.5 s", "give t0 >= 1.5 s"]),
    "sim-t0-huge": ([*SIM, "--pulse", "sine:ap=0.5,Tp=0.5,t0=1e12"], ["starts at 1e+12 s", "1e+06 T_p = 500000 s"]),
    "sim-alpha-tiny": (["simulate", "--R", "1", "--alpha", "1e-9", *SINE], ["alpha = 1e-09 deg", "supported 1 deg"]),
    "sim-alpha-needle": (["simulate", "--R", "1", "--alpha", "0.5", *SINE], ["alpha = 0.5 deg", "h/b = 115 > 57"]),
    "sim-alpha-90": (["simulate", "--R", "1", "--alpha", "90", *SINE], ["strictly between 0 and 90"]),
    "sim-R-tiny": (["simulate", "--R", "1e-6", "--alpha", "10", *SINE], ["R = 1e-06 m", "0.01 m to 100 m"]),
    "sim-height-huge": (["simulate", "--height", "1e6", "--width", "1", *SINE],
                        ["R = 500000 m (from height 1e+06 m and width 1 m)"]),
    "sim-width-nan": (["simulate", "--height", "2", "--width", "nan", *SINE], ["--width 'nan' is not a finite number"]),
    "sim-Tb-tiny": ([*SIM, *SINE, "--isolation", "linear:Tb=1e-6"], ["Tb = 1e-06 s", "0.005 s to 1e+06 s"]),
    "sim-xi-huge": ([*SIM, *SINE, "--isolation", "linear:Tb=2,xi=1e6"], ["xi = 1e+06", "supported 10"]),
    "sim-gamma-1": ([*SIM, *SINE, "--isolation", "linear:Tb=2,gamma=1"], ["0 <= gamma < 1", "got 1"]),
    "sim-Tb-word": ([*SIM, *SINE, "--isolation", "linear:Tb=abc"], ["Tb must be a number, got 'abc'"]),
    "sim-iso-unknown": ([*SIM, *SINE, "--isolation", "rubber:mu=0.1"], ["unknown isolation 'rubber'"]),
    "sim-iso-scss-no-tb": ([*SIM, *SINE, "--isolation", "scss:mu=0.1"], ["needs Tb"]),
    "sim-stiff-undamped": ([*SIM, "--record", "good.AT2", "--isolation", "linear:Tb=0.005,xi=0"],
                           ["integrator steps", "with xi = 0", "linear:Tb=0.005,xi=0"]),
    "sim-tail-huge": ([*SIM, *SINE, "--tail", "1e6"], ["tail must be a time between 0 and 1000 s"]),
    "sim-tail-negative": ([*SIM, *SINE, "--tail", "-1"], ["tail must be a time between 0 and 1000 s"]),
    "sim-rtol": ([*SIM, *SINE, "--rtol", "0.5"], ["rtol must lie between 1e-14 and 1e-2"]),
    "sim-ap-huge": ([*SIM, "--pulse", "sine:ap=500,Tp=0.5"], ["a_p = 500 g", "100 g"]),
    "sim-Tp-huge": ([*SIM, "--pulse", "sine:ap=0.5,Tp=1e5"], ["T_p = 100000 s", "0.001 s to 1000 s"]),
    "sim-Tp-tiny": ([*SIM, "--pulse", "sine:ap=0.5,Tp=1e-9"], ["T_p = 1e-09 s"]),
    "sim-Tp-missing": ([*SIM, "--pulse", "sine:ap=0.5"], ["is missing Tp"]),
    "sim-t0-nan": ([*SIM, "--pulse", "sine:ap=0.5,Tp=0.5,t0=nan"], ["t0 must be finite"]),
    "sim-shape": ([*SIM, "--pulse", "gabor:ap=0.5,Tp=0.5"], ["unknown pulse shape 'gabor'"]),
    "sim-scale-0": ([*SIM, "--record", "good.AT2", "--scale", "0"], ["--scale must be a finite non-zero number"]),
    "sim-scale-nan": ([*SIM, "--record", "good.AT2", "--scale", "nan"], ["--scale 'nan' is not a finite number"]),
    "sim-no-motion": (SIM, ["exactly one of --record SOURCE or --pulse SPEC"]),
    "sim-two-blocks": (["simulate", "--body", "bassae", "--R", "1", "--alpha", "10", *SINE], ["exactly one of"]),
    "sim-record-nan": ([*SIM, "--record", "nan.AT2"], BAD_FILE_WORDS["nan.AT2"]),
    "sim-record-dev-zero": ([*SIM, "--record", "/dev/zero", "--units", "g", "--dt", "0.01"], ["not a regular file"]),
    "sim-history-proc": pytest.param(([*SIM, *SINE, "--history", "/proc/h.csv"], ["--history /proc/h.csv"]),
                                     marks=needs_proc),
    "sim-plot-proc": pytest.param(([*SIM, *SINE, "--plot", "/proc/h.png"], ["--plot /proc/h.png"]), marks=needs_proc),
    "sim-history-under-file": ([*SIM, *SINE, "--history", "afile/h.csv"], ["afile is a file, not a folder"]),
    "sim-plot-suffix": ([*SIM, *SINE, "--plot", "h.abc"], ["'abc' figure"]),
    # ---- assess column
    "assess-all-nan": ([*ASSESS, "--records", "nan.AT2", "--csv", "t.csv"], BAD_FILE_WORDS["nan.AT2"]),
    "assess-all-dt0": ([*ASSESS, "--records", "dt0.AT2", "--csv", "t.csv"], BAD_FILE_WORDS["dt0.AT2"]),
    "assess-all-header": ([*ASSESS, "--records", "header2.AT2", "--csv", "t.csv"], BAD_FILE_WORDS["header2.AT2"]),
    "assess-missing": ([*ASSESS, "--records", "nope.AT2"], ["--records nope.AT2: no such file or folder"]),
    "assess-csv-proc": pytest.param(([*ASSESS, "--records", "good.AT2", "--csv", "/proc/t.csv"], ["--csv /proc/t.csv"]),
                                    marks=needs_proc),
    "assess-plot-proc": pytest.param(([*ASSESS, "--records", "good.AT2", "--plot-dir", "/proc/pd"], ["--plot-dir /proc/pd"]),
                                     marks=needs_proc),
    "assess-csv-under-file": ([*ASSESS, "--records", "good.AT2", "--csv", "afile/t.csv"],
                              ["--csv afile/t.csv: cannot write there: afile is a file, not a folder"]),
    "assess-histories-under-file": ([*ASSESS, "--records", "good.AT2", "--history-dir", "afile/h"],
                                    ["--history-dir afile/h: cannot create the folder: afile is a file"]),
    "assess-histories-is-file": ([*ASSESS, "--records", "good.AT2", "--history-dir", "afile"],
                                 ["--history-dir afile: exists and is not a folder"]),
    "assess-Tb-tiny": (["assess", "column", "bassae", "--records", "good.AT2", "--isolation", "linear:Tb=1e-6"],
                       ["Tb = 1e-06 s"]),
    "assess-xi-huge": (["assess", "column", "bassae", "--records", "good.AT2", "--isolation", "linear:Tb=2,xi=1e6"],
                       ["xi = 1e+06"]),
    "assess-custom-alpha": (["assess", "column", "needle:R=1,alpha=1e-9", "--records", "good.AT2"],
                            ["alpha = 1e-09 deg"]),
    "assess-custom-R": (["assess", "column", "--R", "1e-6", "--alpha", "10", "--records", "good.AT2"],
                        ["R = 1e-06 m"]),
    "assess-unknown-column": (["assess", "column", "parthenon", "--records", "good.AT2"], ["unknown body 'parthenon'"]),
    "fragility-all-nan": (["assess", "fragility", "bassae", "--records", "nan.AT2", "--csv", "f.csv"],
                          BAD_FILE_WORDS["nan.AT2"]),
    "fragility-csv-under-file": (["assess", "fragility", "bassae", "--records", "good.AT2", "--csv", "afile/f.csv"],
                                 ["--csv afile/f.csv: cannot write there: afile is a file, not a folder"]),
    "fragility-plot-suffix": (["assess", "fragility", "bassae", "--records", "good.AT2", "--plot", "f.abc"],
                              ["--plot f.abc", "'abc' figure"]),
    # ---- issue 34: pairs, manifests and suites, sizes known before the work, scale factors, values as given
    "sim-pair-one-file": ([*SIM, "--record", "good.AT2@0", "--record-2", "good.AT2@90", "--azimuth", "30"],
                          ["--record good.AT2@0 and --record-2 good.AT2@90 are one file (good.AT2)",
                           "a pair is two different horizontal components"]),
    "sim-pair-one-file-link": ([*SIM, "--record", "good.AT2@0", "--record-2", "link.AT2@90", "--azimuth", "30"],
                               ["are one file (good.AT2)"]),
    "sim-azimuth-step-fine": ([*SIM, "--record", "good.AT2@0", "--record-2", "link.AT2@90", "--azimuth", "worst",
                               "--azimuth-step", "1e-9"], ["--azimuth-step 1e-09 must lie between 0.1 deg"]),
    "sim-azimuth-step-coarse": ([*SIM, "--record", "good.AT2@0", "--record-2", "link.AT2@90", "--azimuth", "worst",
                                 "--azimuth-step", "95"], ["--azimuth-step 95 must lie between 0.1 deg", "and 90 deg"]),
    "sim-history-dt-rows": ([*SIM, "--record", "good.AT2", "--history-dt", "1e-6", "--history", "h.csv"],
                            ["a history every 1e-06 s from 0 s to 15.99 s (the excitation's end plus the tail)",
                             "rows, more than the 2,000,000 allowed"]),
    "sim-scale-peak": ([*SIM, "--record", "good.AT2", "--scale", "1000"],
                       ["--scale 1000 takes the peak of the record from 0.3 g to 300 g", "the supported 100 g"]),
    "sim-scale-flip-peak": ([*SIM, "--record", "good.AT2", "--scale", "-400", "--flip"], ["--scale -400 takes"]),
    "sim-scale-huge-pulse": ([*SIM, "--pulse", "sine:ap=0.5,Tp=0.5", "--scale", "1e308"],
                             ["--scale 1e+308 takes the peak of the pulse from 0.5 g to 5e+307 g"]),
    "sim-vertical-scale": ([*SIM, "--record", "good.AT2", "--vertical", "link.AT2", "--vertical-scale", "1e306"],
                           ["--vertical-scale 1e+306 takes the peak of the vertical record"]),
    "assess-vertical-scale": ([*ASSESS, "--records", "good.AT2", "--vertical-pulse", "sine:ap=0.1,Tp=0.5",
                               "--vertical-scale", "2000"],
                              ["--vertical-scale 2000 takes the peak of the vertical pulse"]),
    "rocking-scale": (["spectrum", "rocking", "good.AT2", "--alpha", "10", "--scale", "500"],
                      ["--scale 500 takes the peak of the record"]),
    "sim-alpha-as-given": (["simulate", "--R", "1", "--alpha", "0.9999", *SINE], ["alpha = 0.9999 deg is below"]),
    "sim-horizon-as-given": ([*SIM, *SINE, "--horizon", "3600.0001"], ["got 3600.0001"]),
    "critical-Tp-tiny": (["spectrum", "critical-size", "--pulse", "sine:Tp=1e-9", "--alpha", "10", "--step", "0.5"],
                         ["Tp 1e-9 must lie between 0.001 and 1000 s"]),
    "min-ap-max-huge": (["spectrum", "min-overturning", "--alpha", "10", "--ap-max", "1e300", "--wp-over-p", "2:2:1"],
                        ["ap_max must be at most 10000", "got 1e+300"]),
    "column-no-record": ([*ASSESS, "--records", "notes"], ["no record to run: no file of the folder(s) is a record",
                                                           "notes/README.md"]),
    "fragility-no-record": (["assess", "fragility", "bassae", "--records", "notes", "--bootstrap", "0"],
                            ["no record to run: no file of the folder(s) is a record"]),
    "column-manifest-header-only": ([*ASSESS, "--records", "hdr.csv"],
                                    ["hdr.csv: the manifest names no record: it has its header line and no row"]),
    "fragility-manifest-header-only": (["assess", "fragility", "bassae", "--records", "hdr.csv"],
                                       ["hdr.csv: the manifest names no record"]),
    "column-manifest-latin1": ([*ASSESS, "--records", "latin.csv"],
                               ["latin.csv, line 2: the manifest is not UTF-8 text (byte 0xe9)"]),
    "column-csv-over-manifest": ([*ASSESS, "--records", "m.csv", "--csv", "m.csv"],
                                 ["--csv m.csv is also an input (the manifest m.csv)"]),
    # the report is an HTML page whatever its name: any other suffix is refused before the manifest is looked at
    "fragility-report-over-manifest": (["assess", "fragility", "bassae", "--records", "m.csv", "--report", "m.csv"],
                                       ["--report m.csv: this file is written as HTML, so give it the suffix .html "
                                        "or .htm"]),
    "sim-two-pulses-json": ([*SIM, *SINE, "--pulse", "sine:ap=0.3,Tp=2", "--json"],
                            ["--json takes one scene: several --pulse draw their scenes side by side with --plot"]),
    "sim-two-pulses-no-plot": ([*SIM, *SINE, "--pulse", "sine:ap=0.3,Tp=2"],
                               ["several --pulse draw their scenes side by side: give --plot FILE"]),
    "sim-two-of-both": ([*SIM, *SINE, "--pulse", "sine:ap=0.3,Tp=2", "--isolation", "none", "--isolation",
                         "linear:Tb=2", "--plot", "f.png"],
                        ["give several --pulse or several --isolation, not both"]),
    "sim-two-isolations-history": ([*SIM, *SINE, "--isolation", "none", "--isolation", "linear:Tb=2", "--plot",
                                    "f.png", "--history", "h.csv"], ["--history takes one scene"]),
    "sim-report-pdf": ([*SIM, *SINE, "--report", "x.pdf"],
                       ["--report x.pdf: this file is written as HTML, so give it the suffix .html or .htm"]),
    "column-report-no-suffix": ([*ASSESS, "--records", "good.AT2", "--report", "report"],
                                ["--report report: this file is written as HTML"]),
    "column-csv-over-folder-file": ([*ASSESS, "--records", "notes", "--csv", "notes/README.md"],
                                    ["--csv notes/README.md is also an input (a file of the suite folder notes"]),
}


@pytest.mark.parametrize("case", CLI_CASES.values(), ids=list(CLI_CASES))
def test_cli_bad_input(work, case):
    args, words = case
    before = snapshot(work)
    res = run_cli(args)
    assert_one_sentence(res, words)
    assert snapshot(work) == before  # nothing written, no temporary file left


# --------------------------------------------------------------------------------------------------
# a full disk: every output written through rockcli.io.files fails half-way with ENOSPC
# --------------------------------------------------------------------------------------------------
def _full_disk(monkeypatch):
    import rockcli.io.files

    def write(fh, data):
        fh.write(data[: len(data) // 2])  # half of it reaches the disk, then the disk is full
        raise OSError(errno.ENOSPC, os.strerror(errno.ENOSPC))

    monkeypatch.setattr(rockcli.io.files, "_write", write)


FULL_DISK_CASES = {
    "records-list-csv": (["records", "list", "--csv", "out.csv"], "out.csv"),
    "records-show-plot": (["records", "show", "good.AT2", "--plot", "out.png"], "out.png"),
    "fit-csv": (["fit-pulse", "good.AT2", "--csv", "out.csv"], "out.csv"),
    "fit-plot": (["fit-pulse", "good.AT2", "--plot", "out.png"], "out.png"),
    "simulate-history": ([*SIM, *SINE, "--history", "out.csv"], "out.csv"),
    "simulate-plot": ([*SIM, *SINE, "--plot", "out.png"], "out.png"),
    "assess-csv": ([*ASSESS, "--records", "good.AT2", "--csv", "out.csv"], "out.csv"),
    "assess-histories": ([*ASSESS, "--records", "good.AT2", "--history-dir", "h/deeper"], "h/deeper"),
    "assess-plots": ([*ASSESS, "--records", "good.AT2", "--plot-dir", "figs"], "figs"),
}


@pytest.mark.parametrize("case", FULL_DISK_CASES.values(), ids=list(FULL_DISK_CASES))
def test_full_disk_one_sentence_nothing_left(work, monkeypatch, case):
    args, path = case
    _full_disk(monkeypatch)
    before = snapshot(work)
    res = run_cli(args)
    # the command's own results may be printed first; the error is the last line, and alone on it
    out = res.output
    assert res.exit_code == 2 and "Traceback" not in out, out
    last = [ln for ln in out.splitlines() if ln.strip()][-1]
    assert last.startswith("Error: ") and path in last and "no space left on the device" in last, out
    assert sum(ln.startswith("Error: ") for ln in out.splitlines()) == 1
    assert snapshot(work) == before  # no half-written output, no temporary file, no folder created


# --------------------------------------------------------------------------------------------------
# library API: RockcliInputError with one line naming the culprit
# --------------------------------------------------------------------------------------------------
def _pulse(t0=None, shape="sine"):
    return make_pulse(shape, 0.5 * G, 0.5, t0)


BLOCK = Block.from_dimensions(2.0, 0.5)

API_CASES = {
    **{f"read_record-{name}": (lambda name=name: read_record(name), words) for name, words in BAD_FILE_WORDS.items()},
    "read_record-dev-zero": (lambda: read_record("/dev/zero", units="g", dt=0.01), ["not a regular file"]),
    "read_record-dt-nan": (lambda: read_record("nounits.txt", units="g", dt=float("nan")), ["dt=nan"]),
    "read_record-column": (lambda: read_record("good.AT2", column=1.5), ["column 1.5"]),
    "Block-R-tiny": (lambda: Block(1e-6, 0.2), ["R = 1e-06 m"]),
    "Block-R-huge": (lambda: Block(1e4, 0.2), ["R = 10000 m"]),
    "Block-alpha-tiny": (lambda: Block(1.0, 1e-9), ["alpha = 1e-09 rad (5.73e-08 deg)", "below the supported 1 deg"]),
    "Block-alpha-zero": (lambda: Block(1.0, 0.0), ["strictly between 0 and 90"]),
    "Block-R-nan": (lambda: Block(float("nan"), 0.2), ["R must be a positive length", "nan"]),
    "Block-degrees-90": (lambda: Block.from_degrees(1.0, 90), ["strictly between 0 and 90 degrees, got 90"]),
    "Block-dims-negative": (lambda: Block.from_dimensions(-2, 1), ["block height", "got -2"]),
    "Block-dims-needle": (lambda: Block.from_dimensions(10, 1e-5), ["alpha = 5.72957795131e-05 deg", "height 10 m"]),
    "isolation-Tb-tiny": (lambda: parse_isolation_spec("linear:Tb=1e-6"), ["Tb = 1e-06 s"]),
    "isolation-Tb-huge": (lambda: LinearIsolation(1e9), ["Tb = 1e+09 s"]),
    "isolation-xi-huge": (lambda: parse_isolation_spec("linear:Tb=2,xi=1e6"), ["xi = 1e+06"]),
    "isolation-xi-negative": (lambda: parse_isolation_spec("linear:Tb=2,xi=-0.1"), ["xi must be >= 0"]),
    "isolation-gamma": (lambda: parse_isolation_spec("linear:Tb=2,gamma=1"), ["gamma"]),
    "isolation-no-Tb": (lambda: parse_isolation_spec("linear:xi=0.1"), ["needs Tb="]),
    "isolation-key": (lambda: parse_isolation_spec("linear:Tb=2,mu=0.1"), ["'mu=0.1' is not one of"]),
    "make_pulse-ap": (lambda: make_pulse("sine", 1e4 * G, 1.0), ["a_p = 10000 g"]),
    "make_pulse-Tp-tiny": (lambda: make_pulse("ricker-sym", 1.0, 1e-9), ["T_p = 1e-09 s"]),
    "make_pulse-Tp-huge": (lambda: make_pulse("ricker-anti", 1.0, 1e9), ["T_p = 1e+09 s"]),
    "make_pulse-Tp-nan": (lambda: make_pulse("cosine", 1.0, float("nan")), ["T_p must be finite, got nan"]),
    "make_pulse-shape": (lambda: make_pulse("gabor", 1.0, 1.0), ["unknown pulse shape 'gabor'"]),
    "parse_pulse_spec-ap": (lambda: parse_pulse_spec("sine:ap=1e3,Tp=1"), ["'sine:ap=1e3,Tp=1'", "a_p = 1e3 g"]),
    "parse_pulse_spec-twice": (lambda: parse_pulse_spec("sine:ap=1,ap=2,Tp=1"), ["ap is given twice"]),
    "parse_pulse_spec-word": (lambda: parse_pulse_spec("sine:ap=x,Tp=1"), ["ap='x' is not a number"]),
    "simulate-t0-negative": (lambda: simulate(BLOCK, Rigid(), _pulse(-0.25)), ["starts at -0.25 s", "t0 >= 0 s"]),
    "simulate-ricker-starts-early": (lambda: simulate(BLOCK, Rigid(), _pulse(0.2, "ricker-anti")),
                                           ["starts at -1.3 s", "give t0 >= 1.5 s"]),
    "simulate-t0-huge": (lambda: simulate(BLOCK, Rigid(), _pulse(1e12)), ["starts at 1e+12 s"]),
    "simulate-tail": (lambda: simulate(BLOCK, Rigid(), _pulse(), tail=1e5), ["tail must be a time between 0 and 1000"]),
    "simulate-rtol": (lambda: simulate(BLOCK, Rigid(), _pulse(), rtol=0.0), ["rtol must lie between"]),
    "simulate-max-steps": (lambda: simulate(BLOCK, Rigid(), _pulse(), max_steps=0), ["max_steps"]),
    "simulate-rest-tol-0": (lambda: simulate(BLOCK, Rigid(), _pulse(), rest_tol=0.0), ["rest_tol", "never ends"]),
    "simulate-record-nan": (lambda: simulate(BLOCK, Rigid(), Record(np.array([0.0, np.nan, 1.0]), 0.01, "r")),
                            ["record 'r' has NaN or infinite samples"]),
    "simulate-record-dt": (lambda: simulate(BLOCK, Rigid(), Record(np.zeros(5), -0.01, "r")),
                           ["record 'r' has a non-positive time step -0.01"]),
    "simulate-record-long": (lambda: simulate(BLOCK, Rigid(), Record(np.zeros(1_200_000), 0.01, "big")),
                             ["1,200,000 record samples", "integrator steps"]),
    "simulate-stiff": (lambda: simulate(BLOCK, LinearIsolation(0.005, 0.0), _pulse()),
                       ["integrator steps", "with xi = 0", "a run of up to 600.5 s"]),
    "simulate-horizon": (lambda: simulate(BLOCK, Rigid(), _pulse(), horizon=1e5), ["horizon must be a time"]),
    "simulate-block-type": (lambda: simulate("bassae", Rigid(), _pulse()), ["block must be a rockcli.models.Block"]),
    "simulate-no-excitation": (lambda: simulate(BLOCK, Rigid(), None), ["needs an excitation"]),
    "fit_pulse-beyond-record": (lambda: fit_pulse(read_record("good.AT2"), periods=(50.0, 100.0)),
                                ["lasts 5.99 s", "cannot be fitted"]),
    "fit_pulse-wavelet": (lambda: fit_pulse(read_record("good.AT2"), "morlet"), ["unknown wavelet 'morlet'"]),
    "fit_pulse-periods": (lambda: fit_pulse(read_record("good.AT2"), periods=(2.0, 1.0)), ["0 < min < max"]),
    "fit_pulse-too-big": (lambda: fit_pulse(Record(np.random.default_rng(0).standard_normal(2_000_000), 0.001, "big"),
                                            periods=(0.004, 1e4)), ["wavelet transform", "narrow the periods"]),
    "fit_pulse-nan": (lambda: fit_pulse(Record(np.array([1.0, np.nan] * 10), 0.01, "bad")), ["non-finite"]),
    # ---- issue 34: wrong types name the argument, sizes known before the work, values as given
    "simulate-foundation-type": (lambda: simulate(BLOCK, "none", _pulse()),
                                 ["foundation must be a rockcli foundation", "parse_isolation_spec", "got str 'none'"]),
    "simulate_many-jobs-type": (lambda: simulate_many(None), ["jobs must be a list of (block, foundation, excitation"]),
    "default_rtol-type": (lambda: default_rtol("scss"), ["foundation must be a rockcli foundation"]),
    "overturning_map-lists": (lambda: overturning_map(14.0, "ricker-sym", "none", [2, 3], [1, 2]),
                              ["wp_grid must be a grid", "'start:stop:count'", "got list [2, 3]"]),
    "overturning_map-alpha": (lambda: overturning_map("14", "ricker-sym", "none", "2:3:2", "1:2:2"),
                              ["alpha_deg must be a number of degrees, got str '14'"]),
    "overturning_map-pulse": (lambda: overturning_map(14.0, None, "none", "2:3:2", "1:2:2"),
                              ["pulse must be a pulse shape such as 'ricker-sym'", "got NoneType None"]),
    "min_overturning-isolations": (lambda: min_overturning_curves([14.0], ["ricker-sym"], [0.5], [2.0]),
                                   ["isolations: each isolation must be an isolation spec", "got float 0.5"]),
    "min_overturning-wp": (lambda: min_overturning_curves([14.0], ["ricker-sym"], ["none"], "2"),
                           ["wp_values must be a list of numbers, got str '2'"]),
    "search-ap-max": (lambda: min_overturning_curves([14.0], ["ricker-sym"], ["none"], [2.0], ap_max=1e300),
                      ["ap_max must be at most 10000", "got 1e+300"]),
    "critical_sizes-pulses": (lambda: critical_sizes(3, [10.0], ["linear:TbTp=2"]), ["pulses must be a list"]),
    "resolve_excitations-type": (lambda: resolve_excitations(3.0), ["sources must be a list of catalogue ids"]),
    "resolve_excitations-item": (lambda: resolve_excitations([None]), ["sources: each source must be"]),
    "parse_configurations-type": (lambda: parse_configurations([2.5]), ["specs: each spec must be an isolation spec"]),
    "run_assessment-columns": (lambda: run_assessment(["bassae"], [], parse_configurations(["none"])),
                               ["columns: each item must be a Block, got str 'bassae'"]),
    "run_fragility-excitations": (lambda: run_fragility([BLOCK], ["good.AT2"], parse_configurations(["none"])),
                                  ["excitations: each item must be an Excitation"]),
    "history_dt-rows": (lambda: simulate(BLOCK, Rigid(), _pulse(), history_dt=1e-6, tail=100.0),
                        ["would be 100,500,001 rows", "2,000,000"]),
    "horizon-as-given": (lambda: simulate(BLOCK, Rigid(), _pulse(), horizon=3600.0001), ["got 3600.0001"]),
    "rest_tol-as-given": (lambda: simulate(BLOCK, Rigid(), _pulse(), rest_tol=9.999999e-16), ["got 9.999999e-16"]),
    "Block-degrees-as-given": (lambda: Block.from_degrees(1.0, 0.9999), ["alpha = 0.9999 deg is below"]),
    "make_pulse-ap-as-given": (lambda: make_pulse("sine", 100.0001 * G, 1.0), ["a_p = 100.0001 g"]),
    "check_scale-peak": (lambda: check_scale(3.0, 40.0, "factor", "the record"),
                         ["factor 3 takes the peak of the record from 40 g to 120 g", "at most 2.5 here"]),
}


@pytest.mark.parametrize("case", API_CASES.values(), ids=list(API_CASES))
def test_api_bad_input(work, case):
    call, words = case
    with pytest.raises(RockcliInputError) as info:
        call()
    msg = str(info.value)
    assert "\n" not in msg and "np.float64" not in msg, msg
    for w in words:
        assert w in msg, (w, msg)


# --------------------------------------------------------------------------------------------------
# inputs at the edge of the limits are accepted, and the others of the issue give correct results
# --------------------------------------------------------------------------------------------------
def test_limits_themselves_are_accepted():
    Block.from_degrees(0.01, 1.0)
    Block.from_degrees(100.0, 89.9)
    LinearIsolation(0.005, 10.0, 0.0)
    LinearIsolation(1e6, 0.0, 0.999)
    make_pulse("sine", 100 * G, 1e-3)
    make_pulse("ricker-sym", -100 * G, 1e3)
    res = simulate(BLOCK, Rigid(), make_pulse("sine", 0.5 * G, 0.5, 0.0), tail=1000)
    assert res.verdict == "rocked"


def test_late_pulse_is_the_same_scene_shifted():
    """A pulse starting at 1e6 T_p (the bound) gives the verdict and peak of the same pulse at t = 0."""
    ref = simulate(BLOCK, Rigid(), make_pulse("sine", 0.5 * G, 0.5, 0.0))
    late = simulate(BLOCK, Rigid(), make_pulse("sine", 0.5 * G, 0.5, 0.5e6))
    assert late.verdict == ref.verdict == "rocked"
    assert late.theta_max == pytest.approx(ref.theta_max, rel=1e-7)


@pytest.mark.parametrize("block, foundation, tail, rtol", [
    (Block.from_degrees(0.01, 1.0), Rigid(), 10.0, 1e-8),                         # smallest, slenderest block
    (Block.from_degrees(0.01, 5.0), LinearIsolation(0.005, 1.0), 0.0, 1e-8),     # small block, stiffest base
    (Block.from_degrees(0.05, 1.0), LinearIsolation(0.05, 1.0), 100.0, 1e-8),    # long free rocking
    (Block.from_degrees(3.0, 10.0), LinearIsolation(0.3, 0.0), 10.0, 1e-8),      # an undamped base (to the horizon)
    (Block.from_degrees(100.0, 60.0), LinearIsolation(1e6, 0.0), 10.0, 1e-14),
])
def test_accepted_corners_stay_far_below_the_step_cap(block, foundation, tail, rtol):
    """Scenes at the corners of the limits that the step estimate accepts need fewer steps than it says."""
    from rockcli.solve import _estimate_steps, _excitation_arrays

    rec = Record(np.tile(PULSE_G, 10) * G * 0.5, DT, "ten pulses")
    for motion in (rec, make_pulse("ricker-sym", 1.05 * G * math.tan(block.alpha), 0.5)):
        res = simulate(block, foundation, motion, tail=tail, rtol=rtol, history=True)
        estimate = _estimate_steps(block, foundation, _excitation_arrays(motion), rtol, tail, 1e-8, 600.0, True)[0]
        assert res.status >= 0 and estimate <= 1_000_000
        assert res.steps + res.rejected_steps < max(estimate, 5_000)


def test_crcrlf_line_endings_read_like_crlf(work):
    """``\\r\\r\\n`` (a CRLF file converted again) reads as the same record, not as a broken header."""
    path = work / "crcrlf.AT2"
    path.write_bytes(GOOD_AT2.replace("\r\n", "\r\r\n").encode("latin-1"))
    a, b = read_record(path), read_record(work / "good.AT2")
    np.testing.assert_array_equal(a.acc, b.acc)
    assert a.dt == b.dt == DT


def test_assess_some_records_bad_gives_error_rows_and_a_warning(work):
    from rockcli.report.tables import read_assessment_csv

    res = run_cli([*ASSESS, "--records", "good.AT2", "--records", "nan.AT2", "--csv", "t.csv"])
    assert res.exit_code == 0, res.output
    assert "Warning: 1 of 2 records could not be read or run" in res.output and "nan.AT2" in res.output
    df = read_assessment_csv(work / "t.csv")
    assert list(df.record) == ["good.AT2", "nan.AT2"]
    assert df.error[0] == "" and "is nan, not a finite number" in df.error[1]


def test_assess_every_record_bad_one_sentence_per_file(work):
    before = snapshot(work)
    res = run_cli([*ASSESS, "--records", "nan.AT2", "--records", "dt0.AT2", "--records", "empty.txt",
                   "--csv", "t.csv", "--history-dir", "h"])
    assert res.exit_code == 2 and "Traceback" not in res.output
    lines = [ln for ln in res.output.splitlines() if ln.strip()]
    assert lines[0] == "Error: none of the 3 records can be run:"
    assert [ln.split(",")[0].split(":")[0] for ln in lines[1:]] == ["nan.AT2", "dt0.AT2", "empty.txt"]
    assert snapshot(work) == before


def test_arithmetic_failure_is_one_sentence_exit_1(work, monkeypatch):
    """A crash inside the numerics (here simulated) is reported as a numerical failure, not a traceback."""
    import rockcli.solve

    def crash(*args, **kwargs):
        raise ZeroDivisionError("division by zero")

    monkeypatch.setattr(rockcli.solve, "simulate", crash)
    before = snapshot(work)
    res = run_cli([*SIM, *SINE, "--history", "h.csv"])
    lines = [ln for ln in res.output.splitlines() if ln.strip()]
    assert res.exit_code == 1 and "Traceback" not in res.output
    assert len(lines) == 1 and "numerical failure (ZeroDivisionError" in lines[0]
    assert snapshot(work) == before


def test_step_cap_is_one_sentence_exit_1_and_nothing_printed(work, monkeypatch):
    """A genuine numerical failure (simulated: a tiny cap) prints no result and writes nothing."""
    import rockcli.solve
    import rockcli.solve.single

    real = rockcli.solve.simulate

    def capped(*args, **kwargs):
        return real(*args, **{**kwargs, "max_steps": 5})

    monkeypatch.setattr(rockcli.solve.single, "_check_work", lambda *a: None)  # where simulate looks it up
    monkeypatch.setattr(rockcli.solve, "simulate", capped)
    before = snapshot(work)
    res = run_cli([*SIM, *SINE, "--history", "h.csv"])
    assert res.exit_code == 1 and "Traceback" not in res.output
    lines = [ln for ln in res.output.splitlines() if ln.strip()]
    assert len(lines) == 1 and "safety cap" in lines[0] and "verdict" not in res.output
    assert snapshot(work) == before


def test_atomic_write_keeps_the_old_file_when_the_disk_fills(work, monkeypatch):
    """A failed rewrite leaves the previous file intact, and no temporary file."""
    from rockcli.io.files import write_text

    target = work / "keep.csv"
    write_text(target, "old\n")
    _full_disk(monkeypatch)
    before = snapshot(work)
    with pytest.raises(RockcliInputError, match=r"keep.csv: cannot write there: no space left on the device"):
        write_text(target, "new contents\n" * 1000)
    assert target.read_text() == "old\n" and snapshot(work) == before


@pytest.mark.parametrize("code, words", [
    (errno.EACCES, "permission denied"),
    (errno.EROFS, "read-only file system"),
    (errno.EDQUOT, "disk quota exceeded"),
])
def test_preflight_reports_unwritable_folders(work, monkeypatch, code, words):
    """Running as root, chmod cannot make a folder unwritable: the failing probe is simulated."""
    import rockcli.io.output_checks

    def refuse(*args, **kwargs):
        raise OSError(code, os.strerror(code))

    monkeypatch.setattr(rockcli.io.output_checks.tempfile, "mkstemp", refuse)
    before = snapshot(work)
    res = run_cli(["records", "show", "good.AT2", "--plot", "adir/x.png"])
    assert_one_sentence(res, ["--plot adir/x.png: cannot write there", words])
    assert snapshot(work) == before



# ------------------------------------------------------------------------------------------
# Sliding and lead-rubber bearings: the same period limits as linear bearings, and u_y >= 1 micrometre
# ------------------------------------------------------------------------------------------
@pytest.mark.parametrize("spec, words", [
    ("scss:Tb=1e-6,mu=0.05", "outside the supported 0.005 s"),
    ("scss:Tb=2,mu=0.05,uy=1e-12", "between 1e-06 m and 0.1 m"),
    ("lrb:Tb=1e7,Q=0.1,uy=0.01", "outside the supported"),
    ("dcss:Tb=2,mu1=0.03,mu2=0.07,r=1e9", "surface R1 alone"),
    ("dcss:R1=1e-9,R2=1,mu1=0.03,mu2=0.07", "surface R1 alone"),
])
def test_sliding_bearing_limits(spec, words):
    from rockcli.models import parse_isolation_spec

    with pytest.raises(RockcliInputError, match=words) as err:
        parse_isolation_spec(spec)
    assert "\n" not in str(err.value)


@pytest.mark.parametrize("spec", ["scss:Tb=0.005,mu=0.9,uy=1e-6", "scss:Tb=2,mu=0.9,uy=1e-6",
                                  "dcss:Tb=0.01,mu1=0.03,mu2=0.9,r=1,uy=1e-6"])
def test_sliding_bearing_corners_stay_far_below_the_step_cap(spec):
    from rockcli.models import Block, parse_isolation_spec
    from rockcli.pulses import make_pulse
    from rockcli.solve import simulate
    from rockcli.io.units import G

    for pulse in (make_pulse("ricker-sym", 0.5 * G, 0.5), make_pulse("ricker-sym", 5 * G, 0.05)):
        res = simulate(Block.from_degrees(1.0, 10.0), parse_isolation_spec(spec), pulse)
        assert res.status >= 0 and res.steps + res.rejected_steps < 200_000


def _console(args, cwd, stdin=None):
    """The installed console script's entry point (rockcli.cli:run) in a fresh interpreter."""
    import subprocess
    import sys

    code = "import sys; from rockcli.cli import run; sys.argv = ['rockcli'] + sys.argv[1:]; run()"
    return subprocess.run([sys.executable, "-c", code, *args], capture_output=True, text=True, cwd=cwd,
                          input=stdin)


def test_console_script_exit_codes_output_and_files(work):
    """The console script ends the process with os._exit after flushing and the exit handlers:
    the exit code is main()'s (0, 2 for bad input), everything printed arrives, files are whole."""
    ok = _console(["spectrum", "overturning", "--alpha", "10", "--wp-over-p", "1:4:7", "--ap", "0.5:5:9",
                   "--csv", "map.csv"], work)
    assert ok.returncode == 0, ok.stderr
    rows = (work / "map.csv").read_text().splitlines()
    assert len(rows) == 1 + 7 * 9 and rows[0].startswith("alpha_deg,")
    assert ok.stdout.strip()  # the summary reached the pipe
    bad = _console(["spectrum", "overturning", "--alpha", "-3"], work)
    assert bad.returncode == 2 and "Traceback" not in bad.stderr and "--alpha" in bad.stderr
    helped = _console(["--help"], work)
    assert helped.returncode == 0 and "Usage: rockcli" in helped.stdout and helped.stdout.endswith("\n")
    missing = _console(["simulate", "--body", "bassae", "--record", str(work / "nope.AT2")], work)
    assert missing.returncode == 2 and "Traceback" not in missing.stderr and "nope.AT2" in missing.stderr


# --------------------------------------------------------------------------------------------------
# issue 34: the history grid follows --tail, its rows known before the run
# --------------------------------------------------------------------------------------------------
def test_history_follows_the_tail_and_its_grid_rows_are_counted_before_the_run():
    """A block at rest when its record ends: the history (on the grid or at the steps) ends at the record's end plus
    the tail, not 600 s later at the horizon, and the grid has exactly ``grid_rows`` rows; the verdict and the peak
    are those of the verdict-only run."""
    from rockcli.solve.single import grid_rows

    rec = make_pulse("sine", 0.5 * G, 0.5).sampled(0.01, t_end=5.0)  # rocks, then rests before the record ends
    alone = simulate(BLOCK, Rigid(), rec)
    assert alone.verdict == "rocked"
    for tail, hdt in ((0.0, 0.01), (2.0, 0.01), (1.5, 0.003)):
        res = simulate(BLOCK, Rigid(), rec, history_dt=hdt, tail=tail)
        assert res.settled and res.t_end_s == 5.0 + tail and res.history.t[-1] <= 5.0 + tail
        assert len(res.history.t) == grid_rows(hdt, 0.0, 5.0 + tail)
        steps = simulate(BLOCK, Rigid(), rec, history=True, tail=tail)
        assert steps.t_end_s == 5.0 + tail == steps.history.t[-1]
        assert res.verdict == steps.verdict == alone.verdict and res.theta_max == steps.theta_max == alone.theta_max


def test_a_run_past_the_tail_adds_only_its_event_rows():
    """On an undamped base the block overturns 2.2 s after the record ends: the run goes on to prove it, the grid
    stops at the tail (its rows counted before the run), the overturn is still an event row."""
    from rockcli.solve.single import grid_rows

    rec = make_pulse("sine", 0.5 * G, 1.0).sampled(0.01, t_end=3.0)
    res = simulate(BLOCK, LinearIsolation(1.0, 0.0), rec, history_dt=0.01, tail=0.0)
    assert res.overturned and res.t_end_s > 5.0
    assert res.history.t[-1] == 3.0 and len(res.history.t) == grid_rows(0.01, 0.0, 3.0)
    assert res.history.events[-1].event == "overturn" and res.history.events[-1].t_s == res.t_end_s


def test_grid_rows_counts_what_the_kernel_writes():
    """:func:`grid_rows` against the kernel's own loop (``kg = ceil(t0/h)``, rows while ``kg h <= t_end``), over
    random spacings and spans, including times that fall on the grid up to rounding."""
    from rockcli.solve.single import grid_rows

    rng = np.random.default_rng(34)
    for _ in range(2000):
        h = float(10.0 ** rng.uniform(-3, 0))
        t0 = float(rng.choice([0.0, -rng.uniform(0, 3), rng.integers(0, 50) * h]))
        t1 = t0 + float(rng.choice([rng.uniform(0, 3), rng.integers(0, 400) * h]))
        kg, n = math.ceil(t0 / h), 0
        while kg * h <= t1:
            kg, n = kg + 1, n + 1
        assert grid_rows(h, t0, t1) == n, (h, t0, t1)


def test_scale_limit_is_the_motion_peak_limit():
    """One limit for every motion: the records' and the pulses' 100 g are the scale factors' too."""
    from rockcli.io.inputs import MOTION_PEAK_MAX_G
    from rockcli.pulses import A_P_MAX_G
    from rockcli.records.reader import PGA_MAX_G

    assert MOTION_PEAK_MAX_G == A_P_MAX_G == PGA_MAX_G == 100.0
    assert check_scale(-2.5, 40.0, "k") == -2.5 and check_scale(1e300, 0.0, "k") == 1e300  # a still record
