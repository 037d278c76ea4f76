"""Make the pictures of README.md and docs/view.md, and measure view and render on large robots.

    PYTHONPATH=src python -m tests.view.make_docs_images [--measure]

Screenshots come from headless Chromium (tests/view/cdp.py), renders from ``robodesc render``.
"""

from __future__ import annotations

import os
import pathlib
import resource
import subprocess
import sys
import tempfile
import time

from robodesc.options import build_options
from robodesc.validation.corpora import example_robot_data_root
from robodesc.view import render_png, write_view_html
from tests.view.cases import DEFECTS, EXAMPLES, GRIPPER, QUADRUPED, ROOT
from tests.view.cdp import Browser

IMAGES = ROOT / "docs" / "images"
LARGE = {
    "talos": "talos_data/robots/talos_full_v2.urdf",
    "tiago_dual": "tiago_description/robots/tiago_dual.urdf",
    "centauro": "centauro_description/urdf/centauro.urdf",
}


def _erd() -> tuple[str, dict[str, str]]:
    root = example_robot_data_root()
    assert root is not None, "pip install example-robot-data"
    return root, {"example-robot-data": root}


def screenshots(tmp: pathlib.Path) -> None:
    root, packages = _erd()
    talos = tmp / "talos.html"
    write_view_html(
        os.path.join(root, "robots", LARGE["talos"]), str(talos), options=build_options({"package_paths": packages})
    )
    quad = tmp / "quad.html"
    write_view_html(QUADRUPED, str(quad), target="isaac")
    defects = tmp / "defects.urdf"
    defects.write_text(DEFECTS)
    defects_page = tmp / "defects.html"
    write_view_html(str(defects), str(defects_page))
    with Browser(1280, 760) as b:
        b.open(str(talos))
        b.eval(
            "window.robodesc.setJoint('arm_left_4_joint', -1.2); window.robodesc.setJoint('arm_right_2_joint', -0.6)"
        )
        b.click("#toggle-frames")
        b.eval("window.robodesc.select('arm_left_4_link')")
        b.settle()
        (IMAGES / "view_talos.png").write_bytes(b.screenshot())
        b.open(str(quad))
        b.click("#toggle-inertia")
        b.click("#toggle-com")
        b.eval("document.getElementById('repairs-section').scrollIntoView()")
        b.click("#repair-0")
        b.settle()
        (IMAGES / "view_quadruped_isaac.png").write_bytes(b.screenshot())
        b.open(str(defects_page))
        b.click("#toggle-collision")
        b.click("#toggle-axes")
        findings = b.eval("window.robodesc.data.findings")
        index = next(i for i, f in enumerate(findings) if f["link"] == "forearm")
        b.click(f"#finding-{index}")
        b.settle()
        (IMAGES / "view_findings.png").write_bytes(b.screenshot())
        assert not b.console_errors, b.console_errors


def renders() -> None:
    render_png(GRIPPER, str(IMAGES / "render_gripper_arm.png"), size=(480, 360))
    render_png(QUADRUPED, str(IMAGES / "render_quadruped_grid.png"), size=(640, 480), grid_views=True)
    render_png(
        str(EXAMPLES / "arm6_gripper.yaml"), str(IMAGES / "render_arm6_collision.png"), size=(480, 360), collision=True
    )


def measure() -> None:
    """Wall and CPU time of each command in a fresh process (as a user runs it), and the output's
    size. CPU time is the steadier number on a shared machine."""
    root, _ = _erd()
    env = {**os.environ, "PYTHONPATH": str(ROOT / "src")}
    with tempfile.TemporaryDirectory() as tmp:
        for name, rel in LARGE.items():
            src = os.path.join(root, "robots", rel)
            for cmd, out in (("view", f"{name}.html"), ("render", f"{name}.png")):
                path = os.path.join(tmp, out)
                before = resource.getrusage(resource.RUSAGE_CHILDREN)
                start = time.perf_counter()
                done = subprocess.run(
                    [sys.executable, "-m", "robodesc", cmd, src, "-o", path, "--package", f"example-robot-data={root}"],
                    env=env,
                    capture_output=True,
                    text=True,
                    check=True,
                )
                wall = time.perf_counter() - start
                after = resource.getrusage(resource.RUSAGE_CHILDREN)
                cpu = after.ru_utime - before.ru_utime + after.ru_stime - before.ru_stime
                last = done.stderr.strip().splitlines()[-1]
                size = os.path.getsize(path) / 1e6
                print(f"{name:11} {cmd:6} {wall:5.2f} s wall, {cpu:5.2f} s CPU, {size:6.2f} MB  | {last}")


if __name__ == "__main__":
    IMAGES.mkdir(parents=True, exist_ok=True)
    if "--measure" in sys.argv:
        measure()
    else:
        renders()
        with tempfile.TemporaryDirectory() as work:
            screenshots(pathlib.Path(work))
