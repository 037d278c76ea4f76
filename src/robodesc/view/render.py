"""Headless pictures of a robot through MuJoCo's offscreen renderer.

No display and no GPU are needed: MuJoCo renders through EGL (a GPU, or Mesa's software EGL) or
OSMesa (Mesa's software renderer; Debian's ``libosmesa6``). ``MUJOCO_GL`` chooses when it is set;
otherwise EGL is tried, then OSMesa. PyOpenGL fixes its platform when it is first imported, so a
second backend cannot be tried in the same process: when the first fails before drawing anything,
the render runs again in a child process with the other one. When neither works,
:class:`RenderUnavailable` says what to install.
"""

from __future__ import annotations

import ctypes.util
import json
import os
import subprocess
import sys
import time
from dataclasses import dataclass, field

import numpy as np

from robodesc.emit.common.staging import check_output
from robodesc.frontends.load import Source
from robodesc.ir.diagnostics import RobodescError
from robodesc.options import CompileOptions
from robodesc.view.camera import corners, frame_camera
from robodesc.view.mjscene import COLLISION_GROUP, VISUAL_GROUP, WORLD_GROUP, build_model
from robodesc.view.png import Image, write_png
from robodesc.view.source import Loaded, load_for_view
from robodesc.view.views import VIEWS

BACKENDS = ("egl", "osmesa")
GRID_VIEWS = ("front", "side", "top", "iso")


class RenderUnavailable(RobodescError):
    """No OpenGL backend MuJoCo can render offscreen with (exit 2, nothing written)."""


class _BackendFailed(Exception):
    """The GL backend could not make a context: another may, in another process."""


@dataclass(slots=True)
class RenderResult:
    path: str
    width: int
    height: int
    backend: str
    seconds: float
    skipped: list[str] = field(default_factory=list)  # shapes left out of the picture, and why


def _library(backend: str) -> bool:
    return ctypes.util.find_library("EGL" if backend == "egl" else "OSMesa") is not None


def backend_candidates() -> list[str]:
    """The backends to try, in order: ``MUJOCO_GL`` alone when set, else those whose library exists."""
    chosen = os.environ.get("MUJOCO_GL", "").strip().lower()
    if chosen:
        return [chosen]
    return [b for b in BACKENDS if _library(b)]


UNAVAILABLE = (
    "no OpenGL backend for offscreen rendering: MuJoCo needs EGL (a GPU driver, or Mesa's libegl1) or "
    "OSMesa (Debian/Ubuntu: apt-get install libosmesa6, then MUJOCO_GL=osmesa). `robodesc view` makes "
    "a browser page instead, which needs neither"
)


def _chosen_backend() -> str | None:
    """The backend this process's MuJoCo already chose (it reads ``MUJOCO_GL`` once, when it is
    imported: "" means GLFW, which needs a display); None when MuJoCo is not imported yet."""
    if "mujoco" not in sys.modules:
        return None
    module = sys.modules.get("mujoco.rendering.classic.gl_context") or sys.modules.get("mujoco.gl_context")
    return str(getattr(module, "_MUJOCO_GL", "")).strip().lower()


def _select(backend: str) -> None:
    os.environ["MUJOCO_GL"] = backend
    os.environ.setdefault("PYOPENGL_PLATFORM", backend)


def render_views(
    loaded: Loaded, views: list[str], size: tuple[int, int], collision: bool
) -> tuple[list[Image], list[str]]:
    """One image per view of the loaded robot, each ``size`` (width, height)."""
    import mujoco

    built = build_model(loaded.robot, size, collision, loaded.world)
    model = built.model
    data = mujoco.MjData(model)
    mujoco.mj_kinematics(model, data)
    # Visuals unless asked for colliders, or the robot has no visual to show.
    group = VISUAL_GROUP if built.visuals else COLLISION_GROUP
    option = mujoco.MjvOption()
    option.geomgroup[:] = 0
    option.geomgroup[group] = 1
    option.geomgroup[WORLD_GROUP] = 1
    # The camera frames the robot (its copies), not the whole terrain: the ground is seen around it.
    points = corners(model, data, {group})
    try:
        # The smallest font: the picture has no text, and the font textures cost time to make.
        renderer = mujoco.Renderer(model, height=size[1], width=size[0], font_scale=mujoco.mjtFontScale.mjFONTSCALE_50)
    except Exception as exc:  # mujoco.FatalError, GLFW/EGL/OSMesa errors: the backend does not work here
        raise _BackendFailed(f"{type(exc).__name__}: {str(exc).splitlines()[0] if str(exc) else ''}") from None
    try:
        camera = mujoco.MjvCamera()
        camera.type = mujoco.mjtCamera.mjCAMERA_FREE
        images = []
        for view in views:
            frame_camera(camera, points, view, float(model.vis.global_.fovy), size[0] / size[1])
            renderer.update_scene(data, camera=camera, scene_option=option)
            images.append(renderer.render().copy())
    finally:
        renderer.close()
    return images, built.skipped


