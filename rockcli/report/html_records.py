"""The records of an HTML report with their provenance: what each ground motion is and where it came from.

* :func:`provenance`: a record's file, format, SHA-256, units and time step and who stated them (the
  file's header, rockcli's record catalogue, the user), samples, PGA, PGV and fitted pulse; a pulse's
  parameters;
* :func:`records_section`: the section of the page: one row per record, the idealised pulses, the
  records that could not be used, those not available and the files of a folder that are not records.
"""

from __future__ import annotations

import hashlib
from pathlib import Path

from rockcli.report.html import breakable, esc, num, plural, table


def sha256_of(path) -> str:
    """SHA-256 of a file's bytes, in hex (``-`` when it cannot be read)."""
    h = hashlib.sha256()
    try:
        with open(path, "rb") as fh:
            for chunk in iter(lambda: fh.read(1 << 20), b""):
                h.update(chunk)
    except OSError:
        return "-"
    return h.hexdigest()


def _motion_facts(motion) -> dict:
    """A record's samples, PGA [g] and PGV [m/s] (trapezoid rule from rest) and fitted Ricker pulse."""
    from rockcli.records.motion import calc_peaks

    out = {"dt": motion.dt, "npts": motion.npts, "duration": motion.duration, "pga_g": motion.pga_g,
           "pgv_mps": calc_peaks(motion).pgv_mps}
    try:
        from rockcli.pulses_fit import fit_pulse

        fit = fit_pulse(motion)
        out["pulse"] = (f"{fit.shape}, a_p = {fit.a_p_g:+.3f} g, T_p = {fit.T_p_s:.2f} s at t = {fit.t0_s:.2f} s "
                        f"({100 * fit.energy_fraction:.0f} % of the record's energy)")
        out["pulse_words"] = pulse_sign_words(fit.shape, fit.a_p_g)
    except Exception as exc:  # a record no pulse fits still gets its report
        out["pulse"] = f"no pulse fitted ({exc})"
        out["pulse_words"] = ""
    return out


def _component(rec, cos: float | None = None) -> dict:
    """One horizontal component of a pair: its file (name, path, format, SHA-256), orientation, units and
    samples, PGA and PGV (``rec`` a :class:`rockcli.records.Record`, or a dict with ``path`` and
    ``azimuth_deg`` only, from a projection's metadata)."""
    from rockcli.records.motion import calc_peaks

    meta = rec if isinstance(rec, dict) else dict(rec.meta)
    path = meta.get("path") or ""
    out = {"file": Path(path).name if path else "-", "path": str(path or "-"), "format": meta.get("format", "-"),
           "sha256": sha256_of(path) if path else "-", "azimuth_deg": meta.get("azimuth_deg"),
           "units": meta.get("units", "-"), "units_source": meta.get("units_source", ""),
           "dt_source": meta.get("dt_source", ""), "component": meta.get("component", ""), "cos": cos}
    if not isinstance(rec, dict):
        out.update(dt=rec.dt, npts=rec.npts, duration=rec.duration, pga_g=rec.pga_g, pgv_mps=calc_peaks(rec).pgv_mps)
    return out


def provenance(excitation, projections=None) -> dict:
    """Where a ground motion came from and what it is: for a record read from a file, its name,
    format, SHA-256, units as stated (and by whom), time step, samples, PGA [g], PGV [m/s] (trapezoid
    rule from rest) and fitted Ricker pulse; for an analytic or catalogued pulse, its parameters.

    Two horizontal components projected onto the rocking plane (a pair, ``--azimuth``) add ``components``
    (each file with its SHA-256, orientation, PGA and PGV) and ``projections``: each projection the runs used
    (``(record, where)``: ``projections`` given, e.g. the orientation each row of ``--azimuth worst`` kept;
    else the motion itself) with its samples, PGA, PGV and fitted pulse."""
    motion = getattr(excitation, "motion", excitation)
    label = getattr(excitation, "label", getattr(motion, "name", ""))
    if motion is None:
        return {"label": label, "error": getattr(excitation, "error", "") or "could not be read"}
    if not hasattr(motion, "acc"):
        from rockcli.io.units import G

        return {"label": label, "kind": "pulse", "shape": motion.shape, "a_p_g": motion.a_p / G,
                "T_p_s": motion.T_p, "source": getattr(excitation, "source", "analytic pulse")}
    meta = dict(motion.meta)
    projected = meta.get("projection")
    if projected:  # a pair: both files, and each projection run
        pair = getattr(excitation, "pair", None)
        cos = [c.get("cos") for c in projected.get("components", ())]
        comps = ([_component(r, c) for r, c in zip(pair, cos)] if pair else
                 [_component(c, c.get("cos")) for c in projected.get("components", ())])
        swept = tuple(getattr(excitation, "azimuths", ()))  # azimuth="worst": motion is only its 0 deg projection
        used = projections if projections is not None else [] if swept else [(motion, "")]
        return {"label": label, "kind": "pair", "components": comps, "scale": meta.get("scale", 1.0), "swept": swept,
                "event": meta.get("event", ""), "station": meta.get("station", ""),
                "projections": [{"azimuth_deg": m.meta["projection"]["azimuth_deg"], "where": where,
                                 "cos": [c.get("cos") for c in m.meta["projection"]["components"]],
                                 **_motion_facts(m)} for m, where in used]}
    path = meta.get("path") or getattr(excitation, "source", "")
    out = {"label": label, "kind": "record", "file": Path(path).name if path else "-", "path": str(path or "-"),
           "format": meta.get("format", "-"), "sha256": sha256_of(path) if path else "-",
           "units": meta.get("units", "-"), "units_source": meta.get("units_source", ""),
           "scale": meta.get("scale", 1.0), "event": meta.get("event", ""), "station": meta.get("station", ""),
           "component": meta.get("component", "")}
    out["dt_source"] = meta.get("dt_source", "")
    out.update(_motion_facts(motion))
    return out


