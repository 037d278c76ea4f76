"""passes/massless: massless links keep URDF's meaning where a target needs a mass on every body.

The fixture is ANYmal C's shape: the root ``base`` has colliders and no ``<inertial>``; its mass is on
``base_inertia``, fixed to it; massless sensor frames without colliders hang on both; a leg moves.
"""

from __future__ import annotations

import numpy as np
import pytest

from robodesc.ir import Box, Collision, Inertia, Inertial, Joint, JointType, Limit, Link, Pose, Robot
from robodesc.ir.inertia import tensor
from robodesc.ir.principal import inertia_problem
from robodesc.ir.transforms import pose_matrix
from robodesc.ir.verify import check
from robodesc.passes.massless import PLACEHOLDER_MASS, fixed_groups, massless
from robodesc.passes.merge_fixed import combine_inertials
from tests.passes.pass_helpers import codes, ctx

SOURCE_TOTAL = 12.5  # kg: base_inertia 10 + thigh 2 + shank 0.5


def anymal_like() -> Robot:
    box = Box((0.5, 0.2, 0.2))
    links = [
        Link("base", collisions=[Collision(box)]),
        Link(
            "base_inertia",
            inertial=Inertial(mass=10.0, origin=Pose(xyz=(0.02, 0.0, 0.01)), inertia=Inertia(0.1, 0.3, 0.35, ixy=0.01)),
        ),
        Link("imu"),
        Link("camera_parent"),
        Link("camera_optical"),
        Link("thigh", inertial=Inertial(mass=2.0, inertia=Inertia(0.01, 0.01, 0.002)), collisions=[Collision(box)]),
        Link("thigh_fixed", collisions=[Collision(Box((0.05, 0.05, 0.05)))]),
        Link("shank", inertial=Inertial(mass=0.5, inertia=Inertia(0.002, 0.002, 0.0005))),
        Link("foot"),
    ]
    fixed = [
        ("base_to_inertia", "base", "base_inertia", Pose(xyz=(0.0, 0.0, 0.05))),
        ("imu_joint", "base", "imu", Pose(xyz=(0.1, 0.0, 0.1), rpy=(0.0, 0.0, 1.0))),
        ("camera_joint", "base_inertia", "camera_parent", Pose(xyz=(0.3, 0.0, 0.0))),
        ("optical_joint", "camera_parent", "camera_optical", Pose(rpy=(-1.5708, 0.0, -1.5708))),
        ("thigh_fixed_joint", "thigh", "thigh_fixed", Pose(xyz=(0.0, 0.0, -0.1))),
        ("foot_joint", "shank", "foot", Pose(xyz=(0.0, 0.0, -0.3))),
    ]
    joints = [Joint(name, JointType.FIXED, parent, child, origin=origin) for name, parent, child, origin in fixed]
    limit = Limit(lower=-1.0, upper=1.0, effort=40.0, velocity=7.5)
    joints += [
        Joint("HFE", JointType.REVOLUTE, "base", "thigh", Pose(xyz=(0.3, 0.1, 0.0)), (0.0, 1.0, 0.0), limit),
        Joint("KFE", JointType.REVOLUTE, "thigh", "shank", Pose(xyz=(0.0, 0.0, -0.25)), (0.0, 1.0, 0.0), limit),
    ]
    return Robot("anymal_like", links=links, joints=joints)


def _lumps(robot: Robot) -> dict[str, Inertial | None]:
    """Each fixed group's lumped inertial in its top link's frame."""
    links = robot.link_map()
    out: dict[str, Inertial | None] = {}
    for group in fixed_groups(robot):
        total: Inertial | None = None
        for name, frame in group.frames.items():
            total = combine_inertials(total, links[name].inertial, frame)
        out[group.top] = total
    return out


def _total(robot: Robot) -> float:
    return sum(link.inertial.mass or 0.0 for link in robot.links if link.inertial is not None)


def test_placeholders_keep_every_rigid_groups_mass_centre_and_inertia() -> None:
    robot = anymal_like()
    before = _lumps(robot)
    c = ctx(placeholder_masses=True, mass_from_colliders=True)
    massless(robot, c)
    check(robot)
    for link in robot.links:
        assert link.inertial is not None and link.inertial.mass is not None and link.inertial.mass > 0, link.name
        assert link.inertial.inertia is not None and inertia_problem(link.inertial.inertia) is None, link.name
    # base, imu, camera_parent and camera_optical borrow from base_inertia; thigh_fixed from thigh; foot from shank.
    links = robot.link_map()
    for name in ("base", "imu", "camera_parent", "camera_optical", "thigh_fixed", "foot"):
        inertial = links[name].inertial
        assert inertial is not None and inertial.mass == PLACEHOLDER_MASS
    assert links["base_inertia"].inertial is not None
    assert links["base_inertia"].inertial.mass == pytest.approx(10.0 - 4 * PLACEHOLDER_MASS, rel=1e-12)
    assert _total(robot) == pytest.approx(SOURCE_TOTAL, rel=1e-12)
    after = _lumps(robot)
    for top, want in before.items():
        got = after[top]
        assert want is not None and got is not None
        assert got.mass == pytest.approx(want.mass, rel=1e-12)
        assert np.allclose(pose_matrix(got.origin)[:3, 3], pose_matrix(want.origin)[:3, 3], atol=1e-12)
        assert want.inertia is not None and got.inertia is not None
        assert np.allclose(tensor(got.inertia), tensor(want.inertia), rtol=1e-9, atol=1e-12)
    # No colliders' mass anywhere: the base group carries mass, and so do the leg's groups.
    assert "mass-from-geometry" not in codes(c)
    assert codes(c).count("mass-placeholder") == 6


def test_a_moving_group_without_mass_gets_its_colliders_mass_and_a_warning() -> None:
    robot = anymal_like()
    links = robot.link_map()
    links["thigh"].inertial = None  # the thigh group (thigh, thigh_fixed) now has no mass: Allegro's case
    c = ctx(mass_from_colliders=True)
    massless(robot, c)
    thigh, fixed = links["thigh"].inertial, links["thigh_fixed"].inertial
    assert thigh is not None and thigh.mass == pytest.approx(1000.0 * 0.5 * 0.2 * 0.2, rel=1e-9)
    assert fixed is not None and fixed.mass == pytest.approx(1000.0 * 0.05**3, rel=1e-9)
    warned = [f for f in c.findings if f.code == "mass-from-geometry"]
    assert [f.element for f in warned] == ["link 'thigh'", "link 'thigh_fixed'"]
    assert all(f.severity.name == "WARNING" for f in warned)
    # The root's group (base) and the carried links keep URDF's meaning without placeholder_masses.
    assert links["base"].inertial is None and links["imu"].inertial is None and links["foot"].inertial is None


def test_a_group_with_nothing_to_borrow_from_gets_a_token_and_a_warning() -> None:
    robot = anymal_like()
    links = robot.link_map()
    links["base_inertia"].inertial = None  # the root's group has no mass at all
    c = ctx(placeholder_masses=True)
    massless(robot, c)
    for name in ("base", "base_inertia", "imu", "camera_parent", "camera_optical"):
        inertial = links[name].inertial
        assert inertial is not None and inertial.mass == PLACEHOLDER_MASS
    tokens = [f for f in c.findings if f.code == "mass-placeholder" and f.severity.name == "WARNING"]
    assert len(tokens) == 5
    # thigh_fixed and foot borrow theirs: only the five tokens add mass.
    assert _total(robot) == pytest.approx(2.5 + 5 * PLACEHOLDER_MASS, rel=1e-12)
