"""Visuals and colliders of one link: ``<link>/visuals/*`` and ``<link>/collisions/*``.

Primitives map to UsdGeom gprims (a unit ``Cube`` scaled to the box, ``Sphere``, ``Cylinder`` and
``Capsule`` along Z); meshes become ``Mesh`` prims with the file's triangles, the URDF scale baked
into the points and one flat normal per face (``uniform``).
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from robodesc.emit.common.approximation import TRIANGLE_MODES, mode_for, static_links
from robodesc.emit.usd.contact import PhysicsMaterials
from robodesc.emit.usd.context import GEOMETRY, MATERIALS, PHYSICS, UsdContext, UsedNames, set_pose, unique_name
from robodesc.emit.usd.materials import MaterialLibrary
from robodesc.ir.geometry import Box, Capsule, Cylinder, Geometry, Mesh, Sphere
from robodesc.ir.model import Collision, Link, Visual
from robodesc.ir.rigid import pose_frame
from robodesc.usdfile.spec import Prim
from robodesc.usdfile.usdc import keep_packed

# PhysX's default SDF resolution (voxels along the mesh's longest side).
SDF_RESOLUTION = 256

if TYPE_CHECKING:
    from robodesc.meshes.buffers import MeshData


def emit_link_geometry(ctx: UsdContext, link: Link, looks: MaterialLibrary, contacts: PhysicsMaterials) -> None:
    link_path = ctx.link_paths[link.name]
    label = f"link {link.name!r}"
    if link.visuals:
        used: set[str] = UsedNames()
        scope = f"{link_path}/visuals"
        ctx.define(GEOMETRY, scope, "Xform")
        for index, visual in enumerate(link.visuals):
            path = f"{scope}/{unique_name(visual.name or '', used, 'visual')}"
            if _shape(ctx, path, visual, f"{label} visual {index}"):
                look = looks.path_for(visual.material)
                if look is not None:
                    prim = ctx.over(MATERIALS, path)
                    prim.apply("MaterialBindingAPI")
                    prim.rel("material:binding", [look])
    if link.collisions:
        used = UsedNames()
        scope = f"{link_path}/collisions"
        ctx.define(GEOMETRY, scope, "Xform")
        for index, collision in enumerate(link.collisions):
            path = f"{scope}/{unique_name(collision.name or '', used, 'collision')}"
            if _shape(ctx, path, collision, f"{label} collision {index}"):
                prim = _collider(ctx, path, collision, link.name)
                contacts.bind(prim, link.collision_contact(collision), label)


def approximation_notes(ctx: UsdContext) -> None:
    """What PhysX does with the exact-triangle modes (docs/contact.md): a triangle mesh ("none") only
    on a static collider, never on a dynamic body or articulation link, which every link robodesc
    writes is (static links too: they are bodies of the articulation, welded by fixed joints); an
    SDF collider on any body, with GPU dynamics."""
    spec = ctx.options.collision_approximation
    static = static_links(ctx.robot, ctx.options.fix_base)
    by_mode: dict[str, list[str]] = {}
    for link in ctx.robot.links:
        mode = mode_for(spec, link.name)
        if mode in TRIANGLE_MODES and any(isinstance(c.geometry, Mesh) for c in link.collisions):
            by_mode.setdefault(mode, []).append(link.name)
    triangles = by_mode.get("none", [])
    if triangles:
        moving = [n for n in triangles if n not in static]
        ctx.warn(
            "usd-triangle-mesh",
            f"triangle-mesh colliders (approximation none) on {_names(triangles)}: PhysX takes triangle meshes "
            "only on static colliders, and every USD link is a rigid body of the articulation"
            + (
                f" ({_names(moving)} {'moves' if len(moving) == 1 else 'move'})"
                if moving
                else " (these are welded to the world, still bodies)"
            )
            + ", so Isaac's PhysX uses their convex hull; Newton collides the triangles. For exact contact in "
            "PhysX use sdf (GPU dynamics) or convexDecomposition",
            "option 'collision_approximation'",
        )
    moving_sdf = [n for n in by_mode.get("sdf", []) if n not in static]
    if moving_sdf:
        ctx.warn(
            "usd-sdf-collider",
            f"SDF colliders on moving links {_names(moving_sdf)}: PhysX simulates them on dynamic bodies with "
            "GPU dynamics only",
            "option 'collision_approximation'",
        )


def _names(links: list[str]) -> str:
    return ", ".join(links[:5]) + (f" and {len(links) - 5} more" if len(links) > 5 else "")


def _shape(ctx: UsdContext, path: str, item: Visual | Collision, label: str) -> bool:
    geometry: Geometry = item.geometry
    origin = pose_frame(item.origin)
    if isinstance(geometry, Box):
        prim = ctx.define(GEOMETRY, path, "Cube")
        prim.attr("size", "double", 1.0)
        prim.attr("extent", "float3[]", [(-0.5, -0.5, -0.5), (0.5, 0.5, 0.5)])
        sx, sy, sz = (float(v) for v in geometry.size)
        set_pose(prim, origin, (sx, sy, sz))
    elif isinstance(geometry, Sphere):
        prim = ctx.define(GEOMETRY, path, "Sphere")
        r = float(geometry.radius)
        prim.attr("radius", "double", r)
        prim.attr("extent", "float3[]", [(-r, -r, -r), (r, r, r)])
        set_pose(prim, origin)
    elif isinstance(geometry, Cylinder | Capsule):
        r, h = float(geometry.radius), float(geometry.length)
        if isinstance(geometry, Cylinder):
            prim = ctx.define(GEOMETRY, path, "Cylinder")
            half = h / 2
        else:
            prim = ctx.define(GEOMETRY, path, "Capsule")
            half = h / 2 + r
        prim.attr("radius", "double", r)
        prim.attr("height", "double", h)
        prim.attr("axis", "token", "Z", uniform=True)
        prim.attr("extent", "float3[]", [(-r, -r, -half), (r, r, half)])
        set_pose(prim, origin)
    else:
        data = _mesh_data(ctx, geometry, label)
        if data is None:
            return False
        prim = ctx.define(GEOMETRY, path, "Mesh")
        author_mesh(prim, data)
        set_pose(prim, origin)
    if isinstance(item, Collision):
        prim.attr("purpose", "token", "guide", uniform=True)
    return True


def _mesh_data(ctx: UsdContext, mesh: Mesh, label: str) -> MeshData | None:
    from robodesc.meshes.buffers import MeshReadError

    if mesh.path is None:
        ctx.warn("usd-missing-mesh", f"mesh {mesh.uri!r} was not found; this geometry is left out", label, mesh.src)
        return None
    from robodesc.meshes.roots import outside_roots

    outside = outside_roots(mesh.path, ctx.mesh_roots)
    if outside is not None:
        # The rule of --copy-meshes: embedding the geometry is copying the file's content.
        ctx.warn(
            "usd-mesh-not-read",
            f"mesh {outside}; its geometry is not embedded and this shape is left out "
            "(--copy-meshes refuses the same file)",
            label,
            mesh.src,
        )
        return None
    try:
        data = ctx.meshes.get(mesh.path, mesh.scale)
    except MeshReadError as exc:
        ctx.warn(
            "usd-bad-mesh", f"mesh {mesh.path!r} could not be read ({exc}); this geometry is left out", label, mesh.src
        )
        return None
    # MeshData's arrays are never modified: the integer coding of its indices (the costly part of
    # packing them) can serve every robot that uses the mesh in this process (a batch worker keeps
    # meshes across robots). Points and normals need no packing: the writer hands the file views
    # of their memory.
    keep_packed(data.face_vertex_counts, data.face_vertex_indices)
    return data


def author_mesh(prim: Prim, data: MeshData) -> None:
    """A ``Mesh`` prim's triangles, normals, extent and UVs (the robot's meshes and the world's terrains)."""
    prim.attr("points", "point3f[]", data.points)
    prim.attr("faceVertexCounts", "int[]", data.face_vertex_counts)
    prim.attr("faceVertexIndices", "int[]", data.face_vertex_indices)
    # One normal per triangle: the flat shading faceVarying would give by repeating it at each
    # corner, in a third of the data (NVIDIA's converter writes per-face normals too).
    prim.attr("normals", "normal3f[]", data.normals, interpolation="uniform")
    prim.attr("subdivisionScheme", "token", "none", uniform=True)
    prim.attr("extent", "float3[]", data.extent)
    if data.uv is not None:
        prim.attr("primvars:st", "texCoord2f[]", data.uv, interpolation="vertex")


