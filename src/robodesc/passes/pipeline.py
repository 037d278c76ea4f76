"""The ordered pass pipeline.

Each pass is ``def <pass>(robot: Robot, ctx: PassContext) -> Robot``; it mutates the robot in place,
returns it, and records what it changed in ``ctx`` (stage ``pass:<name>``). A pass runs when its
switch in :class:`PassOptions` is on; presets are named option sets (:mod:`robodesc.passes.presets`).
``copy_meshes`` is not here: it needs the output folder, so emitters call it
(:func:`robodesc.passes.copy_meshes.copy_meshes`).
"""

from __future__ import annotations

import importlib
from collections.abc import Callable
from dataclasses import dataclass

from robodesc.ir.diagnostics import Finding, Findings, VerificationError
from robodesc.ir.model import Robot
from robodesc.ir.verify import check
from robodesc.passes.context import PassContext
from robodesc.passes.options import PassOptions, merge_options

PassFn = Callable[[Robot, PassContext], Robot]


@dataclass(slots=True, frozen=True)
class Pass:
    name: str
    enabled: Callable[[PassOptions], bool]

    @property
    def run(self) -> PassFn:
        """The function ``robodesc.passes.<name>.<name>``, imported when a pass first runs: a compile
        pays only for its own passes (the inertia passes import numpy and trimesh)."""
        fn: PassFn = getattr(importlib.import_module(f"robodesc.passes.{self.name}"), self.name)
        return fn


PASSES: tuple[Pass, ...] = (
    Pass("rename", lambda o: bool(o.rename)),
    Pass("sanitize_names", lambda o: o.sanitize_names),
    Pass("unique_materials", lambda o: o.unique_materials),
    Pass("geometric_inertia", lambda o: o.fill_inertia),
    # Before repair_inertia: a link this gives a mass is not a missing inertial to repair.
    Pass("massless", lambda o: o.mass_from_colliders or o.placeholder_masses),
    Pass("repair_inertia", lambda o: o.repair_inertia is not None),
    # Before strip_tags: merging must still see dont_collapse.
    Pass("merge_fixed", lambda o: bool(o.merge_fixed)),
    Pass("strip_tags", lambda o: bool(o.strip)),
    Pass("armature", lambda o: bool(o.armature or o.armature_by_robot)),
    # After armature: the rules (and the source) win; this fills what they leave unset.
    Pass("default_armature", lambda o: bool(o.default_armature)),
    Pass("explicit_damping", lambda o: o.explicit_damping),
    Pass("isaac_limits", lambda o: o.isaac_limits),
    # Isaac lowering too: a flat collision mesh has no hull for PhysX or Newton.
    Pass("flat_colliders", lambda o: o.isaac_limits),
    Pass("keep_bodies", lambda o: o.keep_bodies),
    Pass("zero_pose", lambda o: o.zero_pose_check),
)


def enabled_passes(options: PassOptions) -> tuple[str, ...]:
    return tuple(p.name for p in PASSES if p.enabled(options))


def resolve_options(preset: str | None, options: PassOptions | None) -> PassOptions:
    """The preset's options, overridden by every non-default field of ``options``."""
    from robodesc.passes.presets import preset_options

    if preset is None:
        return options or PassOptions()
    base = preset_options(preset)
    return merge_options(base, options) if options is not None else base


def run_passes(
    robot: Robot,
    *,
    preset: str | None = None,
    options: PassOptions | None = None,
    verify_each: bool = False,
) -> Findings:
    """Run the enabled passes in order on ``robot`` (in place); return their findings.

    ``verify_each`` runs :func:`robodesc.ir.verify.check` after every pass and raises
    :class:`VerificationError` naming the pass that broke an invariant.
    """
    ctx = PassContext(resolve_options(preset, options))
    for p in PASSES:
        if not p.enabled(ctx.options):
            continue
        ctx.stage = p.name
        result = p.run(robot, ctx)
        assert result is robot, f"pass {p.name} must rewrite the robot in place"
        if verify_each:
            try:
                check(robot)
            except VerificationError as exc:
                raise VerificationError(
                    [
                        Finding(f.severity, f.code, f"after pass {p.name}: {f.message}", f.element, f.loc, f.stage)
                        for f in exc.findings
                    ]
                ) from None
    return ctx.findings
