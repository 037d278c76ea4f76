"""What a folder target (the ROS 2 and the Isaac folders) names its files after: the input file.

A robot's ``name`` attribute is often an exporter's leftover (pybullet's humanoid is ``dumpUrdf``), and
two inputs may share it; the file the user gave is what they will look for in the folder. A robot
built in Python without a file falls back to its name.
"""

from __future__ import annotations

import os
import re

from robodesc.ir.model import Robot

# Suffixes that are a kind of robot file rather than part of its name (robot.urdf.xacro -> robot).
_KIND_SUFFIXES = (".xacro",)


def file_stem(robot: Robot) -> str:
    """``arm.urdf.xacro`` -> ``arm``; letters, digits and ``_`` only (the Isaac Lab module is a
    Python module, the launch file a ROS name), ``robot`` when nothing is left."""
    if robot.source_file:
        # A xacro robot's file is its expanded text's ("robot.urdf.xacro (expanded)").
        name = os.path.basename(robot.source_file.removesuffix(" (expanded)"))
        for suffix in _KIND_SUFFIXES:
            if name.lower().endswith(suffix) and len(name) > len(suffix):
                name = name[: -len(suffix)]
        stem = os.path.splitext(name)[0] or name
    else:
        stem = robot.name
    return re.sub(r"[^A-Za-z0-9_]", "_", stem) or "robot"
