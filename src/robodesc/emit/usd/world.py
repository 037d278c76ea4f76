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
from typing import TYPE_CHECKING, Any

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
    from robodesc.ir.model import Robot

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
    robot_mu: float = 1.0,
) -> dict[str, Any]:
    """Write the world stage to ``path``; ``robot_file`` is the robot's final file name beside it,
    brought in once per root (several copies: one payload each, ``/World/<robot>_<i>``). No
    ``roots``: the world alone (a world file as the input). ``robot_mu``: the robot's highest
    friction (:func:`_terrain_material`). Returns what a reader must find in it
    (validation/world_check.py, validation/world.py)."""
    from robodesc._files import write_atomic

    layer, world, count, terrains = _ground(placed, findings, robot_mu)
    _scene(world, placed, contacts)
    for cords, anchors in placed.cords:
        _cords(world, cords, anchors)
    turn = rpy_rotation((0.0, 0.0, placed.yaw))
    names = copy_names(robot_prim, len(roots)) if roots else []
    for name, root in zip(names, roots, strict=True):
        assert robot_file is not None
        robot = world.child(name, "Xform")
        robot.payloads.append(Payload(f"./{os.path.basename(robot_file)}", f"/{robot_prim}"))
        set_pose(robot, Frame(translation=root, rotation=turn))
    write_atomic(path, encode(layer, os.path.splitext(path)[1].lower()))
    gravity = placed.world.physics.gravity or (0.0, 0.0, -9.81)
    return {
        "gravity": math.sqrt(sum(g * g for g in gravity)),
        "colliders": count,
        "terrains": terrains,
        # The first copy: the one the checks find at its spawn.
        "robot": f"/{WORLD}/{names[0]}" if names else None,
        "payload_prim": f"/{robot_prim}",
        "root": tuple(roots[0]) if roots else None,
    }


def write_terrain(path: str, placed: PlacedWorld, findings: Findings, robot_mu: float = 1.0) -> None:
    """The world's ground alone (static bodies and their friction; no scene, robot or cords): what
    Isaac Lab's ``TerrainImporterCfg(terrain_type="usd")`` references under its own prim, beside the
    ``PhysicsScene`` its ``SimulationCfg`` makes."""
    from robodesc._files import write_atomic

    layer = _ground(placed, findings, robot_mu)[0]
    write_atomic(path, encode(layer, os.path.splitext(path)[1].lower()))


def robot_friction(robot: Robot) -> float:
    """The robot's highest given friction, at least 1 (ODE's and Newton's default where it gives none)."""
    given = [
        contact.mu
        for link in robot.links
        for c in link.collisions
        if (contact := link.collision_contact(c)) is not None and contact.mu is not None
    ]
    return max([1.0, *given])


def _ground(placed: PlacedWorld, findings: Findings, robot_mu: float) -> tuple[Layer, Prim, int, dict[str, int]]:
    """A layer whose default prim ``/World`` holds the world's static bodies and their materials;
    the number of colliders it holds, and each terrain mesh's prim with its triangle count."""
    layer = Layer()
    stage_metadata(layer, WORLD)
    world = layer.prim(f"/{WORLD}", "Xform")
    world.kind = "assembly"
    material = _terrain_material(world, placed, robot_mu, findings)
    if not placed.world.bodies:  # a world of cords alone: a ground plane under them
        ground = world.child("ground", "Plane")
        ground.attr("width", "double", PLANE_SIZE)
        ground.attr("length", "double", PLANE_SIZE)
        ground.attr("axis", "token", "Z", uniform=True)
        ground.apply("PhysicsCollisionAPI")
    count = 0 if placed.world.bodies else 1
    terrains: dict[str, int] = {}
    for body in placed.world.bodies:
        body_prim = world.child(_name(body.name), "Xform")
        set_pose(body_prim, pose_frame(body.pose))
        for collider in body.colliders:
            written, triangles = _collider(body_prim, body, collider, material, findings)
            count += written
            if triangles:
                terrains[terrain_prim(body.name, collider.name)] = triangles
    return layer, world, count, terrains


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