#: Where a record's units (or time step) came from, in words (``units_source`` of the record's metadata;
#: any other value, e.g. a reader's own note, is shown as it is).
SOURCE_WORDS = {"file": "as stated in the file",
                "catalogue": "from rockcli's record catalogue (the file does not state them)",
                "caller": "as given by the user (--units; the file does not state them)",
                "suite": "as given by the user (--units, for the files that do not state them)",
                "extra (gmprocess)": "as read from the file by gmprocess"}
DT_WORDS = {"catalogue": "time step from rockcli's record catalogue",
            "caller": "time step as given by the user (--dt)", "suite": "time step as given by the user (--dt)"}


def pulse_sign_words(shape: str, a_p_g: float) -> str:
    """What the sign of a fitted pulse's amplitude means: the direction of its main peak along the record's
    axis (for an antisymmetric pulse, of its first peak), not a size."""
    way = "negative" if a_p_g < 0 else "positive"
    peak = "first peak" if shape == "ricker-anti" else "main peak"
    sign = "<" if a_p_g < 0 else ">"
    return f"a_p {sign} 0: its {peak} accelerates the ground toward the {way} side of the record's axis"


def _units_cell(p) -> str:
    stated = SOURCE_WORDS.get(p["units_source"], p["units_source"])
    return esc(p["units"]) + (f"<br><span class='note'>{esc(stated)}</span>" if stated else "")


def _samples_cell(p, scaled: str = "") -> str:
    dt_said = DT_WORDS.get(p.get("dt_source", ""), "")
    return (f"{p['npts']} at {p['dt']:g} s<br>({p['duration']:.2f} s)" + scaled
            + (f"<br><span class='note'>{esc(dt_said)}</span>" if dt_said else ""))


def _pulse_cell(p) -> str:
    sign = f"<br><span class='note'>{esc(p['pulse_words'])}</span>" if p["pulse_words"] else ""
    return esc(p["pulse"]) + sign


def _hash_cell(sha: str) -> str:
    return f"<code class='hash'>{esc(sha)}</code>"


def _pair_rows(p, what: str, scaled: str) -> list:
    """The rows of a pair: each component's file (with its SHA-256), then each projection run (what ran)."""
    rows = []
    comps = p["components"]
    for k, c in enumerate(comps):
        az = c["azimuth_deg"]
        name = f"component {az:g} deg" if az is not None else f"component {c['component'] or k + 1}"
        head = (f"<b>{breakable(p['label'])}</b><br>{esc(what or '-')}<br>" if k == 0 else "")
        known = "npts" in c
        rows.append((head + f"{esc(name)} ({'first' if k == 0 else 'second'} of the pair)",
                     f"{breakable(c['file'])}<br>{esc(c['format'])}", _units_cell(c),
                     _samples_cell(c) if known else "-", num(c.get("pga_g"), ".3f", "g"),
                     num(c.get("pgv_mps"), ".3f", "m/s"), "-", _hash_cell(c["sha256"])))
    names = [f"{c['azimuth_deg']:g}" if c["azimuth_deg"] is not None else str(k + 1) for k, c in enumerate(comps)]
    swept = p["swept"]
    if swept and not p["projections"]:
        rows.append((f"projected onto each of its {len(swept)} orientations, {swept[0]:g} to {swept[-1]:g} deg",
                     "-", "-", "-", "-", "-", "-", "-"))
    for q in p["projections"]:
        where = f"<br><span class='note'>{esc(q['where'])}</span>" if q["where"] else ""
        rows.append((f"projected onto <b>{q['azimuth_deg']:g} deg</b>: the motion run{where}",
                     esc(_projection_formula(q["azimuth_deg"], q["cos"], names))
                     + "<br><span class='note'>from the two files above</span>",
                     "<span class='note'>as the two files</span>", _samples_cell(q, scaled),
                     num(q["pga_g"], ".3f", "g"), num(q["pgv_mps"], ".3f", "m/s"), _pulse_cell(q), "-"))
    return rows


