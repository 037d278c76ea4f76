"""The ``--world`` wrapper: a ``<world>`` with physics, gravity, sun, ground plane, the robot and props.

Gazebo Harmonic loads its default systems only when a world names none, so a world that adds the
sensor systems must list physics, user commands and the scene broadcaster too.
"""

from __future__ import annotations

from lxml import etree

from robodesc.emit.common.numbers import fmt, fmt_vec
from robodesc.emit.sdf.options import SdfFlavour, SdfOptions
from robodesc.emit.sdf.sensors import GzSystem, required_systems, system_plugin
from robodesc.ir.model import Robot

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
