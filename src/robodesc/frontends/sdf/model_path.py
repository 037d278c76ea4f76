"""Where ``model://`` URIs of a world or a model resolve: Gazebo's model path, as Gazebo Classic and Gazebo
Sim search it, plus the folders a world is usually shipped with.

Order: ``--model-path`` folders, ``GZ_SIM_RESOURCE_PATH``, ``IGN_GAZEBO_RESOURCE_PATH``,
``GAZEBO_MODEL_PATH``, then the world file's folder and the folder above it (Quad-SDK's worlds name
``model:///step_20cm/step_20cm.stl`` from ``worlds/step_20cm/step_20cm.world``). A resolved file
must lie inside the root it was found in: ``..`` cannot climb out."""

from __future__ import annotations

import os
from collections.abc import Sequence

ENV_VARS = ("GZ_SIM_RESOURCE_PATH", "IGN_GAZEBO_RESOURCE_PATH", "GAZEBO_MODEL_PATH")


def model_roots(world_file: str, given: Sequence[str] = ()) -> list[str]:
    roots: list[str] = [os.path.abspath(p) for p in given]
    for var in ENV_VARS:
        roots += [os.path.abspath(p) for p in os.environ.get(var, "").split(os.pathsep) if p]
    here = os.path.dirname(os.path.abspath(world_file))
    roots += [here, os.path.dirname(here)]
    seen: set[str] = set()
    return [r for r in roots if not (r in seen or seen.add(r))]  # type: ignore[func-returns-value]


def resolve_uri(uri: str, world_file: str, roots: Sequence[str]) -> str | None:
    """The file or folder ``uri`` names (``model://``, ``file://``, absolute or relative to the
    world), or None when no root holds it."""
    text = uri.strip()
    if text.startswith("file://"):
        path = text[len("file://") :]
        return path if os.path.exists(path) else None
    if text.startswith("model://"):
        rel = text[len("model://") :].lstrip("/")
        for root in roots:
            found = _inside(root, rel)
            if found is not None:
                return found
        return None
    if os.path.isabs(text):
        return text if os.path.exists(text) else None
    return _inside(os.path.dirname(os.path.abspath(world_file)), text)


def _inside(root: str, rel: str) -> str | None:
    candidate = os.path.realpath(os.path.join(root, rel))
    real_root = os.path.realpath(root)
    if os.path.commonpath([candidate, real_root]) != real_root or not os.path.exists(candidate):
        return None
    return candidate
