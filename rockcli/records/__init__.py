"""Ground-motion records: reading (ObsPy, PEER .AT2 plugin, plain text) and the catalogue.

Only this subpackage imports ObsPy, and only inside the functions that need it.
"""

from rockcli.records.reader import read_record
from rockcli.records.record import Record

__all__ = ["Record", "read_record"]