def _collider(ctx: UsdContext, path: str, collision: Collision, link: str) -> Prim:
    options = ctx.options
    prim = ctx.over(PHYSICS, path)
    prim.apply("PhysicsCollisionAPI")
    if isinstance(collision.geometry, Mesh):
        mode = mode_for(options.collision_approximation, link)
        prim.apply("PhysicsMeshCollisionAPI")
        prim.attr("physics:approximation", "token", mode, uniform=True)
        if mode == "sdf":
            # PhysX collides the triangles through a signed distance field, on any body (GPU
            # dynamics); 256 is PhysX's own default resolution, written so every loader agrees.
            prim.apply("PhysxSDFMeshCollisionAPI")
            prim.attr("physxSDFMeshCollision:sdfResolution", "int", SDF_RESOLUTION)
        if mode == "convexDecomposition":
            # PhysX decomposes on load (V-HACD); its parameters written out so every loader gets
            # the same hulls (PhysX's defaults: up to 32 hulls of up to 64 vertices).
            prim.apply("PhysxConvexDecompositionCollisionAPI")
            prim.attr("physxConvexDecompositionCollision:maxConvexHulls", "int", 32)
            prim.attr("physxConvexDecompositionCollision:hullVertexLimit", "int", 64)
    if options.contact_offset is not None or options.rest_offset is not None:
        prim.apply("PhysxCollisionAPI")
        if options.contact_offset is not None:
            prim.attr("physxCollision:contactOffset", "float", options.contact_offset)
        if options.rest_offset is not None:
            prim.attr("physxCollision:restOffset", "float", options.rest_offset)
    return prim
