"""Contact sensors on the feet, decided once before the emitters (``--contact-sensors [REGEX]``).

Quad-SDK's Isaac bridge guesses contact from foot height (z < 4 cm), which is wrong on uneven ground;
Gazebo publishes each toe's ground reaction force. A contact sensor on each foot gives every engine
the force itself. Bare ``--contact-sensors`` takes the feet robodesc already finds (the lowest
colliding link of each leg, emit/common/stance.py); a REGEX names links instead (full match). Each
becomes an IR ``contact`` sensor on that link, which every target writes in its own terms: MJCF a
``touch`` sensor on a site that covers the link's colliders, USD ``PhysxContactReportAPI`` on the
link, SDF a ``<sensor type="contact">`` naming its collisions, the Isaac Lab module a
``ContactSensorCfg``.
"""

from __future__ import annotations

import re

from robodesc.emit.common.stance import complete, find_legs
from robodesc.ir.diagnostics import ConfigError, Findings
from robodesc.ir.model import Robot, Sensor, SensorType

STAGE = "contact-sensors"
SUFFIX = "_contact"


def add_contact_sensors(robot: Robot, pattern: str, findings: Findings) -> list[str]:
    """Add a contact sensor to each foot (``pattern`` empty) or each link ``pattern`` fully matches
    that has a collider; returns the links, in the robot's order."""
    if pattern:
        try:
            rule = re.compile(pattern)
        except re.error as exc:
            raise ConfigError(f"--contact-sensors {pattern!r}: not a regular expression ({exc})") from None
        links = [link.name for link in robot.links if rule.fullmatch(link.name) and link.collisions]
        if not links:
            raise ConfigError(
                f"--contact-sensors {pattern!r} matches no link with a collider "
                f"(links with colliders: {', '.join(k.name for k in robot.links if k.collisions)[:300]})"
            )
    else:
        legs = find_legs(robot, complete(robot, {}))
        if not legs:
            findings.warn(
                "contact-sensors-no-feet",
                "no legs found, so no feet to put contact sensors on; name the links with --contact-sensors REGEX",
                element=f"robot {robot.name!r}",
                loc=robot.src,
                stage=STAGE,
            )
            return []
        feet = {leg.foot for leg in legs}
        links = [link.name for link in robot.links if link.name in feet]
    have = {s.parent for s in robot.sensors if s.type is SensorType.CONTACT}
    taken = {s.name for s in robot.sensors} | {f.name for f in robot.fixed_frames}
    added = []
    for name in links:
        if name in have:
            continue
        sensor_name = name + SUFFIX
        while sensor_name in taken:
            sensor_name += "_"
        taken.add(sensor_name)
        robot.sensors.append(Sensor(name=sensor_name, type=SensorType.CONTACT, parent=name, src=robot.link(name).src))
        added.append(name)
    if added:
        findings.info(
            "contact-sensors",
            f"contact sensors on {', '.join(added)}",
            element=f"robot {robot.name!r}",
            stage=STAGE,
        )
    return added
