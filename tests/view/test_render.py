"""``robodesc render``: a PNG of the right size, not blank, close to its golden image.

The goldens are compared within a tolerance that software rasterisers on different CPUs stay in
(llvmpipe's and OSMesa's anti-aliased edges and shading differ by a few levels, and a pixel here and
there along an edge): the mean difference and the share of clearly different pixels, over images
shrunk 4x4 so that a one-pixel shift of an edge does not count. Regenerate with --update-golden.
"""

from __future__ import annotations

import pathlib

import numpy as np
import pytest

from robodesc.cli import main
from robodesc.view.png import decode_png, write_png
from robodesc.view.render import parse_size, render_png
from robodesc.view.thumbs import SummaryRow, summary_rows, write_preview_png, write_summary_html
from tests.view.cases import GOLDEN, GRIPPER, QUADRUPED

BACKGROUND_STD = 4.0  # the sky gradient alone varies less than this


def shrink(image: np.ndarray, k: int = 4) -> np.ndarray:
    h, w = image.shape[0] // k * k, image.shape[1] // k * k
    out: np.ndarray = image[:h, :w].astype(float).reshape(h // k, k, w // k, k, 3).mean(axis=(1, 3))
    return out


def assert_close_to(image: np.ndarray, golden: pathlib.Path, update: bool) -> None:
    if update:
        golden.parent.mkdir(parents=True, exist_ok=True)
        write_png(str(golden), image)
    if not golden.exists():
        pytest.fail(f"golden file {golden} is missing; run pytest --update-golden and review it")
    expected = decode_png(golden.read_bytes())
    assert image.shape == expected.shape
    diff = np.abs(shrink(image) - shrink(expected)).max(axis=2)
    assert diff.mean() < 3.0, f"mean difference {diff.mean():.2f} levels"
    assert (diff > 40).mean() < 0.01, f"{(diff > 40).mean():.2%} of the picture differs clearly"


def render(tmp_path: pathlib.Path, source: str, **kw: object) -> np.ndarray:
    out = tmp_path / "robot.png"
    render_png(source, str(out), **kw)  # type: ignore[arg-type]
    return decode_png(out.read_bytes())


def test_render_size_and_not_blank(tmp_path: pathlib.Path, gl: str) -> None:
    image = render(tmp_path, GRIPPER, size=(320, 240))
    assert image.shape == (240, 320, 3)
    assert image.std() > BACKGROUND_STD
    # The robot is in the middle, and the camera frames it: something is drawn near every edge's
    # middle third, nothing is cut off at the borders (the border rows are background).
    rows = np.where((np.abs(image.astype(int) - image[0:1, 0:1].astype(int)).max(axis=2) > 40).any(axis=1))[0]
    assert rows.size and rows.min() > 0 and rows.max() < 239


@pytest.mark.parametrize("view", ["front", "side", "top", "iso"])
def test_views_match_goldens(tmp_path: pathlib.Path, gl: str, view: str, request: pytest.FixtureRequest) -> None:
    image = render(tmp_path, GRIPPER, size=(240, 180), view=view)
    assert_close_to(image, GOLDEN / f"gripper_arm_{view}.png", bool(request.config.getoption("--update-golden")))


def test_grid_and_collision(tmp_path: pathlib.Path, gl: str, request: pytest.FixtureRequest) -> None:
    image = render(tmp_path, QUADRUPED, size=(400, 300), grid_views=True, collision=True)
    assert image.shape == (300, 400, 3)
    quads = [image[:150, :200], image[:150, 200:], image[150:, :200], image[150:, 200:]]
    assert all(q.std() > BACKGROUND_STD for q in quads)
    assert_close_to(image, GOLDEN / "quadruped_grid_collision.png", bool(request.config.getoption("--update-golden")))


def test_cli_render(tmp_path: pathlib.Path, gl: str) -> None:
    out = tmp_path / "r.png"
    assert main(["render", GRIPPER, "-o", str(out), "--size", "200x100", "--view", "side"]) == 0
    assert decode_png(out.read_bytes()).shape == (100, 200, 3)
    assert main(["render", GRIPPER, "-o", str(out), "--size", "big"]) == 2


def test_no_backend_is_a_clear_error(tmp_path: pathlib.Path, monkeypatch: pytest.MonkeyPatch) -> None:
    from robodesc.view import render as module

    monkeypatch.setattr(module, "backend_candidates", lambda: [])
    with pytest.raises(module.RenderUnavailable, match="libosmesa6"):
        render_png(GRIPPER, str(tmp_path / "x.png"))
    assert not (tmp_path / "x.png").exists()


def test_parse_size() -> None:
    assert parse_size("640x480") == (640, 480)


def test_preview_and_summary(tmp_path: pathlib.Path, gl: str) -> None:
    from robodesc import load

    preview = write_preview_png(load(QUADRUPED), str(tmp_path))
    assert preview is not None and decode_png(pathlib.Path(preview).read_bytes()).std() > BACKGROUND_STD
    rows = [
        SummaryRow("gripper_arm", "ok", "8 links", "out/gripper_arm.usda", GRIPPER),
        SummaryRow("broken", "failed", "not XML", None, str(tmp_path / "nothing.urdf")),
    ]
    out = write_summary_html(str(tmp_path / "summary.html"), rows)
    text = pathlib.Path(out).read_text()
    assert text.count("data:image/png;base64,") == 1 and "no picture" in text
    assert "http" not in text.replace("http-equiv", "")


def test_summary_rows_from_a_batch_summary(tmp_path: pathlib.Path) -> None:
    thumb = tmp_path / "t.png"
    write_png(str(thumb), np.full((18, 24, 3), 200, dtype=np.uint8))
    summary = {
        "jobs": [
            {
                "id": "a",
                "status": "ok",
                "input": GRIPPER,
                "output": "a/a.usda",
                "error": None,
                "findings": {"warning": 2},
            },
            {"id": "b", "status": "error", "input": "b.urdf", "output": "b/b.usda", "error": "not XML", "findings": {}},
        ]
    }
    rows = summary_rows(summary, thumbnails={"a": str(thumb)})
    assert [(r.name, r.outcome, r.message, r.source is None) for r in rows] == [
        ("a", "ok", "2 warning", False),
        ("b", "error", "not XML", True),
    ]
    text = pathlib.Path(write_summary_html(str(tmp_path / "summary.html"), rows)).read_text()
    assert text.count("data:image/png;base64,") == 1 and "no picture" in text


def test_render_after_mujoco_chose_another_backend(tmp_path: pathlib.Path, gl: str) -> None:
    """A process whose MuJoCo was imported without MUJOCO_GL (GLFW, which needs a display) still
    renders: in a child process with a headless backend."""
    import os
    import subprocess
    import sys

    out = tmp_path / "child.png"
    code = (
        "import mujoco\n"
        "from robodesc.view.render import render_png\n"
        f"print(render_png({GRIPPER!r}, {str(out)!r}, size=(64, 48)).backend)\n"
    )
    env = {k: v for k, v in os.environ.items() if k not in ("MUJOCO_GL", "PYOPENGL_PLATFORM")}
    done = subprocess.run([sys.executable, "-c", code], env=env, capture_output=True, text=True, check=True)
    assert done.stdout.strip() in ("egl", "osmesa")
    assert decode_png(out.read_bytes()).shape == (48, 64, 3)
