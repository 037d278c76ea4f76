"""repair_inertia: the quad_sdk policy exactly, its gap closed, and the geometry policy."""

from __future__ import annotations

import pytest

from robodesc.ir import Box, Collision, Inertia, Inertial, Joint, JointType, Link, Pose, Robot, Sphere
from robodesc.ir.inertia import inertia_problem
from robodesc.ir.verify import check
from robodesc.passes.repair_inertia import repair_inertia
from tests.passes.pass_helpers import codes, ctx

CUBE = Box((0.1, 0.1, 0.1))


def _robot(*links: Link, kind: JointType = JointType.FIXED) -> Robot:
    """The links under a common root, by joints of ``kind``."""
    root = Link("root", inertial=Inertial(mass=1.0, inertia=Inertia(1.0, 1.0, 1.0)))
    joints = [Joint(f"j{i}", kind, "root", link.name) for i, link in enumerate(links)]
    return Robot("r", links=[*links, root], joints=joints)


def test_quad_sdk_missing_inertial_gets_constants_at_link_origin_even_with_geometry() -> None:
    robot = _robot(Link("a", collisions=[Collision(CUBE, Pose(xyz=(1.0, 0.0, 0.0)))]), Link("b"))
    c = ctx(repair_inertia="quad_sdk")
    repair_inertia(robot, c)
    for link in robot.links[:2]:
        assert link.inertial == Inertial(mass=0.001, origin=Pose(), inertia=Inertia(1e-6, 1e-6, 1e-6))
    assert codes(c) == ["inertial-added", "inertial-added"]
    assert all(f.stage == "pass:repair_inertia" for f in c.findings)


def test_quad_sdk_mass_then_diagonals_offdiagonals_untouched() -> None:
    massless = Link("imu", inertial=Inertial(mass=0.0, origin=Pose(), inertia=Inertia(0.0, 0.0, 0.0)))
    negative = Link("neg", inertial=Inertial(mass=-1.0, inertia=Inertia(-1.0, 2e-6, 2e-6, ixy=1e-7)))
    robot = _robot(massless, negative)
    c = ctx(repair_inertia="quad_sdk")
    repair_inertia(robot, c)
    assert massless.inertial is not None and massless.inertial.mass == 0.001
    assert massless.inertial.inertia == Inertia(1e-6, 1e-6, 1e-6)
    assert negative.inertial is not None and negative.inertial.mass == 0.001
    assert negative.inertial.inertia == Inertia(1e-6, 2e-6, 2e-6, ixy=1e-7)
    assert codes(c) == ["mass-repaired", "inertia-diagonal-repaired"] * 2
    check(robot)


def test_quad_sdk_gap_positive_mass_zero_tensor_from_geometry() -> None:
    # Spirit's text_left: 1e-4 kg with a zero tensor, which Quad-SDK leaves as is.
    text = Link("text", inertial=Inertial(mass=1e-4, inertia=Inertia(0.0, 0.0, 0.0)), collisions=[Collision(CUBE)])
    # Positive diagonal but triangle inequality broken, no geometry: the constant diagonal.
    rod = Link("rod", inertial=Inertial(mass=1.0, inertia=Inertia(1.0, 1.0, 3.0)))
    # A tensor Quad-SDK's diagonal fix leaves non-physical (ixy too large) is also closed.
    skew = Link("skew", inertial=Inertial(mass=2.0, origin=Pose(xyz=(0.0, 0.0, 0.05)), inertia=Inertia(1, 1, 1, ixy=5)))
    skew.collisions = [Collision(Sphere(0.1))]
    robot = _robot(text, rod, skew)
    c = ctx(repair_inertia="quad_sdk")
    repair_inertia(robot, c)
    check(robot)
    assert text.inertial is not None and text.inertial.mass == 1e-4
    assert text.inertial.inertia is not None
    assert text.inertial.inertia.as_tuple() == pytest.approx((1e-4 * 0.02 / 12,) * 3 + (0.0,) * 3, rel=1e-12)
    assert rod.inertial is not None and rod.inertial.inertia == Inertia(1e-6, 1e-6, 1e-6)
    # the given centre of mass is kept; the sphere's tensor is taken about it (parallel axis)
    assert skew.inertial is not None and skew.inertial.origin is not None and skew.inertial.origin.xyz == (0, 0, 0.05)
    i = skew.inertial.inertia
    assert i is not None and (i.ixx, i.iyy, i.izz) == pytest.approx((0.008 + 0.005, 0.008 + 0.005, 0.008), rel=1e-12)
    assert codes(c) == ["inertia-repaired"] * 3
    assert all("a gap Quad-SDK leaves open" in f.message for f in c.findings)


def test_geometry_policy_leaves_a_carried_link_massless() -> None:
    # Fixed to the 1 kg root: URDF's meaning (carried by it, as Gazebo lumps it), never its colliders' mass.
    carried = Link("carried", collisions=[Collision(CUBE)])
    zero = Link("zero", inertial=Inertial(mass=0.0), collisions=[Collision(CUBE)])
    robot = _robot(carried, zero)
    c = ctx(repair_inertia="geometry", density=1000.0)
    repair_inertia(robot, c)
    assert carried.inertial is None
    assert zero.inertial is not None and zero.inertial.mass == 0.0
    assert codes(c) == []


def test_repair_missing_off_only_repairs_invalid() -> None:
    robot = _robot(Link("none"), Link("bad", inertial=Inertial(mass=0.0, inertia=Inertia(0.0, 0.0, 0.0))))
    repair_inertia(robot, ctx(repair_inertia="quad_sdk", repair_missing=False))
    assert robot.links[0].inertial is None
    assert robot.links[1].inertial is not None and robot.links[1].inertial.mass == 0.001


def test_geometry_policy_uses_density_and_shape() -> None:
    missing = Link("missing", collisions=[Collision(CUBE, Pose(xyz=(0.0, 0.0, 0.2)))])
    massless = Link("massless", inertial=Inertial(mass=0.0), collisions=[Collision(CUBE)])
    bare = Link("bare", inertial=Inertial(mass=-2.0, inertia=Inertia(0.0, 0.0, 0.0)))
    good = Link("good", inertial=Inertial(mass=2.0, inertia=Inertia(1.0, 1.0, 1.0)), collisions=[Collision(CUBE)])
    # Moving links: a massless one would be a dead body.
    robot = _robot(missing, massless, bare, good, kind=JointType.CONTINUOUS)
    c = ctx(repair_inertia="geometry", density=1000.0)
    repair_inertia(robot, c)
    check(robot)
    m = missing.inertial
    assert m is not None and m.mass == pytest.approx(1.0, rel=1e-12)  # 1000 kg/m³ x 1 dm³
    assert m.origin is not None and m.origin.xyz == (0.0, 0.0, 0.2)
    assert m.inertia is not None and m.inertia.ixx == pytest.approx(0.02 / 12, rel=1e-12)
    assert massless.inertial is not None and massless.inertial.mass == pytest.approx(1.0)
    assert bare.inertial is not None and bare.inertial.mass == 0.001
    assert bare.inertial.inertia == Inertia(1e-6, 1e-6, 1e-6)
    assert good.inertial is not None and good.inertial.inertia == Inertia(1.0, 1.0, 1.0)  # valid: untouched
    assert codes(c) == ["inertial-added", "mass-repaired", "mass-repaired"]
    for link in robot.links:
        assert link.inertial is not None and link.inertial.inertia is not None
        assert inertia_problem(link.inertial.inertia) is None
