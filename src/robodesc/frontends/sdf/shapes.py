"""An SDF ``<geometry>`` into an IR shape, for a link's visuals and collisions.

Box, cylinder, sphere, capsule (SDF 1.9) and mesh (with ``scale``) are the IR's shapes. An
ellipsoid becomes the sphere of its largest radius, with a warning; a plane, a heightmap, a polyline
or an image has no shape a robot's link can carry in every target: a warning, and the element is
left out. Mesh URIs resolve as Gazebo resolves them (``model://`` through the model path, relative to
the file); an included model's mesh may not leave its folder.
"""

from __future__ import annotations

import os

from lxml import etree

from robodesc.frontends.options import LoadOptions, MissingMesh
from robodesc.frontends.packages import PackageResolver
from robodesc.frontends.sdf.model_path import resolve_uri
from robodesc.frontends.sdf.source import STAGE, Scope
from robodesc.frontends.sdf.values import loc, positive, required, tag, vec3
from robodesc.ir.diagnostics import BrokenReferenceError, Findings, PathEscapeError
from robodesc.ir.geometry import Box, Capsule, Cylinder, Geometry, Mesh, Sphere


def read_shape(
    scope: Scope,
    geometry: etree._Element | None,
    label: str,
    roots: list[str],
    options: LoadOptions,
    findings: Findings,
) -> Geometry | None:
    path = scope.file
    shapes = [c for c in geometry if isinstance(c.tag, str)] if geometry is not None else []
    if not shapes:
        where = loc(path, geometry) if geometry is not None else None
        findings.warn("sdf-no-geometry", "has no geometry; left out", element=label, loc=where, stage=STAGE)
        return None
    el = shapes[0]
    kind = tag(el)
    here = loc(path, el)
    solid = primitive(path, el)
    if solid is not None:
        return solid
    if kind == "ellipsoid":
        radii = vec3(path, required(path, el, "radii"))
        findings.warn(
            "sdf-ellipsoid",
            f"ellipsoid {radii[0]:g} x {radii[1]:g} x {radii[2]:g} has no IR shape: every target gets the sphere of "
            "its largest radius (the link's mass and inertia are the file's, unchanged)",
            element=label,
            loc=here,
            stage=STAGE,
        )
        return Sphere(max(radii), src=here)
    if kind == "mesh":
        return _mesh(scope, el, label, roots, options, findings)
    findings.warn(
        "sdf-geometry-unsupported",
        f"<{kind}> geometry has no shape on a robot's link in robodesc's targets; left out of every target"
        + (" (a ground plane belongs in the world: --world)" if kind == "plane" else ""),
        element=label,
        loc=here,
        stage=STAGE,
    )
    return None


def primitive(path: str, el: etree._Element) -> Box | Sphere | Cylinder | Capsule | None:
    """A box, sphere, cylinder or capsule element as its IR shape (None for any other element); the
    world reader reads its static colliders' solids with it too."""
    kind = tag(el)
    here = loc(path, el)
    if kind == "box":
        return Box(vec3(path, required(path, el, "size")), src=here)
    if kind == "sphere":
        return Sphere(positive(path, required(path, el, "radius")), src=here)
    if kind in ("cylinder", "capsule"):
        radius = positive(path, required(path, el, "radius"))
        length = positive(path, required(path, el, "length"))
        return Cylinder(radius, length, src=here) if kind == "cylinder" else Capsule(radius, length, src=here)
    return None


def _mesh(
    scope: Scope, el: etree._Element, label: str, roots: list[str], options: LoadOptions, findings: Findings
) -> Mesh | Box | None:
    path = scope.file
    here = loc(path, el)
    uri = (el.findtext("uri") or "").strip()
    scale_el = el.find("scale")
    scale = vec3(path, scale_el) if scale_el is not None else None
    if el.find("submesh") is not None:
        findings.warn(
            "sdf-submesh",
            "<submesh> is not read: every target gets the whole mesh file",
            element=label,
            loc=loc(path, el.find("submesh")),  # type: ignore[arg-type]  # checked just above
            stage=STAGE,
        )
    package = None
    if uri.startswith("package://"):
        # A ROS package, found as the URDF frontend finds it (--package, package.xml, ROS paths).
        try:
            found = PackageResolver(explicit=dict(options.package_paths), input_file=scope.file).resolve(uri, None)
            resolved: str | None = found.path
            package = found.package
        except PathEscapeError as exc:
            raise PathEscapeError(f"mesh {uri!r}: {exc.message}", element=label, loc=here) from None
        except BrokenReferenceError:
            resolved = None
    else:
        resolved = _resolve(scope, uri, roots)
    if resolved is None or not os.path.isfile(resolved):
        message = f"mesh {uri!r} is not found (model path: {os.pathsep.join(roots)})"
        if options.missing_mesh is MissingMesh.ERROR:
            raise BrokenReferenceError(message, element=label, loc=here)
        if options.missing_mesh is MissingMesh.DROP:
            findings.warn("mesh-missing", f"{message}; left out", element=label, loc=here, stage=STAGE)
            return None
        if options.missing_mesh is MissingMesh.PRIMITIVE:
            findings.warn(
                "mesh-missing", f"{message}; a box of its scale stands in", element=label, loc=here, stage=STAGE
            )
            return Box(scale or (1.0, 1.0, 1.0), src=here)
        findings.warn("mesh-missing", f"{message}; the reference is kept", element=label, loc=here, stage=STAGE)
        return Mesh(uri=uri, scale=scale, src=here)
    return Mesh(uri=uri, scale=scale, path=resolved, package=package, src=here)


def _resolve(scope: Scope, uri: str, roots: list[str]) -> str | None:
    if uri.startswith(("model://", "file://")) or os.path.isabs(uri):
        return resolve_uri(uri, scope.file, roots)
    candidate = os.path.realpath(os.path.join(scope.folder, uri))
    if scope.confined:
        folder = os.path.realpath(scope.folder)
        if os.path.commonpath([candidate, folder]) != folder:
            return None
    return candidate if os.path.exists(candidate) else None
