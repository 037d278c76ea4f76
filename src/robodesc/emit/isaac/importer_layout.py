"""Where Isaac Sim 6's URDF importer puts each link, joint and collider.

Isaac Sim 6.2's importer is urdf-usd-converter 0.3; measured on its output for the example
quadruped and gripper arm (and read in its ``_impl/link.py``, ``utils.py``, ``convert.py``)::

    /<robot name>                           default prim (the URDF's <robot name>, made a valid name)
        /Geometry/<root link>/<child link>/...  links nested along the tree, in URDF order
            <link>/<visual or collision>    the link's visuals, then its collisions (a mesh file: an
                                            instanced Xform, CollisionAPI and convexHull on the
                                            meshes inside), named by the
                                            element's name, else the mesh file's stem, else the shape
                                            tag (box, sphere, cylinder, capsule), made unique among
                                            the link prim's children ("box", "box_1"); claimed
                                            before the child links' names
        /Physics/<joint>                    every joint, plus root_joint (the base weld) first
    the articulation root: the root link's prim, fixed base or not

Names are made unique with ``_1``, ``_2`` ... (usdex's ``NameCache``). A layout is either computed
by these rules from the IR (:func:`layout_from_rules`) or read from an imported USD
(:func:`layout_from_usd`, which needs usd-core); the physics layer (``physics_layer.py``) addresses
prims only through it.
"""

from __future__ import annotations

import os
import re
from dataclasses import dataclass, field
from typing import Any

from robodesc.ir.geometry import Box, Capsule, Cylinder, Mesh, Sphere
from robodesc.ir.model import Collision, Robot, Visual


@dataclass
class ImporterLayout:
    robot: str  # the default prim's path
    links: dict[str, str] = field(default_factory=dict)  # IR link name -> prim path
    joints: dict[str, str] = field(default_factory=dict)  # IR joint name -> prim path
    # link -> collider paths, IR order; "" where the rules cannot name the importer's prim
    colliders: dict[str, list[str]] = field(default_factory=dict)
    articulation_root: str | None = None
    # Colliders whose shapes the importer puts inside an instance (mesh files): a layer cannot edit
    # instance proxies, so only what the importer itself authors there (CollisionAPI, convexHull) holds.
    instanced: set[str] = field(default_factory=set)
    # Read from an import only (the rules cannot name what a mesh file puts inside): each instanced
    # collider's shapes, the prims inside it with PhysicsCollisionAPI. A layer that makes the
    # collider not instanceable can then address them.
    instance_shapes: dict[str, list[str]] = field(default_factory=dict)
    # The instances to make not instanceable so those shapes become editable: the collider itself,
    # or, for a mesh file of several meshes (HyQ's trunk.dae), the instances inside its plain group.
    instance_roots: dict[str, list[str]] = field(default_factory=dict)
    source: str = "rules"  # "rules", or the imported USD read


def _unique(name: str, used: set[str]) -> str:
    """usdex's NameCache: the name itself when free, else the first free ``name_N`` (N from 1)."""
    if name not in used:
        used.add(name)
        return name
    index = 1
    while f"{name}_{index}" in used:
        index += 1
    used.add(f"{name}_{index}")
    return f"{name}_{index}"


# A name the importer keeps as it is; any other it transcodes (usdex's getValidPrimName: iCub's mesh
# stem "sim_sea_2-5_lap_belt_1_prt-binary" became "tn__sim_sea_25_lap_belt_1_prtbinary_1_pm0Q"),
# which these rules do not reproduce.
_IDENTIFIER = re.compile(r"[A-Za-z_][A-Za-z0-9_]*")


def _geometry_name(item: Visual | Collision) -> str:
    if item.name:
        return item.name
    geometry = item.geometry
    if isinstance(geometry, Mesh):
        return os.path.splitext(os.path.basename(geometry.uri))[0]
    tags = {Box: "box", Sphere: "sphere", Cylinder: "cylinder", Capsule: "capsule"}
    return next((tag for kind, tag in tags.items() if isinstance(geometry, kind)), "geometry")


