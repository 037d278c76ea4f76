"""Moving pictures: ``validate --dynamics --video DIR`` and ``render --video FILE``.

Every frame is drawn by MuJoCo's offscreen renderer (the one ``render`` uses, :mod:`.render`) from
one model of the robot: the picture model of :mod:`.mjscene` with a mocap body per link
(``build_posable``). A frame sets each link's pose from the IR's kinematics (``link_frames``) at the
joint positions an engine reported, under the root pose it reported: so every engine's run is drawn
by the same renderer, from the same model, and only the numbers differ. The IR's kinematics, not
an MJCF of the robot, place the links: the engines report the source's joint names, and the IR is
what every output was compiled from (an MJCF model would need its converted mesh files on disk).

A clip of a scenario has one panel per engine run (labelled with the engine, the file it read and
the time), side by side, all seen by one camera framing every panel's every frame, so a robot that
falls further in one engine is seen lower. MP4 through ``imageio-ffmpeg`` (the optional extra
``robodesc[video]``: its wheels ship an ffmpeg binary), else an animated GIF through Pillow (already
a dependency); the summary says which.
"""

from __future__ import annotations

import math
import os
import re
import sys
import tempfile
import time
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from robodesc.emit.common.staging import OutputPathError, check_output
from robodesc.ir.diagnostics import RobodescError
from robodesc.ir.model import Robot
from robodesc.ir.rigid import Frame, link_frames, quat_rotation
from robodesc.validation.dynamics.result import DynamicsReport
from robodesc.view.camera import corners, frame_camera
from robodesc.view.mjscene import COLLISION_GROUP, FLOOR_GROUP, VISUAL_GROUP, build_posable
from robodesc.view.png import Image
from robodesc.view.render import new_renderer, read_job, run_child, with_backend

FPS = 25  # frames per second of the file
FRAME_DT = 0.02  # s of simulated time per frame: a 1 s scenario plays in 2 s (half speed)
PANEL = (320, 240)  # pixels of one engine's panel; multiples of 16, as H.264's blocks
PER_ROW = 3  # panels side by side before a second row
SWEEP_SECONDS = 4.0  # render --video: one sweep of every joint, lower limit to upper and back
# The scenarios a clip is made of: the slide moves a block, not the robot.
DRAWN = ("hold-fixed", "drop")
RootPose = tuple[float, ...]  # x, y, z, qw, qx, qy, qz


@dataclass(slots=True)
class Panel:
    """One engine's run as frames: (time, root pose or None for the identity, joint positions)."""

    label: str
    frames: list[tuple[float, RootPose | None, dict[str, float]]] = field(default_factory=list)
    note: str = ""  # "failed at 0.31 s", shown after the label


@dataclass(slots=True)
class Clip:
    path: str
    scenario: str
    frames: int  # drawn (a GIF merges identical consecutive ones: fewer in the file, as long)
    width: int
    height: int
    format: str  # "mp4" or "gif"
    panels: list[str]
    seconds: float = 0.0
    skipped: list[str] = field(default_factory=list)  # shapes left out of the picture, and why


def encoder_available() -> bool:
    """Whether MP4 can be written: the optional ``imageio-ffmpeg`` is installed."""
    try:
        import imageio_ffmpeg  # noqa: F401
    except ImportError:
        return False
    return True


def choose_format(wanted: str | None = None) -> str:
    """``mp4`` when its encoder is installed, else ``gif``; ``wanted`` forces one."""
    if wanted == "mp4" and not encoder_available():
        raise RobodescError(
            "MP4 needs imageio-ffmpeg (pip install 'robodesc[video]', which ships ffmpeg); or write a .gif"
        )
    if wanted in ("mp4", "gif"):
        return wanted
    return "mp4" if encoder_available() else "gif"


def check_video_folder(folder: str, source: Any = None) -> None:
    """Refuse a ``--video DIR`` that cannot take the clips before any simulation runs (exit 2)."""
    check_output(folder, folder=True, source=source, what="--video")
    if os.path.isdir(folder) and not os.access(folder, os.W_OK | os.X_OK):
        raise OutputPathError(f"--video {folder}: the folder is not writable")


def check_video_file(out: str, source: Any = None) -> None:
    """Refuse a ``render --video FILE`` that cannot be written, or that is not .mp4 or .gif (exit 2)."""
    check_output(out, folder=False, source=source, what="--video", suffixes=(".mp4", ".gif"), example="robot.mp4")
    choose_format(os.path.splitext(out)[1].lower().lstrip("."))


