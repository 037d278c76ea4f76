"""Fixed frames and sensors as sites, and MuJoCo sensors and cameras where MuJoCo has them.

IMU -> ``accelerometer`` + ``gyro``; force/torque -> ``force`` + ``torque`` (at the site, on the
child link of the measured joint); camera/depth -> ``<camera>``; ray -> ``rangefinder`` (one ray);
contact -> ``touch`` on a box site that covers the link's colliders (MuJoCo's touch sums the normal
force of every contact inside its site's volume); GPS -> a site only, with a warning.
"""

from __future__ import annotations

import math
import xml.etree.ElementTree as ET

from robodesc.emit.mjcf.context import MjcfContext, insert_site, num, set_pose
from robodesc.ir.geometry import Box, Capsule, Cylinder, Mesh, Sphere, Vec3
from robodesc.ir.model import Link, SensorType
from robodesc.ir.rigid import Frame, pose_frame
from robodesc.meshes.buffers import MeshReadError
from robodesc.meshes.data import MeshCache

# MuJoCo cameras look along -Z with +Y up; robodesc's sensor frames (Gazebo's) look along +X with +Z
# up. Columns: the camera's x, y, z axes in the sensor frame.
_CAMERA = Frame(((0.0, 0.0, -1.0), (-1.0, 0.0, 0.0), (0.0, 1.0, 0.0)))
# A rangefinder measures along the site's +Z; the sensor's ray goes along +X.
_RAY = Frame(((0.0, 0.0, 1.0), (0.0, 1.0, 0.0), (-1.0, 0.0, 0.0)))


# m: a touch site reaches this far past the colliders, so contacts on their surface (MuJoCo puts the
# contact point midway through the penetration) fall inside it.
TOUCH_MARGIN = 0.005


def collider_box(link: Link, cache: MeshCache) -> tuple[Vec3, Vec3] | None:
    """The centre and half extents, in the link's frame, of the box around the link's colliders
    (``cache``: one for every sensor of the robot, so a mesh two feet share is read once)."""
    corners: list[Vec3] = []
    for collision in link.collisions:
        g = collision.geometry
        if isinstance(g, Box):
            half: Vec3 = (g.size[0] / 2, g.size[1] / 2, g.size[2] / 2)
            lo, hi = (-half[0], -half[1], -half[2]), half
        elif isinstance(g, Sphere):
            lo, hi = (-g.radius,) * 3, (g.radius,) * 3
        elif isinstance(g, Cylinder | Capsule):
            end = g.length / 2 + (g.radius if isinstance(g, Capsule) else 0.0)
            lo, hi = (-g.radius, -g.radius, -end), (g.radius, g.radius, end)
        elif isinstance(g, Mesh) and g.path:
            try:
                lo, hi = cache.get(str(g.path), g.scale).extent
            except (MeshReadError, OSError):
                continue
        else:
            continue
        place = pose_frame(collision.origin)
        for x in (lo[0], hi[0]):
            for y in (lo[1], hi[1]):
                for z in (lo[2], hi[2]):
                    corners.append((place @ Frame(translation=(x, y, z))).translation)
    if not corners:
        return None
    low = tuple(min(c[i] for c in corners) for i in range(3))
    high = tuple(max(c[i] for c in corners) for i in range(3))
    centre = tuple((a + b) / 2 for a, b in zip(low, high, strict=True))
    extent = tuple((b - a) / 2 for a, b in zip(low, high, strict=True))
    return centre, extent  # type: ignore[return-value]


def sites_and_sensors(ctx: MjcfContext) -> ET.Element | None:
    for fixed in ctx.robot.fixed_frames:
        body = ctx.bodies.get(fixed.parent)
        if body is None:
            continue
        site = ET.Element("site", name=ctx.unique_site(fixed.name))
        set_pose(site, fixed.origin)
        insert_site(body, site)
    out = ET.Element("sensor")
    meshes = MeshCache()
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
        if sensor.type is SensorType.CONTACT:
            box = collider_box(ctx.robot.link(sensor.parent), meshes)
            if box is None:
                ctx.warn("mjcf-contact-no-collider", "the link has no collider to touch anything: site only", label)
            else:
                centre, half = box
                site.attrib.pop("pos", None)
                site.attrib.pop("quat", None)
                site.set("type", "box")
                site.set("pos", " ".join(num(v) for v in centre))
                site.set("size", " ".join(num(v + TOUCH_MARGIN) for v in half))
                site.set("group", "4")  # out of the default view, as a sensor volume should be
        insert_site(body, site)
        name = site.get("name", sensor.name)
        if sensor.type is SensorType.CONTACT and site.get("type") == "box":
            ET.SubElement(out, "touch", name=sensor.name, site=name)
        elif sensor.type is SensorType.IMU:
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
