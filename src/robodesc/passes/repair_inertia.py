"""Repair missing and non-physical inertials by a declared policy (:class:`RepairPolicy`).

``quad_sdk`` reproduces Quad-SDK's step 4 exactly:
- a link without ``<inertial>`` gets 0.001 kg and a 1e-6 kg·m² diagonal at the link origin;
- a mass ≤ 0 (or absent) becomes 0.001 kg, then each diagonal term ≤ 0 becomes 1e-6 (off-diagonals
  untouched);
and closes its gap: a tensor that is still missing or non-physical (not positive definite, triangle
inequality broken: :func:`robodesc.ir.inertia.inertia_problem`) is recomputed from the link's
geometry for its mass, or set to the 1e-6 diagonal when the link has no geometry.

``geometry`` derives everything it repairs from the geometry (mass = density × volume when the mass
is not positive), and uses the Quad-SDK constants only for links without geometry.

``geometry`` gives a massless link (no ``<inertial>``, or no or a zero mass) a mass only where it
would be a dead body: in a moving fixed group without any mass (``passes/massless.py``). A massless
link fixed to one with mass keeps URDF's meaning, carried by it (Gazebo lumps it), and so does the
root's group: neither is given a mass from its geometry.

``repair_missing=False`` leaves links without ``<inertial>`` alone. Every repair is a finding.
"""

from __future__ import annotations

import math

from robodesc.ir.geometry import Inertia, Inertial, Pose
from robodesc.ir.model import Link, Robot
from robodesc.ir.principal import below_engine_floor, engine_floor, inertia_problem, principal_moments, tensor_rows
from robodesc.passes.context import PassContext
from robodesc.passes.options import RepairPolicy

NAME = "repair_inertia"
QUAD_SDK_MASS = 0.001  # kg
QUAD_SDK_DIAGONAL = 1e-6  # kg·m²


def _constant_tensor() -> Inertia:
    return Inertia(ixx=QUAD_SDK_DIAGONAL, iyy=QUAD_SDK_DIAGONAL, izz=QUAD_SDK_DIAGONAL)


def _mass_ok(mass: float | None) -> bool:
    return mass is not None and math.isfinite(mass) and mass > 0


def _carried(link: Link) -> bool:
    """Massless as URDF means it (no mass, no tensor): a zero mass with a tensor is a defect to repair."""
    from robodesc.passes.massless import massless_link

    i = link.inertial.inertia if link.inertial is not None else None
    return massless_link(link) and (i is None or not any((i.ixx, i.iyy, i.izz, i.ixy, i.ixz, i.iyz)))


def _tensor_problem(inertial: Inertial) -> str | None:
    if inertial.inertia is None:
        return "no inertia tensor"
    return inertia_problem(inertial.inertia)


def repair_inertia(robot: Robot, ctx: PassContext) -> Robot:
    ctx.stage = NAME
    policy = ctx.options.repair_inertia
    if policy is None:
        return robot
    # Imported here: the group walk needs numpy, which a robot without repairs never loads.
    from robodesc.passes.massless import fixed_groups, massless_link

    links = robot.link_map()
    dead = {
        name
        for group in fixed_groups(robot)
        if group.moving and all(massless_link(links[n]) for n in group.frames)
        for name in group.frames
    }
    for link in robot.links:
        if policy is RepairPolicy.GEOMETRY and _carried(link) and link.name not in dead:
            continue
        if link.inertial is None:
            if ctx.options.repair_missing:
                _missing(link, policy, ctx)
            continue
        if policy is RepairPolicy.QUAD_SDK:
            _quad_sdk(link, ctx)
        else:
            _geometry(link, ctx)
            _lift(link, ctx)
    return robot


def _lift(link: Link, ctx: PassContext) -> None:
    """Raise a physical tensor whose smallest moment is below the floor Newton enforces
    (:func:`robodesc.ir.principal.below_engine_floor`): adding ``delta`` to the diagonal keeps the
    axes and the triangle inequality, and ``delta`` is the least that clears the floor (with a
    float32 margin), so the body changes far less than Newton's own +1e-6 kg·m² would change it."""
    inertial = link.inertial
    if inertial is None or inertial.inertia is None or _tensor_problem(inertial) is not None:
        return
    problem = below_engine_floor(inertial.inertia)
    if problem is None:
        return
    i = inertial.inertia
    smallest = min(principal_moments(tensor_rows(i)))
    delta = 2.0 * engine_floor(i) - smallest
    i.ixx, i.iyy, i.izz = i.ixx + delta, i.iyy + delta, i.izz + delta
    ctx.warn(
        "inertia-repaired",
        f"{problem}: {delta:.3g} kg·m² added to each principal moment",
        element=f"link {link.name!r}",
        loc=i.src or inertial.src or link.src,
    )