def file_stem(name: str) -> str:
    """A robot's name as a file name: letters, digits, ``-``, ``_`` and ``.`` kept, no leading dot."""
    stem = re.sub(r"[^A-Za-z0-9._-]+", "_", name).lstrip(".")
    return stem[:80] or "robot"


# --- frames from the runs -----------------------------------------------------------------------


def scenario_panels(report: DynamicsReport, scenario: str, frame_dt: float = FRAME_DT) -> list[Panel]:
    """A panel per run of ``scenario`` that reported a trajectory, its frames every ``frame_dt``
    of simulated time from the start pose to the run's end (a failed run's last pose held)."""
    setup = report.info.get("setup", {})
    duration = float(setup.get("duration", 1.0))
    pose = {str(k): float(v) for k, v in setup.get("pose", {}).items()}
    drop = scenario == "drop"
    start_root = (0.0, 0.0, float(setup.get("stand_height", 0.0)) + float(setup.get("drop_clearance", 0.0)), 1, 0, 0, 0)
    times = [i * frame_dt for i in range(round(duration / frame_dt) + 1)]
    panels = []
    for run in report.runs:
        if run.scenario != scenario or not run.trajectory:
            continue
        if drop and not run.root:
            continue  # an engine that reported no root pose: nothing true to draw
        label = f"{run.engine} ({run.file})"
        panel = Panel(label, note="" if run.ok else f"failed at {run.trajectory[-1][0]:.2f} s")
        for t in times:
            q = _at(run.trajectory, t, pose)
            root = _at(run.root, t, start_root) if drop else None
            panel.frames.append((t, root, q))
        panels.append(panel)
    return panels


def _at(samples: Sequence[tuple[float, Any]], t: float, start: Any) -> Any:
    """The last sample at or before ``t`` (``start`` before the first): the runners sample every
    10 ms, a frame every 20 ms, so no sample is interpolated."""
    found = start
    for when, value in samples:
        if when > t + 1e-9:
            break
        found = value
    return found


def sweep_panel(robot: Robot, seconds: float = SWEEP_SECONDS, frame_dt: float = 1.0 / FPS) -> Panel:
    """``render --video``: every driven joint from its home position to its lower limit, to its
    upper limit and back home, all at once (a joint without limits a quarter turn each way), in
    ``seconds``; the root stays still."""
    spans: dict[str, tuple[float, float, float]] = {}
    for joint in robot.joints:
        if joint.mimic is not None or joint.type.dof != 1:
            continue
        lim = joint.limit
        lower = lim.lower if lim is not None and lim.lower is not None and math.isfinite(lim.lower) else -math.pi / 2
        upper = lim.upper if lim is not None and lim.upper is not None and math.isfinite(lim.upper) else math.pi / 2
        if lower > upper:
            continue
        home = min(max(0.0, lower), upper)
        spans[joint.name] = (lower, home, upper)
    panel = Panel(robot.name)
    count = max(2, round(seconds / frame_dt) + 1)
    for i in range(count):
        # One period of -sin: home, the lower limit at a quarter, home, the upper limit, home.
        s = -math.sin(2 * math.pi * i / (count - 1))
        q = {
            n: home + (s * (upper - home) if s > 0 else -s * (lower - home))
            for n, (lower, home, upper) in spans.items()
        }
        panel.frames.append((i * frame_dt, None, q))
    return panel


# --- drawing ------------------------------------------------------------------------------------


@dataclass(slots=True)
class ClipJob:
    """What a clip needs, picklable: drawn here or in a child process with another GL backend."""

    robot: Robot
    panels: list[Panel]
    out: str
    format: str
    panel_size: tuple[int, int] = PANEL
    floor: bool = False
    collision: bool = False
    title: str = ""


