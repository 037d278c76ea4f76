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


def test_view_page_draws_a_height_image_as_its_grid(tmp_path: pathlib.Path) -> None:
    """A height image has no mesh: the page draws its heightfield grid, at the image's heights."""
    from PIL import Image

    from robodesc.view.world import world_page_data

    # A 16-bit ramp: black at -x, white at +x, 2 m by 1 m, white 0.5 m high.
    ramp = np.tile(np.linspace(0, 65535, 21).round().astype(np.uint16), (11, 1))
    image = tmp_path / "ramp.png"
    Image.fromarray(ramp).save(image)
    options = build_options({"terrain": str(image), "terrain_size": (2.0, 1.0, 0.5)})
    loaded = load_for_view(str(QUADRUPED), options)
    assert loaded.world is not None
    data, meshes = world_page_data(loaded.world, 0)
    (ground,) = data["ground"]
    assert ground["kind"] == "mesh" and len(meshes) == 1
    points = np.frombuffer(meshes[0].points, dtype=np.float32).reshape(-1, 3) + np.array(ground["xyz"])
    assert len(meshes[0].face_vertex_indices) == 3 * 2 * 20 * 10  # two triangles per cell
    assert points[:, 2] == pytest.approx((points[:, 0] + 1.0) / 2.0 * 0.5, abs=1e-4)


def test_render_model_holds_every_copy_and_the_terrain() -> None:
    """The picture's MuJoCo model (no GL needed): each copy's shapes at its spawn, the terrain's hfield."""
    from robodesc.view.mjscene import VISUAL_GROUP, WORLD_GROUP, build_model

    one = load_for_view(str(QUADRUPED), build_options({"world": str(STEP)}))
    two = load_for_view(str(QUADRUPED), build_options({"world": str(STEP), "spawn": [(1.0, 0.0), (5.0, 0.0)]}))
    assert one.world is not None and two.world is not None
    single, double = build_model(one.robot, world=one.world), build_model(two.robot, world=two.world)
    assert double.visuals == 2 * single.visuals
    for built in (single, double):
        assert built.model.nhfield == 1 and int((built.model.geom_group == WORLD_GROUP).sum()) == 1
    centres = double.model.geom_pos[double.model.geom_group == VISUAL_GROUP]
    assert centres[:, 0].min() < 2.0 and centres[:, 0].max() > 4.0  # one robot by x = 1 m, one by x = 5 m
