"""The world stage beside a USD robot (``<stem>_world.usda``): the world's ground and physics, and
the robot brought in by a payload at its spawn point (docs/worlds.md).

USD has no heightfield prim, and PhysX and Isaac Lab collide terrains as triangle meshes, so every
terrain is a static ``Mesh`` collider with ``physics:approximation = "none"`` (PhysX honours every
triangle of a static mesh). Boxes, spheres, cylinders and planes are UsdGeom shapes. The scene
carries the world's gravity and step: UsdPhysics' gravity, ``physxScene:timeStepsPerSecond`` and
``newton:timeStepsPerSecond``. The terrain's material combines friction by the minimum
(``physxMaterial:frictionCombineMode``), as Gazebo's ODE does: Quad-SDK's terrains say mu 100 and
mean "the robot's own friction".

The robot is a payload (robodesc's USD writer's composition arc; Isaac Sim loads payloads), under
``/World/<robot>``, translated to where emit/common/world.py placed it.
"""

from __future__ import annotations

import math
import os
from collections.abc import Sequence
from typing import TYPE_CHECKING

from robodesc.emit.usd.context import set_pose
from robodesc.emit.usd.layers import encode, stage_metadata
from robodesc.ir.diagnostics import Findings
from robodesc.ir.geometry import Box, Cylinder, Mesh, Sphere, Vec3
from robodesc.ir.rigid import Frame, pose_frame, rpy_rotation
from robodesc.ir.world import CordField, HeightImage, Plane, StaticBody, WorldCollider
from robodesc.usdfile.spec import Layer, Payload, Prim

if TYPE_CHECKING:  # the placement reads meshes (numpy); a plain USD compile must not import it
    from robodesc.emit.common.target import WorldAlone
    from robodesc.emit.common.world import PlacedWorld

STAGE = "emit:usd"
WORLD = "World"
PLANE_SIZE = 100.0  # m: a finite stand-in for SDF's infinite plane (UsdPhysics' Plane is infinite too)


def world_file_name(robot_file: str) -> str:
    stem, ext = os.path.splitext(os.path.basename(robot_file))
    return f"{stem}_world{ext}"


def copy_names(robot_prim: str, count: int) -> list[str]:
    """The prim of each copy of the robot: its own name alone, ``<name>_0`` ... for several."""
    return [robot_prim] if count == 1 else [f"{robot_prim}_{i}" for i in range(count)]


def write_world(
    path: str,
    robot_file: str | None,
    robot_prim: str,
    placed: PlacedWorld,
    roots: Sequence[Vec3],
    findings: Findings,
    *,
    contacts: bool = False,
) -> int:
    """Write the world stage to ``path``; ``robot_file`` is the robot's final file name beside it,
    brought in once per root (several copies: one payload each, ``/World/<robot>_<i>``). No
    ``roots``: the world alone (a world file as the input). Returns the static colliders written."""
    from robodesc._files import write_atomic

    layer, world, count = _ground(placed, findings)
    _scene(world, placed, contacts)
    for cords, anchors in placed.cords:
        _cords(world, cords, anchors)
    turn = rpy_rotation((0.0, 0.0, placed.yaw))
    for name, root in zip(copy_names(robot_prim, len(roots)) if roots else [], roots, strict=True):
        assert robot_file is not None
        robot = world.child(name, "Xform")
        robot.payloads.append(Payload(f"./{os.path.basename(robot_file)}", f"/{robot_prim}"))
        set_pose(robot, Frame(translation=root, rotation=turn))
    write_atomic(path, encode(layer, os.path.splitext(path)[1].lower()))
    return count


def write_terrain(path: str, placed: PlacedWorld, findings: Findings) -> None:
    """The world's ground alone (static bodies and their friction; no scene, robot or cords): what
    Isaac Lab's ``TerrainImporterCfg(terrain_type="usd")`` references under its own prim, beside the
    ``PhysicsScene`` its ``SimulationCfg`` makes."""
    from robodesc._files import write_atomic

    layer, _, _ = _ground(placed, findings)
    write_atomic(path, encode(layer, os.path.splitext(path)[1].lower()))


def _ground(placed: PlacedWorld, findings: Findings) -> tuple[Layer, Prim, int]:
    """A layer whose default prim ``/World`` holds the world's static bodies and their materials,
    and the number of colliders it holds."""
    layer = Layer()
    stage_metadata(layer, WORLD)
    world = layer.prim(f"/{WORLD}", "Xform")
    world.kind = "assembly"
    material = _terrain_material(world, placed)
    if not placed.world.bodies:  # a world of cords alone: a ground plane under them
        ground = world.child("ground", "Plane")
        ground.attr("width", "double", PLANE_SIZE)
        ground.attr("length", "double", PLANE_SIZE)
        ground.attr("axis", "token", "Z", uniform=True)
        ground.apply("PhysicsCollisionAPI")
    count = 0 if placed.world.bodies else 1
    for body in placed.world.bodies:
        body_prim = world.child(_name(body.name), "Xform")
        set_pose(body_prim, pose_frame(body.pose))
        for collider in body.colliders:
            count += _collider(body_prim, body, collider, material, findings)
    return layer, world, count


