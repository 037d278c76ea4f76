"""USD emitter: golden files plus numbers read back through usd-core's physics parser."""

from __future__ import annotations

import math
import os
from pathlib import Path

import numpy as np
import pytest
from pxr import Sdf, Usd, UsdGeom, UsdPhysics, UsdShade
from usd_readback import (
    check_against_ir,
    parse,
    random_configurations,
    usd_forward_kinematics,
)

from robodesc.emit.usd import UsdOptions, emit_usd
from robodesc.emit.usd.quantities import TRIANGLE_MARGIN, float32_moments
from robodesc.frontends.load import load_path
from robodesc.ir.diagnostics import ConfigError, UnsupportedError
from robodesc.ir.geometry import Inertia, Inertial, Pose
from robodesc.ir.model import Joint, JointType, Link, Robot
from robodesc.ir.transforms import forward_kinematics

DATA = Path(__file__).parent / "data"
ROOT = Path(__file__).resolve().parents[2]
SPIRIT = ROOT / ".." / "shared" / "corpus" / "quadsdk" / "spirit_description/models/spirit/urdf/spirit.urdf.xacro"


def sanitize(robot: Robot) -> Robot:
    """A stand-in for the sanitize_names pass: make names USD identifiers, keep the original."""

    def fix(name: str) -> str:
        out = "".join(c if c.isalnum() or c == "_" else "_" for c in name)
        return out if out and not out[0].isdigit() else f"n{out}"

    links = {link.name: fix(link.name) for link in robot.links}
    for link in robot.links:
        if links[link.name] != link.name:
            link.display_name, link.name = link.name, links[link.name]
    joints = {joint.name: fix(joint.name) for joint in robot.joints}
    for joint in robot.joints:
        joint.parent, joint.child = links[joint.parent], links[joint.child]
        if joint.mimic is not None:
            joint.mimic.joint = joints[joint.mimic.joint]
        if joints[joint.name] != joint.name:
            joint.display_name, joint.name = joint.name, joints[joint.name]
    for sensor in robot.sensors:
        sensor.parent = links[sensor.parent]
    for frame in robot.fixed_frames:
        frame.parent = links[frame.parent]
    return robot


def spirit() -> Robot:
    if not SPIRIT.exists():
        pytest.skip("quadsdk corpus not present")
    robot = sanitize(load_path(str(SPIRIT)).robot)
    for link in robot.links:
        inertial = link.inertial
        if inertial is not None and inertial.inertia is not None and not any(inertial.inertia.as_tuple()):
            # Spirit's text plates carry a zero tensor: give them a thin plate's.
            inertial.inertia = Inertia(ixx=1e-8, iyy=1e-8, izz=2e-8)
    for index, joint in enumerate(robot.joints):
        if joint.type.dof == 1:
            joint.armature = 0.001 * (index + 1)
    return robot


def load(name: str) -> Robot:
    return load_path(str(DATA / f"{name}.urdf")).robot


def emit_and_check(tmp_path: Path, robot: Robot, options: UsdOptions, name: str) -> tuple[str, list[str]]:
    out = tmp_path / f"{name}.usda"
    findings = emit_usd(robot, str(out), options)
    parsed = parse(str(out))
    check_against_ir(parsed, robot, options)
    root = parsed.robot_path
    at_zero = forward_kinematics(robot)
    from usd_readback import body_pose

    for link in robot.links:
        np.testing.assert_allclose(body_pose(parsed.stage, root.AppendChild(link.name)), at_zero[link.name], atol=1e-6)
    for q in random_configurations(robot, 5, seed=len(robot.links)):
        expected = forward_kinematics(robot, q)
        got = usd_forward_kinematics(parsed, q)
        assert set(got) == set(expected)
        for link, m in expected.items():
            np.testing.assert_allclose(got[link], m, atol=1e-6, err_msg=f"{name}: link {link} at {q}")
    return out.read_text(encoding="utf-8"), [f.code for f in findings]


