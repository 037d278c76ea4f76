"""The ``--world`` wrapper: a ``<world>`` with physics, gravity, sun, ground plane, the robot and props.

Gazebo Harmonic loads its default systems only when a world names none, so a world that adds the
sensor systems must list physics, user commands and the scene broadcaster too.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from lxml import etree

from robodesc.emit.common.numbers import fmt, fmt_vec
from robodesc.emit.sdf.options import SdfFlavour, SdfOptions
from robodesc.emit.sdf.sensors import GzSystem, required_systems, system_plugin
from robodesc.ir.diagnostics import Findings
from robodesc.ir.model import Robot

if TYPE_CHECKING:
    from robodesc.emit.common.target import WorldAlone
    from robodesc.emit.common.world import PlacedWorld

E = etree.SubElement

BASE_SYSTEMS = (
    GzSystem("gz-sim-physics-system", "gz::sim::systems::Physics"),
    GzSystem("gz-sim-user-commands-system", "gz::sim::systems::UserCommands"),
    GzSystem("gz-sim-scene-broadcaster-system", "gz::sim::systems::SceneBroadcaster"),
)
GROUND_PLANE = "ground_plane"


def world_element(parent: etree._Element, robots: list[Robot], options: SdfOptions) -> etree._Element:
    """The world and everything in it but the models; the caller appends those."""
    classic = options.flavour is SdfFlavour.CLASSIC
    world = E(parent, "world", name=options.world_name)
    physics = E(world, "physics", name="default_physics", type="ode" if classic else "ignored")
    E(physics, "max_step_size").text = fmt(options.step_size)
    E(physics, "real_time_factor").text = fmt(options.real_time_factor)
    if classic:
        E(E(E(physics, "ode"), "solver"), "type").text = options.resolved_solver()
    else:
        E(E(E(physics, "dart"), "solver"), "solver_type").text = options.resolved_solver()
    E(world, "gravity").text = fmt_vec(options.gravity)
    sensors = [s for r in robots for s in r.sensors]
    if not classic:
        for system in (*BASE_SYSTEMS, *required_systems(sensors)):
            system_plugin(world, system)
    if any(s.type.value == "gps" for s in sensors):
        # NavSat needs a geodetic origin; robodesc knows none, so the world sits at 0°N 0°E.
        sc = E(world, "spherical_coordinates")
        E(sc, "surface_model").text = "EARTH_WGS84"
        E(sc, "world_frame_orientation").text = "ENU"
        for tag in ("latitude_deg", "longitude_deg", "elevation", "heading_deg"):
            E(sc, tag).text = "0"
    _sun(world)
    if options.placed_world is not None:
        from robodesc.emit.sdf.world_models import world_models

        world_models(world, options.placed_world, options)
    if options.placed_world is None or not options.placed_world.world.bodies:
        _ground(world)  # a world of cords alone stands on robodesc's ground plane
    return world


def write_world_alone(
    placed: PlacedWorld, out: str, options: SdfOptions, findings: Findings, validate: bool
) -> WorldAlone:
    """``robodesc compile W.world -t sdf -o world.sdf``: the world's static models and physics, no robot."""
    import os

    from robodesc._files import write_atomic

    options.world, options.placed_world = True, placed
    options.out_dir = os.path.dirname(os.path.abspath(out))
    physics = placed.world.physics
    if physics.step is not None:
        options.step_size = physics.step
    if physics.gravity is not None:
        options.gravity = physics.gravity
    options.check()
    root = etree.Element("sdf", version=options.resolved_version())
    world_element(root, [], options)
    etree.indent(root, space="  ")
    text = '<?xml version="1.0" encoding="utf-8"?>\n' + etree.tostring(root, encoding="unicode") + "\n"
    write_atomic(out, text)
    if not validate:
        return {"sdf": out}, None
    from robodesc.validation.world import check_sdf_world

    # One model per static body and per cord, and the ground plane of a world without bodies.
    models = len(placed.world.bodies) + sum(c.count for c, _ in placed.cords) + (0 if placed.world.bodies else 1)
    return {"sdf": out}, check_sdf_world(text, placed.world.name, models)


def _sun(world: etree._Element) -> None:
    sun = E(world, "light", type="directional", name="sun")
    E(sun, "cast_shadows").text = "true"
    E(sun, "pose").text = "0 0 10 0 0 0"
    E(sun, "diffuse").text = "0.8 0.8 0.8 1"
    E(sun, "specular").text = "0.2 0.2 0.2 1"
    att = E(sun, "attenuation")
    for tag, value in (("range", "1000"), ("constant", "0.9"), ("linear", "0.01"), ("quadratic", "0.001")):
        E(att, tag).text = value
    E(sun, "direction").text = "-0.5 0.1 -0.9"


def _ground(world: etree._Element) -> None:
    model = E(world, "model", name=GROUND_PLANE)
    E(model, "static").text = "true"
    link = E(model, "link", name="link")
    for tag in ("collision", "visual"):
        el = E(link, tag, name=tag)
        plane = E(E(el, "geometry"), "plane")
        E(plane, "normal").text = "0 0 1"
        E(plane, "size").text = "100 100"
        if tag == "visual":
            mat = E(el, "material")
            for m in ("ambient", "diffuse", "specular"):
                E(mat, m).text = "0.8 0.8 0.8 1"
