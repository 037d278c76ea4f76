"""Small builders and comparisons shared by the pass tests."""

from __future__ import annotations

import math

from robodesc.ir import (
    Box,
    Findings,
    Inertia,
    Inertial,
    Joint,
    JointType,
    Limit,
    Link,
    Material,
    Pose,
    Robot,
    Visual,
)
from robodesc.passes.context import PassContext
from robodesc.passes.options import PassOptions, options_from_mapping


def ctx(**options: object) -> PassContext:
    return PassContext(options_from_mapping(options, PassOptions()))


def codes(findings: Findings | PassContext) -> list[str]:
    items = findings.findings if isinstance(findings, PassContext) else findings
    return [f.code for f in items]


def box_link(name: str, size: tuple[float, float, float] = (0.1, 0.2, 0.3), mass: float = 1.0) -> Link:
    a, b, c = size
    return Link(
        name=name,
        inertial=Inertial(
            mass=mass,
            origin=Pose(),
            inertia=Inertia(
                ixx=mass * (b * b + c * c) / 12, iyy=mass * (a * a + c * c) / 12, izz=mass * (a * a + b * b) / 12
            ),
        ),
        visuals=[Visual(geometry=Box(size))],
    )


def chain(*link_names: str, joint_names: list[str] | None = None) -> Robot:
    """A serial chain of box links joined by revolute joints."""
    links = [box_link(n) for n in link_names]
    names = joint_names or [f"j{i}" for i in range(len(links) - 1)]
    joints = [
        Joint(
            name=names[i],
            type=JointType.REVOLUTE,
            parent=links[i].name,
            child=links[i + 1].name,
            origin=Pose(xyz=(0.0, 0.0, 0.1)),
            axis=(0.0, 0.0, 1.0),
            limit=Limit(lower=-1.0, upper=1.0, effort=10.0, velocity=1.0),
        )
        for i in range(len(links) - 1)
    ]
    return Robot(name="chain", links=links, joints=joints)


def resolved_color(robot: Robot, mat: Material | None) -> tuple[float, ...] | None:
    if mat is None:
        return None
    if mat.color is not None:
        return tuple(mat.color)
    for m in robot.materials:
        if m.name == mat.name and m.color is not None:
            return tuple(m.color)
    return None


def close(a: float | None, b: float | None, rel: float = 1e-9, abs_: float = 1e-15) -> bool:
    if a is None or b is None:
        return a is b
    return math.isclose(a, b, rel_tol=rel, abs_tol=abs_)
