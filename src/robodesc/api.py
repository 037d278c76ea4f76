"""The Python API: everything the CLI does, as functions.

>>> import robodesc
>>> result = robodesc.compile_to_urdf("robot.urdf.xacro", "out/robot.urdf",
...                                   package_paths={"my_pkg": "src/my_pkg"})
>>> [f.render() for f in result.findings]

Every compile writes to a staging location beside its output, validates it there and moves it into
place only when it passes: a source defect the output carries is a warning in ``result.findings``;
an output that differs from the source because of robodesc raises
:class:`~robodesc.pipeline.ValidationFailedError` (its ``result.validation`` holds the report) and
writes nothing (docs/diagnostics.md).

``source`` is a path (URDF, xacro, YAML, ``.holo``, a Python file defining ``build()``), a string of URDF XML, an IR :class:`Robot`,
or any object with a ``build() -> Robot`` method (the composition builder). Options are keyword
arguments; an unknown one raises :class:`ConfigError` naming the closest valid option.
"""

from __future__ import annotations

import dataclasses
import os
from typing import Any

from robodesc.frontends.load import Source, load_source
from robodesc.inspect_robot import InspectReport
from robodesc.ir.diagnostics import Findings
from robodesc.ir.model import Robot
from robodesc.options import build_options
from robodesc.pipeline import CompileResult, Progress, ValidationFailedError, compile_robot, verify_source
from robodesc.targets import DEFAULT_TARGET, target_spec
from robodesc.validation.report import ValidationReport

__all__ = [
    "CompileResult",
    "check",
    "compile_for_gazebo",
    "compile_for_isaac_sim",
    "compile_for_ros2",
    "compile_to",
    "compile_to_sdf",
    "compile_to_urdf",
    "compile_to_usd",
    "inspect",
    "load",
    "validate",
    "validate_file",
]


def _option_names(*classes: type[Any]) -> dict[str, str]:
    names: dict[str, str] = {}
    for cls in classes:
        for f in dataclasses.fields(cls):
            if f.name not in ("out_dir", "path_mode", "props"):
                names[f.name] = "target_options"
    return names


def _compile(
    target: str,
    source: Source,
    out: str | os.PathLike[str] | None,
    progress: Progress | None,
    options: dict[str, Any],
    *classes: type[Any],
) -> CompileResult:
    opts = build_options(options, extra_names={**_pass_names(), **_option_names(*classes)})
    return compile_robot(source, target, _out(out), opts, **({"progress": progress} if progress else {}))


def _out(path: str | os.PathLike[str] | None) -> str | None:
    return os.fspath(path) if path is not None else None


def _pass_names() -> dict[str, str]:
    from robodesc.passes.options import OPTION_NAMES

    return {name: "passes" for name in OPTION_NAMES}


def load(source: Source, **options: Any) -> Robot:
    """Read ``source`` into the IR and verify it (warnings are dropped; use ``robodesc inspect`` to see them)."""
    opts = build_options(options)
    findings = Findings()
    robot = load_source(source, opts.load, findings)
    verify_source(robot, opts, findings)
    return robot


def compile_to(
    source: Source,
    target: str,
    out: str | os.PathLike[str] | None = None,
    *,
    progress: Progress | None = None,
    **options: Any,
) -> CompileResult:
    """Compile ``source`` to the target named ``target`` (``robodesc compile -t TARGET``). Options:
    every input and pass option, the target's own (its options class's fields) and the world's
    (``world``, ``terrain``, ``spawn`` ...: docs/worlds.md). A world file as ``source`` compiles the
    world alone (``result.world`` names it)."""
    from robodesc.plugins import load_plugins

    load_plugins(tuple(options.get("plugins", ())))
    cls = target_spec(target).options
    return _compile(target, source, out, progress, options, *((cls,) if cls else ()))


