"""Read an emitted USD robot back the way a simulator importer does and compare it with the IR.

Everything here reads USD only through usd-core (``UsdPhysics.LoadUsdPhysicsFromRange`` and the
schema APIs) and recomputes kinematics independently of the emitter's code.
"""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass

import numpy as np
from pxr import Gf, Sdf, Usd, UsdGeom, UsdPhysics

from robodesc.emit.usd import UsdOptions
from robodesc.ir.inertia import tensor
from robodesc.ir.model import JointType, Robot
from robodesc.ir.transforms import rpy_to_matrix

DEG = 180.0 / math.pi
JOINT_KINDS = {
    JointType.REVOLUTE: "RevoluteJoint",
    JointType.CONTINUOUS: "RevoluteJoint",
    JointType.PRISMATIC: "PrismaticJoint",
    JointType.FIXED: "FixedJoint",
    JointType.SPHERICAL: "SphericalJoint",
    JointType.FLOATING: "D6Joint",
    JointType.PLANAR: "D6Joint",
}
_AXES = {"X": np.array([1.0, 0, 0]), "Y": np.array([0, 1.0, 0]), "Z": np.array([0, 0, 1.0])}


@dataclass
class Parsed:
    stage: Usd.Stage
    robot_path: Sdf.Path
    # kind ("RigidBody", "RevoluteJoint" ...) -> {prim path: descriptor}
    objects: dict[str, dict[str, object]]

    def paths(self, kind: str) -> list[str]:
        return list(self.objects.get(kind, {}))

    def joint_descs(self) -> dict[str, object]:
        out: dict[str, object] = {}
        for kind, items in self.objects.items():
            if kind.endswith("Joint"):
                out.update(items)
        return out


def parse(path: str) -> Parsed:
    stage = Usd.Stage.Open(path)
    assert stage is not None
    prim = stage.GetDefaultPrim()
    assert prim.IsValid(), "no default prim"
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", DeprecationWarning)
        raw = UsdPhysics.LoadUsdPhysicsFromRange(stage, [str(prim.GetPath())])
    objects = {
        str(kind): {str(p): d for p, d in zip(paths, descs, strict=True)} for kind, (paths, descs) in raw.items()
    }
    return Parsed(stage, prim.GetPath(), objects)


