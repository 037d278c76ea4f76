"""An SDF world (SDF 1.4 to 1.11) read into :class:`~robodesc.ir.world.World`.

What a robot needs from its world is read: the physics (step, iterations, gravity), every static
model's colliders (mesh, box, cylinder, sphere, plane) with their friction, and the includes. What
is not read is named in a finding, never dropped silently: dynamic models, heightmap geometry (its
image is read by ``--terrain`` instead), plugins, lights and the GUI are visual or engine-specific.
A missing include is a warning: the world compiles without it.
"""

from __future__ import annotations

import os
from collections.abc import Sequence

import numpy as np
from lxml import etree

from robodesc.frontends.sdf.model_path import model_roots, resolve_uri
from robodesc.frontends.sdf.shapes import primitive
from robodesc.frontends.sdf.values import loc as _loc
from robodesc.frontends.sdf.values import number as _number
from robodesc.frontends.sdf.values import pose_value
from robodesc.frontends.sdf.values import positive as _positive
from robodesc.frontends.sdf.values import tag as _tag
from robodesc.frontends.sdf.values import vec3 as _vec3
from robodesc.frontends.xml_safety import parse_xml, read_file
from robodesc.ir.diagnostics import Findings, ParseError, UnsupportedError
from robodesc.ir.geometry import Box, Cylinder, Mesh, Pose, Sphere
from robodesc.ir.transforms import matrix_pose, pose_matrix
from robodesc.ir.world import Include, Plane, StaticBody, Surface, World, WorldCollider, WorldPhysics

STAGE = "frontend:world"
# Elements of a <world> that hold nothing a robot's physics needs: skipped with one info finding.
_VISUAL_ONLY = {"scene", "gui", "light", "atmosphere", "spherical_coordinates", "audio", "wind"}


def read_sdf_world(path: str, findings: Findings, model_path: Sequence[str] = ()) -> World:
    root = parse_xml(read_file(path), path, findings)
    if _tag(root) != "sdf":
        raise ParseError(f"root element is <{_tag(root)}>, expected <sdf>", loc=_loc(path, root))
    worlds = [c for c in root if _tag(c) == "world"]
    if not worlds:
        raise ParseError("an SDF world file needs a <world> element", loc=_loc(path, root))
    if len(worlds) > 1:
        findings.warn(
            "world-several",
            f"{len(worlds)} <world> elements; the first, {worlds[0].get('name')!r}, is read",
            loc=_loc(path, worlds[1]),
            stage=STAGE,
        )
    element = worlds[0]
    world = World(name=element.get("name") or "default", file=path, src=_loc(path, element))
    roots = model_roots(path, model_path)
    skipped: list[str] = []
    for child in element:
        tag = _tag(child)
        if tag == "physics":
            world.physics = _physics(path, child, world.physics)
        elif tag == "gravity":
            world.physics.gravity = _vec3(path, child)
        elif tag == "model":
            body = _model(path, child, findings, roots)
            if body is not None:
                world.bodies.append(body)
        elif tag == "include":
            world.includes.append(_include(path, child, findings, roots))
        elif tag in _VISUAL_ONLY or tag == "plugin":
            skipped.append(tag)
    if skipped:
        findings.info(
            "world-visual-skipped",
            "not read (lights, scene and GUI settings are each viewer's own; plugins run only in "
            f"Gazebo): {', '.join(sorted(set(skipped)))}",
            element=f"world {world.name!r}",
            loc=world.src,
            stage=STAGE,
        )
    return world


def _physics(path: str, element: etree._Element, physics: WorldPhysics) -> WorldPhysics:
    physics.engine = element.get("type") or physics.engine
    physics.src = _loc(path, element)
    step = element.find("max_step_size")
    if step is not None:
        physics.step = _positive(path, step)
    for engine in ("ode", "bullet", "dart", "simbody"):
        iters = element.find(f"{engine}/solver/iters")
        if iters is not None:
            physics.iterations = int(_positive(path, iters))
    gravity = element.find("gravity")  # SDF 1.4 and 1.5 keep gravity inside <physics>
    if gravity is not None:
        physics.gravity = _vec3(path, gravity)
    return physics


