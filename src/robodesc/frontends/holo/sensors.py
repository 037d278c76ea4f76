"""``@sensor { type, name, ... }`` traits: cameras, depth cameras, lidars and the sensors that are
only a name and a frame (imu, force_torque, contact, gps)."""

from __future__ import annotations

import math

from robodesc.frontends.compose.builder import RobotBuilder
from robodesc.frontends.holo.context import Lowering, Obj
from robodesc.frontends.holo.parser import Trait, Value
from robodesc.frontends.holo.values import fail, num, string, vec3
from robodesc.ir.geometry import Pose
from robodesc.ir.model import CameraSpec, RayAxis, RaySpec

SENSOR_PARAMS = frozenset(
    {
        "type",
        "name",
        "fov",
        "width",
        "height",
        "near",
        "far",
        "format",
        "topic",
        "frameName",
        "updateRate",
        "samples",
        "verticalSamples",
        "minAngle",
        "maxAngle",
        "minRange",
        "maxRange",
        "noise",
        "isaac_sim_config",
        "position",
        "rotation",
    }
)


def builder_has_sensor(builder: RobotBuilder, name: str) -> bool:
    return name in builder._sensors


def lower_sensors(ctx: Lowering, builder: RobotBuilder, obj: Obj) -> None:
    for t in obj.traits_named("sensor"):
        if "type" not in t.params:
            ctx.note(
                "ignored-sensor",
                "@sensor without a type (camera, depth, lidar, imu, force_torque, contact, gps) ignored",
                obj.label,
                t.loc,
                warn=True,
            )
            continue
        _sensor(ctx, builder, obj, t)


def _sensor(ctx: Lowering, builder: RobotBuilder, obj: Obj, t: Trait) -> None:
    label = obj.label
    p = t.params
    stype = string(p["type"], "@sensor.type", label)
    for key in p:
        if key not in SENSOR_PARAMS:
            ctx.note("ignored-parameter", f"@sensor parameter {key!r} ignored", label, t.key_locs.get(key))
    base = string(p["name"], "@sensor.name", label) if "name" in p else f"{obj.name}_{stype}"
    name = base
    i = 2
    while builder_has_sensor(builder, name):
        name = f"{base}_{i}"
        i += 1
    pose = _local_pose(p, label)
    camera = _camera(ctx, p, label) if stype in ("camera", "depth") else None
    ray = _ray(ctx, p, label) if stype in ("lidar", "ray") else None
    builder.sensor(
        name,
        stype,
        obj.name,
        pose=pose,
        update_rate=num(p["updateRate"], "@sensor.updateRate", label) if "updateRate" in p else None,
        topic=string(p["topic"], "@sensor.topic", label) if "topic" in p else None,
        noise=num(p["noise"], "@sensor.noise", label) if "noise" in p else None,
        camera=camera,
        ray=ray,
        isaac_sim_config=string(p["isaac_sim_config"], "@sensor.isaac_sim_config", label)
        if "isaac_sim_config" in p
        else None,
        src=t.loc,
    )
    if "frameName" in p:
        frame_name = string(p["frameName"], "@sensor.frameName", label)
        builder.frame(frame_name, obj.name, pose, src=p["frameName"].loc)


def _camera(ctx: Lowering, p: dict[str, Value], label: str) -> CameraSpec:
    fov = _angle_rad(ctx, p, "fov", label)
    return CameraSpec(
        width=_int(p, "width", label),
        height=_int(p, "height", label),
        hfov=fov,
        near=num(p["near"], "@sensor.near", label) if "near" in p else None,
        far=num(p["far"], "@sensor.far", label) if "far" in p else None,
        format=string(p["format"], "@sensor.format", label) if "format" in p else None,
    )


def _ray(ctx: Lowering, p: dict[str, Value], label: str) -> RaySpec:
    horizontal = RayAxis(
        samples=_int(p, "samples", label),
        min_angle=_angle_rad(ctx, p, "minAngle", label),
        max_angle=_angle_rad(ctx, p, "maxAngle", label),
    )
    vertical = RayAxis(samples=_int(p, "verticalSamples", label)) if "verticalSamples" in p else None
    return RaySpec(
        horizontal=horizontal,
        vertical=vertical,
        min_range=num(p["minRange"], "@sensor.minRange", label) if "minRange" in p else None,
        max_range=num(p["maxRange"], "@sensor.maxRange", label) if "maxRange" in p else None,
    )


def _local_pose(p: dict[str, Value], label: str) -> Pose | None:
    if "position" not in p and "rotation" not in p:
        return None
    xyz = vec3(p["position"], "@sensor.position", label) if "position" in p else (0.0, 0.0, 0.0)
    deg = vec3(p["rotation"], "@sensor.rotation", label) if "rotation" in p else (0.0, 0.0, 0.0)
    return Pose(xyz=xyz, rpy=(math.radians(deg[0]), math.radians(deg[1]), math.radians(deg[2])))


def _angle_rad(ctx: Lowering, p: dict[str, Value], key: str, label: str) -> float | None:
    if key not in p:
        return None
    value = num(p[key], f"@sensor.{key}", label)
    if abs(value) > 2 * math.pi:
        ctx.note(
            "sensor-angle-unit",
            f"@sensor.{key} = {value:g} is read in radians (as URDF and SDF sensors are) but looks like degrees",
            label,
            p[key].loc,
            warn=True,
        )
    return value


def _int(p: dict[str, Value], key: str, label: str) -> int | None:
    if key not in p:
        return None
    value = num(p[key], f"@sensor.{key}", label)
    if value != int(value) or value < 0:
        raise fail(f"@sensor.{key}: expected a whole number, got {value:g}", label, p[key].loc)
    return int(value)