def _missing(link: Link, policy: RepairPolicy, ctx: PassContext) -> None:
    # shape_inertia brings numpy (~0.2 s): imported only when a link needs its shapes' inertia.
    from robodesc.passes.shape_inertia import inertial_from_props, link_props

    label = f"link {link.name!r}"
    found = link_props(link) if policy is RepairPolicy.GEOMETRY else None
    if found is None:
        link.inertial = Inertial(mass=QUAD_SDK_MASS, origin=Pose(), inertia=_constant_tensor())
        ctx.warn(
            "inertial-added",
            f"no <inertial>: given {QUAD_SDK_MASS:g} kg and a {QUAD_SDK_DIAGONAL:g} kg·m² diagonal at the link origin",
            element=label,
            loc=link.src,
        )
        return
    props, source = found
    mass = ctx.options.density * props.volume
    link.inertial = inertial_from_props(props, mass=mass)
    _notes(props.notes, label, link, ctx)
    ctx.warn(
        "inertial-added",
        f"no <inertial>: derived from its {source} geometry at {ctx.options.density:g} kg/m³ ({mass:.6g} kg)",
        element=label,
        loc=link.src,
    )


def _quad_sdk(link: Link, ctx: PassContext) -> None:
    inertial = link.inertial
    assert inertial is not None
    label = f"link {link.name!r}"
    loc = inertial.src or link.src
    if not _mass_ok(inertial.mass):
        old = inertial.mass
        inertial.mass = QUAD_SDK_MASS
        ctx.warn("mass-repaired", f"mass {old!s} -> {QUAD_SDK_MASS:g} kg", element=label, loc=loc)
        i = inertial.inertia
        if i is not None:
            fixed = [a for a in ("ixx", "iyy", "izz") if not getattr(i, a) > 0]
            for a in fixed:
                setattr(i, a, QUAD_SDK_DIAGONAL)
            if fixed:
                ctx.warn(
                    "inertia-diagonal-repaired",
                    f"{', '.join(fixed)} <= 0 -> {QUAD_SDK_DIAGONAL:g} kg·m²",
                    element=label,
                    loc=i.src or loc,
                )
    problem = _tensor_problem(inertial)
    if problem is not None:
        _retensor(link, problem, ctx, gap=True)


def _geometry(link: Link, ctx: PassContext) -> None:
    inertial = link.inertial
    assert inertial is not None
    label = f"link {link.name!r}"
    loc = inertial.src or link.src
    mass_ok = _mass_ok(inertial.mass)
    problem = _tensor_problem(inertial)
    if mass_ok and problem is None:
        return
    if mass_ok:
        assert problem is not None
        _retensor(link, problem, ctx, gap=False)
        return
    from robodesc.passes.shape_inertia import inertial_from_props, link_props  # numpy: see _missing

    found = link_props(link)
    old = inertial.mass
    if found is None:
        inertial.mass = QUAD_SDK_MASS
        message = f"mass {old!s} -> {QUAD_SDK_MASS:g} kg (no geometry)"
        if problem is not None:
            inertial.inertia = _constant_tensor()
            message += f"; {problem}: tensor set to a {QUAD_SDK_DIAGONAL:g} kg·m² diagonal"
        ctx.warn("mass-repaired", message, element=label, loc=loc)
        return
    props, source = found
    mass = ctx.options.density * props.volume
    new = inertial_from_props(props, mass=mass)
    new.src = inertial.src
    link.inertial = new
    _notes(props.notes, label, link, ctx)
    ctx.warn(
        "mass-repaired",
        f"mass {old!s} -> {mass:.6g} kg and tensor from its {source} geometry at {ctx.options.density:g} kg/m³",
        element=label,
        loc=loc,
    )


def _retensor(link: Link, problem: str, ctx: PassContext, *, gap: bool) -> None:
    """New tensor for the link's (valid) mass: from geometry, else the constant diagonal."""
    inertial = link.inertial
    assert inertial is not None and inertial.mass is not None
    label = f"link {link.name!r}"
    loc = inertial.src or link.src
    from robodesc.passes.shape_inertia import inertial_from_props, link_props  # numpy: see _missing

    found = link_props(link)
    suffix = " (a gap Quad-SDK leaves open)" if gap else ""
    if found is None:
        inertial.inertia = _constant_tensor()
        ctx.warn(
            "inertia-repaired",
            f"{problem}: no geometry, tensor set to a {QUAD_SDK_DIAGONAL:g} kg·m² diagonal{suffix}",
            element=label,
            loc=loc,
        )
        return
    props, source = found
    new = inertial_from_props(props, mass=inertial.mass, origin=inertial.origin)
    new.src = inertial.src
    link.inertial = new
    _notes(props.notes, label, link, ctx)
    i = new.inertia
    assert i is not None
    ctx.warn(
        "inertia-repaired",
        f"{problem}: tensor recomputed from its {source} geometry for {inertial.mass:g} kg "
        f"(ixx={i.ixx:.6g} iyy={i.iyy:.6g} izz={i.izz:.6g}){suffix}",
        element=label,
        loc=loc,
    )


def _notes(notes: list[str], label: str, link: Link, ctx: PassContext) -> None:
    for note in notes:
        ctx.warn("mesh-not-watertight", note, element=label, loc=link.src)