def compile_to_urdf(
    source: Source, out: str | os.PathLike[str] | None = None, *, progress: Progress | None = None, **options: Any
) -> CompileResult:
    """Compile to URDF. With ``out`` the file is written atomically; ``result.text`` always holds it.

    Pass options (``preset``, ``rename``, ``armature``, ``strip``, ``repair_inertia``, ``merge_fixed``,
    ``sanitize_names``, ``unique_materials``, ``copy_meshes`` ...) are accepted by every compile
    function; see docs/passes.md."""
    return compile_to(source, "urdf", out, progress=progress, **options)


def compile_to_sdf(
    source: Source, out: str | os.PathLike[str] | None = None, *, progress: Progress | None = None, **options: Any
) -> CompileResult:
    """Compile to SDF (Gazebo Harmonic, SDF 1.10 by default). Options: ``version``, ``world``,
    ``fix_base``, ``flavour`` ("harmonic" | "classic"), ``pose_frames``, ``step_size`` ... (see docs/sdf.md)."""
    from robodesc.emit.sdf import SdfOptions

    return _compile("sdf", source, out, progress, options, SdfOptions)


def compile_for_ros2(
    source: Source, out_dir: str | os.PathLike[str], *, progress: Progress | None = None, **options: Any
) -> CompileResult:
    """Write the ROS 2 / Gazebo Harmonic folder: URDF with ``<ros2_control>``, controllers.yaml,
    launch file, ros_gz_bridge YAML and world. Options: ``command_interface``, ``controller``,
    ``update_rate``, ``spawn_z``."""
    from robodesc.emit.ros2 import Ros2Options

    return _compile("ros2", source, out_dir, progress, options, Ros2Options)


def compile_for_gazebo(
    source: Source, out_dir: str | os.PathLike[str], *, progress: Progress | None = None, **options: Any
) -> CompileResult:
    """The ROS 2 folder plus an SDF world holding the model (``<robot>.sdf``)."""
    from robodesc.emit.ros2 import Ros2Options
    from robodesc.emit.sdf import SdfOptions

    result = _compile("ros2", source, out_dir, progress, options, Ros2Options, SdfOptions)
    sdf_opts = {k: v for k, v in options.items() if k in {f.name for f in dataclasses.fields(SdfOptions)}}
    sdf_path = os.path.join(os.fspath(out_dir), f"{result.robot.name}.sdf")
    sdf = compile_to_sdf(result.robot, sdf_path, world=True, **sdf_opts)
    result.files["sdf"] = sdf_path
    result.findings.extend(sdf.findings)
    return result


def compile_to_usd(
    source: Source, out: str | os.PathLike[str], *, progress: Progress | None = None, **options: Any
) -> CompileResult:
    """Compile to a UsdPhysics articulation (``.usda``, ``.usdc`` or ``.usd``). Names are sanitized
    and materials made unique first (USD needs both). Options: ``fix_base``, ``drive_type``,
    ``target_type``, ``stiffness``/``damping`` (SI; a number or a ``{regex: value}`` table),
    ``collision_approximation``, ``layered``, ``solver_position_iterations``, ... (docs/usd.md)."""
    from robodesc.emit.usd import UsdOptions

    return _compile("usd", source, out, progress, options, UsdOptions)


def compile_for_isaac_sim(
    source: Source, out_dir: str | os.PathLike[str] | None = None, *, progress: Progress | None = None, **options: Any
) -> CompileResult:
    """Everything Isaac Sim and Isaac Lab need, in one folder: the USD asset, the Isaac-flavoured
    URDF, ``importer_settings.json``, an Isaac Lab ``ArticulationCfg`` module, the validation report
    and the findings. Runs the ``isaac_sim`` preset unless ``preset`` says otherwise.

    ``out_dir=None`` writes into a new temporary folder (its paths are in ``result.files``).
    Options (docs/isaac.md): ``fix_base``, ``merge_fixed_joints``, ``drive_type`` (force |
    acceleration), ``target_type`` (none | position | velocity), ``stiffness``/``damping`` (SI, a
    number or ``{regex: value}``), ``armature`` (rules), ``self_collision``,
    ``collision_approximation``, ``solver_position_iterations``, ``solver_velocity_iterations``,
    ``contact_offset``, ``rest_offset``, ``init_pos``, ``init_joint_pos``, ``layered``,
    ``isaac_lab_version`` ("3", the default, or "2": the generated Isaac Lab module's target), and every
    pass and input option. The world options (``world``, ``terrain``, ``terrain_size``, ``spawn`` (a
    point, or a list of points for copies), ``model_path``, ``cords``) add the world stage, the ground
    for Isaac Lab's ``TerrainImporterCfg`` and the module's ``make_terrain_cfg``/``make_sim_cfg``
    (docs/worlds.md, "The Isaac folder's world").
    """
    import tempfile

    from robodesc.emit.isaac import IsaacSettings

    target = os.fspath(out_dir) if out_dir is not None else tempfile.mkdtemp(prefix="robodesc-isaac-")
    return _compile("isaac", source, target, progress, options, IsaacSettings)


