"""The history CSV of a body on a plinth (``simulate --on ... --history FILE``), written atomically."""

from __future__ import annotations

import io
import os
from pathlib import Path

import numpy as np

from rockcli.files import write_text
from rockcli.units import G

#: Columns of a stack's history CSV (SI, g where labelled): the body's rotation on the plinth ``psi``, the plinth's
#: ``theta2``, the pattern of motion of the row and its event.
STACK_HISTORY_COLUMNS = ("t_s", "ag_mps2", "ag_g", "psi_rad", "psi_over_alpha1", "psi_dot_radps", "theta2_rad",
                         "theta2_over_alpha_asm", "theta2_dot_radps", "pattern", "event")


def write_stack_history_csv(response, stack, path: str | os.PathLike) -> Path:
    """Write the rows of ``response.history`` (a :class:`rockcli.solve.StackHistory`: every step end and event of
    the run) as CSV: :data:`STACK_HISTORY_COLUMNS`."""
    H = response.history
    if H is None:
        raise ValueError("this response was computed without history (simulate_stack(..., history=True))")
    table = np.column_stack([H.t, H.ag, H.ag / G, H.psi, H.psi / stack.body.alpha, H.psi_dot, H.theta2,
                             H.theta2 / stack.alpha_asm, H.theta2_dot])
    buf = io.StringIO()
    np.savetxt(buf, table, delimiter=",", comments="", fmt="%.10g")
    lines = buf.getvalue().splitlines()
    body = "".join(f"{line},{pat},{ev}\n" for line, pat, ev in zip(lines, H.pattern, H.event))
    return write_text(path, ",".join(STACK_HISTORY_COLUMNS) + "\n" + body)
