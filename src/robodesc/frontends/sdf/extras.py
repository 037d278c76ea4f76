"""What an SDF model holds beside links and joints: sensors, Gazebo plugins, and the elements the IR
has no place for (each a warning naming the element, its ``file:line`` and what the targets lose).

Sensors the IR has a type for become IR sensors (camera, depth camera, lidar, IMU, force-torque,
contact, navsat); the rest are a warning. Plugins are Gazebo's code: kept verbatim on the robot as a
``<gazebo>`` block (URDF's place for them) with a warning. Where a standard joint
controller plugin plainly gives its gains (Gazebo Sim's JointPositionController, JointController),
they become the joint's drive, in SI units as the plugin takes them.
"""

from __future__ import annotations

import copy

from lxml import etree

from robodesc.frontends.sdf.frames import Frames, Node
from robodesc.frontends.sdf.source import STAGE, Scope
from robodesc.frontends.sdf.values import loc, number, tag
from robodesc.ir.diagnostics import Findings, ParseError
from robodesc.ir.geometry import Extension
from robodesc.ir.model import CameraSpec, Drive, Joint, RayAxis, RaySpec, Robot, Sensor, SensorType

_SENSORS = {
    "camera": SensorType.CAMERA,
    "wideanglecamera": SensorType.CAMERA,
    "depth": SensorType.DEPTH,
    "depth_camera": SensorType.DEPTH,
    "rgbd_camera": SensorType.DEPTH,
    "ray": SensorType.RAY,
    "gpu_ray": SensorType.RAY,
    "lidar": SensorType.RAY,
    "gpu_lidar": SensorType.RAY,
    "imu": SensorType.IMU,
    "force_torque": SensorType.FORCE_TORQUE,
    "contact": SensorType.CONTACT,
    "gps": SensorType.GPS,
    "navsat": SensorType.GPS,
}
# Children each element has that robodesc reads (or that change nothing a target writes).
READ = {
    "model": {
        "link",
        "joint",
        "frame",
        "model",
        "include",
        "pose",
        "static",
        "plugin",
        "self_collide",
        "canonical_link",
    },
    "link": {"inertial", "visual", "collision", "sensor", "pose", "self_collide", "must_be_base_link"},
    "joint": {"parent", "child", "pose", "axis", "axis2", "sensor", "physics"},
}
# Gazebo Sim's systems that run sensors: what they do follows from the sensors themselves.
_SENSOR_SYSTEMS = {
    f"{prefix}-{name}-system"
    for prefix in ("gz-sim", "ignition-gazebo")
    for name in ("imu", "forcetorque", "contact", "navsat", "sensors", "altimeter", "magnetometer", "air-pressure")
}
_CONTROLLERS = {
    "gz::sim::systems::JointPositionController": "position",
    "ignition::gazebo::systems::JointPositionController": "position",
    "gz::sim::systems::JointController": "velocity",
    "ignition::gazebo::systems::JointController": "velocity",
}


def read_sensor(
    frames: Frames, node: Node, el: etree._Element, link: str, ir_frame_inv: object, findings: Findings
) -> Sensor | None:
    """A ``<sensor>`` of a link (or a joint: ``link`` is then its child) into the IR; None when the IR
    has no such type."""
    import numpy as np

    from robodesc.frontends.sdf.links import _clean
    from robodesc.ir.transforms import matrix_pose

    file = node.file
    name = el.get("name") or "sensor"
    kind = (el.get("type") or "").strip()
    sensor_type = _SENSORS.get(kind)
    label = f"sensor {name!r}"
    if sensor_type is None:
        findings.warn(
            "sdf-sensor-unsupported",
            f"a {kind or 'typeless'} sensor has no IR type; every target loses it",
            element=label,
            loc=loc(file, el),
            stage=STAGE,
        )
        return None
    default = node.name
    pose = frames.relative_to(el.find("pose"), node.scope, file, default)
    origin = _clean(matrix_pose(np.asarray(ir_frame_inv) @ pose))
    sensor = Sensor(name=name, type=sensor_type, parent=link, origin=origin, src=loc(file, el))
    if node.kind == "joint":
        sensor.parent_joint = node.name
    rate = el.find("update_rate")
    if rate is not None:
        sensor.update_rate = number(file, rate)
    topic = el.findtext("topic")
    if topic and topic.strip():
        sensor.topic = topic.strip()
    camera = el.find("camera")
    if camera is not None:
        sensor.camera = _camera(file, camera)
    ray = el.find("ray") if el.find("ray") is not None else el.find("lidar")
    if ray is not None:
        sensor.ray = _ray(file, ray)
    return sensor


