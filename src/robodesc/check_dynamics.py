"""``validate --dynamics``: compile what the engines read, then simulate (validation/dynamics).

Driver code: it knows targets only through the table. Each engine reads some target's output
(``validation.dynamics.READERS``, keyed by target name); the engines asked for but not reading the
checked target get their target compiled beside it in the same scratch folder, with the input and
pass options and only the target options their class declares. Newton runs only when asked
(``engines``) or when the checked target is the one it reads: its first import costs seconds.
PhysX runs whenever the checked target is USD or a folder with a USD at its top (the Isaac folder):
it reads that file as written (a SKIP row when no interpreter has ovphysx).

Where the caller gives no pose or gains, the scenarios start from the Isaac folder's defaults
(docs/isaac.md, "Defaults that stand"; :func:`default_stance`): a robot whose root is free gets the
pose a floating robot stands in, and every driven joint the gains derived from its inertia, effort
and gravity load, so engines are compared from a stance the robot can keep.
"""

from __future__ import annotations

import copy
import dataclasses
import os
import re
from collections.abc import Callable, Mapping, Sequence
from typing import Any

from robodesc.emit.common.base import choose_base
from robodesc.ir.diagnostics import Finding, Findings, RobodescError, Severity
from robodesc.ir.model import Robot
from robodesc.targets import TARGETS, target_spec
from robodesc.validation.dynamics import READERS, DynamicsOptions, DynamicsReport, run_dynamics
from robodesc.validation.dynamics.run import STANDS_ON_WORLD, folder_files, joining, kind_of
from robodesc.validation.dynamics.source import write_source
from robodesc.validation.report import Status

# Engines run when none are named: cheap to import, and together they read two formats.
DEFAULT_ENGINES = ("mujoco", "drake")


def dynamics_options(given: DynamicsOptions | bool | Mapping[str, Any], options: Mapping[str, Any]) -> DynamicsOptions:
    """The dynamics options, with the compile's gains, pose and packages where not set."""
    if isinstance(given, DynamicsOptions):
        opts = dataclasses.replace(given)
    elif isinstance(given, Mapping):
        opts = DynamicsOptions(**given)
    else:
        opts = DynamicsOptions()
    opts.stiffness = opts.stiffness if opts.stiffness is not None else options.get("stiffness")
    opts.damping = opts.damping if opts.damping is not None else options.get("damping")
    opts.pose = opts.pose if opts.pose is not None else options.get("init_joint_pos")
    opts.package_paths = opts.package_paths or dict(options.get("package_paths", {}))
    opts.fix_base = opts.fix_base if opts.fix_base is not None else options.get("fix_base")
    return opts


def run_for(
    source: Any,
    robot: Robot,
    target: str,
    out: str,
    folder: str,
    opts: DynamicsOptions,
    options: Mapping[str, Any],
    compile_to: Callable[..., Any],
    compiled: Any = None,
) -> DynamicsReport:
    """``compile_to`` is the API's (passed in: the API imports this module, not the other way);
    ``compiled`` the checked target's CompileResult (its files: the world it wrote)."""
    files: dict[str, str] = {}
    world = _has_world(options)
    worlds: dict[str, str] = {}
    if world and compiled is not None:
        _world_file(target, compiled, worlds)
    if target in READERS:
        files[target] = out
    elif target_spec(target).folder:
        files.update(folder_files(out))
    also = joining(files)
    engines = tuple(opts.engines) or tuple(dict.fromkeys((*DEFAULT_ENGINES, *_engine_of(target), *also)))
    robot = _source_robot(source, options) or robot
    # The base every compiled file has (emit/common/base.py): a welded robot is not dropped.
    opts = dataclasses.replace(opts, fix_base=choose_base(robot, opts.fix_base).fixed)
    # The checked file's drives are what its target wrote: a target that writes its options'
    # constant gains (-t usd: 100 / 1) is simulated with them everywhere, not with derived ones
    # Newton would not read from that file. Then the pose and the gains the others lack.
    opts = _with_source_gains(robot, default_stance(robot, _written_gains(target, opts)), options)
    for engine in engines:
        if any(engine in READERS.get(kind, ()) for kind in files):
            continue
        # With a world, the target that can hold it (MuJoCo: MJCF's scene.xml, not URDF).
        name = next(
            (
                t
                for t in TARGETS
                if engine in READERS.get(t, ()) and not target_spec(t).folder and (target_spec(t).worlds or not world)
            ),
            None,
        )
        if name is None:
            continue
        path = target_spec(name).output_name(os.path.join(folder, f"dynamics-{name}", "dynamics-robot"))
        os.makedirs(os.path.dirname(path), exist_ok=True)  # each its own folder: MJCF's scene.xml beside it
        try:
            side = {**_options_for(target, name, options), **_gains_for(name, opts, options)}
            if world and engine not in STANDS_ON_WORLD:
                # Drake stands on no world (its hold, drop and slide take the robot alone: an SDF
                # world's static terrain link would weigh in its total mass).
                side = {k: v for k, v in side.items() if k not in _WORLD_OPTIONS}
            elif world:
                # The world even when the checked target declares ``world`` as its own option (SDF's).
                side.update({k: v for k, v in options.items() if k in _WORLD_OPTIONS})
            result = compile_to(source, name, path, **side, validate=False)
        except RobodescError:
            continue  # the checked target's validation reports what is wrong with the robot
        files[name] = path
        if world:
            _world_file(name, result, worlds)
    if world:
        _robot_alone(source, target, files, folder, options, compile_to)
    opts = dataclasses.replace(opts, engines=engines)
    if world:
        from robodesc.check_world import world_stand

        sensors = _sensor_links(compiled)
        opts.world = world_stand(robot, opts, options, worlds, sensors, folder)
    return run_dynamics(robot, files, opts, source_urdf=_source_file(source, robot, folder, options))


