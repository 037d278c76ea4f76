"""Sites, cameras, sensors and the ``home`` keyframe.

- A site is a fixed frame on its body's link. A camera is a camera sensor; MuJoCo's look along -Z
  with +Y up, the IR's (Gazebo's) along +X with +Z up (the inverse of emit/mjcf/sensors.py).
- Sensors where the IR has the kind: ``accelerometer``/``gyro`` at a site -> one IMU there,
  ``force``/``torque`` -> one force-torque sensor, ``touch`` -> contact, ``rangefinder`` -> a ray
  along the site's +Z. The others (joint, frame, subtree readings ...) are computed from the state
  by any consumer: one information finding lists them.
- The ``home`` keyframe (else the first) gives the robot's initial joint positions (``qpos - ref``).
"""

from __future__ import annotations

import math

from robodesc.frontends.mjcf.context import Reading
from robodesc.frontends.mjcf.frames import frame, pose
from robodesc.ir.model import CameraSpec, FixedFrame, Sensor, SensorType
from robodesc.ir.rigid import Frame

# emit/mjcf/sensors.py's _CAMERA and _RAY, inverted (their transposes).
_CAMERA_TO_SENSOR = Frame(((0.0, -1.0, 0.0), (0.0, 0.0, 1.0), (-1.0, 0.0, 0.0)))
_SITE_TO_RAY = Frame(((0.0, 0.0, -1.0), (0.0, 1.0, 0.0), (1.0, 0.0, 0.0)))
# mjtSensor values.
_TOUCH, _ACC, _VEL, _GYRO, _FORCE, _TORQUE, _MAG, _RANGE = 0, 1, 2, 3, 4, 5, 6, 7
_KINDS = {
    _ACC: SensorType.IMU,
    _GYRO: SensorType.IMU,
    _FORCE: SensorType.FORCE_TORQUE,
    _TORQUE: SensorType.FORCE_TORQUE,
}


def read_sites(r: Reading) -> set[str]:
    m = r.model
    taken = {f.name for f in r.robot.fixed_frames}
    names: set[str] = set()
    for s in range(m.nsite):
        b = int(m.site_bodyid[s])
        link = _link(r, "site", s, b)
        if link is None:
            continue
        name = r.unique(r.name("site", s) or f"site{s}", taken)
        origin = pose(r.content[b] @ frame(m.site_pos[s], m.site_quat[s]))
        r.robot.fixed_frames.append(FixedFrame(name, link, origin=origin, src=r.loc("site", s)))
        names.add(name)
    return names


def read_cameras(r: Reading) -> None:
    m = r.model
    for c in range(m.ncam):
        b = int(m.cam_bodyid[c])
        link = _link(r, "camera", c, b)
        if link is None:
            continue
        name = r.name("camera", c) or f"camera{c}"
        placed = r.content[b] @ frame(m.cam_pos[c], m.cam_quat[c]) @ _CAMERA_TO_SENSOR
        width, height = (int(v) for v in m.cam_resolution[c])
        fovy = math.radians(float(m.cam_fovy[c]))
        aspect = height / width if width and height else 1.0
        hfov = 2 * math.atan(math.tan(fovy / 2) / aspect)
        spec = CameraSpec(width=width or None, height=height or None, hfov=hfov)
        r.robot.sensors.append(
            Sensor(name, SensorType.CAMERA, link, origin=pose(placed), camera=spec, src=r.loc("camera", c))
        )
        if int(m.cam_mode[c]) != 0:
            r.info(
                "mjcf-camera-mode",
                "a tracking camera (mode other than fixed) is a camera fixed to its body in every output",
                f"camera {name!r}",
                r.loc("camera", c),
            )


def _link(r: Reading, kind: str, index: int, body: int) -> str | None:
    """The link that holds a site or camera; None (said, unless its body was left out as a scene
    object) for one of the world itself when no link stands for the world."""
    link = r.link_of.get(body)
    if link is not None and link in r.link_names:
        return link
    if body not in r.dropped:
        name = r.name(kind, index) or f"{kind}{index}"
        r.info(
            "mjcf-world-frame",
            f"a {kind} of the world, not of the robot: left out (the robot's root is not fixed to a world link)",
            f"{kind} {name!r}",
            r.loc(kind, index),
        )
    return None


def read_sensors(r: Reading, sites: set[str]) -> None:
    import mujoco

    m = r.model
    by_site: dict[tuple[int, SensorType], str] = {}
    others: list[str] = []
    for s in range(m.nsensor):
        kind = int(m.sensor_type[s])
        name = r.name("sensor", s) or f"sensor{s}"
        objtype, obj = int(m.sensor_objtype[s]), int(m.sensor_objid[s])
        stype = _KINDS.get(kind) or {_TOUCH: SensorType.CONTACT, _RANGE: SensorType.RAY}.get(kind)
        if stype is None or objtype != int(mujoco.mjtObj.mjOBJ_SITE):
            others.append(f"{name} ({mujoco.mjtSensor(kind).name.removeprefix('mjSENS_').lower()})")
            continue
        if (obj, stype) in by_site and stype in (SensorType.IMU, SensorType.FORCE_TORQUE):
            continue  # the gyro of an IMU whose accelerometer was read (or the other way round)
        b = int(m.site_bodyid[obj])
        link = r.link_of.get(b)
        if link is None or link not in r.link_names:
            continue
        placed = r.content[b] @ frame(m.site_pos[obj], m.site_quat[obj])
        if stype is SensorType.RAY:
            placed = placed @ _SITE_TO_RAY
        by_site[(obj, stype)] = name
        noise = float(m.sensor_noise[s]) or None
        r.robot.sensors.append(Sensor(name, stype, link, origin=pose(placed), noise=noise, src=r.loc("sensor", s)))
    if others:
        r.info(
            "mjcf-sensor-derived",
            f"{len(others)} sensor(s) read the state (joint, frame, subtree or actuator values), which every "
            f"consumer computes; the IR holds sensors that ride on a frame only: {', '.join(others[:12])}"
            + (" ..." if len(others) > 12 else ""),
            f"robot {r.robot.name!r}",
            r.source.loc(r.source.root),
        )


def read_keyframe(r: Reading) -> None:
    m = r.model
    if m.nkey == 0:
        return
    names = [r.name("key", k) for k in range(m.nkey)]
    k = names.index("home") if "home" in names else 0
    qpos = m.key_qpos[k]
    for j, name in r.joint_of.items():
        kind = int(m.jnt_type[j])
        if kind not in (2, 3):  # slide, hinge
            continue
        adr = int(m.jnt_qposadr[j])
        r.robot.initial_positions[name] = float(qpos[adr]) - float(m.qpos0[adr])
    if names[k] != "home":
        r.info(
            "mjcf-keyframe",
            f"no keyframe named 'home': the first ({names[k] or 'unnamed'}) is the robot's initial pose",
            "keyframe",
            r.loc("key", k),
        )
