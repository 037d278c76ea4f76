"""Options of the SDF emitter (``-t sdf``) and the free props a world may carry."""

from __future__ import annotations

import enum
from dataclasses import dataclass, field
from typing import Any, ClassVar

from robodesc.emit.common import approximation
from robodesc.emit.common import decomposition as decomp
from robodesc.emit.common import flags as common
from robodesc.emit.common.flags import flag
from robodesc.emit.common.paths import PathMode
from robodesc.ir.diagnostics import ConfigError
from robodesc.ir.geometry import Pose, Vec3
from robodesc.ir.model import Robot


class SdfFlavour(enum.Enum):
    HARMONIC = "harmonic"  # Gazebo Harmonic (gz-sim 8) system plugins; the default
    CLASSIC = "classic"  # Gazebo Classic 11 with gazebo_ros (libgazebo_ros_*.so) sensor plugins


class PoseFrames(enum.Enum):
    # Joint pose relative to the parent link, child link relative to its joint: the source's numbers
    # are written unchanged (what libsdformat's own URDF converter does). The default.
    RELATIVE = "relative"
    # Every link posed in the model frame (forward kinematics at zero); joints at their child link.
    MODEL = "model"


SDF_VERSIONS = ("1.7", "1.9", "1.10", "1.11")


@dataclass(slots=True)
class SdfProp:
    """A free object put in the world beside the robot (a composition's ``@grabbable`` part).

    ``model`` is a small robot of its own (usually one link); it floats unless ``static``.
    """

    model: Robot
    pose: Pose | None = None
    static: bool = False


@dataclass(slots=True)
class SdfOptions:
    # --preset gazebo_parity leaves these alone: the SDF is Gazebo's own input, so Gazebo's handling
    # of a mesh (its triangles) is the parity the preset aims at.
    PRESET_EXEMPT: ClassVar[tuple[str, ...]] = ("collision_approximation",)

    # None: "1.10" for Harmonic, "1.7" for Classic (Gazebo 11's libsdformat 9 stops at 1.7).
    # "1.11" is needed to keep mimic joints.
    version: str | None = field(
        default=None,
        metadata=flag(
            "SDF version (default 1.10; 1.11 keeps mimic joints; 1.9 for older libsdformat)",
            name="--sdf-version",
            choices=("1.7", "1.9", "1.10", "1.11"),
        ),
    )
    flavour: SdfFlavour = field(
        default=SdfFlavour.HARMONIC,
        metadata=flag(
            "Gazebo Classic plugins (libgazebo_ros_*) instead of Harmonic's gz-sim systems",
            name="--gazebo-classic",
            kind="on",
            const="classic",
        ),
    )
    # Weld the root link to the world (a fixed joint to ``world``); SDF models float by default.
    fix_base: bool = field(default=False, metadata=common.FIX_BASE)
    # Gazebo collides a <mesh> as its triangles: "none" writes the mesh as given (the default);
    # convexHull asks Gazebo for its hull (SDF 1.11's optimization attribute); convexDecomposition
    # writes robodesc's CoACD parts (docs/contact.md).
    collision_approximation: approximation.Approximation = field(default="none", metadata=approximation.FLAG)
    decomposition_max_parts: int = field(default=32, metadata=decomp.MAX_PARTS)
    decomposition_timeout: float = field(default=300.0, metadata=decomp.TIMEOUT)
    decomposition_threshold: float = field(default=0.05, metadata=decomp.THRESHOLD)
    decomposition_cache: str | None = field(default=None, metadata=decomp.CACHE)
    pose_frames: PoseFrames = PoseFrames.RELATIVE
    path_mode: PathMode = PathMode.RELATIVE
    # The folder the SDF will be written to; relative mesh paths are computed against it.
    out_dir: str | None = None
    # Write the IR's loop joints as extra SDF joints (tree-only consumers such as Drake reject them).
    loop_joints: bool = True
    # Where the model sits in the world (and the model's <pose> when a bare model is written).
    model_pose: Pose | None = None
    # Several copies of the robot in a world (--spawn given more than once): the pose of every copy
    # after the first (which is ``model_pose``); the models are named ``<robot>_<i>``.
    copy_poses: list[Pose] = field(default_factory=list)
    # ---- world wrapper (a bare ``--world``; cli/parser.py declares the flag, which also takes a
    # world file: docs/worlds.md) -------------------------------------------------------------
    world: bool = False
    world_name: str = "default"
    # A world read from --world FILE / --terrain (emit/common/world.PlacedWorld): its static models
    # replace the ground plane (set by the target, not a flag).
    placed_world: Any = None
    props: list[SdfProp] = field(default_factory=list)
    step_size: float = 0.001
    real_time_factor: float = 1.0
    # None: "dantzig" (DART, Harmonic's default engine) or "quick" (ODE, Classic's).
    solver: str | None = None
    gravity: Vec3 = (0.0, 0.0, -9.8)

    def check(self) -> None:
        approximation.check(self.collision_approximation)
        decomp.check_settings(self)

    def resolved_version(self) -> str:
        version = self.version or ("1.7" if self.flavour is SdfFlavour.CLASSIC else "1.10")
        if version not in SDF_VERSIONS:
            raise ConfigError(f"unknown SDF version {version!r} (robodesc writes {', '.join(SDF_VERSIONS)})")
        return version

    def resolved_solver(self) -> str:
        if self.solver is not None:
            return self.solver
        return "quick" if self.flavour is SdfFlavour.CLASSIC else "dantzig"


def version_at_least(version: str, wanted: str) -> bool:
    def key(v: str) -> tuple[int, ...]:
        return tuple(int(p) for p in v.split("."))

    return key(version) >= key(wanted)