def isaac_physics_layer(
    source: Source,
    onto: str | os.PathLike[str],
    out: str | os.PathLike[str],
    *,
    stage: str | os.PathLike[str] | None = None,
    progress: Progress | None = None,
    **options: Any,
) -> CompileResult:
    """``robodesc layer``: the Isaac folder's ``<robot>_physics.usda`` for a robot Isaac Sim 6's URDF
    importer already imported to ``onto``, its prim paths read from that USD (docs/isaac.md), written
    to ``out``. Takes :func:`compile_for_isaac_sim`'s options; prims the layer cannot find are named
    in the warning ``isaac-layer-missing``. ``stage``: also write the stage to open there, a root
    layer sublayering ``out`` over ``onto`` with the importer's ``physx`` variant selected
    (``emit/isaac/composed.py``)."""
    import shutil
    import tempfile

    from robodesc.emit.isaac import IsaacSettings

    with tempfile.TemporaryDirectory(prefix="robodesc-layer-") as tmp:
        options = {**options, "importer_usd": os.path.abspath(onto)}
        result = _compile("isaac", source, os.path.join(tmp, "isaac"), progress, options, IsaacSettings)
        shutil.copyfile(result.files["physics_layer"], out)
    result.files = {"physics_layer": os.fspath(out)}
    if stage is not None:
        from robodesc.emit.isaac.composed import write_composed_stage
        from robodesc.emit.isaac.importer_layout import layout_from_usd

        robot = layout_from_usd(os.fspath(onto), result.robot).robot
        result.files["stage"] = write_composed_stage(os.fspath(stage), robot, [os.fspath(out), os.fspath(onto)])
    return result


def inspect(source: Source, **options: Any) -> InspectReport:
    """Load ``source`` and describe it: tree, DOF, total mass and every finding (``robodesc inspect``)."""
    from robodesc.inspect_robot import describe
    from robodesc.plugins import load_plugins

    opts = build_options(options)
    load_plugins(opts.plugins)
    return describe(source, opts)


def check(source: Source, target: str = DEFAULT_TARGET, *, dynamics: Any = False, **options: Any) -> CompileResult:
    """Compile ``source`` to ``target`` in a temporary folder and validate it; the result (its
    ``validation`` report and findings) is returned whether or not validation passed.

    ``dynamics`` (True, a :class:`~robodesc.validation.dynamics.DynamicsOptions` or its fields as a
    dict) also simulates hold, drop and slide in the engines that read the outputs
    (docs/dynamics.md); the report is ``result.dynamics``."""
    import tempfile

    from robodesc.plugins import load_plugins

    load_plugins(tuple(options.get("plugins", ())))
    spec = target_spec(target)
    on_world = isinstance(options.get("world"), str | os.PathLike) or bool(options.get("terrain"))
    if dynamics is not False and dynamics is not None and on_world and "contact_sensors" not in options:
        # The stand on a world reads the feet's force (docs/dynamics.md, "On a world").
        options = {**options, "contact_sensors": True}
    with tempfile.TemporaryDirectory(prefix="robodesc-validate-") as tmp:
        out = spec.output_name(os.path.join(tmp, "robot"))
        try:
            result = compile_to(source, target, out, **{**options, "validate": True})
        except ValidationFailedError as failed:  # nothing written; the report says why
            result = failed.result
        if dynamics is not False and dynamics is not None and os.path.exists(out):
            from robodesc.check_dynamics import carry_source_refusals, dynamics_options, run_for

            opts = dynamics_options(dynamics, options)
            result.dynamics = run_for(source, result.robot, target, out, tmp, opts, options, compile_to, result)
            carry_source_refusals(result.dynamics, result.findings)
        return result


