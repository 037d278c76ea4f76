"""IR sensors → SDF ``<sensor>`` elements, and the Gazebo systems that run them.

Harmonic: sensors carry their topic (see :mod:`robodesc.emit.sdf.topics`); the systems
(``gz-sim-sensors-system`` for rendering sensors, ``gz-sim-imu-system`` ...) are plugins of the
world, or of the model when no world is written (the rendering ``Sensors`` system only works at
world level, so it is then left to the world and reported). Classic: the gazebo_ros plugin of each
sensor goes inside the sensor; the force-torque one is a model plugin.
"""

from __future__ import annotations

from dataclasses import dataclass

from lxml import etree

from robodesc.emit.common.numbers import fmt, fmt_vec
from robodesc.emit.sdf.options import SdfFlavour, version_at_least
from robodesc.emit.sdf.topics import sensor_base_topic, sensor_topics
from robodesc.ir.geometry import Pose
from robodesc.ir.model import RayAxis, Robot, Sensor, SensorType

E = etree.SubElement


@dataclass(slots=True, frozen=True)
class GzSystem:
    filename: str
    name: str
    world_only: bool = False


SENSORS_SYSTEM = GzSystem("gz-sim-sensors-system", "gz::sim::systems::Sensors", world_only=True)
HARMONIC_SYSTEMS: dict[SensorType, GzSystem] = {
    SensorType.CAMERA: SENSORS_SYSTEM,
    SensorType.DEPTH: SENSORS_SYSTEM,
    SensorType.RAY: SENSORS_SYSTEM,
    SensorType.IMU: GzSystem("gz-sim-imu-system", "gz::sim::systems::Imu"),
    SensorType.FORCE_TORQUE: GzSystem("gz-sim-forcetorque-system", "gz::sim::systems::ForceTorque"),
    SensorType.CONTACT: GzSystem("gz-sim-contact-system", "gz::sim::systems::Contact"),
    SensorType.GPS: GzSystem("gz-sim-navsat-system", "gz::sim::systems::NavSat"),
}

_HARMONIC_TYPE = {
    SensorType.CAMERA: "camera",
    SensorType.DEPTH: "depth_camera",
    SensorType.RAY: "gpu_lidar",
    SensorType.IMU: "imu",
    SensorType.FORCE_TORQUE: "force_torque",
    SensorType.CONTACT: "contact",
    SensorType.GPS: "navsat",
}
_CLASSIC_TYPE = {**_HARMONIC_TYPE, SensorType.DEPTH: "depth", SensorType.RAY: "ray", SensorType.GPS: "gps"}
_CLASSIC_PLUGIN = {
    SensorType.CAMERA: "libgazebo_ros_camera.so",
    SensorType.DEPTH: "libgazebo_ros_camera.so",
    SensorType.RAY: "libgazebo_ros_ray_sensor.so",
    SensorType.IMU: "libgazebo_ros_imu_sensor.so",
    SensorType.CONTACT: "libgazebo_ros_bumper.so",
    SensorType.GPS: "libgazebo_ros_gps_sensor.so",
}
CLASSIC_FT_PLUGIN = "libgazebo_ros_ft_sensor.so"


def required_systems(sensors: list[Sensor]) -> list[GzSystem]:
    """The Harmonic systems these sensors need, each once, in a stable order."""
    out: list[GzSystem] = []
    for t in SensorType:
        if any(s.type is t for s in sensors):
            system = HARMONIC_SYSTEMS[t]
            if system not in out:
                out.append(system)
    return out


def system_plugin(parent: etree._Element, system: GzSystem) -> etree._Element:
    el = E(parent, "plugin", filename=system.filename, name=system.name)
    if system is SENSORS_SYSTEM:
        E(el, "render_engine").text = "ogre2"
    return el


def _noise(parent: etree._Element, stddev: float) -> None:
    n = E(parent, "noise")
    E(n, "type").text = "gaussian"
    E(n, "mean").text = "0"
    E(n, "stddev").text = fmt(stddev)


def _pose(parent: etree._Element, pose: Pose | None, relative_to: str | None) -> None:
    if relative_to is None and (pose is None or pose.is_identity()):
        return
    el = E(parent, "pose")
    if relative_to is not None:
        el.set("relative_to", relative_to)
    if pose is not None and not pose.is_identity():
        el.text = fmt_vec((*pose.xyz, *pose.rpy))


def _scan_axis(parent: etree._Element, tag: str, axis: RayAxis) -> None:
    el = E(parent, tag)
    if axis.samples is not None:
        E(el, "samples").text = str(axis.samples)
    if axis.resolution is not None:
        E(el, "resolution").text = fmt(axis.resolution)
    if axis.min_angle is not None:
        E(el, "min_angle").text = fmt(axis.min_angle)
    if axis.max_angle is not None:
        E(el, "max_angle").text = fmt(axis.max_angle)


