"""What every figure shares: the words and symbols that name a scene's parameters, and the layout.

* :func:`block_text`, :func:`foundation_text`, :func:`spec_text`, :func:`motion_text`: a body, an
  isolation (a foundation, or a spectra spec with ``TbTp``) and a ground motion in the paper's
  symbols (matplotlib mathtext: ``$\\alpha$``, ``$T_b$``, ``$\\xi$``, ``$\\gamma$``, ``$\\mu_1$``), with
  units, so that a title or legend names every parameter a reader needs to redo the run;
* :func:`new_figure`: a figure with constrained layout (titles, legends and axis labels are kept
  inside the canvas at any size); :func:`footnote`: a note under the panels, wrapped to the width
  of the figure and placed by the layout (a free ``fig.text`` is not, and was clipped);
* :func:`plot_grid_dt`: the spacing of the dense history a response figure is drawn from.

matplotlib is imported inside the functions (Agg backend).
"""

from __future__ import annotations

import math
import re

#: Words of the isolation kinds (the paper's abbreviations for the sliding bearings).
KIND_WORDS = {"none": "rigid foundation", "linear": "linear bearings", "scss": "SCSS bearings",
              "dcss": "DCSS bearings", "lrb": "lead-rubber bearings"}
#: Symbol and unit of each spec key (``uy`` is drawn in mm).
SPEC_SYMBOLS = {"TbTp": (r"$T_b/T_p$", ""), "Tb": (r"$T_b$", "s"), "xi": (r"$\xi$", ""), "gamma": (r"$\gamma$", ""),
                "mu": (r"$\mu$", ""), "mu1": (r"$\mu_1$", ""), "mu2": (r"$\mu_2$", ""), "Q": (r"$Q/W$", ""),
                "uy": (r"$u_y$", "mm"), "R1": (r"$R_1$", "m"), "R2": (r"$R_2$", "m"), "r": (r"$R_2/R_1$", ""),
                "mu_e": (r"$\mu_e$", ""), "n": (r"$n$", ""), "beta": (r"$\beta$", ""), "gammabw": (r"$\gamma_{bw}$", "")}
#: A space a title is never wrapped at (between a symbol, its value and its unit).
NBSP = "\u00a0"
#: Words of the pulse shapes.
SHAPE_WORDS = {"ricker-sym": "symmetric Ricker", "ricker-anti": "antisymmetric Ricker", "sine": "one-sine",
               "cosine": "one-cosine"}


def _num(v: float, digits: int = 3) -> str:
    return f"{v:.{digits}g}"


def item_text(key: str, value: str) -> str:
    """One ``key=value`` item of a spec in symbols: ``mu1=0.03`` -> ``$\\mu_1$ = 0.03``."""
    symbol, unit = SPEC_SYMBOLS.get(key, (key, ""))
    if key == "uy":
        try:
            value = _num(float(value) * 1e3)
        except ValueError:
            pass
    elif unit:
        try:
            value = _num(float(value), 4)
        except ValueError:
            pass
    return f"{symbol}{NBSP}={NBSP}{value}" + (f"{NBSP}{unit}" if unit else "")  # never wrapped apart


def spec_items(label: str) -> tuple[str, list[tuple[str, str]]]:
    """``(kind, [(key, value), ...])`` of an isolation label such as ``linear:TbTp=2,xi=0.05,gamma=0.01``."""
    kind, _, rest = label.partition(":")
    return kind, [tuple(kv.split("=", 1)) for kv in rest.split(",") if "=" in kv]


def spec_text(label: str) -> str:
    """An isolation label in words and symbols: ``linear bearings, $T_b/T_p$ = 2, $\\xi$ = 0.05, ...``."""
    kind, items = spec_items(label)
    if kind == "none":
        return KIND_WORDS["none"]
    return ", ".join([KIND_WORDS.get(kind, kind)] + [item_text(k, v) for k, v in items])


def split_labels(labels) -> tuple[dict, str]:
    """Legend texts of several isolation labels: ``({label: the items that differ between them}, the
    items they share)``, both in words and symbols; ``none`` is the rigid foundation. With one
    isolated label, its legend text is all of it and nothing is shared."""
    labels = list(dict.fromkeys(labels))
    isos = [lab for lab in labels if spec_items(lab)[0] != "none"]
    items = {lab: [("kind", spec_items(lab)[0])] + spec_items(lab)[1] for lab in isos}
    keys = list(dict.fromkeys(k for its in items.values() for k, _ in its))
    varying = [k for k in keys if len({dict(its).get(k) for its in items.values()}) > 1]

    def show(pairs):
        return ", ".join(KIND_WORDS.get(v, v) if k == "kind" else item_text(k, v) for k, v in pairs)

    out = {lab: KIND_WORDS["none"] for lab in labels if lab not in items}
    if len(isos) < 2:
        return {**out, **{lab: show(items[lab]) for lab in isos}}, ""
    out.update({lab: show([(k, v) for k, v in items[lab] if k in varying]) for lab in isos})
    return out, show([(k, v) for k, v in items[isos[0]] if k not in varying])


