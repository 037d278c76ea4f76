"""IR → SDF text (``-t sdf``): one articulated model, or a world holding it and free props.

>>> text, findings = emit_sdf(robot, SdfOptions(version="1.11", fix_base=True))  # doctest: +SKIP

Deterministic: links, joints, loop joints, frames, then plugins, each in IR order; every number goes
through :func:`robodesc.emit.numbers.fmt`. What SDF cannot hold (mimic before 1.11, planar and
floating joints, transmissions ...) is reported as a finding, never dropped silently.
"""

from __future__ import annotations

from copy import deepcopy
from dataclasses import dataclass, field, replace

from lxml import etree

from robodesc.emit.common.approximation import asked
from robodesc.emit.common.numbers import fmt_vec
from robodesc.emit.sdf.model import SdfModelEmitter
from robodesc.emit.sdf.names import Namespace
from robodesc.emit.sdf.options import PoseFrames, SdfFlavour, SdfOptions, SdfProp, version_at_least
from robodesc.emit.sdf.world import GROUND_PLANE, world_element
from robodesc.ir.diagnostics import Findings
from robodesc.ir.geometry import Pose
from robodesc.ir.model import Robot

__all__ = ["PoseFrames", "SdfFlavour", "SdfOptions", "SdfProp", "SdfResult", "build_sdf", "emit_sdf"]


@dataclass(slots=True)
class SdfResult:
    text: str
    findings: Findings
    # The robot model's SDF name, and what each IR link / joint / frame is called in the SDF.
    model_name: str
    names: Namespace
    # Files written beside the SDF (convexDecomposition's parts), by role ("mesh:<path>").
    files: dict[str, str] = field(default_factory=dict)


def build_sdf(robot: Robot, options: SdfOptions | None = None) -> SdfResult:
    opts = options or SdfOptions()
    opts.check()
    findings = Findings()
    _approximation_notes(opts, findings)
    version = opts.resolved_version()
    root = etree.Element("sdf", version=version)
    models = Namespace()
    if opts.world:
        parent = world_element(root, [robot, *(p.model for p in opts.props)], opts)
        models.used.add(GROUND_PLANE)
    else:
        parent = root
    main = SdfModelEmitter(robot, opts, findings, in_world=opts.world)
    first = f"{robot.name}_0" if opts.world and opts.copy_poses else robot.name
    model_name = models.claim("model", first, findings, loc=robot.src, label="robot")
    main.model(parent, model_name, pose=opts.model_pose)
    if opts.world and opts.copy_poses:
        _copies(parent, model_name, robot.name, opts.copy_poses, models, findings)
    files: dict[str, str] = {}
    if opts.props and not opts.world:
        findings.warn(
            "sdf-props-dropped",
            f"{len(opts.props)} prop(s) need a world (write --world); an SDF file holds one model",
            element=f"robot {robot.name!r}",
            stage="emit:sdf",
        )
    for prop in opts.props if opts.world else []:
        sub = SdfModelEmitter(prop.model, _prop_options(opts), findings, in_world=True)
        name = models.claim("model", prop.model.name, findings, loc=prop.model.src, label="prop")
        static = prop.static
        if static and any(j.type.dof > 0 for j in prop.model.joints):
            # SDF allows only fixed joints in a static model.
            findings.warn(
                "sdf-prop-not-static",
                "a static prop may only have fixed joints; written as a dynamic model",
                element=f"prop {prop.model.name!r}",
                loc=prop.model.src,
                stage="emit:sdf",
            )
            static = False
        sub.model(parent, name, static=static, pose=prop.pose)
        files.update(sub.written)
    files.update(main.written)
    etree.indent(root, space="  ")
    text = '<?xml version="1.0" encoding="utf-8"?>\n' + etree.tostring(root, encoding="unicode") + "\n"
    return SdfResult(text, findings, model_name, main.names, files)


def _copies(
    parent: etree._Element, model_name: str, stem: str, poses: list[Pose], models: Namespace, findings: Findings
) -> None:
    """Copies of the robot's model, each a model of its own at its pose (Gazebo scopes names and
    topics by model, so the copies' links and joints keep their names)."""
    model = next(m for m in parent.findall("model") if m.get("name") == model_name)
    for i, pose in enumerate(poses, start=1):
        clone = deepcopy(model)
        clone.set("name", models.claim("model", f"{stem}_{i}", findings, label="robot copy"))
        at = clone.find("pose")
        if at is None:
            at = etree.Element("pose")
            clone.insert(0, at)
        at.text = fmt_vec((*pose.xyz, *pose.rpy))
        model.addnext(clone)
        model = clone


def _approximation_notes(opts: SdfOptions, findings: Findings) -> None:
    """What Gazebo does with the modes it has no word for (docs/contact.md)."""
    modes = asked(opts.collision_approximation)
    if "convexHull" in modes and not version_at_least(opts.resolved_version(), "1.11"):
        findings.warn(
            "sdf-approximation",
            f"convexHull: SDF {opts.resolved_version()} cannot ask Gazebo for a mesh's hull (SDF 1.11's "
            "<mesh optimization>, --sdf-version 1.11); the mesh is written as given and collides as its triangles",
            element="option 'collision_approximation'",
            stage="emit:sdf",
        )
    other = sorted(modes & {"boundingCube", "boundingSphere", "sdf"})
    if other:
        findings.warn(
            "sdf-approximation",
            f"collision approximation {', '.join(other)}: Gazebo has no such mesh collider; the mesh is "
            "written as given and Gazebo collides its triangles",
            element="option 'collision_approximation'",
            stage="emit:sdf",
        )


def _prop_options(opts: SdfOptions) -> SdfOptions:
    return replace(opts, fix_base=False, model_pose=None, props=[])


def emit_sdf(robot: Robot, options: SdfOptions | None = None) -> tuple[str, Findings]:
    result = build_sdf(robot, options)
    return result.text, result.findings
