"""``rockcli simulate --drums N``: the body as a column of drums (docs/physics-drums.md), every joint a contact that
sticks, opens about either corner or slides under ``--friction``, run beside its monolith."""

from __future__ import annotations

import math

import click

from rockcli.errors import RockcliInputError

#: The option's help.
DRUMS_HELP = ("The body as a column of drums, free at every joint (docs/physics-drums.md): N equal drums of its "
              "height and width, or the drums bottom to top as HEIGHTxWIDTH,HEIGHTxWIDTH,... [m] (a tapering shaft, "
              "a capital on top; the body's own size is then theirs). Needs --friction (every contact). Run beside "
              "the monolith of the paper. On the ground and on linear bearings.")


def parse_drums(text, block):
    """``--drums`` as a :class:`rockcli.models.drums.DrumColumn` of the body ``block`` (its name; for ``N`` its
    height and width); one sentence otherwise."""
    from rockcli.models.drums import DrumColumn

    s = str(text).strip()
    if "x" not in s.lower():
        try:
            n = int(s)
        except ValueError:
            raise RockcliInputError(f"--drums {s}: give a whole number of drums (e.g. --drums 7) or the drums bottom "
                                    f"to top as HEIGHTxWIDTH,... in m (e.g. 1.2x1.1,1.1x1.05)") from None
        if str(n) != s or n < 1:
            raise RockcliInputError(f"--drums {s}: give a whole number of drums >= 1 (e.g. --drums 7)")
        return DrumColumn.uniform(block.height, block.width, n, block.name)
    drums = []
    for k, part in enumerate(s.split(",")):
        hw = part.lower().split("x")
        try:
            h, w = (float(v) for v in hw)
        except ValueError:
            raise RockcliInputError(f"--drums {s}: drum {k + 1} is {part!r}; write each drum HEIGHTxWIDTH in m "
                                    f"(e.g. 1.2x1.1)") from None
        drums.append((h, w))
    return DrumColumn(tuple(drums), block.name)


def check_drums_scene(*, stacked, restitution, friction, others) -> None:
    """What ``--drums`` does not take (yet), each refused in one sentence."""
    if friction is None:
        raise RockcliInputError("--drums needs --friction MU: the joints of a column of drums stick or slide by it "
                                "(stone on stone: 0.5-0.8)")
    if stacked:
        raise RockcliInputError("--drums and --on: a column of drums stands on the ground or the bearings itself; "
                                "give a plinth as its lowest drum")
    if restitution is not None:
        raise RockcliInputError("--drums takes the plastic impact with Coulomb's law: --restitution is not taken "
                                "with drums yet")
    refused = [name for name, given in others if given]
    if refused:
        raise RockcliInputError(f"--drums prints and writes JSON for now: {', '.join(refused)} "
                                f"{'is' if len(refused) == 1 else 'are'} not taken with --drums yet")


def run_drums(column, foundation, excitation, label, friction, *, as_json, rtol, tail, horizon, pga) -> None:
    """Run and print (or write as JSON) the column of drums and its monolith."""
    import json

    from rockcli.solve.drums import simulate_drums

    run = simulate_drums(column, excitation, friction, foundation, rtol=rtol, tail=tail, horizon=horizon)
    if as_json:
        d = run.as_dict()
        d.update({"excitation": label, "isolation": foundation.label})
        click.echo(json.dumps(_clean(d), allow_nan=False))
        return
    st = run.stack
    rows = [("column", f"{column.name}: {column.n} drums, {column.height:.3f} m tall, {column.width:.3f} m wide at the "
                       f"base; the monolith R = {column.monolith.R:.3f} m, alpha = {column.monolith.alpha_deg:.2f} "
                       f"deg"),
            ("foundation", foundation.label),
            ("excitation", label + pga),
            ("friction", f"mu = {st.mu[0]:g} at every contact (Coulomb, static = kinetic)"
             if len(set(st.mu)) == 1 else "mu = " + ", ".join(f"{m:g}" for m in st.mu) + " bottom to top"),
            ("verdict", _verdict_words(run)),
            ("monolith", f"{run.monolith.verdict}" + ("" if run.monolith.verdict in ("overturned", "slid off") else
                                                      f", peak {run.monolith.base.psi_max_over_alpha:.4f} alpha")),
            ("drums vs monolith", run.compared)]
    fm = run.first_move
    rows.append(("first to move", "nothing moves" if fm is None else f"{fm[0]} {fm[2]} at {fm[1]:.3f} s"))
    thr = column.static_thresholds()
    mus = st.mu
    for j, p in enumerate(st.interfaces):
        start = min(thr[j], mus[j])
        rows.append((p.name, f"starts at {start:.3f} g ({'rocks' if thr[j] <= mus[j] else 'slides'} first), "
                             f"peak opening {p.psi_max_over_alpha:.4f} alpha, {p.n_impacts} impacts, slip peak "
                             f"{p.slide_max_m * 1000:.1f} mm, residual {p.slide_residual_m * 1000:+.1f} mm"))
    rows.append(("residual offsets", ", ".join(f"{x * 1000:+.1f}" for x in run.residual_offsets_m)
                 + " mm (each drum from the footprint's axis, bottom to top)"))
    rows.append(("counts", f"{st.n_slip_impacts} slipping impacts, {st.n_jumps} jumps (a pivot that would pull), "
                           f"{st.n_inconsistent} choices without a consistent pattern"))
    rows.append(("integration", f"{st.steps} steps, {st.nrhs} right-hand sides, ended at {st.t_end:.2f} s"))
    width = max(len(k) for k, _ in rows)
    for k, v in rows:
        click.echo(f"{k:<{width}}  {v}")
    if st.n_inconsistent > 0:
        click.echo(f"NOTE: NOT RELIABLE: at {st.n_inconsistent} events no contact pattern met every condition of the "
                   "contact law (docs/physics-drums.md, 'Not yet'): the answer above is not to be relied on")


def _verdict_words(run) -> str:
    st = run.stack
    if st.verdict == "overturned":
        return ("OVERTURNS: the whole column about its base" if run.falls_at == "base" else
                f"OVERTURNS: the drums above {run.falls_at} fall") + f" at {st.t_fail:.3f} s"
    if st.verdict == "slid off":
        return f"A DRUM SLIDES OFF at {run.falls_at} at {st.t_fail:.3f} s"
    return {"survives": "survives", "no motion": "survives (nothing moves)"}.get(st.verdict, st.verdict)


def _clean(x):
    if isinstance(x, float) and not math.isfinite(x):
        return None
    if isinstance(x, dict):
        return {k: _clean(v) for k, v in x.items()}
    if isinstance(x, (list, tuple)):
        return [_clean(v) for v in x]
    return x
