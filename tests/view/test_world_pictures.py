"""``view`` and ``render`` with a world (docs/worlds.md, "Pictures"): the robot drawn standing on the
terrain at its spawn. The page's own drawing is checked in Chromium (tests/view/test_browser.py,
the browser tier)."""

from __future__ import annotations

import pathlib

import numpy as np
import pytest

from robodesc.cli import main
from robodesc.options import build_options
from robodesc.view.page import scene_data
from robodesc.view.png import decode_png
from robodesc.view.source import load_for_view
from tests.conftest import EXAMPLES, WORLDS

QUADRUPED = EXAMPLES / "quadruped.yaml"
STEP = WORLDS / "step_20cm" / "step_20cm.world"


def test_render_draws_the_terrain_under_the_robot(tmp_path: pathlib.Path, gl: str) -> None:
    images = {}
    for name, extra in (("alone", []), ("world", ["--world", str(STEP), "--spawn", "1,0"])):
        out = tmp_path / f"{name}.png"
        assert main(["render", str(QUADRUPED), "-o", str(out), "--size", "320x240", *extra]) == 0
        images[name] = decode_png(out.read_bytes()).astype(float)
    alone, world = images["alone"], images["world"]
    # The camera frames the robot alike; below its feet, the sky's gradient against the terrain's checker.
    below = slice(int(0.93 * alone.shape[0]), None)
    assert np.abs(alone[below] - world[below]).mean() > 20
    ground = world[below].reshape(-1, 3).mean(axis=0)
    assert ground[1] > ground[2] + 10  # greenish: the ground's colour, not the sky's grey-blue
    # The robot itself (the middle of the picture) is drawn the same.
    middle = slice(int(0.3 * alone.shape[0]), int(0.5 * alone.shape[0]))
    assert np.abs(alone[middle] - world[middle]).mean() < np.abs(alone[below] - world[below]).mean()


def test_picture_places_the_robot_on_the_terrain() -> None:
    """The robot stands on the step's top (x = 5 m) 0.2 m above where it stands below it (x = 1 m)."""
    roots = {}
    for x in (1.0, 5.0):
        loaded = load_for_view(str(QUADRUPED), build_options({"world": str(STEP), "spawn": (x, 0.0)}))
        assert loaded.world is not None
        roots[x] = loaded.world.roots[0].translation
    assert roots[5.0][2] - roots[1.0][2] == pytest.approx(0.2, abs=1e-6)
    assert (roots[5.0][0], roots[5.0][1]) == (5.0, 0.0)


def test_view_page_carries_the_terrain(tmp_path: pathlib.Path) -> None:
    loaded = load_for_view(str(QUADRUPED), build_options({"world": str(STEP), "spawn": (1.0, 0.0)}))
    data = scene_data(loaded)
    world = data["world"]
    assert world["name"] == "default" and len(world["robots"]) == 1
    assert world["robots"][0]["xyz"][0] == pytest.approx(1.0)
    (ground,) = world["ground"]
    # The terrain's mesh, embedded after the robot's (this robot has none).
    assert ground["kind"] == "mesh" and ground["mesh"] == 0 and len(data["meshes"]) == 1
    assert ground["xyz"] == pytest.approx([-1.975, -2.0, -0.1])
    page = tmp_path / "page.html"
    assert main(["view", str(QUADRUPED), "-o", str(page), "--world", str(STEP)]) == 0
    assert '"ground":[{' in page.read_text()
    plain = tmp_path / "plain.html"
    assert main(["view", str(QUADRUPED), "-o", str(plain)]) == 0
    assert '"world":null' in plain.read_text()
