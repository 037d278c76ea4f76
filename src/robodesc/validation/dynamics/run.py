"""Run the scenarios on every file given, in the engine that reads it, and judge the runs.

Which engine reads what: MuJoCo reads URDF and MJCF, Drake reads SDF (and the source URDF, for the
source comparison), Newton and PhysX read USD (each in its own interpreter, :mod:`.newton_run`,
:mod:`.physx_run`). An engine that is not installed is a SKIP row, never a failure.
"""

from __future__ import annotations

import dataclasses
import os
import time
from collections.abc import Callable, Mapping

from robodesc.ir.model import Robot
from robodesc.validation.dynamics.result import READS_DIFFERENTLY, DynamicsReport, Run
from robodesc.validation.dynamics.scenarios import DynamicsOptions, Setup, make_setup
from robodesc.validation.dynamics.verdict import SOURCE, judge
from robodesc.validation.report import Status

SCENARIOS = ("hold-fixed", "drop", "slide")
# File kind (a target's name, or the suffix of a file given directly) -> the engines that read it,
# the first the one a file of that kind is compiled for when only that engine is asked.
READERS = {"urdf": ("mujoco",), "mjcf": ("mujoco",), "sdf": ("drake",), "usd": ("newton", "physx")}
ENGINES = tuple(dict.fromkeys(e for engines in READERS.values() for e in engines))
# Engines that join the default ones whenever a file they read is checked: PhysX, Isaac's engine,
# for every USD (a subprocess, started only then). Newton joins only for its own target.
JOINS_WHEN_READ = ("physx",)
# What a folder output offers the engines: the USD at its top (the Isaac folder's robot).
_FOLDER_KINDS = ("usd",)
# Files at that top that are layers, not stages to simulate: the Isaac folder's physics layer for
# Isaac Sim 6's importer (overs only, emit/isaac/physics_layer.py).
_LAYER_ENDINGS = ("_physics.usda",)
_SUFFIXES = {
    ".urdf": "urdf",
    ".xml": "mjcf",
    ".mjcf": "mjcf",
    ".sdf": "sdf",
    ".usd": "usd",
    ".usda": "usd",
    ".usdc": "usd",
}


def kind_of(path: str) -> str | None:
    """The file kind for a path (by suffix), or None when no engine here reads it."""
    return _SUFFIXES.get(os.path.splitext(path)[1].lower())


def folder_files(folder: str) -> dict[str, str]:
    """kind -> path for the files at the top of a folder output an engine reads (one per kind)."""
    try:
        names = sorted(os.listdir(folder))
    except OSError:
        return {}
    found: dict[str, list[str]] = {}
    for name in names:
        kind = kind_of(name)
        if name.endswith(_LAYER_ENDINGS):
            continue
        if kind in _FOLDER_KINDS and os.path.isfile(os.path.join(folder, name)):
            found.setdefault(kind, []).append(os.path.join(folder, name))
    return {kind: paths[0] for kind, paths in found.items() if len(paths) == 1}


def joining(files: Mapping[str, str]) -> tuple[str, ...]:
    """The engines of :data:`JOINS_WHEN_READ` that read one of ``files``' kinds."""
    return tuple(e for e in JOINS_WHEN_READ if any(e in READERS.get(kind, ()) for kind in files))


def engine_for(path: str) -> str | None:
    kind = kind_of(path)
    return None if kind is None else READERS[kind][0]


