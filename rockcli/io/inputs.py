"""One parser for every number rockcli reads, and one splitter for every ``key=value,...`` spec.

Every number a user gives (an option, a value in a spec such as ``linear:Tb=2.5,xi=0.1``, a sample
or a time step in a record file) goes through :func:`parse_number`, which accepts plain decimal
numbers only and refuses, with one sentence quoting what was written:

* Python-only literal forms that ``float()`` would take: ``1_0`` (read as 10), ``0x1p-3``,
  ``inf``, ``nan``, ``infinity``, non-ASCII digits;
* a decimal comma (``1,5``), named as such: the usual advice ("this is not a number") leads users
  to drop the comma and read 1,5 as 15;
* numbers too large for double precision (``1e999``), and values outside the stated range.

Record files may also use Fortran ``D`` exponents (``1.0D-02``): ``fortran=True``.

Messages never show a rounded value: :func:`format_number` gives the shortest text that reads back
as the same double (``100.0001`` stays ``100.0001``, ``1e-06`` stays ``1e-06``).

:func:`spec_items` splits the items of a spec (``key=value,key=value``) and refuses a key given
twice in any spelling (case, ``_``, an alias): ``ap=0.3,AP=0.5`` and ``mass_ratio=1,massratio=2`` are errors,
never "the last one wins".
"""

from __future__ import annotations

import math
import re

from rockcli.errors import RockcliInputError

#: A plain decimal number: sign, digits with an optional point, optional exponent (ASCII only).
DECIMAL = r"[-+]?(?:[0-9]+\.?[0-9]*|\.[0-9]+)(?:[eE][-+]?[0-9]+)?"
#: The same with Fortran ``D`` exponents (``1.0D-02``), met in record files.
FORTRAN = r"[-+]?(?:[0-9]+\.?[0-9]*|\.[0-9]+)(?:[eEdD][-+]?[0-9]+)?"
_DECIMAL_RE = re.compile(DECIMAL)
_FORTRAN_RE = re.compile(FORTRAN)
#: A number written with a decimal comma: ``1,5``, ``-0,01``, ``1,0e-2`` (one comma, digits after it).
_COMMA_RE = re.compile(r"[-+]?[0-9]*,[0-9]+(?:[eEdD][-+]?[0-9]+)?")


def format_number(x, *, derived: bool = False) -> str:
    """The shortest ``%g`` text of ``x`` that reads back as the same double (never a rounded value).

    ``format_number(100.0001) == '100.0001'`` where ``f"{100.0001:g}"`` gives ``'100'``;
    ``format_number(1e-6) == '1e-06'`` as ``:g`` gives. Non-numbers (a bool among them) are shown with ``repr``.

    ``derived=True`` for a value that went through a unit conversion and back (degrees -> radians ->
    degrees, a semi-diagonal from a height and a width): rounded to 12 significant digits first, which
    gives back what was typed (``0.9999``, not ``0.9999000000000001``) and is still far finer than any
    limit it is compared with.
    """
    if isinstance(x, bool) or type(x).__name__ in ("bool", "bool_"):  # True is no number 1
        return repr(bool(x))
    try:
        v = float(x)
    except (TypeError, ValueError):
        return repr(x)
    if not math.isfinite(v):
        return repr(v)
    if derived:
        v = float(f"{v:.12g}")
    for digits in range(6, 18):
        text = f"{v:.{digits}g}"
        if float(text) == v:
            return text
    return repr(v)  # pragma: no cover -- 17 significant digits always read back


def format_apart(a, b, *, derived: bool = True) -> tuple[str, str]:
    """``a`` and ``b`` as :func:`format_number` writes them, for a sentence that compares them: two different
    numbers never read the same (``derived`` rounding is dropped where it would make them equal), so that a refusal
    such as "the body (0.5 m wide) must be no wider than its plinth (0.49999 m wide)" shows why."""
    ta, tb = format_number(a, derived=derived), format_number(b, derived=derived)
    if ta == tb and float(a) != float(b):
        ta, tb = format_number(a), format_number(b)
    return ta, tb