def validate(
    source: Source, target: str = DEFAULT_TARGET, *, dynamics: Any = False, **options: Any
) -> ValidationReport | None:
    """Compile ``source`` to ``target`` in a temporary folder and return the validation report
    (``report.ok``, ``report.to_text()``, ``to_json()``, ``to_markdown()``); None when the target
    has no check. With ``dynamics``, the simulation's verdicts are added to it as ``dynamics:*``
    rows (``check(..., dynamics=True).dynamics`` has the whole table)."""
    result = check(source, target, dynamics=dynamics, **options)
    report = result.validation
    if report is not None and result.dynamics is not None:
        for row in result.dynamics.checks:
            report.add(
                f"dynamics:{row.name}", row.status, row.element, row.message, error=row.error, tolerance=row.tolerance
            )
    return report


def validate_file(path: str, options: Any = None, load_options: Any = None) -> ValidationReport:
    """Load ``path`` (URDF/xacro), emit URDF with absolute mesh paths and validate it in MuJoCo.

    ``options`` is a :class:`~robodesc.validation.options.ValidateOptions`, ``load_options`` a
    :class:`~robodesc.frontends.options.LoadOptions`. Source defects the IR verifier finds
    (non-physical inertia, dangling references) are added as ``source`` checks: warnings, since they
    are the input's and a faithful compiler keeps them. Raises
    :class:`~robodesc.ir.diagnostics.RobodescError` only when the file cannot be read at all.
    """
    from robodesc.emit.common.paths import PathMode
    from robodesc.emit.urdf import UrdfOptions, emit_urdf
    from robodesc.frontends.load import load_path
    from robodesc.frontends.options import LoadOptions
    from robodesc.validation.mujoco_urdf import validate_urdf_text
    from robodesc.validation.options import ValidateOptions
    from robodesc.validation.report import ValidationReport
    from robodesc.validation.source import add_source_findings

    opts = options or ValidateOptions()
    lopts = load_options or LoadOptions()
    if not opts.package_paths and lopts.package_paths:
        opts.package_paths = dict(lopts.package_paths)
    robot = load_path(path, lopts).robot
    base_dir = os.path.dirname(os.path.abspath(path))
    text = emit_urdf(robot, UrdfOptions(path_mode=PathMode.ABSOLUTE, out_dir=base_dir))
    report = ValidationReport(robot=robot.name, target="urdf", consumer="mujoco")
    add_source_findings(robot, report)
    report.extend(validate_urdf_text(robot, text, base_dir, opts))
    report.info["input"] = path
    return report


def __getattr__(name: str) -> Any:
    """``compile_to_<target>`` for every target of the table that has no named function above
    (``robodesc.compile_to_mjcf``): a new target needs no edit here."""
    target = name.removeprefix("compile_to_")
    from robodesc.targets import TARGETS

    if name.startswith("compile_to_") and target in TARGETS:

        def compile_to_target(
            source: Source,
            out: str | os.PathLike[str] | None = None,
            *,
            progress: Progress | None = None,
            **options: Any,
        ) -> CompileResult:
            return compile_to(source, target, out, progress=progress, **options)

        compile_to_target.__name__ = name
        compile_to_target.__doc__ = f"Compile to {target}: {target_spec(target).summary}. Options as for compile_to()."
        return compile_to_target
    raise AttributeError(f"module 'robodesc.api' has no attribute {name!r}")