CASES = {
    "arm": (lambda: load("arm"), UsdOptions(fix_base=True, physics_scene=True)),
    "spirit": (spirit, UsdOptions(fix_base=False, solver_position_iterations=8, solver_velocity_iterations=1)),
    "gripper": (lambda: load("gripper"), UsdOptions(drive_type="acceleration", stiffness=400.0, damping=2.0)),
    "fourbar": (lambda: load("fourbar"), UsdOptions(target_type="none")),
    "sensors": (lambda: load("sensors"), UsdOptions(target_type="velocity", contact_offset=0.002, rest_offset=0.0)),
}


@pytest.mark.parametrize("name", sorted(CASES))
def test_golden_and_readback(name: str, tmp_path: Path, golden) -> None:  # type: ignore[no-untyped-def]
    make, options = CASES[name]
    text, codes = emit_and_check(tmp_path, make(), options, name)
    assert not codes, codes
    golden.check(f"{name}.usda", text)


def test_deterministic(tmp_path: Path) -> None:
    robot = load("arm")
    a, b = tmp_path / "a.usda", tmp_path / "b.usda"
    emit_usd(robot, str(a), UsdOptions())
    emit_usd(load("arm"), str(b), UsdOptions())
    assert a.read_bytes() == b.read_bytes()
    c, d = tmp_path / "c.usdc", tmp_path / "d.usdc"
    emit_usd(robot, str(c), UsdOptions())
    emit_usd(robot, str(d), UsdOptions())
    assert c.read_bytes() == d.read_bytes()


def test_stage_metadata_and_root(tmp_path: Path) -> None:
    out = tmp_path / "arm.usda"
    emit_usd(load("arm"), str(out), UsdOptions(physics_scene=True))
    stage = Usd.Stage.Open(str(out))
    assert UsdGeom.GetStageMetersPerUnit(stage) == 1.0
    assert UsdPhysics.GetStageKilogramsPerUnit(stage) == 1.0
    assert UsdGeom.GetStageUpAxis(stage) == "Z"
    prim = stage.GetDefaultPrim()
    assert prim.GetPath() == Sdf.Path("/arm")
    assert Usd.ModelAPI(prim).GetKind() == "component"
    assert Usd.ModelAPI(prim).GetAssetName() == "arm"
    # The physics scene is a sibling of the default prim, never inside it.
    assert stage.GetPrimAtPath("/PhysicsScene").IsA(UsdPhysics.Scene)
    assert not [p for p in Usd.PrimRange(prim) if p.IsA(UsdPhysics.Scene)]


def test_materials_unique_per_look(tmp_path: Path) -> None:
    out = tmp_path / "arm.usda"
    emit_usd(load("arm"), str(out), UsdOptions())
    stage = Usd.Stage.Open(str(out))
    looks: dict[str, tuple[float, ...]] = {}
    for prim in Usd.PrimRange(stage.GetPrimAtPath("/arm/Looks")):
        if prim.IsA(UsdShade.Material):
            shader = UsdShade.Shader(prim.GetChild("PreviewSurface"))
            looks[prim.GetName()] = tuple(shader.GetInput("diffuseColor").Get())
    # red and crimson share a colour (one material); the visual-level "red" is blue (its own name).
    assert len(looks) == len(set(looks.values())) == 3
    assert "red" in looks and "crimson" not in looks
    blue = [name for name, rgb in looks.items() if rgb[2] > 0.8]
    assert blue and blue[0] != "red"
    assert stage.GetPrimAtPath(f"/arm/Looks/{blue[0]}").GetDisplayName() == "red"
    bound = UsdShade.MaterialBindingAPI(stage.GetPrimAtPath("/arm/shoulder/visuals/shell")).ComputeBoundMaterial()[0]
    assert bound.GetPath() == Sdf.Path("/arm/Looks/red")