def _terrain_material(world: Prim, placed: PlacedWorld, robot_mu: float, findings: Findings) -> dict[float, str]:
    """One physics material per distinct world friction, combining by the minimum (ODE's rule).

    A world friction above the robot's highest (``robot_mu``: its colliders' largest given one, at
    least 1) is written as that: PhysX's minimum gives every robot collider its own friction either
    way, and Newton, which reads no combine mode and hands both to MuJoCo's maximum, gets the robot's
    friction instead of Quad-SDK's 100, at which its soft contacts let the robot sink through the
    terrain (measured: a robot and two boxes fell through gap_40cm's slab)."""
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
        written = min(mu, robot_mu)
        if written < mu:
            findings.info(
                "usd-world-friction",
                f"the world's mu {mu:g} is written as {written:g}, the robot's highest: PhysX combines by the minimum "
                f"either way, and Newton (MuJoCo's maximum) gets the robot's friction, not {mu:g}",
                element=f"material surface_{i}",
                stage=STAGE,
            )
        material = scope.child(f"surface_{i}", "Material")
        material.apply("PhysicsMaterialAPI")
        material.attr("physics:staticFriction", "float", written)
        material.attr("physics:dynamicFriction", "float", written)
        material.apply("PhysxMaterialAPI")
        material.attr("physxMaterial:frictionCombineMode", "token", "min", uniform=True)
        out[mu] = f"/{WORLD}/PhysicsMaterials/surface_{i}"
    return out


def _collider(
    body_prim: Prim, body: StaticBody, collider: WorldCollider, materials: dict[float, str], findings: Findings
) -> tuple[bool, int]:
    """Write one collider: whether it was written (False: it has no USD form and is left out, with a
    warning), and a terrain mesh's triangle count (0 for any other shape)."""
    shape = collider.shape
    name = _name(collider.name)
    triangles = 0
    if isinstance(shape, Mesh):
        prim = body_prim.child(name, "Mesh")
        triangles = _mesh(prim, shape, collider, body, findings)
        if not triangles:
            del body_prim.children[name]
            return False, 0
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
        return False, 0
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
        return False, 0
    if not isinstance(shape, Box):
        set_pose(prim, pose_frame(collider.origin))
    prim.apply("PhysicsCollisionAPI")
    surface = collider.surface
    if surface is not None and surface.mu is not None:
        prim.apply("MaterialBindingAPI")
        prim.rel("material:binding:physics", [materials[surface.mu]])
    return True, triangles


def write_world_alone(placed: PlacedWorld, out: str, options: object, findings: Findings, validate: bool) -> WorldAlone:
    """``robodesc compile W.world -t usd``: the world stage, with no robot, at ``out``."""
    count = write_world(out, None, "", placed, [], findings)["colliders"]
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


def _mesh(prim: Prim, shape: Mesh, collider: WorldCollider, body: StaticBody, findings: Findings) -> int:
    """The mesh's points and triangles on ``prim``; returns the triangle count (0: unreadable)."""
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
        return 0
    _newton_hull(data.points, data.face_vertex_indices, collider, body, findings)
    author_mesh(prim, data)
    return len(data.face_vertex_counts)


def _newton_hull(points: Any, indices: Any, collider: WorldCollider, body: StaticBody, findings: Findings) -> None:
    """A concave terrain mesh: Newton's MuJoCo solver collides it as its convex hull (docs/worlds.md,
    "Newton and the USD terrain"); PhysX honours every triangle."""
    import numpy as np
    import trimesh

    v = np.frombuffer(points, dtype=np.float32).reshape(-1, 3)
    f = np.frombuffer(indices, dtype=np.int32).reshape(-1, 3)
    if trimesh.Trimesh(v, f, process=True).is_convex:
        return
    findings.warn(
        "usd-world-newton-hull",
        "the terrain is concave: Newton's MuJoCo solver (SolverMuJoCo) collides a mesh as its convex hull, so in "
        "Newton it fills gaps and steps (PhysX and Isaac Sim honour every triangle). Give Newton the terrain as a "
        "heightfield (ModelBuilder.add_shape_heightfield), as validate --dynamics does (docs/worlds.md)",
        element=f"collision {collider.name!r} of {body.name!r}",
        loc=collider.src,
        stage=STAGE,
    )


def terrain_prim(body: str, collider: str) -> str:
    """The path of a world collider's prim in the world stage."""
    return f"/{WORLD}/{_name(body)}/{_name(collider)}"


def _name(text: str) -> str:
    """A prim name from an SDF name (identifiers only)."""
    out = "".join(c if c.isalnum() or c == "_" else "_" for c in text) or "item"
    return out if not out[0].isdigit() else f"_{out}"
