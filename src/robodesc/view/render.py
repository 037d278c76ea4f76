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
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any, TypeVar

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
T = TypeVar("T")


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
    renderer = new_renderer(model, size)
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

    def draw() -> RenderResult:
        images, skipped = render_views(loaded, views, tile, collision)
        image = grid(images) if grid_views else images[0]
        write_png(out, image)
        return RenderResult(out, image.shape[1], image.shape[0], "", time.perf_counter() - start, skipped)

    def child(backend: str) -> RenderResult:
        report = run_child("robodesc.view.render", (loaded.robot, loaded.world, views, tile, collision, out), backend)
        return RenderResult(out, report["width"], report["height"], backend, 0.0, report["skipped"])

    result, backend = with_backend(draw, child)
    result.backend, result.seconds = backend, time.perf_counter() - start
    return result


def with_backend(draw: Callable[[], T], child: Callable[[str], T]) -> tuple[T, str]:
    """``draw()`` in this process with the first GL backend that works, or ``child(backend)`` (a
    render in a new process, :func:`run_child`) when this process cannot use it; (its result, the
    backend). Raises :class:`RenderUnavailable` when none works."""
    candidates = backend_candidates()
    if not candidates:
        raise RenderUnavailable(UNAVAILABLE)
    first, rest = candidates[0], candidates[1:]
    chosen = _chosen_backend()
    if chosen is None or chosen == first:
        _select(first)
        try:
            return draw(), first
        except (_BackendFailed, ImportError) as exc:
            if not rest:
                raise RenderUnavailable(f"{UNAVAILABLE} (MUJOCO_GL={first}: {exc})") from None
            return child(rest[0]), rest[0]
    # This process's MuJoCo chose another backend when it was imported (a worker that validated
    # first, a test run): render in a child process that chooses ours.
    failures = []
    for backend in candidates:
        try:
            return child(backend), backend
        except RenderUnavailable as exc:
            failures.append(str(exc))
    raise RenderUnavailable(failures[-1])


def prefer_backend() -> None:
    """Choose the first working GL backend before MuJoCo is imported (``validate --video``
    simulates before it draws): its renders then run in this process, not a child's."""
    candidates = backend_candidates()
    if candidates and _chosen_backend() is None:
        _select(candidates[0])


def new_renderer(model: Any, size: tuple[int, int]) -> Any:
    """A ``mujoco.Renderer`` of ``size`` (width, height), or :class:`_BackendFailed`."""
    import mujoco

    try:
        # The smallest font: robodesc draws no text with MuJoCo, and font textures cost time to make.
        return mujoco.Renderer(model, height=size[1], width=size[0], font_scale=mujoco.mjtFontScale.mjFONTSCALE_50)
    except Exception as exc:  # mujoco.FatalError, GLFW/EGL/OSMesa errors: the backend does not work here
        raise _BackendFailed(f"{type(exc).__name__}: {str(exc).splitlines()[0] if str(exc) else ''}") from None


def run_child(module: str, job: Any, backend: str) -> dict[str, Any]:
    """Run ``python -m module JOB`` with ``backend`` (``job`` pickled to the file JOB) and return
    the JSON on its last line of output; :class:`RenderUnavailable` when it fails."""
    import pickle
    import tempfile

    with tempfile.TemporaryDirectory(prefix="robodesc-render-") as tmp:
        path = os.path.join(tmp, "job.pickle")
        with open(path, "wb") as handle:
            pickle.dump(job, handle)
        env = {**os.environ, "MUJOCO_GL": backend, "PYOPENGL_PLATFORM": backend}
        done = subprocess.run(
            [sys.executable, "-m", module, path], env=env, capture_output=True, text=True, check=False
        )
    if done.returncode != 0:
        last = (done.stderr.strip().splitlines() or ["no output"])[-1]
        raise RenderUnavailable(f"{UNAVAILABLE} (MUJOCO_GL={backend}: {last})")
    answer: dict[str, Any] = json.loads(done.stdout.strip().splitlines()[-1])
    return answer


def read_job(path: str) -> Any:
    import pickle

    with open(path, "rb") as handle:
        return pickle.load(handle)


def _child_main(job: str) -> int:
    robot, world, views, tile, collision, out = read_job(job)
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