_WORLD_OPTIONS = ("world", "terrain", "terrain_size", "terrain_resolution", "spawn", "cords", "contact_sensors")


def _robot_alone(
    source: Any,
    target: str,
    files: dict[str, str],
    folder: str,
    options: Mapping[str, Any],
    compile_to: Callable[..., Any],
) -> None:
    """A checked file with a world that only engines standing on none read (an SDF world, Drake):
    its hold, drop and slide take the robot compiled alone (the world's static links would weigh
    in its total mass and stand under its drop)."""
    if target not in files or any(e in STANDS_ON_WORLD for e in READERS.get(target, ())):
        return
    path = target_spec(target).output_name(os.path.join(folder, "dynamics-alone", "dynamics-robot"))
    os.makedirs(os.path.dirname(path), exist_ok=True)
    alone = {k: v for k, v in options.items() if k not in _WORLD_OPTIONS}
    try:
        compile_to(source, target, path, **alone, validate=False)
    except RobodescError:
        return
    files[target] = path


def _has_world(options: Mapping[str, Any]) -> bool:
    return isinstance(options.get("world"), str | os.PathLike) or bool(options.get("terrain"))


def _world_file(kind: str, result: Any, worlds: dict[str, str]) -> None:
    """The world a compile wrote, by the kind of file an engine reads: USD's world stage, MJCF's
    scene (SDF's world is its one file, which no engine here stands a robot on)."""
    files = getattr(result, "files", {}) or {}
    path = files.get("world") or files.get("scene")
    if path and kind in READERS:
        worlds[kind] = path


def _sensor_links(compiled: Any) -> tuple[str, ...]:
    robot = getattr(compiled, "robot", None)
    if robot is None:
        return ()
    return tuple(s.parent for s in robot.sensors if s.type.value == "contact")


def stage_dynamics(
    source: Any,
    stages: Mapping[str, str],
    options: Mapping[str, Any],
    dynamics: DynamicsOptions | Mapping[str, Any] | None = None,
) -> dict[str, DynamicsReport]:
    """Each USD stage in ``stages`` (label -> path) run through the scenarios, in the engines that
    read USD (PhysX unless ``dynamics`` names others), from the stance ``validate --dynamics``
    gives ``source`` compiled with ``options``: the same robot, base, pose and gains for every
    stage, so the stages can be compared with
    :func:`robodesc.validation.dynamics.routes.behaviour_differences`. A stage need not be robodesc's
    output: the Isaac Sim 6 route's composed stage (``emit/isaac/composed.py``) is one. Each joint
    and body is found by ``displayName``, else by name, the source's or the one robodesc's
    ``sanitize_names`` gives it (what Isaac Sim 6's import of the Isaac URDF names it)."""
    from robodesc.passes.sanitize_names import unique_names

    robot = _load_robot(source, options)
    opts = dynamics_options(dynamics if dynamics is not None else True, options)
    renamed = {
        new: old
        for names in ([j.name for j in robot.joints], [link.name for link in robot.links])
        for old, new in unique_names(names).items()
    }
    opts = dataclasses.replace(opts, names={**renamed, **opts.names})
    if not opts.engines:
        opts = dataclasses.replace(opts, engines=("physx",))
    opts = dataclasses.replace(opts, fix_base=choose_base(robot, opts.fix_base).fixed)
    opts = default_stance(robot, opts)
    reports = {}
    for label, path in stages.items():
        kind = kind_of(path)  # by suffix: a stage is a .usd/.usda/.usdc
        if kind is None:
            raise RobodescError(f"{path}: no engine here reads this kind of file", element=f"stage {label!r}")
        reports[label] = run_dynamics(robot, {kind: path}, opts)
    return reports


