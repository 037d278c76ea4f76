"""Visuals and colliders of one link: ``<link>/visuals/*`` and ``<link>/collisions/*``.

Primitives map to UsdGeom gprims (a unit ``Cube`` scaled to the box, ``Sphere``, ``Cylinder`` and
``Capsule`` along Z); meshes become ``Mesh`` prims with the file's triangles, the URDF scale baked
into the points and face-varying normals.
"""

from __future__ import annotations

from pxr import Gf, Sdf, UsdGeom, UsdPhysics, UsdShade, Vt

from robodesc.emit.usd_context import (
    GEOMETRY,
    MATERIALS,
    PHYSICS,
    UsdContext,
    apply_schema,
    schema_attr,
    set_pose,
    unique_name,
)
from robodesc.emit.usd_materials import MaterialLibrary
from robodesc.emit.usd_meshio import MeshData, MeshReadError
from robodesc.ir.geometry import Box, Capsule, Cylinder, Geometry, Mesh, Sphere
from robodesc.ir.model import Collision, Link, Visual
from robodesc.ir.transforms import pose_matrix


def emit_link_geometry(ctx: UsdContext, link: Link, looks: MaterialLibrary) -> None:
    link_path = ctx.link_paths[link.name]
    label = f"link {link.name!r}"
    if link.visuals:
        used: set[str] = set()
        scope = link_path.AppendChild("visuals")
        with ctx.layer(GEOMETRY):
            ctx.stage.DefinePrim(scope, "Xform")
        for index, visual in enumerate(link.visuals):
            name = unique_name(visual.name or "", used, "visual")
            path = scope.AppendChild(name)
            if _shape(ctx, path, visual, f"{label} visual {index}"):
                look = looks.path_for(visual.material)
                if look is not None:
                    with ctx.layer(MATERIALS):
                        prim = ctx.stage.GetPrimAtPath(path)
                        UsdShade.MaterialBindingAPI.Apply(prim).Bind(UsdShade.Material(ctx.stage.GetPrimAtPath(look)))
    if link.collisions:
        used = set()
        scope = link_path.AppendChild("collisions")
        with ctx.layer(GEOMETRY):
            ctx.stage.DefinePrim(scope, "Xform")
        for index, collision in enumerate(link.collisions):
            name = unique_name(collision.name or "", used, "collision")
            path = scope.AppendChild(name)
            if _shape(ctx, path, collision, f"{label} collision {index}"):
                _collider(ctx, path, collision)


def _shape(ctx: UsdContext, path: Sdf.Path, item: Visual | Collision, label: str) -> bool:
    geometry: Geometry = item.geometry
    origin = pose_matrix(item.origin)
    stage = ctx.stage
    with ctx.layer(GEOMETRY):
        if isinstance(geometry, Box):
            cube = UsdGeom.Cube.Define(stage, path)
            cube.CreateSizeAttr(1.0)
            cube.CreateExtentAttr(Vt.Vec3fArray([Gf.Vec3f(-0.5, -0.5, -0.5), Gf.Vec3f(0.5, 0.5, 0.5)]))
            sx, sy, sz = (float(v) for v in geometry.size)
            set_pose(cube, origin, (sx, sy, sz))
            gprim: UsdGeom.Gprim = cube
        elif isinstance(geometry, Sphere):
            sphere = UsdGeom.Sphere.Define(stage, path)
            r = float(geometry.radius)
            sphere.CreateRadiusAttr(r)
            sphere.CreateExtentAttr(Vt.Vec3fArray([Gf.Vec3f(-r, -r, -r), Gf.Vec3f(r, r, r)]))
            set_pose(sphere, origin)
            gprim = sphere
        elif isinstance(geometry, Cylinder | Capsule):
            r, h = float(geometry.radius), float(geometry.length)
            if isinstance(geometry, Cylinder):
                shape: UsdGeom.Cylinder | UsdGeom.Capsule = UsdGeom.Cylinder.Define(stage, path)
                half = h / 2
            else:
                shape = UsdGeom.Capsule.Define(stage, path)
                half = h / 2 + r
            shape.CreateRadiusAttr(r)
            shape.CreateHeightAttr(h)
            shape.CreateAxisAttr(UsdGeom.Tokens.z)
            shape.CreateExtentAttr(Vt.Vec3fArray([Gf.Vec3f(-r, -r, -half), Gf.Vec3f(r, r, half)]))
            set_pose(shape, origin)
            gprim = shape
        else:
            data = _mesh_data(ctx, geometry, label)
            if data is None:
                return False
            mesh = UsdGeom.Mesh.Define(stage, path)
            _author_mesh(mesh, data)
            set_pose(mesh, origin)
            gprim = mesh
        if isinstance(item, Collision):
            gprim.CreatePurposeAttr(UsdGeom.Tokens.guide)
    return True


def _mesh_data(ctx: UsdContext, mesh: Mesh, label: str) -> MeshData | None:
    if mesh.path is None:
        ctx.warn("usd-missing-mesh", f"mesh {mesh.uri!r} was not found; this geometry is left out", label, mesh.src)
        return None
    try:
        return ctx.meshes.get(mesh.path, mesh.scale)
    except MeshReadError as exc:
        ctx.warn(
            "usd-bad-mesh", f"mesh {mesh.path!r} could not be read ({exc}); this geometry is left out", label, mesh.src
        )
        return None


def _author_mesh(mesh: UsdGeom.Mesh, data: MeshData) -> None:
    mesh.CreatePointsAttr(Vt.Vec3fArray.FromNumpy(data.points))
    mesh.CreateFaceVertexCountsAttr(Vt.IntArray.FromNumpy(data.face_vertex_counts))
    mesh.CreateFaceVertexIndicesAttr(Vt.IntArray.FromNumpy(data.face_vertex_indices))
    mesh.CreateNormalsAttr(Vt.Vec3fArray.FromNumpy(data.normals))
    mesh.SetNormalsInterpolation(UsdGeom.Tokens.faceVarying)
    mesh.CreateSubdivisionSchemeAttr(UsdGeom.Tokens.none)
    mesh.CreateExtentAttr(Vt.Vec3fArray.FromNumpy(data.extent))
    if data.uv is not None:
        st = UsdGeom.PrimvarsAPI(mesh).CreatePrimvar("st", Sdf.ValueTypeNames.TexCoord2fArray, UsdGeom.Tokens.vertex)
        st.Set(Vt.Vec2fArray.FromNumpy(data.uv))


def _collider(ctx: UsdContext, path: Sdf.Path, collision: Collision) -> None:
    options = ctx.options
    with ctx.layer(PHYSICS):
        prim = ctx.stage.OverridePrim(path)
        UsdPhysics.CollisionAPI.Apply(prim)
        if isinstance(collision.geometry, Mesh):
            api = UsdPhysics.MeshCollisionAPI.Apply(prim)
            api.CreateApproximationAttr(options.collision_approximation)
        if options.contact_offset is not None or options.rest_offset is not None:
            apply_schema(prim, "PhysxCollisionAPI")
            if options.contact_offset is not None:
                schema_attr(prim, "physxCollision:contactOffset", Sdf.ValueTypeNames.Float, options.contact_offset)
            if options.rest_offset is not None:
                schema_attr(prim, "physxCollision:restOffset", Sdf.ValueTypeNames.Float, options.rest_offset)
