"""Fill inertials that give a mass but no tensor, from the link's shapes.

Compositions produce such links (a part declares its mass only). The shapes are the collision
geometry, else the visual geometry; several shapes are combined with the parallel-axis theorem,
the mass split by volume. A given ``<origin>`` is kept (the tensor is taken about it); without one,
the shapes' centre of mass is written into ``Inertial.origin``.
"""

from __future__ import annotations

from robodesc.ir.model import Robot
from robodesc.passes.context import PassContext

NAME = "geometric_inertia"


def geometric_inertia(robot: Robot, ctx: PassContext) -> Robot:
    ctx.stage = NAME
    for link in robot.links:
        inertial = link.inertial
        if inertial is None or inertial.inertia is not None or inertial.mass is None or not inertial.mass > 0:
            continue
        # Imported here: the shape maths needs numpy, which a robot with every tensor given never loads.
        from robodesc.passes.shape_inertia import inertial_from_props, link_props

        label = f"link {link.name!r}"
        found = link_props(link)
        if found is None:
            ctx.warn(
                "no-geometry",
                "has a mass but no inertia tensor, and no readable geometry to derive one from",
                element=label,
                loc=inertial.src or link.src,
            )
            continue
        props, source = found
        new = inertial_from_props(props, mass=inertial.mass, origin=inertial.origin)
        new.src = inertial.src
        link.inertial = new
        for note in props.notes:
            ctx.warn("mesh-not-watertight", note, element=label, loc=link.src)
        i = new.inertia
        assert i is not None
        ctx.info(
            "inertia-from-geometry",
            f"inertia tensor computed from its {source} geometry for mass {inertial.mass:g} kg: "
            f"ixx={i.ixx:.6g} iyy={i.iyy:.6g} izz={i.izz:.6g}",
            element=label,
            loc=inertial.src or link.src,
        )
    return robot
