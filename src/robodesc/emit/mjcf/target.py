"""The MJCF target as the pipeline sees it: a file target (``-o OUT/robot.xml``) that also writes
its scene and converted meshes beside the file (docs/mjcf.md, Outputs)."""

from __future__ import annotations

import os
from typing import TYPE_CHECKING, Any

from robodesc.emit.common.target import EmitRequest, Emitted, Target, WorldAlone
from robodesc.emit.mjcf.actuators import FROM_TARGET, joint_kind
from robodesc.emit.mjcf.check import check_mjcf
from robodesc.emit.mjcf.options import MjcfOptions
from robodesc.emit.mjcf.scene import scene_name
from robodesc.ir.diagnostics import Findings
from robodesc.ir.model import Robot
from robodesc.ir.rules import lookup

if TYPE_CHECKING:
    from robodesc.emit.common.stance import Stance
    from robodesc.emit.common.world import PlacedWorld

STAGE = "emit:mjcf"


def emit_target(robot: Robot, request: EmitRequest, findings: Findings) -> Emitted:
    from robodesc.emit.mjcf.emitter import check_depth, emit_mjcf  # numpy and the writer: only when writing

    out = request.output("MJCF is written to a file: give one with -o OUT/robot.xml")
    check_depth(robot)  # before the derived gains, which take a while on a tree MuJoCo cannot read
    request.default("init_pos", robot.placement.xyz if robot.placement is not None else None)
    stance = _default_pose(robot, request, findings)
    _default_gains(robot, request, findings, stance)
    _source_gains(robot, request, findings)
    if request.world is not None:
        _place_in_world(robot, request, stance)
    files = emit_mjcf(
        robot,
        out,
        request.options,
        findings,
        mesh_paths=request.mesh_paths,
        given=request.given,
        final_name=os.path.basename(request.final or out),
        world=request.world,
    )
    extra = {"mjcf_options": request.options, "drives": _asked_drives(robot, request)}
    if request.world is not None:
        extra["world_probes"] = request.world.probes(grid=True)  # where check.py asks MuJoCo for the ground
    return Emitted(files=files, extra=extra)


def _default_pose(robot: Robot, request: EmitRequest, findings: Findings) -> Stance:
    """The ``home`` pose where the user gave none (docs/mjcf.md, "Defaults and why").

    The base was decided before the emitter, as for every target (emit/common/base.py: a robot on
    three or more legs floats, so that scene.xml drops it onto its feet). A floating robot's home
    keyframe is its stance (the Isaac folder's default pose: named pose, else the legged heuristic),
    with the root at the stance's spawn height. The body itself stays at the zero pose's height: at
    qpos0 its straight legs must not start in the floor.
    """
    # Loaded here, not at import: building the CLI's parser imports this module, and these read meshes.
    from robodesc.emit.common.default_pose import default_pose, given_positions, pose_table, spawn_height

    options: MjcfOptions = request.options
    wanted = given_positions(robot, options.init_joint_pos)
    floating = not options.fix_base and robot.root.name != "world"
    stance = default_pose(robot, wanted, floating, findings, STAGE)
    if not wanted and (floating or stance.source != "zeros"):
        options.init_joint_pos = pose_table(robot, stance)
    if floating:
        if options.init_pos is None:
            options.home_height = spawn_height(stance)
        _contact_defaults(robot, request, stance, findings)
    return stance


def _place_in_world(robot: Robot, request: EmitRequest, stance: Stance) -> None:
    """The root on the world's ground at the spawn point (emit/common/world.py): the body where its
    zero pose clears the ground, the ``home`` keyframe where its stance does (a given --init-pos wins)."""
    from robodesc.emit.common.stance import Stance as _Stance
    from robodesc.emit.common.stance import complete

    options: MjcfOptions = request.options
    placed = request.world
    assert placed is not None
    if "init_pos" in request.given:
        return
    floating = not options.fix_base and robot.root.name != "world"
    zero = _Stance(complete(robot, {}), "zeros")
    # On the heightfield scene.xml writes, not the mesh it was made from (they differ by the grid's error).
    roots = placed.root_positions(robot, zero, floating, grid=True)
    options.init_pos = roots[0]
    homes = (
        [r[2] for r in placed.root_positions(robot, stance, floating, grid=True)] if floating else [r[2] for r in roots]
    )
    if floating:
        options.home_height = homes[0]
    if len(roots) > 1:
        options.copies = tuple(zip(roots, homes, strict=True))


