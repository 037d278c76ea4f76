"""IR → SDF text (``-t sdf``): one articulated model, or a world holding it and free props.

>>> text, findings = emit_sdf(robot, SdfOptions(version="1.11", fix_base=True))  # doctest: +SKIP

Deterministic: links, joints, loop joints, frames, then plugins, each in IR order; every number goes
through :func:`robodesc.emit.numbers.fmt`. What SDF cannot hold (mimic before 1.11, planar and
floating joints, transmissions ...) is reported as a finding, never dropped silently.
"""

from __future__ import annotations

from dataclasses import dataclass, replace

from lxml import etree

from robodesc.emit.sdf.model import SdfModelEmitter
from robodesc.emit.sdf.names import Namespace
from robodesc.emit.sdf.options import PoseFrames, SdfFlavour, SdfOptions, SdfProp
from robodesc.emit.sdf.world import GROUND_PLANE, world_element
from robodesc.ir.diagnostics import Findings
from robodesc.ir.model import Robot

__all__ = ["PoseFrames", "SdfFlavour", "SdfOptions", "SdfProp", "SdfResult", "build_sdf", "emit_sdf"]


@dataclass(slots=True)
class SdfResult:
    text: str
    findings: Findings
    # The robot model's SDF name, and what each IR link / joint / frame is called in the SDF.
    model_name: str
    names: Namespace


def build_sdf(robot: Robot, options: SdfOptions | None = None) -> SdfResult:
    opts = options or SdfOptions()
    findings = Findings()
    version = opts.resolved_version()
    root = etree.Element("sdf", version=version)
    models = Namespace()
    if opts.world:
        parent = world_element(root, [robot, *(p.model for p in opts.props)], opts)
        models.used.add(GROUND_PLANE)
    else:
        parent = root
    main = SdfModelEmitter(robot, opts, findings, in_world=opts.world)
    model_name = models.claim("model", robot.name, findings, loc=robot.src, label="robot")
    main.model(parent, model_name, pose=opts.model_pose)
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
    etree.indent(root, space="  ")
    text = '<?xml version="1.0" encoding="utf-8"?>\n' + etree.tostring(root, encoding="unicode") + "\n"
    return SdfResult(text, findings, model_name, main.names)


def _prop_options(opts: SdfOptions) -> SdfOptions:
    return replace(opts, fix_base=False, model_pose=None, props=[])


def emit_sdf(robot: Robot, options: SdfOptions | None = None) -> tuple[str, Findings]:
    result = build_sdf(robot, options)
    return result.text, result.findings
