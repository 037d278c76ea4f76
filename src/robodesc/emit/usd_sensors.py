"""Fixed frames and sensors: prims under the link they ride on.

- camera / depth: a ``UsdGeom.Camera``. USD cameras look down -Z with +Y up, URDF/ROS sensors look
  along +X with +Z up, so the prim's pose is the sensor pose turned by that fixed rotation.
  Focal length and apertures (mm, USD's convention) come from the horizontal field of view.
- ray (lidar): a ``Camera`` prim in the sensor frame carrying what Isaac Sim 4.x/5.x's RTX lidar
  reads (``cameraSensorType = "lidar"``, ``sensorModelPluginName``, ``sensorModelConfig`` = the
  URDF's ``isaac_sim_config`` preset or JSON path) plus the URDF ray parameters as
  ``robodesc:ray:*`` attributes.
- everything else: an ``Xform`` with the parameters as ``robodesc:*`` custom attributes.
"""

from __future__ import annotations

import math

import numpy as np
from pxr import Gf, Sdf, Usd, UsdGeom

from robodesc.emit.usd_context import GEOMETRY, UsdContext, set_display_name, set_pose
from robodesc.emit.usd_math import camera_from_sensor
from robodesc.ir.model import FixedFrame, RayAxis, Sensor, SensorType
from robodesc.ir.transforms import pose_matrix

# USD's default horizontal aperture (mm, a 35 mm film back).
HORIZONTAL_APERTURE = 20.955
LIDAR_PLUGIN = "omni.sensors.nv.lidar.lidar_core.plugin"

T = Sdf.ValueTypeNames


def emit_fixed_frame(ctx: UsdContext, frame: FixedFrame, path: Sdf.Path) -> None:
    with ctx.layer(GEOMETRY):
        xform = UsdGeom.Xform.Define(ctx.stage, path)
        set_pose(xform, pose_matrix(frame.origin))
        set_display_name(xform.GetPrim(), frame.display_name)


def emit_sensor(ctx: UsdContext, sensor: Sensor, path: Sdf.Path) -> None:
    pose = pose_matrix(sensor.origin)
    with ctx.layer(GEOMETRY):
        if sensor.type in (SensorType.CAMERA, SensorType.DEPTH):
            prim = _camera(ctx, sensor, path, pose)
        elif sensor.type is SensorType.RAY:
            camera = UsdGeom.Camera.Define(ctx.stage, path)
            set_pose(camera, pose)
            prim = camera.GetPrim()
            _lidar(prim, sensor)
        else:
            xform = UsdGeom.Xform.Define(ctx.stage, path)
            set_pose(xform, pose)
            prim = xform.GetPrim()
        set_display_name(prim, sensor.display_name)
        _custom(prim, "robodesc:sensor:type", T.Token, sensor.type.value)
        _custom(prim, "robodesc:sensor:updateRate", T.Double, sensor.update_rate)
        _custom(prim, "robodesc:sensor:topic", T.String, sensor.topic)
        _custom(prim, "robodesc:sensor:noise", T.Double, sensor.noise)
        if sensor.parent_joint is not None:
            _custom(prim, "robodesc:sensor:parentJoint", T.String, sensor.parent_joint)


def _camera(ctx: UsdContext, sensor: Sensor, path: Sdf.Path, pose: np.ndarray) -> Usd.Prim:
    camera = UsdGeom.Camera.Define(ctx.stage, path)
    turned = pose.copy()
    turned[:3, :3] = pose[:3, :3] @ camera_from_sensor()
    set_pose(camera, turned)
    spec = sensor.camera
    prim = camera.GetPrim()
    if spec is None:
        return prim
    camera.CreateHorizontalApertureAttr(HORIZONTAL_APERTURE)
    if spec.hfov is not None and 0 < spec.hfov < math.pi:
        camera.CreateFocalLengthAttr(HORIZONTAL_APERTURE / 2 / math.tan(spec.hfov / 2))
    if spec.width and spec.height:
        camera.CreateVerticalApertureAttr(HORIZONTAL_APERTURE * spec.height / spec.width)
    if spec.near is not None and spec.far is not None:
        camera.CreateClippingRangeAttr(Gf.Vec2f(spec.near, spec.far))
    _custom(prim, "robodesc:camera:width", T.Int, spec.width)
    _custom(prim, "robodesc:camera:height", T.Int, spec.height)
    _custom(prim, "robodesc:camera:hfov", T.Double, spec.hfov)
    _custom(prim, "robodesc:camera:format", T.String, spec.format)
    return prim


def _lidar(prim: Usd.Prim, sensor: Sensor) -> None:
    _custom(prim, "cameraSensorType", T.Token, "lidar")
    _custom(prim, "sensorModelPluginName", T.String, LIDAR_PLUGIN)
    _custom(prim, "sensorModelConfig", T.String, sensor.isaac_sim_config)
    _custom(prim, "robodesc:isaacSimConfig", T.String, sensor.isaac_sim_config)
    ray = sensor.ray
    if ray is None:
        return
    _custom(prim, "robodesc:ray:minRange", T.Double, ray.min_range)
    _custom(prim, "robodesc:ray:maxRange", T.Double, ray.max_range)
    for name, axis in (("horizontal", ray.horizontal), ("vertical", ray.vertical)):
        if axis is not None:
            _ray_axis(prim, name, axis)


def _ray_axis(prim: Usd.Prim, name: str, axis: RayAxis) -> None:
    base = f"robodesc:ray:{name}"
    _custom(prim, f"{base}:samples", T.Int, axis.samples)
    _custom(prim, f"{base}:resolution", T.Double, axis.resolution)
    _custom(prim, f"{base}:minAngle", T.Double, axis.min_angle)
    _custom(prim, f"{base}:maxAngle", T.Double, axis.max_angle)


def _custom(prim: Usd.Prim, name: str, type_name: Sdf.ValueTypeName, value: object) -> None:
    if value is not None:
        prim.CreateAttribute(name, type_name, custom=True).Set(value)
