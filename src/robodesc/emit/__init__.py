"""Emitters: the IR → one output format, one subpackage per target.

Each ``emit/<target>/`` package exports ``TARGET`` (an :class:`~robodesc.emit.common.target.Target`),
which the driver finds through the target table (:data:`robodesc.targets.TARGETS`), and is light to
import: its writer loads when it writes. ``emit/common`` holds what every writer shares: number
formatting, mesh paths, flags declared on option fields, output staging, and the target contract.
Emitters import ``ir``, ``meshes``, ``usdfile`` and ``validation`` (a target's ``check`` calls its
consumer there); never a frontend, a pass or another target's internals (a target may call another
target's public names: ROS 2 writes URDF and uses SDF's, Isaac writes USD and URDF).
"""
