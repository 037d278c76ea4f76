"""Rename joints and links from a table or regex rules, with every reference.

>>> # PassOptions(rename=(RenameRule("8", "j_abad_0"), RenameRule(r"([0-9]+)", r"j_\\1", regex=True)))

The first rule that matches a name wins. With ``rename_actuators`` a transmission named
``transmission_<old>`` and an actuator ``motor_<old>`` follow their joint (Quad-SDK's convention).
A rename that would make two elements share a name raises :class:`ConfigError` naming both.
"""

from __future__ import annotations

from robodesc.ir.diagnostics import ConfigError
from robodesc.ir.model import Robot
from robodesc.passes.context import PassContext
from robodesc.passes.options import RenameRule
from robodesc.passes.references import rename_joints, rename_links

NAME = "rename"


def plan(names: list[str], rules: tuple[RenameRule, ...], kind: str, used: set[int]) -> dict[str, str]:
    """``{old: new}`` for ``names``; refuses duplicates. ``used`` collects the indices of rules that matched."""
    mapping: dict[str, str] = {}
    for name in names:
        for i, rule in enumerate(rules):
            if rule.kind != kind:
                continue
            new = rule.apply(name)
            if new is not None:
                used.add(i)
                if new != name:
                    mapping[name] = new
                break
    final: dict[str, str] = {}
    for name in names:
        new = mapping.get(name, name)
        if new in final and final[new] != name:
            other = final[new]
            raise ConfigError(
                f"renaming would give {kind}s {other!r} and {name!r} the same name {new!r}",
                element=f"{kind} {name!r}",
            )
        final[new] = name
    return mapping


def rename(robot: Robot, ctx: PassContext) -> Robot:
    ctx.stage = NAME
    rules = ctx.options.rename
    used: set[int] = set()
    links = plan([link.name for link in robot.links], rules, "link", used)
    joints = plan([joint.name for joint in robot.joints], rules, "joint", used)
    for i, rule in enumerate(rules):
        if i not in used:
            ctx.warn("rename-unused", f"rename rule {rule.pattern!r} -> {rule.replacement!r} matched no {rule.kind}")
    link_src = {link.name: link.src for link in robot.links}
    for old, new in links.items():
        ctx.info("renamed", f"{old!r} -> {new!r}", element=f"link {old!r}", loc=link_src[old])
    joint_src = {joint.name: joint.src for joint in robot.joints}
    for old, new in joints.items():
        ctx.info("renamed", f"{old!r} -> {new!r}", element=f"joint {old!r}", loc=joint_src[old])
    rename_links(robot, links, keep_original=False)
    rename_joints(robot, joints, keep_original=False)
    if ctx.options.rename_actuators and joints:
        _rename_actuators(robot, joints, ctx)
    return robot


def _rename_actuators(robot: Robot, joints: dict[str, str], ctx: PassContext) -> None:
    tr_names = {tr.name for tr in robot.transmissions}
    for tr in robot.transmissions:
        for old, new in joints.items():
            if tr.name == f"transmission_{old}":
                target = f"transmission_{new}"
                if target in tr_names:
                    raise ConfigError(
                        f"renaming would give transmissions {target!r} and {tr.name!r} the same name",
                        element=f"transmission {tr.name!r}",
                        loc=tr.src,
                    )
                ctx.info("renamed", f"{tr.name!r} -> {target!r}", element=f"transmission {tr.name!r}", loc=tr.src)
                tr_names.discard(tr.name)
                tr_names.add(target)
                tr.name = target
                break
        for act in tr.actuators:
            for old, new in joints.items():
                if act.name == f"motor_{old}":
                    ctx.info(
                        "renamed",
                        f"actuator {act.name!r} -> 'motor_{new}'",
                        element=f"transmission {tr.name!r}",
                        loc=act.src,
                    )
                    act.name = f"motor_{new}"
                    break