def _include(path: str, element: etree._Element, findings: Findings, roots: Sequence[str]) -> Include:
    uri_el = element.find("uri")
    uri = (uri_el.text or "").strip() if uri_el is not None else ""
    name_el = element.find("name")
    pose_el = element.find("pose")
    inc = Include(
        uri=uri,
        name=(name_el.text or "").strip() if name_el is not None else None,
        pose=_pose(path, pose_el) if pose_el is not None else None,
        src=_loc(path, element),
    )
    inc.path = resolve_uri(uri, path, roots) if uri else None
    if inc.path is None:
        findings.warn(
            "world-include-missing",
            f"{uri!r} is not in the model path ({os.pathsep.join(roots)}); the world is compiled without it, so "
            "no target has what it held (add its folder with --model-path, or GAZEBO_MODEL_PATH)",
            element="include",
            loc=inc.src,
            stage=STAGE,
        )
    return inc


def _model(path: str, element: etree._Element, findings: Findings, roots: Sequence[str]) -> StaticBody | None:
    name = element.get("name") or "model"
    static = (element.findtext("static") or "").strip().lower() in ("1", "true")
    if not static:
        findings.warn(
            "world-dynamic-model",
            "is not static; worlds hold static bodies only, so it is left out of every target "
            "(compile it as a robot of its own)",
            element=f"model {name!r}",
            loc=_loc(path, element),
            stage=STAGE,
        )
        return None
    model_pose = pose_matrix(_pose(path, element.find("pose")))
    body = StaticBody(name=name, pose=matrix_pose(model_pose), src=_loc(path, element))
    links = [c for c in element if _tag(c) == "link"]
    for link in links:
        link_pose = model_pose @ pose_matrix(_pose(path, link.find("pose")))
        for collision in link.findall("collision"):
            collider = _collider(path, collision, findings, roots)
            if collider is None:
                continue
            # Colliders carry their link's pose in the model's frame, so a model of several links
            # stays one static body.
            in_model = np.linalg.solve(model_pose, link_pose) @ pose_matrix(collider.origin)
            collider.origin = matrix_pose(in_model)
            body.colliders.append(collider)
    return body


def _collider(path: str, element: etree._Element, findings: Findings, roots: Sequence[str]) -> WorldCollider | None:
    name = element.get("name") or "collision"
    geometry = element.find("geometry")
    loc = _loc(path, element)
    if geometry is None or len(geometry) == 0:
        findings.warn("world-no-geometry", "has no geometry; left out", element=f"collision {name!r}", loc=loc)
        return None
    shape_el = geometry[0]
    kind = _tag(shape_el)
    shape: Box | Cylinder | Sphere | Mesh | Plane
    solid = primitive(path, shape_el) if kind in ("box", "sphere", "cylinder") else None
    if isinstance(solid, Box | Cylinder | Sphere):
        shape = solid
    elif kind == "plane":
        normal = shape_el.find("normal")
        shape = Plane(_vec3(path, normal) if normal is not None else (0.0, 0.0, 1.0), src=loc)
    elif kind == "mesh":
        uri = (shape_el.findtext("uri") or "").strip()
        scale_el = shape_el.find("scale")
        resolved = resolve_uri(uri, path, roots)
        if resolved is None or not os.path.isfile(resolved):
            findings.warn(
                "world-mesh-missing",
                f"mesh {uri!r} is not in the model path ({os.pathsep.join(roots)}); the collider is left out",
                element=f"collision {name!r}",
                loc=loc,
                stage=STAGE,
            )
            return None
        shape = Mesh(uri=uri, scale=_vec3(path, scale_el) if scale_el is not None else None, path=resolved, src=loc)
    else:
        findings.warn(
            "world-geometry-unsupported",
            f"<{kind}> geometry is not read from a world file; left out (a heightmap's image is read with "
            "--terrain IMAGE --terrain-size X Y Z)",
            element=f"collision {name!r}",
            loc=loc,
            stage=STAGE,
        )
        return None
    return WorldCollider(
        name=name,
        shape=shape,
        origin=_pose(path, element.find("pose")),
        surface=_surface(path, element.find("surface")),
        src=loc,
    )


def _surface(path: str, element: etree._Element | None) -> Surface | None:
    if element is None:
        return None
    ode = element.find("friction/ode")
    if ode is None:
        return None
    mu, mu2 = ode.find("mu"), ode.find("mu2")
    if mu is None and mu2 is None:
        return None
    return Surface(
        mu=_number(path, mu) if mu is not None else None,
        mu2=_number(path, mu2) if mu2 is not None else None,
        src=_loc(path, ode),
    )


def _pose(path: str, element: etree._Element | None) -> Pose:
    if element is None:
        return Pose()
    relative = element.get("relative_to")
    if relative not in (None, "", "world", "__model__"):
        raise UnsupportedError(
            f"pose relative_to={relative!r}: world poses relative to another frame are not read yet",
            element="pose",
            loc=_loc(path, element),
        )
    return pose_value(path, element)
