"""MJCF -> IR: read safely (:mod:`.source`), compile with MuJoCo (:mod:`.compiled`), then read the
compiled model section by section, each message naming the element and its ``file:line``."""

from __future__ import annotations

from robodesc.frontends.mjcf.actuators import read_actuators
from robodesc.frontends.mjcf.bodies import read_bodies
from robodesc.frontends.mjcf.compiled import compile_model
from robodesc.frontends.mjcf.constraints import read_contact, read_equalities
from robodesc.frontends.mjcf.context import Reading, locate
from robodesc.frontends.mjcf.extras import read_cameras, read_keyframe, read_sensors, read_sites
from robodesc.frontends.mjcf.geoms import read_geoms
from robodesc.frontends.mjcf.source import read_source
from robodesc.frontends.mjcf.unheld import warn_unheld
from robodesc.frontends.options import LoadOptions
from robodesc.ir.diagnostics import Findings
from robodesc.ir.model import Robot


def read_mjcf(path: str, options: LoadOptions, findings: Findings) -> Robot:
    source = read_source(path, findings)
    model = compile_model(source, findings)
    name = source.root.get("model") or "robot"
    own = [
        b for w in source.root.iter("worldbody") for b in w.iterchildren("body") if source.loc(b).file == source.file
    ]
    if source.included_models and not own:
        # A scene (menagerie's scene.xml: "go1 scene") is named by the robot it includes.
        name = source.included_models[0]
    robot = Robot(name=name, src=source.loc(source.root), source_file=source.file)
    r = Reading(model=model, source=source, options=options, findings=findings, robot=robot)
    r.elements = locate(model, source)
    read_bodies(r)
    r.link_names = {link.name for link in robot.links}
    read_geoms(r)
    read_actuators(r)
    read_equalities(r)
    read_contact(r)
    sites = read_sites(r)
    read_cameras(r)
    read_sensors(r, sites)
    read_keyframe(r)
    warn_unheld(r)
    return robot
