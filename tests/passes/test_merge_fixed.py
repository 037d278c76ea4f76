"""merge_fixed: combined inertia with rotation, re-parented children, frames kept."""

from __future__ import annotations

import math

import numpy as np
import pytest

from robodesc.frontends.load import load_path
from robodesc.frontends.options import LoadOptions, MissingMesh
from robodesc.ir import (
    Box,
    FixedFrame,
    Inertia,
    Inertial,
    Joint,
    JointType,
    Limit,
    Link,
    Pose,
    Robot,
    Sensor,
    SensorType,
    Visual,
)
from robodesc.ir.transforms import forward_kinematics, pose_matrix
from robodesc.ir.verify import check
from robodesc.passes.merge_fixed import merge_fixed
from tests.conftest import GO2_XACRO
from tests.passes.pass_helpers import codes, ctx


def _robot() -> Robot:
    base = Link("base", inertial=Inertial(mass=1.0, origin=Pose(), inertia=Inertia(0.1, 0.2, 0.3)))
    mount = Link(
        "mount",
        inertial=Inertial(mass=1.0, origin=Pose(), inertia=Inertia(0.01, 0.02, 0.03)),
        visuals=[Visual(Box((0.1, 0.1, 0.1)), origin=Pose(xyz=(0.0, 0.1, 0.0)))],
    )
    arm = Link("arm", inertial=Inertial(mass=1.0, inertia=Inertia(0.1, 0.1, 0.1)))
    joints = [
        Joint("fix", JointType.FIXED, "base", "mount", origin=Pose(xyz=(0.5, 0.0, 0.0), rpy=(0.0, 0.0, math.pi / 2))),
        Joint(
            "rev",
            JointType.REVOLUTE,
            "mount",
            "arm",
            origin=Pose(xyz=(0.1, 0.0, 0.0)),
            axis=(0.0, 0.0, 1.0),
            limit=Limit(-1.0, 1.0, 1.0, 1.0),
        ),
    ]
    robot = Robot("r", links=[base, mount, arm], joints=joints)
    robot.fixed_frames = [FixedFrame("tip", parent="mount", origin=Pose(xyz=(0.0, 0.2, 0.0)))]
    robot.sensors = [Sensor("imu", SensorType.IMU, parent="mount", origin=Pose(xyz=(0.0, 0.0, 0.1)))]
    return robot


def _world(robot: Robot, q: dict[str, float]) -> dict[str, np.ndarray]:
    """World transform of every link and fixed frame."""
    fk = forward_kinematics(robot, q)
    out = dict(fk)
    for f in robot.fixed_frames:
        out[f.name] = fk[f.parent] @ pose_matrix(f.origin)
    for s in robot.sensors:
        out["sensor:" + s.name] = fk[s.parent] @ pose_matrix(s.origin)
    return out


def test_merge_combines_inertia_and_keeps_every_frame() -> None:
    robot = _robot()
    before = _world(robot, {"rev": 0.3})
    c = ctx(merge_fixed=True)
    merge_fixed(robot, c)
    check(robot)
    assert [link.name for link in robot.links] == ["base", "arm"]
    assert [j.name for j in robot.joints] == ["rev"]
    after = _world(robot, {"rev": 0.3})
    for key, m in before.items():
        assert after[key] == pytest.approx(m, abs=1e-12), key  # "mount" survives as a fixed frame
    base = robot.link("base").inertial
    assert base is not None and base.mass == 2.0
    assert base.origin is not None and base.origin.xyz == pytest.approx((0.25, 0.0, 0.0))
    # the mount's tensor turned by 90° about z: diag(0.02, 0.01, 0.03); each body 0.25 m from the COM
    assert base.inertia is not None
    assert base.inertia.as_tuple() == pytest.approx(
        (0.1 + 0.02, 0.2 + 0.01 + 2 * 0.0625, 0.3 + 0.03 + 2 * 0.0625, 0.0, 0.0, 0.0), abs=1e-12
    )
    vis = robot.link("base").visuals[0].origin
    assert vis is not None and vis.xyz == pytest.approx((0.4, 0.0, 0.0))
    assert robot.fixed_frames[-1].name == "mount" and robot.fixed_frames[-1].parent == "base"
    assert codes(c) == ["merged-link", "merged-fixed"]


def test_dont_collapse_is_respected() -> None:
    robot = _robot()
    robot.joints[0].dont_collapse = True
    merge_fixed(robot, ctx(merge_fixed=True))
    assert [link.name for link in robot.links] == ["base", "mount", "arm"]


def test_go2_merge_keeps_mass_and_frames() -> None:
    robot = load_path(str(GO2_XACRO), LoadOptions(missing_mesh=MissingMesh.WARN)).robot
    for j in robot.joints:
        j.dont_collapse = None
    q = {j.name: 0.1 * (i % 5) for i, j in enumerate(robot.joints) if j.type.dof == 1}
    before = _world(robot, q)
    mass = robot.total_mass()
    merge_fixed(robot, ctx(merge_fixed=True))
    check(robot)
    assert all(j.type is not JointType.FIXED for j in robot.joints)
    assert robot.total_mass() == pytest.approx(mass, rel=1e-12)
    after = _world(robot, q)
    for key, m in before.items():
        assert after[key] == pytest.approx(m, abs=1e-9), key