def test_meshes_and_colliders(tmp_path: Path) -> None:
    out = tmp_path / "arm.usda"
    emit_usd(load("arm"), str(out), UsdOptions(collision_approximation="convexDecomposition"))
    stage = Usd.Stage.Open(str(out))
    mesh = UsdGeom.Mesh(stage.GetPrimAtPath("/arm/upper_arm/visuals/visual_0"))
    points = np.array(mesh.GetPointsAttr().Get())
    # wedge.stl spans 0.1 x 0.05 x 0.04; scale (2, 2, -3) mirrors z.
    np.testing.assert_allclose(points.min(axis=0), [0, 0, -0.12], atol=1e-7)
    np.testing.assert_allclose(points.max(axis=0), [0.2, 0.1, 0], atol=1e-7)
    assert len(points) == 6 and len(mesh.GetFaceVertexCountsAttr().Get()) == 8
    assert mesh.GetSubdivisionSchemeAttr().Get() == "none"
    # Outward normals survive the mirroring: the bottom face (z = 0 before, the top after) points +z.
    assert mesh.GetNormalsInterpolation() == UsdGeom.Tokens.uniform
    normals = np.array(mesh.GetNormalsAttr().Get())
    centroids = points[np.array(mesh.GetFaceVertexIndicesAttr().Get()).reshape(-1, 3)].mean(axis=1)
    centre = points.mean(axis=0)
    assert np.all(np.einsum("ij,ij->i", normals, centroids - centre) > 0)
    obj = UsdGeom.Mesh(stage.GetPrimAtPath("/arm/forearm/visuals/visual_0"))
    assert len(obj.GetPointsAttr().Get()) == 6
    collider = stage.GetPrimAtPath("/arm/upper_arm/collisions/collision_0")
    assert collider.HasAPI(UsdPhysics.CollisionAPI) and collider.HasAPI(UsdPhysics.MeshCollisionAPI)
    assert UsdPhysics.MeshCollisionAPI(collider).GetApproximationAttr().Get() == "convexDecomposition"
    assert UsdGeom.Imageable(collider).GetPurposeAttr().Get() == "guide"


def test_drive_units_and_extras(tmp_path: Path) -> None:
    out = tmp_path / "arm.usda"
    options = UsdOptions(stiffness={"elbow": 300.0, "sl.*": 2000.0, ".*": 50.0}, damping=3.0)
    emit_usd(load("arm"), str(out), options)
    stage = Usd.Stage.Open(str(out))
    elbow = stage.GetPrimAtPath("/arm/joints/elbow")
    assert math.isclose(elbow.GetAttribute("drive:angular:physics:stiffness").Get(), 300 * math.pi / 180, rel_tol=1e-6)
    assert math.isclose(elbow.GetAttribute("drive:angular:physics:damping").Get(), 3 * math.pi / 180, rel_tol=1e-6)
    # physx-usd-schemas 25.11: PhysxJointAxisAPI:angular, maximum joint velocity in deg/s.
    assert math.isclose(
        elbow.GetAttribute("physxJointAxis:angular:maxJointVelocity").Get(), 2.5 * 180 / math.pi, rel_tol=1e-6
    )
    # newton-usd-schemas 0.6: NewtonJointAPI's velocity limit is newton:velocityLimit, in deg/s.
    assert math.isclose(elbow.GetAttribute("newton:velocityLimit").Get(), 2.5 * 180 / math.pi, rel_tol=1e-6)
    assert not elbow.GetAttribute("newton:maxJointVelocity").IsValid()
    slide = stage.GetPrimAtPath("/arm/joints/slide")
    assert slide.GetAttribute("drive:linear:physics:stiffness").Get() == 2000.0
    assert math.isclose(slide.GetAttribute("physxJointAxis:linear:maxJointVelocity").Get(), 0.3, rel_tol=1e-6)
    # The slide's range excludes 0: it starts (and targets) its lower bound.
    assert math.isclose(slide.GetAttribute("state:linear:physics:position").Get(), 0.01, rel_tol=1e-6)
    yaw = stage.GetPrimAtPath("/arm/joints/yaw")
    assert yaw.GetAttribute("drive:angular:physics:stiffness").Get() == pytest.approx(50 * math.pi / 180)
    # URDF friction is a Coulomb effort: PhysX's static and dynamic friction efforts, in N·m.
    assert yaw.GetAttribute("physxJointAxis:angular:staticFrictionEffort").Get() == pytest.approx(0.2)
    assert yaw.GetAttribute("physxJointAxis:angular:dynamicFrictionEffort").Get() == pytest.approx(0.2)
    assert yaw.GetAttribute("newton:friction").Get() == pytest.approx(0.2)
    # Passive damping is per degree for an angular DOF (NewtonJointAPI: effort·s/deg).
    assert yaw.GetAttribute("newton:damping").Get() == pytest.approx(0.5 * math.pi / 180)
    viscous = yaw.GetAttribute("physxJointAxis:angular:viscousFrictionCoefficient").Get()
    assert viscous == pytest.approx(0.5 * math.pi / 180)
    schemas = yaw.GetPrimTypeInfo().GetAppliedAPISchemas()
    assert "PhysxJointAxisAPI:angular" in schemas and "NewtonJointAPI" in schemas
    assert "PhysicsJointStateAPI:angular" in schemas
    # Isaac Sim 6 (the default) does not read the legacy single-apply PhysxJointAPI.
    assert "PhysxJointAPI" not in schemas and not elbow.GetAttribute("physxJoint:maxJointVelocity").IsValid()
    assert not yaw.GetAttribute("physxJointAxis:angular:armature").IsAuthored()