def default_stance(robot: Robot, opts: DynamicsOptions) -> DynamicsOptions:
    """``opts`` with the Isaac folder's default pose and derived gains where it has none: the pose
    ``--isaac-sim --no-fix-base`` spawns the robot in when its root is free (``world`` welds it:
    zeros, as a fixed Isaac robot), and per-joint gains from the same formula (emit/common/gains.py).
    Computed on a copy lowered as the Isaac preset lowers it (inertia filled and repaired, limits
    completed), so the numbers are the folder's; joint names are the source's."""
    from robodesc.emit.common.default_pose import default_pose
    from robodesc.emit.common.gains import derived_gains
    from robodesc.ir.rules import lookup
    from robodesc.passes.options import PassOptions, RepairPolicy
    from robodesc.passes.pipeline import run_passes

    if opts.pose is not None and opts.stiffness is not None and opts.damping is not None:
        return opts
    lowered = copy.deepcopy(robot)
    try:
        run_passes(
            lowered,
            options=PassOptions(fill_inertia=True, repair_inertia=RepairPolicy.GEOMETRY, isaac_limits=True),
        )
    except RobodescError:
        lowered = copy.deepcopy(robot)
    floating = not (opts.fix_base if opts.fix_base is not None else choose_base(robot, None).fixed)
    driven = [j for j in lowered.actuated_joints() if j.type.dof == 1]
    wanted = {}
    if opts.pose is not None:
        wanted = {j.name: v for j in driven if (v := lookup(opts.pose, j.name, "pose")) is not None}
    # The Isaac folder's choice; its findings are the compile's business, not this check's.
    stance = default_pose(lowered, wanted, floating, Findings(), "dynamics")
    user_kp = None
    if opts.stiffness is not None:
        user_kp = {j.name: lookup(opts.stiffness, j.name, "stiffness") or 0.0 for j in driven}
    gains = derived_gains(lowered, stance, floating, user_kp)
    out = dataclasses.replace(opts)
    if opts.pose is None:
        out.pose = {re.escape(j.name): stance.positions.get(j.name, 0.0) for j in driven}
    if opts.stiffness is None:
        out.stiffness = {re.escape(n): g.stiffness for n, g in gains.items()}
    if opts.damping is None:
        out.damping = {re.escape(n): g.damping for n, g in gains.items()}
    given = "given" if opts.pose is not None else stance.source
    out.defaults = f"pose: {given}; gains: " + (
        "given" if opts.stiffness is not None and opts.damping is not None else "derived (docs/isaac.md)"
    )
    return out


def _with_source_gains(robot: Robot, opts: DynamicsOptions, options: Mapping[str, Any]) -> DynamicsOptions:
    """The source's own servos (an MJCF's actuators, ``Joint.drive``) ahead of the constant or derived
    gains, where the user gave none: every target writes them (emit/common/source_drives.py), so the
    USD Newton and PhysX read carries menagerie's kp 2000 while a URDF carries no gains. Without this
    MuJoCo and Drake simulated the constant 100 beside them and the engines "disagreed" on a hold
    that differed only in the gains each was given."""
    from robodesc.emit.common.source_drives import apply_source_gains

    out = dataclasses.replace(opts)
    given = {k for k in ("stiffness", "damping") if k in options}
    count = apply_source_gains(robot, out, given)
    if count:
        out.defaults = f"{out.defaults}; the source's servos on {count} joints"
    return out


