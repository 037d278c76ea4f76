"""Geoms: shapes, which of them collide and which are drawn, colours, and surface parameters.

- A geom that can collide (``contype`` or ``conaffinity`` non-zero) is a collision; a geom in one of
  the groups MuJoCo draws by default (0 to 2) is a visual. menagerie's pattern (visual meshes in
  group 2 that never collide, primitives in group 3 that do) gives each its one role; a simple
  model's geoms (group 0, colliding) are both.
- Sizes, poses (``fromto`` included) and mesh scales are the compiled model's. MuJoCo moves a
  mesh's vertices to their centre of mass and principal axes and the geom with them; the IR's mesh
  is the file as written, so that move is undone (``mesh_pos``/``mesh_quat``).
- box, sphere, capsule, cylinder and mesh are the IR's shapes. An ellipsoid becomes the sphere of its
  largest radius; a plane, a height field and an SDF have no IR shape: warnings say what is lost.
- ``friction`` (slide, torsion, roll) and ``solref`` differing from MuJoCo's defaults become the
  collision's contact (``mu``, ``torsional``, ``rolling``, ``kp``/``kd``: emit/mjcf/contact_params.py
  inverted, through the same contact mass, so MJCF -> IR -> MJCF gives back the same solref).
"""

from __future__ import annotations

import math
from typing import Any

from robodesc.frontends.mjcf.context import Reading
from robodesc.frontends.mjcf.frames import frame, inverse, pose
from robodesc.frontends.options import MissingMesh
from robodesc.ir.contact import Contact
from robodesc.ir.diagnostics import SourceLoc
from robodesc.ir.geometry import RGBA, Box, Capsule, Cylinder, Geometry, Material, Mesh, Sphere
from robodesc.ir.model import Collision, Link, Visual
from robodesc.ir.rigid import Frame

PLANE, HFIELD, SPHERE, CAPSULE, ELLIPSOID, CYLINDER, BOX, MESH, SDF = range(9)
_NAMES = {PLANE: "plane", HFIELD: "hfield", ELLIPSOID: "ellipsoid", SDF: "sdf"}
DEFAULT_FRICTION = (1.0, 0.005, 0.0001)
DEFAULT_SOLREF = (0.02, 1.0)
DEFAULT_RGBA = (0.5, 0.5, 0.5, 1.0)
VISIBLE_GROUPS = (0, 1, 2)


def read_geoms(r: Reading) -> None:
    m = r.model
    links = r.robot.link_map()
    materials: dict[str, Material] = {}
    surfaces: list[tuple[Collision, tuple[float, float]]] = []
    for g in range(m.ngeom):
        b = int(m.geom_bodyid[g])
        owner = links.get(r.link_of.get(b, ""))
        label = f"geom {r.name('geom', g) or g}"
        loc = r.loc("geom", g)
        kind = int(m.geom_type[g])
        if b in r.dropped or (kind == PLANE and b == 0):
            continue  # a scene's floor: each target's scene writes its own
        if owner is None:
            if kind != PLANE:
                r.warn(
                    "mjcf-world-geom",
                    "static geometry of the world (not of a robot body) is left out of every output",
                    label,
                    loc,
                )
            continue
        shape = _shape(r, g, kind, label, loc)
        if shape is None:
            continue
        geometry, offset = shape
        placed = r.content[b] @ frame(m.geom_pos[g], m.geom_quat[g]) @ offset
        origin = pose(placed)
        collides = int(m.geom_contype[g]) != 0 or int(m.geom_conaffinity[g]) != 0
        shown = int(m.geom_group[g]) in VISIBLE_GROUPS
        name = r.name("geom", g)
        if shown or not collides:
            material = _material(r, g, materials)
            owner.visuals.append(Visual(geometry, origin=origin, name=name, material=material, src=loc))
        if collides:
            collision = Collision(geometry, origin=origin, name=name, src=loc)
            friction = tuple(float(v) for v in m.geom_friction[g])
            solref = (float(m.geom_solref[g][0]), float(m.geom_solref[g][1]))
            if not _close(friction, DEFAULT_FRICTION) or not _close(solref, DEFAULT_SOLREF):
                surfaces.append((collision, solref))
                # Torsion and roll as MuJoCo's defaults stay "not given": the MJCF emitter writes those.
                # MuJoCo's sliding friction is one coefficient for both tangent directions: mu2 says
                # so, where SDF's default mu2 of 1 would otherwise stand (Drake then reads Spot's
                # feet, mu 0.8, as static 0.8 and dynamic 1 and refuses them).
                collision.contact = Contact(
                    mu=friction[0],
                    mu2=friction[0],
                    torsional=None if friction[1] == DEFAULT_FRICTION[1] else friction[1],
                    rolling=None if friction[2] == DEFAULT_FRICTION[2] else friction[2],
                    src=loc,
                )
            owner.collisions.append(collision)
    r.robot.materials.extend(materials.values())
    _solref(r, surfaces, links)
    _unheld_contact(r)


