"""Options, presets, the pipeline, and copy_meshes."""

from __future__ import annotations

import os
from pathlib import Path

import pytest
import trimesh

from robodesc.ir import ConfigError, FixedFrame, Material, Mesh, VerificationError, Visual
from robodesc.passes import PASSES, PRESET_OPTIONS, PRESETS, PassOptions, preset_options, run_passes
from robodesc.passes.context import PassContext
from robodesc.passes.copy_meshes import copy_meshes
from robodesc.passes.options import RepairPolicy, merge_options, options_from_mapping, parse_rename
from robodesc.passes.pipeline import enabled_passes
from tests.passes.pass_helpers import chain, codes


def test_pipeline_reads_like_a_table_of_contents() -> None:
    assert [p.name for p in PASSES] == [
        "rename",
        "sanitize_names",
        "unique_materials",
        "geometric_inertia",
        "massless",
        "repair_inertia",
        "merge_fixed",
        "strip_tags",
        "armature",
        "default_armature",
        "explicit_damping",
        "isaac_limits",
        "flat_colliders",
        "keep_bodies",
        "zero_pose",
    ]


@pytest.mark.parametrize("name", sorted(PRESETS))
def test_presets_list_the_passes_their_options_enable(name: str) -> None:
    assert enabled_passes(preset_options(name)) == PRESETS[name]


def test_preset_names() -> None:
    assert (
        set(PRESETS)
        == set(PRESET_OPTIONS)
        == {"isaac_sim", "ros2", "gazebo", "mujoco", "mjcf", "quad_sdk", "gazebo_parity"}
    )


def test_unknown_option_and_preset_name_the_closest() -> None:
    with pytest.raises(ConfigError, match="did you mean 'merge_fixed'"):
        options_from_mapping({"merge_fixd": True})
    with pytest.raises(ConfigError, match="did you mean 'repair_inertia'"):
        options_from_mapping({"repair-inertai": "geometry"})
    with pytest.raises(ConfigError, match="did you mean 'quad_sdk'"):
        preset_options("quadsdk")
    with pytest.raises(ConfigError, match="did you mean 'quad_sdk'"):
        options_from_mapping({"repair_inertia": "quad-sdk"})
    with pytest.raises(ConfigError, match="did you mean 'isaac_sim'"):
        run_passes(chain("a", "b"), preset="isaac")


def test_option_spellings() -> None:
    opts = options_from_mapping({"merge-fixed": True, "strip": "all", "repair_inertia": "geometry"})
    assert opts.merge_fixed and opts.repair_inertia is RepairPolicy.GEOMETRY and len(opts.strip) == 6
    assert parse_rename("link:re:l(\\d)=link_\\1").kind == "link"
    with pytest.raises(ConfigError):
        parse_rename("no-equals-sign")


def test_preset_plus_explicit_options() -> None:
    merged = merge_options(preset_options("quad_sdk"), PassOptions(merge_fixed=True))
    assert merged.merge_fixed and merged.repair_inertia is RepairPolicy.QUAD_SDK
    robot = chain("a", "b", "c", joint_names=["0", "1"])
    findings = run_passes(robot, preset="quad_sdk", options=PassOptions(sanitize_names=True), verify_each=True)
    assert [j.name for j in robot.joints] == ["j_hip_0", "j_knee_0"]
    assert {f.stage for f in findings} >= {"pass:rename"}


def test_verify_each_names_the_pass() -> None:
    robot = chain("a", "b", "c")
    robot.fixed_frames = [FixedFrame("a", parent="b")]  # shadows a link: every pass leaves it broken
    with pytest.raises(VerificationError, match="after pass zero_pose: a fixed frame may not share"):
        run_passes(robot, options=PassOptions(), verify_each=True)


def test_copy_meshes_collision_free_names_and_conversion(tmp_path: Path) -> None:
    src1, src2 = tmp_path / "one", tmp_path / "two"
    src1.mkdir()
    src2.mkdir()
    box = trimesh.creation.box()
    box.export(src1 / "part.stl")
    box.export(src2 / "part.stl")
    box.export(src2 / "shell.dae")
    (src1 / "skin.png").write_bytes(b"\x89PNG fake")
    robot = chain("a", "b", "c")
    robot.source_file = str(tmp_path / "robot.urdf")  # files are copied only from the input's folder (and packages)
    robot.links[0].visuals = [
        Visual(Mesh("package://x/part.stl", path=str(src1 / "part.stl"), package=("x", "part.stl")))
    ]
    robot.links[1].visuals = [
        Visual(Mesh("two/part.stl", path=str(src2 / "part.stl"))),
        Visual(Mesh("one/part.stl", path=str(src1 / "part.stl"))),  # same file: copied once
    ]
    robot.links[2].visuals = [
        Visual(
            Mesh("shell.dae", path=str(src2 / "shell.dae")),
            material=Material("m", texture="skin.png", texture_path=str(src1 / "skin.png")),
        )
    ]
    out = tmp_path / "out"
    ctx = PassContext(PassOptions(copy_meshes=True, convert_meshes={".dae": ".obj"}))
    copy_meshes(robot, str(out), ctx)
    uris = [v.geometry.uri for link in robot.links for v in link.visuals]  # type: ignore[union-attr]
    assert uris == ["meshes/part.stl", "meshes/part_1.stl", "meshes/part.stl", "meshes/shell.obj"]
    assert sorted(os.listdir(out / "meshes")) == ["part.stl", "part_1.stl", "shell.obj", "skin.png"]
    first = robot.links[0].visuals[0].geometry
    assert isinstance(first, Mesh) and first.package is None and first.path == str(out / "meshes" / "part.stl")
    assert robot.links[2].visuals[0].material is not None
    assert robot.links[2].visuals[0].material.texture == "meshes/skin.png"
    converted = trimesh.load(out / "meshes" / "shell.obj", force="mesh")
    assert converted.volume == pytest.approx(1.0, rel=1e-6)
    assert "mesh-converted" in codes(ctx) and "meshes-copied" in codes(ctx)


def test_copy_meshes_takes_meshes_of_a_given_package_reached_through_find(tmp_path: Path) -> None:
    """moveit_resources' Panda reaches its meshes through xacro's $(find pkg): absolute paths outside
    the input's folder, under a package given with --package. They are the robot's own: copied."""
    import shutil

    import robodesc
    from tests.conftest import EXAMPLES

    pkg = tmp_path / "elsewhere" / "my_description"
    (pkg / "meshes").mkdir(parents=True)
    shutil.copy(EXAMPLES / "urdf" / "meshes" / "finger.stl", pkg / "meshes" / "finger.stl")
    src = tmp_path / "config" / "robot.urdf.xacro"
    src.parent.mkdir()
    src.write_text(
        '<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro"><link name="a"><visual><geometry>'
        '<mesh filename="$(find my_description)/meshes/finger.stl"/></geometry></visual></link></robot>'
    )
    out = tmp_path / "out" / "robot.urdf"
    result = robodesc.compile_to_urdf(str(src), str(out), package_paths={"my_description": str(pkg)}, copy_meshes=True)
    assert "mesh-not-copied" not in [f.code for f in result.findings]
    assert (tmp_path / "out" / "meshes" / "finger.stl").read_bytes() == (pkg / "meshes" / "finger.stl").read_bytes()
    assert 'filename="meshes/finger.stl"' in out.read_text()
