"""Emitters: the IR → one output format, one subpackage per target.

Each ``emit/<target>/`` package names its entry point in its ``__init__`` and exports ``TARGET``
(an :class:`~robodesc.emit.common.target.Target`), which the pipeline finds through its target
table (:data:`robodesc.pipeline.TARGETS`). ``emit/common`` holds what every writer shares: number
formatting, mesh paths, atomic files and folders, and the target contract. Emitters import ``ir``,
``meshes`` and ``usdfile``; never a frontend, a pass, validation or another target's internals
(a target may call another target's entry point: ROS 2 writes URDF and SDF, Isaac writes USD and URDF).
"""