def layout_from_rules(robot: Robot) -> ImporterLayout:
    """The paths the importer gives the robot robodesc writes as the folder's URDF (names already
    valid identifiers: the Isaac preset sanitizes them)."""
    layout = ImporterLayout(robot=f"/{robot.name}")
    children: dict[str, list[str]] = {}
    for joint in robot.joints:
        children.setdefault(joint.parent, []).append(joint.child)
    links = robot.link_map()
    stack = [(robot.root.name, f"{layout.robot}/Geometry", set[str]())]
    while stack:
        name, parent, used = stack.pop()
        path = f"{parent}/{_unique(name, used)}"
        layout.links[name] = path
        link = links[name]
        own: set[str] = set()
        for visual in link.visuals:
            _unique(_geometry_name(visual), own)
        # "" where the importer transcodes the name: no path is predicted rather than a wrong one.
        named = [_unique(_geometry_name(c), own) for c in link.collisions]
        layout.colliders[name] = [f"{path}/{n}" if _IDENTIFIER.fullmatch(n) else "" for n in named]
        layout.instanced.update(
            p
            for p, c in zip(layout.colliders[name], link.collisions, strict=True)
            if p and isinstance(c.geometry, Mesh)
        )
        # Reversed onto the stack so the children are named in URDF order.
        stack.extend((child, path, own) for child in reversed(children.get(name, [])))
    layout.articulation_root = layout.links[robot.root.name]
    used_joints = {"root_joint"}
    for joint in robot.joints:
        layout.joints[joint.name] = f"{layout.robot}/Physics/{_unique(joint.name, used_joints)}"
    return layout


def _within(group: Any) -> list[Any]:
    """The prims under ``group`` (instance proxies included), not entering another rigid body."""
    from pxr import Usd, UsdPhysics

    out = []
    walk = iter(Usd.PrimRange(group, Usd.TraverseInstanceProxies()))
    for prim in walk:
        if prim != group and prim.HasAPI(UsdPhysics.RigidBodyAPI):
            walk.PruneChildren()
            continue
        out.append(prim)
    return out


def _up_to(prim: Any, top: Any) -> list[Any]:
    """``prim`` and its ancestors up to ``top``, both included."""
    chain = [prim]
    while chain[-1] != top and chain[-1].GetPath() != top.GetPath():
        chain.append(chain[-1].GetParent())
    return chain


def layout_from_usd(path: str, robot: Robot) -> ImporterLayout:
    """Read the layout from an imported USD (its ``physx`` variant selected when it has the
    importer's ``Physics`` variant set): links are its rigid bodies, joints its joint prims, both
    matched to the IR by prim name or displayName; colliders the children of each link prim with
    ``PhysicsCollisionAPI``, or instances with it inside (mesh files), in order."""
    from pxr import Usd, UsdPhysics

    stage = Usd.Stage.Open(path)
    default = stage.GetDefaultPrim()
    if not default:
        default = next(iter(stage.GetPseudoRoot().GetChildren()), None)
    if default is None:
        return ImporterLayout(robot="/", source=path)
    variants = default.GetVariantSets()
    if variants.HasVariantSet("Physics") and "physx" in variants.GetVariantSet("Physics").GetVariantNames():
        variants.GetVariantSet("Physics").SetVariantSelection("physx")
    layout = ImporterLayout(robot=str(default.GetPath()), source=path)
    link_names = {link.name for link in robot.links}
    joint_names = {joint.name for joint in robot.joints}
    for prim in Usd.PrimRange(default):
        keys = (prim.GetName(), prim.GetDisplayName())
        if prim.HasAPI(UsdPhysics.RigidBodyAPI):
            name = next((k for k in keys if k in link_names), None)
            if name is not None and name not in layout.links:
                layout.links[name] = str(prim.GetPath())
                layout.colliders[name] = []
                for child in prim.GetChildren():
                    if child.HasAPI(UsdPhysics.CollisionAPI):
                        layout.colliders[name].append(str(child.GetPath()))
                    elif not child.HasAPI(UsdPhysics.RigidBodyAPI):
                        # An instance holding the shapes (a mesh file), or a plain group of
                        # instances (a mesh file of several meshes); a child link is a body.
                        shapes = [p for p in _within(child) if p.HasAPI(UsdPhysics.CollisionAPI)]
                        if shapes:
                            where = str(child.GetPath())
                            layout.colliders[name].append(where)
                            layout.instanced.add(where)
                            layout.instance_shapes[where] = [str(p.GetPath()) for p in shapes]
                            roots = {str(a.GetPath()) for p in shapes for a in _up_to(p, child) if a.IsInstance()}
                            layout.instance_roots[where] = sorted(roots)
        elif prim.IsA(UsdPhysics.Joint):
            name = next((k for k in keys if k in joint_names), None)
            if name is not None and name not in layout.joints:
                layout.joints[name] = str(prim.GetPath())
        if prim.HasAPI(UsdPhysics.ArticulationRootAPI) and layout.articulation_root is None:
            layout.articulation_root = str(prim.GetPath())
    return layout
