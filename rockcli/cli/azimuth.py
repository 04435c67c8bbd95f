"""``--azimuth`` on ``simulate``: the record along the rocking plane, and ``--azimuth worst``."""

from __future__ import annotations

from contextlib import contextmanager

import click

from rockcli.cli.options import add_inputs, given_azimuth
from rockcli.errors import RockcliInputError


def read_excitation(source, kwargs: dict):
    """``(record, pair)`` for ``simulate --record SOURCE``: the record as read (``pair`` None), or, with
    ``--azimuth``, its two horizontal components projected onto the azimuth (``pair`` the checked pair;
    with ``worst``, the record is the projection onto 0 deg and the sweep is run by :func:`run_worst`)."""
    from rockcli.records import read_record
    from rockcli.records.orientation import project, read_pair

    given = given_azimuth()
    if given["azimuth"] is None:
        with _pair_written_as_suite(source):
            rec = read_record(source, **kwargs)
        add_inputs([rec.meta.get("path")], "the record")
        return rec, None
    from rockcli.assess.pairs import one_file_pair

    one = one_file_pair(source, given["record_2"], ("--record", "--record-2"))
    if one:
        raise RockcliInputError(one)
    with _pair_written_as_suite(source):
        pair = read_pair(source, given["record_2"], **kwargs)
    add_inputs([r.meta.get("path") for r in pair], "the record")
    return project(*pair, 0.0 if given["azimuth"] == "worst" else given["azimuth"]), pair


@contextmanager
def _pair_written_as_suite(source):
    """A ``--record A+B`` that cannot be read as written is said to be a pair written as in a suite: ``simulate``
    takes a pair as ``--record A --record-2 B`` with ``--azimuth`` (not "A+B: no such file")."""
    try:
        yield
    except RockcliInputError:
        from rockcli.records.reader import path_exists

        if "+" in str(source) and not path_exists(source):
            raise RockcliInputError(f"--record {source}: simulate takes the two horizontal components of a pair as "
                                    f"--record A --record-2 B, with --azimuth DEG (or --azimuth worst); A+B is "
                                    f"how a suite writes a pair (assess --records)") from None
        raise


def refuse_without_record() -> None:
    """``--azimuth``/``--record-2`` given without ``--record``."""
    ctx = click.get_current_context(silent=True)
    if ctx is not None and any(ctx.meta.get(k) is not None for k in ("rockcli.azimuth", "rockcli.record_2",
                                                                     "rockcli.azimuth_step", "rockcli.component")):
        raise RockcliInputError("--azimuth, --record-2, --azimuth-step and --component apply to --record")


def wants_worst() -> bool:
    return given_azimuth()["azimuth"] == "worst"


def worst_of(results) -> int | None:
    """Index of the most adverse run (:func:`rockcli.assess.azimuth.most_adverse`: the earliest overturn, else
    the largest peak |theta|/alpha), or None when they all rank equal (nothing lifts the body off)."""
    from rockcli.assess.azimuth import adverse_key, most_adverse

    return most_adverse([adverse_key(r.overturned, r.t_overturn_s, r.theta_max_over_alpha) for r in results])


def run_worst(block, foundation, pair, factor: float, *, as_json: bool, label: str, **solver) -> None:
    """Run every azimuth of ``--azimuth worst`` (verdict only, all cores) and print each and the worst."""
    import json

    from rockcli.records.orientation import project, sweep_azimuths
    from rockcli.solve import VERDICT_ERROR, simulate_many

    azimuths = sweep_azimuths(given_azimuth()["step"])
    jobs = [(block, foundation, project(*pair, th), factor) for th in azimuths]
    results = simulate_many(jobs, **solver)
    failed = [r for r in results if r.verdict == VERDICT_ERROR or r.status < 0]
    if failed:
        raise click.ClickException(f"a run of --azimuth worst failed: {getattr(failed[0], 'error', 'numerical failure')}")
    worst = worst_of(results)
    over = [float(th) for th, r in zip(azimuths, results) if r.overturned]
    comps = ", ".join(f"{r.meta.get('component')} at {r.meta['azimuth_deg']:g} deg" for r in pair)
    if as_json:
        click.echo(json.dumps({
            "block": block.name, "isolation": foundation.label, "excitation": label, "components": comps,
            "azimuths_deg": [float(a) for a in azimuths],
            "verdicts": [r.verdict for r in results],
            "theta_max_over_alpha": [None if r.overturned else r.theta_max_over_alpha for r in results],
            "worst_azimuth_deg": None if worst is None else float(azimuths[worst]),
            "worst_verdict": results[0 if worst is None else worst].verdict,
            "overturning_azimuths_deg": over}, allow_nan=False))
        return
    click.echo(f"block       {block.name}: R = {block.R:.3f} m, alpha = {block.alpha_deg:.2f} deg")
    click.echo(f"foundation  {foundation.label}")
    click.echo(f"excitation  {label}: components {comps}, projected onto each azimuth "
               f"(normal to the rocking axis, clockwise from north)")
    click.echo("azimuth  verdict")
    for k, (th, r) in enumerate(zip(azimuths, results)):
        text = (f"OVERTURNS at {r.t_overturn_s:.3f} s" if r.overturned else
                f"{'no uplift' if r.verdict == 'no_uplift' else 'survives'} {r.theta_max_over_alpha:.4f}")
        click.echo(f"{th:7g}  {text}{'   <- worst' if k == worst else ''}")
    if worst is None:
        click.echo("worst azimuth: none (the block does not lift off its base in any orientation, so no orientation "
                   "is worse than another); which one a stronger record would topple first is a question of "
                   "margins: 'rockcli assess column ... --azimuth worst' ranks the orientations by the smallest "
                   "scale factor that overturns")
        return
    r = results[worst]
    what = (f"overturns at {r.t_overturn_s:.3f} s" if r.overturned else
            f"survives, peak |theta|/alpha {r.theta_max_over_alpha:.4f}")
    click.echo(f"worst azimuth: {azimuths[worst]:g} deg ({what}); overturning azimuths: "
               + (", ".join(f"{a:g}" for a in over) + " deg" if over else "none"))