#: The largest peak acceleration [g] of a motion rockcli runs, as read (records) or built (pulses) and after a
#: scale factor the user gives (``--scale``, ``--vertical-scale``): recorded peaks reach about 4 g, so only a
#: unit mistake gets past 100 g (the limit of :data:`rockcli.pulses.A_P_MAX_G` and of the record readers).
MOTION_PEAK_MAX_G = 100.0


def check_scale(factor, peak_g: float, what: str, motion: str = "the motion") -> float:
    """A scale factor the user gave: finite, non-zero, and keeping the motion's peak within
    :data:`MOTION_PEAK_MAX_G` (``|factor| peak_g <= 100 g``; compared without forming the product, which
    may overflow).

    Parameters
    ----------
    factor : float
        The factor (negative: the motion reversed).
    peak_g : float
        The motion's peak acceleration before scaling [g].
    what : str
        How the factor is named in messages (``"--scale"``).
    motion : str
        What is scaled, for the message (``"the record"``).

    Raises
    ------
    RockcliInputError
        One sentence with the factor as given.
    """
    try:
        k = float(factor)
    except (TypeError, ValueError):
        raise RockcliInputError(f"{what} must be a number, got {factor!r}") from None
    if not math.isfinite(k) or k == 0.0:
        raise RockcliInputError(f"{what} must be a finite non-zero number, got {format_number(factor)}")
    if peak_g > 0.0 and abs(k) > MOTION_PEAK_MAX_G / peak_g:
        reached = abs(k) * peak_g
        to = f"{reached:.4g} g" if math.isfinite(reached) else "beyond double precision"
        raise RockcliInputError(f"{what} {format_number(factor)} takes the peak of {motion} from {peak_g:.4g} g to "
                                f"{to}, beyond the supported {MOTION_PEAK_MAX_G:g} g (recorded peaks reach about 4 g; "
                                f"at most {_floor4(MOTION_PEAK_MAX_G / peak_g)} here)")
    return k


def _floor4(x: float) -> str:
    """``x > 0`` rounded down to 4 significant digits (a limit a user may type and be accepted)."""
    step = 10.0 ** (math.floor(math.log10(x)) - 3)
    v = math.floor(x / step) * step
    while v > x:  # the product may round up
        v -= step
    return format_number(float(f"{v:.4g}")) if float(f"{v:.4g}") <= x else format_number(v)


def _form_problem(text: str, fortran: bool) -> str | None:
    """Why ``text`` is not a plain decimal number (None when it is one)."""
    pattern = _FORTRAN_RE if fortran else _DECIMAL_RE
    if pattern.fullmatch(text):
        return None
    if not text:
        return "is empty"
    if _COMMA_RE.fullmatch(text):
        fixed = text.replace(",", ".")
        return (f"is written with a decimal comma; rockcli reads a point as the decimal mark "
                f"(write {fixed})")
    low = text.lower().lstrip("+-")
    if low in ("inf", "infinity", "nan", "snan", "qnan"):
        return "is not a finite number"
    if "_" in text:
        return "is not a plain decimal number (underscores between digits are not accepted; write it without them)"
    if low.startswith("0x") or low.startswith("0b") or low.startswith("0o"):
        return "is not a plain decimal number (hexadecimal, binary and octal forms are not accepted)"
    if any(ch.isdigit() and not ("0" <= ch <= "9") for ch in text):
        return "is not a plain decimal number (write its digits 0-9)"
    if not fortran and re.fullmatch(FORTRAN, text):
        return "is not a plain decimal number (write the exponent with e, e.g. 1e-2)"
    return "is not a number"


