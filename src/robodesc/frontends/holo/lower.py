"""Lower a HoloScript ``.holo`` composition (the syntax tree of ``parser``) to the IR.

The steps, one module each, share one :class:`~robodesc.frontends.holo.context.Lowering`:
``scene`` walks the tree (environment, templates via ``templates``, objects at their world poses),
``build`` decides joints, bodies, props and the base, and lowers them through the builder with
``joint_specs``/``joints``, ``links`` (``geometry``, ``mass``, ``materials``) and ``sensors``;
``values`` reads numbers, strings and poses.

The rules (docs/compositions.md has the full list; every inference is reported as a finding):
- Only what describes a robot is read: objects (``object``, ``orb``, ``entity``, shape blocks ...)
  anywhere in ``composition``/``scene``/group blocks and nested in each other, templates, joint
  blocks, the environment's gravity. Every other block is skipped with an info finding. A
  composition in which nothing declares a joint holds no robot, and is refused saying so.
- Positions are world positions of the composition (metres), rotations roll-pitch-yaw in degrees;
  every link frame sits at its object's world pose, visuals at the link origin, and joint origins
  are the relative transforms between the world poses.
- Joints in every spelling HoloScript uses: ``@joint { }`` / ``@joint(...)``, ``@joint_revolute``
  & co. with ``joint_*`` properties, ``behavior "RevoluteJoint"``, ``joint_type``/``parent``,
  ``joint "Name" { parent, child }`` blocks and ``robot { joints { } }``. Angles are degrees.
- The base is the first static object (else the root of the joint tree; it then floats). An object
  without a joint is fixed to its enclosing object, else to the most recent robot object before it.
- Templates are defaults the object overrides; a name used twice gets a unique link name.
- ``@grabbable`` objects without a joint, and static objects nothing connects to, are props.

>>> result = load_holo_text('''composition "Pendulum" {
...   object "Base" { @physics { type: "static" mass: 1 } geometry: "box" scale: 0.1 position: [0, 0, 1] }
...   object "Bob" { @joint { jointType: "hinge" connectedBody: "Base" axis: [0, 1, 0] limits: { min: -90, max: 90 } }
...                  geometry: "sphere" scale: 0.05 position: [0, 0, 0.5] mass: 0.2 }
... }''', "pendulum.holo")
>>> result.robot.joint("Bob_joint").origin.xyz
(0.0, 0.0, -0.5)
"""

from __future__ import annotations

from robodesc.frontends.holo.build import build
from robodesc.frontends.holo.context import HoloProp, HoloResult, Lowering
from robodesc.frontends.holo.parser import parse
from robodesc.frontends.holo.scene import read_scene
from robodesc.frontends.holo.sensors import builder_has_sensor
from robodesc.frontends.options import LoadOptions
from robodesc.ir.diagnostics import Findings
from robodesc.ir.model import Robot


def load_holo(path: str, options: LoadOptions | None = None, findings: Findings | None = None) -> HoloResult:
    from robodesc.frontends.xml_safety import read_text  # regular files only: a named pipe must not hang

    text = read_text(path)
    return load_holo_text(text, path, options, findings)


def load_holo_text(
    text: str, file: str, options: LoadOptions | None = None, findings: Findings | None = None
) -> HoloResult:
    out = findings if findings is not None else Findings()
    ctx = Lowering(parse(text, file), file, options or LoadOptions(), out)
    name, comp = read_scene(ctx)
    return build(ctx, name, comp)


def holo_frontend(path: str, options: LoadOptions, findings: Findings) -> Robot:
    """The frontend registered for ``.holo`` (props are reported as findings; ``load_holo`` returns them)."""
    return load_holo(path, options, findings).robot


__all__ = ["HoloProp", "HoloResult", "builder_has_sensor", "holo_frontend", "load_holo", "load_holo_text"]