def draw_frames(job: ClipJob) -> tuple[list[Image], list[str]]:
    """Every frame of the clip (the panels tiled, each labelled), and the shapes left out."""
    import mujoco

    half = _floor_half(job) if job.floor else None
    built = build_posable(job.robot, job.panel_size, job.collision, half)
    model = built.model
    data = mujoco.MjData(model)
    group = VISUAL_GROUP if built.visuals else COLLISION_GROUP
    option = mujoco.MjvOption()
    option.geomgroup[:] = 0
    option.geomgroup[group] = 1
    option.geomgroup[FLOOR_GROUP] = int(job.floor)
    # One camera for every panel and frame: the union of the robot's corners over all of them.
    every: list[Any] = []
    for panel in job.panels:
        for _, root, q in panel.frames:
            _place(model, data, job.robot, built.bodies, root, q)
            points = corners(model, data, {group})
            if points is not None:
                every.append(points)
    points = np.concatenate(every) if every else None
    width, height = job.panel_size
    renderer = new_renderer(model, job.panel_size)
    camera = mujoco.MjvCamera()
    camera.type = mujoco.mjtCamera.mjCAMERA_FREE
    frame_camera(camera, points, "iso", float(model.vis.global_.fovy), width / height)
    count = max(len(p.frames) for p in job.panels)
    out: list[Image] = []
    try:
        for i in range(count):
            tiles = []
            for panel in job.panels:
                t, root, q = panel.frames[min(i, len(panel.frames) - 1)]
                _place(model, data, job.robot, built.bodies, root, q)
                renderer.update_scene(data, camera=camera, scene_option=option)
                text = f"{panel.label}  t={t:.2f} s" + (f"  {panel.note}" if panel.note else "")
                tiles.append(_label(renderer.render().copy(), text))
            out.append(_tile(tiles, job.panel_size))
    finally:
        renderer.close()
    return out, built.skipped


def _floor_half(job: ClipJob) -> float:
    """Half the floor's side: a few robot sizes, so its edge stays out of the picture."""
    reach = 0.5
    for panel in job.panels:
        for _, root, _q in panel.frames:
            if root is not None:
                reach = max(reach, abs(root[0]), abs(root[1]), abs(root[2]))
    return 4.0 * reach


def _place(
    model: Any, data: Any, robot: Robot, bodies: Mapping[str, int], root: RootPose | None, q: Mapping[str, float]
) -> None:
    import mujoco

    base = Frame() if root is None else Frame(quat_rotation(tuple(root[3:7])), tuple(root[:3]))  # type: ignore[arg-type]
    frames = link_frames(robot, q)
    for link, index in bodies.items():
        frame = base @ frames.get(link, Frame())
        data.mocap_pos[index] = frame.translation
        data.mocap_quat[index] = frame.quat()
    mujoco.mj_kinematics(model, data)


def _label(image: Image, text: str) -> Image:
    from PIL import Image as PilImage
    from PIL import ImageDraw

    picture = PilImage.fromarray(image)
    draw = ImageDraw.Draw(picture)
    box = draw.textbbox((6, 4), text)
    draw.rectangle((box[0] - 3, box[1] - 2, box[2] + 3, box[3] + 2), fill=(255, 255, 255))
    draw.text((6, 4), text, fill=(20, 20, 20))
    return np.asarray(picture, dtype=np.uint8)


def _tile(tiles: list[Image], size: tuple[int, int]) -> Image:
    """Panels side by side, :data:`PER_ROW` to a row; a short last row padded with white."""
    width, height = size
    per_row = min(PER_ROW, len(tiles))
    rows = []
    for start in range(0, len(tiles), per_row):
        row = tiles[start : start + per_row]
        row += [np.full((height, width, 3), 255, dtype=np.uint8)] * (per_row - len(row))
        rows.append(np.concatenate(row, axis=1))
    return np.concatenate(rows, axis=0)


# --- encoding -----------------------------------------------------------------------------------


def encode(frames: list[Image], out: str, fmt: str, fps: int = FPS) -> None:
    """Write ``frames`` to ``out`` as MP4 or GIF, through a hidden file beside it renamed into
    place: a failure leaves whatever ``out`` was untouched, and nothing is written elsewhere."""
    folder = os.path.dirname(os.path.abspath(out))
    # A new folder (``render --video out/robot.mp4`` on a fresh checkout) is made, as every output's
    # is, and taken back if the clip fails.
    made = []
    missing = folder
    while not os.path.isdir(missing):
        made.append(missing)
        missing = os.path.dirname(missing)
    os.makedirs(folder, exist_ok=True)
    fd, tmp = tempfile.mkstemp(prefix=".robodesc-", suffix=f".{fmt}", dir=folder)
    os.close(fd)
    try:
        if fmt == "mp4":
            _write_mp4(frames, tmp, fps)
        else:
            _write_gif(frames, tmp, fps)
        os.chmod(tmp, 0o644)
        os.replace(tmp, out)  # a symlink at ``out`` is replaced, never written through
    except BaseException:
        if os.path.exists(tmp):
            os.unlink(tmp)
        for new in made:  # the folders this call made, deepest first, now empty
            os.rmdir(new)
        raise


def _write_mp4(frames: list[Image], path: str, fps: int) -> None:
    import imageio_ffmpeg

    height, width = frames[0].shape[:2]
    # H.264 in yuv420p, which every player reads; the frame sizes are multiples of 16 already.
    writer = imageio_ffmpeg.write_frames(path, (width, height), fps=fps, quality=7, macro_block_size=16)
    writer.send(None)
    try:
        for frame in frames:
            writer.send(np.ascontiguousarray(frame))
    finally:
        writer.close()