def foundation_text(foundation) -> str:
    """A foundation (:mod:`rockcli.models`) with all its parameters; a DCSS adds its period and
    effective friction (Eq 38)."""
    label = foundation.label
    kind, items = spec_items(label)
    if kind == "dcss":
        items = [("Tb", repr(foundation.T_b))] + items[:4] + [("mu_e", _num(foundation.mu_e))] + items[4:]
    if kind == "none":
        return KIND_WORDS["none"]
    return ", ".join([KIND_WORDS.get(kind, kind)] + [item_text(k, v) for k, v in items])


#: A ``$`` that opens or closes a formula (one written ``\\$`` by :func:`plain` is a dollar sign).
_DOLLAR = re.compile(r"(?<!\\)\$")


def plain(text: str) -> str:
    """``text`` (a name given by the user or read from a file) drawn as written: a ``$`` opens no formula.

    Every user string that reaches a figure's text goes through here, where it enters the text (a body's, a
    plinth's or a record's name, a file name, a sentence built from them), so that matplotlib's mathtext never
    reads it: ``Plinth $1`` would stop the drawing ("Expected end of text"), ``a$x$b`` would draw an italic x."""
    return str(text).replace("$", r"\$")


def formula_parts(text: str) -> list[str]:
    """``text`` split at the ``$`` that open and close formulas (a dollar sign written ``\\$`` stays): the odd
    items are formulas."""
    return _DOLLAR.split(text)


def block_text(block) -> str:
    """``nemea: $R$ = 5.99 m, $\\alpha$ = 9.60°, $p$ = 1.11 rad/s``; a column of drums: ``nemea-drums: 13 drums,
    as one block $R$ = ...``."""
    drums = getattr(block, "drums", None)
    if isinstance(drums, tuple):
        return f"{plain(block.name)}: {len(drums)} drums, as one block " + block_text(block.monolith).partition(": ")[2]
    return (f"{plain(block.name)}: $R$ = {block.R:.3g} m, $\\alpha$ = {block.alpha_deg:.3g}°, "
            f"$p$ = {block.p:.3g} rad/s")


def pulse_text(shape: str, a_p_g: float | None = None, T_p: float | None = None) -> str:
    """``symmetric Ricker pulse, $a_p$ = 0.5 g, $T_p$ = 0.6 s`` (the values given)."""
    parts = [f"{SHAPE_WORDS.get(shape, shape)} pulse"]
    if a_p_g is not None:
        parts.append(f"$a_p$ = {a_p_g:.3g} g")
    if T_p is not None:
        parts.append(f"$T_p$ = {T_p:.3g} s")
    return ", ".join(parts)


def motion_text(excitation, label: str | None = None) -> str:
    """A ground motion: a pulse by its shape, ``a_p`` and ``T_p``; a record by ``label`` (or its name)
    and its PGA as run (after any scaling)."""
    if excitation is None:
        return label or "free rocking (no ground motion)"
    if hasattr(excitation, "T_p") and hasattr(excitation, "acceleration"):
        text = pulse_text(excitation.shape, excitation.a_p_g, excitation.T_p)
        return f"{plain(label)}: {text}" if label else text
    name = plain(label or f"record {excitation.name}")
    return f"{name}, PGA = {excitation.pga_g:.3g} g"


def plot_grid_dt(excitation) -> float:
    """Spacing [s] of the dense history a response figure is drawn from: 1/400 of a pulse's period,
    half a record's sample interval (at most 2.5 ms), 2 ms without ground motion."""
    if excitation is None:
        return 2e-3
    if hasattr(excitation, "T_p") and hasattr(excitation, "acceleration"):
        return excitation.T_p / 400.0
    return min(0.5 * float(excitation.dt), 2.5e-3)