def _scene(world: Prim, placed: PlacedWorld, contacts: bool) -> None:
    physics = placed.world.physics
    scene = world.child("PhysicsScene", "PhysicsScene")
    if contacts:
        # PhysX stops reporting the contacts of bodies asleep: a robot standing still would read no
        # force on its feet (ovphysx docs, "Sleeping contacts"). Isaac Lab's GPU scenes never sleep.
        scene.apply("PhysxSceneAPI")
        scene.attr("physxScene:disableSleeping", "bool", True, uniform=True)
    gravity = physics.gravity or (0.0, 0.0, -9.81)
    magnitude = math.sqrt(sum(g * g for g in gravity))
    if magnitude > 0:
        scene.attr("physics:gravityDirection", "vector3f", tuple(g / magnitude for g in gravity))
    scene.attr("physics:gravityMagnitude", "float", magnitude)
    if physics.step is not None:
        steps = round(1.0 / physics.step)
        scene.apply("PhysxSceneAPI")
        scene.attr("physxScene:timeStepsPerSecond", "uint", steps)
        scene.apply("NewtonSceneAPI")
        scene.attr("newton:timeStepsPerSecond", "int", steps)


def _terrain_material(world: Prim, placed: PlacedWorld) -> dict[float, str]:
    """One physics material per distinct world friction, combining by the minimum (ODE's rule)."""
    out: dict[float, str] = {}
    values = sorted(
        {
            c.surface.mu
            for b in placed.world.bodies
            for c in b.colliders
            if c.surface is not None and c.surface.mu is not None
        }
    )
    if not values:
        return out
    scope = world.child("PhysicsMaterials", "Scope")
    for i, mu in enumerate(values):
        material = scope.child(f"surface_{i}", "Material")
        material.apply("PhysicsMaterialAPI")
        material.attr("physics:staticFriction", "float", mu)
        material.attr("physics:dynamicFriction", "float", mu)
        material.apply("PhysxMaterialAPI")
        material.attr("physxMaterial:frictionCombineMode", "token", "min", uniform=True)
        out[mu] = f"/{WORLD}/PhysicsMaterials/surface_{i}"
    return out


def _collider(
    body_prim: Prim, body: StaticBody, collider: WorldCollider, materials: dict[float, str], findings: Findings
) -> bool:
    """Write one collider; False when it has no USD form (it is left out, with a warning)."""
    shape = collider.shape
    name = _name(collider.name)
    if isinstance(shape, Mesh):
        prim = body_prim.child(name, "Mesh")
        if not _mesh(prim, shape, collider, body, findings):
            del body_prim.children[name]
            return False
        prim.apply("PhysicsMeshCollisionAPI")
        prim.attr("physics:approximation", "token", "none", uniform=True)
    elif isinstance(shape, HeightImage):
        findings.warn(
            "usd-world-height-image",
            "a height image has no USD form yet (USD has no heightfield prim); give the terrain as a mesh",
            element=f"collision {collider.name!r} of {body.name!r}",
            loc=collider.src,
            stage=STAGE,
        )
        return False
    elif isinstance(shape, Box):
        prim = body_prim.child(name, "Cube")
        prim.attr("size", "double", 1.0)
        prim.attr("extent", "float3[]", [(-0.5, -0.5, -0.5), (0.5, 0.5, 0.5)])
        set_pose(prim, pose_frame(collider.origin), scale=shape.size)
    elif isinstance(shape, Sphere):
        prim = body_prim.child(name, "Sphere")
        prim.attr("radius", "double", shape.radius)
    elif isinstance(shape, Cylinder):
        prim = body_prim.child(name, "Cylinder")
        prim.attr("radius", "double", shape.radius)
        prim.attr("height", "double", shape.length)
        prim.attr("axis", "token", "Z", uniform=True)
    elif isinstance(shape, Plane):
        prim = body_prim.child(name, "Plane")
        prim.attr("width", "double", PLANE_SIZE)
        prim.attr("length", "double", PLANE_SIZE)
        prim.attr("axis", "token", "Z", uniform=True)
    else:  # pragma: no cover - the world IR has no other shape
        return False
    if not isinstance(shape, Box):
        set_pose(prim, pose_frame(collider.origin))
    prim.apply("PhysicsCollisionAPI")
    surface = collider.surface
    if surface is not None and surface.mu is not None:
        prim.apply("MaterialBindingAPI")
        prim.rel("material:binding:physics", [materials[surface.mu]])
    return True


def write_world_alone(placed: PlacedWorld, out: str, options: object, findings: Findings, validate: bool) -> WorldAlone:
    """``robodesc compile W.world -t usd``: the world stage, with no robot, at ``out``."""
    count = write_world(out, None, "", placed, [], findings)
    if not validate:
        return {"usd": out}, None
    from robodesc.validation.world import check_usd_world

    return {"usd": out}, check_usd_world(out, placed.world.name, placed.world.physics, count)