def _write_gif(frames: list[Image], path: str, fps: int) -> None:
    from PIL import Image as PilImage

    pictures = [PilImage.fromarray(f).quantize(colors=128, dither=PilImage.Dither.NONE) for f in frames]
    pictures[0].save(path, format="GIF", save_all=True, append_images=pictures[1:], duration=round(1000 / fps), loop=0)


def read_frames(path: str) -> list[Image]:
    """The RGB frames of a clip robodesc wrote (MP4 through imageio-ffmpeg, GIF through Pillow)."""
    if path.lower().endswith(".gif"):
        from PIL import Image as PilImage
        from PIL import ImageSequence

        with PilImage.open(path) as picture:
            return [np.asarray(f.convert("RGB"), dtype=np.uint8) for f in ImageSequence.Iterator(picture)]
    import imageio_ffmpeg

    reader = imageio_ffmpeg.read_frames(path)
    meta = next(reader)
    width, height = meta["size"]
    return [np.frombuffer(raw, dtype=np.uint8).reshape(height, width, 3).copy() for raw in reader]


# --- clips --------------------------------------------------------------------------------------


def make_clip(job: ClipJob, scenario: str) -> Clip:
    """Draw and write one clip, in this process or a child with a working GL backend."""
    started = time.perf_counter()

    def here() -> dict[str, Any]:
        frames, skipped = draw_frames(job)
        encode(frames, job.out, job.format)
        return {
            "frames": len(frames),
            "width": int(frames[0].shape[1]),
            "height": int(frames[0].shape[0]),
            "skipped": skipped,
        }

    def child(backend: str) -> dict[str, Any]:
        return run_child("robodesc.view.video", job, backend)

    done, _ = with_backend(here, child)
    return Clip(
        job.out,
        scenario,
        int(done["frames"]),
        int(done["width"]),
        int(done["height"]),
        job.format,
        [p.label for p in job.panels],
        time.perf_counter() - started,
        list(done["skipped"]),
    )


def write_dynamics_clips(
    report: DynamicsReport,
    folder: str,
    *,
    fmt: str | None = None,
    progress: Callable[[str], None] | None = None,
) -> list[Clip]:
    """A clip per drawn scenario of ``report`` (its runs recorded with ``DynamicsOptions.record``)
    in ``folder``: ``<robot>_<scenario>.mp4`` or ``.gif``. Scenarios no engine ran are left out."""
    if report.model is None:
        raise RobodescError("the dynamics report carries no robot to draw")
    chosen = choose_format(fmt)
    os.makedirs(folder, exist_ok=True)
    clips = []
    for scenario in DRAWN:
        panels = scenario_panels(report, scenario)
        if not panels:
            continue
        out = os.path.join(folder, f"{file_stem(report.robot)}_{scenario}.{chosen}")
        if progress is not None:
            progress(f"drawing {scenario}: {len(panels)} panel(s)")
        job = ClipJob(report.model, panels, out, chosen, floor=scenario == "drop")
        clips.append(make_clip(job, scenario))
    return clips


def render_video(
    source: Any,
    out: str,
    *,
    size: tuple[int, int] = (640, 480),
    collision: bool = False,
    options: Any = None,
    target: str | None = None,
) -> Clip:
    """``render --video FILE``: a clip of every driven joint swept through its range
    (:func:`sweep_panel`), MP4 or GIF by ``out``'s suffix, ``size`` rounded down to multiples of 16."""
    from robodesc.view.source import Loaded, load_for_view

    check_video_file(out, None if isinstance(source, Loaded) else source)
    fmt = choose_format(os.path.splitext(out)[1].lower().lstrip("."))
    width, height = (max(16, size[0] // 16 * 16), max(16, size[1] // 16 * 16))
    loaded = source if isinstance(source, Loaded) else load_for_view(source, options, target)
    job = ClipJob(loaded.robot, [sweep_panel(loaded.robot)], out, fmt, panel_size=(width, height), collision=collision)
    return make_clip(job, "sweep")


def _child_main(path: str) -> int:
    import json

    job: ClipJob = read_job(path)
    frames, skipped = draw_frames(job)
    encode(frames, job.out, job.format)
    shape = frames[0].shape
    print(json.dumps({"frames": len(frames), "width": int(shape[1]), "height": int(shape[0]), "skipped": skipped}))
    return 0


if __name__ == "__main__":
    raise SystemExit(_child_main(sys.argv[1]))
