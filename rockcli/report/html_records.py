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

from rockcli.report.html import esc, num, plural, table


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


def provenance(excitation) -> dict:
    """Where a ground motion came from and what it is: for a record read from a file, its name,
    format, SHA-256, units as stated (and by whom), time step, samples, PGA [g], PGV [m/s] (trapezoid
    rule from rest) and fitted Ricker pulse; for an analytic or catalogued pulse, its parameters."""
    motion = getattr(excitation, "motion", excitation)
    label = getattr(excitation, "label", getattr(motion, "name", ""))
    if motion is None:
        return {"label": label, "error": getattr(excitation, "error", "") or "could not be read"}
    if not hasattr(motion, "acc"):
        from rockcli.io.units import G

        return {"label": label, "kind": "pulse", "shape": motion.shape, "a_p_g": motion.a_p / G,
                "T_p_s": motion.T_p, "source": getattr(excitation, "source", "analytic pulse")}
    from rockcli.records.motion import calc_peaks

    meta = dict(motion.meta)
    path = meta.get("path") or getattr(excitation, "source", "")
    out = {"label": label, "kind": "record", "file": Path(path).name if path else "-", "path": str(path or "-"),
           "format": meta.get("format", "-"), "sha256": sha256_of(path) if path else "-",
           "units": meta.get("units", "-"), "units_source": meta.get("units_source", ""),
           "dt": motion.dt, "npts": motion.npts, "duration": motion.duration, "pga_g": motion.pga_g,
           "pgv_mps": calc_peaks(motion).pgv_mps, "scale": meta.get("scale", 1.0),
           "event": meta.get("event", ""), "station": meta.get("station", ""),
           "component": meta.get("component", "")}
    out["dt_source"] = meta.get("dt_source", "")
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


def records_section(excitations, unavailable=()) -> str:
    """The records with their provenance: one row each (a pulse: its parameters); then those that could
    not be used and, from ``unavailable``, those asked for (or in the default set) that are not available
    and the files of a folder that are not records."""
    rows, pulses, bad = [], [], []
    for x in excitations:
        p = provenance(x)
        if "error" in p:
            bad.append(f"<li>{esc(p['label'])}: could not be used: {esc(p['error'])}</li>")
        elif p["kind"] == "pulse":
            pulses.append((esc(p["label"]), esc(p["shape"]), num(p["a_p_g"], "+.4f", "g"), num(p["T_p_s"], ".4f", "s"),
                           esc(p["source"])))
        else:
            what = ", ".join(v for v in (p["event"], p["station"], p["component"] and f"component {p['component']}")
                             if v)
            stated = SOURCE_WORDS.get(p["units_source"], p["units_source"])
            dt_said = DT_WORDS.get(p["dt_source"], "")
            scaled = f"<br>scaled by {p['scale']:g} (PGA and PGV of the scaled motion)" if p["scale"] != 1.0 else ""
            sign = f"<br><span class='note'>{esc(p['pulse_words'])}</span>" if p["pulse_words"] else ""
            rows.append((f"<b>{esc(p['label'])}</b><br>{esc(what or '-')}", f"{esc(p['file'])}<br>{esc(p['format'])}",
                         esc(p["units"]) + (f"<br><span class='note'>{esc(stated)}</span>" if stated else ""),
                         f"{p['npts']} at {p['dt']:g} s<br>({p['duration']:.2f} s)" + scaled
                         + (f"<br><span class='note'>{esc(dt_said)}</span>" if dt_said else ""),
                         num(p["pga_g"], ".3f", "g"), num(p["pgv_mps"], ".3f", "m/s"), esc(p["pulse"]) + sign,
                         f"<code class='hash'>{esc(p['sha256'])}</code>"))
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
    from rockcli.assess.excitations import Skipped

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
