"""``<robot>_physics.usda``: robodesc's physics as overs on the USD Isaac Sim 6's importer writes.

Isaac Sim 6's URDF importer (urdf-usd-converter) authors no derived gains, armature, friction
efforts or scene settings. This layer carries them: sublayered over the importer's USD, it sets
drives and gains, effort and velocity limits, armature and joint friction, masses and inertias,
colliders' approximations, offsets and contact materials, the articulation settings and the
physics scene.

It is not written twice: robodesc's own USD emitter authors its physics layer (the ``Physics``
role of the layered layout, ``emit/usd/layers.py``) in memory, and each of its prims is moved onto
the importer's path for the same link, joint or collider (``importer_layout.py``) as an ``over``.
What is dropped, and why: ``physics:body0/1`` (the importer's joints already name its bodies) and
robodesc's base weld (the importer writes its own ``root_joint``); Isaac's robot schema lists
(robodesc's paths). A floating robot's articulation root is the root link in both layouts; for a
fixed base the layer deletes the importer's root API from the base link and applies it to the robot
prim, where robodesc puts it (one root: two would be two articulations). A prim the layout does not
have is left out and named in the result.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass, field

from robodesc.emit.isaac.importer_layout import ImporterLayout
from robodesc.emit.usd import PhysicsOpinions, UsdOptions, physics_opinions
from robodesc.ir.diagnostics import Findings
from robodesc.ir.model import Robot
from robodesc.usdfile.spec import Layer, Prim, Relationship

# Opinions the importer's prims already hold, or that name robodesc's own paths.
_DROPPED_PROPERTIES = ("physics:body0", "physics:body1", "isaac:physics:robotLinks", "isaac:physics:robotJoints")
_DROPPED_SCHEMAS = ("PhysicsArticulationRootAPI", "IsaacRobotAPI", "IsaacLinkAPI", "IsaacJointAPI")


@dataclass
class PhysicsLayer:
    layer: Layer
    robot: str  # the importer's robot prim
    materials: str  # the importer-side scope of robodesc's contact materials
    materials_source: str  # robodesc's scope of them
    articulation_root: str | None  # where the importer put the articulation root
    instanced: set[str] = field(default_factory=set)  # importer colliders inside instances
    instance_shapes: dict[str, list[str]] = field(default_factory=dict)  # ImporterLayout.instance_shapes
    instance_roots: dict[str, list[str]] = field(default_factory=dict)  # ImporterLayout.instance_roots
    # robodesc's materials that say only what PhysX assumes unbound (friction 0.5): losing their
    # binding on an instanced collider changes nothing.
    default_materials: set[str] = field(default_factory=set)
    missing: list[str] = field(default_factory=list)  # "link 'x'", "joint 'y'", ... the layout lacks
    # Importer paths the layer defines rather than overs: prims the import lacks (loop closures).
    defined: set[str] = field(default_factory=set)
    prims: int = 0  # prims of robodesc's physics that found their place


def physics_layer(robot: Robot, options: UsdOptions, layout: ImporterLayout, findings: Findings) -> PhysicsLayer:
    ours = physics_opinions(robot, options, Findings())
    source, robot_path = ours.layer, ours.robot_path
    out = Layer(default_prim=layout.robot.lstrip("/"), meters_per_unit=1.0, kilograms_per_unit=1.0, up_axis="Z")
    result = PhysicsLayer(
        out,
        layout.robot,
        f"{layout.robot}/{ours.materials_scope}",
        f"{robot_path}/{ours.materials_scope}",
        layout.articulation_root,
        layout.instanced,
        layout.instance_shapes,
        layout.instance_roots,
    )
    if layout.articulation_root is None:
        result.missing.append("the articulation root")
    mapping = _path_map(robot, ours, layout, result)
    mapping[f"{robot_path}/{ours.materials_scope}"] = result.materials
    scope = source.find(f"{robot_path}/{ours.materials_scope}")
    for name, material in scope.children.items() if scope is not None else ():
        values = {k: getattr(v, "value", None) for k, v in material.properties.items()}
        if values == {"physics:staticFriction": 0.5, "physics:dynamicFriction": 0.5}:
            result.default_materials.add(f"{robot_path}/{ours.materials_scope}/{name}")
    top = source.find(robot_path)
    if top is not None:
        _move(top, robot_path, mapping, out, result)
    _display_names(robot, layout, out)
    _unlimit_followers(robot, mapping, f"{robot_path}/{ours.joints_scope}", out)
    if ours.scene is not None:
        out.root.children["PhysicsScene"] = ours.scene
    return result


def _display_names(robot: Robot, layout: ImporterLayout, out: Layer) -> None:
    """The source's names, as robodesc's USD keeps them (``displayName``): the Isaac URDF carries
    the sanitized ones (Spirit's joints ``0``..``11`` are ``a0``..``a11``), so the importer's prims
    lack them, and whatever finds a joint by the source's name (``validate --dynamics``' pose table,
    Isaac Sim's stage tree) missed every one of Spirit's and Go2's joints on the composed stage."""
    for elements, paths in ((robot.links, layout.links), (robot.joints, layout.joints)):
        for element in elements:
            where = paths.get(element.name)
            if where is not None and element.display_name and element.display_name != where.rsplit("/", 1)[-1]:
                out.prim(where, specifier="over").display_name = element.display_name


def _unlimit_followers(robot: Robot, mapping: Mapping[str, str], joints: str, out: Layer) -> None:
    """The importer gives a mimic follower its URDF velocity limit (``newton:velocityLimit``, which
    ovphysx reads); robodesc writes none there (emit/usd/joints.py: PhysX runs away with one), so
    the layer lifts it: inf is NewtonJointAPI's "unlimited" (its range is (0, inf])."""
    by_name = robot.joint_map()
    for joint in robot.joints:
        leader = by_name.get(joint.mimic.joint) if joint.mimic is not None else None
        theirs = mapping.get(f"{joints}/{joint.name}")
        if leader is None or leader.type.dof != 1 or joint.type.dof != 1 or theirs is None:
            continue
        if joint.limit is None or not (joint.limit.velocity or 0.0) > 0:
            continue  # the importer writes none either
        prim = out.prim(theirs, specifier="over")
        prim.apply("NewtonJointAPI")
        prim.attr("newton:velocityLimit", "float", math.inf)


def _path_map(robot: Robot, source: PhysicsOpinions, layout: ImporterLayout, result: PhysicsLayer) -> dict[str, str]:
    """robodesc's prim path -> the importer's, for every prim that carries physics."""
    robot_path = source.robot_path
    missing = result.missing
    mapping: dict[str, str] = {}
    for link in robot.links:
        ours = f"{robot_path}/{link.name}"
        theirs = layout.links.get(link.name)
        if theirs is None:
            missing.append(f"link {link.name!r}")
            continue
        mapping[ours] = theirs
        colliders = layout.colliders.get(link.name, [])
        for index in range(len(link.collisions)):
            # robodesc names its collider prims in IR order; the importer's list is in the same order.
            if index < len(colliders) and colliders[index]:
                mapping[f"{ours}/collisions/#{index}"] = colliders[index]
            elif index < len(colliders):
                missing.append(
                    f"collision {index} of link {link.name!r} (the importer transcodes its name, which the "
                    "naming rules do not reproduce: robodesc layer --onto the import reads it)"
                )
            else:
                missing.append(f"collision {index} of link {link.name!r}")
    for joint in robot.joints:
        theirs = layout.joints.get(joint.name)
        if theirs is None:
            missing.append(f"joint {joint.name!r}")
        else:
            mapping[f"{robot_path}/{source.joints_scope}/{joint.name}"] = theirs
    # Isaac Sim 6.2's importer drops <loop_joint> (urdf-usd-converter reads no such tag: its import of
    # the four-bar has no closure), so the chain arrives open and its drives carry the load the
    # closure would (the four-bar's crank at 42 % of its effort instead of 3.5 %, in PhysX). The
    # layer defines the closure beside the importer's joints, between the importer's bodies, as
    # robodesc's USD has it (outside the articulation); link frames are the URDF's in both layouts.
    scope = _joints_scope(layout)
    taken = {path.rsplit("/", 1)[-1] for path in layout.joints.values()} | {"root_joint"}
    for loop in robot.loop_joints:
        ends = [layout.links.get(side.link) for side in (loop.link1, loop.link2)]
        if None in ends or loop.name in taken:
            why = "a link it joins is not in the import" if None in ends else "the import has a joint of that name"
            missing.append(f"loop joint {loop.name!r} ({why})")
            continue
        target = f"{scope}/{loop.name}"
        mapping[f"{robot_path}/{source.loops_scope}/{loop.name}"] = target
        result.defined.add(target)
    return mapping


def _joints_scope(layout: ImporterLayout) -> str:
    """Where the importer puts joints: beside the ones it wrote, else its ``/<robot>/Physics``."""
    for path in layout.joints.values():
        return path.rsplit("/", 1)[0]
    return f"{layout.robot}/Physics"


def _move(prim: Prim, path: str, mapping: Mapping[str, str], out: Layer, result: PhysicsLayer) -> None:
    """Carry ``prim``'s opinions (and its children's) to their importer paths."""
    if "PhysicsArticulationRootAPI" in prim.api_schemas:
        root = result.articulation_root
        if root is not None and "/" not in path[1:] and root != result.robot:
            # A fixed base: robodesc roots the articulation at the robot prim, above the weld to the
            # world; the importer roots it at the base link, and PhysX then floats the base (read in
            # ovphysx 0.7: isFixedBase 0 for the imported gripper arm and panda). Moved.
            moved = out.prim(root, specifier="over")
            moved.deleted_api_schemas += ["PhysicsArticulationRootAPI", "NewtonArticulationRootAPI"]
            root = result.robot
            out.prim(root, specifier="over").apply("PhysicsArticulationRootAPI")
        if root is not None:
            _over(prim, out.prim(root, specifier="over"), mapping, result)
    elif (target := mapping.get(path) or _remap(path, {result.materials_source: result.materials})) in result.instanced:
        extra = _beyond_importer(prim, result.default_materials)
        shapes = result.instance_shapes.get(target or "")
        if extra and shapes and target is not None:
            # Read from the import: the collider is made not instanceable, so the shapes inside
            # become prims of the stage, and each takes robodesc's collider opinions (Talos' sole
            # friction 0.9 and rest offset, which PhysX read as 0.5 and 0 on the instance).
            for root in result.instance_roots.get(target, [target]):
                out.prim(root, specifier="over").instanceable = False
            for shape in shapes:
                _over(prim, out.prim(shape, specifier="over"), mapping, result)
        elif extra:
            result.missing.append(
                f"{path.rsplit('/collisions/', 1)[0].rsplit('/', 1)[-1]}'s mesh collider {target} "
                f"({', '.join(extra)}: inside an instance the importer made; the naming rules cannot name "
                "its shapes, robodesc layer --onto the import reads them)"
            )
        else:
            result.prims += 1  # the importer already authors exactly this
    elif target is not None:
        # Prims robodesc adds (its contact materials, loop closures) are defined; everything else
        # is an over.
        new = prim.specifier == "def" and (target.startswith(result.materials) or target in result.defined)
        made = out.prim(target, prim.type_name if new else "", "def" if new else "over")
        _over(prim, made, mapping, result, keep_bodies=new)
    for index, (name, child) in enumerate(prim.children.items()):
        # Colliders by their place in the link (the importer's names are its own).
        _move(child, f"{path}/#{index}" if path.endswith("/collisions") else f"{path}/{name}", mapping, out, result)


def _beyond_importer(collider: Prim, default_materials: set[str]) -> list[str]:
    """What robodesc's collider says beyond the importer's own (CollisionAPI, convexHull)."""
    # A contact material bound on the instance's root does not reach the meshes inside: ovphysx 0.7
    # read Talos' and Stretch's bound friction (0.9, 0) as its default 0.5 that way.
    binding = collider.properties.get("material:binding:physics")
    plain = isinstance(binding, Relationship) and set(binding.targets) <= default_materials
    handled = ("PhysicsCollisionAPI", "PhysicsMeshCollisionAPI", *(("MaterialBindingAPI",) if plain else ()))
    extra = [s for s in collider.api_schemas if s not in handled]
    for name, prop in collider.properties.items():
        if name == "material:binding:physics" and plain:
            continue
        if name == "physics:approximation" and getattr(prop, "value", None) == "convexHull":
            continue
        extra.append(name)
    return extra


def _over(
    source: Prim, target: Prim, mapping: Mapping[str, str], result: PhysicsLayer, *, keep_bodies: bool = False
) -> None:
    """``source``'s opinions on ``target``; a joint the layer defines (``keep_bodies``) keeps its
    bodies, moved to the importer's paths, where the importer's own joints name theirs."""
    result.prims += 1
    for schema in source.api_schemas:
        if schema not in _DROPPED_SCHEMAS:
            target.apply(schema)
    for name, prop in source.properties.items():
        if name in _DROPPED_PROPERTIES and not (keep_bodies and name.startswith("physics:body")):
            continue
        if isinstance(prop, Relationship):
            targets = [_remap(t, mapping) for t in prop.targets]
            target.rel(name, [t for t in targets if t is not None], custom=prop.custom)
        else:
            target.properties[name] = prop


def _remap(path: str, mapping: Mapping[str, str]) -> str | None:
    for ours, theirs in mapping.items():
        if path == ours or path.startswith(ours + "/"):
            return theirs + path[len(ours) :]
    return None