@pytest.mark.parametrize(("version", "axis", "legacy"), [("6", True, False), ("5", True, True), ("4", False, True)])
def test_isaac_version_chooses_the_joint_vocabulary(tmp_path: Path, version: str, axis: bool, legacy: bool) -> None:
    out = tmp_path / "arm.usda"
    findings = emit_usd(load("arm"), str(out), UsdOptions(isaac_version=version))
    stage = Usd.Stage.Open(str(out))
    elbow = stage.GetPrimAtPath("/arm/joints/elbow")
    schemas = elbow.GetPrimTypeInfo().GetAppliedAPISchemas()
    assert ("PhysxJointAxisAPI:angular" in schemas) is axis
    assert ("PhysxJointAPI" in schemas) is legacy
    if legacy:
        assert elbow.GetAttribute("physxJoint:maxJointVelocity").Get() == pytest.approx(2.5 * 180 / math.pi)
    # The legacy jointFriction is a unitless coefficient: a URDF friction effort is never written to it.
    yaw = stage.GetPrimAtPath("/arm/joints/yaw")
    assert not yaw.GetAttribute("physxJoint:jointFriction").IsValid()
    assert yaw.GetAttribute("newton:friction").Get() == pytest.approx(0.2)
    unwritten = [f for f in findings if f.code == "usd-friction-unwritten"]
    assert [f.element for f in unwritten] == (["joint 'yaw'"] if not axis else [])


def test_motor_envelope(tmp_path: Path) -> None:
    out = tmp_path / "arm.usda"
    robot = load("arm")
    emit_usd(robot, str(out), UsdOptions(motor_envelope=True))
    stage = Usd.Stage.Open(str(out))
    for joint in robot.joints:
        prim = stage.GetPrimAtPath(f"/arm/joints/{joint.name}")
        limit = joint.limit
        kind = "angular" if joint.type.is_angular else "linear"
        base = f"physxDrivePerformanceEnvelope:{kind}"
        if joint.type.dof != 1 or limit is None or not (limit.effort or 0) > 0 or not (limit.velocity or 0) > 0:
            assert not prim.GetAttribute(f"{base}:maxActuatorVelocity").IsValid()
            continue
        unit = 180 / math.pi if kind == "angular" else 1.0
        assert f"PhysxDrivePerformanceEnvelopeAPI:{kind}" in prim.GetPrimTypeInfo().GetAppliedAPISchemas()
        assert prim.GetAttribute(f"{base}:maxActuatorVelocity").Get() == pytest.approx(limit.velocity * unit)
        # The motor line reaches 0 torque at the no-load speed: maxForce = resistance * maxActuatorVelocity.
        resistance = prim.GetAttribute(f"{base}:velocityDependentResistance").Get()
        assert resistance * limit.velocity * unit == pytest.approx(limit.effort, rel=1e-6)
    plain = tmp_path / "plain.usda"
    emit_usd(robot, str(plain), UsdOptions())
    assert "PhysxDrivePerformanceEnvelopeAPI" not in plain.read_text()


def test_armature_written_in_both_vocabularies(tmp_path: Path) -> None:
    out = tmp_path / "spirit.usda"
    robot = spirit()
    emit_usd(robot, str(out), UsdOptions(fix_base=False))
    stage = Usd.Stage.Open(str(out))
    for joint in robot.joints:
        prim = stage.GetPrimAtPath(f"/spirit/joints/{joint.name}")
        if joint.armature is None:
            continue
        armature = prim.GetAttribute("physxJointAxis:angular:armature")
        assert armature.Get() == pytest.approx(joint.armature)
        assert prim.GetAttribute("newton:armature").Get() == pytest.approx(joint.armature)
        assert not armature.IsCustom()
        assert prim.GetDisplayName() == (joint.display_name or "")