def _source_robot(source: Any, options: Mapping[str, Any]) -> Robot | None:
    """The source's IR, before any target's passes: the checked target's robot may carry renamed
    joints (USD sanitizes ``0`` to ``a0``) that neither the pose table nor the other files know.
    Every file names its joints after the source (USD through ``displayName``)."""
    try:
        return _load_robot(source, options)
    except RobodescError:
        return None


def _load_robot(source: Any, options: Mapping[str, Any]) -> Robot:
    from robodesc.frontends.load import load_source
    from robodesc.frontends.options import LoadOptions
    from robodesc.options import build_options

    loading = {f.name for f in dataclasses.fields(LoadOptions)}
    opts = build_options({k: v for k, v in options.items() if k in loading})
    return load_source(source, opts.load, Findings())


def _written_gains(target: str, opts: DynamicsOptions) -> DynamicsOptions:
    spec = target_spec(target)
    if spec.derives_gains or spec.options is None:
        return opts
    defaults = {f.name: f.default for f in dataclasses.fields(spec.options)}
    out = dataclasses.replace(opts)
    if out.stiffness is None and isinstance(defaults.get("stiffness"), int | float):
        out.stiffness = float(defaults["stiffness"])  # type: ignore[arg-type]
    if out.damping is None and isinstance(defaults.get("damping"), int | float):
        out.damping = float(defaults["damping"])  # type: ignore[arg-type]
    return out


def _gains_for(name: str, opts: DynamicsOptions, options: Mapping[str, Any]) -> dict[str, Any]:
    """The simulated gains for a file compiled for another engine, where its target takes them, so
    every engine drives the robot alike."""
    spec = target_spec(name)
    fields = {f.name for f in dataclasses.fields(spec.options)} if spec.options else set()
    return {
        k: getattr(opts, k)
        for k in ("stiffness", "damping")
        if k in fields and k not in options and getattr(opts, k) is not None
    }


def _engine_of(target: str) -> tuple[str, ...]:
    return READERS.get(target, ())


def _options_for(main: str, other: str, options: Mapping[str, Any]) -> dict[str, Any]:
    """The options ``other`` accepts: everything but the main target's own, unless ``other``
    declares it too (``stiffness`` for two targets)."""
    cls_main, cls_other = target_spec(main).options, target_spec(other).options
    own = {f.name for f in dataclasses.fields(cls_main)} if cls_main else set()
    theirs = {f.name for f in dataclasses.fields(cls_other)} if cls_other else set()
    return {k: v for k, v in options.items() if k not in own or k in theirs}


def _source_file(source: Any, robot: Robot, folder: str, options: Mapping[str, Any]) -> str | None:
    """The input as a file MuJoCo and Drake read, when it is one (a URDF, or a xacro expanded with
    the compile's arguments); None for compositions and in-memory robots."""
    if not isinstance(source, str | os.PathLike) or not os.path.isfile(source):
        return None
    from robodesc.frontends.packages import PackageResolver
    from robodesc.frontends.xacro_expand import expand_xacro

    path = os.fspath(source)
    try:
        text = expand_xacro(
            path,
            dict(options.get("xacro_args", {})),
            PackageResolver(explicit=dict(options.get("package_paths", {})), input_file=path),
            Findings(),
            allowed_env=tuple(options.get("allowed_env", ())),
        )
    except (RobodescError, OSError, UnicodeDecodeError):
        return None  # not XML: a composition, whose only description is the IR
    return write_source(robot, text, folder)


def carry_source_refusals(report: DynamicsReport, findings: Sequence[Finding]) -> None:
    """An engine refusing an output for a defect of the source the compile named (a mass without a
    tensor that no readable geometry gives, an ``<inertial>`` without ``<mass>``): the same row the
    structural validation made the source's, a WARN here too, naming the defect."""
    from robodesc.pipeline import DOCUMENT_DEFECTS

    named = [f for f in findings if f.severity is Severity.WARNING and f.code in DOCUMENT_DEFECTS]
    if not named:
        return
    first = named[0]
    where = f"{first.loc}: " if first.loc is not None else ""
    for row in report.checks:
        if row.name == "load" and row.status is Status.FAIL:
            row.status = Status.WARN
            row.message += f" (the source's defect: {where}{first.element}: {first.message})"
