"""Resolving a composition's mesh parts under the ``missing_mesh`` policy."""

from __future__ import annotations

import os

from robodesc.frontends.options import MissingMesh
from robodesc.frontends.packages import PackageResolver
from robodesc.ir.diagnostics import BrokenReferenceError, Findings, SourceLoc
from robodesc.ir.geometry import Box, Geometry, Mesh

STAGE = "compose"


def resolve_mesh(
    mesh: Mesh,
    *,
    element: str,
    loc: SourceLoc | None,
    base_dir: str | None,
    resolver: PackageResolver,
    policy: MissingMesh,
    findings: Findings,
) -> Geometry | None:
    """The mesh with ``path`` set, or its substitute; ``None`` when the policy drops it."""
    try:
        resolved = resolver.resolve(mesh.uri, base_dir)
    except BrokenReferenceError as exc:
        raise BrokenReferenceError(f"mesh {mesh.uri!r}: {exc.message}", element=element, loc=loc) from None
    mesh.path, mesh.package = resolved.path, resolved.package
    if os.path.isfile(resolved.path):
        return mesh
    message = f"mesh file {mesh.uri!r} does not exist (looked for {resolved.path!r})"
    if policy is MissingMesh.ERROR:
        raise BrokenReferenceError(
            message + "; --missing-mesh warn|primitive|drop chooses another policy", element=element, loc=loc
        )
    mesh.path = None
    if policy is MissingMesh.WARN:
        findings.warn("missing-mesh", message + "; reference kept", element=element, loc=loc, stage=STAGE)
        return mesh
    if policy is MissingMesh.DROP:
        findings.warn("missing-mesh", message + "; this part was dropped", element=element, loc=loc, stage=STAGE)
        return None
    size = mesh.scale or (1.0, 1.0, 1.0)
    box = Box(size=(abs(size[0]), abs(size[1]), abs(size[2])), src=mesh.src)
    findings.warn(
        "missing-mesh",
        message + f"; replaced by a box of its declared scale {' '.join(f'{s:g}' for s in box.size)}",
        element=element,
        loc=loc,
        stage=STAGE,
    )
    return box
