"""Pictures where people look: a batch run's ``summary.html`` and a folder target's ``preview.png``.

Both are best effort: a picture that cannot be made (no GL backend, a robot that does not load)
leaves a placeholder or no file, never a failed run. The batch driver and the folder targets call
these after their own work is done (see docs/view.md for the wiring).
"""

from __future__ import annotations

import base64
import html
import os
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from typing import Any

from robodesc._files import write_atomic
from robodesc.frontends.load import Source
from robodesc.ir.diagnostics import RobodescError
from robodesc.ir.model import Robot
from robodesc.options import CompileOptions
from robodesc.view.render import render_png
from robodesc.view.source import Loaded

THUMB_SIZE = (240, 180)


@dataclass(slots=True, frozen=True)
class SummaryRow:
    """One robot of a batch run: its name, outcome (``ok``, ``warnings``, ``failed``, ...), a
    one-line message, the output it produced, and its picture: ``thumbnail``, a PNG already made
    (a worker's :func:`write_preview_png`), else drawn now from ``source`` (an input path or an IR
    robot) with ``options``; neither: a placeholder."""

    name: str
    outcome: str
    message: str = ""
    output: str | None = None
    source: Source | None = None
    options: CompileOptions | None = None
    thumbnail: str | None = None


def summary_rows(
    summary: Mapping[str, Any],
    options: Mapping[str, CompileOptions] | None = None,
    thumbnails: Mapping[str, str] | None = None,
    *,
    draw: bool = True,
) -> list[SummaryRow]:
    """Rows for :func:`write_summary_html` from a batch summary (``robodesc.batch.summary.
    build_summary``'s dict): each job's id, status, error or finding counts and output; its input
    as the source (drawn with ``options[job id]``) unless ``thumbnails[job id]`` names a PNG; with
    ``draw`` False, no pictures (placeholders)."""
    rows = []
    for job in summary.get("jobs", []):
        ident = str(job["id"])
        counts = ", ".join(f"{n} {s}" for s, n in dict(job.get("findings") or {}).items() if n)
        message = str(job.get("error") or counts)
        # Only these wrote an output (robodesc.batch.jobs.WROTE_OUTPUTS): the others have no robot.
        failed = job.get("status") not in ("ok", "validation-failed")
        rows.append(
            SummaryRow(
                name=ident,
                outcome=str(job.get("status", "")),
                message=message,
                output=job.get("output"),
                source=None if failed or not draw else job.get("input"),
                options=(options or {}).get(ident),
                thumbnail=(thumbnails or {}).get(ident),
            )
        )
    return rows


def write_preview_png(
    robot: Robot | Source,
    folder: str,
    *,
    size: tuple[int, int] = (800, 600),
    options: CompileOptions | None = None,
    name: str = "preview.png",
) -> str | None:
    """``folder/preview.png`` (or ``name``): an iso picture of ``robot`` (the compiled IR,
    ``result.robot``, or any source). Returns its path, or None when no picture could be made
    (no GL backend, a mesh-less robot without shapes ...): nothing is raised."""
    path = os.path.join(folder, name)
    source: Source | Loaded = Loaded(robot=robot, findings=[]) if isinstance(robot, Robot) else robot
    try:
        render_png(source, path, view="iso", size=size, options=options)
    except (RobodescError, OSError, RuntimeError, ValueError):
        return None
    return path


def thumbnail_data_uri(source: Source, tmp_png: str, options: CompileOptions | None = None) -> str | None:
    """A small iso picture as a ``data:`` URI (the summary page stays one file), or None."""
    loaded: Source | Loaded = Loaded(robot=source, findings=[]) if isinstance(source, Robot) else source
    try:
        render_png(loaded, tmp_png, view="iso", size=THUMB_SIZE, options=options)
        with open(tmp_png, "rb") as handle:
            data = handle.read()
    except (RobodescError, OSError, RuntimeError, ValueError):
        return None
    finally:
        if os.path.exists(tmp_png):
            os.unlink(tmp_png)
    return "data:image/png;base64," + base64.b64encode(data).decode("ascii")


_STYLE = """
body { font: 13px/1.4 system-ui, sans-serif; margin: 16px; color: #1d2330; }
table { border-collapse: collapse; }
td, th { border-bottom: 1px solid #dde; padding: 6px 10px; text-align: left; vertical-align: middle; }
img { display: block; width: 240px; height: 180px; background: #eef0f3; }
.none { width: 240px; height: 180px; background: #eef0f3; color: #889; display: flex; align-items: center; justify-content: center; }
.ok { color: #17743c; } .validation-failed { color: #b07000; } .error, .crashed, .timeout, .not-run { color: #c02020; }
"""


def write_summary_html(
    out: str,
    rows: Sequence[SummaryRow],
    *,
    title: str = "robodesc batch",
    options: CompileOptions | None = None,
) -> str:
    """Write ``out``: one table row per robot with its thumbnail (rendered now, embedded), outcome
    and message. Robots without a source, or that cannot be drawn, get a placeholder."""
    tmp_png = out + ".thumb.png"
    lines = [
        "<!DOCTYPE html>",
        '<html lang="en"><head><meta charset="utf-8">',
        "<meta http-equiv=\"Content-Security-Policy\" content=\"default-src 'none'; style-src 'unsafe-inline'; img-src data:\">",
        f"<title>{html.escape(title)}</title><style>{_STYLE}</style></head><body>",
        f"<h1>{html.escape(title)}</h1>",
        f"<p>{len(rows)} robot(s)</p>",
        "<table><tr><th>picture</th><th>robot</th><th>outcome</th><th>message</th><th>output</th></tr>",
    ]
    for row in rows:
        uri = None
        if row.thumbnail is not None and os.path.isfile(row.thumbnail):
            with open(row.thumbnail, "rb") as handle:
                uri = "data:image/png;base64," + base64.b64encode(handle.read()).decode("ascii")
        elif row.source is not None:
            uri = thumbnail_data_uri(row.source, tmp_png, row.options or options)
        picture = f'<img alt="{html.escape(row.name)}" src="{uri}">' if uri else '<div class="none">no picture</div>'
        output = html.escape(row.output or "")
        lines.append(
            f"<tr><td>{picture}</td><td>{html.escape(row.name)}</td>"
            f'<td class="{html.escape(row.outcome)}">{html.escape(row.outcome)}</td>'
            f"<td>{html.escape(row.message)}</td><td>{output}</td></tr>"
        )
    lines.append("</table></body></html>")
    write_atomic(out, "\n".join(lines) + "\n")
    return out
