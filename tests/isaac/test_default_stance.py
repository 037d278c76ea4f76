"""The Isaac folder's defaults: a pose a floating robot stands in, the spawn height, gains derived
from inertia and effort, and inertia Newton accepts (issue 29; docs/isaac.md "Defaults that stand")."""

from __future__ import annotations

import math
import runpy
import shutil
from pathlib import Path
from typing import Any

import pytest
from pxr import Usd, UsdPhysics

import robodesc
from robodesc.emit.common.gains import HOLD_ERROR, derived_gains
from robodesc.emit.common.stance import choose_stance, legged_pose, limits
from robodesc.ir.geometry import Inertia
from robodesc.ir.model import Robot
from robodesc.ir.principal import below_engine_floor, principal_moments, tensor_rows
from robodesc.ir.rigid import link_frames
from robodesc.passes.pipeline import run_passes
from tests.conftest import EXAMPLES, GO2_XACRO, SPIRIT_XACRO


def _robot(source: Path, preset: str = "isaac_sim") -> Robot:
    robot = robodesc.load(str(source))
    run_passes(robot, preset=preset)
    return robot


def _module(folder: Path) -> dict[str, Any]:
    path = next(folder.glob("*_isaaclab.py"))
    data: dict[str, Any] = runpy.run_path(str(path))["ROBOT"]
    return data


@pytest.mark.parametrize("source", [SPIRIT_XACRO, GO2_XACRO], ids=["spirit", "go2"])
def test_heuristic_puts_each_foot_under_its_hip_within_limits(source: Path) -> None:
    robot = _robot(source)
    found = legged_pose(robot)
    assert found is not None
    q, legs = found
    assert len(legs) == 4
    frames = link_frames(robot, q)
    joints = robot.joint_map()
    for leg in legs:
        bent = [n for n in leg.joints if q.get(n, 0.0) != 0.0]
        assert len(bent) == 2, leg  # hip pitch and knee; the abduction joint stays at 0
        for name in leg.joints:
            lo, hi = limits(joints[name])
            assert lo - 1e-9 <= q[name] <= hi + 1e-9
        hip = joints[bent[0]]
        hip_x = frames[hip.parent].translation[0] + (hip.origin.xyz[0] if hip.origin else 0.0)
        foot = frames[leg.foot].translation
        assert abs(foot[0] - hip_x) < 0.02, (leg.foot, foot[0], hip_x)
        assert foot[2] < -0.15  # well below the body: a crouch, not a fold


def test_srdf_group_state_wins_over_the_heuristic(tmp_path: Path) -> None:
    src = tmp_path / "pkg" / "urdf"
    src.mkdir(parents=True)
    shutil.copy(EXAMPLES / "urdf" / "gripper_arm.urdf", src / "arm.urdf")
    robot = robodesc.load(str(src / "arm.urdf"))
    name = robot.actuated_joints()[0].name
    (tmp_path / "pkg" / "srdf").mkdir()
    (tmp_path / "pkg" / "srdf" / "arm.srdf").write_text(
        f'<robot name="other"><group_state name="home" group="all"><joint name="{name}" value="0.25"/>'
        '<joint name="not_a_joint" value="1"/></group_state>'
        f'<group_state name="standing" group="all"><joint name="{name}" value="0.5"/></group_state></robot>'
    )
    stance = choose_stance(robot, None)
    assert stance.source == "SRDF group_state 'standing' (arm.srdf)"
    assert stance.positions[name] == pytest.approx(min(0.5, limits(robot.joint(name))[1]))


def test_ros2_control_initial_value_survives_strip_tags() -> None:
    robot = robodesc.load(str(EXAMPLES / "urdf" / "gripper_arm.urdf"))
    from robodesc.ir.model import ControlInterface, ControlJoint, Ros2Control

    name = robot.actuated_joints()[0].name
    robot.ros2_controls = [
        Ros2Control(
            "hw", joints=[ControlJoint(name, state_interfaces=[ControlInterface("position", {"initial_value": "0.3"})])]
        )
    ]
    run_passes(robot, preset="isaac_sim")
    assert robot.ros2_controls == []
    stance = choose_stance(robot, None)
    assert stance.source == "ros2_control initial_value"
    assert stance.positions[name] == pytest.approx(0.3)


def test_floating_robot_without_legs_starts_at_zero_with_a_warning(tmp_path: Path) -> None:
    result = robodesc.compile_for_isaac_sim(str(EXAMPLES / "urdf" / "gripper_arm.urdf"), tmp_path / "f", fix_base=False)
    codes = [f.code for f in result.findings]
    assert "default-pose-zeros" in codes
    assert "default-gains" in codes


