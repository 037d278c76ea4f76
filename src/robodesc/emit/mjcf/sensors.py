"""Fixed frames and sensors as sites, and MuJoCo sensors and cameras where MuJoCo has them.

IMU -> ``accelerometer`` + ``gyro``; force/torque -> ``force`` + ``torque`` (at the site, on the
child link of the measured joint); camera/depth -> ``<camera>``; ray -> ``rangefinder`` (one ray);
contact and GPS -> a site only, with a warning.
"""

from __future__ import annotations

import math
import xml.etree.ElementTree as ET

from robodesc.emit.mjcf.context import MjcfContext, insert_site, num, set_pose
from robodesc.ir.model import SensorType
from robodesc.ir.rigid import Frame, pose_frame

# MuJoCo cameras look along -Z with +Y up; robodesc's sensor frames (Gazebo's) look along +X with +Z
# up. Columns: the camera's x, y, z axes in the sensor frame.
_CAMERA = Frame(((0.0, 0.0, -1.0), (-1.0, 0.0, 0.0), (0.0, 1.0, 0.0)))
# A rangefinder measures along the site's +Z; the sensor's ray goes along +X.
_RAY = Frame(((0.0, 0.0, 1.0), (0.0, 1.0, 0.0), (-1.0, 0.0, 0.0)))


def sites_and_sensors(ctx: MjcfContext) -> ET.Element | None:
    for fixed in ctx.robot.fixed_frames:
        body = ctx.bodies.get(fixed.parent)
        if body is None:
            continue
        site = ET.Element("site", name=ctx.unique_site(fixed.name))
        set_pose(site, fixed.origin)
        insert_site(body, site)
    out = ET.Element("sensor")
    for sensor in ctx.robot.sensors:
        label = f"sensor {sensor.name!r}"
        body = ctx.bodies.get(sensor.parent)
        if body is None:
            ctx.warn("mjcf-sensor-dropped", f"link {sensor.parent!r} is not a body: sensor left out", label)
            continue
        frame = pose_frame(sensor.origin)
        if sensor.type in (SensorType.CAMERA, SensorType.DEPTH):
            cam = ET.Element("camera", name=sensor.name)
            set_pose(cam, frame @ _CAMERA)
            spec = sensor.camera
            if spec is not None and spec.hfov is not None:
                aspect = (spec.height / spec.width) if spec.width and spec.height else 1.0
                fovy = 2 * math.atan(math.tan(spec.hfov / 2) * aspect)
                cam.set("fovy", num(math.degrees(fovy)))  # MuJoCo's fovy is in degrees whatever the angle unit
            if spec is not None and spec.width and spec.height:
                cam.set("resolution", f"{spec.width} {spec.height}")
            insert_site(body, cam)
            if sensor.type is SensorType.DEPTH:
                ctx.info("mjcf-depth-camera", "a depth camera is a MuJoCo camera; render depth from it", label)
            continue
        site = ET.Element("site", name=ctx.unique_site(sensor.name))
        set_pose(site, frame @ _RAY if sensor.type is SensorType.RAY else frame)
        insert_site(body, site)
        name = site.get("name", sensor.name)
        if sensor.type is SensorType.IMU:
            ET.SubElement(out, "accelerometer", name=f"{sensor.name}_acc", site=name)
            ET.SubElement(out, "gyro", name=f"{sensor.name}_gyro", site=name)
        elif sensor.type is SensorType.FORCE_TORQUE:
            ET.SubElement(out, "force", name=f"{sensor.name}_force", site=name)
            ET.SubElement(out, "torque", name=f"{sensor.name}_torque", site=name)
        elif sensor.type is SensorType.RAY:
            ET.SubElement(out, "rangefinder", name=sensor.name, site=name)
            ray = sensor.ray
            if ray is not None and ((ray.horizontal and (ray.horizontal.samples or 1) > 1) or ray.vertical):
                ctx.warn(
                    "mjcf-ray-single",
                    "MuJoCo's rangefinder measures one ray (along the sensor's +X): the scan pattern is not written",
                    label,
                    sensor.src,
                )
        else:
            ctx.warn(
                "mjcf-sensor-site-only",
                f"MuJoCo has no {sensor.type.value} sensor of this kind: only a site marks it",
                label,
                sensor.src,
            )
    return out if len(out) else None