def _projection_formula(theta: float, weights, names) -> str:
    """``a(105) = 0.122 a(22) - 0.993 a(292)``: a projection from its components' weights (cosines)."""
    text = f"a({theta:g}) ="
    for k, (w, n) in enumerate(zip(weights, names)):
        w = 0.0 if w is None else float(w)
        sign = ("-" if w < 0 else "") if k == 0 else ("- " if w < 0 else "+ ")
        text += f" {sign}{abs(w):.3f} a({n})"
    return text


def records_section(excitations, unavailable=(), projections=None) -> str:
    """The records with their provenance: one row each (a pulse: its parameters; a pair of horizontal
    components: each file with its SHA-256, then each projection run, ``projections[label]`` when given, see
    :func:`provenance`); then those that could not be used and, from ``unavailable``, those asked for (or in
    the default set) that are not available and the files of a folder that are not records."""
    rows, pulses, bad = [], [], []
    projections = projections or {}
    for x in excitations:
        p = provenance(x, projections.get(getattr(x, "label", None)))
        if p.get("kind") == "pair":
            what = ", ".join(v for v in (p["event"], p["station"]) if v)
            scaled = f"<br>scaled by {p['scale']:g} (PGA and PGV of the scaled motion)" if p["scale"] != 1.0 else ""
            rows += _pair_rows(p, what, scaled)
            continue
        if "error" in p:
            bad.append(f"<li>{esc(p['label'])}: could not be used: {esc(p['error'])}</li>")
        elif p["kind"] == "pulse":
            pulses.append((esc(p["label"]), esc(p["shape"]), num(p["a_p_g"], "+.4f", "g"), num(p["T_p_s"], ".4f", "s"),
                           esc(p["source"])))
        else:
            what = ", ".join(v for v in (p["event"], p["station"], p["component"] and f"component {p['component']}")
                             if v)
            scaled = f"<br>scaled by {p['scale']:g} (PGA and PGV of the scaled motion)" if p["scale"] != 1.0 else ""
            rows.append((f"<b>{breakable(p['label'])}</b><br>{esc(what or '-')}",
                         f"{breakable(p['file'])}<br>{esc(p['format'])}", _units_cell(p), _samples_cell(p, scaled),
                         num(p["pga_g"], ".3f", "g"), num(p["pgv_mps"], ".3f", "m/s"), _pulse_cell(p),
                         _hash_cell(p["sha256"])))
    parts = ["<p>Each ground motion is used as it is in its file (no filtering, no baseline correction), scaled "
             "only where said. PGA: peak ground acceleration; PGV: peak ground velocity (integrated from rest); "
             "the fitted pulse is the Ricker wavelet that best matches the record's strongest pulse (the sign of "
             "its amplitude a_p is a direction along the record's axis, not a size: the body is symmetric, so the "
             "record reversed would rock it as a mirror image, with the same verdict). The "
             "SHA-256 fingerprint identifies the exact file: the same file gives the same fingerprint anywhere."
             "</p>"]
    if rows:
        parts.append(table(("record", "file, format", "units", "samples", "PGA", "PGV", "fitted pulse", "SHA-256"),
                           rows, numeric=(4, 5)))
    if pulses:
        parts.append("<p>Idealised pulses (not recorded ground motions):</p>"
                     + table(("name", "shape", "amplitude a_p", "period T_p", "source"), pulses, numeric=(2, 3)))
    if bad:
        parts.append("<p>Could not be used:</p><ul>" + "".join(bad) + "</ul>")
    from rockcli.records.unavailable import Skipped

    missing = [u for u in unavailable if not isinstance(u, Skipped)]
    skipped = [u for u in unavailable if isinstance(u, Skipped)]
    if missing:
        parts.append("<p>Not available (asked for, or in the default set, but neither a file nor a pulse could be "
                     "run; the verdicts say nothing about them):</p><ul>"
                     + "".join(f"<li>{esc(u.label)}: {esc(u.reason)}</li>" for u in missing) + "</ul>")
    if skipped:
        parts.append(f"<p class='note'>Skipped {plural(len(skipped), 'file')} of the folder(s) that are not records "
                     "(no reader recognises them): " + esc(", ".join(u.label for u in skipped)) + ".</p>")
    return "\n".join(parts)