def _cords(world: Prim, cords: CordField, anchors: list[Vec3]) -> None:
    """Each cord an articulation: capsule links joined by D6 joints whose translations are locked
    (a spherical joint) and whose three rotations carry a drive to zero, the cord's bending stiffness
    and damping per degree (UsdPhysics' spherical joint has no drive, and PhysX springs a ball joint
    only through D6 drives). The articulation's root is the anchor, a link welded to the world (a
    fixed-base articulation: PhysX makes the joint from the world to the root rigid, so a first
    bending joint there would not bend)."""
    step = cords.length / cords.segments
    mass = cords.cord_mass / cords.segments
    side = mass * (3 * cords.radius**2 + step**2) / 12
    for i, anchor in enumerate(anchors):
        cord = world.child(f"{cords.name}_{i}", "Xform")
        set_pose(cord, Frame(translation=anchor))
        cord.apply("PhysicsArticulationRootAPI")
        cord.apply("PhysxArticulationAPI")
        cord.attr("physxArticulation:enabledSelfCollisions", "bool", False)
        root = cord.child("anchor", "Xform")
        root.apply("PhysicsRigidBodyAPI")
        root.apply("PhysicsMassAPI")
        root.attr("physics:mass", "float", mass)  # immovable: any positive mass
        root.attr("physics:diagonalInertia", "float3", (side, side, side))
        pin = cord.child("pin", "PhysicsFixedJoint")
        pin.attr("physics:localPos0", "point3f", anchor)  # no body0: the world
        pin.rel("physics:body1", [f"/{WORLD}/{cords.name}_{i}/anchor"])
        pin.attr("physics:localPos1", "point3f", (0.0, 0.0, 0.0))
        previous = f"/{WORLD}/{cords.name}_{i}/anchor"
        for k in range(cords.segments):
            link = cord.child(f"s{k}", "Xform")
            set_pose(link, Frame(translation=(0.0, 0.0, -k * step)))
            link.apply("PhysicsRigidBodyAPI")
            link.apply("PhysicsMassAPI")
            link.attr("physics:mass", "float", mass)
            link.attr("physics:centerOfMass", "point3f", (0.0, 0.0, -step / 2))
            link.attr("physics:diagonalInertia", "float3", (side, side, mass * cords.radius**2 / 2))
            shape = link.child("collision", "Capsule")
            shape.attr("radius", "double", cords.radius)
            shape.attr("height", "double", step)
            shape.attr("axis", "token", "Z", uniform=True)
            set_pose(shape, Frame(translation=(0.0, 0.0, -step / 2)))
            shape.apply("PhysicsCollisionAPI")
            joint = cord.child(f"j{k}", "PhysicsJoint")
            joint.rel("physics:body0", [previous])
            joint.attr("physics:localPos0", "point3f", (0.0, 0.0, -step if k else 0.0))
            joint.rel("physics:body1", [f"/{WORLD}/{cords.name}_{i}/s{k}"])
            joint.attr("physics:localPos1", "point3f", (0.0, 0.0, 0.0))
            for axis in ("transX", "transY", "transZ"):
                joint.apply(f"PhysicsLimitAPI:{axis}")  # low above high: locked
                joint.attr(f"limit:{axis}:physics:low", "float", 1.0)
                joint.attr(f"limit:{axis}:physics:high", "float", -1.0)
            for axis in ("rotX", "rotY", "rotZ"):
                joint.apply(f"PhysicsDriveAPI:{axis}")
                joint.attr(f"drive:{axis}:physics:type", "token", "force", uniform=True)
                joint.attr(f"drive:{axis}:physics:stiffness", "float", cords.stiffness * math.pi / 180)
                joint.attr(f"drive:{axis}:physics:damping", "float", cords.damping * math.pi / 180)
                joint.attr(f"drive:{axis}:physics:targetPosition", "float", 0.0)
            previous = f"/{WORLD}/{cords.name}_{i}/s{k}"


def _mesh(prim: Prim, shape: Mesh, collider: WorldCollider, body: StaticBody, findings: Findings) -> bool:
    from robodesc.emit.usd.geometry import author_mesh  # the robot's mesh writer: normals and UVs too
    from robodesc.meshes.buffers import MeshReadError
    from robodesc.meshes.data import build_mesh

    try:
        assert shape.path is not None
        data = build_mesh(shape.path, shape.scale)
    except (MeshReadError, OSError, AssertionError) as exc:
        findings.warn(
            "usd-world-mesh-unreadable",
            f"the terrain mesh cannot be read ({exc}); left out of the world stage",
            element=f"collision {collider.name!r} of {body.name!r}",
            loc=collider.src,
            stage=STAGE,
        )
        return False
    author_mesh(prim, data)
    return True


def _name(text: str) -> str:
    """A prim name from an SDF name (identifiers only)."""
    out = "".join(c if c.isalnum() or c == "_" else "_" for c in text) or "item"
    return out if not out[0].isdigit() else f"_{out}"
