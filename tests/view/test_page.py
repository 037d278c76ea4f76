"""The viewer page without a browser: well-formed, self-contained, every mesh in it, the numbers right."""

from __future__ import annotations

import base64
import gzip
import html.parser
import json
import pathlib
import re
import struct
from typing import Any

import pytest

from robodesc.cli import main
from robodesc.frontends.options import LoadOptions
from robodesc.ir.model import JointType
from robodesc.options import CompileOptions, build_options
from robodesc.view import write_view_html
from robodesc.view.source import load_for_view
from tests.view.cases import GRIPPER, QUADRUPED

ROOT = pathlib.Path(__file__).resolve().parents[2]
VOID = {"meta", "input", "br", "img", "link", "hr", "col", "source", "wbr", "area", "base", "embed", "track"}


class _Balance(html.parser.HTMLParser):
    """Every element closed, in order (html.parser itself accepts anything)."""

    def __init__(self) -> None:
        super().__init__()
        self.stack: list[str] = []
        self.problems: list[str] = []

    def handle_starttag(self, tag: str, attrs: Any) -> None:
        if tag not in VOID:
            self.stack.append(tag)

    def handle_endtag(self, tag: str) -> None:
        if not self.stack or self.stack[-1] != tag:
            self.problems.append(f"</{tag}> closes {self.stack[-1:]} at {self.getpos()}")
        else:
            self.stack.pop()


def page_data(text: str) -> dict[str, Any]:
    match = re.search(r'<script id="robodesc-data" type="application/json">(.*?)</script>', text, re.S)
    assert match, "no scene data in the page"
    data: dict[str, Any] = json.loads(match.group(1))
    return data


def written(tmp_path: pathlib.Path, source: str, **kw: Any) -> tuple[str, dict[str, Any]]:
    out = tmp_path / "robot.html"
    write_view_html(source, str(out), **kw)
    text = out.read_text(encoding="utf-8")
    return text, page_data(text)


def test_page_is_well_formed(tmp_path: pathlib.Path) -> None:
    text, _ = written(tmp_path, GRIPPER)
    assert text.startswith("<!DOCTYPE html>")
    checker = _Balance()
    checker.feed(text)
    checker.close()
    assert not checker.problems and not checker.stack, (checker.problems, checker.stack)


def test_page_fetches_nothing(tmp_path: pathlib.Path) -> None:
    text, _ = written(tmp_path, GRIPPER)
    # No element, stylesheet or script loads anything: not from the network, not from disk.
    assert not re.search(r"""\b(src|href)\s*=\s*["']?(https?:|//|file:)""", text)
    assert not re.search(r"""url\(\s*["']?(https?:|//)""", text)
    assert not re.search(r"""(fetch|importScripts|import)\s*\(\s*["'`](https?:|//)""", text)
    assert "<script src" not in text and "<link " not in text
    # And the browser is told so: a request would be refused (Content-Security-Policy).
    assert "default-src 'none'" in text


def _glb_ok(blob: bytes) -> tuple[int, int]:
    magic, version, length = struct.unpack("<III", blob[:12])
    assert (magic, version, length) == (0x46546C67, 2, len(blob))
    json_len, _ = struct.unpack("<II", blob[12:20])
    doc = json.loads(blob[20 : 20 + json_len])
    accessors = doc["accessors"]
    return accessors[0]["count"], accessors[1]["count"]


def test_every_mesh_is_embedded(tmp_path: pathlib.Path) -> None:
    _, data = written(tmp_path, GRIPPER)
    used = {s["mesh"] for link in data["links"] for s in link["visuals"] + link["collisions"] if s["kind"] == "mesh"}
    assert used == set(range(len(data["meshes"]))) and used
    assert data["mesh_encoding"] == "glb+gzip+base64"
    for blob in data["meshes"]:
        points, indices = _glb_ok(gzip.decompress(base64.b64decode(blob)))
        assert points > 0 and indices % 3 == 0


def test_glb_is_read_back_by_trimesh(tmp_path: pathlib.Path) -> None:
    import io

    import trimesh

    _, data = written(tmp_path, GRIPPER)
    glb = gzip.decompress(base64.b64decode(data["meshes"][0]))
    scene: Any = trimesh.load(io.BytesIO(glb), file_type="glb")
    mesh = next(iter(scene.geometry.values()))
    points, indices = _glb_ok(glb)
    assert len(mesh.faces) * 3 == indices and len(mesh.vertices) <= points


def test_sliders_are_within_the_limits(tmp_path: pathlib.Path) -> None:
    from robodesc import load

    robot = load(GRIPPER)
    _, data = written(tmp_path, GRIPPER)
    joints = {j["name"]: j for j in data["joints"]}
    for joint in robot.joints:
        page = joints[joint.name]
        if joint.type is JointType.FIXED:
            assert page["range"] is None
            continue
        lower, upper = page["range"]
        assert lower <= page["home"] <= upper
        if joint.type is not JointType.CONTINUOUS and joint.limit is not None:
            assert (lower, upper) == (joint.limit.lower, joint.limit.upper)
        if joint.mimic is not None:
            assert page["mimic"]["joint"] == joint.mimic.joint