def run_dynamics(
    robot: Robot,
    files: Mapping[str, str],
    options: DynamicsOptions | None = None,
    source_urdf: str | None = None,
) -> DynamicsReport:
    """Simulate ``files`` (kind -> path, kinds as in :data:`READERS`) compiled from ``robot``.

    ``source_urdf`` is the input as URDF text's file (plain or xacro-expanded), when there is one:
    MuJoCo and Drake then run it too, and each output is compared with it in the same engine.
    """
    opts = options or DynamicsOptions()
    setup = make_setup(robot, opts)
    report = DynamicsReport(robot=robot.name, model=robot)
    report.info["pose_note"] = opts.defaults or "pose from the given table, else 0 clamped into limits"
    report.info["setup"] = setup.as_dict()
    started = time.perf_counter()
    wanted = set(opts.engines) or set(ENGINES)
    scenarios = SCENARIOS if setup.floating else tuple(s for s in SCENARIOS if s != "drop")
    if not setup.floating:
        why = "the base is welded" if opts.fix_base else "fewer than three links touch the ground at the home pose"
        report.add("drop", Status.SKIP, "robot", f"not run: {why}")
    if not any(link.collisions for link in robot.links):
        scenarios = tuple(s for s in scenarios if s != "slide")
        report.add("slide", Status.SKIP, "robot", "not run: the robot has no collider, so no material to slide")
    for kind, path in files.items():
        for engine in READERS.get(kind, ()):
            if engine in wanted:
                report.runs.extend(_run_engine(engine, robot, path, kind, setup, opts, report, scenarios))
        if source_urdf is not None and kind in ("urdf", "mjcf", "sdf"):
            src_engine = "drake" if kind == "sdf" else "mujoco"
            if not any(r.engine == src_engine and r.file == SOURCE for r in report.runs):
                src_setup = _source_setup(setup, report, src_engine, kind)
                runs = _run_engine(src_engine, robot, source_urdf, SOURCE, src_setup, opts, report, ("hold-fixed",))
                report.runs.extend(runs)
    if setup.world is not None:
        _stand(robot, setup, opts, report, wanted)
    judge(report, setup, opts.thresholds)
    report.info["seconds"] = round(time.perf_counter() - started, 3)
    return report


# The world file each engine stands the robot on (WorldStand.files is keyed by file kind).
_WORLD_KIND = {"mujoco": "mjcf", "newton": "usd", "physx": "usd"}
STANDS_ON_WORLD = tuple(_WORLD_KIND)  # the engines given a world file (Drake: none, DRAKE_NO_TERRAIN)
DRAKE_NO_TERRAIN = (
    "not run: Drake has no heightfield, and its point contact collides a mesh as its convex hull "
    "(a concave terrain only as a rigid hydroelastic mesh against compliant robot colliders, which "
    "the SDF robodesc writes does not declare)"
)


def _stand(robot: Robot, setup: Setup, opts: DynamicsOptions, report: DynamicsReport, wanted: set[str]) -> None:
    """The stand on the world in every engine asked for that reads a world file."""
    world = setup.world
    assert world is not None
    for engine in ENGINES:
        if engine not in wanted:
            continue
        kind = _WORLD_KIND.get(engine)
        if kind is None:
            report.add("stand", Status.SKIP, engine, DRAKE_NO_TERRAIN)
            continue
        path = world.files.get(kind)
        if path is None:
            report.add("stand", Status.SKIP, engine, f"not run: no {kind} world was compiled")
            continue
        for run in _run_engine(engine, robot, path, kind, setup, opts, report, ("stand",)):
            measure_stand(run, setup)
            report.runs.append(run)


def measure_stand(run: Run, setup: Setup) -> None:
    """Each foot's sole in the world from the pose the engine reported, against the ground under it:
    the root's height over the ground under each foot, how far the soles are from the ground, and
    how far they slid."""
    import numpy as np

    world = setup.world
    if world is None or not run.ok or not run.feet_end or run.height is None:
        return
    ends = {k: _sole(world.soles[k], v) for k, v in run.feet_end.items() if k in world.soles}
    if not ends:
        return
    xy = np.array([[p[0], p[1]] for p in ends.values()])
    ground = world.ground(xy[:, 0], xy[:, 1])
    run.feet_height = {
        name: run.height - float(g) for name, g in zip(ends, ground.tolist(), strict=True) if np.isfinite(g)
    }
    gaps = [abs(p[2] - g) for p, g in zip(ends.values(), ground.tolist(), strict=True) if np.isfinite(g)]
    run.sole_gap = max(gaps) if gaps else None
    starts = {k: _sole(world.soles[k], v) for k, v in run.feet_start.items() if k in ends}
    moves = [float(np.hypot(ends[k][0] - p[0], ends[k][1] - p[1])) for k, p in starts.items()]
    run.slip = max(moves) if moves else None
    if run.weight is None and run.mass is not None:
        run.weight = run.mass * 9.81  # the workers' engines run the world's gravity, 9.81 in Quad-SDK's