def test_spirit_folder_stands_by_default(tmp_path: Path) -> None:
    """The module and the USD carry the same pose; the spawn height clears the ground; gains are
    per joint, in the USD per degree."""
    result = robodesc.compile_for_isaac_sim(str(SPIRIT_XACRO), tmp_path / "spirit", fix_base=False)
    data = _module(tmp_path / "spirit")
    pose = data["init_state"]["joint_pos"]
    assert sum(1 for v in pose.values() if v != 0.0) == 8
    assert 0.3 < data["init_state"]["pos"][2] < 0.4
    stage = Usd.Stage.Open(str(tmp_path / "spirit" / "spirit.usda"))
    seen = 0
    for prim in stage.Traverse():
        if not prim.IsA(UsdPhysics.RevoluteJoint):
            continue
        name = prim.GetName()
        state = prim.GetAttribute("state:angular:physics:position").Get()
        target = prim.GetAttribute("drive:angular:physics:targetPosition").Get()
        assert state == pytest.approx(math.degrees(pose[name]), abs=1e-4)
        assert target == pytest.approx(state)
        kp = prim.GetAttribute("drive:angular:physics:stiffness").Get()
        group = next(
            g for g in data["actuators"].values() if any(e.replace("\\", "") == name for e in g["joint_names_expr"])
        )
        assert kp == pytest.approx(group["stiffness"] * math.pi / 180, rel=1e-6)
        seen += 1
    assert seen == 12
    messages = " ".join(f.message for f in result.findings if f.code in ("default-pose", "default-gains"))
    assert "legged heuristic" in messages and "kp = I_eff" in messages


def test_derived_gains_follow_the_formula() -> None:
    robot = _robot(SPIRIT_XACRO)
    stance = choose_stance(robot, None)
    gains = derived_gains(robot, stance, floating=True)
    omega = 2 * math.pi * 4.0
    for name, g in gains.items():
        effort = robot.joint(name).limit.effort  # type: ignore[union-attr]
        # I_eff ω² under the effort cap, and at least the gravity floor (bounded by the effort) and the
        # dead-actuator floor (effort at 1 rad, bounded by a 20 Hz loop).
        floor = max(min(g.gravity_torque, effort) / HOLD_ERROR, min(effort / 1.0, g.inertia * (2 * math.pi * 20) ** 2))
        assert g.stiffness == pytest.approx(max(min(g.inertia * omega**2, effort / 0.2), floor))
        # Critical damping, or more: a full-range step driven at no more than twice the velocity limit.
        limit = robot.joint(name).limit
        speed = g.stiffness * (limit.upper - limit.lower) / (2 * limit.velocity)  # type: ignore[union-attr,operator]
        assert g.damping == pytest.approx(max(2 * math.sqrt(g.stiffness * g.inertia), speed))
        # Capped when the inertia's stiffness exceeds the effort's, unless the gravity floor set it.
        assert g.capped == (g.inertia * omega**2 > effort / 0.2 and not g.floor)
        assert g.gravity_torque > 0 and not g.weak


def test_explicit_gains_and_pose_win(tmp_path: Path) -> None:
    robodesc.compile_for_isaac_sim(
        str(SPIRIT_XACRO),
        tmp_path / "s",
        fix_base=False,
        stiffness=30.0,
        damping=2.0,
        init_joint_pos={".*": 0.1},
        init_pos=(0.0, 0.0, 0.5),
    )
    data = _module(tmp_path / "s")
    assert {(g["stiffness"], g["damping"]) for g in data["actuators"].values()} == {(30.0, 2.0)}
    assert data["init_state"]["pos"] == (0.0, 0.0, 0.5)
    assert set(data["init_state"]["joint_pos"].values()) <= {0.1}


def test_usd_target_derives_gains_and_the_old_constants_stay_an_option(tmp_path: Path) -> None:
    """-t usd derives its gains per joint since issue 38 (100 / 1 sagged ur10 by 1.1 rad);
    ``--stiffness 100 --damping 1`` still writes the old constants (per degree in the file)."""

    def gains(**options: float) -> list[float]:
        out = tmp_path / f"arm{len(options)}.usda"
        robodesc.compile_to_usd(str(EXAMPLES / "urdf" / "gripper_arm.urdf"), out, **options)
        stage = Usd.Stage.Open(str(out))
        return [
            p.GetAttribute("drive:angular:physics:stiffness").Get()
            for p in stage.Traverse()
            if p.IsA(UsdPhysics.RevoluteJoint)
        ]

    derived = gains()
    assert derived and len(set(derived)) > 1  # per joint, from each joint's load
    constant = gains(stiffness=100.0, damping=1.0)
    assert constant and all(k == pytest.approx(100 * math.pi / 180) for k in constant)


def test_tensor_below_newtons_floor_is_reported_and_repaired() -> None:
    tiny = Inertia(ixx=1.7e-13, iyy=1.7e-13, izz=1.7e-13)
    assert below_engine_floor(tiny) is not None
    assert below_engine_floor(Inertia(ixx=1e-6, iyy=1e-6, izz=1e-6)) is None
    from robodesc.ir.geometry import Inertial
    from robodesc.ir.model import Link, Robot
    from robodesc.ir.verify import verify

    robot = Robot("r", links=[Link("base", inertial=Inertial(mass=1e-6, inertia=tiny))])
    assert "tiny-inertia" in [f.code for f in verify(robot)]
    findings = run_passes(robot, preset="isaac_sim")
    assert "inertia-repaired" in [f.code for f in findings]
    fixed = robot.links[0].inertial.inertia  # type: ignore[union-attr]
    assert fixed is not None and below_engine_floor(fixed) is None
    assert min(principal_moments(tensor_rows(fixed))) == pytest.approx(2e-10, rel=1e-3)