def parse_number(text, what: str, *, lo: float | None = None, hi: float | None = None, lo_open: bool = False,
                 hi_open: bool = False, unit: str = "", integer: bool = False, fortran: bool = False,
                 bad: str | None = None) -> float:
    """A finite number from what the user wrote, checked against a range.

    Parameters
    ----------
    text : str or number
        What the user wrote (surrounding blanks are ignored); a number (from library callers) is
        checked for finiteness and range only.
    what : str
        How the value is named in messages (``"--R"``, ``"pulse spec 'sine:ap=1,Tp=x': Tp"``).
    lo, hi : float, optional
        The range; ``lo_open``/``hi_open`` make an end exclusive.
    unit : str
        Unit named after the range in messages (``"s"``, ``"m"``).
    integer : bool
        Whole numbers only (digits with an optional sign); returns an ``int``.
    fortran : bool
        Also accept Fortran ``D`` exponents (``1.0D-02``; record files).
    bad : str, optional
        The message for text that is simply not a number (default: ``"<what> <text> is not a number"``);
        the specific refusals (decimal comma, ``1_0``, ``inf``) keep their own words.

    Returns
    -------
    float (or int with ``integer=True``)

    Raises
    ------
    RockcliInputError
        One sentence quoting ``text`` as written.
    """
    if isinstance(text, bool):
        raise RockcliInputError(f"{what} {text!r} is not a number")
    if isinstance(text, (int, float)) and not isinstance(text, str):
        value = text
        shown = format_number(text)
    else:
        shown = str(text).strip()
        problem = _form_problem(shown, fortran)
        if integer and problem is None and not re.fullmatch(r"[-+]?[0-9]+", shown):
            problem = "is not a whole number"
        if problem is not None:
            if problem == "is not a number" and bad is not None:
                raise RockcliInputError(bad)
            if problem == "is empty":
                raise RockcliInputError(f"{what} is empty; give a number")
            raise RockcliInputError(f"{what} {shown!r} {problem}")
        value = int(shown) if integer else float(shown.replace("D", "e").replace("d", "e"))
    if not integer and not math.isfinite(value):
        if isinstance(text, str) and math.isinf(value):
            raise RockcliInputError(f"{what} {shown} is too large (beyond double precision)")
        raise RockcliInputError(f"{what} {shown} is not a finite number")
    if integer and isinstance(value, float) and value != int(value):
        raise RockcliInputError(f"{what} {shown} is not a whole number")
    below = lo is not None and (value <= lo if lo_open else value < lo)
    above = hi is not None and (value >= hi if hi_open else value > hi)
    if below or above:
        raise RockcliInputError(f"{what} {shown} {range_words(lo, hi, lo_open, hi_open, unit)}")
    return int(value) if integer else float(value)


def range_words(lo, hi, lo_open=False, hi_open=False, unit="") -> str:
    """``must lie between 0.01 and 100 m``, ``must be > 0 s``, ... (limits shown exactly)."""
    u = f" {unit}" if unit else ""
    lo, hi = (v if isinstance(v, int) or v is None else format_number(v) for v in (lo, hi))
    if lo is not None and hi is not None:
        if not lo_open and not hi_open:
            return f"must lie between {lo} and {hi}{u}"
        return (f"must be {'>' if lo_open else '>='} {lo} and {'<' if hi_open else '<='} "
                f"{hi}{u}")
    if lo is not None:
        return f"must be {'>' if lo_open else '>='} {lo}{u}"
    return f"must be {'<' if hi_open else '<='} {hi}{u}"


def type_words(value) -> str:
    """What a wrong argument is, for a message: its type and (shortened) value, ``str 'none'``, ``list [2, 3]``."""
    text = " ".join(repr(value).split())  # one line (a numpy array's repr has several)
    if len(text) > 40:
        text = text[:37] + "..."
    return f"{type(value).__name__} {text}"


def check_type(value, types, what: str, expected: str):
    """``value`` when it is an instance of ``types`` (a bool is not a number), else one sentence:
    ``<what> must be <expected>, got <type value>``."""
    if not isinstance(value, types) or (isinstance(value, bool) and bool not in (types if isinstance(types, tuple)
                                                                                  else (types,))):
        raise RockcliInputError(f"{what} must be {expected}, got {type_words(value)}")
    return value