def _camera(file: str, el: etree._Element) -> CameraSpec:
    spec = CameraSpec()
    for key, path, cast in (
        ("hfov", "horizontal_fov", float),
        ("width", "image/width", int),
        ("height", "image/height", int),
        ("near", "clip/near", float),
        ("far", "clip/far", float),
    ):
        found = el.find(path)
        if found is not None:
            setattr(spec, key, cast(number(file, found)))
    fmt = el.findtext("image/format")
    if fmt:
        spec.format = fmt.strip()
    return spec


def _ray(file: str, el: etree._Element) -> RaySpec:
    spec = RaySpec()
    for direction in ("horizontal", "vertical"):
        scan = el.find(f"scan/{direction}")
        if scan is None:
            continue
        axis = RayAxis()
        for key, cast in (("samples", int), ("resolution", float), ("min_angle", float), ("max_angle", float)):
            found = scan.find(key)
            if found is not None:
                setattr(axis, key, cast(number(file, found)))
        setattr(spec, direction, axis)
    for key, path in (("min_range", "range/min"), ("max_range", "range/max")):
        found = el.find(path)
        if found is not None:
            setattr(spec, key, number(file, found))
    return spec


def keep_plugins(robot: Robot, scope: Scope, findings: Findings) -> list[etree._Element]:
    """A model's ``<plugin>``s, kept on the robot; returns them for the controller gains."""
    plugins = [c for c in scope.element if tag(c) == "plugin"]
    for plugin in plugins:
        if (plugin.get("filename") or "") in _SENSOR_SYSTEMS:
            findings.info(
                "sdf-sensor-system",
                "Gazebo's system for the model's sensors: the SDF target writes it again for the sensors it writes",
                element=f"plugin {plugin.get('name')!r}",
                loc=loc(scope.file, plugin),
                stage=STAGE,
            )
            continue
        # URDF's place for a Gazebo plugin is a <gazebo> block: the URDF target writes it back there.
        block = etree.Element("gazebo")
        block.append(_copy(plugin))
        robot.extensions.append(
            Extension(tag="gazebo", xml=etree.tostring(block, encoding="unicode"), src=loc(scope.file, plugin))
        )
        findings.warn(
            "sdf-plugin",
            f"{plugin.get('filename')!r} ({plugin.get('name')}) is Gazebo's code: kept in a <gazebo> block of the "
            "URDF target; the other targets lose what it does"
            + (" (its gains are the joint's drive)" if plugin.get("name") in _CONTROLLERS else ""),
            element=f"plugin {plugin.get('name')!r}",
            loc=loc(scope.file, plugin),
            stage=STAGE,
        )
    return plugins


def controller_gains(plugins: list[etree._Element], scope: Scope, joints: dict[str, Joint]) -> None:
    """Gazebo Sim's joint controllers into ``Joint.drive`` where their gains are written out."""
    for plugin in plugins:
        kind = _CONTROLLERS.get(plugin.get("name") or "")
        if kind is None:
            continue
        names = [t.strip() for t in (e.text or "" for e in plugin.iterfind("joint_name")) if t.strip()]
        p_el, d_el = plugin.find("p_gain"), plugin.find("d_gain")
        if not names or p_el is None:
            continue
        p = number(scope.file, p_el)
        d = number(scope.file, d_el) if d_el is not None else None
        for name in names:
            joint = joints.get(scope.scoped(name))
            if joint is None:
                raise ParseError(f"<joint_name> {name!r} names no joint of the model", loc=loc(scope.file, plugin))
            # JointController's p_gain acts on the velocity error: that is a damping gain.
            joint.drive = (
                Drive("position", p, d, src=loc(scope.file, plugin))
                if kind == "position"
                else Drive("velocity", 0.0, p, src=loc(scope.file, plugin))
            )


def warn_unread(node_kind: str, label: str, file: str, el: etree._Element, findings: Findings) -> None:
    """The children of a model, link or joint robodesc does not read: one warning naming them."""
    unread = [c for c in el if isinstance(c.tag, str) and tag(c) not in READ[node_kind]]
    if not unread:
        return
    names = ", ".join(sorted({f"<{tag(c)}>" for c in unread}))
    findings.warn(
        "sdf-unread",
        f"{names} not read into the IR: every target loses it",
        element=f"{node_kind} {label!r}",
        loc=loc(file, unread[0]),
        stage=STAGE,
    )


def _copy(el: etree._Element) -> etree._Element:
    out = copy.deepcopy(el)
    out.tail = None
    return out