def _contact_defaults(robot: Robot, request: EmitRequest, stance: Stance, findings: Findings) -> None:
    """A floating robot on three legs or more gets mujoco_menagerie's legged contact: an elliptic friction cone with
    impratio 100 (no sliding under a standing load: with MuJoCo's pyramidal cone and impratio 1 the
    quadrupeds crept 0.14-0.64 m in 3 s, issue 35) and feet with torsional and rolling friction."""
    options: MjcfOptions = request.options
    # Three legs or more: on Talos (two, Gazebo soles) the elliptic cone cost 2.5x the steps per
    # second and it stood as well without (docs/mjcf.md).
    if len(stance.legs) < 3:
        return
    from robodesc.emit.common.stance import foot_colliders

    options.feet = foot_colliders(robot, stance)
    if "cone" not in request.given:
        options.cone = "elliptic"
    if "impratio" not in request.given:
        options.impratio = 100.0
    findings.info(
        "mjcf-legged-contact",
        f"legged contact defaults: cone {options.cone}, impratio {options.impratio:g}; feet "
        f"{', '.join(options.feet)} with condim 6, priority 1 and friction 0.8 0.02 0.01 where the source gives "
        "none (mujoco_menagerie's legged robots); --mjcf-cone and --mjcf-impratio choose otherwise",
        element=f"robot {robot.name!r}",
        stage=STAGE,
    )


def _default_gains(robot: Robot, request: EmitRequest, findings: Findings, stance: Stance) -> None:
    """Gains the user did not give are derived per joint, as the Isaac folder's are
    (emit/common/gains.py): one constant kp is too stiff for a 10 g finger at MuJoCo's timestep
    (mujoco_menagerie's test went to NaN on 18 corpus robots with kp 100) and too weak for a knee.
    A floating robot's gains depend on the legs it stands on; a fixed one's on its zero pose."""
    options: MjcfOptions = request.options
    if options.target_type == "none" or {"stiffness", "damping"} <= request.given:
        return
    from robodesc.emit.common.gains import fill_default_gains

    floating = not options.fix_base and robot.root.name != "world"
    fill_default_gains(robot, options, request.given, stance, floating, findings, STAGE)


def _source_gains(robot: Robot, request: EmitRequest, findings: Findings) -> None:
    """The source's own servo gains (an MJCF's actuators) over the derived ones, where the user gave none."""
    from robodesc.emit.common.source_drives import apply_source_gains

    if request.options.target_type == "none":
        return
    count = apply_source_gains(robot, request.options, request.given)
    if count:
        findings.info(
            "source-gains",
            f"{count} joint(s) keep the gains of the source's own actuators (--stiffness/--damping override them)",
            element=f"robot {robot.name!r}",
            stage=STAGE,
        )


def _asked_drives(robot: Robot, request: EmitRequest) -> dict[str, tuple[float, float]]:
    """The (kp, kv) the options ask of each position actuator, SI: what validation compares."""
    options: MjcfOptions = request.options
    kind = options.actuator if "actuator" in request.given else FROM_TARGET[options.target_type]
    return {
        j.name: (
            lookup(options.stiffness, j.name, "stiffness") or 0.0,
            lookup(options.damping, j.name, "damping") or 0.0,
        )
        for j in robot.actuated_joints()
        if j.type.dof == 1 and joint_kind(kind, j, request.given) == "position"
    }


def world_alone(placed: PlacedWorld, out: str, options: Any, findings: Findings, validate: bool) -> WorldAlone:
    """A world file given as the input, written alone (robodesc.emit.mjcf.world.write_world_alone)."""
    from robodesc.emit.mjcf.world import write_world_alone  # the writer loads when it writes

    return write_world_alone(placed, out, options, findings, validate)


# The "mjcf" preset (passes/presets.py): MuJoCo refuses an invalid inertia on a moving body, so
# invalid ones are repaired from geometry, as the Isaac folder does, and each repair reported.
TARGET = Target(
    name="mjcf",
    emit=emit_target,
    summary="MuJoCo XML (robot.xml, scene.xml, meshes) for MuJoCo, MJX and Newton; checked by MuJoCo",
    suffixes=(".xml",),
    options=MjcfOptions,
    preset="mjcf",
    check=check_mjcf,
    # scene.xml is rewritten with each robot.xml: the earlier one is restored if the run fails.
    owned=lambda options, out: (scene_name(out),) if options.scene else (),
    derives_gains=True,
    worlds=True,
    world_alone=world_alone,
    # The writer copies or converts every mesh into the folder by default and writes no texture.
    copies=frozenset(),
    options_title="MJCF (-t mjcf; docs/mjcf.md)",
)