def test_mimic(tmp_path: Path) -> None:
    out = tmp_path / "gripper.usda"
    emit_usd(load("gripper"), str(out), UsdOptions())
    stage = Usd.Stage.Open(str(out))
    follower = stage.GetPrimAtPath("/gripper/joints/finger_mimic")
    assert follower.GetAttribute("newton:mimicCoef1").Get() == pytest.approx(-1.0)
    assert follower.GetAttribute("newton:mimicCoef0").Get() == pytest.approx(0.05 * 180 / math.pi)
    schemas = follower.GetPrimTypeInfo().GetAppliedAPISchemas()
    assert "NewtonMimicAPI" in schemas and "PhysxMimicJointAPI:rotX" in schemas
    assert follower.GetAttribute("physxMimicJoint:rotX:gearing").Get() == pytest.approx(1.0)
    assert follower.GetAttribute("physxMimicJoint:rotX:offset").Get() == pytest.approx(-0.05)
    ref = follower.GetRelationship("physxMimicJoint:rotX:referenceJoint").GetTargets()
    assert ref == [Sdf.Path("/gripper/joints/finger")]
    assert follower.GetAttribute("physxMimicJoint:rotX:referenceJointAxis").Get() == "rotY"
    # The follower keeps its effort limit on a drive without gains (as Isaac Sim 6.2's importer).
    drive = UsdPhysics.DriveAPI(follower, "angular")
    assert follower.HasAPI(UsdPhysics.DriveAPI, "angular")
    assert drive.GetStiffnessAttr().Get() == 0.0 and drive.GetDampingAttr().Get() == 0.0
    assert drive.GetMaxForceAttr().Get() > 0
    slide = stage.GetPrimAtPath("/gripper/joints/pad_slide")
    assert slide.GetAttribute("newton:mimicCoef0").Get() == pytest.approx(0.001)


def test_a_mimic_follower_has_no_velocity_limit_and_starts_where_its_leader_does(tmp_path: Path) -> None:
    """PhysX fights a velocity limit on a mimic follower and can run away (tiago_pro's arms went
    4.9e27 rad off): the follower carries none, in either vocabulary ovphysx reads; the leader keeps
    its own. A follower starts at multiplier x its leader's start + offset."""
    robot = load("gripper")
    out = tmp_path / "gripper.usda"
    findings = emit_usd(robot, str(out), UsdOptions(initial_positions={"finger": 0.3}))
    stage = Usd.Stage.Open(str(out))
    leader = stage.GetPrimAtPath("/gripper/joints/finger")
    assert leader.GetAttribute("physxJointAxis:angular:maxJointVelocity").Get() == pytest.approx(math.degrees(1.5))
    assert leader.GetAttribute("newton:velocityLimit").Get() == pytest.approx(math.degrees(1.5))
    for name in ("finger_mimic", "pad_slide"):
        prim = stage.GetPrimAtPath(f"/gripper/joints/{name}")
        names = {a.GetName() for a in prim.GetAttributes()}
        assert not {n for n in names if n.endswith(("maxJointVelocity", "velocityLimit"))}, name
    # finger_mimic = -1 x finger + 0.05; pad_slide = 0.02 x finger + 0.001 (m).
    start = stage.GetPrimAtPath("/gripper/joints/finger_mimic").GetAttribute("state:angular:physics:position")
    assert start.Get() == pytest.approx(math.degrees(-0.3 + 0.05), rel=1e-6)
    slide = stage.GetPrimAtPath("/gripper/joints/pad_slide").GetAttribute("state:linear:physics:position")
    assert slide.Get() == pytest.approx(0.02 * 0.3 + 0.001, rel=1e-6)
    # The leader bounds both followers (1.5 rad/s and 0.03 m/s): nothing is lost, nothing to say.
    assert not [f for f in findings if f.code == "usd-mimic-velocity"]
    # A follower limit tighter than its leader's allows is lost: the compile says so, naming it.
    next(j for j in robot.joints if j.name == "finger_mimic").limit.velocity = 0.5  # type: ignore[union-attr]
    lost = [f for f in emit_usd(robot, str(out), UsdOptions()) if f.code == "usd-mimic-velocity"]
    assert len(lost) == 1 and "finger_mimic" in lost[0].element and "1.5" in lost[0].message


