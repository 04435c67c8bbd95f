"""Units. Everything inside rockcli is SI (m, s, rad, m/s^2); g appears only at the edges."""

#: Standard gravity [m/s^2] (CGPM 1901), used both for the block's weight and to convert records
#: stated in g.
G = 9.80665

#: Factors converting an acceleration stated in a unit to m/s^2. Keys are lower-case, spaces removed.
ACCEL_UNITS = {
    "m/s^2": 1.0, "m/s/s": 1.0, "m/s2": 1.0, "m/sec^2": 1.0, "m/sec2": 1.0, "m/sec/sec": 1.0, "mps2": 1.0,
    "cm/s^2": 0.01, "cm/s/s": 0.01, "cm/s2": 0.01, "cm/sec^2": 0.01, "cm/sec2": 0.01,
    "cm/sec/sec": 0.01, "gal": 0.01, "gals": 0.01,
    "mm/s^2": 0.001, "mm/s/s": 0.001, "mm/s2": 0.001, "mm/sec^2": 0.001, "mm/sec2": 0.001,
    "g": G, "g/10": G / 10.0,
}


#: The unit words listed in messages (every spelling in :data:`ACCEL_UNITS` is accepted).
KNOWN_UNITS = "g, g/10, m/s^2, cm/s^2 (gal), mm/s^2"


def accel_factor(unit: str) -> float:
    """Factor that converts an acceleration in ``unit`` to m/s^2.

    Raises
    ------
    RockcliInputError
        If the unit word is not known.
    """
    from rockcli.errors import RockcliInputError

    key = str(unit).strip().lower().replace(" ", "")
    if key not in ACCEL_UNITS:
        raise RockcliInputError(f"unknown acceleration unit {unit!r} (known: {KNOWN_UNITS})")
    return ACCEL_UNITS[key]


#: Words a file uses for raw digitizer counts (refused unless a gain converts them).
COUNTS_WORDS = {"counts", "count", "digitalcounts"}


def is_counts(unit) -> bool:
    """True when ``unit`` names raw counts (``counts``), which need a gain to become an acceleration."""
    return str(unit).strip().lower().replace(" ", "") in COUNTS_WORDS
