"""Default gains that hold (issue 35, docs/mjcf.md "Defaults and why"): welded arms from
example-robot-data, compiled with default flags, hold their home pose in MuJoCo within 0.01 rad for
5 s, and random control within ctrlrange drives no joint faster than twice its URDF velocity limit."""

from __future__ import annotations

import xml.etree.ElementTree as ET
from pathlib import Path

import mujoco
import numpy as np
import pytest

from robodesc.api import compile_to_mjcf
from robodesc.validation.corpora import example_robot_data_root

ERD = example_robot_data_root()
ARMS = {
    "panda": "panda_description/urdf/panda.urdf",
    "ur5": "ur_description/urdf/ur5_robot.urdf",
    "z1": "z1_description/urdf/z1.urdf",
}


def _compile(name: str, tmp_path: Path) -> tuple[mujoco.MjModel, Path]:
    if ERD is None:
        pytest.skip("example-robot-data is not installed (the test extra)")
    source = Path(ERD) / "robots" / ARMS[name]
    compile_to_mjcf(str(source), str(tmp_path / "robot.xml"), package_paths={"example-robot-data": ERD})
    return mujoco.MjModel.from_xml_path(str(tmp_path / "scene.xml")), source


def _home(model: mujoco.MjModel, data: mujoco.MjData) -> None:
    mujoco.mj_resetDataKeyframe(model, data, mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_KEY, "home"))


@pytest.mark.parametrize("name", sorted(ARMS))
def test_welded_arm_holds_home_within_a_hundredth_of_a_radian(name: str, tmp_path: Path) -> None:
    model, _ = _compile(name, tmp_path)
    data = mujoco.MjData(model)
    _home(model, data)
    q0 = data.qpos.copy()
    worst = 0.0
    touches = 0
    for _ in range(int(5.0 / model.opt.timestep)):
        mujoco.mj_step(model, data)
        worst = max(worst, float(np.abs(data.qpos - q0).max()))
        touches = max(touches, int(data.ncon))
    # Before issue 35: 0.018 (panda), 0.012 (ur5), 0.050 (z1); menagerie's arms sag 0.004-0.008.
    assert worst < 0.01
    # The floor lies far enough under the lowest collider for the sag: with a 1 mm gap the UR5's wrist
    # came to rest on it (4 contacts, 44 % of its steps/s).
    assert touches == 0
    assert (model.dof_armature > 0).sum() >= 6  # the estimated rotor inertia reached the file


@pytest.mark.parametrize("name", ["panda", "z1"])
def test_random_control_stays_near_the_velocity_limits(name: str, tmp_path: Path) -> None:
    model, source = _compile(name, tmp_path)
    limits = {
        j.get("name"): float(j.find("limit").get("velocity", "0"))  # type: ignore[union-attr]
        for j in ET.parse(source).getroot().iter("joint")
        if j.find("limit") is not None and j.get("type") in ("revolute", "prismatic")
    }
    data = mujoco.MjData(model)
    _home(model, data)
    rng = np.random.default_rng(0)
    lo, hi = model.actuator_ctrlrange[:, 0], model.actuator_ctrlrange[:, 1]
    ratio = 0.0
    for i in range(int(2.0 / model.opt.timestep)):
        if i % 50 == 0:
            data.ctrl[:] = rng.uniform(lo, hi)
        mujoco.mj_step(model, data)
        for j in range(model.njnt):
            limit = limits.get(mujoco.mj_id2name(model, mujoco.mjtObj.mjOBJ_JOINT, j))
            if limit:
                ratio = max(ratio, abs(float(data.qvel[model.jnt_dofadr[j]])) / limit)
    assert np.isfinite(data.qpos).all()
    # Before issue 35: panda_joint7 at x19.7 its limit, z1's joint6 at x9.2.
    assert ratio < 2.5