def quat_matrix(q: Gf.Quatf | Gf.Quatd) -> np.ndarray:
    w = q.GetReal()
    x, y, z = q.GetImaginary()
    n = math.sqrt(w * w + x * x + y * y + z * z)
    w, x, y, z = w / n, x / n, y / n, z / n
    return np.array(
        [
            [1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
            [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
            [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)],
        ]
    )


def frame(pos: Gf.Vec3f | Gf.Vec3d, rot: Gf.Quatf) -> np.ndarray:
    m = np.eye(4)
    m[:3, :3] = quat_matrix(rot)
    m[:3, 3] = [pos[0], pos[1], pos[2]]
    return m


def axis_rotation(axis: np.ndarray, angle: float) -> np.ndarray:
    x, y, z = axis
    c, s, t = math.cos(angle), math.sin(angle), 1 - math.cos(angle)
    return np.array(
        [
            [t * x * x + c, t * x * y - s * z, t * x * z + s * y],
            [t * x * y + s * z, t * y * y + c, t * y * z - s * x],
            [t * x * z - s * y, t * y * z + s * x, t * z * z + c],
        ]
    )


def usd_forward_kinematics(parsed: Parsed, q: dict[str, float]) -> dict[str, np.ndarray]:
    """Link poses composed through the USD joints only: parent @ frame0 @ motion @ inv(frame1).

    ``q`` holds URDF joint values (rad, m) by joint prim name; mimic followers are computed from the
    NewtonMimicAPI attributes in the file.
    """
    stage = parsed.stage
    joints: dict[str, Usd.Prim] = {}
    for prim in Usd.PrimRange(stage.GetPrimAtPath(parsed.robot_path.AppendChild("joints"))):
        if prim.IsA(UsdPhysics.Joint):
            joints[prim.GetName()] = prim
    values = dict(q)

    def value(name: str) -> float:
        if name in values:
            return values[name]
        prim = joints[name]
        rel = prim.GetRelationship("newton:mimicJoint")
        if rel and rel.GetTargets():
            leader = rel.GetTargets()[0].name
            coef0 = prim.GetAttribute("newton:mimicCoef0").Get()
            coef1 = prim.GetAttribute("newton:mimicCoef1").Get()
            unit = 1 / DEG if prim.IsA(UsdPhysics.RevoluteJoint) else 1.0
            values[name] = coef1 * value(leader) + coef0 * unit
        else:
            values[name] = 0.0
        return values[name]

    edges: dict[str, tuple[str, Usd.Prim]] = {}
    root = None
    for prim in joints.values():
        j = UsdPhysics.Joint(prim)
        b0 = j.GetBody0Rel().GetTargets()
        b1 = j.GetBody1Rel().GetTargets()[0].name
        if not b0:
            root = b1
            continue
        edges[b1] = (b0[0].name, prim)
    if root is None:
        parents = {p for p, _ in edges.values()}
        roots = parents - set(edges)
        assert len(roots) == 1, roots
        root = roots.pop()
    out = {root: np.eye(4)}
    pending = dict(edges)
    while pending:
        progressed = False
        for child, (parent, prim) in list(pending.items()):
            if parent not in out:
                continue
            j = UsdPhysics.Joint(prim)
            f0 = frame(j.GetLocalPos0Attr().Get(), j.GetLocalRot0Attr().Get())
            f1 = frame(j.GetLocalPos1Attr().Get(), j.GetLocalRot1Attr().Get())
            motion = np.eye(4)
            if prim.IsA(UsdPhysics.RevoluteJoint):
                axis = _AXES[UsdPhysics.RevoluteJoint(prim).GetAxisAttr().Get()]
                motion[:3, :3] = axis_rotation(axis, value(prim.GetName()))
            elif prim.IsA(UsdPhysics.PrismaticJoint):
                axis = _AXES[UsdPhysics.PrismaticJoint(prim).GetAxisAttr().Get()]
                motion[:3, 3] = axis * value(prim.GetName())
            out[child] = out[parent] @ f0 @ motion @ np.linalg.inv(f1)
            del pending[child]
            progressed = True
        assert progressed, f"joints do not form a tree: {sorted(pending)}"
    return out


def body_pose(stage: Usd.Stage, path: Sdf.Path) -> np.ndarray:
    """translate + orient read directly: Gf's matrix path rounds through float and loses ~1e-6."""
    prim = stage.GetPrimAtPath(path)
    assert UsdGeom.Xformable(prim).GetXformOpOrderAttr().Get() == ["xformOp:translate", "xformOp:orient"]
    t = prim.GetAttribute("xformOp:translate").Get()
    return frame(t, prim.GetAttribute("xformOp:orient").Get())


def recomposed_tensor(prim: Usd.Prim) -> np.ndarray:
    mass_api = UsdPhysics.MassAPI(prim)
    diag = np.array(mass_api.GetDiagonalInertiaAttr().Get(), dtype=float)
    if not diag.any():
        return np.zeros((3, 3))  # a zero tensor: robodesc leaves diagonalInertia and principalAxes unauthored
    r = quat_matrix(mass_api.GetPrincipalAxesAttr().Get())
    return r @ np.diag(diag) @ r.T


def ir_tensor_in_link(robot: Robot, link_name: str) -> np.ndarray:
    inertial = robot.link(link_name).inertial
    assert inertial is not None and inertial.inertia is not None
    m = tensor(inertial.inertia)
    if inertial.origin is not None:
        r = rpy_to_matrix(inertial.origin.rpy)
        m = r @ m @ r.T
    return m


def check_against_ir(parsed: Parsed, robot: Robot, options: UsdOptions) -> None:
    """Bodies, joints, limits, drives, masses and the articulation root against the IR."""
    stage, root = parsed.stage, parsed.robot_path
    bodies = {Sdf.Path(p).name for p in parsed.paths("RigidBody")}
    assert bodies == {link.name for link in robot.links}
    n_shapes = sum(len(items) for kind, items in parsed.objects.items() if kind.endswith("Shape"))
    n_colliders = sum(len(link.collisions) for link in robot.links)
    assert n_shapes == n_colliders

    descs = {
        Sdf.Path(p).name: (p, d)
        for p, d in parsed.joint_descs().items()
        if Sdf.Path(p).GetParentPath().name == "joints"
    }
    expected = {j.name for j in robot.joints} | ({"root_joint"} if options.fix_base else set())
    assert set(descs) == expected
    for joint in robot.joints:
        path, desc = descs[joint.name]
        assert path in parsed.objects[JOINT_KINDS[joint.type]], (joint.name, joint.type)
        assert Sdf.Path(str(desc.body0)).name == joint.parent
        assert Sdf.Path(str(desc.body1)).name == joint.child
        prim = stage.GetPrimAtPath(path)
        if joint.type.dof != 1:
            continue
        angular = joint.type.is_angular
        unit = DEG if angular else 1.0
        limit = desc.limit
        ir_limit = joint.limit
        if joint.type is JointType.CONTINUOUS or ir_limit is None or ir_limit.lower is None or ir_limit.upper is None:
            assert not limit.enabled
        else:
            assert limit.enabled
            assert math.isclose(limit.lower, ir_limit.lower * unit, rel_tol=1e-6, abs_tol=1e-6)
            assert math.isclose(limit.upper, ir_limit.upper * unit, rel_tol=1e-6, abs_tol=1e-6)
        # The axis token turned by localRot1 is the URDF axis in the child frame.
        token = str(desc.axis)
        axis_in_child = quat_matrix(prim.GetAttribute("physics:localRot1").Get()) @ _AXES[token]
        ir_axis = np.asarray(joint.effective_axis, dtype=float)
        np.testing.assert_allclose(axis_in_child, ir_axis / np.linalg.norm(ir_axis), atol=1e-6)
        drive = desc.drive
        if joint.mimic is not None:
            # A follower keeps only its effort limit: a drive without gains (Isaac Sim 6.2's form).
            effort = joint.limit.effort if joint.limit is not None else None
            assert drive.enabled == bool(effort is not None and effort > 0)
            if drive.enabled:
                assert drive.stiffness == 0.0 and drive.damping == 0.0
                assert math.isclose(drive.forceLimit, effort, rel_tol=1e-6)
            assert prim.GetRelationship("newton:mimicJoint").GetTargets()[0].name == joint.mimic.joint
            continue
        assert drive.enabled
        assert drive.acceleration == (options.drive_type == "acceleration")
        per = math.pi / 180 if angular else 1.0
        if options.target_type == "position":
            assert isinstance(options.stiffness, float | int) and isinstance(options.damping, float | int)
            assert math.isclose(drive.stiffness, options.stiffness * per, rel_tol=1e-6)
            assert math.isclose(drive.damping, options.damping * per, rel_tol=1e-6)
        if joint.limit is not None and joint.limit.effort:
            assert math.isclose(drive.forceLimit, joint.limit.effort, rel_tol=1e-6)

    for link in robot.links:
        prim = stage.GetPrimAtPath(root.AppendChild(link.name))
        inertial = link.inertial
        if inertial is None or inertial.mass is None:
            continue
        mass_api = UsdPhysics.MassAPI(prim)
        assert math.isclose(mass_api.GetMassAttr().Get(), inertial.mass, rel_tol=1e-6)
        com = inertial.origin.xyz if inertial.origin is not None else (0.0, 0.0, 0.0)
        np.testing.assert_allclose(np.array(mass_api.GetCenterOfMassAttr().Get()), com, atol=1e-7)
        expected_tensor = ir_tensor_in_link(robot, link.name)
        got = recomposed_tensor(prim)
        scale = max(float(np.abs(expected_tensor).max()), 1e-300)
        # 1e-5: a tensor on the triangle inequality's boundary is moved TRIANGLE_MARGIN (1e-6) inside it.
        assert float(np.abs(got - expected_tensor).max()) <= 1e-5 * scale, (link.name, got, expected_tensor)

    robot_prim = stage.GetPrimAtPath(root)
    root_link = stage.GetPrimAtPath(root.AppendChild(robot.root.name))
    if options.fix_base:
        assert robot_prim.HasAPI(UsdPhysics.ArticulationRootAPI)
        assert not root_link.HasAPI(UsdPhysics.ArticulationRootAPI)
        fixed = UsdPhysics.FixedJoint(stage.GetPrimAtPath(root.AppendChild("joints").AppendChild("root_joint")))
        assert not fixed.GetBody0Rel().GetTargets()
        assert [p.name for p in fixed.GetBody1Rel().GetTargets()] == [robot.root.name]
    else:
        assert root_link.HasAPI(UsdPhysics.ArticulationRootAPI)
        assert not robot_prim.HasAPI(UsdPhysics.ArticulationRootAPI)
    assert [str(p) for p in parsed.paths("Articulation")]


def random_configurations(robot: Robot, count: int, seed: int) -> list[dict[str, float]]:
    rng = np.random.default_rng(seed)
    out = []
    for _ in range(count):
        q: dict[str, float] = {}
        for joint in robot.actuated_joints():
            if joint.type.dof != 1:
                continue
            lim = joint.limit
            if (
                joint.type is not JointType.CONTINUOUS
                and lim is not None
                and lim.lower is not None
                and lim.upper is not None
            ):
                q[joint.name] = float(rng.uniform(lim.lower, lim.upper))
            else:
                q[joint.name] = float(rng.uniform(-math.pi, math.pi))
        out.append(q)
    return out
