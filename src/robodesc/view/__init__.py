"""Pictures of robots: a self-contained viewer page (three.js) and headless images (MuJoCo).

Public functions (the CLI's ``view`` and ``render`` commands, the batch summary and the folder
targets' previews call these):

- :func:`write_view_html` — the HTML viewer page of a robot, or of the robot as compiled for a target;
- :func:`render_png` — a PNG of a robot through MuJoCo's offscreen renderer (EGL or OSMesa);
- :func:`write_preview_png` — ``preview.png`` in an output folder, never failing the caller;
- :func:`write_summary_html` — a batch run's ``summary.html`` with a thumbnail per robot.

A driver-layer package: it uses the pipeline, and only the CLI (and the batch driver) import it.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

__all__ = [
    "PageResult",
    "RenderResult",
    "RenderUnavailable",
    "SummaryRow",
    "render_png",
    "summary_rows",
    "write_preview_png",
    "write_summary_html",
    "write_view_html",
]

if TYPE_CHECKING:
    from robodesc.view.page import PageResult, write_view_html
    from robodesc.view.render import RenderResult, RenderUnavailable, render_png
    from robodesc.view.thumbs import SummaryRow, summary_rows, write_preview_png, write_summary_html

_HOME = {
    "PageResult": "robodesc.view.page",
    "write_view_html": "robodesc.view.page",
    "RenderResult": "robodesc.view.render",
    "RenderUnavailable": "robodesc.view.render",
    "render_png": "robodesc.view.render",
    "SummaryRow": "robodesc.view.thumbs",
    "summary_rows": "robodesc.view.thumbs",
    "write_preview_png": "robodesc.view.thumbs",
    "write_summary_html": "robodesc.view.thumbs",
}


def __getattr__(name: str) -> Any:
    # Loaded on first use: ``render`` imports MuJoCo, ``view`` does not need it.
    if name in _HOME:
        import importlib

        return getattr(importlib.import_module(_HOME[name]), name)
    raise AttributeError(name)