# MuJoCo's defaults of the contact parameters the IR has no field for.
_CONDIM, _PRIORITY, _MARGIN = 3, 0, 0.0
_SOLIMP = (0.9, 0.95, 0.001, 0.5, 2.0)


def _unheld_contact(r: Reading) -> None:
    """One finding each for collision bitmasks and contact parameters the IR cannot hold, counted
    over the robot's colliding geoms (per-geom messages would repeat on every foot)."""
    m = r.model
    colliders = [
        g
        for g in range(m.ngeom)
        if int(m.geom_bodyid[g]) in r.link_of
        and r.link_of[int(m.geom_bodyid[g])] in r.link_names
        and (int(m.geom_contype[g]) or int(m.geom_conaffinity[g]))
    ]
    masks = sorted({(int(m.geom_contype[g]), int(m.geom_conaffinity[g])) for g in colliders})
    if len(masks) > 1 or (masks and masks[0] != (1, 1)):
        r.warn(
            "mjcf-collision-filter",
            f"contype/conaffinity bitmasks {', '.join(f'{a}/{b}' for a, b in masks)} choose which geoms collide; the IR "
            "has no collision filter: each output collides by its target's self-collision option",
            f"robot {r.robot.name!r}",
            r.source.loc(r.source.root),
        )
    counts = {
        "condim": sum(int(m.geom_condim[g]) != _CONDIM for g in colliders),
        "priority": sum(int(m.geom_priority[g]) != _PRIORITY for g in colliders),
        "margin": sum(float(m.geom_margin[g]) != _MARGIN for g in colliders),
        "solimp": sum(not _close(tuple(float(v) for v in m.geom_solimp[g]), _SOLIMP) for g in colliders),
    }
    given = {k: v for k, v in counts.items() if v}
    if given:
        r.info(
            "mjcf-contact-params",
            f"{', '.join(f'{k} on {v} geom(s)' for k, v in given.items())}: the IR's contact (Gazebo's terms) has no "
            "field for these; every output uses its engine's defaults",
            f"robot {r.robot.name!r}",
            r.source.loc(r.source.root),
        )


def _close(a: tuple[float, ...], b: tuple[float, ...]) -> bool:
    return all(math.isclose(x, y, rel_tol=1e-9, abs_tol=1e-12) for x, y in zip(a, b, strict=True))


def _shape(r: Reading, g: int, kind: int, label: str, loc: SourceLoc) -> tuple[Geometry, Frame] | None:
    m = r.model
    size = [float(v) for v in m.geom_size[g]]
    if kind == SPHERE:
        return Sphere(size[0]), Frame()
    if kind == CAPSULE:
        return Capsule(size[0], 2 * size[1]), Frame()
    if kind == CYLINDER:
        return Cylinder(size[0], 2 * size[1]), Frame()
    if kind == BOX:
        return Box((2 * size[0], 2 * size[1], 2 * size[2])), Frame()
    if kind == ELLIPSOID:
        r.warn(
            "mjcf-ellipsoid",
            f"ellipsoid {size[0]:g} x {size[1]:g} x {size[2]:g} has no IR shape: every output gets the sphere of its "
            "largest radius (the body's mass and inertia are MuJoCo's, unchanged)",
            label,
            loc,
        )
        return Sphere(max(size)), Frame()
    if kind == MESH:
        return _mesh(r, g, label, loc)
    what = _NAMES.get(kind, str(kind))
    if kind == PLANE:
        r.warn(
            "mjcf-plane",
            "a plane on a body has no IR shape: every output leaves it out (each target's scene has its own floor)",
            label,
            loc,
        )
    else:
        r.warn(
            "mjcf-shape-not-held",
            f"a {what} geom has no IR shape: URDF, SDF, USD and MJCF outputs leave it out",
            label,
            loc,
        )
    return None


