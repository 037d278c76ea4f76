"""Where the real-robot corpora live on this machine.

The Quad-SDK robots ship beside the project (``../shared/corpus``); the others install from PyPI
(``example-robot-data``, ``icub-models``, ``hello-robot-stretch-urdf``). Each entry names the
package map a robot needs so that ``package://`` URIs resolve without a ROS install.
"""

from __future__ import annotations

import glob
import os
import site
import sys
from dataclasses import dataclass, field


@dataclass(slots=True, frozen=True)
class CorpusRobot:
    corpus: str
    name: str
    path: str
    packages: dict[str, str] = field(default_factory=dict)
    xacro_args: dict[str, str] = field(default_factory=dict)


def _prefixes() -> list[str]:
    # A venv over the system's packages has its own sys.prefix; the share/ data of packages
    # installed outside it (icub-models) lives under sys.base_prefix.
    out = [sys.prefix, sys.base_prefix]
    for sp in site.getsitepackages():
        out.append(os.path.join(sp, "cmeel.prefix"))
    return [p for p in dict.fromkeys(out) if os.path.isdir(p)]


def example_robot_data_root() -> str | None:
    for prefix in _prefixes():
        root = os.path.join(prefix, "share", "example-robot-data")
        if os.path.isdir(os.path.join(root, "robots")):
            return root
    return None


def icub_root() -> str | None:
    for prefix in _prefixes():
        root = os.path.join(prefix, "share", "iCub")
        if os.path.isdir(os.path.join(root, "robots")):
            return root
    return None


def stretch_root() -> str | None:
    try:
        import stretch_urdf
    except ImportError:
        return None
    return os.path.dirname(os.path.abspath(str(stretch_urdf.__file__)))


def quadsdk_robots(shared_corpus: str) -> list[CorpusRobot]:
    base = os.path.join(shared_corpus, "quadsdk")
    out = []
    for robot, pkg in (("spirit", "spirit_description"), ("go2", "go2_description")):
        path = os.path.join(base, pkg, "models", robot, "urdf", f"{robot}.urdf.xacro")
        if os.path.isfile(path):
            out.append(CorpusRobot("quadsdk", robot, path))
    return out


def example_robot_data_robots() -> list[CorpusRobot]:
    root = example_robot_data_root()
    if root is None:
        return []
    out = []
    for path in sorted(glob.glob(os.path.join(root, "robots", "*", "**", "*.urdf"), recursive=True)):
        rel = os.path.relpath(path, os.path.join(root, "robots"))
        out.append(CorpusRobot("example-robot-data", rel.removesuffix(".urdf"), path, {"example-robot-data": root}))
    return out


def icub_robots() -> list[CorpusRobot]:
    root = icub_root()
    if root is None:
        return []
    return [
        CorpusRobot("icub-models", os.path.basename(os.path.dirname(p)), p, {"iCub": root})
        for p in sorted(glob.glob(os.path.join(root, "robots", "*", "model.urdf")))
    ]


def stretch_robots() -> list[CorpusRobot]:
    root = stretch_root()
    if root is None:
        return []
    return [
        CorpusRobot("hello-robot-stretch-urdf", os.path.basename(p).removesuffix(".urdf"), p)
        for p in sorted(glob.glob(os.path.join(root, "*", "*.urdf")))
    ]


def all_robots(shared_corpus: str) -> list[CorpusRobot]:
    return quadsdk_robots(shared_corpus) + example_robot_data_robots() + icub_robots() + stretch_robots()
