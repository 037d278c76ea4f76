"""Fixed frames and sensors: prims under the link they ride on.

- camera / depth: a ``UsdGeom.Camera``. USD cameras look down -Z with +Y up, URDF/ROS sensors look
  along +X with +Z up, so the prim's pose is the sensor pose turned by that fixed rotation.
  Focal length and apertures (mm, USD's convention) come from the horizontal field of view.
- ray (lidar): a ``Camera`` prim in the sensor frame carrying what Isaac Sim 4.x/5.x's RTX lidar
  reads (``cameraSensorType = "lidar"``, ``sensorModelPluginName``, ``sensorModelConfig`` = the
  URDF's ``isaac_sim_config`` preset or JSON path) plus the URDF ray parameters as
  ``robodesc:ray:*`` attributes.
- contact: PhysX reports the contacts of a rigid body that carries ``PhysxContactReportAPI``
  (threshold 0: every contact), so the link's prim gets it; the sensor's own prim is an ``Xform``.
- everything else: an ``Xform`` with the parameters as ``robodesc:*`` custom attributes.
"""

from __future__ import annotations

import math

from robodesc.emit.usd.context import GEOMETRY, PHYSICS, UsdContext, set_display_name, set_pose
from robodesc.emit.usd.quantities import CAMERA_FROM_SENSOR
from robodesc.ir.model import FixedFrame, RayAxis, Sensor, SensorType
from robodesc.ir.rigid import Frame, pose_frame
from robodesc.usdfile.spec import Prim

# USD's default horizontal aperture (mm, a 35 mm film back).
HORIZONTAL_APERTURE = 20.955
LIDAR_PLUGIN = "omni.sensors.nv.lidar.lidar_core.plugin"


def emit_fixed_frame(ctx: UsdContext, frame: FixedFrame, path: str) -> None:
    xform = ctx.define(GEOMETRY, path, "Xform")
    set_pose(xform, pose_frame(frame.origin))
    set_display_name(xform, frame.display_name)


def emit_sensor(ctx: UsdContext, sensor: Sensor, path: str) -> None:
    pose = pose_frame(sensor.origin)
    if sensor.type in (SensorType.CAMERA, SensorType.DEPTH):
        prim = _camera(ctx, sensor, path, pose)
    elif sensor.type is SensorType.RAY:
        prim = ctx.define(GEOMETRY, path, "Camera")
        set_pose(prim, pose)
        _lidar(prim, sensor)
    else:
        prim = ctx.define(GEOMETRY, path, "Xform")
        set_pose(prim, pose)
        if sensor.type is SensorType.CONTACT:
            body = ctx.over(PHYSICS, ctx.link_paths[sensor.parent])
            body.apply("PhysxContactReportAPI")
            body.attr("physxContactReport:threshold", "float", 0.0)
    set_display_name(prim, sensor.display_name)
    _custom(prim, "robodesc:sensor:type", "token", sensor.type.value)
    _custom(prim, "robodesc:sensor:updateRate", "double", sensor.update_rate)
    _custom(prim, "robodesc:sensor:topic", "string", sensor.topic)
    _custom(prim, "robodesc:sensor:noise", "double", sensor.noise)
    if sensor.parent_joint is not None:
        _custom(prim, "robodesc:sensor:parentJoint", "string", sensor.parent_joint)


def _camera(ctx: UsdContext, sensor: Sensor, path: str, pose: Frame) -> Prim:
    prim = ctx.define(GEOMETRY, path, "Camera")
    set_pose(prim, pose.rotated(CAMERA_FROM_SENSOR))
    spec = sensor.camera
    if spec is None:
        return prim
    prim.attr("horizontalAperture", "float", HORIZONTAL_APERTURE)
    if spec.hfov is not None and 0 < spec.hfov < math.pi:
        prim.attr("focalLength", "float", HORIZONTAL_APERTURE / 2 / math.tan(spec.hfov / 2))
    if spec.width and spec.height:
        prim.attr("verticalAperture", "float", HORIZONTAL_APERTURE * spec.height / spec.width)
    if spec.near is not None and spec.far is not None:
        prim.attr("clippingRange", "float2", (spec.near, spec.far))
    _custom(prim, "robodesc:camera:width", "int", spec.width)
    _custom(prim, "robodesc:camera:height", "int", spec.height)
    _custom(prim, "robodesc:camera:hfov", "double", spec.hfov)
    _custom(prim, "robodesc:camera:format", "string", spec.format)
    return prim


def _lidar(prim: Prim, sensor: Sensor) -> None:
    _custom(prim, "cameraSensorType", "token", "lidar")
    _custom(prim, "sensorModelPluginName", "string", LIDAR_PLUGIN)
    _custom(prim, "sensorModelConfig", "string", sensor.isaac_sim_config)
    _custom(prim, "robodesc:isaacSimConfig", "string", sensor.isaac_sim_config)
    ray = sensor.ray
    if ray is None:
        return
    _custom(prim, "robodesc:ray:minRange", "double", ray.min_range)
    _custom(prim, "robodesc:ray:maxRange", "double", ray.max_range)
    for name, axis in (("horizontal", ray.horizontal), ("vertical", ray.vertical)):
        if axis is not None:
            _ray_axis(prim, name, axis)


def _ray_axis(prim: Prim, name: str, axis: RayAxis) -> None:
    base = f"robodesc:ray:{name}"
    _custom(prim, f"{base}:samples", "int", axis.samples)
    _custom(prim, f"{base}:resolution", "double", axis.resolution)
    _custom(prim, f"{base}:minAngle", "double", axis.min_angle)
    _custom(prim, f"{base}:maxAngle", "double", axis.max_angle)


def _custom(prim: Prim, name: str, type_name: str, value: object) -> None:
    if value is not None:
        prim.attr(name, type_name, value, custom=True)