def as_list(value, what: str, expected: str, *, one=()) -> list:
    """The items of a sequence argument (a list, a tuple, a numpy array, any other iterable that is not text or a
    mapping) as a list; a single value of the types ``one`` (e.g. ``str`` for one spec) is a list of itself; anything
    else is refused in one sentence (``<what> must be <expected>, got <type value>``)."""
    import os

    if one and isinstance(value, one):
        return [value]
    if isinstance(value, (str, bytes, os.PathLike, dict)) or value is None:
        raise RockcliInputError(f"{what} must be {expected}, got {type_words(value)}")
    try:
        return list(value)
    except TypeError:
        raise RockcliInputError(f"{what} must be {expected}, got {type_words(value)}") from None


def spec_key(key: str, names: dict | None = None) -> str:
    """What a spec key means, for telling whether two keys are one: ``names[key]`` (the parser's table, lower-case
    keys and their aliases to one name) when it lists it, else the key in lower case without ``_`` and ``-``
    (``MassRatio``, ``mass_ratio`` and ``massratio`` are one key)."""
    k = str(key).strip().lower()
    if names and k in names:
        return names[k]
    return k.replace("_", "").replace("-", "")


def spec_items(rest: str, what: str, names: dict | None = None) -> list[tuple[str, str, bool]]:
    """The items of ``key=value,key=value``: ``(key, value, has_equals)``, blanks stripped, empty items skipped.

    Parameters
    ----------
    rest : str
        The part of a spec after ``NAME:``.
    what : str
        How the spec is named in messages (``"pulse spec 'sine:ap=1,ap=2,Tp=1'"``).
    names : dict, optional
        The parser's keys (lower case, aliases included) to the name each stands for: two spellings of one
        name are one key (see :func:`spec_key`).

    Raises
    ------
    RockcliInputError
        A key given twice in any spelling (``ap=1,AP=2``, ``mass_ratio=1,massratio=2``): ``"<what>: ap is given
        twice"``, ``"<what>: mass_ratio (as massratio) is given twice"``; never "the last one wins".
    """
    out, seen = [], {}
    for item in filter(None, (s.strip() for s in str(rest).split(","))):
        key, eq, val = item.partition("=")
        key, val = key.strip(), val.strip()
        k = spec_key(key, names)
        if not eq and out and out[-1][2] and re.fullmatch(r"[0-9]+(?:[eE][-+]?[0-9]+)?", key) \
                and re.fullmatch(r"[-+]?[0-9]+", out[-1][1]):
            prev_key, prev_val, _ = out[-1]
            raise RockcliInputError(f"{what}: {prev_key}={prev_val},{key} is written with a decimal comma; the "
                                    f"comma separates items: write {prev_key}={prev_val}.{key}")
        if eq and k in seen:
            shown = key if key == seen[k] else f"{seen[k]} (as {key})"
            raise RockcliInputError(f"{what}: {shown} is given twice")
        if eq:
            seen[k] = key
        out.append((key, val, bool(eq)))
    return out


def spec_numbers(rest: str, what: str, keys: dict, listing: str, *, limits: dict | None = None,
                 refuse: dict | None = None) -> dict:
    """The ``key=number`` items of a spec (the part after ``NAME:``) as ``{keys[key]: value}``.

    ``keys`` maps each key as written (lower case; its aliases too) to its name; ``listing`` is how the
    keys are shown in the sentence for an unknown one (``"height=..., width=..."``); ``limits`` maps a
    name to :func:`parse_number`'s range keywords; ``refuse`` maps a key (lower case) to the sentence
    that refuses it as ``key=...`` (``{key}`` in it: the key as written), for a key that belongs to
    another spec. Anything wrong is one sentence beginning with ``what``.
    """
    values = {}
    for key, val, eq in spec_items(rest, what, keys):
        k = key.lower()
        if eq and refuse and k in refuse:
            raise RockcliInputError(f"{what}: {refuse[k].format(key=key)}")
        if not eq or k not in keys:
            item = f"{key}={val}" if eq else key
            raise RockcliInputError(f"{what}: {item!r} is not one of {listing}")
        values[keys[k]] = parse_number(val, f"{what}: {key}", bad=f"{what}: {key} must be a number, got {val!r}",
                                       **(limits or {}).get(keys[k], {}))
    return values