def grid(images: list[Image]) -> Image:
    """Four images as a 2x2 grid (front, side / top, iso)."""
    top = np.concatenate(images[0:2], axis=1)
    bottom = np.concatenate(images[2:4], axis=1)
    return np.concatenate([top, bottom], axis=0)


def render_png(
    source: Source | Loaded,
    out: str,
    *,
    view: str = "iso",
    size: tuple[int, int] = (800, 600),
    grid_views: bool = False,
    collision: bool = False,
    options: CompileOptions | None = None,
    target: str | None = None,
) -> RenderResult:
    """Render ``source`` (or the robot as compiled for ``target``) to the PNG ``out``, ``size``
    pixels (width, height); ``grid_views`` puts front, side, top and iso in a 2x2 grid of that size.
    Raises :class:`RenderUnavailable` when no GL backend works."""
    start = time.perf_counter()
    if view not in VIEWS:
        raise RobodescError(f"unknown view {view!r} (one of {', '.join(VIEWS)})")
    width, height = size
    if width < 16 or height < 16 or width > 8192 or height > 8192:
        raise RobodescError(f"--size {width}x{height}: each side between 16 and 8192 pixels")
    check_output(out, folder=False, source=None if isinstance(source, Loaded) else source, example="robot.png")
    loaded = source if isinstance(source, Loaded) else load_for_view(source, options, target)
    tile = (width // 2, height // 2) if grid_views else (width, height)
    views = list(GRID_VIEWS) if grid_views else [view]
    candidates = backend_candidates()
    if not candidates:
        raise RenderUnavailable(UNAVAILABLE)
    first, rest = candidates[0], candidates[1:]
    chosen = _chosen_backend()
    if chosen is None or chosen == first:
        _select(first)
        try:
            images, skipped = render_views(loaded, views, tile, collision)
        except (_BackendFailed, ImportError) as exc:
            if not rest:
                raise RenderUnavailable(f"{UNAVAILABLE} (MUJOCO_GL={first}: {exc})") from None
            return _in_child(loaded, out, rest[0], views, tile, collision, start)
        image = grid(images) if grid_views else images[0]
        write_png(out, image)
        return RenderResult(out, image.shape[1], image.shape[0], first, time.perf_counter() - start, skipped)
    # This process's MuJoCo chose another backend when it was imported (a worker that validated
    # first, a test run): render in a child process that chooses ours.
    failures = []
    for backend in candidates:
        try:
            return _in_child(loaded, out, backend, views, tile, collision, start)
        except RenderUnavailable as exc:
            failures.append(str(exc))
    raise RenderUnavailable(failures[-1])


def _in_child(
    loaded: Loaded, out: str, backend: str, views: list[str], tile: tuple[int, int], collision: bool, start: float
) -> RenderResult:
    """Render in a new Python process with ``backend`` (this one has another GL platform loaded)."""
    import pickle
    import tempfile

    with tempfile.TemporaryDirectory(prefix="robodesc-render-") as tmp:
        job = os.path.join(tmp, "job.pickle")
        with open(job, "wb") as handle:
            pickle.dump((loaded.robot, loaded.world, views, tile, collision, out), handle)
        env = {**os.environ, "MUJOCO_GL": backend, "PYOPENGL_PLATFORM": backend}
        done = subprocess.run(
            [sys.executable, "-m", "robodesc.view.render", job], env=env, capture_output=True, text=True, check=False
        )
    if done.returncode != 0:
        last = (done.stderr.strip().splitlines() or ["no output"])[-1]
        raise RenderUnavailable(f"{UNAVAILABLE} (MUJOCO_GL={backend}: {last})")
    report = json.loads(done.stdout.strip().splitlines()[-1])
    return RenderResult(out, report["width"], report["height"], backend, time.perf_counter() - start, report["skipped"])


def _child_main(job: str) -> int:
    import pickle

    with open(job, "rb") as handle:
        robot, world, views, tile, collision, out = pickle.load(handle)
    images, skipped = render_views(Loaded(robot=robot, findings=[], world=world), views, tile, collision)
    image = grid(images) if len(images) == 4 else images[0]
    write_png(out, image)
    print(json.dumps({"width": int(image.shape[1]), "height": int(image.shape[0]), "skipped": skipped}))
    return 0


def parse_size(text: str) -> tuple[int, int]:
    """``"800x600"`` -> (800, 600)."""
    w, sep, h = text.lower().partition("x")
    if not sep or not w.isdigit() or not h.isdigit():
        raise RobodescError(f"--size {text!r}: expected WIDTHxHEIGHT, e.g. 800x600")
    return int(w), int(h)


if __name__ == "__main__":
    raise SystemExit(_child_main(sys.argv[1]))