def test_loop_joint_and_fixed_frame(tmp_path: Path) -> None:
    out = tmp_path / "fourbar.usda"
    emit_usd(load("fourbar"), str(out), UsdOptions())
    parsed = parse(str(out))
    loops = [p for p in parsed.paths("SphericalJoint") if "/loop_joints/" in p]
    assert loops == ["/fourbar/loop_joints/close_loop"]
    desc = parsed.objects["SphericalJoint"][loops[0]]
    assert desc.excludeFromArticulation
    assert Sdf.Path(str(desc.body0)).name == "coupler" and Sdf.Path(str(desc.body1)).name == "rocker"
    # usd-core's parser still lists the closure among the articulation's joints; the simulator
    # (PhysX, Newton) keeps it out of the tree because of excludeFromArticulation.
    prim = parsed.stage.GetPrimAtPath(loops[0])
    assert UsdPhysics.Joint(prim).GetExcludeFromArticulationAttr().Get() is True
    tcp = UsdGeom.Xformable(parsed.stage.GetPrimAtPath("/fourbar/coupler/tcp"))
    assert tcp and np.allclose(np.array(tcp.GetLocalTransformation()).T[:3, 3], [0.15, 0.02, 0])


def test_sensors(tmp_path: Path) -> None:
    out = tmp_path / "sensors.usda"
    emit_usd(load("sensors"), str(out), UsdOptions())
    stage = Usd.Stage.Open(str(out))
    camera = UsdGeom.Camera(stage.GetPrimAtPath("/sensor_head/head/front_camera"))
    assert camera
    h = camera.GetHorizontalApertureAttr().Get()
    f = camera.GetFocalLengthAttr().Get()
    assert 2 * math.atan(h / 2 / f) == pytest.approx(1.5708, rel=1e-6)
    assert tuple(camera.GetClippingRangeAttr().Get()) == pytest.approx((0.01, 50.0))
    assert camera.GetVerticalApertureAttr().Get() / h == pytest.approx(480 / 640)
    # The USD camera looks down its -Z: that must be the sensor's +X (pitched down by 0.2 rad).
    m = np.array(camera.GetPrim().GetAttribute("xformOp:orient").Get().GetImaginary())
    del m
    look = np.array(UsdGeom.Xformable(camera).GetLocalTransformation()).T[:3, :3] @ [0, 0, -1]
    assert look == pytest.approx([math.cos(0.2), 0, -math.sin(0.2)], abs=1e-6)
    lidar = stage.GetPrimAtPath("/sensor_head/head/lidar")
    assert lidar.GetTypeName() == "Camera"
    assert lidar.GetAttribute("sensorModelConfig").Get() == "Velodyne_VLS128"
    assert lidar.GetAttribute("cameraSensorType").Get() == "lidar"
    assert lidar.GetAttribute("robodesc:ray:horizontal:samples").Get() == 21
    imu = stage.GetPrimAtPath("/sensor_head/base/imu")
    assert imu.GetTypeName() == "Xform" and imu.GetAttribute("robodesc:sensor:type").Get() == "imu"
    collider = stage.GetPrimAtPath("/sensor_head/head/visuals/visual_0")
    assert collider


def test_contact_offsets(tmp_path: Path) -> None:
    out = tmp_path / "arm.usda"
    emit_usd(load("arm"), str(out), UsdOptions(contact_offset=0.002, rest_offset=0.0005))
    stage = Usd.Stage.Open(str(out))
    prim = stage.GetPrimAtPath("/arm/wrist/collisions/collision_0")
    assert "PhysxCollisionAPI" in prim.GetPrimTypeInfo().GetAppliedAPISchemas()
    assert prim.GetAttribute("physxCollision:contactOffset").Get() == pytest.approx(0.002)
    assert prim.GetAttribute("physxCollision:restOffset").Get() == pytest.approx(0.0005)


