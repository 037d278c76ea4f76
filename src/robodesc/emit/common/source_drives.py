"""The source's own servos (``Joint.drive``, from an MJCF's actuators) as the gains a target writes.

A gain the user gives (``--stiffness``/``--damping``) wins; else the source's, which its authors
tuned (menagerie's), win over robodesc's derived or constant gains. They are put first in the
options' ordered ``{regex: value}`` tables, so every other joint keeps what it had.
"""

from __future__ import annotations

import re
from collections.abc import Collection, Mapping
from typing import Any, Protocol

from robodesc.ir.model import Robot

# A drive's kind as MuJoCo's actuator element. A source's motor ("effort") is not among them: its
# control is a torque the user's controller supplies, so an output keeps the target's own servo
# (holding the home pose, the effort limit the motor's), which validation and `validate --dynamics`
# can simulate; `--mjcf-actuator motor` writes motors, with the source's gear.
MJCF_ACTUATOR = {"position": "position", "velocity": "velocity"}


class HasGains(Protocol):
    # Any: each target's options class types its gains its own way (a number or a regex table).
    stiffness: Any
    damping: Any


def source_gains(robot: Robot) -> dict[str, tuple[float | None, float | None]]:
    """Joint name -> (stiffness, damping) of the source's position and velocity servos."""
    out: dict[str, tuple[float | None, float | None]] = {}
    for joint in robot.actuated_joints():
        drive = joint.drive
        if drive is not None and drive.kind in ("position", "velocity"):
            out[joint.name] = (drive.stiffness if drive.kind == "position" else 0.0, drive.damping)
    return out


def apply_source_gains(robot: Robot, settings: HasGains, given: Collection[str]) -> int:
    """Put the source's gains first in ``settings``' tables where the user gave none; how many joints."""
    gains = source_gains(robot)
    if not gains:
        return 0
    for field, index in (("stiffness", 0), ("damping", 1)):
        if field in given:
            continue
        table = {re.escape(name): value[index] for name, value in gains.items() if value[index] is not None}
        current = getattr(settings, field)
        rest = dict(current) if isinstance(current, Mapping) else {".*": float(current)}
        setattr(settings, field, {**table, **{k: v for k, v in rest.items() if k not in table}})
    return len(gains)