def test_findings_are_listed_and_linked(tmp_path: pathlib.Path, defects_urdf: str) -> None:
    _, data = written(tmp_path, defects_urdf)
    by_code = {f["code"]: f for f in data["findings"]}
    assert by_code["bad-inertia"]["link"] == "forearm", data["findings"]
    assert any(f["link"] == "hand" and "does_not_exist" in f["message"] for f in data["findings"])
    hand = next(link for link in data["links"] if link["name"] == "hand")
    assert hand["visuals"][0]["kind"] == "missing"


def test_repairs_before_and_after(tmp_path: pathlib.Path, defects_urdf: str) -> None:
    opts = build_options({"invalid_inertia": "repair", "missing_mesh": "drop"})
    opts.passes = {"merge_fixed": True}
    _, data = written(tmp_path, defects_urdf, options=opts, target="urdf")
    kinds = {(r["kind"], r["link"]) for r in data["repairs"]}
    assert ("inertia", "forearm") in kinds
    assert ("dropped", "hand") in kinds
    assert ("merged", "hand") in kinds
    forearm = next(r for r in data["repairs"] if r["kind"] == "inertia" and r["link"] == "forearm")
    assert forearm["before_box"]["box"] is None  # no box has those moments
    assert forearm["after_box"]["box"] is not None
    assert "tool" not in {link["name"] for link in data["links"]}


def test_target_shows_the_compiled_robot(tmp_path: pathlib.Path) -> None:
    _, data = written(tmp_path, QUADRUPED, target="isaac")
    assert data["target"] == "isaac"
    assert data["repairs"] and all(r["kind"] in ("inertia", "dropped", "merged") for r in data["repairs"])


def test_equivalent_inertia_box() -> None:
    from robodesc.ir.geometry import Inertia, Inertial
    from robodesc.view.scene import inertia_box

    # A 2 x 1 x 0.5 m box of 3 kg has these moments; the equivalent box is that box.
    m, a, b, c = 3.0, 2.0, 1.0, 0.5
    inertia = Inertia(ixx=m / 12 * (b * b + c * c), iyy=m / 12 * (a * a + c * c), izz=m / 12 * (a * a + b * b))
    box = inertia_box(Inertial(mass=m, inertia=inertia))
    assert box is not None and box["box"] is not None
    assert sorted(box["box"]) == pytest.approx(sorted([a, b, c]))


@pytest.mark.parametrize("source", ["examples/arm6_gripper.yaml", "examples/four_bar.py", "examples/mobile_base.yaml"])
def test_every_input_kind(tmp_path: pathlib.Path, source: str) -> None:
    root = pathlib.Path(__file__).resolve().parents[2]
    _, data = written(tmp_path, str(root / source))
    assert data["links"] and data["roots"]


def test_loads_xacro_with_packages() -> None:
    root = pathlib.Path(__file__).resolve().parents[2]
    opts = CompileOptions(load=LoadOptions(package_paths={"robodesc_examples": str(root / "examples/urdf")}))
    loaded = load_for_view(str(root / "examples/urdf/pendulum.urdf.xacro"), opts)
    assert loaded.robot.links


def test_cli_view_and_inspect_html(tmp_path: pathlib.Path, capsys: pytest.CaptureFixture[str]) -> None:
    out = tmp_path / "page.html"
    assert main(["view", GRIPPER, "-o", str(out)]) == 0
    assert "links" in capsys.readouterr().err and out.stat().st_size > 100_000
    also = tmp_path / "inspect.html"
    assert main(["inspect", GRIPPER, "--html", str(also)]) == 0
    assert page_data(also.read_text())["robot"] == "gripper_arm"
    assert main(["view", str(tmp_path / "missing.urdf"), "-o", str(out)]) == 2
    assert main(["view", GRIPPER, "-o", GRIPPER]) == 2  # never over its input


def test_batch_writes_summary_html(tmp_path: pathlib.Path) -> None:
    """Every batch writes summary.html beside summary.md: a row per robot (thumbnails with --thumbnails)."""
    robots = tmp_path / "robots"
    robots.mkdir()
    (robots / "arm.urdf").write_text(
        (ROOT / "examples/urdf/gripper_arm.urdf")
        .read_text()
        .replace("package://robodesc_examples/", str(ROOT / "examples/urdf") + "/")
    )
    out = tmp_path / "out"
    assert main(["batch", str(robots), "-o", str(out), "-q", "--no-validate"]) == 0
    page = (out / "summary.html").read_text()
    assert "<table" in page and ">arm<" in page and "ok" in page


def test_folder_targets_get_a_preview(tmp_path: pathlib.Path) -> None:
    from robodesc.view.render import backend_candidates

    if not backend_candidates():
        pytest.skip("no offscreen OpenGL (EGL or OSMesa): the compile says so and writes no preview")
    out = tmp_path / "isaac"
    assert main(["compile", str(ROOT / "examples/quadruped.yaml"), "--isaac-sim", "-o", str(out), "-q"]) == 0
    assert (out / "preview.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert (
        main(["compile", str(ROOT / "examples/quadruped.yaml"), "--isaac-sim", "-o", str(out), "-q", "--no-preview"])
        == 0
    )
    assert not (out / "preview.png").exists()