def test_layered_matches_single_file(tmp_path: Path) -> None:
    robot = load("arm")
    single = tmp_path / "single" / "arm.usda"
    layered = tmp_path / "layered" / "arm.usda"
    emit_usd(robot, str(single), UsdOptions(physics_scene=True))
    emit_usd(robot, str(layered), UsdOptions(physics_scene=True, layered=True))
    files = sorted(str(p.relative_to(layered.parent)) for p in layered.parent.rglob("*") if p.is_file())
    assert files == [
        "Payload/Contents.usda",
        "Payload/Geometry.usdc",
        "Payload/Materials.usda",
        "Payload/Physics.usda",
        "arm.usda",
    ]
    a = Usd.Stage.Open(str(single)).Flatten()
    b = Usd.Stage.Open(str(layered)).Flatten()
    assert _dump(a) == _dump(b)
    parsed = parse(str(layered))
    check_against_ir(parsed, robot, UsdOptions())
    interface = Usd.Stage.Open(str(layered), load=Usd.Stage.LoadNone)
    assert interface.GetDefaultPrim().HasAuthoredPayloads()


def _dump(layer: Sdf.Layer) -> dict[str, dict[str, object]]:
    out: dict[str, dict[str, object]] = {}

    def visit(path: Sdf.Path) -> None:
        spec = layer.GetObjectAtPath(path)
        if isinstance(spec, Sdf.PrimSpec):
            props = {
                p.name: (
                    p.default if isinstance(p, Sdf.AttributeSpec) else list(p.targetPathList.GetAddedOrExplicitItems())
                )
                for p in spec.properties
            }
            schemas = spec.GetInfo("apiSchemas") if spec.HasInfo("apiSchemas") else None
            out[str(path)] = {"type": spec.typeName, "props": props, "schemas": str(schemas)}

    layer.Traverse(Sdf.Path.absoluteRootPath, visit)
    return out


def test_usdc_output(tmp_path: Path) -> None:
    out = tmp_path / "arm.usdc"
    robot = load("arm")
    emit_usd(robot, str(out), UsdOptions())
    assert out.read_bytes()[:8] == b"PXR-USDC"
    check_against_ir(parse(str(out)), robot, UsdOptions())
    assert [p.name for p in tmp_path.iterdir()] == ["arm.usdc"]


def test_invalid_names_are_refused(tmp_path: Path) -> None:
    robot = load("gripper")
    robot.joints[0].name = "0bad"
    out = tmp_path / "g.usda"
    with pytest.raises(UnsupportedError, match="sanitize"):
        emit_usd(robot, str(out), UsdOptions())
    assert not out.exists() and not list(tmp_path.iterdir())


def test_failure_keeps_previous_output(tmp_path: Path) -> None:
    out = tmp_path / "g.usda"
    out.write_text("old")
    robot = load("gripper")
    robot.links[0].name = "joints"
    with pytest.raises(UnsupportedError):
        emit_usd(robot, str(out), UsdOptions())
    assert out.read_text() == "old"
    assert os.listdir(tmp_path) == ["g.usda"]


def test_bad_options() -> None:
    robot = load("gripper")
    with pytest.raises(ConfigError):
        emit_usd(robot, "/tmp/x.usda", UsdOptions(drive_type="torque"))
    with pytest.raises(ConfigError):
        emit_usd(robot, "/tmp/x.urdf", UsdOptions())
    with pytest.raises(ConfigError):
        emit_usd(robot, "/tmp/x.usda", UsdOptions(stiffness={"(": 1.0}))


def test_planar_and_floating_joints(tmp_path: Path) -> None:
    robot = Robot(name="mover")
    for name in ("world", "sled", "puck"):
        robot.links.append(Link(name=name))
    robot.joints.append(Joint(name="plane", type=JointType.PLANAR, parent="world", child="sled", axis=(0.0, 0.0, 1.0)))
    robot.joints.append(Joint(name="free", type=JointType.FLOATING, parent="sled", child="puck"))
    out = tmp_path / "mover.usda"
    findings = emit_usd(robot, str(out), UsdOptions())
    assert {f.code for f in findings} == {"usd-no-mass"}
    parsed = parse(str(out))
    d6 = parsed.objects["D6Joint"]
    plane = d6["/mover/joints/plane"]
    locked = {str(pair.first): (pair.second.lower, pair.second.upper) for pair in plane.jointLimits}
    # Normal Z: z translation and x, y rotations are locked; a locked DOF has lower > upper.
    assert set(locked) == {"TransZ", "RotX", "RotY"} and all(lo > hi for lo, hi in locked.values())
    assert not d6["/mover/joints/free"].jointLimits