def excitation_samples(excitation, t_begin: float, t_end: float):
    """``(t, ag)`` [s, m/s^2] of the ground motion itself over ``[t_begin, t_end]``: a pulse evaluated
    on its own fine grid (400 points per period), a record's samples (zero outside the record, as
    the solver takes it)."""
    import numpy as np

    if excitation is None:
        return np.array([t_begin, t_end]), np.zeros(2)
    if hasattr(excitation, "T_p") and hasattr(excitation, "acceleration"):
        n = int(min(200_000, max(2000, math.ceil((t_end - t_begin) / (excitation.T_p / 400.0)) + 1)))
        t = np.linspace(t_begin, t_end, n)
        return t, excitation.acceleration(t)
    t, a = excitation.times, excitation.acc
    keep = (t >= t_begin) & (t <= t_end)
    t, a = t[keep], a[keep]
    if t.size and t[-1] < t_end:  # the solver's ground is at rest after the record
        t, a = np.append(t, [t[-1], t_end]), np.append(a, [0.0, 0.0])
    return t, a


def pyplot():
    """matplotlib.pyplot on the Agg backend."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    return plt


def new_figure(width: float, height: float, **kwargs):
    """A figure of ``width`` x ``height`` inches with constrained layout (nothing falls off the canvas)."""
    plt = pyplot()
    fig = plt.figure(figsize=(width, height), layout="constrained", **kwargs)
    return fig


def text_width_pt(text: str, fontsize: float) -> float:
    """Width [pt] of one line of ``text`` as matplotlib draws it (mathtext measured as rendered)."""
    from matplotlib.font_manager import FontProperties
    from matplotlib.textpath import TextToPath

    width, _, _ = TextToPath().get_text_width_height_descent(text, FontProperties(size=fontsize),
                                                             ismath=len(formula_parts(text)) >= 3)
    return width


def wrap_room(fig, share: float = 1.0) -> float:
    """The width [pt] a wrapped line may take: ``share`` of the figure's width, less a margin."""
    return 0.97 * share * fig.get_figwidth() * 72.0


def glued_words(text: str) -> str:
    """``text`` with the spaces no line may break at as NUL characters: inside a ``$...$`` formula, and around
    `` = `` between a name and its value with its unit (``$T_b$ = 2 s``)."""
    parts = formula_parts(text)
    glued = "$".join(p.replace(" ", "\0") if k % 2 else p for k, p in enumerate(parts))
    return re.sub(r" = (\S+)( (?:g|s|m|mm|rad/s|m/s)\b)?",
                  lambda m: "\0=\0" + m.group(1) + (m.group(2) or "").replace(" ", "\0"), glued)


def wrap_to(fig, text: str, fontsize: float, share: float = 1.0) -> str:
    """``text`` wrapped to ``share`` of the figure's width, by the measured width of each line, never
    inside a ``$...$`` formula nor between a value and its symbol or unit (``$T_b$ = 2 s``)."""
    room = wrap_room(fig, share)
    out = []
    for para in glued_words(text).split("\n"):
        if text_width_pt(para.replace("\0", " "), fontsize) <= room:  # it fits: no word would move (a prefix of
            out.append(para)  # a line is never wider than the line), one measurement instead of one a word
            continue
        words = para.split(" ")

        def fits(i, k):  # words i .. i + k - 1 as one line
            return text_width_pt(" ".join(words[i:i + k]).replace("\0", " "), fontsize) <= room

        i = 0
        while i < len(words):
            while i < len(words) - 1 and not words[i]:  # a line starts at a word, not at a space
                i += 1
            # the longest line from word i that fits (its first word in any case), the line the words fill one by
            # one: a prefix of a line is never wider than the line, so it is found by bisection on its length
            lo, hi = 1, len(words) - i  # lo words fit (or are the first); more than hi do not exist
            while lo < hi:
                mid = (lo + hi + 1) // 2
                if fits(i, mid):
                    lo = mid
                else:
                    hi = mid - 1
            out.append(" ".join(words[i:i + lo]))
            i += lo
    return "\n".join(out).replace("\0", " ")


def footnote(fig, text: str, fontsize: float = 7.0) -> None:
    """A note under the panels, wrapped to the figure's width; the layout makes room for it."""
    fig.supxlabel(wrap_to(fig, text, fontsize, 0.97), fontsize=fontsize, x=0.01, ha="left", color="0.3")


def title(fig_or_ax, text: str, fontsize: float = 9.0, **kwargs) -> None:
    """A title wrapped to the width of the figure (``fig.suptitle`` for a figure, ``set_title`` for axes)."""
    if hasattr(fig_or_ax, "suptitle"):
        fig_or_ax.suptitle(wrap_to(fig_or_ax, text, fontsize), fontsize=fontsize, **kwargs)
    else:
        fig = fig_or_ax.get_figure()
        share = fig_or_ax.get_position().width
        fig_or_ax.set_title(wrap_to(fig, text, fontsize, share), fontsize=fontsize, **kwargs)
