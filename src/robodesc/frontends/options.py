"""Options every frontend understands."""

from __future__ import annotations

import enum
from collections.abc import Mapping
from dataclasses import dataclass, field


class MissingMesh(enum.Enum):
    """What to do when a mesh file does not exist."""

    ERROR = "error"  # fail, naming the file and the link
    WARN = "warn"  # keep the reference as written, with a warning (the default; docs/diagnostics.md)
    PRIMITIVE = "primitive"  # substitute a box of the declared scale, with a warning
    DROP = "drop"  # drop that visual/collision, with a warning


@dataclass(slots=True)
class LoadOptions:
    package_paths: Mapping[str, str] = field(default_factory=dict)
    xacro_args: Mapping[str, str] = field(default_factory=dict)
    # A missing mesh is a warning by default: URDF and SDF keep the reference, USD leaves the shape
    # out and says so (docs/diagnostics.md).
    missing_mesh: MissingMesh = MissingMesh.WARN
    # Treat unknown elements as errors instead of keeping them with a warning.
    strict: bool = False
    # Expand xacro with upstream's Python evaluation (code, any file, the whole environment) instead
    # of robodesc's sandbox: only for files the user trusts (docs/security.md).
    trust_xacro: bool = False
    # Environment variables xacro's $(env NAME) / $(optenv NAME) may read; others are refused.
    allowed_env: tuple[str, ...] = ()
    # Folders searched for an SDF model's model:// URIs (its includes and meshes) before Gazebo's
    # environment variables; ``--model-path``, shared with the world.
    model_path: tuple[str, ...] = ()