def test_missing_mesh_is_a_finding(tmp_path: Path) -> None:
    robot = load("arm")
    geometry = robot.link("upper_arm").visuals[0].geometry
    geometry.path = None  # type: ignore[union-attr]
    findings = emit_usd(robot, str(tmp_path / "arm.usda"), UsdOptions())
    assert [f.code for f in findings] == ["usd-missing-mesh"]
    stage = Usd.Stage.Open(str(tmp_path / "arm.usda"))
    assert not stage.GetPrimAtPath("/arm/upper_arm/visuals/visual_0")


@pytest.mark.parametrize(
    "moments",
    [
        (1.822845e-05, 7.632537e-05, 9.455382e-05),  # allegro_right_hand link_1.0: A + B = C in the source
        (1e-8, 1e-8, 2e-8),  # spirit's toes
        (1.0, 1.0, 2.0),
        (0.1, 0.2, 0.3000000001),
    ],
)
def test_float32_moments_keep_the_triangle_inequality(moments: tuple[float, float, float]) -> None:
    """Rounded to float32 and rebuilt by a consumer, a boundary tensor must still be physical."""
    out = float32_moments(moments)
    assert all(np.float32(x) == x for x in out)  # exactly the float32 values the file holds
    a, b, c = sorted(out)
    assert a + b > c and float(np.float32(a) + np.float32(b)) > c
    assert (a + b - c) / c >= TRIANGLE_MARGIN * 0.999
    assert max(abs(x - y) / y for x, y in zip(out, moments, strict=True)) < 1e-5


def test_float32_moments_leave_real_violations_and_zero_alone() -> None:
    bad = (2.3006407e-06, 3.4852651e-06, 7.2659022e-06)  # allegro link_3.0: 20 % off, the source's
    assert float32_moments(bad) == tuple(float(np.float32(x)) for x in bad)
    assert float32_moments((0.0, 0.0, 0.0)) == (0.0, 0.0, 0.0)
    assert float32_moments((1e-4, 1e-4, 1e-4)) == tuple(float(np.float32(1e-4)) for _ in range(3))


def test_zero_tensor_leaves_inertia_unauthored(tmp_path: Path) -> None:
    """A massless link: UsdPhysics' fallback, which NVIDIA's SimReady MassChecker accepts only when
    diagonalInertia and principalAxes are both unauthored (or both zero)."""
    robot = load("arm")
    link = robot.links[-1]
    link.inertial = Inertial(mass=0.0, origin=Pose(), inertia=Inertia(ixx=0.0, iyy=0.0, izz=0.0))
    out = tmp_path / "arm.usda"
    emit_usd(robot, str(out), UsdOptions())
    stage = Usd.Stage.Open(str(out))
    prim = stage.GetPrimAtPath(f"/arm/{link.name}")
    api = UsdPhysics.MassAPI(prim)
    assert api.GetMassAttr().Get() == 0.0
    assert not api.GetDiagonalInertiaAttr().IsAuthored() and not api.GetPrincipalAxesAttr().IsAuthored()


def test_isaac_robot_schema(tmp_path: Path) -> None:
    out = tmp_path / "gripper.usda"
    robot = load("gripper")
    emit_usd(robot, str(out), UsdOptions())
    stage = Usd.Stage.Open(str(out))
    root = stage.GetPrimAtPath("/gripper")
    assert "IsaacRobotAPI" in root.GetPrimTypeInfo().GetAppliedAPISchemas()
    links = [t.name for t in root.GetRelationship("isaac:physics:robotLinks").GetTargets()]
    joints = [t.name for t in root.GetRelationship("isaac:physics:robotJoints").GetTargets()]
    assert links == [x.name for x in robot.links] and joints == [j.name for j in robot.joints]
    for name in links:
        assert "IsaacLinkAPI" in stage.GetPrimAtPath(f"/gripper/{name}").GetPrimTypeInfo().GetAppliedAPISchemas()
