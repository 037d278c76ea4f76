"""SDF's values, read the same way by the model and the world frontends: numbers, vectors and
poses, each error naming the element and its ``file:line``."""

from __future__ import annotations

import math

from lxml import etree

from robodesc.ir.diagnostics import ParseError, SourceLoc
from robodesc.ir.geometry import Pose, Vec3
from robodesc.ir.transforms import matrix_to_rpy, quat_wxyz_to_matrix


def tag(element: etree._Element) -> str:
    name = element.tag
    return etree.QName(name).localname if isinstance(name, str) else ""


def loc(path: str, element: etree._Element) -> SourceLoc:
    line = element.sourceline
    return SourceLoc(path, line if isinstance(line, int) else None)


def numbers(path: str, element: etree._Element) -> list[float]:
    try:
        values = [float(t) for t in (element.text or "").split()]
    except ValueError:
        raise ParseError(
            f"<{tag(element)}>: {element.text!r} is not a list of numbers", loc=loc(path, element)
        ) from None
    if not all(math.isfinite(v) for v in values):
        raise ParseError(f"<{tag(element)}>: numbers must be finite", loc=loc(path, element))
    return values


def number(path: str, element: etree._Element) -> float:
    values = numbers(path, element)
    if len(values) != 1:
        raise ParseError(f"<{tag(element)}> needs one number", loc=loc(path, element))
    return values[0]


def positive(path: str, element: etree._Element) -> float:
    value = number(path, element)
    if not value > 0:
        raise ParseError(f"<{tag(element)}> must be positive, got {value:g}", loc=loc(path, element))
    return value


def vec3(path: str, element: etree._Element) -> Vec3:
    values = numbers(path, element)
    if len(values) != 3:
        raise ParseError(f"<{tag(element)}> needs 3 numbers, got {len(values)}", loc=loc(path, element))
    return (values[0], values[1], values[2])


def required(path: str, parent: etree._Element, name: str) -> etree._Element:
    found = parent.find(name)
    if found is None:
        raise ParseError(f"<{tag(parent)}> needs <{name}>", loc=loc(path, parent))
    return found


def pose_value(path: str, element: etree._Element | None) -> Pose:
    """A ``<pose>``'s numbers (its ``relative_to`` is the caller's): ``x y z roll pitch yaw``, in
    degrees with ``degrees="true"``, or ``x y z qx qy qz qw`` with ``rotation_format="quat_xyzw"``
    (SDF 1.9). An empty pose is the identity."""
    if element is None:
        return Pose()
    values = numbers(path, element)
    here = loc(path, element)
    if not values:
        return Pose(src=here)
    quat = (element.get("rotation_format") or "euler_rpy").strip() == "quat_xyzw"
    wanted = 7 if quat else 6
    if len(values) != wanted:
        spelled = "x y z qx qy qz qw" if quat else "x y z roll pitch yaw"
        raise ParseError(f"<pose> needs {wanted} numbers ({spelled}), got {len(values)}", loc=here)
    xyz = (values[0], values[1], values[2])
    if quat:
        x, y, z, w = values[3:7]
        norm = math.sqrt(x * x + y * y + z * z + w * w)
        if norm == 0:
            raise ParseError("<pose>: the quaternion is zero", loc=here)
        rpy = matrix_to_rpy(quat_wxyz_to_matrix((w / norm, x / norm, y / norm, z / norm)))
        return Pose(xyz, rpy, src=here)
    rpy = (values[3], values[4], values[5])
    if (element.get("degrees") or "").strip().lower() in ("true", "1"):
        rpy = (math.radians(rpy[0]), math.radians(rpy[1]), math.radians(rpy[2]))
    return Pose(xyz, rpy, src=here)
