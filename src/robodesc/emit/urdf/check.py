"""How a URDF output is checked: MuJoCo reads it and the numbers are compared with the IR.

Folder targets that hold a URDF (ROS 2, Isaac) are checked through the URDF they contain."""

from __future__ import annotations

import os
import re

from robodesc.emit.common.target import CheckRequest, Emitted
from robodesc.emit.urdf.ros import ros_equivalent
from robodesc.ir.model import JointType, Robot
from robodesc.validation.report import Status, ValidationReport

_MODELLED_SHAPES = frozenset({"box", "cylinder", "sphere", "mesh", "capsule"})
_SPHERICAL_JOINT = re.compile(r'<joint\b[^>]*\btype="spherical"')


def check_urdf(robot: Robot, emitted: Emitted, request: CheckRequest) -> ValidationReport | None:
    from robodesc.validation.mujoco_urdf import validate_urdf_text  # the consumer loads only when a check runs

    text = emitted.text
    base_dir = os.path.dirname(os.path.abspath(request.out)) if request.out and not request.folder else os.getcwd()
    if text is None:  # folder targets: validate the URDF they contain
        urdf = next((p for p in emitted.files.values() if p.endswith(".urdf")), None)
        if urdf is None:
            return None
        with open(urdf, encoding="utf-8") as handle:
            text = handle.read()
        base_dir = os.path.dirname(urdf)
    text, unmodelled = without_unmodelled_shapes(text)
    # Written for ROS, a spherical joint of the IR is three revolute joints (emit/urdf/ros.py):
    # the URDF is compared with the robot it stands for.
    # A <loop_joint type="spherical"> (an MJCF <connect>) is not a tree joint: only <joint> counts.
    split = any(j.type is JointType.SPHERICAL for j in robot.joints) and not _SPHERICAL_JOINT.search(text)
    report = validate_urdf_text(ros_equivalent(robot) if split else robot, text, base_dir, request.options)
    if split:
        report.add(
            "joint-type",
            Status.SKIP,
            "spherical joints",
            "written for ROS as three revolute joints each; compared as such (emit/urdf/ros.py)",
        )
    if unmodelled:
        report.add(
            "unmodelled-geometry",
            Status.SKIP,
            "document",
            f"{unmodelled} visual/collision element(s) with a geometry robodesc does not model are kept "
            "verbatim in the output; MuJoCo cannot read them, so the URDF was checked without them",
        )
    return report


def without_unmodelled_shapes(text: str) -> tuple[str, int]:
    """The URDF without the visual/collision elements kept verbatim because their geometry is one
    robodesc does not model (a plane, a heightmap): MuJoCo refuses those whatever robodesc does."""
    if "<geometry" not in text:
        return text, 0
    from lxml import etree

    root = etree.fromstring(text.encode("utf-8"))
    removed = 0
    for el in root.iterfind("link/*"):
        if el.tag not in ("visual", "collision"):
            continue
        geometry = el.find("geometry")
        shapes = [c.tag for c in geometry if isinstance(c.tag, str)] if geometry is not None else []
        parent = el.getparent()
        if shapes and shapes[0] not in _MODELLED_SHAPES and parent is not None:
            parent.remove(el)
            removed += 1
    if not removed:
        return text, 0
    return etree.tostring(root, encoding="unicode"), removed
