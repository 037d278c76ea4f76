"""The robot a picture shows: as read (and verified), or as compiled for a target after its passes.

Both pictures go through the pipeline's own functions, so the page shows exactly what a compile
would see: the source through :func:`~robodesc.pipeline.load_source` and
:func:`~robodesc.pipeline.verify_source`; a target through :func:`~robodesc.pipeline.compile_robot`
into a temporary folder with validation off (the IR after the passes is ``result.robot``; nothing
the user owns is written). With a target, the source is loaded too, so the repairs can be shown
before and after.
"""

from __future__ import annotations

import copy
import os
import tempfile
from dataclasses import dataclass, field

from robodesc.frontends.load import Source, load_source
from robodesc.frontends.options import MissingMesh
from robodesc.frontends.world.options import WorldOptions
from robodesc.ir.diagnostics import Finding, Findings
from robodesc.ir.model import Robot
from robodesc.options import CompileOptions
from robodesc.pipeline import compile_robot, verify_source
from robodesc.targets import target_spec
from robodesc.view.world import ViewWorld, place_for_view


@dataclass(slots=True)
class Loaded:
    """What a picture needs: the robot shown, robodesc's findings about it, and, with a target,
    the verified source robot before the passes (``before``)."""

    robot: Robot
    findings: list[Finding]
    target: str | None = None
    before: Robot | None = None
    source_name: str = ""
    notes: list[str] = field(default_factory=list)
    # The world the robot stands in (--world, --terrain, --spawn); None: the robot alone.
    world: ViewWorld | None = None


def _name(source: Source) -> str:
    if isinstance(source, (str, os.PathLike)):
        text = os.fspath(source)
        return text if not text.lstrip().startswith("<") else "<string>"
    return type(source).__name__


def load_for_view(source: Source, options: CompileOptions | None = None, target: str | None = None) -> Loaded:
    """The source robot (verified, as ``robodesc inspect`` sees it) or, with ``target``, the robot
    as compiled for it. Raises what the compile raises (a :class:`RobodescError` for bad input)."""
    opts = options if options is not None else CompileOptions()
    findings = Findings()
    robot = load_source(source, opts.load, findings)
    repairing = target is not None and opts.invalid_inertia.value == "repair"
    verify_source(robot, opts, findings, repairing=repairing)
    if target is None:
        world = place_for_view(robot, opts.world, findings)
        return Loaded(robot=robot, findings=list(findings), source_name=_name(source), world=world)
    before = robot
    if opts.load.missing_mesh is not MissingMesh.WARN:
        # "Before" is the source as written: a mesh the options drop or replace is shown as a
        # repair, so it must still be there. (The compile below applies the options.)
        as_written = copy.deepcopy(opts)
        as_written.load.missing_mesh = MissingMesh.WARN
        before = load_source(source, as_written.load, Findings())
        verify_source(before, as_written, Findings(), repairing=True)
    spec = target_spec(target)
    compiled_opts = copy.deepcopy(opts)
    compiled_opts.validate = False  # the picture needs the IR, not a second opinion on the file
    compiled_opts.load.strict = False
    # The picture places the robot in the world itself (below): any target can be drawn in one.
    compiled_opts.world = WorldOptions()
    with tempfile.TemporaryDirectory(prefix="robodesc-view-") as tmp:
        out = spec.output_name(os.path.join(tmp, "robot"))
        # The compile reads the source again: the passes change the robot they are given.
        result = compile_robot(robot, target, out, compiled_opts)
    # The source's findings come first; the compile repeats them (it verified the same robot), so
    # only its new ones (the passes' and the emitter's) are added.
    seen = {(f.code, f.element, f.message) for f in findings}
    extra = [f for f in result.findings if (f.code, f.element, f.message) not in seen]
    return Loaded(
        robot=result.robot,
        findings=[*findings, *extra],
        target=target,
        before=before,
        source_name=_name(source),
        world=place_for_view(result.robot, opts.world, findings),
    )
