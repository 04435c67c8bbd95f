"""The HTML report of one friction run (``simulate --friction MU --report``): a placeholder page until the full
report lands (the verdict in words, the friction assumed, the figure)."""

from __future__ import annotations


def slide_report(body, foundation, excitation, res, *, label: str, command: str) -> str:
    raise NotImplementedError