def _mesh(r: Reading, g: int, label: str, loc: SourceLoc) -> tuple[Geometry, Frame] | None:
    m = r.model
    mesh_id = int(m.geom_dataid[g])
    mesh_name = r.name("mesh", mesh_id) or f"mesh{mesh_id}"
    written, path = r.source.mesh_files.get(mesh_name, (mesh_name, None))
    sx, sy, sz = (float(v) for v in m.mesh_scale[mesh_id])
    scale = None if (sx, sy, sz) == (1.0, 1.0, 1.0) else (sx, sy, sz)
    # The compiled geom carries MuJoCo's recentring of the vertices: undo it for the file as written.
    offset = inverse(frame(m.mesh_pos[mesh_id], m.mesh_quat[mesh_id]))
    if path is None and mesh_name in r.source.missing_meshes:
        policy = r.options.missing_mesh
        message = f"mesh file {written!r} (mesh {mesh_name!r}) not found"
        if policy is MissingMesh.ERROR:
            from robodesc.ir.diagnostics import BrokenReferenceError

            raise BrokenReferenceError(
                message + "; --missing-mesh warn|primitive|drop chooses another policy", element=label, loc=loc
            )
        if policy is MissingMesh.DROP:
            r.warn("missing-mesh", message + "; geom dropped", label, loc)
            return None
        r.warn("missing-mesh", message + "; reference kept", label, loc)
        # Without the file MuJoCo's recentring is unknown: the geom's own frame is kept.
        return Mesh(uri=written, scale=scale, src=loc), Frame()
    if path is None:
        r.warn(
            "mjcf-inline-mesh",
            "a mesh given by its vertices in the file (no mesh file) has no IR form: every output leaves it out",
            label,
            loc,
        )
        return None
    mesh = Mesh(uri=written, path=path, scale=scale, src=loc)
    return mesh, offset


def _material(r: Reading, g: int, materials: dict[str, Material]) -> Material | None:
    m = r.model
    mat = int(m.geom_matid[g])
    rgba = _colour(m.geom_rgba[g])
    if mat >= 0:
        base = r.name("material", mat) or f"material{mat}"
        name, color = base, _colour(m.mat_rgba[mat])
        if rgba != DEFAULT_RGBA and rgba != color:
            name, color = f"{base}_{g}", rgba  # a geom's own rgba wins over its material's
        if name not in materials:
            texture = r.source.textures.get(r.source.material_textures.get(base, ""))
            materials[name] = Material(
                name=name,
                color=color,
                texture=texture[0] if texture else None,
                texture_path=texture[1] if texture else None,
            )
        return Material(name=name)
    if rgba == DEFAULT_RGBA:
        return None
    name = f"rgba_{'_'.join(f'{c:.3g}' for c in rgba)}"
    if name not in materials:
        materials[name] = Material(name=name, color=rgba)
    return Material(name=name)


def _colour(values: Any) -> RGBA:
    # MuJoCo keeps colours in float32: 0.1 reads back as 0.10000000149; 7 digits are what was written.
    r, g, b, a = (float(f"{float(v):.7g}") for v in values)
    return (r, g, b, a)


def _solref(r: Reading, surfaces: list[tuple[Collision, tuple[float, float]]], links: dict[str, Link]) -> None:
    """MuJoCo's (timeconst, dampratio) as the IR's spring and damper, through the contact mass the
    MJCF emitter divides by (the robot's mass over the links that carry contact parameters)."""
    if not surfaces:
        return
    bearing = {name for name, link in links.items() if any(c.contact is not None for c in link.collisions)}
    mass = max(r.robot.total_mass(), 1e-6) / max(len(bearing), 1)
    for collision, (timeconst, ratio) in surfaces:
        assert collision.contact is not None
        if _close((timeconst, ratio), DEFAULT_SOLREF):
            continue
        if timeconst <= 0 or ratio <= 0:
            r.warn(
                "mjcf-solref-direct",
                f"solref {timeconst:g} {ratio:g} (MuJoCo's direct stiffness/damping form) has no IR form: left out",
                f"geom {collision.name or ''}",
                collision.src,
            )
            continue
        omega = 1.0 / (ratio * timeconst)
        kp = mass * omega * omega
        collision.contact.kp = kp
        collision.contact.kd = 2.0 * ratio * math.sqrt(kp * mass)