def _sole(local: tuple[float, float, float], pose: list[float]) -> tuple[float, float, float]:
    """A point of a link (``local``, in its frame) in the world, the link at ``pose`` (x, y, z, qw, qx, qy, qz)."""
    x, y, z, w, a, b, c = pose
    px, py, pz = local
    # v' = v + 2 w (q × v) + 2 q × (q × v), q = (a, b, c)
    tx, ty, tz = 2 * (b * pz - c * py), 2 * (c * px - a * pz), 2 * (a * py - b * px)
    return (
        x + px + w * tx + (b * tz - c * ty),
        y + py + w * ty + (c * tx - a * tz),
        z + pz + w * tz + (a * ty - b * tx),
    )


Runner = Callable[[Robot, str, str, Setup, DynamicsOptions, tuple[str, ...]], "list[Run] | str"]


def _source_setup(setup: Setup, report: DynamicsReport, engine: str, kind: str) -> Setup:
    """The setup of the source's run beside ``kind`` in ``engine``: given the armature that file adds
    where the source has none (the mjcf preset's default armature). z1's MJCF otherwise ran 1.5 mrad
    from its source over 1 s and failed the comparison (exit 1) for a documented default, not for
    anything written wrong; the report names the joints (``info["source_armature"]``)."""
    added = next(
        (r.armature for r in report.runs if r.engine == engine and r.file == kind and r.armature),
        None,
    )
    if not added:
        return setup
    report.info["source_armature"] = dict(sorted(added.items()))
    return dataclasses.replace(setup, source_armature=dict(added))


def _run_engine(
    engine: str,
    robot: Robot,
    path: str,
    kind: str,
    setup: Setup,
    opts: DynamicsOptions,
    report: DynamicsReport,
    scenarios: tuple[str, ...] = SCENARIOS,
) -> list[Run]:
    if opts.progress is not None:
        opts.progress(f"{engine} ({kind}): {', '.join(scenarios)}")
    started = time.perf_counter()
    try:
        return _run_engine_timed(engine, robot, path, kind, setup, opts, report, scenarios)
    finally:
        spent = report.info.setdefault("engine_seconds", {})
        spent[engine] = round(spent.get(engine, 0.0) + time.perf_counter() - started, 3)


def _run_engine_timed(
    engine: str,
    robot: Robot,
    path: str,
    kind: str,
    setup: Setup,
    opts: DynamicsOptions,
    report: DynamicsReport,
    scenarios: tuple[str, ...],
) -> list[Run]:
    try:
        runner = _runner(engine)
    except ImportError as exc:
        report.add("engine", Status.SKIP, engine, f"not installed ({exc})")
        return []
    result = runner(robot, path, kind, setup, opts, scenarios)
    if isinstance(result, str):  # the engine refused the file, or is not available
        status = Status.SKIP if result.startswith("not available") else Status.FAIL
        if kind == SOURCE or result.startswith(READS_DIFFERENTLY):
            status = Status.WARN  # the source's own trouble: nothing to compare with
        report.add("load", status, f"{engine}/{kind}", result)
        return []
    return result


def _runner(engine: str) -> Runner:
    # Imported when asked: Drake's import alone takes a second, Newton's a subprocess.
    if engine == "mujoco":
        from robodesc.validation.dynamics.mujoco_run import run_file

        return run_file
    if engine == "drake":
        from robodesc.validation.dynamics.drake_run import run_file as drake_file

        return drake_file
    if engine == "physx":
        from robodesc.validation.dynamics.physx_run import run_file as physx_file

        return physx_file
    from robodesc.validation.dynamics.newton_run import run_file as newton_file

    return newton_file