def sensor_element(
    parent: etree._Element,
    robot: Robot,
    sensor: Sensor,
    *,
    name: str,
    link: str,
    flavour: SdfFlavour,
    version: str,
    contact_collisions: list[str],
    anchored: bool = True,
) -> etree._Element:
    """Write one ``<sensor>``; its pose is given relative to ``link`` (the IR's parent link).

    ``anchored=False`` leaves ``relative_to`` out, for a URDF ``<gazebo reference="link">`` block
    (Gazebo's URDF converter may merge that link away and re-poses the sensor itself).
    """
    classic = flavour is SdfFlavour.CLASSIC
    kind = (_CLASSIC_TYPE if classic else _HARMONIC_TYPE)[sensor.type]
    el = E(parent, "sensor", name=name, type=kind)
    _pose(el, sensor.origin, link if anchored else None)
    E(el, "always_on").text = "true"
    if sensor.update_rate is not None:
        E(el, "update_rate").text = fmt(sensor.update_rate)
    topics = sensor_topics(robot, sensor)
    if not classic:
        E(el, "topic").text = topics["main"].gz_topic
    t = sensor.type
    if t in (SensorType.CAMERA, SensorType.DEPTH):
        cam = E(el, "camera")
        spec = sensor.camera
        if spec is not None and spec.hfov is not None:
            E(cam, "horizontal_fov").text = fmt(spec.hfov)
        if spec is not None and (spec.width is not None or spec.height is not None or spec.format is not None):
            image = E(cam, "image")
            if spec.width is not None:
                E(image, "width").text = str(spec.width)
            if spec.height is not None:
                E(image, "height").text = str(spec.height)
            if spec.format is not None:
                E(image, "format").text = sdf_image_format(spec.format)
        if spec is not None and (spec.near is not None or spec.far is not None):
            clip = E(cam, "clip")
            if spec.near is not None:
                E(clip, "near").text = fmt(spec.near)
            if spec.far is not None:
                E(clip, "far").text = fmt(spec.far)
        if not classic and version_at_least(version, "1.9"):
            E(cam, "camera_info_topic").text = topics["camera_info"].gz_topic
        if sensor.noise is not None:
            _noise(cam, sensor.noise)
    elif t is SensorType.RAY:
        ray = E(el, "ray" if classic else "lidar")
        spec_r = sensor.ray
        if spec_r is not None and (spec_r.horizontal is not None or spec_r.vertical is not None):
            scan = E(ray, "scan")
            if spec_r.horizontal is not None:
                _scan_axis(scan, "horizontal", spec_r.horizontal)
            if spec_r.vertical is not None:
                _scan_axis(scan, "vertical", spec_r.vertical)
        if spec_r is not None and (spec_r.min_range is not None or spec_r.max_range is not None):
            rng = E(ray, "range")
            if spec_r.min_range is not None:
                E(rng, "min").text = fmt(spec_r.min_range)
            if spec_r.max_range is not None:
                E(rng, "max").text = fmt(spec_r.max_range)
        if sensor.noise is not None:
            _noise(ray, sensor.noise)
    elif t is SensorType.FORCE_TORQUE:
        ft = E(el, "force_torque")
        E(ft, "frame").text = "child"
        E(ft, "measure_direction").text = "child_to_parent"
    elif t is SensorType.CONTACT:
        contact = E(el, "contact")
        for collision in contact_collisions:
            E(contact, "collision").text = collision
        if not classic:
            E(contact, "topic").text = topics["main"].gz_topic
    if classic and t in _CLASSIC_PLUGIN:
        plugin = E(el, "plugin", name=f"{name}_plugin", filename=_CLASSIC_PLUGIN[t])
        ros = E(plugin, "ros")
        E(ros, "namespace").text = "/" + sensor_base_topic(robot, sensor)
        if t is SensorType.RAY:
            E(plugin, "output_type").text = "sensor_msgs/LaserScan"
        E(plugin, "frame_name").text = link
    return el


def classic_ft_plugin(parent: etree._Element, robot: Robot, sensor: Sensor, link: str) -> None:
    """gazebo_ros's force-torque plugin is a model plugin that reads the wrench on a body."""
    plugin = E(parent, "plugin", name=f"{sensor.name}_plugin", filename=CLASSIC_FT_PLUGIN)
    ros = E(plugin, "ros")
    E(ros, "namespace").text = "/" + sensor_base_topic(robot, sensor)
    E(plugin, "body_name").text = link
    E(plugin, "frame_name").text = link
    if sensor.update_rate is not None:
        E(plugin, "update_rate").text = fmt(sensor.update_rate)


# URDF/Isaac and ROS image encodings → SDF's <image><format> values (libsdformat rejects the others).
_IMAGE_FORMATS = {
    "rgb8": "R8G8B8",
    "bgr8": "B8G8R8",
    "rgba8": "R8G8B8",  # SDF cameras have no alpha format
    "mono8": "L8",
    "l8": "L8",
    "mono16": "L16",
    "l16": "L16",
    "r8g8b8": "R8G8B8",
    "b8g8r8": "B8G8R8",
    "r_float32": "R_FLOAT32",
    "r_float16": "R_FLOAT16",
}


def sdf_image_format(name: str) -> str:
    """The SDF spelling of an image format (``RGB8`` → ``R8G8B8``); unknown names pass through."""
    return _IMAGE_FORMATS.get(name.strip().lower(), name)
