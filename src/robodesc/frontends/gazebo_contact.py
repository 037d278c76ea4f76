"""Contact parameters in URDF ``<gazebo reference="LINK">`` blocks, read into the IR.

Two spellings are in use, often in one file:
- Gazebo Classic's shorthand, children of the block: ``mu1``, ``mu2``, ``kp``, ``kd``, ``minDepth``,
  ``maxVel``, ``fdir1``, ``selfCollide``;
- SDF's ``<collision><surface>`` nested in the block (``friction/ode/mu``, ``bounce/...``,
  ``contact/ode/kp`` ...), as Spirit's toes write them.
Gazebo applies both to every collision of the link (urdf2sdf copies the block into each), so they
become the link's contact (``Link.contact``); the block itself stays an extension, kept verbatim in
the URDF output. A value that is not a number is a warning naming it, and is left out.
"""

from __future__ import annotations

from typing import Any

from lxml import etree

from robodesc.ir.contact import Contact
from robodesc.ir.diagnostics import Findings, SourceLoc
from robodesc.ir.model import Robot

# Shorthand child -> Contact field.
_SHORTHAND = {"mu1": "mu", "mu2": "mu2", "kp": "kp", "kd": "kd", "minDepth": "min_depth", "maxVel": "max_vel"}
# Path under <surface> -> Contact field (ODE's parameters, and the engine-neutral ones SDF has).
_SURFACE = {
    "friction/ode/mu": "mu",
    "friction/ode/mu2": "mu2",
    "bounce/restitution_coefficient": "restitution",
    "bounce/threshold": "bounce_threshold",
    "contact/ode/kp": "kp",
    "contact/ode/kd": "kd",
    "contact/ode/min_depth": "min_depth",
    "contact/ode/max_vel": "max_vel",
}


def read_gazebo_contact(robot: Robot, findings: Findings) -> None:
    """Gazebo blocks into ``Link.contact``; a ``<surface>`` written inside a URDF ``<collision>``
    (SDF's spelling, which some URDFs carry) into that ``Collision.contact``."""
    _read_link_blocks(robot, findings)
    for link in robot.links:
        for index, collision in enumerate(link.collisions):
            for ext in collision.extensions:
                if ext.tag != "surface":
                    continue
                values: dict[str, Any] = {}
                _surface(_parse(ext.xml), values, f"link {link.name!r} collision {index}", ext.src, findings)
                if values:
                    collision.contact = Contact(**values, src=ext.src).merged_over(collision.contact)


def surface_contact(surface: Any, label: str, src: SourceLoc | None, findings: Findings) -> Contact | None:
    """An SDF ``<surface>`` element's parameters (None when it gives none): the SDF model frontend's
    collisions, read as a URDF's embedded ``<surface>`` is."""
    values: dict[str, Any] = {}
    _surface(surface, values, label, src, findings)
    return Contact(**values, src=src) if values else None


def _parse(xml: str) -> Any:
    return etree.fromstring(xml, etree.XMLParser(resolve_entities=False, no_network=True))


def _surface(surface: Any, values: dict[str, Any], label: str, src: SourceLoc | None, findings: Findings) -> None:
    for path, name in _SURFACE.items():
        _number(surface.find(path), name, values, label, src, findings)
    _vector(surface.find("friction/ode/fdir1"), values, label, src, findings)
    # ODE's torsional friction torque is coefficient x patch radius x normal force: the IR keeps the
    # product (m), as MuJoCo and Newton take it. Without a patch radius ODE applies none.
    torsion: dict[str, Any] = {}
    _number(surface.find("friction/torsional/coefficient"), "coefficient", torsion, label, src, findings)
    _number(surface.find("friction/torsional/patch_radius"), "radius", torsion, label, src, findings)
    if "coefficient" in torsion and "radius" in torsion:
        values["torsional"] = torsion["coefficient"] * torsion["radius"]
    # Bullet's parameters (<bullet>) are Bullet's: Gazebo's ODE and DART ignore them, and so does robodesc.


def _read_link_blocks(robot: Robot, findings: Findings) -> None:
    links = robot.link_map()
    for ext in robot.extensions:
        if ext.tag != "gazebo" or ext.reference not in links:
            continue
        link = links[ext.reference]
        root = _parse(ext.xml)
        values: dict[str, Any] = {}
        label = f"gazebo reference {ext.reference!r}"
        for tag, name in _SHORTHAND.items():
            _number(root.find(tag), name, values, label, ext.src, findings)
        _vector(root.find("fdir1"), values, label, ext.src, findings)
        for surface in root.iterfind("collision/surface"):
            _surface(surface, values, label, ext.src, findings)
        self_collide = root.findtext("selfCollide")
        if self_collide is not None and self_collide.strip().lower() in ("true", "1", "false", "0"):
            link.self_collide = self_collide.strip().lower() in ("true", "1")
        if values:
            contact = Contact(**values, src=ext.src)
            link.contact = contact.merged_over(link.contact)


def _number(el: Any, name: str, values: dict[str, Any], label: str, src: SourceLoc | None, findings: Findings) -> None:
    if el is None or el.text is None:
        return
    try:
        values[name] = float(el.text.strip())
    except ValueError:
        findings.warn(
            "bad-contact",
            f"<{el.tag}> {el.text.strip()!r} is not a number; left out (the engine's default applies)",
            element=label,
            loc=src,
            stage="frontend",
        )


def _vector(el: Any, values: dict[str, Any], label: str, src: SourceLoc | None, findings: Findings) -> None:
    if el is None or el.text is None:
        return
    try:
        x, y, z = (float(v) for v in el.text.split())
    except ValueError:
        findings.warn(
            "bad-contact",
            f"<fdir1> {el.text.strip()!r} is not three numbers; left out",
            element=label,
            loc=src,
            stage="frontend",
        )
        return
    values["fdir1"] = (x, y, z)