def test_fixed_links_are_fused_and_survive_as_sites(tmp_path: Path) -> None:
    """Fixed links fused by default (menagerie's models have no welded frame bodies); the frame is a
    site at the same place; --no-merge-fixed keeps the body."""
    urdf = """<robot name="f">
      <link name="base"><inertial><mass value="1"/><inertia ixx="0.01" iyy="0.01" izz="0.01" ixy="0" ixz="0" iyz="0"/></inertial></link>
      <link name="arm"><inertial><origin xyz="0 0 0.1"/><mass value="0.5"/><inertia ixx="0.01" iyy="0.01" izz="0.01" ixy="0" ixz="0" iyz="0"/></inertial></link>
      <link name="tool"/>
      <joint name="j" type="revolute"><parent link="base"/><child link="arm"/><axis xyz="0 1 0"/>
        <limit lower="-1" upper="1" effort="20" velocity="2"/></joint>
      <joint name="mount" type="fixed"><parent link="arm"/><child link="tool"/><origin xyz="0 0 0.3"/></joint>
    </robot>"""
    compile_to_mjcf(urdf, str(tmp_path / "a" / "robot.xml"))
    fused = mujoco.MjModel.from_xml_path(str(tmp_path / "a" / "robot.xml"))
    assert mujoco.mj_name2id(fused, mujoco.mjtObj.mjOBJ_BODY, "tool") == -1
    site = mujoco.mj_name2id(fused, mujoco.mjtObj.mjOBJ_SITE, "tool")
    assert site >= 0
    np.testing.assert_allclose(fused.site_pos[site], [0.0, 0.0, 0.3], atol=1e-12)
    compile_to_mjcf(urdf, str(tmp_path / "b" / "robot.xml"), merge_fixed=False)
    kept = mujoco.MjModel.from_xml_path(str(tmp_path / "b" / "robot.xml"))
    assert mujoco.mj_name2id(kept, mujoco.mjtObj.mjOBJ_BODY, "tool") >= 0
    assert fused.nbody == kept.nbody - 1


def test_legged_contact_defaults_on_a_floating_quadruped(tmp_path: Path) -> None:
    """A quadruped gets menagerie's legged contact (elliptic cone, impratio 100, feet with condim 6 and
    priority 1); an arm keeps MuJoCo's own."""
    if ERD is None:
        pytest.skip("example-robot-data is not installed (the test extra)")
    source = Path(ERD) / "robots" / "go1_description/urdf/go1.urdf"
    compile_to_mjcf(str(source), str(tmp_path / "robot.xml"), package_paths={"example-robot-data": ERD})
    model = mujoco.MjModel.from_xml_path(str(tmp_path / "scene.xml"))
    assert model.opt.cone == mujoco.mjtCone.mjCONE_ELLIPTIC and model.opt.impratio == pytest.approx(100.0)
    feet = [g for g in range(model.ngeom) if model.geom_condim[g] == 6]
    assert len(feet) >= 4 and all(model.geom_priority[g] == 1 for g in feet)
    assert all(model.geom_friction[g][0] == pytest.approx(0.8) for g in feet)
    arm, _ = _compile("z1", tmp_path / "z1")
    assert arm.opt.cone == mujoco.mjtCone.mjCONE_PYRAMIDAL and arm.opt.impratio == pytest.approx(1.0)


def test_welded_arm_starts_from_its_named_pose(tmp_path: Path) -> None:
    """An arm's home is the pose its SRDF names (panda.srdf's 'default'), as a leg robot's is; before,
    zeros clamped into the ranges (panda_joint4's range excludes 0)."""
    model, _ = _compile("panda", tmp_path)
    home = model.key_qpos[0]
    joint4 = model.jnt_qposadr[mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_JOINT, "panda_joint4")]
    joint6 = model.jnt_qposadr[mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_JOINT, "panda_joint6")]
    assert home[joint4] == pytest.approx(-2.35619) and home[joint6] == pytest.approx(1.5707)


def test_the_folder_is_self_contained(tmp_path: Path) -> None:
    """Every mesh under OUT/meshes with a relative path, named by content (one file per distinct
    content), so the folder loads after it is moved; --mesh-paths absolute references them in place."""
    import shutil

    from robodesc.emit.common.paths import PathMode
    from tests.conftest import EXAMPLES

    compile_to_mjcf(str(EXAMPLES / "urdf" / "gripper_arm.urdf"), str(tmp_path / "a" / "robot.xml"))
    files = [m.get("file", "") for m in ET.parse(tmp_path / "a" / "robot.xml").getroot().iter("mesh")]
    assert files and all(f.startswith("meshes/") for f in files)
    assert len(list((tmp_path / "a" / "meshes").iterdir())) == len(set(files))
    shutil.move(str(tmp_path / "a"), str(tmp_path / "moved"))
    assert mujoco.MjModel.from_xml_path(str(tmp_path / "moved" / "scene.xml")).nmesh == len(files)
    compile_to_mjcf(
        str(EXAMPLES / "urdf" / "gripper_arm.urdf"), str(tmp_path / "b" / "robot.xml"), mesh_paths=PathMode.ABSOLUTE
    )
    absolute = [m.get("file", "") for m in ET.parse(tmp_path / "b" / "robot.xml").getroot().iter("mesh")]
    assert all(Path(f).is_absolute() for f in absolute) and not (tmp_path / "b" / "meshes").exists()
